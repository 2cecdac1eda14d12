"""NURBS curves and surfaces: nurbscurve(3G), nurbssurface(3G), bgntrim(3G),
pwlcurve(3G), set/getnurbsproperty(3G) (docs/nurbs.md).

Windows put pixel centres on integer coordinates (ortho2 from -0.5), so a
shape spanning x0..x1 covers the pixel centres x0 <= x < x1.  Expectations
are computed here: Bernstein polynomials typed in from their definition,
the sampling rule of docs/nurbs.md, pixel sets of plain polygons.
"""
import math
from pathlib import Path

import numpy as np
import pytest

from irisgl import *
from irisgl import GLError
from irisgl.nurbs import (bgncurve, bgnsurface, bgntrim, endcurve, endsurface, endtrim,
                          getnurbsproperty, nurbscurve, nurbssurface, pwlcurve,
                          setnurbsproperty)
from vgx_emulator import VGXWarning, run_program

ROOT = Path(__file__).resolve().parent.parent
DEMO = ROOT / "programs" / "demos" / "nurbs.py"
D = 8                                   # sizeof(double): offsets are in bytes
RED, GREEN, BLACK = 0xFF0000FF, 0xFF00FF00, 0xFF000000
BEZ = [[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]]


def _window(open_window, w=100, h=100):
    open_window(w, h)
    mmode(MVIEWING)
    ortho2(-0.5, w - 0.5, -0.5, h - 0.5)
    cpack(BLACK)
    clear()


def _quad(x0=10, y0=10, x1=90, y1=90, z=0.0, swap=False):
    """A bilinear (order 2) surface: s runs along x, t along y (or swapped)."""
    ctl = [[[x0, y0, z], [x0, y1, z]], [[x1, y0, z], [x1, y1, z]]]
    if swap:
        ctl = [[ctl[0][0], ctl[1][0]], [ctl[0][1], ctl[1][1]]]
    nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 3 * D, 3 * D, ctl, 2, 2, N_V3D)


def _image():
    return lrectread(0, 0, 99, 99)


def _box(x0, y0, x1, y1):
    """Pixels whose centres lie in [x0, x1) x [y0, y1)."""
    m = np.zeros((100, 100), bool)
    m[y0:y1, x0:x1] = True
    return m


# -- properties ----------------------------------------------------------------
def test_property_defaults_are_the_man_page_ones(open_window):
    open_window()
    assert getnurbsproperty(N_PIXEL_TOLERANCE) == 50.0
    assert getnurbsproperty(N_DISPLAY) == N_FILL
    assert getnurbsproperty(N_ERRORCHECKING) == 0.0
    assert getnurbsproperty(N_CULLING) == 0.0


@pytest.mark.parametrize("prop, value", [(N_PIXEL_TOLERANCE, 12.5), (N_DISPLAY, N_OUTLINE_POLY),
                                         (N_DISPLAY, N_OUTLINE_PATCH), (N_DISPLAY, N_ISOLINE_S),
                                         (N_ERRORCHECKING, 1.0), (N_CULLING, 1.0),
                                         (N_S_STEPS, 7.0)])
def test_properties_round_trip(open_window, prop, value):
    open_window()
    setnurbsproperty(prop, value)
    assert getnurbsproperty(prop) == value


def test_properties_are_per_window(open_window):
    a = open_window()
    setnurbsproperty(N_PIXEL_TOLERANCE, 5.0)
    open_window()
    assert getnurbsproperty(N_PIXEL_TOLERANCE) == 50.0
    winset(a)
    assert getnurbsproperty(N_PIXEL_TOLERANCE) == 5.0


@pytest.mark.parametrize("prop, value", [(N_PIXEL_TOLERANCE, 0.0), (N_PIXEL_TOLERANCE, -3.0),
                                         (N_PIXEL_TOLERANCE, math.nan), (N_DISPLAY, 3.0),
                                         (99, 1.0), (N_TMP1, 1.0)])
def test_bad_properties_raise_and_change_nothing(open_window, prop, value):
    open_window()
    with pytest.raises(GLError, match="^setnurbsproperty: "):
        setnurbsproperty(prop, value)
    assert getnurbsproperty(N_PIXEL_TOLERANCE) == 50.0
    assert getnurbsproperty(N_DISPLAY) == N_FILL


