"""Numerical stability on stiff and extreme cases (issue section 2).

One test (or parametrised group) per row of ``docs/stability.md``.  Every
expectation is computed here, independently of the library: pixel sets from
the analytic geometry (float64 numpy, with a 0.02-pixel margin where an edge
is only known to the rasterizer's 1/256 of a pixel), exact stencil counts
from ray casts, z decisions from the depth mapping of docs/semantics.md §5
(docs/semantics.md §5), fill-rule coverage from ``tests/reference/raster.py`` or its
vectorised twin ``cover`` below (checked against it).

``python -m tests.test_stability`` (from the repository root) prints the
measured tables of the doc.
"""
import math
import warnings

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from irisgl import GLError
from vgx_emulator import VGXWarning

try:                                    # tests/ on sys.path (pytest)
    from banks import colour, stencil_bank, z_bank
    from reference import raster as ref
    from reference.camera import lookat_matrix
except ImportError:                     # python -m tests.test_stability
    from tests.banks import colour, stencil_bank, z_bank
    from tests.reference import raster as ref
    from tests.reference.camera import lookat_matrix

ZMIN, ZMAX = -0x800000, 0x7FFFFF
F32MAX = float(np.finfo(np.float32).max)
MYZERO = 128                            # Heidmann's stencil zero


# -- common helpers ---------------------------------------------------------------
def fresh():
    """Forget every window (several renders in one test)."""
    from irisgl._current import machine
    machine.reset()


def pixel_window(w, h, planes=0):
    """A window whose ortho2 puts pixel (i, j)'s centre at object (i, j)."""
    fresh()
    prefsize(w, h)
    winopen("stability")
    RGBmode()
    if planes:
        stensize(planes)
    gconfig()
    ortho2(-0.5, w - 0.5, -0.5, h - 0.5)


def polygon(vs, call=v3f):
    bgnpolygon()
    for v in vs:
        call(v)
    endpolygon()


def sure_and_maybe(inside, xs, ys, eps=0.02):
    """(surely inside, possibly inside) pixel masks of a region given by the
    vectorised predicate ``inside(x, y)``: the centre and four points ``eps``
    pixels away must agree, else the pixel is on an edge that the 1/256 grid
    may move."""
    probes = [inside(xs + dx, ys + dy)
              for dx, dy in ((0, 0), (eps, 0), (-eps, 0), (0, eps), (0, -eps))]
    return np.logical_and.reduce(probes), np.logical_or.reduce(probes)


def assert_region(got, sure, maybe, max_unsure=0.05):
    """Drawn pixels contain every sure pixel and nothing outside the maybe
    set; the unsure band stays thin so that the check means something."""
    assert not (sure & ~got).any(), f"{(sure & ~got).sum()} pixels missing"
    assert not (got & ~maybe).any(), f"{(got & ~maybe).sum()} stray pixels"
    assert (maybe & ~sure).sum() <= max(16, max_unsure * sure.sum())


def assert_banks_sane(colours, untouched=None):
    """No garbage anywhere: every colour word is one of ``colours``, every z
    in the signed 24-bit range; pixels of ``untouched`` (mask) still hold the
    clear colour 0 and GD_ZMAX."""
    c = colour()
    assert set(np.unique(c).tolist()) <= set(colours)
    from irisgl._current import machine
    z = machine.current.fb.z
    if z is not None:
        zb = z_bank()
        assert ZMIN <= zb.min() and zb.max() <= ZMAX
        if untouched is not None:
            assert (zb[untouched] == ZMAX).all()
    if untouched is not None:
        assert (c[untouched] == 0).all()


