"""System calls: bell, keyboard and dial box, video, version and
compatibility, multisampling, old pixel calls, z drawing, gamma, the
textport (docs/windows-and-devices.md).

Calls whose effect is only physical (the bell, the lamps, the screen saver,
the textport) keep their state headless and their queries answer it; a
real display gives them effect.
"""
import numpy as np

from vgx_emulator import config
from vgx_emulator.errors import fail

from . import constants as K
from ._current import (HEADLESS, boolean, fill, glcall, integer, machine, not_emulated, num,
                       out_array, token, ulong, win)
from ._current import words as _words

__all__ = ["ringbell", "setbell", "blanktime", "blankscreen", "clkon", "clkoff", "lampon",
           "lampoff", "dbtext", "setdblights", "setvideo", "getvideo", "videocmd",
           "getmonitor", "setmonitor", "getothermonitor", "gversion", "glcompat", "gsync",
           "swapinterval", "mswapbuffers", "RGBsize", "getbuffer", "zdraw", "zsource",
           "pixmode", "pixmodef", "mssize", "msalpha", "msmask", "mspattern", "mssample",
           "multisample", "getmultisample", "gammaramp", "writeRGB", "readRGB",
           "writepixels", "readpixels", "readcomponent", "readdisplay", "textinit",
           "textport", "tpon", "tpoff", "textcolor", "pagecolor", "chunksize", "compactify"]

#: the string gversion(3G) gives on the emulated machine: a VGX with the
#: IRIS GL of IRIX 3.3 (1990)
VERSION = "GL4DVGX-3.3"


def _sys(key, default):
    return machine.system.setdefault(key, default)


def _keep(key, value):
    machine.system[key] = value


# -- bell, keyboard, dial and button box ---------------------------------------------
_PHYS = "the keyboard, dial box and monitor exist only with a display"


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def ringbell():
    """ringbell(3G): ring the keyboard bell (counted: system["bells"])."""
    machine.system["bells"] = machine.system.get("bells", 0) + 1


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def setbell(mode):
    """setbell(3G): bell duration: 0 off, 1 short, 2 long."""
    m = integer("setbell", mode, "mode")
    if m not in (0, 1, 2):
        fail("setbell", f"mode {m}", "0 (off), 1 (short) or 2 (long)")
    _keep("bellmode", m)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def blanktime(nframes):
    """blanktime(3G): blank the screen after nframes without input (0: never)."""
    n = integer("blanktime", nframes, "nframes")
    if n < 0:
        fail("blanktime", f"nframes {n}", "0 (never) or a positive count")
    _keep("blanktime", n)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def blankscreen(b):
    """blankscreen(3G): blank (TRUE) or restore the screen; GLV_UNBLANK of
    getvideo(GL_VIDEO_REG) follows."""
    v = boolean("blankscreen", b)
    _keep("blank", v)
    reg = _video()
    reg[K.GL_VIDEO_REG] = (reg[K.GL_VIDEO_REG] & ~K.GLV_UNBLANK) | (0 if v else K.GLV_UNBLANK)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def clkon():
    """clkon(3G): keyboard click on."""
    _keep("click", True)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def clkoff():
    """clkoff(3G): keyboard click off."""
    _keep("click", False)


def _lamps(call, lamps):
    m = integer(call, lamps, "lamps")
    if not 0 <= m <= 0xF:
        fail(call, f"lamps {m:#x}", "a mask of the four keyboard lamps, 0..0xF")
    return m


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def lampon(lamps):
    """lampon(3G): turn on the keyboard lamps in the 4-bit mask."""
    on = _lamps("lampon", lamps)
    _keep("lamps", _sys("lamps", 0) | on)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def lampoff(lamps):
    """lampoff(3G): turn off the keyboard lamps in the 4-bit mask."""
    off = _lamps("lampoff", lamps)
    _keep("lamps", _sys("lamps", 0) & ~off)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def dbtext(string):
    """dbtext(3G): the 8-character display of the dial and button box."""
    s = str(string)
    if len(s) > 8:
        fail("dbtext", f"{len(s)} characters", "at most 8")
    _keep("dbtext", s)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def setdblights(mask):
    """setdblights(3G): the 32 lights of the dial and button box."""
    _keep("dblights", ulong(integer("setdblights", mask, "mask")))