def test_property_calls_need_a_window():
    with pytest.raises(GLError, match="^getnurbsproperty: no window"):
        getnurbsproperty(N_DISPLAY)


# -- curves --------------------------------------------------------------------
CTL4 = [(10, 10, 0), (30, 90, 0), (70, -30, 0), (90, 60, 0)]


def _segments(pts, tol):
    """docs/nurbs.md: ceil(control-polygon length in pixels / N_PIXEL_TOLERANCE)."""
    p = np.array(pts, float)[:, :2]
    return math.ceil(np.linalg.norm(np.diff(p, axis=0), axis=1).sum() / tol)


@pytest.mark.parametrize("tol", [50.0, 10.0, 2.0])
def test_cubic_with_bezier_knots_is_the_bezier_crv(open_window, tol):
    """Order 4 with knots 0,0,0,0,1,1,1,1 is the cubic Bezier: it draws the
    pixels crv() draws with the Bezier basis at the same precision."""
    _window(open_window)
    cpack(RED)
    setnurbsproperty(N_PIXEL_TOLERANCE, tol)
    bgncurve()
    nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * D, CTL4, 4, N_V3D)
    endcurve()
    got = _image()
    cpack(BLACK)
    clear()
    cpack(RED)
    defbasis(1, BEZ)
    curvebasis(1)
    curveprecision(_segments(CTL4, tol))
    crv(CTL4)
    want = _image()
    assert (got == RED).sum() > 80
    assert np.array_equal(got, want)


def test_curve_passes_through_bernstein_points(open_window):
    _window(open_window)
    cpack(RED)
    setnurbsproperty(N_PIXEL_TOLERANCE, 1.0)
    bgncurve()
    nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * D, CTL4, 4, N_V3D)
    endcurve()
    img = _image()
    p = np.array(CTL4, float)
    for t in (0.0, 0.25, 0.5, 0.75, 1.0):
        b = np.array([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3])
        x, y = b @ p[:, :2]
        near = img[int(round(y)) - 1:int(round(y)) + 2, int(round(x)) - 1:int(round(x)) + 2]
        assert (near == RED).any(), (t, x, y)


def test_rational_quadratic_is_a_circular_arc(open_window):
    """N_V3DR: (wx, wy, wz, w); weights 1, sqrt(2)/2, 1 make a quarter circle."""
    _window(open_window)
    cpack(RED)
    setnurbsproperty(N_PIXEL_TOLERANCE, 1.0)
    r, c = 80.0, 10.0
    h = math.sqrt(0.5)
    ctl = [(c + r, c, 0, 1), ((c + r) * h, (c + r) * h, 0, h), (c, c + r, 0, 1)]
    bgncurve()
    nurbscurve(6, [0, 0, 0, 1, 1, 1], 4 * D, ctl, 3, N_V3DR)
    endcurve()
    ys, xs = np.nonzero(_image() == RED)
    d = np.hypot(xs - c, ys - c)
    assert len(d) > 100
    assert np.all(np.abs(d - r) < 1.5)


def test_multi_span_curve_with_order_2_is_its_control_polygon(open_window):
    """Order 2 (linear) through 3 points: the polyline itself, like bgnline."""
    _window(open_window)
    cpack(RED)
    pts = [(10, 10, 0), (50, 80, 0), (90, 20, 0)]
    bgncurve()
    nurbscurve(5, [0, 0, 1, 2, 2], 3 * D, pts, 2, N_V3D)
    endcurve()
    got = _image()
    cpack(BLACK)
    clear()
    cpack(RED)
    bgnline()
    for p in pts:
        v3f(p)
    endline()
    assert np.array_equal(got, _image())


