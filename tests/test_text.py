"""Characters and fonts: cmov*, charstr, lcharstr, strwidth, getheight,
getdescender, getcpos, font, getfont, getfontencoding, defrasterfont,
deflfont, loadXfont (charstr(3G), cmov(3G), defrasterfont(3G), deflfont(3G)).

Expected glyph pixels are decoded here, independently of the emulator's
font code, from the shipped Fontchar records and 16-bit raster words as
defrasterfont(3G) describes them (rows bottom to top, bits left-justified,
lower-left corner at (xoff, yoff) from the character origin); the shipped
records are checked against the X font file itself when it is installed.
"""
import base64
import gzip
from pathlib import Path

import numpy as np
import pytest

from irisgl import (GLError, STR_16, STR_2B, STR_B, SRC_ZBUFFER, TRUE, bgnline, callobj,
                    charstr, closeobj, cmov, cmov2, cmov2i, cmov2s, cmovi, cmovs, color,
                    cpack, clear, deflfont, defpattern, defrasterfont, draw2i, endline, font,
                    getcpos, getdescender, getfont, getfontencoding, getheight, lcharstr,
                    loadXfont, lrectread, lstrwidth, makeobj, move2i, ortho2, pnt, polf,
                    readsource, scrmask, setpattern, strwidth, swapbuffers, translate, viewport,
                    wmpack, writemask, zbuffer, zclear)
from vgx_emulator import fonts as vfonts
from vgx_emulator.fonts import xfixed

PCF = Path("/usr/share/fonts/X11/misc")


# -- an independent decoder of the shipped font data ------------------------------
def shipped(name="9x15"):
    """{value: (offset, w, h, xoff, yoff, width)}, raster words."""
    e = xfixed.FONTS[name]
    chars = np.frombuffer(base64.b64decode("".join(e["chars"])), "<i4").reshape(-1, 7)
    raster = np.frombuffer(base64.b64decode("".join(e["raster"])), "<u2")
    return {int(r[0]): tuple(int(v) for v in r[1:]) for r in chars}, raster