# -- video and monitor --------------------------------------------------------------
_GLV_BITS = (K.GLV_GENLOCK | K.GLV_UNBLANK | K.GLV_SRED | K.GLV_SGREEN | K.GLV_SBLUE |
             K.GLV_SALPHA | K.GLV_TTLGENLOCK | K.GLV_GREENGENLOCK)


def _video():
    return _sys("video", {K.GL_VIDEO_REG: K.GLV_UNBLANK})


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def setvideo(reg, value):
    """setvideo(3G): write a video register.  The emulated VGX has the
    generic GL_VIDEO_REG (GLV_* bits) and no video option board (CG2, CG3,
    BVO), so any other register is an error."""
    r = integer("setvideo", reg, "register")
    v = integer("setvideo", value, "value")
    if r != K.GL_VIDEO_REG:
        fail("setvideo", f"register {r:#x}", "GL_VIDEO_REG (no video option board)")
    if v & ~_GLV_BITS:
        fail("setvideo", f"value {v:#x} has bits GL_VIDEO_REG does not define",
             "GLV_GENLOCK, GLV_UNBLANK, GLV_SRED, GLV_SGREEN, GLV_SBLUE, GLV_SALPHA, "
             "GLV_TTLGENLOCK, GLV_GREENGENLOCK")
    _video()[r] = v
    _keep("blank", not v & K.GLV_UNBLANK)


@glcall(immediate=True)
def getvideo(reg):
    """getvideo(3G): the register's value, or -1 for a register that is not
    there (getvideo(3G) returns -1 rather than failing)."""
    try:
        r = int(reg)
    except (TypeError, ValueError, OverflowError):      # OverflowError: int(inf)
        return -1
    return _video().get(r, -1)


videocmd = not_emulated("videocmd", "the emulated VGX has no video peripheral (CG2/CG3)")

_FORMATS = {getattr(K, n): n for n in (
    "HZ30", "HZ60", "NTSC", "HDTV", "VGA", "IRIS3K", "PR60", "PAL", "HZ30_SG", "A343",
    "STR_RECT", "VOF0", "VOF1", "VOF2", "VOF3", "SGI0", "SGI1", "SGI2", "HZ72", "HZ50",
    "HZ76", "HZ70", "STR_BOT", "STR_TOP", "PRESENTER", "HZ48")}


@glcall(immediate=True)
def getmonitor():
    """getmonitor(3G): the video format in force: HZ60 (1280x1024, 60 Hz)
    unless setmonitor chose another."""
    return _sys("monitor", K.HZ60)


@glcall(immediate=True, status=HEADLESS, why=_PHYS)
def setmonitor(mtype):
    """setmonitor(3G): choose the video format (kept; the virtual screen
    stays 1280x1024)."""
    _keep("monitor", token("setmonitor", mtype, _FORMATS, "video format"))


@glcall(immediate=True)
def getothermonitor():
    """getothermonitor(3G): the standard of the non-primary (composite)
    video output: NTSC (our choice; the VGX has no second format set)."""
    return _sys("othermonitor", K.NTSC)


@glcall(immediate=True)
def gversion(v=None):
    """gversion(3G): ``ret, v = gversion()``: 0 (the return value has no use,
    gversion(3G)) and the hardware and library string, GL4DVGX-m.n.  As C's
    ``gversion(buf)``, a writable byte buffer (bytearray, uint8 array) is
    filled in place with the NUL-terminated string, and 0 is returned."""
    if v is None:
        return 0, VERSION
    if isinstance(v, str):
        fail("gversion", "a Python str cannot be filled in",
             "write ret, v = gversion(), or pass a bytearray(12)")
    data = VERSION.encode("ascii") + b"\0"
    try:
        if len(v) < len(data):
            fail("gversion", f"buffer of {len(v)} bytes",
                 f"at least {len(data)} (the string and its NUL)")
        if isinstance(v, np.ndarray):
            v.reshape(-1)[:len(data)] = np.frombuffer(data, np.uint8)
        else:
            v[:len(data)] = data
    except TypeError:
        fail("gversion", f"{type(v).__name__} is not a writable byte buffer",
             "pass a bytearray(12) or nothing")
    return 0


