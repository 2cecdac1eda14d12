"""Per-vertex fog (fogvertex(3G)): the fog factor at known eye distances.

Expectations follow the formulas of vgx_emulator/geometry/fog.py and
docs/clip-planes-fog-and-extras.md: C' = f C + (1 - f) C_fog with
LIN f = (end - z) / (end - start), EXP f = 255^-(d z), EXP2 f = 255^-((d z)^2),
z the eye distance, density 1 fully opaque (f = 1/255) at distance 1.
"""
import math

import numpy as np
import pytest

from irisgl import (FG_OFF, FG_ON, FG_PIX_EXP, FG_PIX_LIN, FG_VTX_EXP, FG_VTX_EXP2, FG_VTX_LIN,
                    FG_DEFINE, GD_FOGPIXEL, GD_FOGVERTEX, GLError, MVIEWING, bgnpolygon,
                    callobj, clear, closeobj, color, cpack, endpolygon, fogvertex, getgdesc,
                    lrectread, makeobj, mapcolor, mmode, ortho, v3f)

W, H = 64, 48
RED = 0xFF0000FF


def _scene(open_window, rgb=True):
    open_window(W, H, rgb=rgb)
    mmode(MVIEWING)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, 0.0, 100.0)
    if rgb:
        cpack(0)
    else:
        color(0)
    clear()


def _quad(x0, x1, z0, z1=None, y0=0, y1=20):
    """A quad at eye depth -z0 (left) .. -z1 (right)."""
    z1 = z0 if z1 is None else z1
    bgnpolygon()
    v3f([x0, y0, -z0])
    v3f([x1, y0, -z1])
    v3f([x1, y1, -z1])
    v3f([x0, y1, -z0])
    endpolygon()


def _rgb(word):
    w = int(word)
    return w & 0xFF, (w >> 8) & 0xFF, (w >> 16) & 0xFF


def _expect(f, obj=(255, 0, 0), fog=(0, 0, 255)):
    return tuple(int(math.floor(f * o + (1 - f) * g + 0.5)) for o, g in zip(obj, fog))


def test_vgx_has_vertex_fog_only():
    assert getgdesc(GD_FOGVERTEX) == 1
    assert getgdesc(GD_FOGPIXEL) == 0
    assert FG_DEFINE == FG_VTX_EXP


def test_linear_fog_factor_at_known_distance(open_window):
    """start 0, end 25, distance 10: f = 0.6 -> red 153, blue 102."""
    _scene(open_window)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 30, 10.0)
    img = lrectread(0, 0, W - 1, H - 1)
    assert _rgb(img[5, 5]) == (153, 0, 102)
    assert img[5, 5] >> 24 == 0xFF                    # alpha unchanged


def test_linear_fog_before_start_and_after_end(open_window):
    _scene(open_window)
    fogvertex(FG_VTX_LIN, [20.0, 40.0, 0.0, 1.0, 0.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 20, 10.0)           # nearer than start: no fog
    _quad(30, 60, 50.0)          # beyond end: all fog
    img = lrectread(0, 0, W - 1, H - 1)
    assert _rgb(img[5, 5]) == (255, 0, 0)
    assert _rgb(img[5, 40]) == (0, 255, 0)


@pytest.mark.parametrize("mode, density, z", [(FG_VTX_EXP, 0.05, 10.0), (FG_VTX_EXP, 1.0, 1.0),
                                              (FG_VTX_EXP2, 0.07, 10.0),
                                              (FG_PIX_EXP, 0.02, 30.0)])
def test_exponential_fog(open_window, mode, density, z):
    _scene(open_window)
    fogvertex(mode, [density, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 30, z)
    dz = density * z
    f = 255.0 ** -(dz if mode in (FG_VTX_EXP, FG_PIX_EXP) else dz * dz)
    got = _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5])
    assert got == _expect(f)


def test_density_one_is_opaque_at_distance_one(open_window):
    """fogvertex(3G): density 1.0 makes the fog completely opaque at eye
    distance 1.0: what is left of the object is below one 8-bit step."""
    _scene(open_window)
    fogvertex(FG_VTX_EXP, [1.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 30, 1.0)
    r, g, b = _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5])
    assert r <= 1 and b >= 254