def cover(tri, w, h, sub=True):
    """Vectorised fill-rule model (the rule of tests/reference/raster.py on
    the 1/256 grid, int64 edge functions): coverage mask (h, w) of one
    triangle given in window coordinates, no clipping (vertices within the
    guard band); ``sub`` False: vertices snapped to pixel centres."""
    if sub:
        p = [(math.floor(x * 256 + 0.5), math.floor(y * 256 + 0.5)) for x, y in tri]
    else:
        p = [(math.floor(x + 0.5) * 256, math.floor(y + 0.5) * 256) for x, y in tri]
    a, b, c = p
    area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if area == 0:
        return np.zeros((h, w), bool)
    if area < 0:
        b, c = c, b
    ys, xs = np.mgrid[0:h, 0:w].astype(np.int64) * 256
    out = np.ones((h, w), bool)
    for (px, py), (qx, qy) in ((a, b), (b, c), (c, a)):
        e = (qx - px) * (ys - py) - (qy - py) * (xs - px)
        owned = qy < py or (qy == py and qx > px)
        out &= (e > 0) | ((e == 0) & owned)
    return out


# ==================================================================================
# 1. planar projection shadows (Tessman / Bentley ground matrix)
PW = PH = 128
PS = 8.0                       # the top view sees the ground x, z in [-8, 8]
WALL = [(-1.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 3.0, 0.0), (-1.0, 3.0, 0.0)]


def ground_matrix(light):
    """The planar projection onto y = 0 from the homogeneous light L:
    p' = ly p - y L (row vectors).  With lw = 1 it is Tessman's local
    matrix (programs/tessman_flat_shadows.py); with lw = 0 it is the
    infinite light *without* the division by ly, so w = ly."""
    lx, ly, lz, lw = light
    return [[ly, 0, 0, 0], [-lx, 0, -lz, -lw], [0, 0, ly, 0], [0, 0, 0, ly]]


def top_view():
    """ModelView looking straight down on the ground: eye = (x, -z, y - 10)."""
    return [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, -10, 1]]


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


# ==================================================================================
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


# ==================================================================================
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


# ==================================================================================
# 4. depth precision: near/far ratio and 16- versus 24-bit z
DFAR, DFOV = 1000.0, 400
DCOLS, DPHASES = 128, 16
DREL = np.logspace(-8, 1, DCOLS)          # relative separations, one per column
RATIOS = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7]


def z_range(bits):
    """24 bits: the VGX's signed range; 16 bits: lsetdepth(0, 0xFFFF), the
    65536 levels a 16-bit z-buffer holds (the VGX itself has only 24)."""
    return (ZMIN, ZMAX) if bits == 24 else (0, 0xFFFF)


def depth_constant(near, bits):
    """K of zw = const - K / d (d = eye depth), perspective(3G) + docs/semantics.md §5."""
    lo, hi = z_range(bits)
    return DFAR * near * (hi - lo) / (DFAR - near)


def one_level(near, bits, d):
    """Relative separation s/d that moves zw by exactly one level at depth d
    (K (1/d - 1/(d + s)) = 1); inf when d .. far spans less than one level."""
    K = depth_constant(near, bits)
    rel = d / (K - d) if K > d else math.inf
    return rel if d * (1 + rel) < DFAR else math.inf


def _cell(j, k, d):
    """A quad at eye depth d covering pixel (j, k) of the DCOLS x DPHASES window."""
    c = 1.0 / math.tan(math.radians(DFOV / 20.0))

    def eye(v, n, aspect):
        return ((v + 0.5) / n * 2 - 1) * aspect / c * d
    x0, x1 = eye(j - 0.4, DCOLS, DCOLS / DPHASES), eye(j + 0.4, DCOLS, DCOLS / DPHASES)
    y0, y1 = eye(k - 0.4, DPHASES, 1.0), eye(k + 0.4, DPHASES, 1.0)
    polygon([(x0, y0, -d), (x1, y0, -d), (x1, y1, -d), (x0, y1, -d)])


