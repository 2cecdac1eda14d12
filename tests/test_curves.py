"""Curves and patches (docs/semantics.md §17), the emulator's patch surfaces,
the Utah teapot data and programs/teapot.py.

Expectations are computed here, independently of the library: the basis
matrices are typed in from the Programming Guide, P(t) = [t^3 t^2 t 1].M.G is
evaluated with plain Python arithmetic (exact fractions where pixels are
predicted), and drawn output is read back from a window whose ortho2 puts
pixel centres on integer coordinates (docs/semantics.md §1: snapped lines are closed).
"""
import math
from fractions import Fraction
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from irisgl import *
from irisgl import GLError
from banks import new_window
from vgx_emulator import VGXWarning, run_program
from vgx_emulator.geometry import curves as C
from vgx_emulator.surfaces import patch_mesh

ROOT = Path(__file__).resolve().parent.parent
TEAPOT = ROOT / "programs" / "teapot.py"

# The bases as printed in the Programming Guide (docs/semantics.md §17), rows as printed.
BEZ = [[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]]
CAR = [[-0.5, 1.5, -1.5, 0.5], [1, -2.5, 2, -0.5], [-0.5, 0, 0.5, 0], [0, 1, 0, 0]]
BSP = [[-1 / 6, 3 / 6, -3 / 6, 1 / 6], [3 / 6, -6 / 6, 3 / 6, 0],
       [-3 / 6, 0, 3 / 6, 0], [1 / 6, 4 / 6, 1 / 6, 0]]
BASES = {"bezier": BEZ, "cardinal": CAR, "bspline": BSP}
BEZIER_ID, CARDINAL_ID, BSPLINE_ID = 1, 2, 3


# ----------------------------------------------------------------------------
# independent evaluation

def weights(M, t):
    """[t^3 t^2 t 1] . M, as 4 numbers (works with Fractions too)."""
    T = [t ** 3, t ** 2, t, 1]
    return [sum(T[i] * M[i][j] for i in range(4)) for j in range(4)]


def curve_point(M, G, t):
    w = weights(M, t)
    return [sum(w[j] * G[j][k] for j in range(4)) for k in range(len(G[0]))]


def patch_point(Mu, Mv, Gs, u, v):
    """[v^3 v^2 v 1].Mv.G.Mu^T.[u^3 u^2 u 1]^T for each coordinate matrix."""
    wu, wv = weights(Mu, u), weights(Mv, v)
    return [sum(wv[r] * G[r][c] * wu[c] for r in range(4) for c in range(4)) for G in Gs]


# ----------------------------------------------------------------------------
# a pixel-exact window

W, H = 40, 28


#: a W x H window, pixel centres on integers, cleared to 0, drawing in white
_window = partial(new_window, W, H, pixels=True, cleared=True)


def _lit(w=W, h=H):
    img = lrectread(0, 0, w - 1, h - 1)
    ys, xs = np.nonzero(img & 0x00FFFFFF)
    return set(zip(xs.tolist(), ys.tolist()))


def _snap(q):
    """Nearest integer of an exact value that is not a tie."""
    q = Fraction(q)
    assert q - math.floor(q) != Fraction(1, 2), "choose data without ties"
    return math.floor(q + Fraction(1, 2))


def _hline(x0, x1, y):
    return {(x, y) for x in range(min(x0, x1), max(x0, x1) + 1)}


def _vline(x, y0, y1):
    return {(x, y) for y in range(min(y0, y1), max(y0, y1) + 1)}


def _bases():
    defbasis(BEZIER_ID, BEZ)
    defbasis(CARDINAL_ID, CAR)
    defbasis(BSPLINE_ID, BSP)


@pytest.fixture
def drawn(monkeypatch):
    """Records the vertex lists that curves and patches send down the pipeline."""
    from irisgl._current import machine
    lines = []
    real = machine.polyline_vertices

    def record(win, kind, pts, call):
        lines.append(np.array([list(p) for p in pts], np.float64))
        return real(win, kind, pts, call)

    monkeypatch.setattr(machine, "polyline_vertices", record)
    return lines