def test_fog_is_per_vertex_then_gouraud(open_window):
    """A quad from depth 0 (x = 0) to 50 (x = 63) under LIN 0..50: the
    vertices get f = 1 and 0; pixels in between interpolate linearly."""
    _scene(open_window)
    fogvertex(FG_VTX_LIN, [0.0, 50.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 63, 0.0, 50.0)
    row = lrectread(0, 5, W - 1, 5)[0]
    reds = np.array([_rgb(v)[0] for v in row[:63]])
    blues = np.array([_rgb(v)[2] for v in row[:63]])
    assert reds[0] == 255 and blues[0] == 0
    assert (np.diff(reds) <= 0).all() and (np.diff(blues) >= 0).all()
    assert (np.abs(reds + blues - 255) <= 1).all()
    # half way along x: half fogged
    assert abs(int(reds[31]) - 255 * (1 - 31 / 63)) <= 2


def test_pixel_modes_are_computed_per_vertex(open_window):
    """GD_FOGPIXEL is 0: FG_PIX_LIN draws what FG_VTX_LIN draws."""
    _scene(open_window)
    cpack(RED)
    fogvertex(FG_VTX_LIN, [0.0, 50.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    _quad(0, 63, 0.0, 50.0, 0, 10)
    fogvertex(FG_PIX_LIN, [0.0, 50.0, 0.0, 0.0, 1.0])
    _quad(0, 63, 0.0, 50.0, 20, 30)
    img = lrectread(0, 0, W - 1, H - 1)
    assert (img[5, :63] == img[25, :63]).all()
    assert len(set(img[5, :63].tolist())) > 20


def test_fog_off_and_default(open_window):
    _scene(open_window)
    cpack(RED)
    fogvertex(FG_ON)                       # nothing defined yet: density 0, no fog
    _quad(0, 20, 30.0)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fogvertex(FG_OFF)
    _quad(30, 60, 10.0)
    img = lrectread(0, 0, W - 1, H - 1)
    assert _rgb(img[5, 5]) == (255, 0, 0)
    assert _rgb(img[5, 40]) == (255, 0, 0)


def test_redefinition_keeps_what_was_drawn(open_window):
    """Batching: the quad drawn before the redefinition keeps the old fog."""
    _scene(open_window)
    cpack(RED)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    _quad(0, 20, 10.0)
    fogvertex(FG_VTX_LIN, [0.0, 20.0, 0.0, 1.0, 0.0])
    _quad(30, 60, 10.0)
    img = lrectread(0, 0, W - 1, H - 1)
    assert _rgb(img[5, 5]) == (153, 0, 102)
    assert _rgb(img[5, 40]) == (128, 128, 0)        # f = 0.5: 127.5 -> 128


def test_fog_colour_is_clamped(open_window):
    _scene(open_window)
    cpack(RED)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, -1.0, 2.0, 0.0])
    fogvertex(FG_ON)
    _quad(0, 20, 10.0)
    assert _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5]) == (153, 102, 0)


def test_no_fog_in_colour_map_mode(open_window):
    _scene(open_window, rgb=False)
    mapcolor(9, 255, 0, 0)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    color(9)
    _quad(0, 20, 10.0)
    assert int(lrectread(0, 0, W - 1, H - 1)[5, 5]) == 9


def test_recorded_in_objects(open_window):
    _scene(open_window)
    makeobj(3)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 20, 10.0)
    fogvertex(FG_OFF)
    closeobj()
    callobj(3)
    assert _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5]) == (153, 0, 102)


def test_errors_change_nothing(vgx, open_window):
    _scene(open_window)
    fogvertex(FG_VTX_LIN, [0.0, 25.0, 0.0, 0.0, 1.0])
    fs = vgx.current.st.fog
    before = (fs.mode, fs.kind, fs.density, fs.start, fs.end, fs.colour, fs.on)
    with pytest.raises(GLError, match="fogvertex: unknown mode"):
        fogvertex(99, [0, 0, 0, 0])
    with pytest.raises(GLError, match="FG_\\*_LIN takes"):
        fogvertex(FG_VTX_LIN, [1.0, 2.0, 0.0, 0.0])
    with pytest.raises(GLError, match="density"):
        fogvertex(FG_VTX_EXP, [float("nan"), 0.0, 0.0, 0.0])
    with pytest.raises(GLError, match="not finite"):
        fogvertex(FG_VTX_LIN, [0.0, float("inf"), 0.0, 0.0, 0.0])
    with pytest.raises(GLError, match="not a number"):
        fogvertex(FG_VTX_EXP, ["thick", 0.0, 0.0, 0.0])
    assert (fs.mode, fs.kind, fs.density, fs.start, fs.end, fs.colour, fs.on) == before
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 20, 10.0)
    assert _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5]) == (153, 0, 102)


def test_negative_density_is_no_fog(open_window):
    _scene(open_window)
    with pytest.warns(Warning, match="density"):
        fogvertex(FG_VTX_EXP, [-2.0, 0.0, 0.0, 1.0])
    fogvertex(FG_ON)
    cpack(RED)
    _quad(0, 20, 10.0)
    assert _rgb(lrectread(0, 0, W - 1, H - 1)[5, 5]) == (255, 0, 0)