_GLC = {K.GLC_OLDPOLYGON: "GLC_OLDPOLYGON", K.GLC_ZRANGEMAP: "GLC_ZRANGEMAP",
        K.GLC_MQUEUERATE: "GLC_MQUEUERATE", K.GLC_SOFTATTACH: "GLC_SOFTATTACH",
        K.GLC_MANAGEBG: "GLC_MANAGEBG", K.GLC_SLOWMAPCOLORS: "GLC_SLOWMAPCOLORS",
        K.GLC_INPUTCHANGEBUG: "GLC_INPUTCHANGEBUG", K.GLC_NOBORDERBUG: "GLC_NOBORDERBUG",
        K.GLC_SET_VSYNC: "GLC_SET_VSYNC", K.GLC_GET_VSYNC: "GLC_GET_VSYNC",
        K.GLC_VSYNC_SLEEP: "GLC_VSYNC_SLEEP", K.GLC_FORCECIMAP: "GLC_FORCECIMAP",
        K.GLC_TABLETSCALE: "GLC_TABLETSCALE"}


@glcall(immediate=True)
def glcompat(mode, value):
    """glcompat(3G): compatibility modes, kept in system["glcompat"]
    (GLC_OLDPOLYGON, GLC_ZRANGEMAP, ...).  They change nothing in drawing
    here (docs/windows-and-devices.md says why)."""
    m = token("glcompat", mode, _GLC, "mode")
    v = integer("glcompat", value, "value")
    _sys("glcompat", {})[m] = v


@glcall
def gsync():
    """gsync(3G): wait for the next vertical retrace: headless, what was
    issued is drawn and the call returns.  In a single-buffered window it
    is a frame point for the runner: GL2-era programs (Haeberli's stars.c)
    pace their frames with it; a double-buffered one has swapbuffers."""
    w = machine.current
    if w is not None and not w.st.double:
        machine.frame_end(w)
    else:
        machine.flush()


@glcall(immediate=True, status=HEADLESS, why="swaps are paced only on a display")
def swapinterval(i):
    """swapinterval(3G): frames between buffer swaps (kept, default 1)."""
    n = integer("swapinterval", i, "interval")
    if not 1 <= n <= 0x7FFF:
        fail("swapinterval", f"interval {n}", "1 or more frames")
    win("swapinterval").wm["swapinterval"] = n


_DRAWMODES = K.NORMALDRAW | K.PUPDRAW | K.OVERDRAW | K.UNDERDRAW


@glcall
def mswapbuffers(fbuf):
    """mswapbuffers(3G): swap the framebuffers in the mask; NORMALDRAW swaps
    the normal front and back (as swapbuffers), the overlay, underlay and
    pop-up planes have no second buffer here."""
    w = win("mswapbuffers")
    m = integer("mswapbuffers", fbuf, "mask")
    if m & ~_DRAWMODES or not m:
        fail("mswapbuffers", f"mask {m:#x}",
             "an OR of NORMALDRAW, OVERDRAW, UNDERDRAW, PUPDRAW")
    if m & K.NORMALDRAW:
        machine.swapbuffers(w)


@glcall(immediate=True)
def RGBsize(planes):
    """RGBsize(3G): bits per colour component asked for at gconfig; the VGX
    gives 8 whatever is asked (getgconfig tells)."""
    n = integer("RGBsize", planes, "planes")
    if not 1 <= n <= 12:
        fail("RGBsize", f"{n} planes", "1..12 per component")
    win("RGBsize").wm["rgbsize"] = n


@glcall
def getbuffer():
    """getbuffer(3G): the buffers drawing goes to: BCKBUFFER, FRNTBUFFER,
    DRAWZBUFFER (zdraw) OR-ed."""
    st = win("getbuffer").st
    v = 0
    if st.double and st.back_enabled:
        v |= K.BCKBUFFER
    if st.front_enabled or (not st.double and not st.zdraw):
        v |= K.FRNTBUFFER
    if st.zdraw:
        v |= K.DRAWZBUFFER
    return v


