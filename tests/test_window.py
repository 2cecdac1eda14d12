"""Windows and framebuffer configuration (docs/semantics.md §4, §13, §15, §20, §5, §8)."""
import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

RED_WORD = 0xFF0000FF
GREEN_WORD = 0xFF00FF00


def fb():
    from irisgl._current import machine
    return machine.current.fb


# -- winopen, sizes, ids -------------------------------------------------------------
def test_winopen_returns_distinct_ids_and_makes_current():
    prefsize(20, 10)
    a = winopen("a")
    prefsize(30, 15)
    b = winopen("b")
    assert isinstance(a, int) and isinstance(b, int)
    assert a > 0 and b > 0 and a != b
    assert winget() == b
    assert getsize() == (30, 15)
    winset(a)
    assert winget() == a
    assert getsize() == (20, 10)


def test_prefsize_sets_size_origin_defaults_to_screen_origin():
    prefsize(64, 48)
    winopen("x")
    assert getsize() == (64, 48)
    assert getorigin() == (0, 0)          # docs/semantics.md §8


def test_prefposition_sets_size_and_origin():
    prefposition(100, 163, 200, 247)      # x1, x2, y1, y2 inclusive
    winopen("x")
    assert getsize() == (64, 48)
    assert getorigin() == (100, 200)


def test_prefposition_takes_corners_in_either_order_and_past_the_screen():
    """prefposition(3G): (x1, y1) and (x2, y2) are opposite corners, in
    either order, and no error is listed: SGI's tpbig passes GD_XPMAX and
    GD_YPMAX (1280, 1024), a window one pixel wider and taller than the
    screen, as winposition allows; more than twice the screen is an error."""
    prefposition(300, 100, 400, 200)
    winopen("x")
    assert getsize() == (201, 201) and getorigin() == (100, 200)
    prefposition(0, getgdesc(GD_XPMAX), 0, getgdesc(GD_YPMAX))
    winopen("y")
    assert getsize() == (1281, 1025) and getorigin() == (0, 0)
    with pytest.raises(GLError, match="^prefposition: a 2600x10 window"):
        prefposition(0, 2599, 0, 9)


def test_pref_applies_to_next_window_only():
    prefposition(100, 163, 200, 247)
    winopen("x")
    prefsize(10, 12)
    winopen("y")
    assert getsize() == (10, 12)
    assert getorigin() == (0, 0)


def test_window_size_sets_banks_and_viewport():
    prefsize(33, 17)
    winopen("x")
    assert fb().front.shape == (17, 33)
    assert tuple(getviewport()) == (0, 32, 0, 16)


def test_winclose_and_winset():
    prefsize(8, 8)
    a = winopen("a")
    prefsize(9, 9)
    b = winopen("b")
    winclose(b)
    assert winget() == a
    with pytest.raises(GLError) as e:
        winset(b)
    assert str(e.value).startswith("winset")
    winclose(a)
    assert winget() == 0
    with pytest.raises(GLError):
        getsize()


def test_windows_have_separate_state(open_window):
    a = open_window(16, 16)
    loadmatrix(np.eye(4))
    translate(1, 2, 3)
    b = open_window(16, 16)
    loadmatrix(np.eye(4))
    assert getmatrix()[3][0] == 0
    winset(a)
    assert getmatrix()[3][0] == 1


# -- gconfig -------------------------------------------------------------------------
def test_back_bank_only_after_doublebuffer_and_gconfig():
    prefsize(16, 16)
    winopen("x")
    RGBmode()
    assert fb().back is None
    doublebuffer()
    assert fb().back is None              # effective at gconfig
    gconfig()
    assert fb().back is not None and fb().back.shape == (16, 16)
    assert getgconfig(GC_DOUBLE) == 1
    singlebuffer()
    gconfig()
    assert fb().back is None
    assert getgconfig(GC_DOUBLE) == 0


def test_z_bank_created_by_zbuffer(open_window):
    open_window(16, 16)
    assert fb().z is None
    zbuffer(FALSE)
    assert fb().z is None
    zbuffer(TRUE)
    assert fb().z is not None and fb().z.shape == (16, 16)


@pytest.mark.parametrize("call", ["zclear", "czclear"])
def test_z_bank_created_by_clears(open_window, call):
    open_window(16, 16)
    assert fb().z is None
    zclear() if call == "zclear" else czclear(0, 0)
    assert fb().z is not None
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, 15, 15)
    assert np.all(z == (0x7FFFFF if call == "zclear" else 0))


def test_stencil_bank_after_stensize_and_gconfig():
    prefsize(16, 16)
    winopen("x")
    RGBmode()
    gconfig()
    assert fb().stencil is None
    stensize(4)
    assert fb().stencil is None
    gconfig()
    assert fb().stencil is not None and fb().stencil.shape == (16, 16)
    assert getgconfig(GC_BITS_STENCIL) == 4
    stensize(0)
    gconfig()
    assert fb().stencil is None
    assert getgconfig(GC_BITS_STENCIL) == 0


