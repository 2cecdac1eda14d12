"""Windows and framebuffer configuration (docs/semantics.md §4, §13).

winopen opens a headless window on the virtual 1280x1024 VGX screen; its
size and place come from prefsize/prefposition (default: 640x480 at the
screen origin, docs/semantics.md §8).  Configuration requests (RGBmode, cmode,
doublebuffer, singlebuffer, stensize, acsize) take effect at gconfig, which
creates the banks they ask for.
"""
from vgx_emulator import config
from vgx_emulator.gdesc import VALUES
from vgx_emulator.errors import fail
from vgx_emulator.framebuffer import ZMAX, ZMIN

from . import constants as K
from ._current import HEADLESS, boolean, glcall, integer, machine, win

__all__ = ["winopen", "winclose", "winset", "winget", "prefsize", "prefposition",
           "keepaspect", "getsize", "getorigin", "RGBmode", "cmode", "singlebuffer",
           "doublebuffer", "stensize", "acsize", "zbsize", "gconfig", "getgconfig",
           "getdisplaymode", "getplanes", "swapbuffers", "frontbuffer", "backbuffer",
           "getgdesc", "gexit", "ginit", "greset", "gflush", "finish", "foreground",
           "noport", "winconstraints", "gbegin", "monobuffer",
           "minsize", "maxsize", "stepunit", "fudge", "noborder", "iconsize",
           "imakebackground", "wintitle", "icontitle", "winpop", "winpush", "windepth",
           "winposition", "winmove", "winattach", "swinopen", "getport", "ismex",
           "fullscrn", "endfullscrn", "getwscrn", "scrnselect", "scrnattach"]

#: getgdesc(3G) on the emulated VGX: every inquiry, each value with its
#: source (vgx_emulator/gdesc.py)
GDESC = VALUES


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
    """winclose(3G): close window gid (its banks are freed)."""
    machine.winclose(_gid("winclose", gid))


@glcall
def winset(gid):
    """winset(3G): make window gid the current window."""
    machine.winset(_gid("winset", gid))


@glcall
def winget():
    """winget(3G): the current window's id (0 when none is open)."""
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
    """prefposition(3G): screen rectangle x1..x2, y1..y2 of the next window.
    (x1, y1) and (x2, y2) are "one corner" and "the opposite corner", in
    either order; the rules are winposition's (_screen_rect), so SGI's
    ``prefposition(0, getgdesc(GD_XPMAX), 0, getgdesc(GD_YPMAX))``, one
    pixel past the screen, opens a 1281 x 1025 window as it did."""
    xa, xb, ya, yb = _screen_rect("prefposition", x1, x2, y1, y2)
    _on_screen_plane("prefposition", xa, xb, ya, yb)
    machine.pref["origin"] = (xa, ya)
    machine.pref["size"] = (xb - xa + 1, yb - ya + 1)


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def keepaspect(x, y):
    """keepaspect(3G): aspect ratio constraint for the next winopen (or for
    the current window at winconstraints); kept, a headless window is never
    reshaped by a user."""
    x = integer("keepaspect", x)
    y = integer("keepaspect", y)
    if x <= 0 or y <= 0:
        fail("keepaspect", "ratio terms must be positive", "x > 0, y > 0")
    machine.pref["aspect"] = (x, y)


@glcall(immediate=True)
def foreground():
    """foreground(3G): accepted; there is no shell to detach from."""
    machine.pref["foreground"] = True


@glcall(immediate=True)
def noport():
    """noport(3G): kept (wm["noport"]); the next winopen still gets a window
    so that colour-map programs can run headless."""
    machine.pref["noport"] = True


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def winconstraints():
    """winconstraints(3G): bind the constraints given since winopen
    (minsize, maxsize, keepaspect, stepunit, fudge, prefsize, prefposition)
    to the current window; prefposition/prefsize also reshape it there."""
    w = win("winconstraints")
    pref = dict(machine.pref)
    machine.pref = {}
    if "origin" in pref or "size" in pref:
        x, y = pref.get("origin", w.origin)
        wd, ht = pref.get("size", (w.width, w.height))
        _reshape(w, x, y, wd, ht)
    for k in ("origin", "size"):
        pref.pop(k, None)
    w.wm.update(pref)