# -- z drawing ------------------------------------------------------------------------
@glcall
def zdraw(b):
    """zdraw(3G): draw colours into the z-buffer as into a third colour
    buffer (with zbuffer FALSE).  FALSE after gconfig."""
    w = win("zdraw")
    v = boolean("zdraw", b)
    machine.state_change(w)
    w.st.zdraw = v
    if not v and not w.st.double:
        w.st.front_enabled = True


@glcall
def zsource(src):
    """zsource(3G): what the z test compares: ZSRC_DEPTH (depth values).
    ZSRC_COLOR (compare colours) is not emulated."""
    w = win("zsource")
    s = token("zsource", src, {K.ZSRC_DEPTH: "ZSRC_DEPTH", K.ZSRC_COLOR: "ZSRC_COLOR"},
              "source")
    if s == K.ZSRC_COLOR:
        fail("zsource", "ZSRC_COLOR is not emulated", "ZSRC_DEPTH")
    machine.state_change(w)
    w.st.zsource = s


# -- pixmode ----------------------------------------------------------------------------
_PM = {v: n for n, v in vars(K).items() if n.startswith("PM_") and n[3:] in (
    "SHIFT", "EXPAND", "C0", "C1", "ADD24", "SIZE", "OFFSET", "STRIDE", "TTOB", "RTOL",
    "ZDATA", "WARP", "RDX", "RDY", "CDX", "CDY", "XSTART", "YSTART", "VO1")}
#: the default of each mode (pixmode(3G))
PM_DEFAULTS = {K.PM_SHIFT: 0, K.PM_EXPAND: 0, K.PM_C0: 0, K.PM_C1: 0, K.PM_ADD24: 0,
               K.PM_SIZE: 32, K.PM_OFFSET: 0, K.PM_STRIDE: 0, K.PM_TTOB: 0, K.PM_RTOL: 0,
               K.PM_ZDATA: 0}


def _pixmode(call, mode, value):
    w = win(call)
    m = token(call, mode, _PM, "mode")
    if m in (K.PM_TTOB, K.PM_RTOL):
        value = int(bool(value))
    elif value != PM_DEFAULTS.get(m, 0):
        fail(call, f"{_PM[m]} {value} is not emulated",
             f"{_PM[m]} {PM_DEFAULTS.get(m, 0)} (only PM_TTOB and PM_RTOL take other values)")
    w.wm.setdefault("pixmode", dict(PM_DEFAULTS))[m] = value


@glcall
def pixmode(mode, value):
    """pixmode(3G): pixel transfer modes of lrectwrite/lrectread and their
    16-bit forms: PM_TTOB (rows top to bottom) and PM_RTOL (columns right
    to left) are honoured; the other modes accept their default only."""
    _pixmode("pixmode", mode, integer("pixmode", value, "value"))


@glcall
def pixmodef(mode, value):
    """pixmodef(3G): pixmode with a float value."""
    _pixmode("pixmodef", mode, num("pixmodef", value, "value"))


# -- multisampling: the VGX has no multisample buffer -----------------------------------
def _ms(call, key, value):
    win(call)
    _sys("multisample", {})[key] = value


@glcall(immediate=True)
def mssize(samples, zsize, ssize):
    """mssize(3G): multisample buffer asked for at gconfig; the VGX has none
    (GD_MULTISAMPLE 0), so gconfig configures 0 samples
    (getgconfig(GC_MS_SAMPLES) = 0) and drawing is single-sample."""
    vals = [integer("mssize", v, w) for v, w in ((samples, "samples"), (zsize, "zsize"),
                                                  (ssize, "ssize"))]
    if min(vals) < 0:
        fail("mssize", f"sizes {vals}", "non-negative counts")
    win("mssize").wm["mssize"] = tuple(vals)