def test_accum_bank_after_acsize_and_gconfig():
    prefsize(16, 16)
    winopen("x")
    RGBmode()
    acsize(16)
    assert fb().accum is None
    gconfig()
    assert fb().accum is not None
    assert getgconfig(GC_BITS_ACBUF) == -16     # signed on the VGX: negative


def test_doublebuffer_draws_into_back_only(open_window):
    open_window(16, 12, double=True)
    cpack(RED_WORD)
    clear()
    readsource(SRC_FRONT)
    assert np.all(lrectread(0, 0, 15, 11) == 0)
    readsource(SRC_BACK)
    assert np.all(lrectread(0, 0, 15, 11) == RED_WORD)
    assert np.all(vgx_emulator.window_image() == 0)      # the screen shows the front
    swapbuffers()
    readsource(SRC_FRONT)
    assert np.all(lrectread(0, 0, 15, 11) == RED_WORD)
    readsource(SRC_BACK)
    assert np.all(lrectread(0, 0, 15, 11) == 0)          # old front
    img = vgx_emulator.window_image()
    assert img.shape == (12, 16, 3)
    assert np.all(img == (255, 0, 0))


def test_swapbuffers_exchanges_twice(open_window):
    open_window(8, 8, double=True)
    ortho2(-0.5, 7.5, -0.5, 7.5)
    cpack(RED_WORD)
    pnt2i(1, 1)
    swapbuffers()
    cpack(GREEN_WORD)
    pnt2i(2, 2)
    swapbuffers()
    readsource(SRC_FRONT)
    front = lrectread(0, 0, 7, 7)
    assert front[2, 2] == GREEN_WORD and front[1, 1] == 0
    readsource(SRC_BACK)
    back = lrectread(0, 0, 7, 7)
    assert back[1, 1] == RED_WORD and back[2, 2] == 0


def test_readsource_auto_reads_back_in_double_buffer(open_window):
    open_window(8, 8, double=True)
    cpack(RED_WORD)
    clear()
    assert np.all(lrectread(0, 0, 7, 7) == RED_WORD)     # SRC_AUTO


def test_swapbuffers_ignored_single_buffered(open_window):
    open_window(8, 8)
    cpack(RED_WORD)
    clear()
    swapbuffers()
    assert np.all(lrectread(0, 0, 7, 7) == RED_WORD)
    assert fb().back is None


def test_frontbuffer_enables_front_in_double_buffer(open_window):
    open_window(8, 8, double=True)
    frontbuffer(TRUE)
    cpack(RED_WORD)
    clear()
    readsource(SRC_FRONT)
    assert np.all(lrectread(0, 0, 7, 7) == RED_WORD)
    readsource(SRC_BACK)
    assert np.all(lrectread(0, 0, 7, 7) == RED_WORD)
    backbuffer(FALSE)
    cpack(GREEN_WORD)
    clear()
    assert np.all(lrectread(0, 0, 7, 7) == RED_WORD)
    readsource(SRC_FRONT)
    assert np.all(lrectread(0, 0, 7, 7) == GREEN_WORD)


def test_gconfig_resets_colour_and_writemasks(open_window):
    open_window(8, 8)
    cpack(RED_WORD)
    clear()
    cpack(GREEN_WORD)
    wmpack(0)
    gconfig()                         # colour := 0, writemask := all ones
    clear()
    assert np.all(lrectread(0, 0, 7, 7) == 0)


def test_gconfig_resets_zwritemask(open_window):
    open_window(8, 8)
    czclear(0, 0)
    zwritemask(0)
    zclear()
    readsource(SRC_ZBUFFER)
    assert np.all(lrectread(0, 0, 7, 7) == 0)            # masked
    gconfig()
    zclear()
    assert np.all(lrectread(0, 0, 7, 7) == 0x7FFFFF)


# -- getgdesc / getgconfig / getplanes ----------------------------------------------------
GDESC = [("GD_XPMAX", 1280), ("GD_YPMAX", 1024), ("GD_ZMIN", -0x800000), ("GD_ZMAX", 0x7FFFFF),
         ("GD_BITS_STENCIL", 8), ("GD_NVERTEX_POLY", 256), ("GD_BITS_NORM_SNG_RED", 8),
         ("GD_BITS_NORM_DBL_BLUE", 8), ("GD_BITS_NORM_SNG_CMODE", 12),
         ("GD_BITS_NORM_DBL_CMODE", 12), ("GD_BITS_NORM_SNG_MMAP", 8),
         ("GD_BITS_NORM_ZBUFFER", 24), ("GD_BITS_ACBUF", 16), ("GD_READSOURCE_ZBUFFER", 1),
         ("GD_TEXTURE", 1), ("GD_TEXTURE_PERSP", 0), ("GD_BLEND", 1), ("GD_LOGICOP", 1)]


@pytest.mark.parametrize("name, value", GDESC)
def test_getgdesc_before_winopen(name, value):
    import irisgl
    assert getgdesc(getattr(irisgl, name)) == value