@glcall(immediate=True)
def gbegin():
    """gbegin(3G): as ginit, except that the colour map is left as it is."""
    _fullscreen_window("gbegin")


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
    """RGBmode(3G): ask for RGB mode (colours as 0xAABBGGRR words); takes effect at gconfig."""
    win("RGBmode").st.req_rgb = True


@glcall
def cmode():
    """cmode(3G): ask for colour-map mode (12-bit indices); takes effect at gconfig."""
    win("cmode").st.req_rgb = False


@glcall
def doublebuffer():
    """doublebuffer(3G): ask for a front and a back buffer; takes effect at gconfig."""
    win("doublebuffer").st.req_double = True


@glcall
def singlebuffer():
    """singlebuffer(3G): ask for one colour buffer; takes effect at gconfig."""
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
    """getdisplaymode(3G): DMRGB, DMSINGLE, DMDOUBLE or DMRGBDOUBLE for the
    current window's configuration."""
    st = win("getdisplaymode").st
    if st.rgb:
        return K.DMRGBDOUBLE if st.double else K.DMRGB
    return K.DMDOUBLE if st.double else K.DMSINGLE


@glcall
def getplanes():
    """getplanes(3G): planes of the current drawmode: 24 in RGB mode, 12 in
    colour-map mode (8 in multimap mode); pop-up/overlay/underlay their
    planes; 0 in CURSORDRAW (VGX)."""
    from vgx_emulator.framebuffer.layers import planes
    return planes(win("getplanes"))


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


@glcall(immediate=True)
def monobuffer():
    """monobuffer(3G): ask for a monoscopic configuration at gconfig.  The
    VGX has no stereo buffers (getgdesc(GD_STEREO) is 0), so mono is the
    only configuration and the request changes nothing; stereobuffer(3G)
    raises GLError."""
    win("monobuffer")


@glcall
def frontbuffer(b):
    """frontbuffer(3G): enable drawing into the front buffer (double-buffer
    mode; single-buffered it can be disabled only while zdraw is on, zdraw(3G))."""
    w = win("frontbuffer")
    v = boolean("frontbuffer", b)
    machine.state_change(w)
    if w.st.double:
        w.st.front_enabled = v
    elif w.st.zdraw or v:
        w.st.front_enabled = v


@glcall
def backbuffer(b):
    """backbuffer(3G): enable or disable drawing into the back buffer
    (double-buffered windows; ignored in single-buffer mode)."""
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
    except (TypeError, ValueError, OverflowError):
        return -1                   # getgdesc(3G): -1 for an invalid inquiry


@glcall
def gexit():
    """gexit(3G): close every window and end graphics."""
    machine.gexit()


@glcall(immediate=True)
def ginit():
    """ginit(3G): initialise graphics: the whole 1280x1024 screen becomes the
    (current) window, in its initial state (colour map mode, single buffer);
    the colour map returns to its default."""
    from vgx_emulator.display import default_colormap
    _fullscreen_window("ginit")
    machine.colormap[:] = default_colormap()


def _fullscreen_window(name):
    machine.pref["origin"] = (0, 0)
    machine.pref["size"] = (config.SCREEN_WIDTH, config.SCREEN_HEIGHT)
    machine.winopen(name)
    machine.current.wm["border"] = False