# ----------------------------------------------------------------------------
# 1. evaluation against the basis formulas

def test_library_bases_are_the_printed_ones():
    assert np.allclose(C.BEZIER, BEZ)
    assert np.allclose(C.CARDINAL, CAR)
    assert np.allclose(C.BSPLINE, BSP)


@pytest.mark.parametrize("name", sorted(BASES))
@pytest.mark.parametrize("n", [1, 3, 7])
def test_curve_points_follow_the_basis_formula(name, n):
    M = BASES[name]
    G = np.random.default_rng(len(name) * 10 + n).uniform(-5, 5, (4, 3)).tolist()
    got = C.curve_points(np.array(M, float), G, n)
    want = [curve_point(M, G, k / n) for k in range(n + 1)]
    assert got.shape == (n + 1, 3)
    assert np.allclose(got, want, atol=1e-12)


def test_basis_end_conditions():
    """Properties of the three bases that do not depend on the formula above:
    Bezier interpolates G0 and G3, Cardinal interpolates G1 and G2, the
    uniform B-spline starts at (G0 + 4 G1 + G2)/6."""
    G = np.array([[0.0, 1.0, 2.0], [3.0, -1.0, 0.5], [4.0, 4.0, -2.0], [-1.0, 2.0, 1.0]])
    bez = C.curve_points(np.array(BEZ, float), G, 4)
    car = C.curve_points(np.array(CAR, float), G, 4)
    bsp = C.curve_points(np.array(BSP, float), G, 4)
    assert np.allclose(bez[0], G[0]) and np.allclose(bez[-1], G[3])
    assert np.allclose(car[0], G[1]) and np.allclose(car[-1], G[2])
    assert np.allclose(bsp[0], (G[0] + 4 * G[1] + G[2]) / 6)
    assert np.allclose(bsp[-1], (G[1] + 4 * G[2] + G[3]) / 6)
    # Bezier midpoint: Bernstein weights 1/8, 3/8, 3/8, 1/8
    assert np.allclose(bez[2], (G[0] + 3 * G[1] + 3 * G[2] + G[3]) / 8)


def test_patch_points_follow_the_formula_rows_are_v():
    """Different bases in u and v, so that a transposition shows."""
    rng = np.random.default_rng(7)
    Gs = [rng.uniform(-3, 3, (4, 4)) for _ in range(3)]
    us = np.array([0.0, 0.3, 1.0])
    vs = np.array([0.0, 0.6, 0.9, 1.0])
    got = C.patch_points(np.array(BEZ, float), np.array(BSP, float), Gs, us, vs)
    assert got.shape == (4, 3, 3)
    for i, v in enumerate(vs):
        for j, u in enumerate(us):
            assert np.allclose(got[i, j], patch_point(BEZ, BSP, [g.tolist() for g in Gs], u, v))
    # Bezier both ways: the v = 0 edge is the Bezier curve of row 0, the
    # u = 0 edge the Bezier curve of column 0
    got = C.patch_points(np.array(BEZ, float), np.array(BEZ, float), Gs, np.array([0.25]),
                         np.array([0.0, 0.25]))
    row0 = np.stack([g[0] for g in Gs], axis=1)          # 4 points (x, y, z) along u
    col0 = np.stack([g[:, 0] for g in Gs], axis=1)       # 4 points along v
    assert np.allclose(got[0, 0], curve_point(BEZ, row0.tolist(), 0.25))
    got_u0 = C.patch_points(np.array(BEZ, float), np.array(BEZ, float), Gs, np.array([0.0]),
                            np.array([0.25]))
    assert np.allclose(got_u0[0, 0], curve_point(BEZ, col0.tolist(), 0.25))


