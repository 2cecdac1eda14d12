"""Hostile values (docs/stability.md): NaN and infinity in vertices, normals
and matrices drop only what they touch, and singular matrices with lighting
on give defined colours."""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from irisgl import GLError
from vgx_emulator import VGXWarning
from banks import colour
from stability_helpers import (PW, PH, PS, LW, LH, pixel_window, polygon, top_view)


# 8. NaN and infinity in vertices, normals, matrices
nan, inf = math.nan, math.inf
REF_SQUARE = [(40.0, 30.0, 0.0), (60.0, 30.0, 0.0), (60.0, 44.0, 0.0), (40.0, 44.0, 0.0)]
BAD_TRI = [(5.0, 5.0, 0.0), (30.0, 5.0, 0.0), (5.0, 25.0, 0.0)]


def lit_window():
    """Lighting on in MVIEWING (default material, light and model); the
    ortho projection maps object (x, y) to window (x, y)."""
    pixel_window(LW, LH)
    mmode(MVIEWING)
    ortho(-0.5, LW - 0.5, -0.5, LH - 0.5, -10, 10)
    for deftype in (DEFMATERIAL, DEFLIGHT, DEFLMODEL):
        lmdef(deftype, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LMODEL, 1)
    lmbind(LIGHT0, 1)
    n3f((0.0, 0.0, 1.0))


def _matrix_with(value, where=(1, 1)):
    m = [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]
    m[where[0]][where[1]] = value
    return m


def _drop(draw_bad):
    """Draw the bad primitive under pushmatrix (where it has matrices)."""
    def run():
        pushmatrix()
        draw_bad()
        popmatrix()
    return run


DROPPED = {      # drawn with a VGXWarning; only the bad primitive goes
    "v4f w = nan": lambda: polygon([BAD_TRI[0] + (nan,)] + [v + (1.0,) for v in BAD_TRI[1:]], v4f),
    "v4f w = inf": lambda: polygon([BAD_TRI[0] + (inf,)] + [v + (1.0,) for v in BAD_TRI[1:]], v4f),
    "v4f (0, 0, 0, 0)": lambda: polygon([(0.0, 0.0, 0.0, 0.0)] + [v + (1.0,) for v in BAD_TRI[1:]], v4f),
    "n3f inf, lighting on": lambda: (n3f((inf, 0.0, 1.0)), polygon(BAD_TRI), n3f((0.0, 0.0, 1.0))),
    "loadmatrix nan": _drop(lambda: (loadmatrix(_matrix_with(nan)), polygon(BAD_TRI))),
    "multmatrix -inf, lighting on": _drop(lambda: (multmatrix(_matrix_with(-inf, (3, 0))),
                                                   polygon(BAD_TRI))),
    "rot(nan)": _drop(lambda: (rot(nan, "x"), polygon(BAD_TRI))),
    "rotate(inf) (raised ValueError before the fix)": _drop(lambda: (rotate(inf, "z"),
                                                                     polygon(BAD_TRI))),
    "translate(inf)": _drop(lambda: (translate(inf, 0, 0), polygon(BAD_TRI))),
    "scale(nan)": _drop(lambda: (scale(1.0, nan, 1.0), polygon(BAD_TRI))),
    "polarview(inf)": _drop(lambda: (polarview(1.0, inf, 0, 0), polygon(BAD_TRI))),
    "rectf(nan)": lambda: rectf(nan, 5.0, 20.0, 20.0),
}


@pytest.mark.parametrize("name", sorted(DROPPED))
def test_non_finite_input_drops_only_its_primitive_with_lighting_on(name):
    """The rest of the scene is intact: the reference square drawn after
    the bad primitive has its exact pixels and lit colour, and nothing else
    is drawn.  (test_clip.py::test_non_finite_input_drops_the_primitive does
    vertices, normals, colours, lines and points without lighting.)"""
    lit_window()
    with pytest.warns(VGXWarning, match="dropped"):
        DROPPED[name]()
        polygon(REF_SQUARE)
        img = colour()
    want = np.zeros((LH, LW), bool)
    want[30:44, 40:60] = True
    assert ((img != 0) == want).all()
    expected = round((0.2 * 0.2 + 0.8) * 255)            # ambient + N.L = 1 diffuse
    assert set(np.unique(img[want] & 0xFF).tolist()) == {expected}


def _projection_nan():
    mmode(MPROJECTION)
    loadmatrix(_matrix_with(nan, (2, 2)))