@glcall
def greset():
    """greset(3G): the current window's modes, matrices, viewport and the
    colour map return to their initial values; the configuration in force
    (and the banks) are kept."""
    from vgx_emulator.display import default_colormap
    from vgx_emulator.state import WindowState
    w = win("greset")
    machine.state_change(w)
    from vgx_emulator.framebuffer import layers
    layers.switch(w.st, layers.NORMALDRAW)      # the normal framebuffer's modes (drawmode(3G))
    old = w.st
    st = WindowState(w.width, w.height)
    st.rgb, st.double = old.rgb, old.double
    st.req_rgb, st.req_double = old.req_rgb, old.req_double
    st.req_stencil, st.req_accum = old.req_stencil, old.req_accum
    st.front_enabled = not st.double
    st.back_enabled = st.double
    w.batch.synced = len(w.batch.ev)   # the old state's events do not carry over
    st.events, w.batch.owner = w.batch, st
    w.st = st
    machine.rebind()                # the per-vertex calls write to the new state
    machine.matrices_changed(w)
    machine.attributes_changed(w)
    machine.colormap[:] = default_colormap()


# -- window-manager requests (docs/semantics.md §13, docs/windows-and-devices.md) ------
def _pos(call, x, y, what):
    x = integer(call, x, f"{what} x")
    y = integer(call, y, f"{what} y")
    if x <= 0 or y <= 0:
        fail(call, f"{what} {x}x{y}", "positive sizes")
    return x, y


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def minsize(x, y):
    """minsize(3G): smallest size the user may give the window (next winopen,
    or the current window at winconstraints); kept, and a winopen without
    prefsize gets at least this size (docs/windows-and-devices.md)."""
    machine.pref["minsize"] = _pos("minsize", x, y, "size")


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def maxsize(x, y):
    """maxsize(3G): largest size the user may give the window; kept, and a
    winopen without prefsize gets at most this size."""
    machine.pref["maxsize"] = _pos("maxsize", x, y, "size")


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def stepunit(xunit, yunit):
    """stepunit(3G): the window is reshaped in steps of xunit x yunit; kept."""
    machine.pref["stepunit"] = _pos("stepunit", xunit, yunit, "unit")


@glcall(immediate=True, status=HEADLESS, why="the user reshapes windows only on a display")
def fudge(xfudge, yfudge):
    """fudge(3G): border allowance added to stepunit/keepaspect sizes; kept."""
    x = integer("fudge", xfudge)
    y = integer("fudge", yfudge)
    if x < 0 or y < 0:
        fail("fudge", f"fudge {x}, {y}", "x >= 0, y >= 0")
    machine.pref["fudge"] = (x, y)


@glcall(immediate=True, status=HEADLESS, why="borders are drawn by a window manager")
def noborder():
    """noborder(3G): the next window has no border; kept (wm["border"])."""
    machine.pref["border"] = False


@glcall(immediate=True, status=HEADLESS, why="icons exist only on a display")
def iconsize(x, y):
    """iconsize(3G): size of the next window's icon; kept."""
    machine.pref["iconsize"] = _pos("iconsize", x, y, "icon size")


@glcall(immediate=True)
def imakebackground():
    """imakebackground(3G): the next window is the screen background: the
    whole screen, no border, drawn again on REDRAW."""
    machine.pref["origin"] = (0, 0)
    machine.pref["size"] = (config.SCREEN_WIDTH, config.SCREEN_HEIGHT)
    machine.pref["border"] = False
    machine.pref["background"] = True


@glcall(immediate=True, status=HEADLESS, why="titles are drawn by a window manager")
def wintitle(name):
    """wintitle(3G): the current window's title; kept (wm["title"])."""
    win("wintitle").wm["title"] = str(name)


@glcall(immediate=True, status=HEADLESS, why="icons exist only on a display")
def icontitle(name):
    """icontitle(3G): the title of the current window's icon; kept."""
    win("icontitle").wm["icontitle"] = str(name)


@glcall(immediate=True, status=HEADLESS, why="stacking is visible only on a display")
def winpop():
    """winpop(3G): the current window goes in front of the others."""
    w = win("winpop")
    machine.stacking.remove(w.gid)
    machine.stacking.append(w.gid)


