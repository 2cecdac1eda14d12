"""readsource, lrectread, rectread, lrectwrite, rectwrite, rectzoom, rectcopy
(docs/semantics.md §11, §5; docs/porting.md §3)."""
from functools import partial

import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import new_window, box, colour


open_win = partial(new_window, pixels=True)      # pixel (i, j)'s centre at (i, j)



def distinct_words(h, w, seed=3):
    rng = np.random.default_rng(seed)
    return rng.integers(0, 1 << 32, (h, w), dtype=np.uint64).astype(np.uint32)


# -- lrectread ---------------------------------------------------------------------
def test_lrectread_packing_red_in_low_byte():
    open_win(2, 2)
    RGBcolor(255, 0, 0)
    box(0, 0, 0, 0)
    c4i((0x10, 0x20, 0x30, 0x40))
    box(1, 1, 1, 1)
    img = lrectread(0, 0, 1, 1)
    assert img.dtype == np.uint32 and img.shape == (2, 2)
    assert img[0, 0] == 0xFF0000FF            # alpha 255 from RGBcolor, red low
    assert img[1, 1] == 0x40302010


def test_lrectread_row_order_bottom_first_and_subrectangle():
    W, H = 7, 5
    open_win(W, H)
    for y in range(H):
        for x in range(W):
            cpack(0xFF000000 | (y << 8) | x)
            box(x, y, x, y)
    img = lrectread(2, 1, 5, 3)
    assert img.shape == (3, 4)
    for r in range(3):
        for c in range(4):
            assert img[r, c] == 0xFF000000 | ((1 + r) << 8) | (2 + c)


def test_lrectread_into_given_array_returns_count():
    W, H = 5, 4
    open_win(W, H)
    words = distinct_words(H, W)
    lrectwrite(0, 0, W - 1, H - 1, words)
    buf = np.zeros(3 * 2, np.uint32)
    n = lrectread(1, 2, 3, 3, buf)
    assert n == 6
    # left to right, then bottom to top
    assert list(buf) == [words[2, 1], words[2, 2], words[2, 3],
                         words[3, 1], words[3, 2], words[3, 3]]


def test_lrectread_count_even_when_off_window():
    open_win(4, 4)
    buf = np.zeros(10 * 3, np.uint32)
    assert lrectread(100, 100, 109, 102, buf) == 30


def test_lrectread_wrong_array_size_raises():
    open_win(4, 4)
    with pytest.raises(GLError):
        lrectread(0, 0, 1, 1, np.zeros(3, np.uint32))


def test_lrectwrite_lrectread_round_trip():
    W, H = 9, 6
    open_win(W, H)
    words = distinct_words(H, W, seed=11)
    lrectwrite(0, 0, W - 1, H - 1, words)
    assert (lrectread(0, 0, W - 1, H - 1) == words).all()
    # a flat C-style array works too, left to right then bottom to top
    lrectwrite(2, 1, 4, 2, list(range(1, 7)))
    assert list(lrectread(2, 1, 4, 2).ravel()) == [1, 2, 3, 4, 5, 6]


def test_lrectwrite_wrong_size_raises_and_writes_nothing():
    open_win(4, 4)
    with pytest.raises(GLError):
        lrectwrite(0, 0, 1, 1, [1, 2, 3])
    assert (colour() == 0).all()


# -- lrectwrite and the fragment operations (docs/semantics.md §11) ---------------------------------
def test_lrectwrite_applies_writemask():
    open_win(2, 2)
    czclear(0x11223344, 0)
    wmpack(0x00FF00FF)
    lrectwrite(0, 0, 1, 1, [0xAABBCCDD] * 4)
    assert (colour() == (0x11223344 & 0xFF00FF00) | (0xAABBCCDD & 0x00FF00FF)).all()


def test_lrectwrite_applies_blending():
    open_win(2, 1)
    czclear(0x10203040, 0)
    blendfunction(BF_ONE, BF_ONE)
    lrectwrite(0, 0, 1, 0, [0x01010101, 0xF0F0F0F0])
    got = list(colour()[0])
    assert got[0] == 0x11213141
    assert got[1] == (0xFF << 24) | (0xFF << 16) | (0xFF << 8) | 0xFF


