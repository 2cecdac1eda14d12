"""Colour maps (docs/semantics.md §15; docs/colour-map-and-depthcue.md).

Every framebuffer has its own map (drawmode(3G)): mapcolor/getmcolor use
the current drawmode's.  The normal map has 4096 entries, or 16 maps of
256 in multimap mode (the small map m is entries 256*m .. 256*m+255 of the
4096, [S]).  Maps are applied at scan-out, so mapcolor recolours pixels
already drawn; cyclemap and blink act at frame points (display/colormaps.py).
"""
from vgx_emulator.display import colormaps as CM
from vgx_emulator.errors import fail
from vgx_emulator.framebuffer import layers as L

from . import constants as K
from ._current import glcall, integer, machine, num, win

__all__ = ["mapcolor", "getmcolor", "colorf", "onemap", "multimap", "getcmmode", "setmap",
           "getmap", "cyclemap", "blink"]


def _map_slot(i):
    """(array, row) that index i of the current drawmode's map names, or
    None when i is outside that map (mapcolor(3G): ignored)."""
    w = machine.current
    mode = w.st.drawmode if w is not None else L.NORMALDRAW
    if mode == L.NORMALDRAW:
        if w is not None and w.st.multimap:
            if 0 <= i < CM.MMAP_SIZE:
                return machine.colormap, CM.MMAP_SIZE * machine.maps.current + i
            return None
        return (machine.colormap, i) if 0 <= i < 4096 else None
    n = L.CURSOR_PLANES if mode == L.CURSORDRAW else w.fb.layer_planes[mode]
    return (machine.maps.maps[mode], i) if 0 <= i < (1 << n) else None


@glcall(immediate=True)
def mapcolor(i, r, g, b):
    """mapcolor(3G): entry i of the current drawmode's map := (r, g, b),
    components clamped to 0..255; an index outside the map is ignored.
    Pixels already drawn change colour (the map is applied at scan-out)."""
    win("mapcolor")             # a window first, as every drawing-state call
    i = integer("mapcolor", i, "index")
    c = [min(max(integer("mapcolor", v, "component"), 0), 255) for v in (r, g, b)]
    slot = _map_slot(i)
    if slot is not None:
        slot[0][slot[1]] = c


@glcall
def getmcolor(i):
    """getmcolor(3G): ``r, g, b = getmcolor(i)`` from the current drawmode's
    map ((0, 0, 0) outside it, [S])."""
    i = integer("getmcolor", i, "index")
    slot = _map_slot(i)
    if slot is None:
        return (0, 0, 0)
    return tuple(int(v) for v in slot[0][slot[1]])


@glcall(inside=True)
def colorf(c):
    """colorf(3G): a floating-point colour index, clamped like color(3G) to
    0..2**planes-1; rounded to the nearest index when written (the VGX
    iterates indices with fractional precision, getgdesc(GD_CIFRACT) = 1,
    so Gouraud shading interpolates the unrounded value).  An error in RGB
    mode."""
    from .primitives import color_limit
    w = win("colorf")
    f = num("colorf", c, "colour index")
    if w.st.rgb:
        fail("colorf", "colour index in RGB mode", "use RGBcolor/cpack/c3f in RGBmode")
    if f != f:
        fail("colorf", "colour index is NaN", "pass a finite index")
    top = color_limit(w)
    machine.set_colour(w, (min(max(f, 0.0), float(top)), 0.0, 0.0, 0.0))


def _normal_only(call, w):
    if w.st.drawmode != L.NORMALDRAW:
        fail(call, "only the normal framebuffer has multiple colour maps",
             "call it in drawmode(NORMALDRAW)")


@glcall(immediate=True)
def onemap():
    """onemap(3G): the normal map as one map of 4096 entries, at gconfig."""
    w = win("onemap")
    _normal_only("onemap", w)
    w.st.req_multimap = False


@glcall(immediate=True)
def multimap():
    """multimap(3G): the normal map as getgdesc(GD_NMMAPS) = 16 maps of 256
    entries (8 planes: getplanes() = 8), at gconfig."""
    w = win("multimap")
    _normal_only("multimap", w)
    w.st.req_multimap = True


@glcall
def getcmmode():
    """getcmmode(3G): CMAPMULTI (0) or CMAPONE (1), the mode in force."""
    return K.CMAPMULTI if win("getcmmode").st.multimap else K.CMAPONE


def _mapnum(call, m, what="map number"):
    m = integer(call, m, what)
    if not 0 <= m < CM.NMMAPS:
        fail(call, f"{what} {m}", f"0..{CM.NMMAPS - 1} (GD_NMMAPS is {CM.NMMAPS})")
    return m


@glcall(immediate=True)
def setmap(mapnum):
    """setmap(3G): the small map (0..15) the normal framebuffer is shown
    through in multimap mode, and that mapcolor/getmcolor address; ignored
    in onemap mode."""
    w = win("setmap")
    m = _mapnum("setmap", mapnum)
    if w.st.multimap:
        machine.maps.current = m
        machine.maps.cycle_count = 0


@glcall
def getmap():
    """getmap(3G): the current small map (0..15); 0 in onemap mode ([S])."""
    w = win("getmap")
    return machine.maps.current if w.st.multimap else 0


@glcall(immediate=True)
def cyclemap(duration, map, nextmap):
    """cyclemap(3G): in multimap mode, after ``duration`` vertical retraces
    on ``map`` the display moves to ``nextmap``; duration 0 removes the link.
    Retraces are counted at frame points (2 per swapbuffers/gflush/finish,
    docs/colour-map-and-depthcue.md), so cycling is deterministic."""
    w = win("cyclemap")
    d = integer("cyclemap", duration, "duration")
    m = _mapnum("cyclemap", map, "map")
    n = _mapnum("cyclemap", nextmap, "nextmap")
    if d < 0:
        fail("cyclemap", f"duration {d}", "a number of vertical retraces >= 0")
    if not w.st.multimap:
        fail("cyclemap", "onemap mode", "multimap() then gconfig() first")
    if d == 0:
        machine.maps.cycles.pop(m, None)
    else:
        machine.maps.cycles[m] = (d, n)


@glcall(immediate=True)
def blink(rate, color, red, green, blue):
    """blink(3G): entry ``color`` of the current normal map alternates with
    (red, green, blue) every ``rate`` vertical retraces (counted at frame
    points); rate 0 stops that entry, -1 every entry.  At most 20 entries
    (GD_NBLINKS).  The map itself keeps the original colour (getmcolor)."""
    w = win("blink")
    r = integer("blink", rate, "rate")
    if r == -1:
        machine.maps.blinks.clear()
        return
    i = integer("blink", color, "colour index")
    rgb = tuple(min(max(integer("blink", v, "component"), 0), 255)
                for v in (red, green, blue))
    if r < -1:
        fail("blink", f"rate {r}", "retraces > 0, 0 to stop, -1 to stop all")
    if w.st.multimap:
        if not 0 <= i < CM.MMAP_SIZE:
            fail("blink", f"index {i}", "0..255 in multimap mode")
        i += CM.MMAP_SIZE * machine.maps.current
    elif not 0 <= i < 4096:
        fail("blink", f"index {i}", "0..4095")
    if r == 0:
        machine.maps.blinks.pop(i, None)
        return
    if i not in machine.maps.blinks and len(machine.maps.blinks) >= CM.MAX_BLINKS:
        fail("blink", f"more than {CM.MAX_BLINKS} blinking entries",
             "stop one with rate 0 first (GD_NBLINKS)")
    machine.maps.blinks[i] = (r, rgb)
