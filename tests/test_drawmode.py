"""drawmode(3G) and the pop-up, overlay and underlay framebuffers:
per-framebuffer index, writemask and colour map, the display rule of
overlay(3G)/underlay(3G), plane counts (getplanes(3G)), readsource of the
banks, pupmode/endpupmode (docs/colour-map-and-depthcue.md)."""
import pytest

import vgx_emulator
from irisgl import *
from irisgl._current import machine

W, H = 32, 24


def shown(x, y):
    img = vgx_emulator.window_image()
    return tuple(int(v) for v in img[img.shape[0] - 1 - y, x])


def read(src, x, y):
    readsource(src)
    v = int(lrectread(x, y, x, y)[0, 0])
    readsource(SRC_AUTO)
    return v


def test_default_drawmode_and_errors(open_window):
    open_window(W, H, rgb=False)
    assert getdrawmode() == NORMALDRAW
    with pytest.raises(GLError, match="drawmode"):
        drawmode(0x33)
    assert getdrawmode() == NORMALDRAW
    with pytest.raises(GLError, match="overlay"):
        overlay(3)
    with pytest.raises(GLError, match="underlay"):
        underlay(16)


def test_getplanes_in_every_drawmode(open_window):
    open_window(W, H, rgb=True)
    expect = {NORMALDRAW: 24, PUPDRAW: 2, OVERDRAW: 2, UNDERDRAW: 0, CURSORDRAW: 0}
    for mode, n in expect.items():
        drawmode(mode)
        assert getplanes() == n, mode
    drawmode(NORMALDRAW)
    overlay(8)
    underlay(4)                     # the overlay took the 8 shared planes
    gconfig()
    for mode, n in {OVERDRAW: 8, UNDERDRAW: 0}.items():
        drawmode(mode)
        assert getplanes() == n
    drawmode(NORMALDRAW)
    overlay(4)
    underlay(4)
    gconfig()
    drawmode(UNDERDRAW)
    assert getplanes() == 4


def test_overlay_shows_over_normal_with_its_own_map(open_window):
    open_window(W, H, rgb=False)
    color(RED)
    clear()
    drawmode(OVERDRAW)
    mapcolor(1, 0, 0, 200)          # the overlay's map, not the normal one
    mapcolor(2, 9, 9, 9)
    color(1)
    rectfi(0, 0, 8, 8)
    assert getmcolor(1) == (0, 0, 200)
    drawmode(NORMALDRAW)
    assert getmcolor(1) == (255, 0, 0)
    assert shown(4, 4) == (0, 0, 200)
    assert shown(20, 20) == (255, 0, 0)     # overlay index 0: transparent
    assert int(lrectread(4, 4, 4, 4)[0, 0]) == RED   # normal bank untouched
    assert read(SRC_OVER, 4, 4) == 1 and read(SRC_OVER, 20, 20) == 0
    # erasing the overlay (rubber banding) shows the normal planes again
    drawmode(OVERDRAW)
    color(0)
    clear()
    drawmode(NORMALDRAW)
    assert shown(4, 4) == (255, 0, 0)


def test_overlay_over_rgb_window(open_window):
    open_window(W, H, rgb=True)
    cpack(0x00FF00)
    clear()
    drawmode(OVERDRAW)
    color(3)                        # colour-map mode in the overlay
    with pytest.raises(GLError, match="RGBcolor"):
        RGBcolor(1, 2, 3)
    mapcolor(3, 255, 255, 0)
    rectfi(0, 0, 4, 4)
    drawmode(NORMALDRAW)
    cpack(0x0000FF)                 # RGB again in the normal framebuffer
    assert shown(2, 2) == (255, 255, 0)
    assert shown(10, 10) == (0, 255, 0)
    assert int(lrectread(2, 2, 2, 2)[0, 0]) & 0xFFFFFF == 0x00FF00


def test_each_drawmode_keeps_index_and_writemask(open_window):
    open_window(W, H, rgb=False)
    color(77)
    writemask(0xF0F)
    drawmode(OVERDRAW)
    assert getcolor() == 0 and getwritemask() == 3
    color(9)                        # clamped to the 2 overlay planes
    assert getcolor() == 3
    writemask(1)
    drawmode(PUPDRAW)
    assert getcolor() == 0
    drawmode(NORMALDRAW)
    assert getcolor() == 77 and getwritemask() == 0xF0F
    drawmode(OVERDRAW)
    assert getcolor() == 3 and getwritemask() == 1
    clear()                         # index 3 under writemask 1 -> bit 0 only
    assert read(SRC_OVER, 0, 0) == 1
    gconfig()                       # every drawmode: index 0, writemask all ones
    assert getdrawmode() == OVERDRAW
    assert getcolor() == 0 and getwritemask() == 3
    drawmode(NORMALDRAW)
    assert getcolor() == 0 and getwritemask() == 0xFFF


def test_overlay_has_no_zbuffer(open_window):
    open_window(W, H, rgb=False)
    zbuffer(TRUE)
    zclear()
    color(4)
    bgnpolygon()                    # nearest z everywhere
    for p in ((0, 0, 0.99), (W, 0, 0.99), (W, H, 0.99), (0, H, 0.99)):
        v3f(p)
    endpolygon()
    drawmode(OVERDRAW)
    color(2)
    bgnpolygon()                    # farther, but the overlay is not z-tested
    for p in ((0, 0, -0.99), (8, 0, -0.99), (8, 8, -0.99), (0, 8, -0.99)):
        v3f(p)
    endpolygon()
    drawmode(NORMALDRAW)
    assert read(SRC_OVER, 4, 4) == 2
    assert int(lrectread(4, 4, 4, 4)[0, 0]) == 4