def test_lrectwrite_applies_logicop_and_afunction():
    open_win(2, 1)
    czclear(0x0F0F0F0F, 0)
    logicop(LO_XOR)
    lrectwrite(0, 0, 1, 0, [0xFFFFFFFF, 0x00000000])
    assert list(colour()[0]) == [0xF0F0F0F0, 0x0F0F0F0F]
    logicop(LO_SRC)
    czclear(0, 0)
    afunction(128, AF_GEQUAL)
    lrectwrite(0, 0, 1, 0, [0x7FFFFFFF, 0x80FFFFFF])
    assert list(colour()[0]) == [0, 0x80FFFFFF]


def test_lrectwrite_ignores_z_stencil_and_pattern():
    open_win(4, 4, planes=8)
    zmin = getgdesc(GD_ZMIN)
    czclear(0, zmin)                       # any z test would fail
    zbuffer(TRUE)
    sclear(3)
    stencil(TRUE, 9, SF_NEVER, 0xFF, ST_ZERO, ST_ZERO, ST_ZERO)
    defpattern(1, PATTERN_16, [0] * 16)    # would protect every pixel
    setpattern(1)
    words = distinct_words(4, 4)
    lrectwrite(0, 0, 3, 3, words)
    assert (lrectread(0, 0, 3, 3) == words).all()
    readsource(SRC_ZBUFFER)
    assert (lrectread(0, 0, 3, 3) == zmin).all()          # z not written
    from irisgl._current import machine
    assert (machine.current.fb.stencil == 3).all()        # stencil untouched


def test_lrectwrite_clipped_to_scrmask_and_viewport():
    W = H = 8
    open_win(W, H)
    czclear(0x01010101, 0)
    words = distinct_words(H, W)
    scrmask(2, 5, 1, 6)
    lrectwrite(0, 0, W - 1, H - 1, words)
    got = colour()
    inside = np.zeros((H, W), bool)
    inside[1:7, 2:6] = True
    assert (got[inside] == words[inside]).all()
    assert (got[~inside] == 0x01010101).all()
    scrmask(0, W - 1, 0, H - 1)
    czclear(0x01010101, 0)
    viewport(3, 7, 0, 2)
    lrectwrite(0, 0, W - 1, H - 1, words)
    inside = np.zeros((H, W), bool)
    inside[0:3, 3:8] = True
    got = colour()
    assert (got[inside] == words[inside]).all()
    assert (got[~inside] == 0x01010101).all()


def test_lrectwrite_partly_off_window():
    open_win(4, 4)
    words = distinct_words(3, 3)
    lrectwrite(2, 2, 4, 4, words)
    got = colour()
    assert (got[2:4, 2:4] == words[0:2, 0:2]).all()
    assert (got[:2, :] == 0).all() and (got[:, :2] == 0).all()


# -- rectzoom ----------------------------------------------------------------------
def test_rectzoom_2x_replicates():
    open_win(8, 8)
    src = np.array([[1, 2, 3], [4, 5, 6]], np.uint32)
    rectzoom(2.0, 2.0)
    lrectwrite(1, 1, 3, 2, src)
    got = colour()
    want = np.zeros((8, 8), np.int64)
    want[1:5, 1:7] = np.kron(src, np.ones((2, 2), np.int64))
    assert (got == want).all()


def test_rectzoom_does_not_affect_reads():
    open_win(4, 4)
    lrectwrite(0, 0, 1, 1, [1, 2, 3, 4])
    rectzoom(2.0, 2.0)
    assert lrectread(0, 0, 1, 1).shape == (2, 2)
    assert list(lrectread(0, 0, 1, 1).ravel()) == [1, 2, 3, 4]


def test_rectzoom_half_decimates():
    open_win(8, 8)
    czclear(0xDEADBEEF, 0)
    src = np.arange(1, 17, dtype=np.uint32).reshape(4, 4)
    rectzoom(0.5, 0.5)
    lrectwrite(2, 3, 5, 6, src)
    got = colour()
    # a 2x2 result at (2, 3), each pixel one of the source pixels of its block
    for r in range(2):
        for c in range(2):
            block = src[2 * r:2 * r + 2, 2 * c:2 * c + 2].ravel().tolist()
            assert got[3 + r, 2 + c] in block, (r, c)
    changed = got != 0xDEADBEEF
    assert changed.sum() == 4 and changed[3:5, 2:4].all()


def test_rectzoom_mixed_factors():
    open_win(8, 4)
    src = np.array([[7, 8]], np.uint32)
    rectzoom(3.0, 1.0)
    lrectwrite(0, 0, 1, 0, src)
    assert list(colour()[0]) == [7, 7, 7, 8, 8, 8, 0, 0]
    assert (colour()[1:] == 0).all()


