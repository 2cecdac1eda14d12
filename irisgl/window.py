"""Windows and framebuffer configuration (reference sections 4 and 13).

winopen opens a headless window on the virtual 1280x1024 VGX screen; its
size and place come from prefsize/prefposition (default: 640x480 at the
screen origin, Decision 15).  Configuration requests (RGBmode, cmode,
doublebuffer, singlebuffer, stensize, acsize) take effect at gconfig, which
creates the banks they ask for.
"""
from vgx_emulator import config
from vgx_emulator.errors import fail
from vgx_emulator.framebuffer import ZMAX, ZMIN

from . import constants as K
from ._current import glcall, integer, machine, win, boolean

__all__ = ["winopen", "winclose", "winset", "winget", "prefsize", "prefposition",
           "keepaspect", "getsize", "getorigin", "RGBmode", "cmode", "singlebuffer",
           "doublebuffer", "stensize", "acsize", "zbsize", "gconfig", "getgconfig",
           "getdisplaymode", "getplanes", "swapbuffers", "frontbuffer", "backbuffer",
           "getgdesc", "gexit", "ginit", "greset", "gflush", "finish", "foreground",
           "noport", "winconstraints", "gbegin"]

#: getgdesc(3G) on the emulated VGX (reference section 4, Decision 12).
GDESC = {
    K.GD_XPMAX: config.SCREEN_WIDTH, K.GD_YPMAX: config.SCREEN_HEIGHT,
    K.GD_XMMAX: 360, K.GD_YMMAX: 290, K.GD_ZMIN: ZMIN, K.GD_ZMAX: ZMAX,
    K.GD_BITS_NORM_SNG_RED: 8, K.GD_BITS_NORM_SNG_GREEN: 8, K.GD_BITS_NORM_SNG_BLUE: 8,
    K.GD_BITS_NORM_DBL_RED: 8, K.GD_BITS_NORM_DBL_GREEN: 8, K.GD_BITS_NORM_DBL_BLUE: 8,
    K.GD_BITS_NORM_SNG_CMODE: 12, K.GD_BITS_NORM_DBL_CMODE: 12,
    K.GD_BITS_NORM_SNG_MMAP: 8, K.GD_BITS_NORM_DBL_MMAP: 8,
    K.GD_BITS_NORM_ZBUFFER: 24, K.GD_BITS_NORM_SNG_ALPHA: 8, K.GD_BITS_NORM_DBL_ALPHA: 8,
    K.GD_BLEND: 1, K.GD_LOGICOP: 1, K.GD_DITHER: 1, K.GD_AFUNCTION: 1,
    K.GD_NVERTEX_POLY: config.MAX_POLYGON_VERTICES, K.GD_PATSIZE_64: 1,
    K.GD_READSOURCE: 1, K.GD_READSOURCE_ZBUFFER: 1, K.GD_ZDRAW_GEOM: 1,
    K.GD_ZDRAW_PIXELS: 1, K.GD_BITS_ACBUF: 16, K.GD_BITS_ACBUF_HW: 0,
    K.GD_BITS_STENCIL: 8, K.GD_TEXTURE: 1, K.GD_TEXTURE_PERSP: 0,
    K.GD_CLIPPLANES: 6, K.GD_LIGHTING_TWOSIDE: 1, K.GD_STEREO: 0,
}


@glcall
def winopen(name=""):
    """winopen(3G): open a window (headless), make it current, return its id;
    queues INPUTCHANGE and REDRAW."""
    return machine.winopen(str(name))


def _gid(call, gid):
    g = integer(call, gid, "window id")
    if g not in machine.windows:
        fail(call, f"no window {gid}", "pass an id returned by winopen")
    return g


@glcall
def winclose(gid):
    machine.winclose(_gid("winclose", gid))


@glcall
def winset(gid):
    machine.winset(_gid("winset", gid))


@glcall
def winget():
    """The current window's id (0 when none is open)."""
    return machine.current.gid if machine.current else 0


@glcall
def prefsize(x, y):
    """prefsize(3G): size of the next window, in pixels."""
    x = integer("prefsize", x, "width")
    y = integer("prefsize", y, "height")
    if not (1 <= x <= config.SCREEN_WIDTH and 1 <= y <= config.SCREEN_HEIGHT):
        fail("prefsize", f"size {x}x{y} does not fit the screen",
             f"1..{config.SCREEN_WIDTH} by 1..{config.SCREEN_HEIGHT}")
    machine.pref["size"] = (x, y)


@glcall
def prefposition(x1, x2, y1, y2):
    """prefposition(3G): screen rectangle x1..x2, y1..y2 of the next window."""
    x1, x2, y1, y2 = (integer("prefposition", v) for v in (x1, x2, y1, y2))
    if not (0 <= x1 <= x2 < config.SCREEN_WIDTH and 0 <= y1 <= y2 < config.SCREEN_HEIGHT):
        fail("prefposition", f"rectangle ({x1}, {x2}, {y1}, {y2}) is not on the screen",
             "0 <= x1 <= x2 <= 1279, 0 <= y1 <= y2 <= 1023")
    machine.pref["origin"] = (x1, y1)
    machine.pref["size"] = (x2 - x1 + 1, y2 - y1 + 1)


@glcall
def keepaspect(x, y):
    """keepaspect(3G): recorded; a headless window is never resized."""
    x = integer("keepaspect", x)
    y = integer("keepaspect", y)
    if x <= 0 or y <= 0:
        fail("keepaspect", "ratio terms must be positive", "x > 0, y > 0")
    machine.pref["aspect"] = (x, y)


@glcall
def foreground():
    """foreground(3G): accepted; there is no shell to detach from."""


@glcall
def noport():
    """noport(3G): accepted (the next winopen still gets a window)."""