def test_crv_sends_the_curve_points(drawn):
    _window()
    _bases()
    curvebasis(CARDINAL_ID)
    curveprecision(5)
    G = [(1.0, 2.0, 0.0), (5.0, 20.0, 0.0), (30.0, 3.0, 0.0), (36.0, 25.0, 0.0)]
    crv(G)
    assert len(drawn) == 1
    want = [curve_point(CAR, G, k / 5) + [1.0] for k in range(6)]
    assert np.allclose(drawn[0], want)


def test_a_curve_leaves_the_graphics_position_at_its_end(drawn):
    """[S] crv(3G) calls the position undefined afterwards; it is left at
    the curve's last point, so curved.c's move2, crv, draw2 draws on from
    the curve's end: the draw2 segment starts where the curve stopped."""
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    curveprecision(4)
    G = [(2.0, 2.0, 0.0), (10.0, 20.0, 0.0), (20.0, 20.0, 0.0), (30.0, 5.0, 0.0)]
    move2(2.0, 2.0)
    crv(G)
    draw2(35.0, 5.0)
    gflush()
    assert np.allclose(drawn[0][-1], (30.0, 5.0, 0.0, 1.0))
    assert _hline(30, 35, 5) <= _lit()                  # the draw2 goes on from (30, 5)
    assert not {(15, 3), (20, 4)} & _lit()              # not from the move2 at (2, 2)


# ----------------------------------------------------------------------------
# 2. drawn curves, pixel-exact

def test_straight_bezier_along_a_row_covers_it_exactly():
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    for n in (1, 2, 3, 6, 18):
        cpack(0)
        clear()
        cpack(0xFFFFFFFF)
        curveprecision(n)
        crv([(2, 5, 0), (8, 5, 0), (14, 5, 0), (20, 5, 0)])
        assert _lit() == _hline(2, 20, 5), n
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    crv([(7, 1, 0), (7, 9, 0), (7, 17, 0), (7, 25, 0)])     # a column
    assert _lit() == _vline(7, 1, 25)


@pytest.mark.parametrize("n", [1, 2, 3, 5])
def test_curveprecision_sets_the_points_drawn(n):
    """A Bezier that goes out along a row and comes back: x(t) peaks at
    t = 1/2, so how far the line strip reaches depends on which t = k/n are
    drawn (n = 1: only the chord 4..6; n = 3 stops short of the peak)."""
    X = [4, 28, 28, 6]
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    curveprecision(n)
    crv([(x, 9, 0) for x in X])
    xs = [curve_point(BEZ, [[x] for x in X], Fraction(k, n))[0] for k in range(n + 1)]
    xs = [_snap(min(xs)), _snap(max(xs))]          # the strip covers the row between them
    assert _lit() == _hline(min(xs), max(xs), 9)
    assert max(xs) == {1: 6, 2: 22, 3: 21, 5: 22}[n]     # the data discriminates n


def test_crvn_draws_n_minus_3_segments(drawn):
    """Uniform B-spline through evenly spaced collinear points x_k = 2 + 4k:
    segment i runs from x_(i+1) to x_(i+2), so n points cover x_1 .. x_(n-2).
    Ten points are passed; only the first n count."""
    pts = [(2 + 4 * k, 6, 0) for k in range(10)]
    _window()
    _bases()
    curvebasis(BSPLINE_ID)
    curveprecision(4)
    for n in (4, 6, 9):
        cpack(0)
        clear()
        cpack(0xFFFFFFFF)
        drawn.clear()
        crvn(n, pts)
        assert len(drawn) == n - 3
        assert _lit() == _hline(2 + 4 * 1, 2 + 4 * (n - 2), 6), n
        for i, line in enumerate(drawn):
            assert np.allclose(line[0][:3], (2 + 4 * (i + 1), 6, 0))
            assert np.allclose(line[-1][:3], (2 + 4 * (i + 2), 6, 0))


def test_rcrv_with_equal_weights_is_the_plain_curve():
    G = [(3, 4, 0), (10, 20, 0), (25, 2, 0), (36, 22, 0)]
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    curveprecision(12)
    crv(G)
    plain = _lit()
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    rcrv([(2 * x, 2 * y, 2 * z, 2) for x, y, z in G])
    assert _lit() == plain
    assert (3, 4) in plain and (36, 22) in plain