def test_offsets_are_bytes_of_the_c_array(open_window):
    """offset = sizeof of a struct {double tag; double x, y, z; double pad}:
    ctlarray starts at the first x, as &points[0].x in C."""
    _window(open_window)
    cpack(RED)
    bgncurve()
    nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * D, CTL4, 4, N_V3D)
    endcurve()
    want = _image()
    cpack(BLACK)
    clear()
    cpack(RED)
    rec = np.zeros((4, 5))
    rec[:, 1:4] = CTL4
    rec[:, 0] = -99.0
    bgncurve()
    nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 5 * D, rec.ravel()[1:], 4, N_V3D)
    endcurve()
    assert np.array_equal(_image(), want)
    cpack(BLACK)
    clear()
    cpack(RED)
    f32 = np.array(CTL4, np.float32)             # a float array: 4-byte elements
    bgncurve()
    nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * 4, f32, 4, N_V3D)
    endcurve()
    assert np.array_equal(_image(), want)


# -- surfaces --------------------------------------------------------------------
def test_bilinear_surface_fills_exactly_its_quad(open_window):
    _window(open_window)
    cpack(RED)
    bgnsurface()
    _quad()
    endsurface()
    img = _image()
    assert np.array_equal(img == RED, _box(10, 10, 90, 90))


def test_bicubic_bezier_surface_of_a_plane_fills_its_square(open_window):
    """A 4x4 control net spread evenly over a square is that square (a
    Bezier patch reproduces linear functions), at any tessellation."""
    _window(open_window)
    cpack(RED)
    g = np.linspace(20, 80, 4)
    ctl = np.array([[[x, y, 0.0] for y in g] for x in g])
    k = [0, 0, 0, 0, 1, 1, 1, 1]
    bgnsurface()
    nurbssurface(8, k, 8, k, 4 * 3 * D, 3 * D, ctl, 4, 4, N_V3D)
    endsurface()
    assert np.array_equal(_image() == RED, _box(20, 20, 80, 80))


def _light():
    lmdef(DEFMATERIAL, 1, 0, [LMNULL])
    lmdef(DEFLIGHT, 1, 0, [LMNULL])           # directional, from +z
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)


def test_normals_come_from_the_surface_derivatives(open_window):
    """dS/ds x dS/dt: s along x, t along y faces +z (lit like a polygon with
    n3f(0, 0, 1)); with s and t swapped it faces -z (ambient only)."""
    _window(open_window)
    _light()
    bgnsurface()
    _quad(10, 10, 45, 90)
    endsurface()
    bgnsurface()
    _quad(55, 10, 90, 90, swap=True)
    endsurface()
    img = _image()
    front, back = int(img[50, 30]), int(img[50, 70])
    cpack(BLACK)
    clear()
    for nz, x0 in ((1.0, 10), (-1.0, 55)):
        bgnpolygon()
        n3f((0.0, 0.0, nz))
        for p in ((x0, 10, 0), (x0 + 35, 10, 0), (x0 + 35, 90, 0), (x0, 90, 0)):
            v3f(p)
        endpolygon()
    ref = _image()
    assert front == int(ref[50, 30]) and back == int(ref[50, 70])
    # default material and light: 0.2 * 0.2 ambient + 0.8 diffuse; ambient only
    assert abs((front & 0xFF) - round(0.84 * 255)) <= 1
    assert abs((back & 0xFF) - round(0.04 * 255)) <= 1


def test_curved_surface_shades_with_its_normal(open_window):
    """A half cylinder (rational quadratic in s, bulging to +z): the lit
    colour falls off towards its silhouette as n.z = cos of the angle."""
    _window(open_window)
    ortho(-0.5, 99.5, -0.5, 99.5, -100, 100)
    _light()
    h = math.sqrt(0.5)
    r, cx = 40.0, 50.0
    prof = [(cx - r, 0, 1), (cx - r, r, 1), (cx, r, 1), (cx + r, r, 1), (cx + r, 0, 1)]
    wts = [1, h, 1, h, 1]
    ctl = np.array([[[x * w, y * w, z * w, w] for y in (10, 90)]
                    for (x, z, _), w in zip(prof, wts)])
    setnurbsproperty(N_PIXEL_TOLERANCE, 2.0)
    bgnsurface()
    nurbssurface(8, [0, 0, 0, 1, 1, 2, 2, 2], 4, [0, 0, 1, 1], 2 * 4 * D, 4 * D, ctl, 3, 2,
                 N_V3DR)
    endsurface()
    img = _image()
    for x in (50, 70, 85):
        nz = math.sqrt(max(0.0, 1 - ((x - cx) / r) ** 2))
        want = (0.04 + 0.8 * nz) * 255
        assert abs((int(img[50, x]) & 0xFF) - want) <= 4, (x, img[50, x] & 0xFF, want)


