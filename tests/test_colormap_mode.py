"""Colour-map mode for real: per-pixel indices, mapcolor at scan-out,
getplanes, clamped color/colorf, masked clears, multimap/setmap, cyclemap
and blink at frame points (color(3G), mapcolor(3G), getplanes(3G),
writemask(3G), clear(3G), multimap(3G), setmap(3G), cyclemap(3G), blink(3G),
colorf(3G); docs/colour-map-and-depthcue.md)."""
import pytest

import vgx_emulator
from irisgl import *
from irisgl._current import machine

W, H = 32, 24


def shown(x, y):
    """(r, g, b) the screen shows at window pixel (x, y)."""
    img = vgx_emulator.window_image()
    return tuple(int(v) for v in img[img.shape[0] - 1 - y, x])


def cwin(open_window):
    open_window(W, H, rgb=False)


def test_getplanes_per_mode(open_window):
    cwin(open_window)
    assert getplanes() == 12
    multimap()
    assert getplanes() == 12            # effective at gconfig
    gconfig()
    assert getplanes() == 8
    assert getcmmode() == CMAPMULTI
    onemap()
    gconfig()
    assert getplanes() == 12 and getcmmode() == CMAPONE
    RGBmode()
    gconfig()
    assert getplanes() == 24
    # flight's use: a mask of all the planes fits a short
    cmode()
    gconfig()
    assert (1 << getplanes()) - 1 == 0xFFF


def test_getgdesc_colour_maps():
    assert getgdesc(GD_NMMAPS) == 16
    assert getgdesc(GD_BITS_NORM_SNG_MMAP) == 8
    assert getgdesc(GD_BITS_NORM_SNG_CMODE) == 12
    assert getgdesc(GD_BITS_PUP_SNG_CMODE) == 2
    assert getgdesc(GD_BITS_OVER_SNG_CMODE) == 8


def test_the_default_map_is_makemaps(open_window):
    """makemap(1G): the eight named colours at 0..7, a black to almost-white
    grey ramp of 24 entries at 32..55, a 5 x 8 x 5 colour cube from black to
    white at 56..255 with green changing fastest, then red, then blue.
    Entries the man page does not give (8..31, past 255) are black; greset
    brings the map back."""
    open_window(4, 4, rgb=False)
    assert getmcolor(YELLOW) == (255, 255, 0) and getmcolor(WHITE) == (255, 255, 255)
    greys = [getmcolor(32 + k) for k in range(24)]
    assert all(r == g == b for r, g, b in greys)
    assert greys[0] == (0, 0, 0) and greys[12] == (128, 128, 128) and greys[23][0] == 244
    assert all(a[0] < b[0] for a, b in zip(greys, greys[1:]))
    for r in range(5):
        for g in range(8):
            for b in range(5):
                want = tuple(round(v * 255 / n) for v, n in ((r, 4), (g, 7), (b, 4)))
                assert getmcolor(56 + g + 8 * r + 40 * b) == want
    assert getmcolor(56) == (0, 0, 0) and getmcolor(255) == (255, 255, 255)
    assert all(getmcolor(i) == (0, 0, 0) for i in (8, 15, 16, 31, 256, 4095))
    mapcolor(40, 1, 2, 3)
    greset()
    assert getmcolor(40) == greys[8]


def test_mapcolor_recolours_what_is_drawn(open_window):
    cwin(open_window)
    color(BLACK)
    clear()
    color(100)
    rectfi(4, 4, 9, 9)
    mapcolor(100, 10, 20, 30)
    before = lrectread(0, 0, W - 1, H - 1).copy()
    assert shown(5, 5) == (10, 20, 30)
    assert shown(20, 20) == (0, 0, 0)
    mapcolor(100, 200, 100, 50)             # after drawing
    assert shown(5, 5) == (200, 100, 50)
    assert (lrectread(0, 0, W - 1, H - 1) == before).all()   # indices stay
    assert int(before[5, 5]) == 100 and int(before[0, 0]) == 0
    assert getmcolor(100) == (200, 100, 50)


