"""drawmode(3G) and the pop-up, overlay and underlay framebuffers
(docs/colour-map-and-depthcue.md; vgx_emulator/framebuffer/layers.py).

drawmode picks the framebuffer that drawing, clear, lrectwrite and the
per-framebuffer calls (color, colorf, getcolor, writemask, getwritemask,
mapcolor, getmcolor) address.  The pop-up, overlay and underlay
framebuffers are single-buffered colour-map banks without z or stencil;
at scan-out index 0 of the pop-up and overlay banks is transparent, and
the underlay shows where the normal framebuffer holds 0 (overlay(3G)).
"""
from vgx_emulator.errors import fail
from vgx_emulator.framebuffer import layers as L

from ._current import glcall, integer, machine, token, win

__all__ = ["drawmode", "getdrawmode", "overlay", "underlay", "pupmode", "endpupmode",
           "gRGBmask"]


def _switch(w, mode):
    if w.st.drawmode == mode:
        return
    machine.state_change(w)            # what was issued is drawn where it was aimed
    L.switch(w.st, mode)
    machine.attributes_changed(w)      # the next vertex takes this framebuffer's colour
    machine.rebind()                   # RGB or colour-map calls, as this framebuffer takes


@glcall(immediate=True)
def drawmode(mode):
    """drawmode(3G): NORMALDRAW, PUPDRAW, OVERDRAW, UNDERDRAW or CURSORDRAW;
    each keeps its own current index, writemask and colour map.  Drawing in
    CURSORDRAW, or into a framebuffer without planes, changes nothing."""
    w = win("drawmode")
    _switch(w, token("drawmode", mode, L.DRAWMODES, "drawmode"))


@glcall
def getdrawmode():
    """getdrawmode(3G): the current drawmode."""
    return win("getdrawmode").st.drawmode


def _planes(call, planes, what):
    n = integer(call, planes, "planes")
    if n not in L.LAYER_SIZES:
        fail(call, f"{n} {what} planes", "0, 2, 4 or 8")
    return n


@glcall(immediate=True)
def overlay(planes):
    """overlay(3G): 0, 2, 4 or 8 overlay planes (default 2 on the emulated
    VGX, [S]), allocated at gconfig; overlay and underlay share 8 planes,
    the overlay is served first."""
    n = _planes("overlay", planes, "overlay")
    win("overlay").st.req_overlay = n


@glcall(immediate=True)
def underlay(planes):
    """underlay(3G): 0 (default), 2, 4 or 8 underlay planes, at gconfig
    (what the overlay leaves of the 8 shared planes, [S])."""
    n = _planes("underlay", planes, "underlay")
    win("underlay").st.req_underlay = n


@glcall(immediate=True)
def pupmode():
    """pupmode(3G): old form of drawmode(PUPDRAW)."""
    _switch(win("pupmode"), L.PUPDRAW)


@glcall(immediate=True)
def endpupmode():
    """endpupmode(3G): old form of drawmode(NORMALDRAW)."""
    _switch(win("endpupmode"), L.NORMALDRAW)


@glcall(immediate=True)
def gRGBmask():
    """gRGBmask(3G): ``r, g, b = gRGBmask()``, the RGB writemask of the
    current framebuffer; an error in colour-map mode ([S])."""
    st = win("gRGBmask").st
    if not st.rgb:
        fail("gRGBmask", "RGB writemask in colour-map mode", "use getwritemask() in cmode")
    m = st.cmask
    return (m & 0xFF, (m >> 8) & 0xFF, (m >> 16) & 0xFF)
