"""depthcue(3G), lshaderange(3G)/shaderange(3G), lRGBrange(3G)/RGBrange(3G),
getdcm(3G), setshade/getshade: colour from screen z, clamped beyond the
range, on lines, points and polygons (docs/colour-map-and-depthcue.md)."""
from pathlib import Path

import numpy as np
import pytest

from irisgl import *
from irisgl._current import machine

ZMIN, ZMAX = -0x800000, 0x7FFFFF
W, H = 65, 40
ROOT = Path(__file__).resolve().parent.parent


def setup(open_window, rgb):
    """A window where x = 0..64 maps eye z from +1 (near, screen z GD_ZMIN)
    to -1 (far, GD_ZMAX) along a line: ortho(..., -1, 1)."""
    open_window(W, H, rgb=rgb)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    (cpack(0) if rgb else color(0))
    clear()


def ramp_line(y, z0=1.0, z1=-1.0):
    bgnline()
    v3f((0, y, z0))
    v3f((64, y, z1))
    endline()


def screen_z(x, z0=1.0, z1=-1.0):
    """Window z of pixel x of ramp_line (the depth mapping of lsetdepth(3G))."""
    zn = -(z0 + (z1 - z0) * x / 64.0)           # eye z -> normalized device z
    return (ZMAX + ZMIN) / 2 + zn * (ZMAX - ZMIN) / 2


def test_index_ramp_on_a_line(open_window):
    setup(open_window, rgb=False)
    assert getdcm() == 0
    depthcue(TRUE)
    assert getdcm() == 1
    lshaderange(100, 164, ZMIN, ZMAX)
    color(7)                                   # ignored: z alone decides
    ramp_line(10)
    got = lrectread(0, 10, 64, 10)[0].astype(int)
    # t = x / 64 from znear to zfar: index 164 - x, exactly
    assert list(got) == [164 - x for x in range(65)]


def test_index_ramp_clamps_beyond_range(open_window):
    """z nearer than znear gives highin, farther than zfar lowin; inside,
    the ramp.  (The ramp is evaluated per vertex, so a primitive reaching
    beyond the range interpolates between clamped vertex values:
    docs/colour-map-and-depthcue.md.)"""
    setup(open_window, rgb=False)
    depthcue(TRUE)
    zn, zf = screen_z(16), screen_z(48)
    lshaderange(200, 232, int(zn), int(zf))

    def seg(y, xa, xb):
        bgnline()
        v3f((xa, y, 1 - xa / 32.0))
        v3f((xb, y, 1 - xb / 32.0))
        endline()
        return list(lrectread(xa, y, xb, y)[0].astype(int))
    assert seg(5, 0, 12) == [232] * 13          # all nearer than znear
    assert seg(6, 52, 64) == [200] * 13         # all farther than zfar
    inside = seg(7, 16, 48)
    want = [int(np.floor(232 + (screen_z(x) - zn) / (zf - zn) * (200 - 232) + 0.5))
            for x in range(16, 49)]
    assert inside == want
    assert inside[0] == 232 and inside[-1] == 200 and inside[16] == 216


def test_flat_shading_still_cues_along_the_line(open_window):
    setup(open_window, rgb=False)
    shademodel(FLAT)
    depthcue(TRUE)
    lshaderange(0, 64, ZMIN, ZMAX)
    ramp_line(3)
    got = lrectread(0, 3, 64, 3)[0].astype(int)
    assert list(got) == [64 - x for x in range(65)]


def test_rgb_ramp(open_window):
    setup(open_window, rgb=True)
    depthcue(TRUE)
    lRGBrange(0, 64, 10, 128, 0, 74, ZMIN, ZMAX)
    ramp_line(7)
    got = lrectread(0, 7, 64, 7)[0].astype(np.int64)
    r, g, b = got & 0xFF, (got >> 8) & 0xFF, (got >> 16) & 0xFF
    x = np.arange(65)
    assert (r == 128 - 2 * x).all()             # rmax at znear -> rmin at zfar
    assert (g == x).all()                       # gmax 0, gmin 64
    assert (b == 74 - x).all()


def test_old_forms_match(open_window):
    setup(open_window, rgb=False)
    depthcue(TRUE)
    shaderange(100, 164, ZMIN, ZMAX)
    ramp_line(10)
    assert list(lrectread(0, 10, 64, 10)[0].astype(int)) == [164 - x for x in range(65)]
    winclose(winget())
    setup(open_window, rgb=True)
    depthcue(TRUE)
    RGBrange(0, 64, 10, 128, 0, 74, ZMIN, ZMAX)
    ramp_line(7)
    assert int(lrectread(0, 7, 0, 7)[0, 0]) & 0xFFFFFF == (74 << 16) | 128


def test_points_and_polygons(open_window):
    setup(open_window, rgb=False)
    depthcue(TRUE)
    lshaderange(100, 164, ZMIN, ZMAX)
    bgnpoint()
    v3f((3, 30, 0.0))                           # screen z in the middle: t = 1/2
    v3f((5, 30, 1.0))                           # the near plane: highin
    endpoint()
    assert list(lrectread(3, 30, 5, 30)[0].astype(int)) == [132, 0, 164]
    bgnpolygon()
    v3f((0, 15, 1.0))
    v3f((64, 15, -1.0))
    v3f((64, 25, -1.0))
    v3f((0, 25, 1.0))
    endpolygon()
    got = lrectread(0, 20, 63, 20)[0].astype(int)
    assert list(got) == [164 - x for x in range(64)]