def test_rectzoom_rejects_nonpositive():
    open_win(2, 2)
    with pytest.raises(GLError):
        rectzoom(0, 1)
    with pytest.raises(GLError):
        rectzoom(1, -2)


# -- rectcopy ------------------------------------------------------------------------
def test_rectcopy_to_a_new_place():
    W = H = 8
    open_win(W, H)
    words = distinct_words(3, 2)
    lrectwrite(0, 0, 1, 2, words)
    rectcopy(0, 0, 1, 2, 5, 4)
    got = colour()
    assert (got[4:7, 5:7] == words).all()
    assert (got[0:3, 0:2] == words).all()           # source unchanged
    mask = np.ones((H, W), bool)
    mask[4:7, 5:7] = False
    mask[0:3, 0:2] = False
    assert (got[mask] == 0).all()


def test_rectcopy_from_front_into_back_with_zoom():
    open_win(6, 6, double=True)
    frontbuffer(TRUE)
    backbuffer(FALSE)
    lrectwrite(0, 0, 1, 0, [0x11, 0x22])
    frontbuffer(FALSE)
    backbuffer(TRUE)
    czclear(0, 0)
    readsource(SRC_FRONT)
    rectzoom(2.0, 2.0)
    rectcopy(0, 0, 1, 0, 1, 2)
    readsource(SRC_BACK)
    got = colour()
    want = np.zeros((6, 6), np.int64)
    want[2:4, 1:3] = 0x11
    want[2:4, 3:5] = 0x22
    assert (got == want).all()
    readsource(SRC_FRONT)
    assert (colour()[2:] == 0).all()                 # front not written


def test_rectcopy_honours_writemask():
    open_win(4, 1)
    lrectwrite(0, 0, 1, 0, [0xAABBCCDD, 0x11223344])
    wmpack(0x0000FFFF)
    rectcopy(0, 0, 1, 0, 2, 0)
    assert list(colour()[0])[2:] == [0xCCDD, 0x3344]


# -- readsource ------------------------------------------------------------------------
def test_readsource_zbuffer_gives_signed_z():
    open_win(3, 2)
    czclear(0, -1000)
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, 2, 1)
    assert z.dtype == np.int32
    assert (z == -1000).all()
    buf = np.zeros(6, np.uint32)
    assert lrectread(0, 0, 2, 1, buf) == 6
    assert (buf == (-1000) & 0xFFFFFFFF).all()       # two's complement words
    czclear(0, getgdesc(GD_ZMIN))
    assert (lrectread(0, 0, 2, 1) == -0x800000).all()


def test_readsource_back_needs_double_buffer():
    open_win(2, 2)
    with pytest.raises(GLError):
        readsource(SRC_BACK)


def test_readsource_auto_is_back_in_double_buffer():
    open_win(2, 2, double=True)
    frontbuffer(TRUE)
    backbuffer(FALSE)
    czclear(0x111, 0)
    frontbuffer(FALSE)
    backbuffer(TRUE)
    czclear(0x222, 0)
    assert (lrectread(0, 0, 1, 1) == 0x222).all()
    readsource(SRC_FRONT)
    assert (lrectread(0, 0, 1, 1) == 0x111).all()


# -- colour-map mode --------------------------------------------------------------------
def test_rectread_gives_uint16_indices_in_cmode():
    open_win(3, 2, rgb=False)
    for x, idx in enumerate((0x123, 0xFFF, 7)):
        color(idx)
        box(x, 0, x, 1)
    img = rectread(0, 0, 2, 1)
    assert img.dtype == np.uint16 and img.shape == (2, 3)
    assert (img == np.array([[0x123, 0xFFF, 7]] * 2)).all()
    buf = np.zeros(6, np.uint16)
    assert rectread(0, 0, 2, 1, buf) == 6
    assert list(buf) == [0x123, 0xFFF, 7, 0x123, 0xFFF, 7]


def test_rectwrite_in_cmode_with_writemask():
    open_win(2, 1, rgb=False)
    czclear(0xF0F, 0)
    writemask(0x0FF)
    rectwrite(0, 0, 1, 0, [0xABC, 0x123])
    assert list(rectread(0, 0, 1, 0)[0]) == [(0xF0F & 0xF00) | (0xABC & 0xFF),
                                            (0xF0F & 0xF00) | (0x123 & 0xFF)]