def test_colour_surface_colours_the_vertices(open_window):
    """N_C4D: RGBA 0.0-1.0 across s: red at s = 0, green at s = 1."""
    _window(open_window)
    bgnsurface()
    col = [[[1, 0, 0, 1], [1, 0, 0, 1]], [[0, 1, 0, 1], [0, 1, 0, 1]]]
    nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 4 * D, 4 * D, col, 2, 2, N_C4D)
    _quad()
    endsurface()
    img = _image()
    left, right, mid = int(img[50, 10]), int(img[50, 89]), int(img[50, 50])
    assert (left & 0xFF) > 240 and ((left >> 8) & 0xFF) < 15
    assert ((right >> 8) & 0xFF) > 240 and (right & 0xFF) < 15
    assert abs((mid & 0xFF) - 127) < 8 and abs(((mid >> 8) & 0xFF) - 127) < 8


def test_colour_surface_in_cmode_is_an_error(open_window):
    open_window(rgb=False)
    bgnsurface()
    col = [[[1, 0, 0, 1], [1, 0, 0, 1]], [[0, 1, 0, 1], [0, 1, 0, 1]]]
    with pytest.raises(GLError, match="^nurbssurface: .*colour-map"):
        nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 4 * D, 4 * D, col, 2, 2, N_C4D)


def test_surface_uses_the_zbuffer(open_window):
    _window(open_window)
    zbuffer(TRUE)
    zclear()
    cpack(GREEN)
    bgnsurface()
    _quad(10, 10, 90, 90, z=0.5)          # nearer: ortho2 looks down -z
    endsurface()
    cpack(RED)
    bgnsurface()
    _quad(30, 30, 70, 70, z=-0.5)
    endsurface()
    assert np.array_equal(_image() == GREEN, _box(10, 10, 90, 90))


def test_display_list_replays_the_surface(open_window):
    _window(open_window)
    cpack(RED)
    ctl = np.array([[[10, 10, 0], [10, 90, 0]], [[90, 10, 0], [90, 90, 0]]], float)
    makeobj(1)
    bgnsurface()
    nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 3 * D, 3 * D, ctl, 2, 2, N_V3D)
    endsurface()
    closeobj()
    ctl[:] = 0                             # values were copied at the call
    assert (_image() == RED).sum() == 0    # nothing drawn while compiling
    callobj(1)
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))


# -- trimming --------------------------------------------------------------------
OUTER = [(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)]            # counter-clockwise
HOLE = [(0.4, 0.4), (0.4, 0.6), (0.6, 0.6), (0.6, 0.4), (0.4, 0.4)]   # clockwise


def _trimmed(*loops, display=None, trims_first=False):
    if display is not None:
        setnurbsproperty(N_DISPLAY, display)
    bgnsurface()
    if not trims_first:
        _quad()
    for lp in loops:
        bgntrim()
        pwlcurve(len(lp), lp, 2 * D, N_ST)
        endtrim()
    if trims_first:
        _quad()
    endsurface()


def test_trim_hole_leaves_the_background(open_window):
    """Outer loop counter-clockwise, hole clockwise (bgntrim(3G)): the hole
    (s, t) in [0.4, 0.6]^2 maps to pixels 42..58; straight trims are exact."""
    _window(open_window)
    cpack(RED)
    _trimmed(OUTER, HOLE)
    img = _image()
    assert int(img[50, 50]) == BLACK
    assert np.array_equal(img == RED, _box(10, 10, 90, 90) & ~_box(42, 42, 58, 58))


def test_trims_may_come_before_the_surface(open_window):
    """bgnsurface(3G) lists no order between the shape and the trimming
    loops (SGI's sgiflag trims first): the same pixels either way."""
    _window(open_window)
    cpack(RED)
    _trimmed(OUTER, HOLE, trims_first=True)
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90) & ~_box(42, 42, 58, 58))


