"""Lighting (docs/semantics.md §9) checked against the equation.

Every expected colour is computed here, by a small numpy implementation of
the docs/semantics.md §9 equation for one vertex (``_expected``), from the
properties the test itself passed to lmdef; nothing is taken from the
library's lighting module.  Scene: a W x H window, ``mmode(MVIEWING)``,
``ortho(-0.5, W-0.5, -0.5, H-0.5, -100, 100)`` so that eye space is pixel
space (x, y as pixel centres, the eye at the origin looking down -z).
Polygons are flat-shaded, so the whole polygon shows the lighting of its
**last** vertex (docs/semantics.md §3), whose eye position and normal are known.  A
pixel is read back with lrectread (0xAABBGGRR) and compared per component
within +-1 (rounding of clamp(C)*255).
"""
import math

import numpy as np
import pytest

from banks import new_window
from irisgl import *  # noqa: F401,F403
from irisgl import (ALPHA, AMBIENT, ATTENUATION, ATTENUATION2, BACKMATERIAL, DEFLIGHT,
                    DEFLMODEL, DEFMATERIAL, DIFFUSE, EMISSION, FLAT, GLError, LCOLOR,
                    LIGHT0, LMC_AD, LMC_AMBIENT, LMC_COLOR, LMC_DIFFUSE, LMC_EMISSION,
                    LMC_NULL, LMC_SPECULAR, LMNULL, LMODEL, LOCALVIEWER, MATERIAL,
                    MSINGLE, MVIEWING, NAUTO, NNORMALIZE, POSITION, SHININESS, SPECULAR,
                    SPOTDIRECTION, SPOTLIGHT, TWOSIDE, RGBmode, bgnpolygon, c3f, c4f,
                    clear, cpack, endpolygon, multmatrix, gconfig, lmbind, lmcolor, lmdef, loadmatrix,
                    lrectread, mmode, n3f, nmode, ortho, popmatrix, prefsize, pushmatrix,
                    rotate, scale, shademodel, translate, v3f, winopen)

W, H = 16, 16
CX, CY = 8, 8                      # the pixel read back
CLEAR = 0xFF204060                 # a background no lit colour below equals


def _window(w=W, h=H):
    """A w x h RGB window in MVIEWING whose ortho maps pixel centres to
    integers (eye space in pixels, z in -100..100), FLAT, cleared."""
    gid = new_window(w, h)
    mmode(MVIEWING)
    ortho(-0.5, w - 0.5, -0.5, h - 0.5, -100.0, 100.0)
    shademodel(FLAT)
    cpack(CLEAR)
    clear()
    return gid


# ----------------------------------------------------------------------------
# the docs/semantics.md §9 equation, one vertex, written independently of the library

MAT_DEFAULTS = {EMISSION: (0, 0, 0), AMBIENT: (.2, .2, .2), DIFFUSE: (.8, .8, .8),
                SPECULAR: (0, 0, 0), SHININESS: (0,), ALPHA: (1,)}
LIGHT_DEFAULTS = {LCOLOR: (1, 1, 1), AMBIENT: (0, 0, 0), POSITION: (0, 0, 1, 0),
                  SPOTDIRECTION: (0, 0, -1), SPOTLIGHT: (0, 180)}
MODEL_DEFAULTS = {AMBIENT: (.2, .2, .2), LOCALVIEWER: (0,), ATTENUATION: (1, 0),
                  ATTENUATION2: (0,), TWOSIDE: (0,)}


def _props(defaults, **kw):
    """{token: tuple} from defaults overridden by a token-keyed dict."""
    out = {k: tuple(float(x) for x in v) for k, v in defaults.items()}
    for k, v in kw.get("over", {}).items():
        out[k] = tuple(float(x) for x in v)
    return out


def mat(**over):
    return _props(MAT_DEFAULTS, over=over)


def light(**over):
    return _props(LIGHT_DEFAULTS, over=over)


def model(**over):
    return _props(MODEL_DEFAULTS, over=over)


def _plist(d, base):
    """An lmdef property list for the entries of d that differ from base."""
    out = []
    for tok, vals in d.items():
        if tuple(vals) != tuple(float(x) for x in base[tok]):
            out += [tok] + list(vals)
    return out + [LMNULL]


def _unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def _expected(p, n, m, lights, lm):
    """docs/semantics.md §9 for one vertex.  p: eye position (3,), n: unit eye normal,
    m: material props, lights: [(props, eye POSITION (4,), eye unit SPOTDIRECTION)],
    lm: model props.  Returns (r, g, b, a) bytes."""
    p = np.asarray(p, float)
    n = np.asarray(n, float)
    em, am = np.array(m[EMISSION]), np.array(m[AMBIENT])
    dm, sm = np.array(m[DIFFUSE]), np.array(m[SPECULAR])
    sh = m[SHININESS][0]
    c = em + am * np.array(lm[AMBIENT])
    v = _unit(-p) if lm[LOCALVIEWER][0] else np.array([0.0, 0.0, 1.0])
    k0, k1 = lm[ATTENUATION]
    k2 = lm[ATTENUATION2][0]
    for props, pos, sdir in lights:
        pos = np.asarray(pos, float)
        ci, ali = np.array(props[LCOLOR]), np.array(props[AMBIENT])
        if pos[3] == 0:
            li = _unit(pos[:3])
            att = spot = 1.0
        else:
            q = pos[:3] / pos[3] - p
            d = np.linalg.norm(q)
            li = q / d
            att = 1.0 / (k0 + k1 * d + k2 * d * d)
            expo, spread = props[SPOTLIGHT]
            if spread == 180:
                spot = 1.0
            else:
                cosang = -np.dot(li, sdir)
                spot = max(cosang, 0.0) ** expo if cosang >= math.cos(math.radians(spread)) \
                    else 0.0
        term = am * ali + dm * ci * max(np.dot(n, li), 0.0)
        if sh != 0:
            hi = _unit(li + v)
            term = term + sm * ci * max(np.dot(n, hi), 0.0) ** sh
        c = c + att * spot * term
    rgb = [int(math.floor(min(max(x, 0.0), 1.0) * 255 + 0.5)) for x in c]
    return tuple(rgb) + (int(math.floor(min(max(m[ALPHA][0], 0.0), 1.0) * 255 + 0.5)),)


# ----------------------------------------------------------------------------
# drawing and reading

