"""Axis-aligned spans: clear, czclear, zclear (and later rectf fast paths,
lrectwrite, rectcopy).  The rectangle is inclusive and already clipped to
viewport ∩ scrmask ∩ window by the caller."""
import math

import numpy as np

from ..jit import kernel, njit
from ..raster import fragment as F
from ..raster.blend import key_terms
from ..raster.depth import masked_write


@njit
def fill(plane, x0, x1, y0, y1, value, mask):
    """plane[y, x] = (old & ~mask) | (value & mask) over the rectangle.
    A zero mask writes nothing and touches nothing."""
    if mask == 0:
        return
    keep = ~mask
    for y in range(y0, y1 + 1):
        row = plane[y]
        for x in range(x0, x1 + 1):
            u = np.uint64(x)            # unsigned index: the loop vectorises
            row[u] = (row[u] & keep) | (value & mask)


@kernel
def fill_z(plane, x0, x1, y0, y1, value, mask):
    """z bank fill under zwritemask (24-bit value, sign-extended storage).
    A zero mask touches nothing; a full one stores without reading."""
    if mask & 0xFFFFFF == 0:
        return
    if mask & 0xFFFFFF == 0xFFFFFF:
        v = masked_write(np.int64(0), value, mask)
        for y in range(y0, y1 + 1):
            row = plane[y]
            for x in range(x0, x1 + 1):
                row[np.uint64(x)] = v
        return
    for y in range(y0, y1 + 1):
        row = plane[y]
        for x in range(x0, x1 + 1):
            u = np.uint64(x)
            row[u] = masked_write(np.int64(row[u]), value, mask)


@njit
def fill_pattern(plane, x0, x1, y0, y1, value, mask, rows, n, orgy):
    """fill() where the screen-aligned pattern bit is 1 (clear under
    setpattern); ``rows``: the pattern laid out for the window
    (raster.variants.pattern_rows), ``n`` its size."""
    keep = ~mask
    for y in range(y0, y1 + 1):
        prow = rows[(y + orgy) % n]
        for x in range(x0, x1 + 1):
            if prow[x]:
                plane[y, x] = (plane[y, x] & keep) | (value & mask)


_pixel_kernels = {}


def pixel_kernel(key):
    """lrectwrite/rectwrite/rectcopy writer for a raster key (docs/semantics.md §11:
    afunction, blend/logicop and writemasks apply; no z, stencil or pattern)."""
    k = _pixel_kernels.get(key)
    if k is None:
        k = _pixel_kernels[key] = _make_pixel_kernel(*key)
    return k


def _make_pixel_kernel(ztest, zwrite, color, gouraud, cmode, twoside,
                       stencil, blend, logic, atest, pattern, cmask, texture, dual):
    key = (ztest, zwrite, color, gouraud, cmode, twoside, stencil, blend, logic, atest,
           pattern, cmask, texture, dual)
    bterms = key_terms(blend)
    frag = F.fragment_function(False, False, color, cmode, False, blend, logic, atest, False,
                               cmask, dual)

    @kernel(variant=key)
    def write_pixels(words, x1, y1, xzoom, yzoom, planes, ip):
        """words: (h, w) source rows, row 0 at the bottom; lower-left at (x1, y1)."""
        bt = F.blend_terms(blend, bterms, F.params(ip))
        h, w = words.shape
        xe = x1 + int(math.ceil(w * xzoom)) - 1
        ye = y1 + int(math.ceil(h * yzoom)) - 1
        for y in range(max(y1, ip[F.P_SY0]), min(ye, ip[F.P_SY1]) + 1):
            sy = int((y - y1) / yzoom)
            if sy >= h:
                continue
            for x in range(max(x1, ip[F.P_SX0]), min(xe, ip[F.P_SX1]) + 1):
                sx = int((x - x1) / xzoom)
                if sx >= w:
                    continue
                v = np.int64(words[sy, sx])
                if cmode:
                    r = float(v & 0xFFF)
                    g = 0.0
                    b = 0.0
                    a = 0.0
                else:
                    r = float(v & 0xFF)
                    g = float((v >> 8) & 0xFF)
                    b = float((v >> 16) & 0xFF)
                    a = float((v >> 24) & 0xFF)
                frag(bt, x, y, 0.0, r, g, b, a, planes, ip)

    return write_pixels
