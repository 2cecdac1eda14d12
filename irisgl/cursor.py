"""Cursors (defcursor(3G), setcursor(3G), curstype(3G) ...;
docs/windows-and-devices.md).

Headless there is no cursor to see: the calls keep the cursor table and the
current cursor, and the queries answer them; a real display draws it.
Cursor 0 is the predefined arrow and cannot be redefined.
"""
from vgx_emulator import events as E
from vgx_emulator.errors import fail

from . import constants as K
from ._current import HEADLESS, glcall, integer, machine

__all__ = ["defcursor", "setcursor", "getcursor", "curson", "cursoff", "curstype",
           "curorigin", "RGBcursor", "gRGBcursor", "attachcursor"]

_WHY = "the cursor is drawn only on a display"
_TYPES = {K.C16X1: "C16X1", K.C16X2: "C16X2", K.C32X1: "C32X1", K.C32X2: "C32X2",
          K.CCROSS: "CCROSS"}
#: 16-bit words a glyph of each type holds (two layers for the x2 types)
_WORDS = {K.C16X1: 16, K.C16X2: 32, K.C32X1: 64, K.C32X2: 128}


def _cursor():
    """The cursor state, created with its defaults (getcursor(3G): glyph 0,
    colour 1, writemask 1, shown and updated by the system)."""
    c = machine.system.get("cursor")
    if c is None:
        c = machine.system["cursor"] = {
            "glyphs": {0: (K.C16X1, None)},      # the arrow: type, words
            "origins": {0: (0, 0)},
            "type": K.C16X1, "index": 0, "color": 1, "wtm": 1, "visible": True,
            "rgb": {0: (255, 0, 0, 255, 255, 255)},
            "attached": (E.MOUSEX, E.MOUSEY)}
    return c


def _defined(call, n):
    n = integer(call, n, "cursor index")
    if n not in _cursor()["glyphs"]:
        fail(call, f"cursor {n} is not defined", "define it with defcursor first")
    return n


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def defcursor(n, curs):
    """defcursor(3G): glyph n from a bitmap of 16-bit words, 16 (C16X1), 32
    (C16X2), 64 (C32X1) or 128 (C32X2) of them as curstype says; ignored
    for CCROSS.  Cursor 0 (the arrow) cannot be redefined."""
    c = _cursor()
    n = integer("defcursor", n, "cursor index")
    if n == 0:
        fail("defcursor", "cursor 0 is the predefined arrow", "use an index 1..32767")
    if not 0 < n <= 0x7FFF:
        fail("defcursor", f"cursor index {n}", "1..32767 (a short)")
    t = c["type"]
    if t == K.CCROSS:
        return
    need = _WORDS[t]
    try:
        if len(curs) < need:
            fail("defcursor", f"glyph has {len(curs)} words",
                 f"{_TYPES[t]} takes {need} 16-bit words")
        words = tuple(integer("defcursor", curs[i], "glyph word") & 0xFFFF
                      for i in range(need))
    except TypeError:
        fail("defcursor", "glyph is not an array", f"pass {need} 16-bit words")
    c["glyphs"][n] = (t, words)
    c["origins"].setdefault(n, (0, 0))
    c["rgb"].setdefault(n, (255, 0, 0, 255, 255, 255))


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def setcursor(index, color, wtm):
    """setcursor(3G): make glyph ``index`` the cursor, with colour and
    writemask (kept; the 4D draws the cursor in its own planes)."""
    n = _defined("setcursor", index)
    col = integer("setcursor", color, "color") & 0xFFFF
    m = integer("setcursor", wtm, "writemask") & 0xFFFF
    c = _cursor()
    c["index"], c["color"], c["wtm"] = n, col, m


@glcall(immediate=True)
def getcursor():
    """getcursor(3G): ``index, color, wtm, b = getcursor()``: the glyph,
    its colour and writemask, and whether the cursor is shown."""
    c = _cursor()
    return c["index"], c["color"], c["wtm"], int(c["visible"])


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def curson():
    """curson(3G): show the cursor."""
    _cursor()["visible"] = True


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def cursoff():
    """cursoff(3G): hide the cursor."""
    _cursor()["visible"] = False


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def curstype(typ):
    """curstype(3G): the type of the glyphs defcursor defines next: C16X1,
    C16X2, C32X1, C32X2 or CCROSS (a cross-hair)."""
    t = integer("curstype", typ, "type")
    if t not in _TYPES:
        fail("curstype", f"unknown type {typ!r}", "C16X1, C16X2, C32X1, C32X2 or CCROSS")
    _cursor()["type"] = t


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def curorigin(n, xorigin, yorigin):
    """curorigin(3G): the hot spot of glyph n, from its lower-left corner."""
    n = _defined("curorigin", n)
    x = integer("curorigin", xorigin, "xorigin")
    y = integer("curorigin", yorigin, "yorigin")
    t = _cursor()["glyphs"][n][0]
    size = 32 if t in (K.C32X1, K.C32X2) else 16
    if not (0 <= x < size and 0 <= y < size):
        fail("curorigin", f"origin ({x}, {y}) is outside the {size}x{size} glyph",
             f"0..{size - 1} each way")
    _cursor()["origins"][n] = (x, y)


def _byte(call, v, what):
    return min(max(integer(call, v, what), 0), 255)


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def RGBcursor(index, red, green, blue, redm, greenm, bluem):
    """RGBcursor(3G): make glyph ``index`` the cursor, with an RGB colour
    and writemask (values clamped to 0..255)."""
    n = _defined("RGBcursor", index)
    vals = tuple(_byte("RGBcursor", v, w) for v, w in (
        (red, "red"), (green, "green"), (blue, "blue"),
        (redm, "redm"), (greenm, "greenm"), (bluem, "bluem")))
    c = _cursor()
    c["index"] = n
    c["rgb"][n] = vals


@glcall(immediate=True)
def gRGBcursor():
    """gRGBcursor(3G): ``index, red, green, blue, redm, greenm, bluem, b =
    gRGBcursor()``: the cursor, its RGB colour and mask, and whether shown."""
    c = _cursor()
    return (c["index"],) + tuple(c["rgb"][c["index"]]) + (int(c["visible"]),)


@glcall(immediate=True, status=HEADLESS, why=_WHY)
def attachcursor(vx, vy):
    """attachcursor(3G): the valuators that move the cursor (MOUSEX, MOUSEY
    by default)."""
    ds = []
    for v, w in ((vx, "vx"), (vy, "vy")):
        d = integer("attachcursor", v, w)
        if not E.is_valuator(d):
            fail("attachcursor", f"{w} {d} is not a valuator", "valuators 256-511")
        ds.append(d)
    _cursor()["attached"] = tuple(ds)