def test_crv_with_a_nan_point_is_dropped_with_a_warning():
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    curveprecision(6)
    with pytest.warns(VGXWarning):
        crv([(2, 5, 0), (math.nan, 5, 0), (14, 5, 0), (20, 5, 0)])
        crv([(2, 9, 0), (8, 9, 0), (14, 9, 0), (20, 9, 0)])
        got = _lit()
    assert got == _hline(2, 20, 9)


# ----------------------------------------------------------------------------
# 3. patch webs

def _flat_patch(x0, dx, y0, dy):
    """Bezier control points on a uniform grid: P(u, v) = (x0 + 3 dx u, y0 + 3 dy v)."""
    gx = [[x0 + c * dx for c in range(4)] for _ in range(4)]
    gy = [[y0 + r * dy for _ in range(4)] for r in range(4)]
    gz = [[0.0] * 4 for _ in range(4)]
    return gx, gy, gz


def test_patch_web_is_a_grid_of_lines_through_the_edges():
    """patchcurves(4, 3): 4 curves along u (rows, at v = 0, 1/3, 2/3, 1) and
    3 along v (columns, at u = 0, 1/2, 1).  u runs along x, v along y."""
    _window()
    _bases()
    patchbasis(BEZIER_ID, BEZIER_ID)
    patchcurves(4, 3)
    patchprecision(5, 5)
    patch(*_flat_patch(2, 8, 3, 6))            # x 2..26, y 3..21
    want = set()
    for y in (3, 9, 15, 21):
        want |= _hline(2, 26, y)
    for x in (2, 14, 26):
        want |= _vline(x, 3, 21)
    assert _lit() == want


@pytest.mark.parametrize("prec,other,want", [
    (5, 4, 6), (6, 4, 6), (7, 4, 9), (1, 4, 3), (10, 2, 10), (3, 3, 4), (4, 3, 4),
    (1, 2, 1), (9, 5, 12)])
def test_segment_count_rounds_up_to_a_multiple(prec, other, want):
    assert C.segment_count(prec, other) == want


def test_patch_curves_have_rounded_segment_counts_and_meet_at_vertices(drawn):
    _window()
    _bases()
    patchbasis(BEZIER_ID, BEZIER_ID)
    patchcurves(4, 3)
    patchprecision(5, 7)
    patch(*_flat_patch(2, 8, 3, 6))
    assert len(drawn) == 4 + 3
    ucurves = [l for l in drawn if np.allclose(l[:, 1], l[0, 1])]     # rows: constant y
    vcurves = [l for l in drawn if np.allclose(l[:, 0], l[0, 0])]     # columns: constant x
    assert len(ucurves) == 4 and len(vcurves) == 3
    # along u: 5 rounded up to a multiple of (3 - 1) = 6 segments;
    # along v: 7 rounded up to a multiple of (4 - 1) = 9 segments
    assert all(len(l) == 6 + 1 for l in ucurves)
    assert all(len(l) == 9 + 1 for l in vcurves)
    assert sorted(l[0, 1] for l in ucurves) == pytest.approx([3, 9, 15, 21])
    assert sorted(l[0, 0] for l in vcurves) == pytest.approx([2, 14, 26])
    # every crossing is a vertex of both curves
    for lu in ucurves:
        for lv in vcurves:
            p = (lv[0, 0], lu[0, 1])
            assert any(np.allclose(q[:2], p) for q in lu)
            assert any(np.allclose(q[:2], p) for q in lv)


