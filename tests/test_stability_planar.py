"""Stability of planar projection shadows (Tessman, Bentley): a local light at,
below or above the top of the object, lights near the horizon, w near 0
(docs/stability.md).  Expected pixels from the analytic geometry."""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from vgx_emulator import VGXWarning
from banks import colour
from stability_helpers import (PW, PH, PS, fresh, pixel_window, polygon, sure_and_maybe,
                               assert_region, cover, top_view)


# 1. planar projection shadows (Tessman / Bentley ground matrix)
WALL = [(-1.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 3.0, 0.0), (-1.0, 3.0, 0.0)]


def ground_matrix(light):
    """The planar projection onto y = 0 from the homogeneous light L:
    p' = ly p - y L (row vectors).  With lw = 1 it is Tessman's local
    matrix (programs/tessman_flat_shadows.py); with lw = 0 it is the
    infinite light *without* the division by ly, so w = ly."""
    lx, ly, lz, lw = light
    return [[ly, 0, 0, 0], [-lx, 0, -lz, -lw], [0, 0, ly, 0], [0, 0, 0, ly]]


def draw_flattened(poly, matrix):
    """The polygon through the shadow matrix, seen from above (white on black)."""
    fresh()
    prefsize(PW, PH)
    winopen("planar")
    RGBmode()
    gconfig()
    mmode(MVIEWING)
    ortho(-PS, PS, -PS, PS, 1.0, 100.0)
    subpixel(TRUE)
    cpack(0)
    clear()
    loadmatrix(top_view())
    multmatrix(matrix)
    cpack(0xFFFFFFFF)
    polygon(poly)
    return colour() != 0


def ground_region(poly, light, beyond=False):
    """Predicate on window (x, y): the ground point there is in the shadow
    of the convex planar polygon (the segment to a local light, or the ray
    towards an infinite one, crosses it); ``beyond``: the anti-shadow, where
    the polygon lies on the far side of the light (w < 0)."""
    P = np.array(poly, float)
    L = np.asarray(light, float)
    n = np.cross(P[1] - P[0], P[2] - P[0])

    def inside(xw, yw):
        gx = -PS + (xw + 0.5) * 2 * PS / PW
        gz = PS - (yw + 0.5) * 2 * PS / PH
        g = np.stack((gx, np.zeros_like(gx), gz), axis=-1)
        d = np.broadcast_to(L[:3], g.shape) if L[3] == 0 else L[:3] - g
        with np.errstate(all="ignore"):
            t = ((P[0] - g) @ n) / (d @ n)
        q = g + t[..., None] * d
        if L[3] == 0:
            ok = t < 0 if beyond else t >= 0
        else:
            ok = t > 1 if beyond else (t >= 0) & (t <= 1)
        for k in range(len(P)):
            ok &= (np.cross(P[(k + 1) % len(P)] - P[k], q - P[k]) @ n) >= 0
        return ok
    return inside


def planar_case(light):
    got = draw_flattened(WALL, ground_matrix(light))
    ys, xs = np.mgrid[0:PH, 0:PW].astype(float)
    sure, maybe = sure_and_maybe(ground_region(WALL, light), xs, ys)
    anti, _ = sure_and_maybe(ground_region(WALL, light, beyond=True), xs, ys)
    return got, sure, maybe, anti


@pytest.mark.parametrize("ly", [2.0, 1.0, 2.999999, 3.0, 3.0 + 1e-12, 3.000001, 3.1])
def test_local_light_below_or_at_the_top_draws_only_the_real_shadow(ly):
    """The wall reaches y = 3.  A light below its top: the part above the
    light has w = ly - y < 0 and would land on the far side of the light (the
    anti-shadow); the w > 0 clip plane removes it, and the part below casts
    its shadow out to the window's edge.  Light at the top: the top edge has
    w = 0 (points at infinity), just above: w -> 0+."""
    light = (0.3, ly, 2.0, 1.0)
    got, sure, maybe, anti = planar_case(light)
    assert sure.sum() > 1000
    assert_region(got, sure, maybe)
    assert not (got & anti).any()
    if ly <= 2.0:
        assert anti.sum() > 300            # where an unclipped divide would draw


ELEVATIONS = [45.0, 1.0, 1e-2, 1e-6, 1e-12, 1e-20, 1e-28]


@pytest.mark.parametrize("deg", ELEVATIONS)
def test_infinite_light_nearly_parallel_to_the_ground(deg):
    """Light at infinity ``deg`` degrees above the horizon, homogeneous form
    (w = ly for every point): as ly -> 0+ every projected point goes to
    infinity; the shadow is the strip behind the wall out to the window edge,
    exactly, down to ly ~ 1e-30 (the clipper's w epsilon, next test)."""
    e = math.radians(deg)
    light = (0.2 * math.cos(e), math.sin(e), math.cos(e), 0.0)
    got, sure, maybe, _ = planar_case(light)
    assert sure.sum() > 300
    assert_region(got, sure, maybe)


@pytest.mark.parametrize("ly", [0.0, -1e-6, -0.5])
def test_light_on_or_below_the_horizon_draws_nothing(ly):
    """ly <= 0: w <= 0 for every point; nothing is drawn (not the inverted
    shadow of the anti-shadow region, which is non-empty)."""
    light = (0.2, ly, 1.0, 0.0)
    got, _, _, anti = planar_case(light)
    assert not got.any()
    if ly < 0:
        assert anti.sum() > 300


def test_w_below_the_clip_epsilon_is_behind_the_eye():
    """Documented limit (docs/decisions.md, W_EPSILON = 1e-30): the seventh
    clip plane is w >= 1e-30, so a homogeneous matrix scaled so that every w
    is below 1e-30 draws nothing, though any positive multiple of a
    projective matrix is the same map.  Scaling it by 1e6 draws the shadow."""
    light = (0.2, 1e-31, 1.0, 0.0)
    assert not draw_flattened(WALL, ground_matrix(light)).any()
    scaled = np.array(ground_matrix(light)) * 1e6
    ys, xs = np.mgrid[0:PH, 0:PW].astype(float)
    sure, maybe = sure_and_maybe(ground_region(WALL, light), xs, ys)
    assert_region(draw_flattened(WALL, scaled), sure, maybe)


def test_vertex_at_the_light_is_dropped_not_drawn_to_the_window_origin():
    """A vertex exactly at a local light goes through the ground matrix to
    the clip-space point (0, 0, 0, 0), which no divide can place.  Before the
    fix in geometry/__init__.py the clipper's cut vertex came out as that
    point, its 0/0 window position was replaced by (0, 0) and a triangle was
    drawn to the window's corner.  Now the triangle is dropped with a warning
    and the rest of the batch is drawn."""
    pixel_window(64, 48)
    cpack(0xFFFFFFFF)
    with pytest.warns(VGXWarning, match="divide"):
        polygon([(0, 0, 0, 0), (40, 10, 0, 1), (30, 40, 0, 1)], v4f)
        polygon([(50, 5, 0, 1), (60, 5, 0, 1), (60, 15, 0, 1)], v4f)
        got = colour() != 0
    want = cover([(50, 5), (60, 5), (60, 15)], 64, 48, sub=False)
    assert (got == want).all()
    # the same through the shadow matrix: a triangle touching the light
    light = (0.0, 2.0, 0.0, 1.0)
    with pytest.warns(VGXWarning):
        got = draw_flattened([(0.0, 2.0, 0.0), (1.0, 0.5, 0.0), (1.0, 0.5, 1.0)],
                             ground_matrix(light))
    assert not got[:2, :2].any()