def test_counter_clockwise_loop_alone_keeps_its_inside(open_window):
    _window(open_window)
    cpack(RED)
    _trimmed(HOLE[::-1])
    assert np.array_equal(_image() == RED, _box(42, 42, 58, 58))


def test_clockwise_loop_alone_keeps_the_outside(open_window):
    """The region to the left of a lone clockwise loop is its outside."""
    _window(open_window)
    cpack(RED)
    _trimmed(HOLE)
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90) & ~_box(42, 42, 58, 58))


def test_nurbs_trim_curve_cuts_a_round_hole(open_window):
    """A clockwise circle of radius 0.2 in (s, t) as four rational quadratic
    pieces (N_P2DR, (ws, wt, w)): pixels near the centre are background,
    pixels beyond the circle are drawn."""
    _window(open_window)
    cpack(RED)
    h = math.sqrt(0.5)
    c, r = 0.5, 0.2
    # clockwise: from the top, through the right, bottom, left
    corners = [(0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1), (0, 1)]
    bgnsurface()
    _quad()
    bgntrim()
    pwlcurve(5, OUTER, 2 * D, N_ST)
    endtrim()
    bgntrim()
    for i in range(0, 8, 2):
        pts = []
        for j, wt in zip(range(i, i + 3), (1, h, 1)):
            dx, dy = corners[j]
            pts.append((wt * (c + r * dx), wt * (c + r * dy), wt))
        nurbscurve(6, [0, 0, 0, 1, 1, 1], 3 * D, pts, 3, N_P2DR)
    endtrim()
    endsurface()
    img = _image()
    ys, xs = np.mgrid[0:100, 0:100]
    d = np.hypot(xs - 50, ys - 50)                     # radius 0.2 -> 16 pixels
    assert np.all(img[d < 13] == BLACK)
    inside_quad = _box(10, 10, 90, 90)
    assert np.all(img[(d > 19) & inside_quad] == RED)


def test_errorchecking_refuses_an_open_loop(open_window):
    _window(open_window)
    setnurbsproperty(N_ERRORCHECKING, 1.0)
    bgnsurface()
    _quad()
    bgntrim()
    pwlcurve(4, OUTER, 2 * D, N_ST)              # last point missing
    with pytest.raises(GLError, match="^endtrim: .*not closed"):
        endtrim()
    pwlcurve(2, [(0, 1), (0, 0)], 2 * D, N_ST)   # still inside the loop: close it
    endtrim()
    cpack(RED)
    endsurface()
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))


def test_without_errorchecking_an_open_loop_is_closed(open_window):
    _window(open_window)
    cpack(RED)
    _trimmed(OUTER[:-1])
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))


# -- display modes -----------------------------------------------------------------
def test_outline_patch_draws_the_patch_border_only(open_window):
    _window(open_window)
    cpack(RED)
    _trimmed(display=N_OUTLINE_PATCH)
    drawn = _image() == RED
    border = _box(9, 9, 92, 92) & ~_box(12, 12, 89, 89)
    assert drawn.sum() > 4 * 70
    assert not (drawn & ~border).any()
    assert drawn[10, 50] and drawn[90, 50] and drawn[50, 10] and drawn[50, 90]


def test_outline_patch_draws_the_trim_curves(open_window):
    _window(open_window)
    cpack(RED)
    _trimmed(OUTER, HOLE, display=N_OUTLINE_PATCH)
    drawn = _image() == RED
    assert drawn[42, 50] and drawn[58, 50] and drawn[50, 42] and drawn[50, 58]
    assert not drawn[50, 50] and not drawn[30, 30]


def test_outline_poly_draws_the_tessellation(open_window):
    """80 pixels at N_PIXEL_TOLERANCE 50: two cells along each side, so the
    grid line s = 0.5 (x = 50) and the cell diagonals are drawn."""
    _window(open_window)
    cpack(RED)
    _trimmed(display=N_OUTLINE_POLY)
    drawn = _image() == RED
    assert drawn[30, 50] and drawn[70, 50] and drawn[50, 30]
    assert drawn[30, 30]                        # a diagonal of the first cell
    assert not drawn[20, 40]
    assert drawn.sum() < 0.25 * 80 * 80