def test_getgdesc_constants_and_unknown():
    assert (GD_XPMAX, GD_ZMIN, GD_ZMAX, GD_NVERTEX_POLY, GD_BITS_STENCIL) == (0, 4, 5, 39, 72)
    assert getgdesc(9999) == -1
    assert getgdesc(-77) == -1


def test_getgdesc_same_after_winopen(open_window):
    open_window()
    assert getgdesc(GD_BITS_STENCIL) == 8
    assert getgdesc(GD_ZMAX) == 0x7FFFFF


def test_getgconfig_rgb(open_window):
    open_window(8, 8)
    assert getgconfig(GC_BITS_RED) == 8
    assert getgconfig(GC_BITS_GREEN) == 8
    assert getgconfig(GC_BITS_BLUE) == 8
    assert getgconfig(GC_BITS_CMODE) == 0
    assert getgconfig(GC_BITS_ZBUFFER) == -24            # signed z: negative
    assert getgconfig(GC_ZMIN) == -0x800000
    assert getgconfig(GC_ZMAX) == 0x7FFFFF
    assert getgconfig(GC_DOUBLE) == 0
    assert getgconfig(GC_BITS_STENCIL) == 0


def test_getgconfig_cmode(open_window):
    open_window(8, 8, rgb=False)
    assert getgconfig(GC_BITS_CMODE) == 12
    assert getgconfig(GC_BITS_RED) == 0


def test_getplanes(open_window):
    open_window(8, 8)
    assert getplanes() == 24
    open_window(8, 8, double=True)
    assert getplanes() == 24
    open_window(8, 8, rgb=False)
    assert getplanes() == 12


def test_getdisplaymode(open_window):
    open_window(8, 8)
    assert getdisplaymode() == DMRGB
    open_window(8, 8, double=True)
    assert getdisplaymode() == DMRGBDOUBLE
    open_window(8, 8, rgb=False)
    assert getdisplaymode() == DMSINGLE


# -- colour-map mode -----------------------------------------------------------------
DEFAULT_MAP = {BLACK: (0, 0, 0), RED: (255, 0, 0), GREEN: (0, 255, 0), YELLOW: (255, 255, 0),
               BLUE: (0, 0, 255), MAGENTA: (255, 0, 255), CYAN: (0, 255, 255),
               WHITE: (255, 255, 255)}


def test_default_colour_map_names():
    assert (BLACK, RED, GREEN, YELLOW, BLUE, MAGENTA, CYAN, WHITE) == tuple(range(8))


@pytest.mark.parametrize("index", sorted(DEFAULT_MAP))
def test_default_colour_map(open_window, index):
    open_window(8, 6, rgb=False)
    color(index)
    clear()
    img = vgx_emulator.window_image()
    assert img.shape == (6, 8, 3)
    assert np.all(img == DEFAULT_MAP[index])
    assert getmcolor(index) == DEFAULT_MAP[index]


def test_winopen_default_is_colour_map():
    prefsize(8, 8)
    winopen("x")
    gconfig()
    assert getplanes() == 12
    color(RED)
    clear()
    assert np.all(vgx_emulator.window_image() == (255, 0, 0))


def test_mapcolor_recolours_drawn_pixels(open_window):
    open_window(8, 6, rgb=False)
    ortho2(-0.5, 7.5, -0.5, 5.5)
    color(RED)
    clear()
    color(100)
    pnt2i(2, 1)
    img = vgx_emulator.window_image()
    # entry 100 by default: makemap's colour cube, 100 = 56 + g + 8 r + 40 b with b = 1,
    # r = 0, g = 4: (0, 4 * 255 / 7, 255 / 4) rounded
    assert tuple(img[6 - 1 - 1, 2]) == (0, 146, 64)
    mapcolor(RED, 10, 20, 30)
    mapcolor(100, 200, 150, 100)
    img = vgx_emulator.window_image()
    assert tuple(img[4, 2]) == (200, 150, 100)            # top row first: y=1 is row 4
    mask = np.ones((6, 8), bool)
    mask[4, 2] = False
    assert np.all(img[mask] == (10, 20, 30))
    assert getmcolor(RED) == (10, 20, 30)
    # the stored indices did not change
    assert lrectread(2, 1, 2, 1)[0, 0] == 100
    assert lrectread(0, 0, 0, 0)[0, 0] == RED


def test_rgb_calls_are_errors_in_cmode_and_color_in_rgb(open_window):
    open_window(8, 8, rgb=False)
    with pytest.raises(GLError):
        RGBcolor(1, 2, 3)
    with pytest.raises(GLError):
        cpack(0xFF)
    open_window(8, 8)
    with pytest.raises(GLError):
        color(RED)


def test_rgb_window_image_orientation(open_window):
    open_window(8, 6)
    ortho2(-0.5, 7.5, -0.5, 5.5)
    cpack(0xFF332211)                 # r 0x11, g 0x22, b 0x33
    pnt2i(0, 0)
    img = vgx_emulator.window_image()
    assert tuple(img[5, 0]) == (0x11, 0x22, 0x33)        # bottom-left is the last row
    assert img[:5].sum() == 0 and img[5, 1:].sum() == 0