@pytest.mark.parametrize("vcurves", [2, 3])
def test_patchprecision_rounding_shows_in_pixels(vcurves):
    """Rows bulge out along x as in test_curveprecision_sets_the_points_drawn
    (x = 4, 28, 28, 4: peak 22 at u = 1/2).  patchprecision(3, 3): with 2
    column curves the rows get 3 segments (reach 20), with 3 columns they get
    4 (a multiple of 2) and reach the peak."""
    X = [4, 28, 28, 4]
    gx = [X[:] for _ in range(4)]
    gy = [[3 + 6 * r] * 4 for r in range(4)]      # y = 3 + 18 v
    gz = [[0] * 4 for _ in range(4)]
    _window()
    _bases()
    patchbasis(BEZIER_ID, BEZIER_ID)
    patchcurves(2, vcurves)
    patchprecision(3, 3)
    patch(gx, gy, gz)
    nu = {2: 3, 3: 4}[vcurves]
    reach = _snap(max(curve_point(BEZ, [[x] for x in X], Fraction(k, nu))[0]
                      for k in range(nu + 1)))     # (rounding is monotonic: the
                                                   # farthest vertex gives the reach)
    want = _hline(4, reach, 3) | _hline(4, reach, 21)
    for k in range(vcurves):
        want |= _vline(_snap(curve_point(BEZ, [[x] for x in X], Fraction(k, vcurves - 1))[0]),
                       3, 21)
    assert reach == {2: 20, 3: 22}[vcurves]
    assert _lit() == want


# ----------------------------------------------------------------------------
# 4. errors and state

def test_crv_before_curvebasis_or_curveprecision_raises():
    _window()
    _bases()
    G = [(2, 5, 0), (8, 5, 0), (14, 5, 0), (20, 5, 0)]
    curveprecision(4)
    with pytest.raises(GLError, match=r"^crv"):
        crv(G)
    with pytest.raises(GLError, match=r"^crvn"):
        crvn(4, G)
    from irisgl._current import machine
    machine.reset()
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    with pytest.raises(GLError, match=r"^crv"):
        crv(G)
    assert _lit() == set()


def test_undefined_basis_raises_and_changes_nothing():
    _window()
    defbasis(BEZIER_ID, BEZ)
    curvebasis(BEZIER_ID)
    curveprecision(3)
    with pytest.raises(GLError, match=r"^curvebasis"):
        curvebasis(99)
    with pytest.raises(GLError, match=r"^patchbasis"):
        patchbasis(BEZIER_ID, 99)
    with pytest.raises(GLError, match=r"^patchbasis"):
        patchbasis(99, BEZIER_ID)
    # still the Bezier basis: the straight curve covers 2..20 (a B-spline of
    # the same points would cover 8..14)
    crv([(2, 5, 0), (8, 5, 0), (14, 5, 0), (20, 5, 0)])
    assert _lit() == _hline(2, 20, 5)
    # no patch basis was set by the failed calls
    patchcurves(2, 2)
    patchprecision(2, 2)
    with pytest.raises(GLError, match=r"^patch"):
        patch(*_flat_patch(2, 8, 3, 6))