def test_mapcolor_clamps_and_ignores_bad_index(open_window):
    cwin(open_window)
    mapcolor(9, 300, -5, 128)
    assert getmcolor(9) == (255, 0, 128)
    old = machine.colormap.copy()
    mapcolor(4096, 1, 2, 3)                 # outside the map: ignored
    mapcolor(-1, 1, 2, 3)
    assert (machine.colormap == old).all()
    assert getmcolor(RED) == (255, 0, 0)    # the default map's named colours


def test_color_clamps_to_planes(open_window):
    cwin(open_window)
    color(5000)
    assert getcolor() == 4095
    color(-3)
    assert getcolor() == 0
    multimap()
    gconfig()
    color(300)
    assert getcolor() == 255
    clear()
    assert int(lrectread(1, 1, 1, 1)[0, 0]) == 255


def test_colorf_rounds_to_nearest(open_window):
    cwin(open_window)
    colorf(2.4)
    assert getcolor() == 2
    bgnpoint()
    v2i((0, 0))
    colorf(2.6)
    v2i((1, 0))
    endpoint()
    assert getcolor() == 3
    got = lrectread(0, 0, 1, 0)[0]
    assert list(got) == [2, 3]
    colorf(1e9)
    assert getcolor() == 4095


def test_colorf_gouraud_keeps_fraction(open_window):
    """GD_CIFRACT = 1: Gouraud shading iterates the unrounded indices.  A
    line from 0.4 to 1.4 over x = 0..4 shades 0.4, 0.65, 0.9, 1.15, 1.4 ->
    0, 1, 1, 1, 1; ends rounded first (0 and 1) would give 0, 0, 1, 1, 1."""
    cwin(open_window)
    assert getgdesc(GD_CIFRACT) == 1
    bgnline()
    colorf(0.4)
    v2i((0, 5))
    colorf(1.4)
    v2i((4, 5))
    endline()
    assert list(lrectread(0, 5, 4, 5)[0]) == [0, 1, 1, 1, 1]


def test_masked_clear(open_window):
    cwin(open_window)
    color(0x123)
    clear()
    writemask(0x0F0)
    assert getwritemask() == 0x0F0
    color(0xABC)
    clear()
    want = (0x123 & ~0x0F0) | (0xABC & 0x0F0)
    got = lrectread(0, 0, W - 1, H - 1)
    assert (got == want).all()


def test_masked_clear_honours_pattern(open_window):
    cwin(open_window)
    color(0x100)
    clear()
    defpattern(1, PATTERN_16, [0xFF00] * 16)        # left half of each tile
    setpattern(1)
    writemask(0x00F)
    color(0x0F5)
    clear()
    got = lrectread(0, 0, 15, 0)[0]
    assert list(got[:8]) == [0x105] * 8
    assert list(got[8:]) == [0x100] * 8


def test_getwritemask_after_gconfig(open_window):
    cwin(open_window)
    assert getwritemask() == 0xFFF
    writemask(0x7777)
    assert getwritemask() == 0x777
    gconfig()
    assert getwritemask() == 0xFFF


def test_multimap_setmap_selects_map_at_scanout(open_window):
    cwin(open_window)
    multimap()
    gconfig()
    setmap(3)
    assert getmap() == 3
    mapcolor(5, 11, 22, 33)                 # physical entry 3*256+5
    assert tuple(machine.colormap[3 * 256 + 5]) == (11, 22, 33)
    setmap(4)
    mapcolor(5, 44, 55, 66)
    assert getmcolor(5) == (44, 55, 66)
    color(5)
    clear()
    assert shown(1, 1) == (44, 55, 66)
    setmap(3)
    assert shown(1, 1) == (11, 22, 33)
    assert getmcolor(5) == (11, 22, 33)
    mapcolor(300, 1, 1, 1)                  # beyond the 256 entries: ignored
    assert tuple(machine.colormap[3 * 256 + 44]) == (0, 0, 0)


def test_setmap_errors_and_onemap(open_window):
    cwin(open_window)
    setmap(7)                               # onemap mode: ignored
    assert getmap() == 0
    multimap()
    gconfig()
    setmap(2)
    with pytest.raises(GLError, match="setmap"):
        setmap(16)
    assert getmap() == 2
    drawmode(OVERDRAW)
    with pytest.raises(GLError, match="multimap"):
        multimap()