@glcall
def msalpha(mode):
    """msalpha(3G): MSA_MASK, MSA_MASK_ONE or MSA_ALPHA (kept; no effect
    without a multisample buffer)."""
    _ms("msalpha", "alpha", token("msalpha", mode, {K.MSA_MASK: "MSA_MASK", K.MSA_MASK_ONE:
                                         "MSA_MASK_ONE", K.MSA_ALPHA: "MSA_ALPHA"}, "mode"))


@glcall
def msmask(mask, inverse):
    """msmask(3G): sample mask coverage 0..1 (clamped) and its inversion (kept)."""
    m = num("msmask", mask, "mask")
    if m != m:
        fail("msmask", "mask is NaN", "0.0..1.0")
    _ms("msmask", "mask", (min(max(m, 0.0), 1.0), boolean("msmask", inverse)))


_MSP = {v: n for n, v in vars(K).items() if n.startswith("MSP_")}


@glcall
def mspattern(pattern):
    """mspattern(3G): MSP_DEFAULT or a 2-/4-pass pattern (kept)."""
    _ms("mspattern", "pattern", token("mspattern", pattern, _MSP, "pattern"))


@glcall
def mssample(sample):
    """mssample(3G): MSS_POINT, MSS_AREA or MSS_CENTER_POINT (kept)."""
    _ms("mssample", "sample", token("mssample", sample, {K.MSS_POINT: "MSS_POINT", K.MSS_AREA:
                                             "MSS_AREA", K.MSS_CENTER_POINT:
                                             "MSS_CENTER_POINT"}, "sample"))


@glcall
def multisample(b):
    """multisample(3G): use the multisample buffer (default TRUE); with none
    configured it changes nothing."""
    _ms("multisample", "on", boolean("multisample", b))


@glcall
def getmultisample():
    """getmultisample(3G): TRUE if multisample is enabled (multisample(3G))."""
    win("getmultisample")
    return int(_sys("multisample", {}).get("on", True))


# -- gamma ramp -----------------------------------------------------------------------
@glcall(immediate=True)
def gammaramp(r, g, b):
    """gammaramp(3G): 256-entry tables every displayed red, green and blue
    goes through at scan-out (the bitplanes keep the true values);
    entries clamped to 0..255.  The identity is the default."""
    lut = np.empty((256, 3), np.uint8)
    for c, (a, name) in enumerate(((r, "r"), (g, "g"), (b, "b"))):
        try:
            arr = np.asarray(a, dtype=np.float64).reshape(-1)
        except (TypeError, ValueError):
            fail("gammaramp", f"{name} is not an array of numbers", "256 shorts per table")
        if arr.size < 256:
            fail("gammaramp", f"{name} has {arr.size} entries", "256 per table")
        arr = np.nan_to_num(arr[:256], nan=0.0)
        lut[:, c] = np.clip(arr, 0, 255).astype(np.uint8)
    ident = np.arange(256, dtype=np.uint8)
    machine.gamma = None if all((lut[:, c] == ident).all() for c in range(3)) else lut


# -- old pixel calls: a row at the character position -----------------------------------
def _cpos(w):
    """The current character position in window pixels (set by cmov; the
    pixel calls advance it).  WindowState.cpos, (0, 0) if none was set."""
    p = getattr(w.st, "cpos", None)
    if p is None:
        return 0, 0
    return int(round(p[0])), int(round(p[1]))


def _set_cpos(w, x, y):
    w.st.cpos = (x, y)


def _count(call, n):
    n = integer(call, n, "n")
    if not 0 <= n <= 0x7FFF:
        fail(call, f"n = {n}", "0..32767 pixels (a short)")
    return n


def _row(call, a, n, what, mask):
    try:
        arr = np.asarray(a).reshape(-1)
        if arr.dtype.kind not in "iubfO":
            raise TypeError
        if arr.size < n:
            fail(call, f"{what} has {arr.size} elements", f"n = {n}")
        return _words(arr[:n], mask)
    except (TypeError, ValueError):
        fail(call, f"{what} is not an array of integers", f"{n} values")


def _write_row(call, w, words):
    x, y = _cpos(w)
    if len(words) and getattr(w.st, "cpos_valid", True):
        machine.write_pixels(w, x, y, words.reshape(1, -1).astype(np.uint32), (1.0, 1.0))
    _set_cpos(w, x + len(words), y)