def test_bad_arguments_raise():
    _window()
    _bases()
    with pytest.raises(GLError, match=r"^defbasis"):
        defbasis(9, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(GLError, match=r"^curveprecision"):
        curveprecision(0)
    with pytest.raises(GLError, match=r"^patchprecision"):
        patchprecision(0, 4)
    curvebasis(BEZIER_ID)
    curveprecision(2)
    pts = [(2, 5, 0), (8, 5, 0), (14, 5, 0), (20, 5, 0), (26, 5, 0)]
    with pytest.raises(GLError, match=r"^crvn"):
        crvn(3, pts)
    with pytest.raises(GLError, match=r"^crvn"):
        crvn(6, pts)
    with pytest.raises(GLError, match=r"^crv"):
        crv(pts[:3])                                # three points (five: the first four)
    assert _lit() == set()


def test_reset_forgets_curve_state():
    from irisgl._current import machine
    _window()
    _bases()
    curvebasis(BEZIER_ID)
    curveprecision(3)
    machine.reset()
    assert machine.curve_state is None
    _window()
    with pytest.raises(GLError):
        crv([(2, 5, 0), (8, 5, 0), (14, 5, 0), (20, 5, 0)])
    with pytest.raises(GLError):
        curvebasis(BEZIER_ID)                        # the basis went too


def test_defbasis_is_immediate_inside_makeobj():
    _window()
    makeobj(1)
    defbasis(5, BEZ)
    closeobj()
    curvebasis(5)                                    # defined at once, not at callobj


# ----------------------------------------------------------------------------
# 5. patch surfaces (emulator extension)

def _bumpy():
    rng = np.random.default_rng(3)
    gx = [[c + rng.uniform(-.3, .3) for c in range(4)] for _ in range(4)]
    gy = [[r + rng.uniform(-.3, .3) for _ in range(4)] for r in range(4)]
    gz = rng.uniform(-1.5, 1.5, (4, 4)).tolist()
    return gx, gy, gz


@pytest.mark.parametrize("name", ["bezier", "bspline"])
def test_patch_mesh_points_and_normals(name):
    M = BASES[name]
    G = _bumpy()
    p, n = patch_mesh(*G, usegs=6, vsegs=4, ubasis=M, vbasis=M)
    assert p.shape == n.shape == (5, 7, 3)
    assert np.allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-9)
    h = 1e-6
    for i in range(5):
        for j in range(7):
            u, v = j / 6, i / 4
            P = np.array(patch_point(M, M, G, u, v))
            assert np.allclose(p[i, j], P, atol=1e-12)
            # tangents by central differences of the formula
            tu = (np.array(patch_point(M, M, G, u + h, v)) -
                  np.array(patch_point(M, M, G, u - h, v))) / (2 * h)
            tv = (np.array(patch_point(M, M, G, u, v + h)) -
                  np.array(patch_point(M, M, G, u, v - h))) / (2 * h)
            assert abs(n[i, j] @ tu) / np.linalg.norm(tu) < 1e-6
            assert abs(n[i, j] @ tv) / np.linalg.norm(tv) < 1e-6
            assert n[i, j] @ np.cross(tu, tv) > 0          # cross(dP/du, dP/dv)


def test_patch_mesh_uses_the_current_patchbasis():
    G = _bumpy()
    _window()
    _bases()
    patchbasis(BEZIER_ID, BSPLINE_ID)
    patchcurves(3, 3)
    patchprecision(4, 4)
    p, _ = patch_mesh(*G, usegs=2, vsegs=2)
    assert np.allclose(p[1, 2], patch_point(BEZ, BSP, G, 1.0, 0.5))
    assert np.allclose(p[2, 1], patch_point(BEZ, BSP, G, 0.5, 1.0))


def test_degenerate_pole_gets_a_unit_normal():
    """The teapot's lid knob: row 0 of the patch is one point (the top)."""
    from programs.teapot_data import patch_geometry
    gx, gy, gz = patch_geometry()[20]
    p, n = patch_mesh(gx, gy, gz, 8, 8, BEZ, BEZ)
    assert np.allclose(p[0], p[0, 0])                       # the pole
    assert np.all(np.isfinite(n))
    assert np.allclose(np.linalg.norm(n, axis=-1), 1.0)
    assert np.all(n[0] @ np.array([0.0, 1.0, 0.0]) > 0.9)   # the top of the knob faces up


# ----------------------------------------------------------------------------
# 6. the teapot

