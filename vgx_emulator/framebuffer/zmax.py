"""Per-segment z maxima: the largest stored z of every run of ``SEGMENT``
pixels of a row, for rejecting spans that cannot pass the z test.

Mesa's llvmpipe tests every fragment; the VGX did too.  Here a pass whose
z-failing fragments change nothing (zfunction LESS, EQUAL or LEQUAL, and
with stencil on the fail and z-fail ops both ST_KEEP: machine._z_maxima)
skips a span whose smallest quantized z exceeds the maxima under it: every
fragment of it would fail, so the banks end the same.  The maxima are
rebuilt from the z bank when a pass wants them after any z write
(Framebuffer.z_written), over the rectangle the writes since the last
build may have touched (the union of the passes' vertex boxes, clipped to
their scissor: a small pass no longer rebuilds the whole window, 0.15 ms
at 640x480); a pass of triangles that changed no stored z (the walker
reports it in the parameter slot P_ZCHANGED: a ZF_EQUAL or
ZF_LEQUAL redraw of what the bank holds, as multipass shadow algorithms
do) does not count.  Writes by an eligible pass itself only lower z, so
the maxima it uses stay upper bounds while it runs.
"""
import numpy as np

from ..jit import njit

SEGMENT_SHIFT = 4                 # build() reduces 16 values as a tree
SEGMENT = 1 << SEGMENT_SHIFT


def empty(height, width):
    """The maxima array of a (height, width) z bank."""
    return np.empty((height, (width + SEGMENT - 1) >> SEGMENT_SHIFT), np.int32)


@njit
def build(z, out, x0, x1, y0, y1):
    """out[y, s] = max(z[y, s * SEGMENT : (s + 1) * SEGMENT]) for the rows
    y0..y1 and the segments that hold pixels x0..x1 (inclusive; the whole
    bank: 0, width - 1, 0, height - 1).  A full segment is reduced as a
    tree of pairwise maxima (the compiler makes it one 8-lane vector
    maximum and a horizontal reduction: 0.3 ms for a 1280 x 1024 bank,
    against 0.9 ms for a loop of 16); a last partial segment element by
    element."""
    w = z.shape[1]
    full = w >> SEGMENT_SHIFT
    s0 = x0 >> SEGMENT_SHIFT
    s1 = min(x1 >> SEGMENT_SHIFT, full - 1)
    for y in range(y0, y1 + 1):
        row = z[y]
        orow = out[y]
        for s in range(s0, s1 + 1):
            x = np.uint64(s << SEGMENT_SHIFT)
            a0 = max(row[x], row[x + 8])
            a1 = max(row[x + 1], row[x + 9])
            a2 = max(row[x + 2], row[x + 10])
            a3 = max(row[x + 3], row[x + 11])
            a4 = max(row[x + 4], row[x + 12])
            a5 = max(row[x + 5], row[x + 13])
            a6 = max(row[x + 6], row[x + 14])
            a7 = max(row[x + 7], row[x + 15])
            orow[s] = max(max(max(a0, a4), max(a2, a6)), max(max(a1, a5), max(a3, a7)))
        if full < out.shape[1] and x1 >= full << SEGMENT_SHIFT:
            xs = full << SEGMENT_SHIFT
            m = row[xs]
            for x in range(xs + 1, w):
                m = max(m, row[x])
            orow[full] = m