def test_underlay_shows_where_normal_is_zero(open_window):
    open_window(W, H, rgb=False)
    underlay(2)
    gconfig()
    color(0)
    clear()
    color(GREEN)
    rectfi(0, 0, 8, 8)
    drawmode(UNDERDRAW)
    mapcolor(1, 50, 60, 70)
    color(1)
    clear()
    drawmode(NORMALDRAW)
    assert shown(4, 4) == (0, 255, 0)       # normal non-zero wins
    assert shown(20, 20) == (50, 60, 70)    # normal 0: the underlay
    assert read(SRC_UNDER, 20, 20) == 1


def test_pup_over_everything_and_old_forms(open_window):
    open_window(W, H, rgb=False)
    color(BLUE)
    clear()
    drawmode(OVERDRAW)
    color(1)
    mapcolor(1, 1, 1, 1)
    clear()
    pupmode()
    assert getdrawmode() == PUPDRAW
    mapcolor(2, 250, 0, 250)
    color(2)
    rectfi(0, 0, 4, 4)
    endpupmode()
    assert getdrawmode() == NORMALDRAW
    assert shown(2, 2) == (250, 0, 250)
    assert shown(10, 10) == (1, 1, 1)
    assert read(SRC_PUP, 2, 2) == 2


def test_without_planes_or_in_cursordraw_nothing_is_drawn(open_window):
    open_window(W, H, rgb=False)
    overlay(0)
    gconfig()
    color(5)
    clear()
    drawmode(OVERDRAW)
    assert getplanes() == 0
    color(1)
    clear()
    drawmode(CURSORDRAW)
    mapcolor(1, 9, 8, 7)            # the cursor map
    assert getmcolor(1) == (9, 8, 7)
    color(1)
    clear()
    drawmode(NORMALDRAW)
    assert (lrectread(0, 0, W - 1, H - 1) == 5).all()
    assert shown(3, 3) == (255, 0, 255)
    assert read(SRC_OVER, 0, 0) == 0


def test_lrectwrite_in_overdraw(open_window):
    open_window(W, H, rgb=True)
    drawmode(OVERDRAW)
    mapcolor(2, 7, 7, 7)
    lrectwrite(0, 0, 1, 0, [2, 6])  # 6 is beyond the 2 planes: 6 & 3 = 2
    drawmode(NORMALDRAW)
    assert read(SRC_OVER, 0, 0) == 2 and read(SRC_OVER, 1, 0) == 2
    assert shown(1, 0) == (7, 7, 7)


def test_gRGBmask(open_window):
    open_window(W, H, rgb=True)
    assert gRGBmask() == (255, 255, 255)
    RGBwritemask(0x12, 0x34, 0x56)
    assert gRGBmask() == (0x12, 0x34, 0x56)
    drawmode(OVERDRAW)
    with pytest.raises(GLError, match="gRGBmask"):
        gRGBmask()


def test_rectread_and_rectcopy_in_overdraw(open_window):
    """The pixel calls address the current drawmode's bank: SRC_AUTO reads
    the overlay in OVERDRAW, rectcopy copies overlay to overlay."""
    open_window(W, H, rgb=False)
    color(6)
    clear()
    drawmode(OVERDRAW)
    color(2)
    rectfi(0, 0, 4, 4)
    assert int(lrectread(1, 1, 1, 1)[0, 0]) == 2
    assert int(lrectread(20, 20, 20, 20)[0, 0]) == 0
    rectcopy(0, 0, 3, 3, 10, 10)
    assert int(lrectread(11, 11, 11, 11)[0, 0]) == 2
    drawmode(NORMALDRAW)
    assert int(lrectread(11, 11, 11, 11)[0, 0]) == 6


def test_swapbuffers_and_greset_from_overdraw(open_window):
    """The normal framebuffer's buffering is its own: swapbuffers in
    OVERDRAW still swaps it, frontbuffer there does not touch it, and
    greset returns to NORMALDRAW with the normal framebuffer's modes."""
    open_window(W, H, rgb=True, double=True)
    cpack(0x0000FF)
    clear()                         # the back buffer
    drawmode(OVERDRAW)
    frontbuffer(TRUE)               # the overlay is single-buffered: ignored
    swapbuffers()
    drawmode(NORMALDRAW)
    assert shown(5, 5) == (255, 0, 0)
    assert getdisplaymode() == DMRGBDOUBLE
    cpack(0x00FF00)
    clear()                         # still only the back buffer
    assert shown(5, 5) == (255, 0, 0)
    drawmode(OVERDRAW)
    greset()
    assert getdrawmode() == NORMALDRAW
    assert getdisplaymode() == DMRGBDOUBLE


def test_the_popup_map_has_black_and_white_where_gl_h_names_them(open_window):
    """gl.h: PUP_BLACK 2, PUP_WHITE 3; SGI's menu package draws black text on
    PUP_WHITE (the overlay map keeps the eight default colours)."""
    open_window(W, H, rgb=False)
    drawmode(PUPDRAW)
    assert getmcolor(PUP_BLACK) == (0, 0, 0) and getmcolor(PUP_WHITE) == (255, 255, 255)
    drawmode(OVERDRAW)
    assert getmcolor(2) == (0, 255, 0) and getmcolor(3) == (255, 255, 0)