def test_isoline_s_draws_lines_of_constant_s(open_window):
    _window(open_window)
    cpack(RED)
    _trimmed(display=N_ISOLINE_S)
    drawn = _image() == RED
    assert drawn[30, 10] and drawn[30, 50] and drawn[30, 90]
    assert not drawn[10, 30] and not drawn[50, 30]


def test_pixel_tolerance_sets_the_tessellation(open_window):
    _window(open_window)
    cpack(RED)
    setnurbsproperty(N_PIXEL_TOLERANCE, 20.0)          # 80 / 20: four cells
    _trimmed(display=N_ISOLINE_S)
    drawn = _image() == RED
    assert all(drawn[50, x] for x in (10, 30, 50, 70, 90))
    assert not drawn[50, 40]


def test_culling_drops_a_surface_outside_the_viewport(open_window):
    _window(open_window)
    cpack(RED)
    setnurbsproperty(N_CULLING, 1.0)
    bgnsurface()
    _quad(200, 10, 300, 90)
    endsurface()
    bgnsurface()
    _quad()
    endsurface()
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))


# -- misuse -------------------------------------------------------------------------
def test_nurbssurface_outside_bgnsurface(open_window):
    _window(open_window)
    with pytest.raises(GLError, match="^nurbssurface: outside"):
        _quad()


@pytest.mark.parametrize("args, what", [
    ((3, [0, 0, 1], 4, [0, 0, 1, 1], 48, 24, None, 2, 2, N_V3D), "knots for order"),
    ((4, [0, 1, 0, 1], 4, [0, 0, 1, 1], 48, 24, None, 2, 2, N_V3D), "decrease"),
    ((4, [0, 0, 0, 0], 4, [0, 0, 1, 1], 48, 24, None, 2, 2, N_V3D), "empty"),
    ((4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 48, 20, None, 2, 2, N_V3D), "multiple of 8"),
    ((4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 96, 24, None, 2, 2, N_V3D), "ctlarray has"),
    ((4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 48, 24, None, 2, 2, N_P2D), "type"),
    ((4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 48, 24, None, 9, 2, N_V3D), "order 9"),
    ((4, [0, 0, 1], 4, [0, 0, 1, 1], 48, 24, None, 2, 2, N_V3D), "knot array has"),
])
def test_bad_nurbssurface_raises_and_keeps_the_definition_open(open_window, args, what):
    _window(open_window)
    ctl = [[[10, 10, 0], [10, 90, 0]], [[90, 10, 0], [90, 90, 0]]]
    args = tuple(ctl if a is None else a for a in args)
    bgnsurface()
    with pytest.raises(GLError, match=f"^nurbssurface: .*{what}"):
        nurbssurface(*args)
    cpack(RED)
    _quad()                                 # the definition is still open and empty
    endsurface()
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))


def test_definition_order_errors(open_window):
    _window(open_window)
    with pytest.raises(GLError, match="^endsurface: outside"):
        endsurface()
    with pytest.raises(GLError, match="^pwlcurve: outside"):
        pwlcurve(5, OUTER, 2 * D, N_ST)
    with pytest.raises(GLError, match="^nurbscurve: outside"):
        nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * D, CTL4, 4, N_V3D)
    bgnsurface()
    with pytest.raises(GLError, match="^bgnsurface: inside bgnsurface"):
        bgnsurface()
    with pytest.raises(GLError, match="^bgncurve: inside bgnsurface"):
        bgncurve()
    with pytest.raises(GLError, match="^endsurface: no nurbssurface"):
        endsurface()
    _quad()
    with pytest.raises(GLError, match="^nurbssurface: a second"):
        _quad()
    bgntrim()
    with pytest.raises(GLError, match="^nurbscurve: type"):
        nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 3 * D, CTL4, 4, N_V3D)
    with pytest.raises(GLError, match="^pwlcurve: type"):
        pwlcurve(5, OUTER, 2 * D, N_V3D)
    with pytest.raises(GLError, match="^endsurface: inside bgntrim"):
        endsurface()
    with pytest.raises(GLError, match="^endtrim: an empty"):
        endtrim()
    pwlcurve(5, OUTER, 2 * D, N_ST)
    endtrim()
    endsurface()
    bgncurve()
    with pytest.raises(GLError, match="^nurbscurve: type"):
        nurbscurve(8, [0, 0, 0, 0, 1, 1, 1, 1], 2 * D, CTL4, 4, N_P2D)
    endcurve()