@glcall
def writeRGB(n, red, green, blue):
    """writeRGB(3G): n RGB pixels from the character position rightwards
    (RGB mode); the position moves past the last one.  No rectzoom."""
    w = win("writeRGB")
    n = _count("writeRGB", n)
    if not w.st.rgb:
        fail("writeRGB", "in colour-map mode", "RGBmode() then gconfig(); or writepixels")
    r, g, b = (_row("writeRGB", a, n, nm, 0xFF) for a, nm in
               ((red, "red"), (green, "green"), (blue, "blue")))
    _write_row("writeRGB", w, (0xFF << 24) | (b << 16) | (g << 8) | r)


@glcall
def writepixels(n, colors):
    """writepixels(3G): n colour-index pixels from the character position
    rightwards (colour-map mode); the position moves past the last one."""
    w = win("writepixels")
    n = _count("writepixels", n)
    if w.st.rgb:
        fail("writepixels", "in RGB mode", "cmode() then gconfig(); or writeRGB")
    _write_row("writepixels", w, _row("writepixels", colors, n, "colors", 0xFFFF))


def _read_row(call, w, n):
    """(count, words) read from the character position; count 0 when the
    position is outside the viewport (readRGB(3G))."""
    x, y = _cpos(w)
    vp = w.st.viewport
    if n == 0 or not getattr(w.st, "cpos_valid", True) or \
            not (vp[0] <= x <= vp[1] and vp[2] <= y <= vp[3]):
        return 0, np.zeros(n, np.uint32)
    row = machine.lrectread(w, x, y, x + n - 1, y, w.readsource).reshape(-1)
    _set_cpos(w, x + n, y)
    return n, row.view(np.uint32) if row.dtype == np.int32 else row


@glcall(immediate=True)
def readRGB(n, red=None, green=None, blue=None):
    """readRGB(3G): n pixels from the character position rightwards (from
    readsource), 0 if it is outside the viewport; the position moves past
    the last one.  ``count, r, g, b = readRGB(n)``; given the three arrays
    (C's), fills them and returns the count, as C does."""
    w = win("readRGB")
    n = _count("readRGB", n)
    if not w.st.rgb:
        fail("readRGB", "in colour-map mode", "RGBmode() then gconfig(); or readpixels")
    given = (red, green, blue)
    if any(a is not None for a in given) and any(a is None for a in given):
        fail("readRGB", "some of red, green, blue given", "pass all three arrays, or none")
    for a, what in zip(given, ("red", "green", "blue")):
        out_array("readRGB", a, n, what)
    count, words = _read_row("readRGB", w, n)
    out = [((words >> s) & 0xFF).astype(np.uint8) for s in (0, 8, 16)]
    if red is None:
        return (count,) + tuple(out)
    for a, val in zip(given, out):
        fill(a, val[:count])
    return count


@glcall(immediate=True)
def readpixels(n, colors=None):
    """readpixels(3G): n colour indices from the character position
    rightwards, 0 if it is outside the viewport; the position moves past
    the last one.  ``count, colors = readpixels(n)``; ``readpixels(n, buf)``
    fills buf and returns the count, as C does.  Colour-map mode only, as
    readpixels(3G) says (RGB mode: readRGB)."""
    w = win("readpixels")
    n = _count("readpixels", n)
    if w.st.rgb:
        fail("readpixels", "in RGB mode", "cmode() then gconfig(); or readRGB")
    out_array("readpixels", colors, n, "colors")
    count, words = _read_row("readpixels", w, n)
    vals = (words.astype(np.int64) & 0xFFFF).astype(np.uint16)
    if colors is None:
        return count, vals
    fill(colors, vals[:count])
    return count


_RC = {K.RC_ABGR: "RC_ABGR", K.RC_ALPHA: "RC_ALPHA", K.RC_BLUE: "RC_BLUE",
       K.RC_GREEN: "RC_GREEN", K.RC_RED: "RC_RED"}