@glcall(immediate=True, status=HEADLESS, why="stacking is visible only on a display")
def winpush():
    """winpush(3G): the current window goes behind the others."""
    w = win("winpush")
    machine.stacking.remove(w.gid)
    machine.stacking.insert(0, w.gid)


@glcall(immediate=True)
def windepth(gid):
    """windepth(3G): a number comparing the window's place in the stack with
    the program's other windows: 1 for the front one, larger further back
    (the man page fixes only that the numbers compare)."""
    g = _gid("windepth", gid)
    return len(machine.stacking) - machine.stacking.index(g)


def _top(w):
    """The top-level window a (sub)window is placed in."""
    while w.parent is not None and w.parent in machine.windows:
        w = machine.windows[w.parent]
    return w


def _place_children(w):
    """Subwindows keep their origin relative to the moved parent (swinopen(3G))."""
    for c in machine.windows.values():
        if c.parent == w.gid:
            machine.state_change(c)
            c.origin = (w.origin[0] + c.offset[0], w.origin[1] + c.offset[1])
            _place_children(c)


def _reshape(w, x, y, width, height):
    """Move/reshape a window as the window system would; REDRAW when its
    size changes."""
    machine.state_change(w)
    resized = (width, height) != (w.width, w.height)
    w.resize(x, y, width, height)
    if w.parent is not None and w.parent in machine.windows:
        p = _top(w)
        w.offset = (x - p.origin[0], y - p.origin[1])
    _place_children(w)
    if resized:
        machine.events.post(K.REDRAW, w.gid, coalesce=True)


@glcall(immediate=True)
def winposition(x1, x2, y1, y2):
    """winposition(3G): move and reshape the current window to the screen
    rectangle x1..x2, y1..y2 (corners in either order; a subwindow's are
    relative to its parent's origin).  The banks are rebuilt at the new
    size and REDRAW is queued."""
    w = win("winposition")
    xa, xb, ya, yb = _screen_rect("winposition", x1, x2, y1, y2)
    if w.parent is not None and w.parent in machine.windows:
        p = _top(w)
        xa, xb, ya, yb = xa + p.origin[0], xb + p.origin[0], ya + p.origin[1], yb + p.origin[1]
    _on_screen_plane("winposition", xa, xb, ya, yb)
    _reshape(w, xa, ya, xb - xa + 1, yb - ya + 1)


def _screen_rect(call, x1, x2, y1, y2):
    """A window rectangle given by two opposite corners in either order:
    (xmin, xmax, ymin, ymax); at most twice the screen each way."""
    x1, x2, y1, y2 = (integer(call, v) for v in (x1, x2, y1, y2))
    xa, xb, ya, yb = min(x1, x2), max(x1, x2), min(y1, y2), max(y1, y2)
    wd, ht = xb - xa + 1, yb - ya + 1
    if wd > 2 * config.SCREEN_WIDTH or ht > 2 * config.SCREEN_HEIGHT:
        fail(call, f"a {wd}x{ht} window", "at most twice the screen each way")
    return xa, xb, ya, yb


def _on_screen_plane(call, *coords):
    """Screen coordinates of a window's corners are Screencoords (shorts):
    a window may lie partly or wholly off the screen, not beyond that."""
    for c in coords:
        if not -32768 <= c <= 32767:
            fail(call, f"screen coordinate {c}", "a Screencoord is a short: -32768..32767")


@glcall(immediate=True)
def winmove(orgx, orgy):
    """winmove(3G): move the current window's lower-left corner to
    (orgx, orgy) on the screen (a subwindow: relative to its parent)."""
    w = win("winmove")
    x = integer("winmove", orgx)
    y = integer("winmove", orgy)
    if w.parent is not None and w.parent in machine.windows:
        p = _top(w)
        x, y = x + p.origin[0], y + p.origin[1]
    _on_screen_plane("winmove", x, y, x + w.width - 1, y + w.height - 1)
    _reshape(w, x, y, w.width, w.height)


