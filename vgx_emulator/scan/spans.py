"""Axis-aligned spans: clear, czclear, zclear (and later rectf fast paths,
lrectwrite, rectcopy).  The rectangle is inclusive and already clipped to
viewport ∩ scrmask ∩ window by the caller."""
from ..jit import njit


@njit
def fill(plane, x0, x1, y0, y1, value, mask):
    """plane[y, x] = (old & ~mask) | (value & mask) over the rectangle."""
    keep = ~mask
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            plane[y, x] = (plane[y, x] & keep) | (value & mask)


@njit
def fill_z(plane, x0, x1, y0, y1, value, mask):
    """z bank fill under zwritemask (24-bit value, sign-extended storage)."""
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            v = ((plane[y, x] & ~mask) | (value & mask)) & 0xFFFFFF
            if v & 0x800000:
                v -= 0x1000000
            plane[y, x] = v


@njit
def fill_pattern(plane, x0, x1, y0, y1, value, mask, pat, n, orgx, orgy):
    """fill() where the screen-aligned pattern bit is 1 (clear under setpattern)."""
    keep = ~mask
    for y in range(y0, y1 + 1):
        py = (y + orgy) % n
        for x in range(x0, x1 + 1):
            if pat[py, (x + orgx) % n]:
                plane[y, x] = (plane[y, x] & keep) | (value & mask)