def depth_separation(ratio, bits, d):
    """Plane A at depth d_k (row k: 16 phases across one z level) in red,
    then B at d_k (1 + DREL[j]) in green, ZF_LEQUAL: green shows where the
    two quantize alike.  Returns (green mask, predicted mask, measured
    relative separation from which every column is separable in every row)."""
    near = DFAR / ratio
    fresh()
    prefsize(DCOLS, DPHASES)
    winopen("depth")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(DFOV, DCOLS / DPHASES, near, DFAR)
    lo, hi = z_range(bits)
    if bits == 16:
        lsetdepth(lo, hi)
    subpixel(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    K = depth_constant(near, bits)
    finite = math.isfinite(one_level(near, bits, d))
    dk = np.array([1 / (1 / d - k / DPHASES / K) if finite else d * (1 + k * 1e-3)
                   for k in range(DPHASES)])
    cpack(0xFF0000FF)
    for k in range(DPHASES):
        for j in range(DCOLS):
            _cell(j, k, dk[k])
    dB = dk[:, None] * (1 + DREL[None, :])
    drawn = dB < DFAR * 0.9999
    cpack(0xFF00FF00)
    for k, j in zip(*np.nonzero(drawn)):
        _cell(j, k, dB[k, j])
    green = (colour() & 0xFFFFFF) == 0x00FF00
    mmode(MPROJECTION)
    P = np.asarray(getmatrix(), np.float64)      # the float32 matrix the pipeline uses
    mmode(MVIEWING)

    def q(depth):
        zw = (hi + lo) / 2 + (-depth * P[2, 2] + P[3, 2]) / depth * (hi - lo) / 2
        return np.clip(np.floor(zw + 0.5), lo, hi)
    kept = (-dB * P[2, 3] + P[3, 3]) - (-dB * P[2, 2] + P[3, 2]) >= 0    # far: w - z >= 0
    predicted = drawn & kept & (q(dB) <= q(dk[:, None]))
    bad = np.nonzero(green.any(axis=0))[0]
    measured = DREL[0] if len(bad) == 0 else (
        DREL[bad[-1] + 1] if bad[-1] + 1 < DCOLS and drawn[:, bad[-1] + 1].all() else math.inf)
    return green, predicted, measured


@pytest.mark.parametrize("bits", [24, 16])
@pytest.mark.parametrize("ratio", RATIOS)
def test_depth_separation_is_the_z_quantum(ratio, bits):
    """Two planes at depth d = far/10 and d (1 + s): which cells z-fight is
    exactly what the depth mapping and round-to-nearest predict, and the
    smallest separation that is safe whatever the phase is one z level
    (within one column step of the log grid)."""
    d = DFAR / 10
    green, predicted, measured = depth_separation(ratio, bits, d)
    assert (green == predicted).all(), (green != predicted).sum()
    level = one_level(DFAR / ratio, bits, d)
    step = DREL[1] / DREL[0]
    if math.isfinite(level):     # else less than a level lies between d and far
        assert level * (1 - 1 / DPHASES) / step <= measured <= level * step


def floor_fight(ratio, bits, sub, s=0.01, h=1.0, w=160, hgt=120):
    """A floor h below the eye and a second one s below it, drawn after it
    (ZF_LEQUAL): (floor pixels, pixels where the lower floor shows).  For the
    doc's table; each row of the floor has one depth, so rows fight whole."""
    fresh()
    prefsize(w, hgt)
    winopen("floor")
    RGBmode()
    gconfig()
    subpixel(sub)
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(DFOV, w / hgt, DFAR / ratio, DFAR)
    if bits == 16:
        lsetdepth(*z_range(16))
    czclear(0, getgdesc(GD_ZMAX))
    g = 2 * DFAR
    for y, word in ((-h, 0xFF0000FF), (-h - s, 0xFF00FF00)):
        cpack(word)
        polygon([(-g, y, 0), (g, y, 0), (g, y, -g), (-g, y, -g)])
    img = colour() & 0xFFFFFF
    return int(((img == 0x0000FF) | (img == 0x00FF00)).sum()), int((img == 0x00FF00).sum())


# ==================================================================================
# 5. self-shadowing acne versus bias at grazing light angles
LS = 128                                 # the light's depth image
GR = 4.0                                 # the ground square is [-4, 4]^2


def light_depth(elev_deg, azim_deg=30.0):
    """The ground drawn from an infinite light (ortho, lookat) into the z-buffer
    only; returns (ModelView.Projection, light z image)."""
    from programs import shadowbuf as sb
    fresh()
    prefsize(LS, LS)
    winopen("light")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    e, a = math.radians(elev_deg), math.radians(azim_deg)
    to_light = np.array([math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a)])
    ext, dist = GR * math.sqrt(2), 20.0
    ortho(-ext, ext, -ext, ext, dist - 2 * ext, dist + 2 * ext)
    lookat(*(dist * to_light), 0.0, 0.0, 0.0, 0)
    subpixel(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    wmpack(0)
    polygon([(-GR, 0, -GR), (-GR, 0, GR), (GR, 0, GR), (GR, 0, -GR)])
    wmpack(0xFFFFFFFF)
    return sb.current_mvp(), sb.read_depth(LS, LS)


def acne(elev_deg, biases, n=160):
    """Fraction of ground points (random, seen by the light) that the shadow
    test ``z - bias > light z`` (nearest sample, Williams) wrongly puts in
    shadow, per bias; and the slope bound b* = 0.5 (|dz/dx| + |dz/dy|) + 0.5
    of the plane in light-window units (half a texel of slope plus half a z
    level), past which no point can be acne.  ``biases``: a list, or a
    function of b* giving one."""
    from programs import shadowbuf as sb
    mvp, zl = light_depth(elev_deg)
    x0, y0, z0 = sb.world_to_window(np.array([[1.0, 0, 0], [0, 0, 1.0], [0, 0, 0]]), mvp, LS, LS)
    J = np.array([[x0[0] - x0[2], x0[1] - x0[2]], [y0[0] - y0[2], y0[1] - y0[2]]])
    g = np.linalg.solve(J.T, np.array([z0[0] - z0[2], z0[1] - z0[2]]))
    bound = 0.5 * (abs(g[0]) + abs(g[1])) + 0.5
    rng = np.random.default_rng(7)
    m = 0.9 * GR
    p = np.stack((rng.uniform(-m, m, n * n), np.zeros(n * n), rng.uniform(-m, m, n * n)), -1)
    x, y, zp = sb.world_to_window(p, mvp, LS, LS)
    zs = sb.light_depth_at(zl, x, y)
    biases = biases(bound) if callable(biases) else biases
    return [float(np.mean(zp - b > zs)) for b in biases], bound


@pytest.mark.parametrize("elev", [60.0, 30.0, 10.0, 3.0, 1.0])
def test_acne_versus_bias_at_grazing_angles(elev):
    """No bias: about half the ground shadows itself (the nearest light
    sample is as often in front as behind).  A slope-scaled bias just past
    the bound removes every false shadow at every angle; half of it leaves
    many; the constant bias that is just enough at 60 degrees fails more and
    more towards grazing angles: b* - 1/2 grows as cot(elevation)."""
    _, bound60 = acne(60.0, [])
    (zero, half, enough, const60), bound = acne(
        elev, lambda b: [0.0, 0.5 * b, 1.01 * b, 1.01 * bound60])
    assert 0.35 <= zero <= 0.6
    assert half > 0.1
    assert enough == 0.0
    if elev <= 10.0:
        assert const60 > 0.3
    cot = math.tan(math.radians(60.0)) / math.tan(math.radians(elev))
    assert abs((bound - 0.5) / (bound60 - 0.5) / cot - 1) < 0.02


# ==================================================================================
# 6. huge, sub-pixel and sliver triangles
def test_vectorised_fill_model_agrees_with_the_reference():
    """So that ``cover`` cannot hide a bug: it equals the Fraction model on
    triangles with vertices on, off and between pixel centres."""
    rng = np.random.default_rng(3)
    tris = [[(1, 1), (6, 1), (1, 6)], [(2, 2), (9, 5), (4, 9)], [(3.5, 0.5), (3.5, 8.5), (0.5, 4)]]
    tris += [[tuple(rng.uniform(0, 12, 2)) for _ in range(3)] for _ in range(20)]
    for t in tris:
        for sub in (True, False):
            want = ref.triangle_pixels(*ref.place(t, sub), 12, 12)
            ys, xs = np.nonzero(cover(t, 12, 12, sub))
            assert set(zip(xs.tolist(), ys.tolist())) == want, (t, sub)


HUGE = [
    # inside the guard band: no clipping, the fill rule exactly (area 1.0e7)
    [(-4000.3, 700.35), (5200.1, -300.65), (900.45, 2400.8)],
    # guard-band clipped (areas 1e12 and 2e18): the analytic edges
    [(-1e6, 300.3), (1e6, 800.7), (640.2, 1e6)],
    [(-1e9, -1e9 + 0.3), (1e9, 1e9 + 0.3), (-1e9, 1e9)],
]


@pytest.mark.parametrize("k", range(len(HUGE)))
def test_huge_triangle_in_the_largest_window(k):
    """1280 x 1024 (the screen, the largest window).  Pixel count equals the
    analytic count: exactly the fill rule while no clipping happens, the
    exact edges up to the 1/256 grid when the guard band cuts."""
    W, H = 1280, 1024
    tri = HUGE[k]
    pixel_window(W, H)
    subpixel(TRUE)
    cpack(0xFFFFFFFF)
    polygon(tri, v2f)
    got = colour() != 0
    if k == 0:
        assert (got == cover(tri, W, H)).all()
        return
    a, b, c = (np.array(p, float) for p in tri)
    if (b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0] < 0:
        b, c = c, b

    def inside(x, y):
        ok = np.ones(x.shape, bool)
        for p, q in ((a, b), (b, c), (c, a)):
            d = q - p
            ok &= d[0] * (y - p[1]) - d[1] * (x - p[0]) >= 0
        return ok
    ys, xs = np.mgrid[0:H, 0:W].astype(float)
    sure, maybe = sure_and_maybe(inside, xs, ys, eps=0.01)
    assert_region(got, sure, maybe, max_unsure=0.001)


def additive_counts(tris, w, h):
    """How many triangles drew each pixel (one batch, blendfunction(BF_ONE, BF_ONE))."""
    cpack(0)
    clear()
    blendfunction(BF_ONE, BF_ONE)
    cpack(0x00000001)
    for t in tris:
        polygon(t, v2f)
    img = colour() & 0xFF
    blendfunction(BF_ONE, BF_ZERO)
    return img


def reference_counts(tris, w, h, sub):
    out = np.zeros((h, w), np.int64)
    for t in tris:
        for x, y in ref.triangle_pixels(*ref.place(t, sub), w, h):
            out[y, x] += 1
    return out


@pytest.mark.parametrize("sub", [True, False], ids=["subpixel", "snapped"])
def test_subpixel_triangles_cover_zero_or_one_pixel_as_the_fill_rule_says(sub):
    """2048 triangles each smaller than a pixel (one per 4 x 4 cell) in one
    batch: every pixel is drawn exactly as often as the reference model says
    (0 or 1 per triangle)."""
    W, H = 256, 128
    pixel_window(W, H)
    subpixel(sub)
    rng = np.random.default_rng(11)
    tris = []
    for cy in range(H // 4):
        for cx in range(W // 4):
            c = np.array([cx * 4 + 1.5, cy * 4 + 1.5]) + rng.uniform(-0.5, 0.5, 2)
            tris.append([tuple(c + rng.uniform(-0.45, 0.45, 2)) for _ in range(3)])
    got = additive_counts(tris, W, H)
    want = reference_counts(tris, W, H, sub)
    assert want.sum() > 50 and want.max() == 1
    assert (got == want).all()


@pytest.mark.parametrize("sub", [True, False], ids=["subpixel", "snapped"])
def test_slivers_match_the_fill_rule(sub):
    """60 slivers 200+ pixels long and 0, 1/256, 1e-3 or 1e-6 pixel thick:
    zero-area ones draw nothing, the others exactly the reference pixels."""
    W, H = 256, 128
    pixel_window(W, H)
    subpixel(sub)
    rng = np.random.default_rng(5)
    tris = []
    for k in range(60):
        y0 = 2 + 2 * k + rng.uniform(0, 1)
        x0, x1 = rng.uniform(0, 20), rng.uniform(200, 250)
        dy = (x1 - x0) * rng.uniform(-0.02, 0.02)
        thick = [0.0, 1 / 256, 1e-3, 1e-6][k % 4]
        tris.append([(x0, y0), (x1, y0 + dy), ((x0 + x1) / 2, y0 + dy / 2 + thick)])
    want = reference_counts(tris, W, H, sub)
    assert want.sum() > 0
    assert (additive_counts(tris, W, H) == want).all()


def test_fan_of_720_slivers_is_watertight():
    """A 720-gon fanned from an off-centre point: slivers half a pixel wide
    at the rim; every pixel inside is drawn exactly once."""
    W, H = 160, 128
    pixel_window(W, H)
    subpixel(TRUE)
    c = (80.3, 64.2)
    rim = [(80 + 60 * math.cos(a), 64 + 60 * math.sin(a))
           for a in np.linspace(0, 2 * math.pi, 721)[:-1]]
    tris = [[c, rim[i], rim[(i + 1) % 720]] for i in range(720)]
    got = additive_counts(tris, W, H)
    want = sum(cover(t, W, H).astype(np.int64) for t in tris)
    assert want.max() == 1 and want.sum() > 10000
    assert (got == want).all()


# ==================================================================================
# 7. coordinates near the float32 limits
LW, LH = 64, 48
INNER = (8, 55, 6, 41)                   # the viewport the hostile cases draw in


def inner_window():
    """A z-buffered window drawing only into the INNER viewport, mapped so
    that object (x, y) is window (x, y); returns the mask of pixels outside
    it, which nothing may touch."""
    pixel_window(LW, LH)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    l, r, b, t = INNER
    viewport(l, r, b, t)
    ortho2(l - 0.5, r + 0.5, b - 0.5, t + 0.5)
    outside = np.ones((LH, LW), bool)
    outside[b:t + 1, l:r + 1] = False
    return outside


def inner_rect():
    l, r, b, t = INNER
    m = np.zeros((LH, LW), bool)
    m[b:t + 1, l:r + 1] = True
    return m


def quadrant(x0, y0, right, up):
    """Pixels of the INNER viewport in the quadrant beyond a corner at pixel
    boundaries (x0, y0 half-integers)."""
    ys, xs = np.mgrid[0:LH, 0:LW]
    return inner_rect() & ((xs > x0) if right else (xs < x0)) & ((ys > y0) if up else (ys < y0))


LIMIT_CASES = {
    "corner with f32max legs": (
        [(20.5, 10.5, 0), (20.5, F32MAX, 0), (-F32MAX, 10.5, 0)], lambda: quadrant(20.5, 10.5, False, True)),
    "corner with 1e300 legs": (
        [(30.5, 20.5, 0), (1e300, 20.5, 0), (30.5, -1e300, 0)], lambda: quadrant(30.5, 20.5, True, False)),
    "z at +-3e38 (crosses the depth range in a zero-width line)": (
        [(1, 1, 3e38), (40, 1, 3e38), (1, 40, -3e38)], lambda: np.zeros((LH, LW), bool)),
    "z beyond far everywhere": (
        [(1, 1, -3e38), (40, 1, -3e38), (1, 40, -F32MAX)], lambda: np.zeros((LH, LW), bool)),
}


@pytest.mark.parametrize("name", sorted(LIMIT_CASES))
def test_float32_limit_coordinates(name):
    """No crash, no warning (the input is finite), exactly the expected
    pixels, nothing outside the viewport, sane banks."""
    vs, want = LIMIT_CASES[name]
    outside = inner_window()
    subpixel(TRUE)
    cpack(0xFFFFFFFF)
    with warnings.catch_warnings():
        warnings.simplefilter("error", VGXWarning)
        polygon(vs)
        got = colour() != 0
    assert (got == want()).all(), (got != want()).sum()
    assert_banks_sane({0, 0xFFFFFFFF}, outside)


CLIP_CANCEL = pytest.mark.xfail(strict=True, reason=(
    "BUG (the one of test_clip.py::test_huge_triangle_diagonal_edge at 1e20/1e30): "
    "geometry/clip.py cuts an edge as vin + s*(vout - vin); with both ends near 3e38 the "
    "guard-band cut lands ~1e22 off, so a triangle covering the viewport draws a part"))


@pytest.mark.parametrize("big", [1e6, pytest.param(3e38, marks=CLIP_CANCEL)])
def test_window_covering_triangle_at_the_float32_limit(big):
    """(-big, -big) (big, -big) (0, big) covers the whole viewport."""
    outside = inner_window()
    cpack(0xFFFFFFFF)
    polygon([(-big, -big, 0), (big, -big, 0), (0, big, 0)])
    assert_banks_sane({0, 0xFFFFFFFF}, outside)          # holds even with the bug
    assert ((colour() != 0) == inner_rect()).all()


TRI = [(10.3, 8.6), (50.2, 12.4), (22.7, 40.1)]


@pytest.mark.parametrize("s", [1e-38, 1e-30, 1e30, 1e36])
def test_scaled_scenes_draw_the_same_pixels(s):
    """A scene and its projection both scaled by s (ortho2 of a 1e-38-wide
    world, or scale(s) with vertices / s) draws the pixels of the unscaled
    scene: float32 matrices keep 24 relative bits down to the smallest
    normal float."""
    pixel_window(LW, LH)
    subpixel(TRUE)
    cpack(0xFFFFFFFF)
    ortho2(-0.5 * s, (LW - 0.5) * s, -0.5 * s, (LH - 0.5) * s)
    polygon([(x * s, y * s) for x, y in TRI], v2f)
    ours = colour() != 0
    pixel_window(LW, LH)
    subpixel(TRUE)
    cpack(0xFFFFFFFF)
    scale(s, s, 1.0)
    polygon([(x / s, y / s) for x, y in TRI], v2f)
    theirs = colour() != 0
    want = cover(TRI, LW, LH)
    assert (ours == want).all() and (theirs == want).all()


def test_denormal_scale_collapses_the_geometry_quietly():
    """scale(1e-45) (a float32 denormal) times the ortho2 matrix underflows
    to 0 in the float32 Matrix: every vertex lands on one point, nothing is
    drawn, nothing crashes and no warning is due (the input is finite)."""
    outside = inner_window()
    cpack(0xFFFFFFFF)
    scale(1e-45, 1e-45, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", VGXWarning)
        polygon([(x * 1e45, y * 1e45, 0) for x, y in TRI])
        assert not (colour() != 0).any()
    assert_banks_sane({0}, outside)


@pytest.mark.parametrize("near,far", [(1e-30, 1e30), (float(np.finfo(np.float32).tiny), F32MAX)])
def test_extreme_perspective_ranges_keep_coverage(near, far):
    """x and y do not depend on near and far: the triangle covers the same
    pixels as with perspective(450, a, 1, 10); z is squeezed against GD_ZMAX
    but stays in range."""
    def draw(n, f):
        pixel_window(LW, LH)
        zbuffer(TRUE)
        czclear(0, getgdesc(GD_ZMAX))
        mmode(MVIEWING)
        perspective(450, LW / LH, n, f)
        subpixel(TRUE)
        cpack(0xFFFFFFFF)
        polygon([(-1.1, -0.7, -5), (1.3, -0.9, -5), (0.1, 1.2, -5)])
        return colour() != 0
    want = draw(1.0, 10.0)
    assert want.sum() > 200
    assert (draw(near, far) == want).all()
    assert_banks_sane({0, 0xFFFFFFFF})


# ==================================================================================
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


# ==================================================================================
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


# ==================================================================================
# 10. float32 geometry versus float64 geometry (the four spheres)
def four_spheres(round32, subpix):
    """programs/four_spheres' configuration and draw_scene, its v3f/n3f
    arguments as given (float64) or rounded to float32 first (what a C
    program's float arrays hold)."""
    import programs.four_spheres as fs
    fresh()
    prefsize(fs.WIDTH, fs.HEIGHT)
    winopen("four spheres")
    RGBmode()
    gconfig()
    subpixel(subpix)
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, fs.WIDTH / fs.HEIGHT, 1.0, 50.0)
    fs.define_lighting()
    lmbind(MATERIAL, fs.SPHERE_MAT)
    lmbind(LMODEL, fs.MODEL)
    if round32:
        def f32(call):
            return lambda a: call(tuple(float(x) for x in np.float32(a)))
        fs.v3f, fs.n3f = f32(v3f), f32(n3f)
    try:
        fs.draw_scene()
    finally:
        fs.v3f, fs.n3f = v3f, n3f
    return colour(), z_bank()


def float_differences(subpix):
    """(drawn pixels, coverage differences, colour differences, largest
    channel difference, z differences, largest z difference)."""
    c64, z64 = four_spheres(False, subpix)
    c32, z32 = four_spheres(True, subpix)
    drawn = (c64 != 0) | (c32 != 0)
    chan = np.abs(np.stack([((c64 >> s) & 255) - ((c32 >> s) & 255) for s in (0, 8, 16)]))
    return (int(drawn.sum()), int(((c64 != 0) != (c32 != 0)).sum()), int((c64 != c32).sum()),
            int(chan.max()), int((z64 != z32).sum()), int(np.abs(z64 - z32).max()))


@pytest.mark.parametrize("subpix", [FALSE, TRUE], ids=["snapped", "subpixel"])
def test_float32_rounded_geometry_changes_almost_nothing(subpix):
    """Rounding the spheres' vertices and normals to float32 moves a vertex
    by <= 2**-24 of its size (< 3e-7 world units, ~2e-4 of a sub-pixel
    step) and a colour by < 1e-4 of a level.  So: at most 0.1 % of the
    pixels change coverage or colour, by one level at most; z (about 1.2e5
    units per world unit at the spheres) moves by < 0.04 units, so stored z
    changes by one unit at most, at < 2 * 0.04 of the pixels."""
    drawn, cov, col, chan, zd, zmax = float_differences(subpix)
    assert drawn > 30000
    assert cov <= 0.001 * drawn and col <= 0.001 * drawn and chan <= 1
    assert zmax <= 1 and zd <= 0.08 * drawn


# ==================================================================================
# the tables of docs/stability.md
def _print_tables():
    print("depth: smallest separable relative depth difference at d = far/10 and far/2, "
          f"far = {DFAR:g}")
    for ratio in RATIOS:
        cells = []
        for bits in (24, 16):
            for frac in (10, 2):
                d = DFAR / frac
                _, _, measured = depth_separation(ratio, bits, d)
                cells.append(f"{bits}b f/{frac}: {measured:.2e} (1 level {one_level(DFAR / ratio, bits, d):.2e})")
        print(f"  far/near {ratio:.0e}: " + " | ".join(cells))
    print("floor 1 below the eye and a second 0.01 below it: pixels of the lower one shown")
    for ratio in RATIOS:
        print(f"  far/near {ratio:.0e}: " + " | ".join(
            "{}b {}: {} of {}".format(bits, "subpixel" if sub else "snapped",
                                      *floor_fight(ratio, bits, sub)[::-1])
            for bits in (24, 16) for sub in (TRUE, FALSE)))
    print("acne (% of ground points) vs bias in z units, and with the slope bound b*")
    biases = [0, 256, 4096, 65536, 1 << 20]
    for elev in (60.0, 30.0, 10.0, 3.0, 1.0, 0.3):
        fr, bound = acne(elev, biases)
        near_bound, _ = acne(elev, lambda b: [0.5 * b, 0.9 * b, 1.01 * b])
        print(f"  {elev:5.1f} deg  b* = {bound:10.0f}  " +
              " ".join(f"{b}: {100 * f:.1f}" for b, f in zip(biases, fr)) +
              "  | b*/2 {:.1f} 0.9b* {:.2f} 1.01b* {:.2f}".format(*(100 * f for f in near_bound)))
    print("float32 vs float64 four spheres: drawn, coverage diff, colour diff, max channel "
          "diff, z diff, max z diff")
    for subpix in (FALSE, TRUE):
        print("  ", "subpixel" if subpix else "snapped", float_differences(subpix))
    for where in sorted(EYES):
        for zfail in (False, True):
            for far in (None, 20.0, 12.0):
                eye, ref_pt = EYES[where]
                sure, want, _ = expected_counts(eye, ref_pt, zfail, far or math.inf)
                got = volume_counts(eye, ref_pt, zfail, far)
                print(f"  volume eye {where} {'zfail' if zfail else 'zpass'} far {far}: "
                      f"{int(sure.sum())} ground px, {int((sure & (got != want)).sum())} wrong, "
                      f"{int((sure & (want != MYZERO)).sum())} != MYZERO")


if __name__ == "__main__":
    _print_tables()