SQUARE = [(1.0, 1.0), (14.0, 1.0), (14.0, 14.0), (1.0, 14.0)]   # counter-clockwise
LAST = (1.0, 14.0)                                                # its last vertex


def _polygon(normal, z=0.0, pts=SQUARE, colour_first=None):
    """A polygon with one normal at every vertex (flat shaded)."""
    bgnpolygon()
    for x, y in pts:
        if colour_first is not None:
            cpack(colour_first)
        n3f(normal)
        v3f((x, y, z))
    endpolygon()


def _rgba(x=CX, y=CY):
    word = int(lrectread(x, y, x, y)[0, 0])
    return (word & 0xFF, (word >> 8) & 0xFF, (word >> 16) & 0xFF, (word >> 24) & 0xFF)


def _close(got, want, tol=1, alpha=True):
    k = 4 if alpha else 3
    assert all(abs(int(a) - int(b)) <= tol for a, b in zip(got[:k], want[:k])), \
        f"got {got}, expected {want}"


def _define(m=None, lights=(), lm=None, mi=1, mo=1):
    """lmdef + lmbind (under the current ModelView) of a material, lights
    LIGHT0.. (indices 1..) and a model; returns the light list for _expected
    assuming an identity ModelView."""
    m = m or mat()
    lm = lm or model()
    lmdef(DEFMATERIAL, mi, 0, _plist(m, MAT_DEFAULTS))
    lmdef(DEFLMODEL, mo, 0, _plist(lm, MODEL_DEFAULTS))
    out = []
    for i, lp in enumerate(lights):
        lmdef(DEFLIGHT, i + 1, 0, _plist(lp, LIGHT_DEFAULTS))
        lmbind(LIGHT0 + i, i + 1)
        out.append((lp, lp[POSITION], _unit(lp[SPOTDIRECTION])))
    lmbind(MATERIAL, mi)
    lmbind(LMODEL, mo)
    return m, out, lm


def _check(m, lights, lm, normal=(0, 0, 1), z=0.0, tol=1):
    _polygon(normal, z)
    want = _expected((LAST[0], LAST[1], z), _unit(normal), m, lights, lm)
    _close(_rgba(), want, tol)
    return want


# ----------------------------------------------------------------------------
# material terms


def test_default_definitions():
    """Defaults of docs/semantics.md §9: 0.2*0.2 ambient + 0.8 diffuse from the
    default light behind the viewer = 0.84 -> 214, alpha 1."""
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    want = _check(m, lights, lm)
    assert want == (214, 214, 214, 255)


def test_emission_only():
    _window()
    m = _props(MAT_DEFAULTS, over={EMISSION: (.3, .1, .5), AMBIENT: (0, 0, 0),
                                   DIFFUSE: (0, 0, 0)})
    m, lights, lm = _define(m, [light()], model())
    want = _check(m, lights, lm)
    assert want[:3] == (77, 26, 128)


def test_material_ambient_times_model_and_light_ambient():
    _window()
    m = _props(MAT_DEFAULTS, over={AMBIENT: (.5, .25, 1.0), DIFFUSE: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={AMBIENT: (.2, .4, .1)})
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (.3, .6, .2)})
    m, lights, lm = _define(m, [lt], lm)
    want = _check(m, lights, lm)
    # Am*(Alm + Ali) = (.25, .25, .3)
    assert want[:3] == (64, 64, 77)


@pytest.mark.parametrize("direction", [(0, 0, 1), (1, 0, 1), (0, -2, 1), (3, 1, 1)])
def test_diffuse_lambert(direction):
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (.9, .6, .3), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: tuple(direction) + (0,)})
    m, lights, lm = _define(m, [lt], model())
    _check(m, lights, lm)


def test_light_behind_surface_gives_no_diffuse():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (.4, .4, .4)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (0, 0, -1, 0)})
    m, lights, lm = _define(m, [lt], model())
    want = _check(m, lights, lm)
    assert want[:3] == (20, 20, 20)         # 0.4 * 0.2 only


def test_lcolor_tints_diffuse_and_specular():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (.5, .5, .5), SPECULAR: (.5, .5, .5),
                                   SHININESS: (10,), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={LCOLOR: (1, .5, 0), POSITION: (1, 1, 2, 0)})
    m, lights, lm = _define(m, [lt], model())
    want = _check(m, lights, lm)
    assert want[2] == 0 and want[0] > want[1] > 0


@pytest.mark.parametrize("shininess", [1.0, 5.0, 30.0, 128.0])
def test_specular_blinn_phong(shininess):
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 0), AMBIENT: (0, 0, 0),
                                   SPECULAR: (1, .8, .6), SHININESS: (shininess,)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (.5, .3, 1, 0)})
    m, lights, lm = _define(m, [lt], model())
    want = _check(m, lights, lm)
    assert want[0] > 0


def test_shininess_zero_disables_specular():
    """SHININESS 0 turns the specular term off (docs/semantics.md §9), even with a
    bright SPECULAR and the highlight exactly on the normal."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 0), AMBIENT: (0, 0, 0),
                                   SPECULAR: (1, 1, 1), SHININESS: (0,)})
    m, lights, lm = _define(m, [light()], model())
    want = _check(m, lights, lm)
    assert want == (0, 0, 0, 255)


@pytest.mark.parametrize("a", [0.0, 0.25, 0.5, 1.0])
def test_material_alpha(a):
    _window()
    m = _props(MAT_DEFAULTS, over={ALPHA: (a,)})
    m, lights, lm = _define(m, [light()], model())
    want = _check(m, lights, lm)
    assert want[3] == int(math.floor(a * 255 + 0.5))


def test_components_clamp_at_one():
    _window()
    m = _props(MAT_DEFAULTS, over={EMISSION: (.9, .1, 0), DIFFUSE: (.9, .1, 0)})
    m, lights, lm = _define(m, [light()], model())
    want = _check(m, lights, lm)
    assert want[0] == 255


# ----------------------------------------------------------------------------
# lights: infinite, local, attenuation, spot, local viewer, several


def test_infinite_light_is_independent_of_position_scale():
    """w = 0: only the direction counts; (0, 0, 5, 0) acts as (0, 0, 1, 0)
    and no attenuation applies even with a strong model ATTENUATION."""
    _window()
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (0, 0, 5, 0)})
    lm = _props(MODEL_DEFAULTS, over={ATTENUATION: (4, 2), ATTENUATION2: (1,)})
    m, lights, lm = _define(mat(), [lt], lm)
    want = _check(m, lights, lm)
    assert want[:3] == (214, 214, 214)


@pytest.mark.parametrize("k0,k1,k2", [(1, 0, 0), (0.5, 0.1, 0), (1, 0, 0.01),
                                      (0.2, 0.05, 0.002)])
def test_local_light_attenuation(k0, k1, k2):
    """w = 1: L from the vertex to the light, Att = 1/(k0 + k1 d + k2 d^2)."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (9, 4, 6, 1), AMBIENT: (0, 0, 0)})
    lm = _props(MODEL_DEFAULTS, over={ATTENUATION: (k0, k1), ATTENUATION2: (k2,)})
    m, lights, lm = _define(m, [lt], lm)
    _check(m, lights, lm)