@glcall
def readcomponent(c):
    """readcomponent(3G): the component the pixel reads transfer: RC_ABGR
    (the default, all four).  A single component (RC_RED ...) is not
    emulated."""
    w = win("readcomponent")
    v = token("readcomponent", c, _RC, "component")
    if v != K.RC_ABGR:
        fail("readcomponent", f"{_RC[v]} is not emulated", "RC_ABGR")
    w.wm["readcomponent"] = v


@glcall(immediate=True)
def readdisplay(x1, y1, x2, y2, parray=None, hints=0):
    """readdisplay(3G): the screen rectangle (corners in any order,
    inclusive) as displayed: every window at its place, front ones over back
    ones, the rest of the screen black; packed ABGR with alpha 0xFF.
    Returns an (h, w) uint32 array (row 0 at the bottom), or, given
    ``parray``, fills it and returns the pixel count."""
    xs = sorted(integer("readdisplay", v) for v in (x1, x2))
    ys = sorted(integer("readdisplay", v) for v in (y1, y2))
    integer("readdisplay", hints, "hints")
    wd, ht = xs[1] - xs[0] + 1, ys[1] - ys[0] + 1
    if wd > 2 * config.SCREEN_WIDTH or ht > 2 * config.SCREEN_HEIGHT:
        fail("readdisplay", f"a {wd}x{ht} rectangle", "at most the screen")
    out_array("readdisplay", parray, wd * ht, "parray", f"{wd * ht} elements, or nothing")
    from vgx_emulator.display import screen_words
    out = screen_words(machine, xs[0], xs[1], ys[0], ys[1])
    if parray is None:
        return out
    fill(parray, out.reshape(-1))
    return wd * ht


# -- the textport: a shell's text window, headless state --------------------------------
_TP = "the textport is a window of the display's shell"


def _tp():
    return _sys("textport", {"on": True, "rect": (0, config.SCREEN_WIDTH - 1, 0,
                                                  config.SCREEN_HEIGHT - 1),
                             "textcolor": 7, "pagecolor": 0})


@glcall(immediate=True, status=HEADLESS, why=_TP)
def textinit():
    """textinit(3G): the textport returns to its default place and colours."""
    machine.system.pop("textport", None)
    _tp()


@glcall(immediate=True, status=HEADLESS, why=_TP)
def textport(left, right, bottom, top):
    """textport(3G): where the textport goes (screen coordinates)."""
    r = tuple(integer("textport", v) for v in (left, right, bottom, top))
    if r[0] > r[1] or r[2] > r[3]:
        fail("textport", f"rectangle {r}", "left <= right, bottom <= top")
    _tp()["rect"] = r


@glcall(immediate=True, status=HEADLESS, why=_TP)
def tpon():
    """tpon(3G): show the textport."""
    _tp()["on"] = True


@glcall(immediate=True, status=HEADLESS, why=_TP)
def tpoff():
    """tpoff(3G): hide the textport."""
    _tp()["on"] = False


@glcall(immediate=True, status=HEADLESS, why=_TP)
def textcolor(tcolor):
    """textcolor(3G): colour index of the textport's text."""
    _tp()["textcolor"] = integer("textcolor", tcolor, "colour") & 0xFFF


@glcall(immediate=True, status=HEADLESS, why=_TP)
def pagecolor(pcolor):
    """pagecolor(3G): colour index of the textport's background."""
    _tp()["pagecolor"] = integer("pagecolor", pcolor, "colour") & 0xFFF


# -- display-list memory ------------------------------------------------------------------
@glcall(immediate=True)
def chunksize(chunk):
    """chunksize(3G): memory granule of display lists, before the first
    makeobj (kept; objects here grow as needed)."""
    n = integer("chunksize", chunk, "chunk")
    if n <= 0:
        fail("chunksize", f"chunk {n}", "a positive byte count")
    _keep("chunksize", n)


@glcall(immediate=True)
def compactify(obj):
    """compactify(3G): compact an object's storage: nothing to do here; the
    object must exist."""
    o = integer("compactify", obj, "object")
    if o not in machine.objects:
        fail("compactify", f"object {o} does not exist", "pass an object made with makeobj")
