"""Stability of stencil shadow volumes (docs/stability.md): volumes extruded to
infinity, the eye inside a volume, z-pass and z-fail, finite far planes, and
more volumes than the 8-bit stencil counts around MYZERO.  Expected counts
from ray casts."""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from banks import colour, stencil_bank
from reference.camera import lookat_matrix
from stability_helpers import (MYZERO, fresh, pixel_window, polygon)


# 2. shadow volumes extruded to infinity (w = 0), eye inside a volume
VW, VH = 160, 120
VFOV, VNEAR = 600, 0.05
V_LIGHT = np.array([0.5, 5.0, 0.3])
V_SQUARE = np.array([(-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1)], float)
EYES = {"outside": ((6.0, 4.0, 8.0), (0.0, 0.0, 0.0)),
        "inside": ((0.3, 1.0, 0.2), (3.0, 0.0, 2.0))}


def infinite_perspective(fovy, aspect, near):
    """perspective(3G) in the limit far -> infinity; IRIS GL has no such
    call and no depth clamp, but loadmatrix in MPROJECTION takes it.  A point
    at infinity (w = 0) then has z/w = 1 exactly: on the far plane, kept."""
    c = 1.0 / math.tan(math.radians(fovy / 20.0))
    return [[c / aspect, 0, 0, 0], [0, c, 0, 0], [0, 0, -1, -1], [0, 0, -2 * near, 0]]


def volume_faces():
    """The closed shadow volume of the floating square: the square (near
    cap), its copy at infinity (far cap, vertices v4f(p - L, 0)) and four
    sides, each wound counter-clockwise seen from outside."""
    fin = [tuple(p) + (1.0,) for p in V_SQUARE]
    away = [tuple(p - V_LIGHT) + (0.0,) for p in V_SQUARE]
    faces = [fin, away] + [[fin[k], fin[(k + 1) % 4], away[(k + 1) % 4], away[k]]
                           for k in range(4)]
    centre = V_SQUARE.mean(axis=0)
    inner = centre + 0.5 * (centre - V_LIGHT)
    out = []
    for f in faces:
        pts = [np.array(v[:3]) if v[3] else centre + 3.0 * np.array(v[:3]) for v in f]
        n = np.cross(pts[1] - pts[0], pts[2] - pts[0])
        out.append(f if n @ (np.mean(pts, axis=0) - inner) > 0 else f[::-1])
    return out


def in_volume(P):
    """Exact: below the square and seen from the light through it."""
    t = (V_LIGHT[1] - 2.0) / (V_LIGHT[1] - P[..., 1])
    q = V_LIGHT + t[..., None] * (P - V_LIGHT)
    return (P[..., 1] < 2.0) & (np.abs(q[..., 0]) < 1) & (np.abs(q[..., 2]) < 1)


def volume_counts(eye, ref_pt, zfail, far=None):
    """Heidmann's volume pass (z and colour writes off, sclear(MYZERO)) over
    the ground plane, z-pass (front faces ST_INCR on zpass, back faces
    ST_DECR) or z-fail (back faces ST_INCR on pass, front ST_DECR); returns
    the stencil bank."""
    fresh()
    prefsize(VW, VH)
    winopen("volumes")
    RGBmode()
    stensize(8)
    gconfig()
    mmode(MVIEWING)
    if far is None:
        mmode(MPROJECTION)
        loadmatrix(infinite_perspective(VFOV, VW / VH, VNEAR))
        mmode(MVIEWING)
    else:
        perspective(VFOV, VW / VH, VNEAR, far)
    lookat(*eye, *ref_pt, 0)
    subpixel(TRUE)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    cpack(0xFF808080)
    polygon([(-30, 0, -30), (-30, 0, 30), (30, 0, 30), (30, 0, -30)])
    zwritemask(0)
    wmpack(0)
    sclear(MYZERO)
    for cull_back in (True, False):             # front faces, then back faces
        if zfail:
            stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP,
                    ST_DECR if cull_back else ST_INCR, ST_KEEP)
        else:
            stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP,
                    ST_INCR if cull_back else ST_DECR)
        backface(cull_back)
        frontface(not cull_back)
        for f in volume_faces():
            polygon(f, v4f)
    backface(FALSE)
    frontface(FALSE)
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    return stencil_bank()


def expected_counts(eye, ref_pt, zfail, far=math.inf):
    """Per pixel, cast from the eye through the pixel centre (float64): the
    ground pixels whose count is the same at the centre and 0.02 px around
    it, MYZERO + (inside at the ground point) - (inside where the ray
    crosses the near plane, z-pass only), and the shadowed ground."""
    eye = np.asarray(eye, float)
    R = lookat_matrix(eye, ref_pt)[:3, :3]
    c = 1.0 / math.tan(math.radians(VFOV / 20.0))
    ys, xs = np.mgrid[0:VH, 0:VW].astype(float)
    results = []
    for dx, dy in ((0, 0), (0.02, 0), (-0.02, 0), (0, 0.02), (0, -0.02)):
        xn = (xs + dx + 0.5) / VW * 2 - 1
        yn = (ys + dy + 0.5) / VH * 2 - 1
        d = np.stack((xn * (VW / VH) / c, yn / c, -np.ones_like(xn)), axis=-1) @ R.T
        t = -eye[1] / d[..., 1]                 # d has eye depth 1: t is the depth
        P = eye + t[..., None] * d
        ground = (t > 0) & (t < 0.999 * far) & (np.abs(P[..., 0]) < 30) & \
            (np.abs(P[..., 2]) < 30)
        shadow = in_volume(P)
        count = shadow.astype(int)
        if not zfail:
            count -= in_volume(eye + VNEAR * d).astype(int)
        results.append((ground, MYZERO + count, shadow))
    sure = np.logical_and.reduce([g for g, _, _ in results])
    sure &= np.logical_and.reduce([e == results[0][1] for _, e, _ in results])
    return sure, results[0][1], results[0][2]