def test_local_light_position_divided_by_w():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (18, 8, 12, 2)})     # = (9, 4, 6)
    lm = _props(MODEL_DEFAULTS, over={ATTENUATION: (0.5, 0.1)})
    m, lights, lm = _define(m, [lt], lm)
    want = _check(m, lights, lm)
    # the same as the w = 1 light at (9, 4, 6)
    same = _expected((LAST[0], LAST[1], 0), (0, 0, 1), m,
                     [(lt, (9, 4, 6, 1), (0, 0, -1))], lm)
    assert want == same


def test_local_light_differs_from_infinite_light():
    """The same POSITION xyz with w = 1 and w = 0 gives different results."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (1, 14, 3, 1)})
    m, lights, lm = _define(m, [lt], model())
    local = _check(m, lights, lm)
    inf = _expected((LAST[0], LAST[1], 0), (0, 0, 1), m,
                    [(lt, (1, 14, 3, 0), (0, 0, -1))], lm)
    assert local[0] == 255 and inf[0] < 60


def test_light_ambient_is_attenuated_for_local_lights():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 0), AMBIENT: (1, 1, 1)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (1, 14, 4, 1), AMBIENT: (.8, .8, .8)})
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (0, 0, 0), ATTENUATION: (0, 0.5)})
    m, lights, lm = _define(m, [lt], lm)
    want = _check(m, lights, lm)
    assert want[:3] == (102, 102, 102)          # 0.8 / (0.5 * 4)


def test_ambient_pass_with_every_light_bound():
    """Heidmann's ambient pass: an emission-and-ambient material drawn with
    four local lights bound (colour, no ambient) under a local viewer gets
    Em + Am * Alm and nothing from the lights (the lighting loop skips
    them: docs/performance.md); with lmcolor(LMC_DIFFUSE) a colour call
    gives the same material a diffuse colour, and the lights count again."""
    _window()
    m = _props(MAT_DEFAULTS, over={EMISSION: (.1, 0, .05), AMBIENT: (.5, .4, .3),
                                   DIFFUSE: (0, 0, 0), SPECULAR: (0, 0, 0)})
    lts = [_props(LIGHT_DEFAULTS, over={POSITION: (4.0 * k, 10, 30, 1),
                                        LCOLOR: (1, .5, .25)}) for k in range(4)]
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (.4, .4, .4), LOCALVIEWER: (1,)})
    m, lights, lm = _define(m, lts, lm)
    want = _check(m, lights, lm)
    assert want[:3] == (77, 41, 43)             # (.1 + .2, .16, .05 + .12) * 255
    lmcolor(LMC_DIFFUSE)
    c3f((.5, .5, .5))
    _polygon((0, 0, 1))
    lit = dict(m)
    lit[DIFFUSE] = (.5, .5, .5)
    want_lit = _expected((LAST[0], LAST[1], 0.0), (0, 0, 1), lit, lights, lm)
    _close(_rgba(), want_lit)
    assert want_lit[0] > want[0] + 50           # the lights add their diffuse now


SPOT_POS = (1.0, 14.0, 10.0, 1.0)          # 10 above the last vertex


@pytest.mark.parametrize("offset,inside", [(0.0, True), (2.0, True), (3.5, True),
                                           (5.0, False), (9.0, False)])
def test_spotlight_cone(offset, inside):
    """SPOTLIGHT exponent 4, spread 25 degrees, pointing straight down at a
    point ``offset`` away from the lit vertex: outside the cone the spot
    factor is 0 and multiplies the whole light term (its ambient too)."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (.5, .5, .5),
                                   SPECULAR: (.5, .5, .5), SHININESS: (8,)})
    target = np.array([LAST[0] + offset, LAST[1], 0.0])
    sdir = tuple(target - np.array(SPOT_POS[:3]))
    lt = _props(LIGHT_DEFAULTS, over={POSITION: SPOT_POS, SPOTDIRECTION: sdir,
                                      SPOTLIGHT: (4, 25), AMBIENT: (.4, .4, .4)})
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (.1, .1, .1)})
    m, lights, lm = _define(m, [lt], lm)
    want = _check(m, lights, lm)
    angle = math.degrees(math.atan2(offset, 10.0))
    assert (angle <= 25) == inside
    if not inside:
        assert want[:3] == (13, 13, 13)     # 0.5 * 0.1: Em + Am*Alm only
    else:
        assert want[0] > 100


def test_spotlight_ignored_for_infinite_light():
    _window()
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (0, 0, 1, 0), SPOTDIRECTION: (1, 0, 0),
                                      SPOTLIGHT: (10, 5)})
    m, lights, lm = _define(mat(), [lt], model())
    want = _check(m, lights, lm)
    assert want[:3] == (214, 214, 214)


def test_spotlight_spread_180_is_no_spot():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (6, 10, 5, 1), SPOTDIRECTION: (1, 0, 0),
                                      SPOTLIGHT: (50, 180)})
    m, lights, lm = _define(m, [lt], model())
    want = _check(m, lights, lm)
    assert want[0] > 100