def test_cyclemap_moves_along_the_chain_at_frame_points(open_window):
    cwin(open_window)
    multimap()
    gconfig()
    for m, rgb in ((0, (10, 0, 0)), (1, (0, 10, 0)), (2, (0, 0, 10))):
        setmap(m)
        mapcolor(9, *rgb)
    setmap(0)
    color(9)
    clear()
    cyclemap(2, 0, 1)                       # 2 retraces = one frame point
    cyclemap(4, 1, 2)
    cyclemap(2, 2, 0)
    seen = []
    for _ in range(6):
        seen.append((getmap(), shown(0, 0)))
        gflush()
    assert [m for m, _ in seen] == [0, 1, 1, 2, 0, 1]
    assert seen[0][1] == (10, 0, 0) and seen[1][1] == (0, 10, 0) and seen[3][1] == (0, 0, 10)
    cyclemap(0, 1, 2)                       # duration 0 removes the link
    for _ in range(3):
        gflush()
    assert getmap() == 1


def test_cyclemap_needs_multimap(open_window):
    cwin(open_window)
    with pytest.raises(GLError, match="cyclemap"):
        cyclemap(2, 0, 1)
    assert machine.maps.cycles == {}


def test_blink_alternates_at_frame_points(open_window):
    cwin(open_window)
    mapcolor(20, 1, 2, 3)
    color(20)
    clear()
    blink(2, 20, 200, 100, 0)               # every 2 retraces = every frame point
    seq = []
    for _ in range(4):
        gflush()
        seq.append(shown(3, 3))
    assert seq == [(200, 100, 0), (1, 2, 3), (200, 100, 0), (1, 2, 3)]
    assert getmcolor(20) == (1, 2, 3)       # the map keeps the colour
    blink(4, 20, 9, 9, 9)                   # a new rate for the same entry
    gflush()                                # retrace 10: 10 // 4 = 2, even
    assert shown(3, 3) == (1, 2, 3)
    gflush()                                # retrace 12: 3, odd
    assert shown(3, 3) == (9, 9, 9)
    blink(0, 20, 0, 0, 0)
    assert shown(3, 3) == (1, 2, 3)
    for i in range(20):
        blink(2, 100 + i, 1, 1, 1)
    with pytest.raises(GLError, match="blink"):
        blink(2, 200, 1, 1, 1)
    blink(-1, 0, 0, 0, 0)
    assert machine.maps.blinks == {}


def test_colour_index_calls_in_rgb_mode_fail(open_window):
    open_window(W, H, rgb=True)
    cpack(0x00FF00)
    for call, args in ((color, (3,)), (colorf, (3.0,)), (setshade, (3,))):
        with pytest.raises(GLError, match=call.__name__):
            call(*args)
    assert gRGBcolor() == (0, 255, 0)


def test_colormap_cycle_demo():
    """Frame after frame the same pixels change colour (the map entries move
    along the palette) while the stored indices stay the same."""
    import importlib.util
    from pathlib import Path
    from vgx_emulator.runner import run_program
    path = Path(__file__).resolve().parent.parent / "programs" / "demos" / "colormap_cycle.py"
    spec = importlib.util.spec_from_file_location("colormap_cycle", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    images, indices = [], []
    for frames in (1, 2, 3):
        images.append(run_program(path, frames, []))
        readsource(SRC_FRONT)
        indices.append(lrectread(0, 0, mod.WIDTH - 1, mod.HEIGHT - 1).copy())
    h = mod.HEIGHT
    for phase, img in enumerate(images, start=1):
        for i in range(mod.NBANDS):
            x = i * mod.BANDW + mod.BANDW // 2
            assert tuple(img[h - 1 - 100, x]) == mod.PALETTE[(i + phase) % mod.NBANDS]
        assert tuple(img[h - 1 - 5, 10]) == (0, 0, 0)          # below the bands
    assert (indices[0] == indices[1]).all() and (indices[1] == indices[2]).all()
    assert int(indices[0][100, 3 * mod.BANDW + 1]) == mod.BASE + 3
    assert (images[0] != images[1]).any()