def test_depthcue_off_draws_the_colour(open_window):
    setup(open_window, rgb=False)
    depthcue(TRUE)
    depthcue(FALSE)
    color(7)
    ramp_line(2)
    assert (lrectread(0, 2, 64, 2) == 7).all()


def test_errors_leave_state(open_window):
    setup(open_window, rgb=False)
    lshaderange(1, 2, 3, 4)
    with pytest.raises(GLError, match="lshaderange"):
        lshaderange(1, "x", 3, 4)
    with pytest.raises(GLError, match="lRGBrange"):
        lRGBrange(0, 0, 0, 1, 1, None, 0, 1)
    assert machine.current.st.shaderange == (1, 2, 3, 4)
    assert machine.current.st.rgbrange == (0, 0, 0, 255, 255, 255, ZMIN, ZMAX)
    lshaderange(0, 9, -2 ** 30, 2 ** 30)        # z clamped to the VGX range
    assert machine.current.st.shaderange == (0, 9, ZMIN, ZMAX)
    lshaderange(0, 9, 0xff800000, 2 ** 32 + 7)  # C longs: 32-bit two's complement first
    assert machine.current.st.shaderange == (0, 9, ZMIN, 7)


def test_setshade_getshade(open_window):
    setup(open_window, rgb=False)
    setshade(12)
    assert getshade() == 12 and getcolor() == 12
    clear()
    assert int(lrectread(0, 0, 0, 0)[0, 0]) == 12


def test_depthcue_needs_a_window():
    with pytest.raises(GLError, match="depthcue"):
        depthcue(TRUE)


def _load_demo(name):
    import importlib.util
    spec = importlib.util.spec_from_file_location(name, ROOT / "programs" / "demos" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_depthcue_wire_demo():
    """The demo's first frame: a wire cube turned 25 degrees about x and 30
    about y, 6 units away.  Its nearest vertex shows the ramp entry of its
    screen z (the brightest green drawn), its farthest the dimmest; every
    lit pixel is a ramp colour (0, g, 0)."""
    from vgx_emulator.runner import run_program
    mod = _load_demo("depthcue_wire")
    img = run_program(ROOT / "programs" / "demos" / "depthcue_wire.py", 1, [])
    assert img is not None and img.shape == (400, 400, 3)
    # eye z of the vertices (the set is the same for either rotation sense)
    ax, ay = np.radians(25.0), np.radians(30.0)
    rx = np.array([[1, 0, 0], [0, np.cos(ax), np.sin(ax)], [0, -np.sin(ax), np.cos(ax)]])
    ry = np.array([[np.cos(ay), 0, -np.sin(ay)], [0, 1, 0], [np.sin(ay), 0, np.cos(ay)]])
    z = (np.array(mod.CUBE, float) @ ry @ rx)[:, 2]
    d = mod.DIST - z                               # eye distances
    zn = int(mod.screen_z(mod.DIST - mod.HALF))
    zf = int(mod.screen_z(mod.DIST + mod.HALF))

    def index(dist):
        t = min(max((mod.screen_z(dist) - zn) / (zf - zn), 0.0), 1.0)
        return int(np.floor(mod.RAMP_HI + t * (mod.RAMP_LO - mod.RAMP_HI) + 0.5))
    lit = img.sum(axis=2) > 0
    assert lit.sum() > 500
    green = img[lit][:, 1].astype(int)
    assert (img[lit][:, 0] == 0).all() and (img[lit][:, 2] == 0).all()
    assert green.max() == mod.ramp_green(index(d.min()))      # nearest vertex
    assert green.min() == mod.ramp_green(index(d.max()))      # farthest vertex
    assert green.max() - green.min() > 60                      # near brighter than far
    # and at the pixels the two vertices project to (perspective(3G) matrix,
    # default viewport, vertices snapped to pixel centres)
    f, n = mod.FAR, mod.NEAR
    c = 1.0 / np.tan(np.radians(40.0 / 2))
    proj = np.array([[c, 0, 0, 0], [0, c, 0, 0], [0, 0, -(f + n) / (f - n), -1],
                     [0, 0, -2 * f * n / (f - n), 0]])
    eye = np.array(mod.CUBE, float) @ ry @ rx + (0.0, 0.0, -mod.DIST)
    clip = np.hstack((eye, np.ones((8, 1)))) @ proj
    px = np.floor(-0.5 + (clip[:, 0] / clip[:, 3] + 1) * 200 + 0.5).astype(int)
    py = np.floor(-0.5 + (clip[:, 1] / clip[:, 3] + 1) * 200 + 0.5).astype(int)
    for k in (int(np.argmin(d)), int(np.argmax(d))):
        assert tuple(img[399 - py[k], px[k]]) == (0, mod.ramp_green(index(d[k])), 0)