@glcall
def winconstraints():
    """winconstraints(3G): accepted; headless windows are not reshaped."""


def gbegin():
    """gbegin(3G): old form of ginit."""
    ginit()


@glcall
def getsize():
    """getsize(3G): ``x, y = getsize()``."""
    w = win("getsize")
    return w.width, w.height


@glcall
def getorigin():
    """getorigin(3G): screen position of the window's lower-left corner."""
    return win("getorigin").origin


@glcall
def RGBmode():
    win("RGBmode").st.req_rgb = True


@glcall
def cmode():
    win("cmode").st.req_rgb = False


@glcall
def doublebuffer():
    win("doublebuffer").st.req_double = True


@glcall
def singlebuffer():
    win("singlebuffer").st.req_double = False


@glcall
def stensize(planes):
    """stensize(3G): 0..8 stencil planes, effective at gconfig."""
    n = integer("stensize", planes, "plane count")
    if not 0 <= n <= 8:
        fail("stensize", f"{n} planes", "0..8 (GD_BITS_STENCIL is 8)")
    win("stensize").st.req_stencil = n


@glcall
def acsize(planes):
    """acsize(3G): 0 or 16 bits per accumulation component, at gconfig."""
    n = integer("acsize", planes, "plane count")
    if n not in (0, 16):
        fail("acsize", f"{n} planes", "0 or 16 on the VGX")
    win("acsize").st.req_accum = n


@glcall
def zbsize(planes):
    """zbsize(3G): not supported on the VGX; ignored."""
    integer("zbsize", planes)


@glcall
def gconfig():
    """gconfig(3G): apply the configuration; colour := 0, every writemask
    all ones, in double-buffer mode back enabled and front disabled."""
    machine.gconfig(win("gconfig"))


@glcall
def getgconfig(what):
    """getgconfig(3G): sizes of the configuration in force (z and the
    accumulation buffer are signed on the VGX, so reported negative)."""
    w = win("getgconfig")
    st, fb = w.st, w.fb
    rgb = 8 if st.rgb else 0
    table = {K.GC_BITS_CMODE: 0 if st.rgb else 12, K.GC_BITS_RED: rgb,
             K.GC_BITS_GREEN: rgb, K.GC_BITS_BLUE: rgb, K.GC_BITS_ALPHA: rgb,
             K.GC_BITS_ZBUFFER: -24, K.GC_ZMIN: ZMIN, K.GC_ZMAX: ZMAX,
             K.GC_BITS_STENCIL: fb.stencil_planes,
             K.GC_BITS_ACBUF: -16 if fb.accum is not None else 0,
             K.GC_MS_SAMPLES: 0, K.GC_BITS_MS_ZBUFFER: 0, K.GC_MS_ZMIN: 0,
             K.GC_MS_ZMAX: 0, K.GC_BITS_MS_STENCIL: 0, K.GC_STEREO: 0,
             K.GC_DOUBLE: 1 if st.double else 0}
    v = integer("getgconfig", what, "inquiry")
    if v not in table:
        fail("getgconfig", f"unknown inquiry {what!r}", "pass a GC_* constant")
    return table[v]


@glcall
def getdisplaymode():
    st = win("getdisplaymode").st
    if st.rgb:
        return K.DMRGBDOUBLE if st.double else K.DMRGB
    return K.DMDOUBLE if st.double else K.DMSINGLE


@glcall
def getplanes():
    """getplanes(3G): 24 in RGB mode, 12 in colour-map mode (VGX)."""
    return 24 if win("getplanes").st.rgb else 12


@glcall
def swapbuffers():
    """swapbuffers(3G): exchange front and back (ignored single-buffered);
    a frame point for the runner."""
    machine.swapbuffers(win("swapbuffers"))


@glcall
def gflush():
    """gflush(3G): everything issued is drawn; a frame point."""
    machine.frame_end(win("gflush"))


@glcall
def finish():
    """finish(3G): as gflush; the emulated pipeline is drained synchronously."""
    machine.frame_end(win("finish"))


@glcall
def frontbuffer(b):
    """frontbuffer(3G): enable drawing into the front buffer (double-buffer
    mode only; ignored single-buffered)."""
    w = win("frontbuffer")
    v = boolean("frontbuffer", b)
    machine.state_change(w)
    if w.st.double:
        w.st.front_enabled = v


@glcall
def backbuffer(b):
    w = win("backbuffer")
    v = boolean("backbuffer", b)
    machine.state_change(w)
    if w.st.double:
        w.st.back_enabled = v


@glcall
def getgdesc(inquiry):
    """getgdesc(3G): the VGX's value, or -1 for an unknown inquiry."""
    try:
        return GDESC.get(int(inquiry), -1)
    except (TypeError, ValueError):
        return -1


@glcall
def gexit():
    """gexit(3G): close every window and end graphics."""
    machine.gexit()


@glcall
def ginit():
    """ginit(3G): initialise graphics; the colour map returns to its default."""
    from vgx_emulator.display import default_colormap
    machine.colormap[:] = default_colormap()


@glcall
def greset():
    """greset(3G): the current window's modes, matrices, viewport and the
    colour map return to their initial values; the configuration in force
    (and the banks) are kept."""
    from vgx_emulator.display import default_colormap
    from vgx_emulator.state import WindowState
    w = win("greset")
    machine.state_change(w)
    old = w.st
    st = WindowState(w.width, w.height)
    st.rgb, st.double = old.rgb, old.double
    st.req_rgb, st.req_double = old.req_rgb, old.req_double
    st.req_stencil, st.req_accum = old.req_stencil, old.req_accum
    st.front_enabled = not st.double
    st.back_enabled = st.double
    w.st = st
    machine.matrices_changed(w)
    machine.colormap[:] = default_colormap()