@pytest.mark.parametrize("z", [-5.0, -20.0])
def test_local_viewer(z):
    """LOCALVIEWER 1: V is the unit vector from the vertex to the eye at the
    origin; the result differs from the viewer at infinity."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 0), AMBIENT: (0, 0, 0),
                                   SPECULAR: (1, 1, 1), SHININESS: (20,)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (0, 0, 1, 0)})
    lm = _props(MODEL_DEFAULTS, over={LOCALVIEWER: (1,)})
    m, lights, lm = _define(m, [lt], lm)
    want = _check(m, lights, lm, z=z)
    far = _expected((LAST[0], LAST[1], z), (0, 0, 1), m, lights,
                    _props(MODEL_DEFAULTS, over={LOCALVIEWER: (0,)}))
    assert far[0] == 255 and want[0] < 250


def test_eight_lights_sum():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (.5, .5, .5)})
    lts = []
    for i in range(8):
        a = 2 * math.pi * i / 8
        lts.append(_props(LIGHT_DEFAULTS, over={
            LCOLOR: (.06 * (i + 1) / 4, .04, .02 * (8 - i) / 4),
            AMBIENT: (.01, .02 * (i % 2), .0),
            POSITION: (math.cos(a), math.sin(a), 1.5, 0)}))
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (.05, .05, .05)})
    m, lights, lm = _define(m, lts, lm)
    want = _check(m, lights, lm)
    # removing one light changes the result: all eight count
    seven = _expected((LAST[0], LAST[1], 0), (0, 0, 1), m, lights[:7], lm)
    assert seven != want


def test_model_ambient():
    _window()
    m = _props(MAT_DEFAULTS, over={AMBIENT: (1, .5, .25), DIFFUSE: (0, 0, 0)})
    lm = _props(MODEL_DEFAULTS, over={AMBIENT: (.4, .4, .8)})
    m, lights, lm = _define(m, [light()], lm)
    want = _check(m, lights, lm)
    assert want[:3] == (102, 51, 51)


def test_no_light_bound_gives_emission_and_model_ambient():
    _window()
    m = _props(MAT_DEFAULTS, over={EMISSION: (.1, 0, 0)})
    m, lights, lm = _define(m, [], model())
    want = _check(m, lights, lm)
    assert want[:3] == (36, 10, 10)


# ----------------------------------------------------------------------------
# binding


@pytest.mark.parametrize("target", [MATERIAL, LMODEL])
def test_binding_zero_turns_lighting_off(target):
    _window()
    _define(mat(), [light()], model())
    lmbind(target, 0)
    cpack(0xFF00FF00)
    _polygon((0, 0, 1))
    assert _rgba() == (0, 255, 0, 255)
    # and rebinding turns it back on
    lmbind(target, 1)
    _polygon((0, 0, 1))
    _close(_rgba(), (214, 214, 214, 255))


@pytest.mark.parametrize("target", [MATERIAL, LMODEL])
def test_undefined_index_binds_zero(target):
    _window()
    _define(mat(), [light()], model())
    lmbind(target, 42)
    cpack(0xFF0000FF)
    _polygon((0, 0, 1))
    assert _rgba() == (255, 0, 0, 255)


def test_undefined_light_index_unbinds_light():
    _window()
    m = _props(MAT_DEFAULTS, over={EMISSION: (.1, .1, .1)})
    m, lights, lm = _define(m, [light()], model())
    lmbind(LIGHT0, 42)
    want = _check(m, [], lm)
    assert want[:3] == (36, 36, 36)


def test_light_position_taken_at_lmbind():
    """Bound under rotate(450, 'y'), the default light (0, 0, 1, 0) points
    along (sin 45, 0, cos 45) in eye space; popping the matrix afterwards
    does not move it."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lmdef(DEFMATERIAL, 1, 0, _plist(m, MAT_DEFAULTS))
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmdef(DEFLIGHT, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LMODEL, 1)
    pushmatrix()
    rotate(450, 'y')
    lmbind(LIGHT0, 1)
    popmatrix()
    s = math.sin(math.radians(45))
    lights = [(light(), (s, 0, s, 0), (0, 0, -1))]
    want = _check(m, lights, model())
    assert want[0] == 180                       # cos 45 * 255