def test_teapot_data_shape_and_symmetry():
    from programs import teapot_data as T
    assert len(T.PATCHES) == 32 and all(len(p) == 16 for p in T.PATCHES)
    assert len(T.POINTS) == 306
    assert all(0 <= i < 306 for p in T.PATCHES for i in p)
    geo = T.patch_geometry()
    assert len(geo) == 32
    allp = np.concatenate([np.stack(g, axis=-1).reshape(16, 3) for g in geo])
    # +y up: from the bottom (y = 0) to the top of the knob (3.15); spout at +x
    assert allp[:, 1].min() == pytest.approx(0.0) and allp[:, 1].max() == pytest.approx(3.15)
    assert allp[:, 0].max() == pytest.approx(3.525) and allp[:, 0].min() == pytest.approx(-3.0)
    # mirror symmetric about the vertical plane z = 0 (the classic y = 0)
    keys = {tuple(np.round(q, 6)) for q in allp}
    assert {tuple(np.round(q * [1, 1, -1], 6)) for q in allp} == keys
    # the bodies of revolution (rim, body, lid, bottom): each quarter patch is
    # the previous one turned by 90 degrees about the vertical axis
    for first in (0, 4, 8, 20, 24, 28):
        quarters = [np.stack(geo[first + k], axis=-1) for k in range(4)]
        for k in range(4):
            a, b = quarters[k], quarters[(k + 1) % 4]
            turned_l = np.stack((-a[..., 2], a[..., 1], a[..., 0]), axis=-1)
            turned_r = np.stack((a[..., 2], a[..., 1], -a[..., 0]), axis=-1)
            assert np.allclose(turned_l, b) or np.allclose(turned_r, b), (first, k)


def test_teapot_patches_face_outwards():
    """cross(dP/du, dP/dv) points away from the teapot's axis (or up/down at
    the lid and bottom) on every patch, so the surface needs no flip."""
    from programs.teapot_data import patch_geometry
    for k, (gx, gy, gz) in enumerate(patch_geometry()):
        p, n = patch_mesh(gx, gy, gz, 4, 4, BEZ, BEZ)
        c, nc = p[2, 2], n[2, 2]
        if 12 <= k < 20:                    # handle and spout: away from z = 0
            assert nc[2] * c[2] > 0, k
        elif k >= 28:                       # bottom: down
            assert nc[1] < -0.9, k
        elif k < 4 or 24 <= k < 28:         # rim and lid: up
            assert nc[1] > 0.9, k
        else:                               # body and knob: away from the axis
            assert nc[0] * c[0] + nc[2] * c[2] > 0, k


BACKGROUND = (0x10, 0x20, 0x40)


@pytest.fixture(scope="module")
def surface_image():
    return run_program(TEAPOT, frames=1)


@pytest.fixture(scope="module")
def wire_image():
    return run_program(TEAPOT, frames=1, argv=["--wire"])


def test_teapot_surface_is_drawn_and_lit_from_the_left(surface_image):
    img = surface_image
    assert img.shape == (480, 640, 3)
    mask = (img != BACKGROUND).any(axis=2)
    assert 30000 < mask.sum() < 90000                 # about 54000 pixels
    ys, xs = np.nonzero(mask)
    assert 100 < xs.min() and xs.max() < 600 and 80 < ys.min() and ys.max() < 420
    lum = img.astype(int).sum(axis=2)
    cx = xs.mean()
    cols = np.arange(img.shape[1])[None, :]
    left = lum[mask & (cols < cx)].mean()
    right = lum[mask & (cols > cx)].mean()
    assert left > 1.5 * right, (left, right)          # the light is at the upper left
    # the body's widest row: bright towards the left end, dark at the right end
    y = (ys.min() + ys.max()) // 2
    row = np.nonzero(mask[y])[0]
    assert lum[y, row.min() + 40] > 2 * lum[y, row.max() - 70]


def test_teapot_wire_is_patch_curves_of_the_same_teapot(wire_image, surface_image):
    img = wire_image
    mask = (img != BACKGROUND).any(axis=2)
    assert 5000 < mask.sum() < 25000                  # about 11000 pixels
    # curves only: one flat colour, no lighting
    assert {tuple(c) for c in img[mask].tolist()} == {(0xFF, 0xFF, 0x40)}
    # the same view: the web's extent matches the shaded silhouette
    ys, xs = np.nonzero(mask)
    smask = (surface_image != BACKGROUND).any(axis=2)
    sys_, sxs = np.nonzero(smask)
    for a, b in ((xs.min(), sxs.min()), (xs.max(), sxs.max()),
                 (ys.min(), sys_.min()), (ys.max(), sys_.max())):
        assert abs(int(a) - int(b)) <= 4