@pytest.mark.parametrize("zfail", [False, True], ids=["zpass", "zfail"])
@pytest.mark.parametrize("where", sorted(EYES))
def test_volume_extruded_to_infinity_counts_exactly(where, zfail):
    """Far vertices at w = 0 under an infinite-far projection: the stencil
    equals the exact count at every ground pixel.  With the eye inside the
    volume z-pass starts one short (the lit ground reads MYZERO - 1, the
    shadow reads MYZERO: inverted), z-fail is exact.  (The Heidmann program's
    test_zfail_correct_with_eye_inside_volume checks two points of its
    scene; this is every pixel against a ray cast.)"""
    eye, ref_pt = EYES[where]
    got = volume_counts(eye, ref_pt, zfail)
    sure, want, shadow = expected_counts(eye, ref_pt, zfail)
    assert sure.sum() > 0.6 * VW * VH
    assert (got[sure] == want[sure]).all(), (got[sure] != want[sure]).sum()
    shadow &= sure
    assert shadow.sum() > 300
    if where == "inside" and not zfail:
        assert (got[shadow] == MYZERO).all() and (got[sure & ~shadow] == MYZERO - 1).all()


@pytest.mark.parametrize("far", [20.0, 12.0])
def test_zfail_with_a_finite_far_plane_miscounts(far):
    """perspective() needs a finite far plane: the far cap at infinity and
    the side faces beyond ``far`` are clipped, so z-fail loses exits behind
    the ground: lit ground reads MYZERO - 1 (false shadow) and, with the far
    plane close, shadowed ground reads MYZERO (lost shadow); z-pass is
    unaffected (it counts in front of the ground only)."""
    eye, ref_pt = EYES["outside"]
    sure, want, _ = expected_counts(eye, ref_pt, True, far)
    got = volume_counts(eye, ref_pt, True, far)
    wrong = sure & (got != want)
    assert wrong.sum() > 1000
    assert (got[wrong] == want[wrong] - 1).all()          # one exit lost
    assert (wrong & (want == MYZERO)).sum() > 1000        # false shadow on lit ground
    sure_p, want_p, _ = expected_counts(eye, ref_pt, False, far)
    got_p = volume_counts(eye, ref_pt, False, far)
    assert (got_p[sure_p] == want_p[sure_p]).all()


# 3. more overlapping volumes than the 8-bit stencil counts around MYZERO
def saturating(start, ops, top=255):
    """The VGX stencil arithmetic (ST_INCR/ST_DECR clamp, docs/semantics.md §6)."""
    s = start
    for op in ops:
        s = min(s + 1, top) if op == ST_INCR else max(s - 1, 0)
    return s


def nested_volume_faces(n, order):
    """z-pass operations at a ground pixel in front of which n volumes lie
    whole (each contributes one front face and one back face): 'in-first' is
    Heidmann's order (every ingoing face first), 'out-first' the reverse,
    'interleaved' volume by volume."""
    if order == "in-first":
        return [ST_INCR] * n + [ST_DECR] * n
    if order == "out-first":
        return [ST_DECR] * n + [ST_INCR] * n
    return [ST_INCR, ST_DECR] * n


@pytest.mark.parametrize("n,order", [(n, o) for o in ("in-first", "out-first")
                                     for n in (127, 128, 129, 300)] + [(129, "interleaved")])
def test_stencil_saturates_around_myzero(n, order):
    """The true count is 0 (the ground is lit), but INCR stops at 255 and
    DECR at 0: Heidmann's order is exact up to 127 volumes in front of a
    point, the reverse order up to 128; past that the pixel is shadowed by
    mistake.  Drawing each volume's faces together never saturates."""
    pixel_window(16, 8, planes=8)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    # ortho2: object z = -0.9 is window-z far, 0.5 near, -0.95 behind the ground
    polygon([(-1, -1, -0.9), (16, -1, -0.9), (16, 8, -0.9), (-1, 8, -0.9)])   # ground
    zwritemask(0)
    wmpack(0)
    sclear(MYZERO)
    ops = nested_volume_faces(n, order)
    for k, op in enumerate(ops):
        if k == 0 or op != ops[k - 1]:        # a stencil call only when it changes
            stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, op)
        polygon([(-1, -1, 0.5), (16, -1, 0.5), (16, 8, 0.5), (-1, 8, 0.5)])   # in front
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)
    polygon([(-1, -1, -0.95), (16, -1, -0.95), (16, 8, -0.95), (-1, 8, -0.95)])  # z fails
    got = stencil_bank()
    want = saturating(MYZERO, ops)
    assert (got == want).all()
    limit = {"in-first": 127, "out-first": 128, "interleaved": math.inf}[order]
    assert (want == MYZERO) == (n <= limit)