def test_light_does_not_follow_later_matrix_changes():
    """A local light bound under the identity stays at its eye position
    when the ModelView changes before drawing."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (8, 8, 6, 1)})
    lm = _props(MODEL_DEFAULTS, over={ATTENUATION: (0, 0.1)})
    m, lights, lm = _define(m, [lt], lm)
    translate(0.0, 0.0, -4.0)                   # object z = 4 -> eye z = 0
    _polygon((0, 0, 1), z=4.0)
    want = _expected((LAST[0], LAST[1], 0.0), (0, 0, 1), m, lights, lm)
    _close(_rgba(), want)
    # had the light moved with the translation it would be elsewhere
    moved = _expected((LAST[0], LAST[1], 0.0), (0, 0, 1), m,
                      [(lt, (8, 8, 2, 1), (0, 0, -1))], lm)
    assert abs(moved[0] - want[0]) > 5


def test_rebinding_retransforms_position():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    m, lights, lm = _define(m, [light()], model())
    pushmatrix()
    rotate(600, 'x')
    lmbind(LIGHT0, 1)
    popmatrix()
    _polygon((0, 0, 1))
    _close(_rgba(), (128, 128, 128, 255))        # cos 60
    lmbind(LIGHT0, 1)                            # identity now
    _polygon((0, 0, 1))
    _close(_rgba(), (255, 255, 255, 255))


def test_spot_direction_transformed_at_lmbind():
    """SPOTDIRECTION goes through the ModelView at lmbind like a normal:
    bound under a 180-degree rotation about y, (0, 0, 1) points down -z."""
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (-1, 14, -10, 1), SPOTDIRECTION: (0, 0, 1),
                                      SPOTLIGHT: (1, 30)})
    m, _, lm = _define(m, [], model())
    lmdef(DEFLIGHT, 1, 0, _plist(lt, LIGHT_DEFAULTS))
    pushmatrix()
    rotate(1800, 'y')                           # (x, y, z) -> (-x, y, -z)
    lmbind(LIGHT0, 1)
    popmatrix()
    lights = [(lt, (1, 14, 10, 1), (0, 0, -1))]
    want = _check(m, lights, lm)
    assert want[0] > 200


def test_one_definition_one_light_target():
    """A light definition is bound to one target at a time: binding it to
    LIGHT1 takes it off LIGHT0 (docs/semantics.md §9), so it counts once."""
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    lmbind(LIGHT0 + 1, 1)
    want = _check(m, lights, lm)
    assert want[:3] == (214, 214, 214)          # twice would be 0.04 + 1.6 -> 255


def test_no_lighting_in_msingle():
    """Lighting needs MVIEWING (docs/semantics.md §9; docs/decisions.md): in
    MSINGLE the current colour is drawn."""
    _window()
    mmode(MSINGLE)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -100.0, 100.0)
    _define(mat(), [light()], model())
    cpack(0xFF00FF00)
    _polygon((0, 0, 1))
    assert _rgba() == (0, 255, 0, 255)


def test_lmdef_np_counts_floats_including_lmnull():
    """np = 5 reads DIFFUSE r g b LMNULL and nothing after it."""
    _window()
    lmdef(DEFMATERIAL, 1, 5, [DIFFUSE, 1, 0, 0, LMNULL, 999, 1])
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 0, 0)})
    lmdef(DEFLIGHT, 1, 0, [LMNULL])
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)
    want = _check(m, [(light(), (0, 0, 1, 0), (0, 0, -1))], model())
    assert want[:3] == (255, 10, 10)


def test_lmdef_is_incremental():
    _window()
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, .5, 0, 0, AMBIENT, 0, 0, 0, LMNULL])
    lmdef(DEFMATERIAL, 1, 0, [EMISSION, 0, 0, .2, LMNULL])       # diffuse kept
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (.5, 0, 0), AMBIENT: (0, 0, 0),
                                   EMISSION: (0, 0, .2)})
    lmdef(DEFLIGHT, 1, 0, [LMNULL])
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)
    want = _check(m, [(light(), (0, 0, 1, 0), (0, 0, -1))], model())
    assert want[:3] == (128, 0, 51)


def test_lmdef_of_bound_definition_takes_effect_immediately():
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    _check(m, lights, lm)
    lmdef(DEFLIGHT, 1, 0, [LCOLOR, 0, 1, 0, LMNULL])
    lmdef(DEFMATERIAL, 1, 0, [AMBIENT, 0, 0, 0, LMNULL])
    lt = _props(LIGHT_DEFAULTS, over={LCOLOR: (0, 1, 0)})
    m2 = _props(MAT_DEFAULTS, over={AMBIENT: (0, 0, 0)})
    want = _check(m2, [(lt, (0, 0, 1, 0), (0, 0, -1))], lm)
    assert want[:3] == (0, 204, 0)


@pytest.mark.parametrize("reset", [None, [LMNULL]])
def test_lmdef_reset_to_defaults(reset):
    _window()
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, .1, .9, .3, EMISSION, .5, 0, 0, LMNULL])
    lmdef(DEFLIGHT, 1, 0, [LCOLOR, 0, 0, 1, LMNULL])
    lmdef(DEFLMODEL, 1, 0, [AMBIENT, 1, 1, 1, LMNULL])
    lmdef(DEFMATERIAL, 1, 0, reset)
    lmdef(DEFLIGHT, 1, 0, reset)
    lmdef(DEFLMODEL, 1, 0, reset)
    lmbind(MATERIAL, 1)
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)
    _polygon((0, 0, 1))
    _close(_rgba(), (214, 214, 214, 255))


# ----------------------------------------------------------------------------
# lmcolor


def test_lmc_color_colour_after_normal_is_not_lit():
    _window()
    _define(mat(), [light()], model())
    bgnpolygon()
    for x, y in SQUARE:
        n3f((0, 0, 1))
        cpack(0xFF10E0A0)                       # a colour after the normal
        v3f((x, y, 0))
    endpolygon()
    assert _rgba() == (0xA0, 0xE0, 0x10, 0xFF)


def test_lmc_color_normal_after_colour_is_lit():
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    bgnpolygon()
    for x, y in SQUARE:
        cpack(0xFF10E0A0)
        n3f((0, 0, 1))
        v3f((x, y, 0))
    endpolygon()
    _close(_rgba(), (214, 214, 214, 255))


def _lmc_material(mode, rgba):
    """The material after lmcolor(mode) redirected colour rgba (0..1)."""
    base = {EMISSION: (.05, .05, .05), AMBIENT: (.3, .3, .3), DIFFUSE: (.4, .4, .4),
            SPECULAR: (.2, .2, .2), SHININESS: (6,)}
    m = _props(MAT_DEFAULTS, over=base)
    over = dict(m)
    target = {LMC_EMISSION: [EMISSION], LMC_AMBIENT: [AMBIENT], LMC_DIFFUSE: [DIFFUSE],
              LMC_SPECULAR: [SPECULAR], LMC_AD: [AMBIENT, DIFFUSE], LMC_NULL: [],
              LMC_COLOR: []}[mode]
    for t in target:
        over[t] = tuple(rgba[:3])
    if mode in (LMC_DIFFUSE, LMC_AD):
        over[ALPHA] = (rgba[3],)
    return m, over


@pytest.mark.parametrize("mode", [LMC_EMISSION, LMC_AMBIENT, LMC_DIFFUSE, LMC_SPECULAR,
                                  LMC_AD, LMC_NULL])
def test_lmcolor_redirects_colour_calls(mode):
    _window()
    rgba = (0.8, 0.4, 0.2, 0.6)
    m, redirected = _lmc_material(mode, rgba)
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (.3, .2, 1, 0), AMBIENT: (.2, .2, .2)})
    m, lights, lm = _define(m, [lt], model())
    lmcolor(mode)
    c4f(rgba)
    _polygon((0, 0, 1))
    want = _expected((LAST[0], LAST[1], 0), (0, 0, 1), redirected, lights, lm)
    _close(_rgba(), want)
    unchanged = _expected((LAST[0], LAST[1], 0), (0, 0, 1), m, lights, lm)
    if mode != LMC_NULL:
        assert want != unchanged                # the test can tell


def test_material_bind_discards_lmcolor_changes():
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    lmcolor(LMC_DIFFUSE)
    c3f((1.0, 0.0, 0.0))
    _polygon((0, 0, 1))
    _close(_rgba(), (255, 10, 10, 255))         # Dm = (1, 0, 0): 0.04 + 1 / 0.04
    lmbind(MATERIAL, 1)
    _polygon((0, 0, 1))
    _close(_rgba(), (214, 214, 214, 255))


@pytest.mark.parametrize("then", [LMC_COLOR, LMC_AMBIENT])
def test_lmcolor_change_lasts_until_next_material_bind(then):
    """docs/semantics.md §9: LMC_DIFFUSE colour calls set the bound material's
    diffuse; the change is lost only at the next material bind, so it stays
    after lmcolor switches to another mode."""
    _window()
    m, lights, lm = _define(mat(), [light()], model())
    lmcolor(LMC_DIFFUSE)
    c3f((1.0, 0.0, 0.0))                        # material diffuse := red
    lmcolor(then)
    over = {DIFFUSE: (1, 0, 0)}
    if then == LMC_AMBIENT:
        c3f((0.0, 0.0, 1.0))                    # material ambient := blue
        over[AMBIENT] = (0, 0, 1)
    _polygon((0, 0, 1))
    want = _expected((LAST[0], LAST[1], 0), (0, 0, 1), _props(MAT_DEFAULTS, over=over),
                     lights, lm)
    assert want[:3] == ((255, 10, 10) if then == LMC_COLOR else (255, 0, 51))
    _close(_rgba(), want)


def test_lmcolor_without_lighting_sets_current_colour():
    _window()
    _define(mat(), [light()], model())
    lmcolor(LMC_DIFFUSE)
    lmbind(MATERIAL, 0)
    cpack(0xFF3366CC)
    _polygon((0, 0, 1))
    assert _rgba() == (0xCC, 0x66, 0x33, 0xFF)


# ----------------------------------------------------------------------------
# normals


def _diffuse_setup(position=(0, 0, 1, 0)):
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 1, 1), AMBIENT: (0, 0, 0)})
    lt = _props(LIGHT_DEFAULTS, over={POSITION: position})
    return _define(m, [lt], model())


@pytest.mark.parametrize("mode", [NAUTO, NNORMALIZE])
def test_uniform_scale_renormalises_in_both_modes(mode):
    """scale(2, 2, 2): the inverse transpose halves a unit normal; the matrix
    is not orthonormal, so NAUTO renormalises as NNORMALIZE does."""
    _window()
    m, lights, lm = _diffuse_setup()
    nmode(mode)
    scale(2.0, 2.0, 2.0)
    bgnpolygon()
    for x, y in SQUARE:
        n3f((0, 0, 1))
        v3f((x / 2, y / 2, 0))
    endpolygon()
    _close(_rgba(), (255, 255, 255, 255))


@pytest.mark.parametrize("mode,expected", [(NAUTO, 128), (NNORMALIZE, 255)])
def test_non_unit_normal_under_rigid_matrix(mode, expected):
    """Identity ModelView (orthonormal): NAUTO keeps a normal of length 0.5
    as it is; NNORMALIZE makes it unit."""
    _window()
    m, lights, lm = _diffuse_setup()
    nmode(mode)
    _polygon((0, 0, 0.5))
    _close(_rgba(), (expected,) * 3 + (255,))


def test_nonuniform_scale_uses_inverse_transpose():
    """scale(1, 2, 1) with object normal (0, 1, 1)/sqrt 2: the eye normal is
    normalize((0, 1, 1) . diag(1, 1/2, 1)) = (0, 1, 2)/sqrt 5, so with a
    light along +z N.L = 2/sqrt 5 (0.894), not 1/sqrt 5 (the matrix itself)
    nor 1/sqrt 2 (no transform)."""
    _window()
    m, lights, lm = _diffuse_setup()
    scale(1.0, 2.0, 1.0)
    nobj = _unit((0, 1, 1))
    bgnpolygon()
    for x, y in SQUARE:
        n3f(tuple(nobj))
        v3f((x, y / 2, 0))
    endpolygon()
    neye = _unit(nobj * np.array([1, 0.5, 1]))
    want = _expected((LAST[0], LAST[1], 0), neye, m, lights, lm)
    assert want[0] == 228
    _close(_rgba(), want)


def test_rotation_rotates_normal():
    """rotate(300, 'y'): object normal (0, 0, 1) becomes row 2 of R_y,
    (sin 30, 0, cos 30), in eye space; a light along that direction gives
    full diffuse (rotating the other way would give cos 60)."""
    _window()
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    m, lights, lm = _diffuse_setup(position=(s, 0, c, 0))
    rotate(300, 'y')
    bgnpolygon()
    for x, y in SQUARE:
        n3f((0, 0, 1))
        v3f((x, y, 0))
    endpolygon()
    # eye x = 0.87 x .. 12.1 x: the pixel read is still inside
    _close(_rgba(), (255, 255, 255, 255))


@pytest.mark.parametrize("mode", [NAUTO, NNORMALIZE])
def test_shear_uses_inverse_transpose(mode):
    """A shear z' = z - x (rows [1 0 -1; 0 1 0; 0 0 1]) maps the object plane
    z = x, normal (-1, 0, 1)/sqrt 2, to the eye plane z = 0.  The inverse
    transpose gives the eye normal (0, 0, 1)/sqrt 2, renormalised (the matrix
    is not orthonormal): full diffuse from a light along +z.  The inverse
    without the transpose would give (-1, 0, 0): no diffuse at all."""
    _window()
    m, lights, lm = _diffuse_setup()
    nmode(mode)
    multmatrix([[1, 0, -1, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    bgnpolygon()
    for x, y in SQUARE:
        n3f(tuple(_unit((-1, 0, 1))))
        v3f((x, y, x))
    endpolygon()
    _close(_rgba(), (255, 255, 255, 255))


# ----------------------------------------------------------------------------
# two-sided lighting

CLOCKWISE = list(reversed(SQUARE))                 # ends at (1, 1)


def _cw_polygon(normal):
    bgnpolygon()
    for x, y in CLOCKWISE:
        n3f(normal)
        v3f((x, y, 0))
    endpolygon()


def test_twoside_back_face_uses_negated_normal_and_backmaterial():
    """A clockwise polygon whose normal points away (0, 0, -1), lit from
    +z: with TWOSIDE its visible back is lit with -N and BACKMATERIAL."""
    _window()
    front = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 0, 0), AMBIENT: (0, 0, 0)})
    back = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, .8), AMBIENT: (.5, .5, .5)})
    lm = _props(MODEL_DEFAULTS, over={TWOSIDE: (1,)})
    front, lights, lm = _define(front, [light()], lm)
    lmdef(DEFMATERIAL, 2, 0, _plist(back, MAT_DEFAULTS))
    lmbind(BACKMATERIAL, 2)
    _cw_polygon((0, 0, -1))
    want = _expected((1, 1, 0), (0, 0, 1), back, lights, lm)
    assert want[:3] == (26, 26, 230)
    _close(_rgba(), want)


def test_twoside_without_backmaterial_uses_material():
    _window()
    front = _props(MAT_DEFAULTS, over={DIFFUSE: (1, .5, 0), AMBIENT: (0, 0, 0)})
    lm = _props(MODEL_DEFAULTS, over={TWOSIDE: (1,)})
    front, lights, lm = _define(front, [light()], lm)
    _cw_polygon((0, 0, -1))
    _close(_rgba(), (255, 128, 0, 255))


def test_twoside_front_face_uses_front_material():
    _window()
    front = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 0, 0), AMBIENT: (0, 0, 0)})
    back = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 1), AMBIENT: (0, 0, 0)})
    lm = _props(MODEL_DEFAULTS, over={TWOSIDE: (1,)})
    front, lights, lm = _define(front, [light()], lm)
    lmdef(DEFMATERIAL, 2, 0, _plist(back, MAT_DEFAULTS))
    lmbind(BACKMATERIAL, 2)
    _polygon((0, 0, 1))
    _close(_rgba(), (255, 0, 0, 255))


def test_without_twoside_back_face_uses_front_material_and_n():
    _window()
    front = _props(MAT_DEFAULTS, over={DIFFUSE: (1, 0, 0), AMBIENT: (.5, .5, .5)})
    back = _props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, 1)})
    front, lights, lm = _define(front, [light()], model())
    lmdef(DEFMATERIAL, 2, 0, _plist(back, MAT_DEFAULTS))
    lmbind(BACKMATERIAL, 2)
    _cw_polygon((0, 0, -1))
    _close(_rgba(), (26, 26, 26, 255))              # N faces away: ambient only


# ----------------------------------------------------------------------------
# degenerate matrices, errors


def test_singular_matrix_does_not_crash():
    """scale(1, 0, 1) with lighting on: no exception, no non-finite colour.
    The polygon lies in the object xz plane and a 90-degree rotation about x
    (applied after the scale) stands it up in the screen plane, so it has
    area and must be drawn (its input is finite: nothing to drop)."""
    import warnings
    _window()
    _define(mat(), [light()], model())
    rotate(900, 'x')
    scale(1.0, 0.0, 1.0)                    # v . S . R: scale first, then rotate
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bgnpolygon()
        for x, y in SQUARE:
            n3f((0, 1, 0))
            v3f((x, 5.0, -y))               # eye (x, y, 0)
        endpolygon()
        got = _rgba()
    assert got != ((CLEAR & 0xFF), (CLEAR >> 8) & 0xFF, (CLEAR >> 16) & 0xFF, CLEAR >> 24)
    assert got[3] == 255
    # a flat polygon in the xy plane collapses to a line: still no crash
    loadmatrix(np.diag([1.0, 0.0, 1.0, 1.0]))
    _polygon((0, 0, 1))
    _rgba()


def test_lmdef_index_zero_is_an_error():
    _window()
    for d in (DEFMATERIAL, DEFLIGHT, DEFLMODEL):
        with pytest.raises(GLError, match="^lmdef"):
            lmdef(d, 0, 0, [LMNULL])


@pytest.mark.parametrize("deftype,props", [
    (DEFMATERIAL, [999, 1, LMNULL]),
    (DEFMATERIAL, [LCOLOR, 1, 1, 1, LMNULL]),          # a light property
    (DEFLIGHT, [DIFFUSE, 1, 1, 1, LMNULL]),            # a material property
    (DEFLMODEL, [POSITION, 0, 0, 1, 0, LMNULL]),
    (DEFLIGHT, [LCOLOR, 1, 1, 1, 77, LMNULL]),
])
def test_unknown_property_token_is_an_error(deftype, props):
    _window()
    with pytest.raises(GLError, match="^lmdef"):
        lmdef(deftype, 1, 0, props)


def test_failed_lmdef_changes_nothing():
    _window()
    m = _props(MAT_DEFAULTS, over={DIFFUSE: (.5, .5, 0), AMBIENT: (0, 0, 0)})
    m, lights, lm = _define(m, [light()], model())
    with pytest.raises(GLError):
        lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0, 0, 1, 999, 0, LMNULL])
    with pytest.raises(GLError):
        lmdef(DEFMATERIAL, 0, 0, [DIFFUSE, 0, 0, 1, LMNULL])
    want = _check(m, lights, lm)
    assert want[:3] == (128, 128, 0)


def test_lmbind_unknown_target_is_an_error():
    _window()
    with pytest.raises(GLError, match="^lmbind"):
        lmbind(1234, 1)


# ----------------------------------------------------------------------------
# materials change between primitives without a flush (batch.mats)

def _count_batches(monkeypatch):
    from vgx_emulator import scan
    calls = []
    real = scan.scan_batch
    monkeypatch.setattr(scan, "scan_batch", lambda *a, **k: (calls.append(1), real(*a, **k)))
    return calls


def test_materials_bound_between_polygons_light_each_polygon(monkeypatch):
    """lmbind(MATERIAL, i) between primitives: each polygon is lit with the
    material bound when its vertices were sent (shininess 0 and not, alpha,
    an lmcolor override), and the three polygons are drawn as one batch."""
    calls = _count_batches(monkeypatch)
    _window(48, 16)
    lt = _props(LIGHT_DEFAULTS, over={POSITION: (0.3, 0.4, 1.0, 0.0)})
    mats = [_props(MAT_DEFAULTS, over=o) for o in (
        {DIFFUSE: (1, 0, 0), ALPHA: (.25,)},
        {SPECULAR: (1, 1, 1), SHININESS: (20,), DIFFUSE: (0, .5, 0)},
        {ALPHA: (.5,), AMBIENT: (0, 0, 1)})]
    for i, m in enumerate(mats):
        lmdef(DEFMATERIAL, i + 1, 0, _plist(m, MAT_DEFAULTS))
    _, lights, lm = _define(mats[0], [lt], model())
    lmcolor(LMC_DIFFUSE)
    wants = []
    for i, m in enumerate(mats):
        lmbind(MATERIAL, i + 1)
        pts = [(x + 16 * i, y) for x, y in SQUARE]
        over = m
        if i == 2:                              # diffuse from the colour call
            c3f((0.0, 0.0, 1.0))
            over = {**m, DIFFUSE: (0.0, 0.0, 1.0), ALPHA: (1.0,)}   # c3f: alpha 1
        _polygon((0, 0, 1), pts=pts)
        wants.append(_expected((pts[-1][0], pts[-1][1], 0), (0, 0, 1), over, lights, lm))
    assert len(set(wants)) == 3                 # the test can tell the materials apart
    gflush()
    assert len(calls) == 1
    for i, want in enumerate(wants):
        _close(_rgba(CX + 16 * i, CY), want)


def _lmcolor_polygons(flush_between):
    """Five polygons, each under another lmcolor mode with a colour sent
    before its vertices (LMC_AD, LMC_DIFFUSE, LMC_COLOR with the normal last,
    LMC_COLOR with the colour last, LMC_EMISSION), the mode set between
    primitives; the pixels of each."""
    _window(80, 16)
    mat = _props(MAT_DEFAULTS, over={DIFFUSE: (0.3, 0.3, 0.3), AMBIENT: (0.1, 0.1, 0.1)})
    lmdef(DEFMATERIAL, 1, 0, _plist(mat, MAT_DEFAULTS))
    _define(mat, [_props(LIGHT_DEFAULTS, over={POSITION: (0.3, 0.4, 1.0, 0.0)})], model())
    lmbind(MATERIAL, 1)
    for i, (mode, rgb, colour_last) in enumerate((
            (LMC_AD, (0.5, 0.2, 0.1), False), (LMC_DIFFUSE, (0.1, 0.4, 0.3), False),
            (LMC_COLOR, (0.2, 0.3, 0.5), False), (LMC_COLOR, (0.6, 0.4, 0.2), True),
            (LMC_EMISSION, (0.3, 0.0, 0.4), False))):
        lmcolor(mode)
        c3f(rgb)
        bgnpolygon()
        for x, y in SQUARE:
            if colour_last:
                n3f((0, 0, 1))
                c3f(rgb)
            else:
                n3f((0, 0, 1))
            v3f((x + 16 * i, y, 0))
        endpolygon()
        if flush_between:
            gflush()
    return [_rgba(CX + 16 * i, CY) for i in range(5)]


def test_lmcolor_between_polygons_needs_no_flush(monkeypatch):
    """lmcolor(3G) between primitives does not end the batch: each vertex is
    lit under the mode in force when it was sent (its material entry holds
    the mode), so one batch draws what a flush after every polygon draws,
    and each mode's pixel is what its redirection gives."""
    calls = _count_batches(monkeypatch)
    one = _lmcolor_polygons(False)
    assert len(calls) == 1
    calls.clear()
    flushed = _lmcolor_polygons(True)
    assert len(calls) == 5
    assert one == flushed
    # LMC_COLOR with the normal last lights with the material, which keeps
    # the LMC_DIFFUSE colour until the next bind (docs/semantics.md §9)
    assert one[2] == one[1] and len(set(one)) == 4
    assert one[3] == (153, 102, 51, 255)            # LMC_COLOR, colour last: unlit