@glcall(immediate=True)
def winattach():
    """winattach(3G): input focus to the current window; returns the id of
    the window that had it (INPUTCHANGE is queued for the new one)."""
    w = win("winattach")
    old = machine.system.get("focus", w.gid)
    machine.system["focus"] = w.gid
    if old != w.gid:
        machine.events.post(K.INPUTCHANGE, w.gid)
    return old


@glcall(immediate=True)
def swinopen(parent):
    """swinopen(3G): a subwindow of ``parent``: a window of its own (own
    banks and state) whose origin stays fixed relative to the parent's; it
    becomes current.  Placed by winposition relative to the parent (before
    that: the parent's rectangle, our choice)."""
    p = machine.windows.get(_gid("swinopen", parent))
    top = _top(p)
    machine.pref = {"origin": top.origin, "size": (top.width, top.height)}
    gid = machine.winopen("")
    w = machine.windows[gid]
    w.parent = top.gid
    w.offset = (0, 0)
    w.wm["border"] = False
    return gid


@glcall(immediate=True)
def getport(name=""):
    """getport(3G): the GL2 form of winopen: initialise graphics and open a
    window by the constraints given before it; returns its id."""
    return machine.winopen(str(name))


@glcall(immediate=True)
def ismex():
    """ismex(3G): TRUE: the emulated VGX runs a window system (4Sight,
    which answered for mex), so programs take their windowed path."""
    return 1


@glcall(immediate=True)
def fullscrn():
    """fullscrn(3G): the program may draw on the whole screen: headless the
    current window becomes the 1280x1024 screen at (0, 0), with
    viewport(0, 1279, 0, 1023) and the matching ortho2.  The old viewport
    and matrices are not saved (the man page leaves that to the caller)."""
    from .matrix import ortho2, viewport
    w = win("fullscrn")
    if w.saved_geometry is None:
        w.saved_geometry = (w.origin[0], w.origin[1], w.width, w.height)
    _reshape(w, 0, 0, config.SCREEN_WIDTH, config.SCREEN_HEIGHT)
    viewport(0, config.SCREEN_WIDTH - 1, 0, config.SCREEN_HEIGHT - 1)
    ortho2(-0.5, config.SCREEN_WIDTH - 0.5, -0.5, config.SCREEN_HEIGHT - 0.5)


@glcall(immediate=True)
def endfullscrn():
    """endfullscrn(3G): end fullscrn: the window returns to its place and
    size (viewport and matrices stay as the program left them)."""
    w = win("endfullscrn")
    if w.saved_geometry is None:
        return
    x, y, wd, ht = w.saved_geometry
    w.saved_geometry = None
    _reshape(w, x, y, wd, ht)


@glcall(immediate=True)
def getwscrn():
    """getwscrn(3G): the screen of the current window: 0 (one screen)."""
    win("getwscrn")
    return 0


def _screen(gsnr, focus=False):
    try:
        g = int(gsnr)
    except (TypeError, ValueError, OverflowError):      # OverflowError: int(inf)
        return None
    if g == 0 or (focus and g == K.INFOCUSSCRN):
        return g
    return None


@glcall(immediate=True)
def scrnselect(gsnr):
    """scrnselect(3G): the screen new windows go to; the VGX has one
    (GD_NSCRNS 1): returns the previous screen 0, or -1 for any other."""
    return -1 if _screen(gsnr) is None else 0


@glcall(immediate=True)
def scrnattach(gsnr):
    """scrnattach(3G): input focus to a screen: returns the screen that had
    it (0), or -1 for a screen that does not exist; INFOCUSSCRN asks."""
    return -1 if _screen(gsnr, focus=True) is None else 0