def test_not_allowed_inside_bgnpolygon(open_window):
    _window(open_window)
    bgnpolygon()
    with pytest.raises(GLError, match="^bgnsurface: not allowed inside bgnpolygon"):
        bgnsurface()
    endpolygon()


def test_nan_control_point_is_dropped_with_a_warning(open_window):
    _window(open_window)
    cpack(RED)
    bgnsurface()
    ctl = [[[10, 10, 0], [10, 90, 0]], [[90, 10, 0], [math.nan, 90, 0]]]
    nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 3 * D, 3 * D, ctl, 2, 2, N_V3D)
    with pytest.warns(VGXWarning, match="nurbssurface"):
        endsurface()
    assert (_image() == RED).sum() == 0


# -- the demo ------------------------------------------------------------------------
def test_demo_draws_a_lit_surface_with_a_hole():
    img = run_program(str(DEMO), 1, [])
    assert img is not None
    h, w, _ = img.shape
    lum = img.astype(int).sum(axis=2)
    cy, cx = h // 2, w // 2
    # the hole at the centre shows the background; the surface around it is lit
    assert lum[cy, cx] == lum[5, 5]
    ring = lum[cy, cx + w // 5]
    assert ring > lum[5, 5] + 60
    # shading varies across the curved surface
    row = lum[cy, w // 6: 5 * w // 6]
    assert row.max() - row[row > lum[5, 5] + 30].min() > 30


def test_non_finite_trim_and_attribute_data_never_crash(open_window):
    _window(open_window)
    cpack(RED)
    bgnsurface()
    _quad()
    bgntrim()
    with pytest.warns(VGXWarning, match="nurbscurve"):
        nurbscurve(6, [0, 0, 0, 1, 1, math.inf], 2 * D, [(0, 0), (1, 0), (0, 0)], 3, N_P2D)
    pwlcurve(3, [(0, 0), (math.nan, 0), (0, 1)], 2 * D, N_ST)
    with pytest.warns(VGXWarning, match="pwlcurve"):
        endtrim()
    endsurface()                                  # the bad loop is dropped: untrimmed
    assert np.array_equal(_image() == RED, _box(10, 10, 90, 90))
    bgnsurface()
    nurbssurface(4, [0, 0, 1, math.nan], 4, [0, 0, 1, 1], 2 * 2 * D, 2 * D, [0.0] * 8, 2, 2,
                 N_T2D)
    _quad()
    with pytest.warns(VGXWarning, match="nurbssurface"):
        endsurface()


def test_texture_surface_gives_the_texture_coordinates(open_window):
    """N_T2D: (s, t) texture coordinates across the surface; a 2 x 1 texture
    red | green shows red on the left half, green on the right."""
    _window(open_window)
    texdef2d(1, 4, 2, 1, [RED, GREEN], 0,
             [TX_MINFILTER, TX_POINT, TX_MAGFILTER, TX_POINT, TX_NULL])
    tevdef(1, 0, [TV_MODULATE, TV_NULL])
    tevbind(TV_ENV0, 1)
    texbind(TX_TEXTURE_0, 1)
    cpack(0xFFFFFFFF)
    bgnsurface()
    tc = [[[0, 0], [0, 1]], [[1, 0], [1, 1]]]
    nurbssurface(4, [0, 0, 1, 1], 4, [0, 0, 1, 1], 2 * 2 * D, 2 * D, tc, 2, 2, N_T2D)
    _quad()
    endsurface()
    img = _image()
    assert np.all(img[10:90, 10:49] == RED) and np.all(img[10:90, 51:90] == GREEN)
    t2f((0.25, 0.5))                       # without a texture surface: the current one
    bgnsurface()
    _quad()
    endsurface()
    assert np.all(_image()[10:90, 10:90] == RED)
