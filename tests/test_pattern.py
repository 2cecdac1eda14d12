"""defpattern(3G), setpattern(3G), getpattern(3G) (docs/semantics.md §8):
bit layout, screen-aligned tiling, what a 0 bit protects and
which primitives the pattern applies to."""
from functools import partial

import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import new_window, box, colour, z_bank, stencil_bank


open_win = partial(new_window, pixels=True)      # pixel (i, j)'s centre at (i, j)



def pattern_mask(words, size, w, h, ox=0, oy=0):
    """Expected coverage from the man page: shorts left to right then
    bottom to top, bit 15 the leftmost pixel; tiles aligned to the screen."""
    per_row = size // 16
    out = np.zeros((h, w), bool)
    for y in range(h):
        for x in range(w):
            X, Y = (x + ox) % size, (y + oy) % size
            word = words[Y * per_row + X // 16]
            out[y, x] = (word >> (15 - X % 16)) & 1
    return out


RED = 0xFF0000FF
rng = np.random.default_rng(1234)
RAND16 = [int(v) for v in rng.integers(0, 1 << 16, 16)]
RAND32 = [int(v) for v in rng.integers(0, 1 << 16, 64)]
RAND64 = [int(v) for v in rng.integers(0, 1 << 16, 256)]
CHECKER = [0xAAAA if r % 2 == 0 else 0x5555 for r in range(16)]
ZERO16 = [0] * 16


def test_bit15_is_leftmost_and_row0_is_bottom():
    open_win(16, 16)
    words = [0] * 16
    words[0] = 0x8000            # bottom row, leftmost pixel
    words[3] = 0x0001            # row 3, rightmost pixel
    defpattern(1, PATTERN_16, words)
    setpattern(1)
    cpack(RED)
    box(0, 0, 15, 15)
    c = colour() == RED
    assert c.sum() == 2
    assert c[0, 0] and c[3, 15]


@pytest.mark.parametrize("size,words", [(16, RAND16), (32, RAND32), (64, RAND64)],
                         ids=["16", "32", "64"])
def test_defpattern_layout_and_tiling(size, words):
    W, H = 72, 70                   # more than one tile in both directions
    open_win(W, H)
    defpattern(5, size, words)
    setpattern(5)
    assert getpattern() == 5
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    assert ((colour() == RED) == pattern_mask(words, size, W, H)).all()


@pytest.mark.parametrize("origin", [(5, 3), (17, 40), (100, 7)])
def test_phase_follows_window_origin(origin):
    """docs/semantics.md §8: the pattern is tiled over the screen, so a window at an
    origin that is not a multiple of 16 sees a shifted phase."""
    W, H = 20, 18
    open_win(W, H, origin=origin)
    assert tuple(getorigin()) == origin
    defpattern(2, PATTERN_16, RAND16)
    setpattern(2)
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    got = colour() == RED
    assert (got == pattern_mask(RAND16, 16, W, H, *origin)).all()
    # and it really differs from the unshifted phase
    assert (got != pattern_mask(RAND16, 16, W, H)).any()


@pytest.mark.parametrize("size,words", [(PATTERN_16, RAND16), (PATTERN_32, RAND32),
                                        (PATTERN_64, RAND64)])
@pytest.mark.parametrize("origin", [(37, 11), (1000, 3)])
def test_phase_in_a_wide_window_of_small_polygons(size, words, origin):
    """The kernels read the pattern laid out for the window's columns
    (raster.variants.pattern_rows); short spans, padded to whole vectors,
    and long ones see the screen-aligned phase of every pattern size."""
    W, H = 203, 37
    open_win(W, H, origin=origin)
    defpattern(3, size, words)
    setpattern(3)
    cpack(RED)
    for x0 in range(0, W, 9):                   # 9 boxes of 7 pixels a row of boxes
        for y0 in range(0, H, 6):
            box(x0, y0, min(x0 + 6, W - 1), min(y0 + 4, H - 1))
    box(0, H - 1, W - 1, H - 1)                 # and one long span
    covered = np.zeros((H, W), bool)
    for x0 in range(0, W, 9):
        for y0 in range(0, H, 6):
            covered[y0:y0 + 5, x0:x0 + 7] = True
    covered[H - 1, :] = True
    expect = covered & pattern_mask(words, size, W, H, *origin)
    assert ((colour() == RED) == expect).all()


def test_zero_bit_protects_colour_z_and_stencil():
    W = H = 16
    open_win(W, H, planes=8)
    zmax = getgdesc(GD_ZMAX)
    czclear(0x11111111, zmax)
    sclear(7)
    zbuffer(TRUE)
    stencil(TRUE, 200, SF_ALWAYS, 0xFF, ST_REPLACE, ST_REPLACE, ST_REPLACE)
    defpattern(3, PATTERN_16, RAND16)
    setpattern(3)
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    m = pattern_mask(RAND16, 16, W, H)
    c, z, s = colour(), z_bank(), stencil_bank()
    assert (c[m] == RED).all() and (c[~m] == 0x11111111).all()
    assert (z[~m] == zmax).all() and (z[m] != zmax).all()
    assert (s[~m] == 7).all() and (s[m] == 200).all()


def test_pattern_applies_to_bgnpolygon_and_polf():
    W = H = 16
    open_win(W, H)
    defpattern(1, PATTERN_16, CHECKER)
    setpattern(1)
    subpixel(TRUE)
    cpack(RED)
    bgnpolygon()
    for p in ((-0.5, -0.5), (7.5, -0.5), (7.5, 15.5), (-0.5, 15.5)):
        v2f(p)
    endpolygon()
    cpack(0xFF00FF00)
    polf2(4, [(7.5, -0.5), (15.5, -0.5), (15.5, 15.5), (7.5, 15.5)])
    m = pattern_mask(CHECKER, 16, W, H)
    c = colour()
    assert (c[:, :8][m[:, :8]] == RED).all() and (c[:, :8][~m[:, :8]] == 0).all()
    assert (c[:, 8:][m[:, 8:]] == 0xFF00FF00).all() and (c[:, 8:][~m[:, 8:]] == 0).all()


def test_pattern_applies_to_clear():
    W, H = 20, 20
    open_win(W, H, origin=(3, 9))
    czclear(0x22222222, 0)
    defpattern(1, PATTERN_16, RAND16)
    setpattern(1)
    cpack(RED)
    clear()
    m = pattern_mask(RAND16, 16, W, H, 3, 9)
    c = colour()
    assert (c[m] == RED).all() and (c[~m] == 0x22222222).all()


def test_pattern_does_not_apply_to_lines_and_points():
    W = H = 8
    open_win(W, H)
    defpattern(1, PATTERN_16, ZERO16)        # protects every pixel of a fill
    setpattern(1)
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    assert (colour() == 0).all()
    bgnline()
    v2f((-0.5, 3.0))
    v2f((W + 0.5, 3.0))
    endline()
    pnt2i(5, 6)
    c = colour() == RED
    assert c[3, 1:W - 1].all()
    assert c[6, 5]


def test_pattern_does_not_apply_to_czclear_or_sclear():
    W = H = 8
    open_win(W, H, planes=8)
    defpattern(1, PATTERN_16, ZERO16)
    setpattern(1)
    czclear(RED, 4321)
    sclear(9)
    assert (colour() == RED).all()
    assert (z_bank() == 4321).all()
    assert (stencil_bank() == 9).all()


def test_setpattern_zero_and_undefined_draw_solid():
    W = H = 8
    open_win(W, H)
    assert getpattern() == 0
    defpattern(1, PATTERN_16, ZERO16)
    setpattern(1)
    setpattern(0)
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    assert (colour() == RED).all()
    czclear(0, 0)
    setpattern(1)
    setpattern(4711)                 # never defined -> solid
    box(0, 0, W - 1, H - 1)
    assert (colour() == RED).all()


def test_redefining_a_pattern_in_use():
    W = H = 16
    open_win(W, H)
    defpattern(1, PATTERN_16, ZERO16)
    setpattern(1)
    defpattern(1, PATTERN_16, CHECKER)
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    assert ((colour() == RED) == pattern_mask(CHECKER, 16, W, H)).all()


def test_patterns_are_shared_by_windows():
    W = H = 16
    open_win(W, H)
    defpattern(6, PATTERN_16, CHECKER)
    open_win(W, H)
    setpattern(6)
    assert getpattern() == 6
    cpack(RED)
    box(0, 0, W - 1, H - 1)
    assert ((colour() == RED) == pattern_mask(CHECKER, 16, W, H)).all()


def test_defpattern_errors():
    open_win(4, 4)
    with pytest.raises(GLError):
        defpattern(0, PATTERN_16, CHECKER)       # 0 is the built-in solid pattern
    with pytest.raises(GLError):
        defpattern(1, 8, [0] * 4)                # size 16, 32 or 64 only
    with pytest.raises(GLError):
        defpattern(1, PATTERN_32, CHECKER)       # 64 shorts needed
    with pytest.raises(GLError):
        defpattern(1, PATTERN_16, [0] * 17)
    # the failed calls defined nothing: pattern 1 is undefined -> solid
    setpattern(1)
    cpack(RED)
    box(0, 0, 3, 3)
    assert (colour() == RED).all()
