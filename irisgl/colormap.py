"""Colour-map mode calls (reference section 15)."""
from ._current import glcall, integer, machine

__all__ = ["mapcolor", "getmcolor"]


@glcall
def mapcolor(i, r, g, b):
    """mapcolor(3G): entry i := (r, g, b); invalid indices are ignored.
    Pixels already drawn change colour (the map is applied at scan-out)."""
    i = integer("mapcolor", i, "index")
    c = [min(max(integer("mapcolor", v, "component"), 0), 255) for v in (r, g, b)]
    if 0 <= i < 4096:
        machine.flush()
        machine.colormap[i] = c


@glcall
def getmcolor(i):
    """getmcolor(3G): ``r, g, b = getmcolor(i)``."""
    i = integer("getmcolor", i, "index")
    if 0 <= i < 4096:
        return tuple(int(v) for v in machine.colormap[i])
    return (0, 0, 0)