def test_backmaterial_bound_between_polygons():
    """TWOSIDE: two back-facing polygons with different BACKMATERIALs bound
    between them, in one batch, each lit with its own back material."""
    _window(32, 16)
    lm = _props(MODEL_DEFAULTS, over={TWOSIDE: (1,)})
    backs = [_props(MAT_DEFAULTS, over={DIFFUSE: (0, 0, .8)}),
             _props(MAT_DEFAULTS, over={DIFFUSE: (.8, .8, 0)})]
    _, lights, lm = _define(mat(), [light()], lm)
    wants = []
    for i, b in enumerate(backs):
        lmdef(DEFMATERIAL, i + 2, 0, _plist(b, MAT_DEFAULTS))
        lmbind(BACKMATERIAL, i + 2)
        bgnpolygon()
        for x, y in reversed(SQUARE):           # clockwise: the back is seen
            n3f((0, 0, -1))
            v3f((x + 16 * i, y, 0))
        endpolygon()
        wants.append(_expected((1, 1, 0), (0, 0, 1), b, lights, lm))
    assert wants[0] != wants[1]
    for i, want in enumerate(wants):
        _close(_rgba(CX + 16 * i, CY), want)


def test_material_zero_between_polygons_turns_lighting_off(monkeypatch):
    """lmbind(MATERIAL, 0) ends lighting: the polygon after it keeps its
    colour while the one before is lit (a flush separates them)."""
    calls = _count_batches(monkeypatch)
    _window(32, 16)
    m, lights, lm = _define(mat(), [light()], model())
    _polygon((0, 0, 1))
    lmbind(MATERIAL, 0)
    cpack(0xFF0000FF)
    _polygon((0, 0, 1), pts=[(x + 16, y) for x, y in SQUARE])
    _close(_rgba(), _expected((LAST[0], LAST[1], 0), (0, 0, 1), m, lights, lm))
    _close(_rgba(CX + 16, CY), (255, 0, 0, 255))
    assert len(calls) == 2


