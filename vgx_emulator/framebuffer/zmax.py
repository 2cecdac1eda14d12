"""Per-segment z maxima: the largest stored z of every run of ``SEGMENT``
pixels of a row, for rejecting spans that cannot pass the z test.

Mesa's llvmpipe tests every fragment; the VGX did too.  Here a pass whose
z-failing fragments change nothing (zfunction LESS, EQUAL or LEQUAL, and
with stencil on the fail and z-fail ops both ST_KEEP: machine._z_maxima)
skips a span whose smallest quantized z exceeds the maxima under it: every
fragment of it would fail, so the banks end the same.  The maxima are
rebuilt from the z bank when a pass wants them after any z write
(Framebuffer.z_written); writes by such a pass itself only lower z, so
the maxima it uses stay upper bounds while it runs.
"""
import numpy as np

from ..jit import njit

SEGMENT_SHIFT = 4
SEGMENT = 1 << SEGMENT_SHIFT


def empty(height, width):
    """The maxima array of a (height, width) z bank."""
    return np.empty((height, (width + SEGMENT - 1) >> SEGMENT_SHIFT), np.int32)


@njit
def build(z, out):
    """out[y, s] = max(z[y, s * SEGMENT : (s + 1) * SEGMENT])."""
    w = z.shape[1]
    for y in range(z.shape[0]):
        row = z[y]
        orow = out[y]
        for s in range(out.shape[1]):
            x0 = s << SEGMENT_SHIFT
            m = row[x0]
            for x in range(x0 + 1, min(x0 + SEGMENT, w)):
                m = max(m, row[x])
            orow[s] = m