REFUSED = {      # GLError, nothing changed
    "lmdef POSITION nan": lambda: lmdef(DEFLIGHT, 1, 0, [POSITION, nan, 0, 1, 0, LMNULL]),
    "lmdef DIFFUSE inf": lambda: lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, inf, 0, 0, LMNULL]),
    "perspective aspect nan": lambda: perspective(450, nan, 1.0, 10.0),
    "perspective far inf": lambda: perspective(450, 1.0, 1.0, inf),
    "ortho nan": lambda: ortho(nan, 1, 0, 1, -1, 1),
    "window nan": lambda: window(-1, 1, -1, nan, 1, 10),
    "lookat nan": lambda: lookat(0, 0, nan, 0, 0, 0, 0),
    "viewport nan": lambda: viewport(0, nan, 0, 10),
    "lsetdepth inf": lambda: lsetdepth(0, inf),
    "czclear z nan": lambda: czclear(0, nan),
    "cpack nan": lambda: cpack(nan),
}


@pytest.mark.parametrize("name", sorted(REFUSED))
def test_non_finite_arguments_of_validated_calls_raise_and_change_nothing(name):
    lit_window()
    with pytest.raises(GLError):
        REFUSED[name]()
    polygon(REF_SQUARE)
    img = colour()
    want = np.zeros((LH, LW), bool)
    want[30:44, 40:60] = True
    assert ((img != 0) == want).all()
    assert set(np.unique(img[want] & 0xFF).tolist()) == {round((0.04 + 0.8) * 255)}


def test_nan_projection_drops_everything_until_replaced():
    """A NaN in the projection matrix drops every primitive drawn under it
    (with a warning); a new projection brings the scene back exactly."""
    lit_window()
    _projection_nan()
    mmode(MVIEWING)
    with pytest.warns(VGXWarning):
        polygon(REF_SQUARE)
        assert not (colour() != 0).any()
    ortho(-0.5, LW - 0.5, -0.5, LH - 0.5, -10, 10)
    polygon(REF_SQUARE)
    assert (colour() != 0).sum() == 20 * 14


# 9. singular matrices with lighting on
def lighting_colour(n_dot_l):
    """Default material and model, one white light: 0.2 * 0.2 ambient plus
    0.8 * max(N.L, 0) diffuse, 0..255 rounded (docs/semantics.md §9)."""
    return round((0.04 + 0.8 * max(n_dot_l, 0.0)) * 255)


QUADS = [  # (x0, x1, z0, z1, y, normal) in object space
    (-7, -4, -6, 6, 0.5, (0.0, 1.0, 0.0)),
    (-3, 0, -6, 6, 1.5, (0.0, -1.0, 0.0)),
    (1, 3, -6, 6, 2.5, (1.0, 0.0, 0.0)),
    (4, 7, -6, 6, 3.5, (0.6, 0.8, 0.0)),
]


def test_scale_1_0_1_with_lighting_gives_defined_colours():
    """Tessman's shadow scale(1, 0, 1) under lighting: the normal matrix is
    singular; its cofactor matrix keeps the y component of a normal and
    zeroes x and z (docs/decisions.md).  Seen from above with the light at
    (0, 0.6, 0.8) in eye space: a normal with y > 0 lights like the up
    normal (N.L = 0.8), y < 0 and y = 0 get the ambient term only; no NaN,
    no other colour."""
    pixel_window(PW, PH)
    mmode(MVIEWING)
    ortho(-PS, PS, -PS, PS, 1.0, 100.0)
    for deftype in (DEFMATERIAL, DEFLMODEL):
        lmdef(deftype, 1, 0, [LMNULL])
    lmdef(DEFLIGHT, 1, 0, [POSITION, 0.0, 0.6, 0.8, 0.0, LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LMODEL, 1)
    lmbind(LIGHT0, 1)                    # bound under the identity: eye space
    loadmatrix(top_view())
    scale(1.0, 0.0, 1.0)
    for x0, x1, z0, z1, y, n in QUADS:
        n3f(n)
        polygon([(x0, y, z1), (x1, y, z1), (x1, y, z0), (x0, y, z0)])
    img = colour()
    lit, dark = lighting_colour(0.8), lighting_colour(-0.8)
    assert set(np.unique(img & 0xFF).tolist()) == {0, lit, dark}
    for x0, x1, _, _, _, n in QUADS:
        col = (x0 + x1) / 2
        px = int((col + PS) / (2 * PS) * PW)
        assert img[PH // 2, px] & 0xFF == (lit if n[1] > 0 else dark)


@pytest.mark.parametrize("s", [1.0, 1e-3, 1e-13, 0.0, -1e-13, -1e-12, -1e-11, -1.0])
def test_nearly_singular_mirror_lights_like_the_mirror(s):
    """scale(1, 1, s) on a face with normal +z, light along +z: s > 0 lit
    (N.L = 1), s < 0 is a mirror whose inverse transpose flips the normal
    (ambient only).  Before the fix in geometry/lighting.py, |s| below the
    1e-12 singularity threshold used the cofactor matrix without the sign of
    the determinant and lit -1e-13 and -1e-12 like +1.  s = 0 (no
    orientation) takes the cofactor: lit."""
    lit_window()
    scale(1.0, 1.0, s)
    polygon(REF_SQUARE)
    red = colour()[37, 50] & 0xFF
    assert red == lighting_colour(-1.0 if s < 0 else 1.0)