def bitmap_pixels(rec, raster):
    """Set pixels (x, y) of one Fontchar-style record, relative to the origin."""
    offset, w, h, xoff, yoff = rec[:5]
    words = (w + 15) // 16
    out = set()
    for j in range(h):                       # row j: j rows above the bitmap's bottom
        for i in range(w):
            word = int(raster[offset + j * words + i // 16])
            if word & (0x8000 >> (i % 16)):
                out.add((xoff + i, yoff + j))
    return out


def text_pixels(text, x, y, name="9x15", limit=128):
    """Pixels the string covers when its character position is (x, y)."""
    chars, raster = shipped(name)
    out = set()
    for ch in text:
        rec = chars.get(ord(ch)) if ord(ch) < limit else None
        if rec is None:
            continue
        out |= {(x + px, y + py) for px, py in bitmap_pixels(rec, raster)}
        x += rec[5]
    return out


def lit(img, value=None):
    """{(x, y)} of pixels that differ from 0 (or equal ``value``)."""
    ys, xs = np.nonzero(img != 0) if value is None else np.nonzero(img == value)
    return set(zip(xs.tolist(), ys.tolist()))


@pytest.fixture
def rgb(open_window):
    open_window(64, 32)
    cpack(0)
    clear()
    return None


# -- the default font ------------------------------------------------------------
def test_default_font_metrics(rgb):
    assert getheight() == 15 and getdescender() == 3
    assert strwidth("abc") == 27 and strwidth("") == 0
    assert strwidth("a\x7fb") == 27                 # 0..127 are all defined
    assert strwidth("a\xe9b") == 18                 # 128..255 are not: zero width
    assert strwidth("ab\0cd") == 18                 # a C string ends at NUL
    assert getfont() == 0 and getfontencoding() == "ISO8859-1"


@pytest.mark.skipif(not (PCF / "9x15-ISO8859-1.pcf.gz").exists(), reason="xfonts-base not "
                    "installed: the shipped data cannot be compared with its source")
@pytest.mark.parametrize("name,fname", [("9x15", "9x15-ISO8859-1.pcf.gz"),
                                        ("9x15bold", "9x15B-ISO8859-1.pcf.gz")])
def test_shipped_glyphs_are_the_x_font(name, fname):
    from PIL import PcfFontFile
    pcf = PcfFontFile.PcfFontFile(gzip.open(PCF / fname))
    chars, raster = shipped(name)
    for code, g in enumerate(pcf.glyph):
        if g is None:
            assert code not in chars
            continue
        (adv, _), (x0, y0, _, _), _, image = g
        cell = np.array(image, bool).reshape(image.size[1], image.size[0])
        want = {(x0 + c, -y0 - 1 - r) for r, c in zip(*np.nonzero(cell))}
        assert bitmap_pixels(chars[code], raster) == want, chr(code)
        assert chars[code][5] == adv == 9


def test_charstr_pixels_are_the_glyphs(rgb):
    cpack(0xFF00FF00)
    cmov2i(5, 10)
    charstr("Ag,|")
    img = lrectread(0, 0, 63, 31)
    want = text_pixels("Ag,|", 5, 10)
    assert len(want) > 40
    assert lit(img) == want
    assert lit(img, 0xFF00FF00) == want
    assert getcpos() == (5 + 36, 10)
    # one z, colour, position rule for every character: in pieces or whole
    cpack(0)
    clear()
    cpack(0xFF00FF00)
    cmov2i(5, 10)
    charstr("Ag")
    charstr(",|")
    assert lit(lrectread(0, 0, 63, 31)) == want


def test_baseline_and_descender(rgb):
    cpack(0xFFFFFFFF)
    cmov2i(0, 10)
    charstr("g")
    ys = [y for _, y in lit(lrectread(0, 0, 63, 31))]
    assert min(ys) == 10 - 3                       # the descender: 3 rows below
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(0, 10)
    charstr("H")
    ys = [y for _, y in lit(lrectread(0, 0, 63, 31))]
    assert min(ys) == 10                           # capitals stand on the baseline


@pytest.mark.parametrize("call,args", [(cmov, (7.0, 3.0, 0.0)), (cmovi, (7, 3, 0)),
                                       (cmovs, (7, 3, 0)), (cmov2, (7.0, 3.0)),
                                       (cmov2i, (7, 3)), (cmov2s, (7, 3))])
def test_cmov_flavours_transform_like_a_vertex(rgb, call, args):
    translate(10.0, 4.0, 0.0)
    call(*args)
    assert getcpos() == (17, 7)


def test_cmov_uses_viewport_and_leaves_graphics_position(rgb):
    viewport(32, 63, 0, 31)
    ortho2(-0.5, 31.5, -0.5, 31.5)
    cmov2(2.0, 3.0)
    assert getcpos() == (34, 3)
    viewport(0, 63, 0, 31)
    ortho2(-0.5, 63.5, -0.5, 31.5)
    cpack(0xFFFFFFFF)
    move2i(1, 1)
    cmov2i(40, 20)
    draw2i(1, 6)                       # the line starts at the move, not at the cmov
    img = lrectread(0, 0, 63, 31)
    assert all(img[y, 1] for y in range(1, 7)) and not img[20, 40]


def test_origin_outside_viewport_drops_whole_string(rgb):
    cpack(0xFFFFFFFF)
    cmov2i(-2, 10)                     # the first glyph would reach into the window
    charstr("MMMM")
    assert not lrectread(0, 0, 63, 31).any()
    assert getcpos() == (-2 + 36, 10)  # the position still advances
    charstr("M")                       # now inside: drawn
    assert lit(lrectread(0, 0, 63, 31)) == text_pixels("M", 34, 10)
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(60, 40)                     # above the window
    charstr("M")
    assert not lrectread(0, 0, 63, 31).any()


def test_pixels_clipped_to_scrmask_not_viewport(rgb):
    cpack(0xFFFFFFFF)
    scrmask(0, 12, 0, 31)
    cmov2i(2, 10)
    charstr("MMM")
    assert lit(lrectread(0, 0, 63, 31)) == {p for p in text_pixels("MMM", 2, 10) if p[0] <= 12}
    # a string running past the window edge is cut there
    scrmask(0, 63, 0, 31)
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(58, 10)
    charstr("MM")
    assert lit(lrectread(0, 0, 63, 31)) == {p for p in text_pixels("MM", 58, 10) if p[0] <= 63}


def test_z_one_value_tested_and_written(rgb):
    zbuffer(TRUE)
    zclear()
    # a reference point at the text's z, drawn like any primitive
    cpack(0xFF0000FF)
    pnt(60.0, 30.0, 0.5)
    # a polygon at z = 0 over the left half: nearer than z = -0.5, farther than 0.5
    cpack(0xFFFF0000)
    polf(4, [(0, 0, 0), (20, 0, 0), (20, 31, 0), (0, 31, 0)])
    covered = lit(lrectread(0, 0, 63, 31), 0xFFFF0000)
    assert {(x, 10) for x in range(20)} <= covered
    cpack(0xFF00FF00)
    cmov(5.0, 10.0, -0.5)              # behind the polygon: hidden where it covers
    charstr("MMMM")
    img = lrectread(0, 0, 63, 31)
    glyphs = text_pixels("MMMM", 5, 10)
    assert lit(img, 0xFF00FF00) == glyphs - covered
    assert glyphs & covered
    cmov(5.0, 10.0, 0.5)               # in front: drawn over it
    charstr("MMMM")
    img = lrectread(0, 0, 63, 31)
    assert lit(img, 0xFF00FF00) == glyphs
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, 63, 31)
    zs = {int(z[y, x]) for x, y in glyphs}
    assert zs == {int(z[30, 60])}      # every glyph pixel has the origin's z


def test_colour_writemask_applies_pattern_does_not(rgb):
    cpack(0xFF102030)
    clear()
    wmpack(0x0000FF00)                 # green only
    cpack(0xFFFFFFFF)
    defpattern(1, 16, [0xAAAA, 0x5555] * 8)
    setpattern(1)
    cmov2i(3, 8)
    charstr("W")
    img = lrectread(0, 0, 63, 31)
    glyph = text_pixels("W", 3, 8)
    assert lit(img, 0xFF10FF30) == glyph           # every glyph pixel, green only
    assert len(lit(img, 0xFF102030)) == 64 * 32 - len(glyph)


def test_colour_index_mode_and_writemask(open_window):
    open_window(64, 32, rgb=False)
    color(8)
    clear()
    writemask(0x3)
    color(7)
    cmov2i(4, 9)
    charstr("x")
    img = lrectread(0, 0, 63, 31)
    assert lit(img, 0xB) == text_pixels("x", 4, 9)       # (8 & ~3) | (7 & 3)
    assert len(lit(img, 8)) == 64 * 32 - len(text_pixels("x", 4, 9))


def test_double_buffer_draws_to_back(open_window):
    open_window(64, 32, double=True)
    cpack(0)
    clear()
    swapbuffers()
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(2, 5)
    charstr("ok")
    from vgx_emulator import window_image
    assert not window_image().any()
    swapbuffers()
    img = window_image()[::-1, :, 0]             # bottom row first
    assert lit(img) == text_pixels("ok", 2, 5)


def test_display_list_records_cmov_and_charstr(rgb):
    cpack(0xFFFFFFFF)
    makeobj(5)
    cmov2i(3, 12)
    charstr("Hi")
    assert strwidth("Hi") == 18        # a query runs at once inside makeobj
    closeobj()
    assert not lrectread(0, 0, 63, 31).any()
    callobj(5)
    assert lit(lrectread(0, 0, 63, 31)) == text_pixels("Hi", 3, 12)
    assert getcpos() == (21, 12)


def test_non_finite_position_drops_with_warning(rgb):
    cpack(0xFFFFFFFF)
    with pytest.warns(UserWarning, match="cmov"):
        cmov(float("nan"), 1.0, 0.0)
    charstr("M")
    assert not lrectread(0, 0, 63, 31).any()


def test_misuse_raises_and_changes_nothing(rgb):
    cmov2i(3, 4)
    with pytest.raises(GLError, match="^cmov2: "):
        cmov2("a", 1)
    with pytest.raises(GLError, match="^cmov2i: "):
        cmov2i(1, 2, 3)
    with pytest.raises(GLError, match="^charstr: "):
        charstr(17)
    with pytest.raises(GLError, match="^charstr: .*lcharstr"):
        charstr("\u4e00")
    with pytest.raises(GLError, match="^lcharstr: unknown string type"):
        lcharstr(99, "a")
    bgnline()
    with pytest.raises(GLError, match="^charstr: not allowed inside bgnline"):
        charstr("a")
    endline()
    assert getcpos() == (3, 4) and not lrectread(0, 0, 63, 31).any()


def test_calls_before_winopen_raise():
    with pytest.raises(GLError, match="^charstr: no window"):
        charstr("a")
    with pytest.raises(GLError, match="^getcpos: no window"):
        getcpos()


# -- user fonts --------------------------------------------------------------------
def _font_chars(n, entries):
    """nc records; ``entries`` {value: (offset, w, h, xoff, yoff, width)}."""
    return [entries.get(i, (0, 0, 0, 0, 0, 0)) for i in range(n)]


def test_defrasterfont_layout_and_metrics(rgb):
    raster = [0b1010000000000000, 0b0100000000000000,          # 'A': 3 wide, 2 rows
              0xFFFF, 0xF000, 0x8000, 0x1000]                    # 'B': 20 wide, 2 rows
    chars = _font_chars(67, {65: (0, 3, 2, 1, -1, 5), 66: (2, 20, 2, 0, 0, 22)})
    defrasterfont(1, 6, 67, chars, 6, raster)
    font(1)
    assert getfont() == 1 and getheight() == 6 and getdescender() == 1
    assert getfontencoding() == ""
    assert strwidth("AA") == 10 and strwidth("AC") == 5 and strwidth("B") == 22
    cpack(0xFFFFFFFF)
    cmov2i(10, 10)
    charstr("ACA")                     # C is undefined: zero width, nothing drawn
    want = {(11, 9), (13, 9), (12, 10), (16, 9), (18, 9), (17, 10)}
    assert lit(lrectread(0, 0, 63, 31)) == want
    assert getcpos() == (20, 10)
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(1, 20)
    charstr("B")                       # a row of two words: bits 16.. are x 16..
    row0 = {(1 + i, 20) for i in range(16)} | {(1 + 16 + i, 20) for i in range(4)}
    row1 = {(1, 21), (1 + 19, 21)}
    assert lit(lrectread(0, 0, 63, 31)) == row0 | row1


def test_font_selection_and_deletion(rgb):
    defrasterfont(3, 4, 66, _font_chars(66, {65: (0, 1, 1, 0, 0, 2)}), 1, [0x8000])
    font(3)
    assert strwidth("AAA") == 6
    font(9)                            # undefined: font 0
    assert getfont() == 0 and strwidth("AAA") == 27
    font(3)
    defrasterfont(3, 0, 0, [], 0, [])  # deleted: charstr falls back to font 0
    assert getfont() == 0 and strwidth("A") == 9


def test_defrasterfont_errors_define_nothing(rgb):
    ok = _font_chars(66, {65: (0, 1, 1, 0, 0, 2)})
    with pytest.raises(GLError, match="^defrasterfont: font 0 cannot be redefined"):
        defrasterfont(0, 4, 66, ok, 1, [0x8000])
    with pytest.raises(GLError, match="^defrasterfont: .*runs past raster"):
        defrasterfont(2, 4, 66, _font_chars(66, {65: (0, 17, 2, 0, 0, 2)}), 3, [1, 2, 3])
    with pytest.raises(GLError, match="^defrasterfont: chars has fewer"):
        defrasterfont(2, 4, 70, ok, 1, [0x8000])
    with pytest.raises(GLError, match=r"^defrasterfont: character 65's bitmap .*raster\[1\]"):
        defrasterfont(2, 4, 66, _font_chars(66, {65: (1, 1, 1, 0, 0, 2)}), 10, [0x8000])
    font(2)
    assert getfont() == 0


def test_defrasterfont_takes_nr_in_bytes(rgb):
    """SGI's font3.c passes nr = sizeof efont_bits, bytes for an array of
    shorts: past the array's end, read harmlessly by the C library as no
    glyph lies there.  The font is the one nr = the array's length gives."""
    chars = _font_chars(66, {65: (0, 1, 2, 0, 0, 2)})
    bits = [0x8000, 0xC000]
    defrasterfont(2, 4, 66, chars, 2 * len(bits), bits)
    font(2)
    cpack(0xFFFFFFFF)
    cmov2i(1, 1)
    charstr("A")
    as_bytes = lrectread(0, 0, 7, 7)
    defrasterfont(2, 4, 66, chars, len(bits), bits)
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    cmov2i(1, 1)
    charstr("A")
    assert np.array_equal(lrectread(0, 0, 7, 7), as_bytes) and as_bytes.any()


def test_deflfont_values_and_moves(rgb):
    chars = [(0x4E00, 0, 2, 1, 0, 0, 4, 2),       # two pixels, moves (4, 2)
             (0x41, 1, 1, 1, 0, 0, 3, 0)]
    deflfont(4, 2, chars, 2, [0xC000, 0x8000])
    font(4)
    cpack(0xFFFFFFFF)
    cmov2i(5, 5)
    lcharstr(STR_16, [0x4E00, 0x4E00, 0x41, 0, 0x41])       # stops at the zero id
    assert lit(lrectread(0, 0, 63, 31)) == {(5, 5), (6, 5), (9, 7), (10, 7), (13, 9)}
    assert getcpos() == (16, 9)
    assert lstrwidth(STR_2B, b"\x4e\x00\x00\x41") == 7     # 0x4E00, 0x0041
    assert lstrwidth(STR_B, b"AA\0A") == 6
    assert strwidth("A") == 3


def test_loadxfont_names(rgb):
    loadXfont(2, "9x15bold")
    loadXfont(3, "-Misc-Fixed-Medium-R-Normal--15-140-75-75-C-90-ISO8859-1")
    with pytest.raises(GLError, match="^loadXfont: no X font 'helvetica'"):
        loadXfont(5, "helvetica")
    with pytest.raises(GLError, match="^loadXfont: font 0"):
        loadXfont(0, "fixed")
    font(3)
    assert strwidth("\xe9") == 9 and getfontencoding() == "ISO8859-1"   # the full font
    font(2)
    cpack(0xFFFFFFFF)
    cmov2i(3, 8)
    charstr("H")
    assert lit(lrectread(0, 0, 63, 31)) == text_pixels("H", 3, 8, "9x15bold", 256)
    assert text_pixels("H", 0, 0, "9x15bold") != text_pixels("H", 0, 0)
    font(5)
    assert getfont() == 0


def test_shipped_font_module_metrics():
    f = vfonts.default_font()
    assert (f.height, f.descender) == (15, 3)
    assert len(f.values) == 128


def test_defrasterfont_takes_an_array_of_records(rgb):
    chars = np.zeros((66, 6), np.int16)
    chars[65] = (0, 2, 1, 0, 0, 3)
    defrasterfont(6, 1, 66, chars, 1, np.array([0xC000], np.uint16))
    font(6)
    cpack(0xFFFFFFFF)
    cmov2i(1, 1)
    charstr("AA")
    assert lit(lrectread(0, 0, 63, 31)) == {(1, 1), (2, 1), (4, 1), (5, 1)}
