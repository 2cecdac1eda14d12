"""Characters and fonts: cmov*, charstr, lcharstr, strwidth, lstrwidth,
getheight, getdescender, getcpos, font, getfont, getfontencoding,
defrasterfont, deflfont, loadXfont (docs/text-and-menus.md).

``cmov*`` sends a point through the current matrices and viewport like a
vertex; it becomes the character position (x, y and z).  ``charstr`` draws
the current font's glyphs there, left to right, with the current colour and
writemask and one z (the origin's) for every pixel; a string whose origin
lies outside the viewport is dropped, otherwise its pixels are clipped to
the screen mask (charstr(3G)).  The position then advances past the string.
Font 0 is the 9x15 fixed-pitch font (vgx_emulator/fonts).
"""
import math

import numpy as np

from vgx_emulator import fonts as F
from vgx_emulator.errors import fail, warn

from . import constants as K
from ._current import glcall, integer, machine, num, token, win

__all__ = ["cmov", "cmov2", "cmovi", "cmovs", "cmov2i", "cmov2s", "charstr", "lcharstr",
           "strwidth", "lstrwidth", "getheight", "getdescender", "getcpos", "font",
           "getfont", "getfontencoding", "defrasterfont", "deflfont", "loadXfont"]

_STR_TYPES = {K.STR_B: "STR_B", K.STR_2B: "STR_2B", K.STR_3B: "STR_3B", K.STR_4B: "STR_4B",
              K.STR_16: "STR_16", K.STR_32: "STR_32"}
_BYTES_PER = {K.STR_B: 1, K.STR_2B: 2, K.STR_3B: 3, K.STR_4B: 4}


# -- character position ----------------------------------------------------------
def _move(call, x, y, z):
    """The point (x, y, z) through ModelView, Projection and the viewport
    (the mapping of geometry/viewport.py, not snapped) becomes the character
    position.  Strings are drawn there only while it lies inside the clip
    volume: w > 0 and z inside here, x and y inside the viewport at charstr."""
    w = win(call)
    st = w.st
    mv, proj = st.matrices.vertex_matrices()
    with np.errstate(all="ignore"):
        c = np.array([x, y, z, 1.0]) @ mv @ proj
    if not np.isfinite(c).all() or c[3] == 0.0:
        warn(call, "the character position is not finite; strings drawn there are dropped")
        st.cpos_valid = False
        return
    cx, cy, cz, cw = (float(v) for v in c)
    if machine._picking(w):
        machine.flush()                 # what was drawn before counts under its names
        machine.picking.test_point(cx, cy, cz, cw)      # pick(3G): cmov causes hits
    l, r, b, t = st.viewport
    near, far = st.depth_range
    xw = (l - 0.5) + (cx / cw + 1.0) * 0.5 * (r - l + 1)
    yw = (b - 0.5) + (cy / cw + 1.0) * 0.5 * (t - b + 1)
    zw = (far + near) * 0.5 + (cz / cw) * ((far - near) * 0.5)
    st.cpos = (xw, yw)
    st.cpos_z = zw
    # x and y are judged by each charstr against the viewport (the position
    # advances); w and z only here
    st.cpos_valid = cw > 0 and abs(cz) <= cw


def _cmov_call(name, dim, conv):
    def call(*args):
        if len(args) != dim:
            fail(name, f"{len(args)} coordinates", f"it takes {dim}")
        p = [float(conv(name, a, "coordinate")) for a in args] + [0.0] * (3 - dim)
        _move(name, *p)
    call.__name__ = call.__qualname__ = name
    call.__doc__ = (f"{name}(3G): the character position := the {dim}-D point, "
                    "transformed like a vertex (the graphics position is untouched).")
    return glcall(call)


cmov = _cmov_call("cmov", 3, num)
cmovi = _cmov_call("cmovi", 3, integer)
cmovs = _cmov_call("cmovs", 3, integer)
cmov2 = _cmov_call("cmov2", 2, num)
cmov2i = _cmov_call("cmov2i", 2, integer)
cmov2s = _cmov_call("cmov2s", 2, integer)