def test_colour_map_lighting_per_material_in_one_batch(monkeypatch):
    """Colour-map lighting (docs/semantics.md §9): index = amb + (dif - amb) * D +
    (spe - dif) * S.  Lit head-on (D = 1) with SHININESS 0 (S = 0) each
    polygon takes its own material's diffuse index, with the materials bound
    between polygons of one batch."""
    from irisgl import COLORINDEXES, cmode
    calls = _count_batches(monkeypatch)
    prefsize(32, 16)
    winopen("cmap lighting")
    cmode()
    gconfig()
    mmode(MVIEWING)
    ortho(-0.5, 31.5, -0.5, 15.5, -100.0, 100.0)
    shademodel(FLAT)
    indexes = [(16.0, 100.0, 200.0), (300.0, 700.0, 900.0)]
    for i, (a, d, s) in enumerate(indexes):
        lmdef(DEFMATERIAL, i + 1, 0, [COLORINDEXES, a, d, s, LMNULL])
    lmdef(DEFLIGHT, 1, 0, [POSITION, 0.0, 0.0, 1.0, 0.0, LMNULL])
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)
    for i in range(2):
        lmbind(MATERIAL, i + 1)
        _polygon((0, 0, 1), pts=[(x + 16 * i, y) for x, y in SQUARE])
    got = [int(lrectread(CX + 16 * i, CY, CX + 16 * i, CY)[0, 0]) & 0xFFF for i in range(2)]
    assert got == [100, 700]
    assert len(calls) == 1


def test_specular_power_matches_pow():
    """shade._power: integral exponents by repeated squaring agree with pow
    to a few ulps; other exponents are pow itself."""
    from vgx_emulator.geometry.shade import _power
    for x in np.linspace(0.0, 1.0, 101):
        for e in (1.0, 2.0, 7.0, 30.0, 128.0, 0.5, 12.7, 129.0):
            assert _power(x, e) == pytest.approx(x ** e, rel=1e-13, abs=1e-300)