@glcall
def getcpos():
    """getcpos(3G): ``x, y = getcpos()``, the window-relative character
    position in pixels."""
    x, y = win("getcpos").st.cpos[:2]
    return int(math.floor(x + 0.5)), int(math.floor(y + 0.5))


# -- strings -------------------------------------------------------------------
def _char_codes(call, s):
    """The character ids of a C string: one byte each, up to the first NUL."""
    if isinstance(s, str):
        codes = [ord(c) for c in s]
        if codes and max(codes) > 255:
            bad = next(c for c in s if ord(c) > 255)
            fail(call, f"character {bad!r} (U+{ord(bad):04X}) is not one byte",
                 "a C string holds bytes 1-255; use lcharstr(STR_16, ...) for wider ids")
    elif isinstance(s, (bytes, bytearray, memoryview)):
        codes = list(bytes(s))
    else:
        fail(call, f"string {s!r} is not a str or bytes", "pass a str")
    a = np.array(codes, np.int64)
    z = np.nonzero(a == 0)[0]
    return a[:z[0]] if len(z) else a


def _typed_codes(call, kind, s):
    """lcharstr/lstrwidth: character ids of the given STR_* type, up to the
    first zero id (charstr(3G) formulas: STR_2B = s[2i]*256 + s[2i+1] ...)."""
    t = token(call, kind, _STR_TYPES, "string type")
    if t in _BYTES_PER:
        if isinstance(s, str):
            raw = _char_codes(call, s)
        elif isinstance(s, (bytes, bytearray, memoryview)):
            raw = np.frombuffer(bytes(s), np.uint8).astype(np.int64)
        else:
            raw = _int_array(call, s) & 0xFF
        n = _BYTES_PER[t]
        raw = raw[:len(raw) // n * n].reshape(-1, n)
        a = np.zeros(len(raw), np.int64)
        for k in range(n):                 # most significant byte first
            a = a * 256 + raw[:, k]
    else:
        if isinstance(s, str):
            a = np.array([ord(c) for c in s], np.int64)
        else:
            a = _int_array(call, s)
        a &= 0xFFFF if t == K.STR_16 else 0xFFFFFFFF
    z = np.nonzero(a == 0)[0]
    return a[:z[0]] if len(z) else a


def _int_array(call, s):
    try:
        a = np.asarray(s)
        if a.ndim != 1 or not (np.issubdtype(a.dtype, np.integer) or len(a) == 0):
            raise TypeError
        return a.astype(np.int64)
    except (TypeError, ValueError):
        fail(call, "the string is not a sequence of character ids",
             "pass a str, bytes, or a sequence of integers")


def _font(st):
    """The current font: a defined font n, or font 0."""
    return machine.fonts.get(st.font) or F.default_font()


def _draw(call, codes):
    w = win(call)
    st = w.st
    f = _font(st)
    xs, ys, dx, dy = f.layout(codes)
    x, y = st.cpos[:2]
    l, r, b, t = st.viewport
    if st.cpos_valid and l - 0.5 <= x <= r + 0.5 and b - 0.5 <= y <= t + 0.5 and len(xs):
        ox, oy = math.floor(x + 0.5), math.floor(y + 0.5)
        machine.char_pixels(w, xs + ox, ys + oy, st.cpos_z)
    st.cpos = (x + dx, y + dy)


@glcall
def charstr(s):
    """charstr(3G): the string in the current raster font at the character
    position, which then advances by the characters' spacing."""
    _draw("charstr", _char_codes("charstr", s))


@glcall
def lcharstr(kind, s):
    """lcharstr(3G): charstr for character ids of type STR_B, STR_2B,
    STR_3B, STR_4B (bytes, most significant first), STR_16 or STR_32."""
    _draw("lcharstr", _typed_codes("lcharstr", kind, s))


@glcall(immediate=True)
def strwidth(s):
    """strwidth(3G): the string's width in pixels in the current font
    (undefined characters have zero width)."""
    st = win("strwidth").st
    return _font(st).advance(_char_codes("strwidth", s))[0]


@glcall(immediate=True)
def lstrwidth(kind, s):
    """lstrwidth(3G): strwidth for lcharstr's character id types."""
    st = win("lstrwidth").st
    return _font(st).advance(_typed_codes("lstrwidth", kind, s))[0]


# -- fonts -----------------------------------------------------------------------
@glcall
def getheight():
    """getheight(3G): the current font's height, ascender top to descender
    bottom (15 for font 0; ``ht`` for a defrasterfont font)."""
    return _font(win("getheight").st).height


@glcall
def getdescender():
    """getdescender(3G): the current font's longest descender (3 for font 0)."""
    return _font(win("getdescender").st).descender


@glcall
def font(n):
    """font(3G): select raster font n for charstr; an undefined n selects 0."""
    w = win("font")
    n = integer("font", n, "font")
    w.st.font = n if n in machine.fonts else 0


@glcall
def getfont():
    """getfont(3G): the current font's index."""
    st = win("getfont").st
    return st.font if st.font in machine.fonts else 0


@glcall
def getfontencoding():
    """getfontencoding(3G): the registry and encoding of the current font
    (``"ISO8859-1"`` for font 0 and the shipped X fonts; empty for user
    defined fonts, whose string the man page says is NULL)."""
    return _font(win("getfontencoding").st).encoding


def _font_number(call, n):
    n = integer(call, n, "font")
    if n == 0:
        fail(call, "font 0 cannot be redefined", "use another index")
    if not -0x80000000 <= n <= 0x7FFFFFFF:
        fail(call, f"font {n}", "a long index")
    return n


def _records(call, chars, nc, width, what):
    """nc rows of ``width`` integers from chars (the first nc are read)."""
    if isinstance(chars, np.ndarray) and np.issubdtype(chars.dtype, np.integer) and \
            chars.ndim == 2 and chars.shape[0] >= nc and chars.shape[1] >= width:
        return chars[:nc, :width].astype(np.int64)
    try:
        rows = [list(chars[i]) for i in range(nc)]
    except (IndexError, TypeError, KeyError):
        fail(call, f"chars has fewer than nc = {nc} {what} records",
             f"pass nc records of {width} integers")
    if any(len(r) < width for r in rows):
        fail(call, f"a {what} record has fewer than {width} fields",
             f"each record is {width} integers")
    return np.array([[integer(call, v, f"{what} field") for v in r[:width]] for r in rows],
                    np.int64).reshape(nc, width)


def _raster(call, raster, nr):
    """The first nr shorts of raster.  An nr past the array's end (C's
    ``sizeof bits``, bytes for an array of shorts, as SGI's font3.c passes)
    reads the whole array: the C library read past it harmlessly, as no
    glyph's bitmap lies there, and _check_bitmaps still refuses a glyph
    that would (its count is the length returned)."""
    try:
        r = np.asarray(list(raster[:nr]) if not isinstance(raster, np.ndarray)
                       else raster.reshape(-1)[:nr])
    except TypeError:
        fail(call, "raster is not a sequence of 16-bit integers", "pass nr shorts")
    if nr and not np.issubdtype(r.dtype, np.integer):
        fail(call, "raster holds something that is not an integer", "pass nr shorts")
    return (r.astype(np.int64) & 0xFFFF).astype(np.uint16)


def _check_bitmaps(call, offset, w, h, nr):
    need = offset + h * ((w + 15) // 16)
    bad = np.nonzero((h > 0) & (w > 0) & ((offset < 0) | (need > nr)))[0]
    if len(bad):
        i = int(bad[0])
        fail(call, f"character {i}'s bitmap (offset {int(offset[i])}, {int(h[i])} rows of "
             f"{(int(w[i]) + 15) // 16} words) runs past raster[{nr}]",
             "each bitmap is h rows of (w + 15) / 16 shorts inside raster")


def _font_counts(call, n, nc, nr):
    """nc (records) and nr (raster shorts) of a font definition; nc = 0
    deletes font n (defrasterfont(3G), deflfont(3G))."""
    nc = integer(call, nc, "nc")
    nr = integer(call, nr, "nr")
    if nc < 0 or nr < 0:
        fail(call, f"nc = {nc}, nr = {nr}", "counts are >= 0")
    if nc == 0:
        machine.fonts.pop(n, None)
    return nc, nr


@glcall(immediate=True)
def defrasterfont(n, ht, nc, chars, nr, raster):
    """defrasterfont(3G): font n from nc Fontchar records (offset, w, h,
    xoff, yoff, width; character value = record index) and nr shorts of
    bitmap rows, bottom to top, left-justified.  nc = 0 deletes font n."""
    call = "defrasterfont"
    n = _font_number(call, n)
    ht = integer(call, ht, "ht")
    nc, nr = _font_counts(call, n, nc, nr)
    if nc == 0:
        return
    rec = _records(call, chars, nc, 6, "Fontchar")
    rs = _raster(call, raster, nr)
    offset, w, h, xoff, yoff = (rec[:, k] for k in range(5))
    for name, col, lo, hi in (("offset", offset, 0, 0xFFFF), ("w", w, 0, 255),
                              ("h", h, 0, 255), ("xoff", xoff, -128, 127),
                              ("yoff", yoff, -128, 127), ("width", rec[:, 5], -32768, 32767)):
        if ((col < lo) | (col > hi)).any():
            fail(call, f"a Fontchar {name} is outside {lo}..{hi}",
                 "Fontchar: unsigned short offset; Byte w, h; signed char xoff, yoff; "
                 "short width")
    _check_bitmaps(call, offset, w, h, len(rs))
    machine.fonts[n] = F.user_font(ht, rec, rs)


@glcall(immediate=True)
def deflfont(n, nc, chars, nr, raster):
    """deflfont(3G): font n from nc Lfontchar records (value, offset, w, h,
    xoff, yoff, xmove, ymove) and nr shorts of bitmap; xmove and ymove are
    added to the character position after each character."""
    call = "deflfont"
    n = _font_number(call, n)
    nc, nr = _font_counts(call, n, nc, nr)
    if nc == 0:
        return
    rec = _records(call, chars, nc, 8, "Lfontchar")
    rs = _raster(call, raster, nr)
    if (rec[:, 2:4] < 0).any():
        fail(call, "an Lfontchar w or h is negative", "w, h >= 0")
    rec[:, 0] &= 0xFFFFFFFF
    _check_bitmaps(call, rec[:, 1], rec[:, 2], rec[:, 3], len(rs))
    machine.fonts[n] = F.long_font(rec, rs)


@glcall(immediate=True)
def loadXfont(n, name):
    """loadXfont(3G): font n := the X font called name.  The emulator has
    the misc-fixed 9x15 fonts: names matching *9x15*, "fixed" or the
    -misc-fixed-*--15-* XLFDs (bold with *9x15bold* / *9x15B*); any other
    name raises GLError."""
    call = "loadXfont"
    n = _font_number(call, n)
    if not isinstance(name, str):
        fail(call, f"font name {name!r} is not a str", "pass an X font name")
    f = F.x_font(name)
    if f is None:
        fail(call, f"no X font {name!r} in the emulator",
             "it has 9x15 (\"9x15\", \"fixed\", -misc-fixed-medium-r-normal--15-*) and "
             "9x15bold (\"9x15bold\", \"9x15B\", -misc-fixed-bold-r-normal--15-*)")
    machine.fonts[n] = f
