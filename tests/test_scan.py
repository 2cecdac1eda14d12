"""Scan conversion: exact pixel sets against the reference model.

Expected pixel sets come from ``tests/reference/raster.py`` (the documented
fill rule, computed with fractions), never from the emulator.  Window
coordinates equal object coordinates through ``ortho2(-0.5, w-0.5, -0.5,
h-0.5)`` (docs/semantics.md §2), so a vertex given at (x, y) lands at window (x, y).
Watertightness is checked two ways: each triangle drawn alone equals its
reference set, and the whole mesh drawn in one batch with additive blending
(``blendfunction(BF_ONE, BF_ONE)``, red 1 per triangle) counts every pixel
exactly as often as the reference coverages do (0 or 1).
"""
import random
from functools import partial

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from irisgl import (FALSE, FLAT, GOURAUD, TRUE, BF_ONE, BF_ZERO, backface, bgnclosedline,
                    bgnline, bgnpoint, bgnpolygon, bgnqstrip, bgntmesh, blendfunction,
                    c3i, clear, concave, cpack, draw2i, endclosedline, endline,
                    endpoint, endpolygon, endqstrip, endtmesh, frontface, gconfig,
                    lrectread, move2i, ortho2, pnt2, polf, polf2, polf2i, polf2s, prefsize,
                    rectf, rectfi, rectfs, RGBmode, shademodel, subpixel,
                    swaptmesh, v2f, winopen)
from banks import new_window
from reference import raster as ref

W, H = 32, 32


_window = partial(new_window, W, H, pixels=True)   # pixel (i, j)'s centre at (i, j)


def _read(w=W, h=H):
    return lrectread(0, 0, w - 1, h - 1)


def _pixels(img):
    ys, xs = np.nonzero(img)
    return set(zip(xs.tolist(), ys.tolist()))


def _blank():
    blendfunction(BF_ONE, BF_ZERO)
    cpack(0)
    clear()


def _polygon(vs, colour=0xFFFFFFFF):
    cpack(colour)
    bgnpolygon()
    for v in vs:
        v2f(v)
    endpolygon()


def _alone(vs, w=W, h=H):
    """Pixel set of one polygon drawn alone."""
    _blank()
    _polygon(vs)
    return _pixels(_read(w, h))


def _counts(polys, w=W, h=H):
    """Per-pixel number of times the polygons are drawn (one batch, additive)."""
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(0x00000001)
    for vs in polys:
        bgnpolygon()
        for v in vs:
            v2f(v)
        endpolygon()
    img = _read(w, h)
    blendfunction(BF_ONE, BF_ZERO)
    return (img & 0xFF).astype(int)


def _count_array(sets, w=W, h=H):
    a = np.zeros((h, w), int)
    for s in sets:
        for x, y in s:
            a[y, x] += 1
    return a


def _q(k):
    """A float on the 1/256 grid (exact in binary)."""
    return k / 256.0


def _check_mesh(tris, subpix=True):
    """Every triangle alone equals the model; the model's coverages are
    disjoint; one additive batch of all of them counts exactly the model."""
    placed = [ref.place(t, subpix) for t in tris]
    expected = [ref.triangle_pixels(*p, W, H) for p in placed]
    for t, e in zip(tris, expected):
        assert _alone(t) == e, t
    model = _count_array(expected)
    assert model.max() <= 1, "reference coverages overlap"
    got = _counts(tris)
    np.testing.assert_array_equal(got, model)
    return model


def _ascii(rows):
    """ASCII art (top row first, '#' = drawn) -> pixel set."""
    out = set()
    h = len(rows)
    for r, line in enumerate(rows):
        for x, ch in enumerate(line):
            if ch == "#":
                out.add((x, h - 1 - r))
    return out


# --------------------------------------------------------------------------
# the reference model itself (so that a wrong model cannot hide a bug)

def test_reference_model_small_triangle_ascii():
    """CCW triangle (1,1) (6,1) (1,6): bottom and left edges are owned, the
    hypotenuse x + y = 7 is not."""
    got = ref.triangle_pixels((1, 1), (6, 1), (1, 6), 8, 8)
    assert got == _ascii([
        "........",
        "........",
        ".#......",
        ".##.....",
        ".###....",
        ".####...",
        ".#####..",
        "........",
    ])


def test_reference_model_shared_edges_partition_a_square():
    a, b, c, d = (0, 0), (5, 0), (5, 5), (0, 5)
    t1 = ref.triangle_pixels(a, b, c, 8, 8)
    t2 = ref.triangle_pixels(a, c, d, 8, 8)
    assert not (t1 & t2)
    assert t1 | t2 == ref.rect_pixels(0, 4, 0, 4)
    # orientation does not change the set
    assert ref.triangle_pixels(a, c, b, 8, 8) == t1


# --------------------------------------------------------------------------
# default projection

def test_default_projection_maps_pixel_centres():
    new_window(W, H)                   # the matrices winopen leaves
    assert _alone([(2, 3), (10, 3), (10, 8), (2, 8)]) == ref.rect_pixels(2, 9, 3, 7)


# --------------------------------------------------------------------------
# squares, rectangles

@pytest.mark.parametrize("subpix", [False, True])
@pytest.mark.parametrize("x0,y0,w,h", [(0, 0, 32, 32), (3, 5, 7, 11), (10, 2, 1, 1),
                                       (4, 4, 20, 1), (6, 1, 1, 25)])
@pytest.mark.parametrize("diag", [0, 1])
def test_square_split_in_two_covers_exactly_w_times_h(subpix, x0, y0, w, h, diag):
    _window()
    subpixel(TRUE if subpix else FALSE)
    a, b, c, d = (x0, y0), (x0 + w, y0), (x0 + w, y0 + h), (x0, y0 + h)
    tris = [(a, b, c), (a, c, d)] if diag == 0 else [(a, b, d), (b, c, d)]
    model = _check_mesh(tris, subpix)
    assert model.sum() == w * h
    assert _pixels(model) == ref.rect_pixels(x0, x0 + w - 1, y0, y0 + h - 1)


def test_rectangle_ascii():
    """A 3x2 rectangle with corners on pixel centres: left and bottom edges in,
    right and top edges out."""
    new_window(8, 6, pixels=True)
    got = _alone([(2, 1), (5, 1), (5, 3), (2, 3)], 8, 6)
    assert got == _ascii([
        "........",
        "........",
        "........",
        "..###...",
        "..###...",
        "........",
    ])


# --------------------------------------------------------------------------
# single triangles against the model

coord = st.integers(min_value=-6 * 256, max_value=(W + 6) * 256)


@settings(max_examples=80, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.tuples(coord, coord), min_size=3, max_size=3))
def test_subpixel_triangle_equals_reference(pts):
    from irisgl._current import machine
    if machine.current is None:
        _window()
    subpixel(TRUE)
    tri = [(_q(x), _q(y)) for x, y in pts]
    assert _alone(tri) == ref.triangle_pixels(*ref.place(tri, True), W, H)


@settings(max_examples=40, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.tuples(coord, coord), min_size=3, max_size=3))
def test_snapped_triangle_equals_reference(pts):
    from irisgl._current import machine
    if machine.current is None:
        _window()
    subpixel(FALSE)
    # 1/256 grid values never tie at .5 after the float ortho mapping except
    # exact halves; move those off the tie (the rounding of a tie is not the
    # subject here)
    tri = [(_q(x + (128 == x % 256)), _q(y + (128 == y % 256))) for x, y in pts]
    assert _alone(tri) == ref.triangle_pixels(*ref.place(tri, False), W, H)


def test_triangle_with_vertices_on_pixel_centres_both_windings():
    _window()
    subpixel(TRUE)
    tri = [(3, 2), (20, 9), (7, 25)]
    expected = ref.triangle_pixels(*tri, W, H)
    assert _alone(tri) == expected
    assert _alone(tri[::-1]) == expected


# --------------------------------------------------------------------------
# watertightness

def _fan_tris(centre, ring, closed=True):
    n = len(ring)
    m = n if closed else n - 1
    return [(centre, ring[k], ring[(k + 1) % n]) for k in range(m)]


@pytest.mark.parametrize("seed", range(6))
def test_fan_around_a_subpixel_centre_is_watertight(seed):
    _window()
    subpixel(TRUE)
    rnd = random.Random(seed)
    cx, cy = rnd.randint(12 * 256, 20 * 256), rnd.randint(12 * 256, 20 * 256)
    n = rnd.randint(5, 13)
    # keep every wedge below 180 degrees so the fan is a partition
    angles = [2 * np.pi * k / n + rnd.uniform(-0.2, 0.2) for k in range(n)]
    ring = []
    for a in angles:
        r = rnd.uniform(6, 22) * 256
        ring.append((_q(round(cx + r * np.cos(a))), _q(round(cy + r * np.sin(a)))))
    centre = (_q(cx), _q(cy))
    model = _check_mesh(_fan_tris(centre, ring))
    assert model.sum() > 100


def test_fan_on_pixel_centres_with_axis_aligned_spokes():
    """Centre and ring on pixel centres; spokes horizontal, vertical and
    diagonal: many centres lie exactly on shared edges."""
    _window()
    subpixel(TRUE)
    c = (16, 16)
    ring = [(28, 16), (28, 28), (16, 28), (4, 28), (4, 16), (4, 4), (16, 4), (28, 4)]
    model = _check_mesh(_fan_tris(c, ring))
    # the union is the square [4, 28) x [4, 28)
    assert _pixels(model) == ref.rect_pixels(4, 27, 4, 27)


def test_fan_as_tmesh_with_swaptmesh_is_watertight():
    _window()
    subpixel(TRUE)
    c = (15.25, 16.75)
    ring = [(27.5, 16.0), (25.0, 26.25), (15.0, 29.5), (5.75, 24.0), (3.0, 15.5),
            (6.5, 5.0), (16.0, 2.25), (26.0, 6.5)]
    pts = [c] + ring + [ring[0]]
    events = [0, 1] + [e for k in range(2, len(pts)) for e in ("swap", k)]
    idx_tris = ref.tmesh_triangles(events)
    assert idx_tris == [(0, k - 1, k) for k in range(2, len(pts))]      # a fan
    expected = [ref.triangle_pixels(*ref.place([pts[i] for i in t]), W, H) for t in idx_tris]
    model = _count_array(expected)
    assert model.max() == 1
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(1)
    bgntmesh()
    v2f(pts[0])
    v2f(pts[1])
    for p in pts[2:]:
        swaptmesh()
        v2f(p)
    endtmesh()
    got = (_read() & 0xFF).astype(int)
    np.testing.assert_array_equal(got, model)


def _grid(nx, ny, x0, y0, x1, y1, jitter, rnd):
    """(ny+1, nx+1) grid points, inner ones jittered by up to ``jitter``
    pixels, on the 1/256 grid."""
    pts = {}
    for j in range(ny + 1):
        for i in range(nx + 1):
            x = x0 + (x1 - x0) * i / nx
            y = y0 + (y1 - y0) * j / ny
            if 0 < i < nx and 0 < j < ny:
                x += rnd.uniform(-jitter, jitter)
                y += rnd.uniform(-jitter, jitter)
            pts[i, j] = (_q(round(x * 256)), _q(round(y * 256)))
    return pts


def _grid_tris(pts, nx, ny, rnd):
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = pts[i, j], pts[i + 1, j], pts[i + 1, j + 1], pts[i, j + 1]
            if rnd.random() < 0.5:
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    return tris


@pytest.mark.parametrize("seed", range(4))
def test_random_subpixel_grid_is_watertight(seed):
    _window()
    subpixel(TRUE)
    rnd = random.Random(100 + seed)
    pts = _grid(5, 4, 1.3, 2.6, 30.2, 29.9, 2.4, rnd)
    _check_mesh(_grid_tris(pts, 5, 4, rnd))


@pytest.mark.parametrize("subpix", [False, True])
def test_integer_grid_shared_horizontal_and_vertical_edges(subpix):
    """Grid lines through pixel centres: shared horizontal and vertical edges
    hold whole rows and columns of centres; the union is exactly the
    rectangle, each pixel once."""
    _window()
    subpixel(TRUE if subpix else FALSE)
    rnd = random.Random(7)
    pts = _grid(6, 5, 2, 3, 26, 28, 0, rnd)
    model = _check_mesh(_grid_tris(pts, 6, 5, rnd), subpix)
    assert _pixels(model) == ref.rect_pixels(2, 25, 3, 27)


def test_snapped_random_grid_is_watertight():
    _window()
    subpixel(FALSE)
    rnd = random.Random(11)
    pts = _grid(6, 6, 0.7, 1.2, 30.6, 31.1, 1.9, rnd)
    # avoid exact half-pixel ties (their rounding is not the subject here)
    pts = {k: tuple(v + 1 / 256 if (v * 2) % 2 == 1 else v for v in p)
           for k, p in pts.items()}
    _check_mesh(_grid_tris(pts, 6, 6, rnd), False)


def test_qstrip_grid_rows_are_watertight():
    """The same jittered grid drawn as one qstrip per row: quads
    (2k, 2k+1, 2k+3, 2k+2) of the vertex stream (docs/semantics.md §3)."""
    _window()
    subpixel(TRUE)
    rnd = random.Random(3)
    nx, ny = 5, 4
    pts = _grid(nx, ny, 1.1, 0.9, 30.7, 30.3, 2.0, rnd)
    expected = []
    for j in range(ny):
        stream = [p for i in range(nx + 1) for p in (pts[i, j], pts[i, j + 1])]
        for q in ref.qstrip_quads(len(stream)):
            expected.append(ref.polygon_pixels(ref.place([stream[k] for k in q]), W, H))
    model = _count_array(expected)
    assert model.max() == 1
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(1)
    for j in range(ny):
        bgnqstrip()
        for i in range(nx + 1):
            v2f(pts[i, j])
            v2f(pts[i, j + 1])
        endqstrip()
    np.testing.assert_array_equal((_read() & 0xFF).astype(int), model)


# --------------------------------------------------------------------------
# culling (docs/semantics.md §3: by screen winding)

CCW = [(4, 4), (24, 6), (10, 26)]
CW = CCW[::-1]


@pytest.mark.parametrize("bf,ff,ccw_drawn,cw_drawn", [
    (FALSE, FALSE, True, True),
    (TRUE, FALSE, True, False),
    (FALSE, TRUE, False, True),
    (TRUE, TRUE, False, False),
])
def test_backface_frontface_by_screen_winding(bf, ff, ccw_drawn, cw_drawn):
    _window()
    backface(bf)
    frontface(ff)
    expected = ref.triangle_pixels(*CCW, W, H)
    assert ref.winding(*CCW) == "ccw" and ref.winding(*CW) == "cw"
    assert _alone(CCW) == (expected if ccw_drawn else set())
    assert _alone(CW) == (expected if cw_drawn else set())


def test_backface_uses_screen_winding_after_a_mirror():
    """scale(-1, 1, 1) mirrors: a triangle CCW in object space is CW on the
    screen and is removed by backface(TRUE) (docs/semantics.md §2, scale)."""
    _window()
    backface(TRUE)
    ortho2(W - 0.5, -0.5, -0.5, H - 0.5)          # x mirrored
    assert _alone(CCW) == set()
    mirrored = [(W - 1 - x, y) for x, y in CW]   # where the CW triangle lands
    assert _alone(CW) == ref.triangle_pixels(*mirrored, W, H)


def test_backface_culls_rectf_and_polf():
    _window()
    backface(TRUE)
    _blank()
    cpack(0xFFFFFFFF)
    rectf(10, 3, 2, 8)         # (10,3) (2,3) (2,8) (10,8): clockwise
    assert _pixels(_read()) == set()
    rectf(2, 3, 10, 8)         # counter-clockwise
    assert _pixels(_read()) == ref.rect_pixels(2, 9, 3, 7)


def _strip_events(n):
    return list(range(n))


ZIGZAG = [(2, 4), (2, 20), (9, 3), (10, 22), (18, 5), (17, 21), (27, 4), (28, 24)]


@pytest.mark.parametrize("flip", [False, True])
def test_tmesh_strip_triangles_and_winding(flip):
    """No swaps = strip; each triangle is (R0, R1, new) (docs/semantics.md §3 [S]);
    culling follows each triangle's screen winding."""
    pts = [(x, H - 1 - y) for x, y in ZIGZAG] if flip else ZIGZAG
    tris = [[pts[i] for i in t] for t in ref.tmesh_triangles(_strip_events(len(pts)))]
    assert len(tris) == len(pts) - 2
    windings = {ref.winding(*t) for t in tris}
    assert len(windings) == 1              # a strip has one winding
    sets = [ref.triangle_pixels(*t, W, H) for t in tris]
    union = set().union(*sets)
    for bf, ff in ((FALSE, FALSE), (TRUE, FALSE), (FALSE, TRUE)):
        _window()
        subpixel(TRUE)
        backface(bf)
        frontface(ff)
        _blank()
        blendfunction(BF_ONE, BF_ONE)
        cpack(1)
        bgntmesh()
        for p in pts:
            v2f(p)
        endtmesh()
        got = (_read() & 0xFF).astype(int)
        culled = (bf and windings == {"cw"}) or (ff and windings == {"ccw"})
        expected = np.zeros_like(got) if culled else _count_array(sets)
        np.testing.assert_array_equal(got, expected)
        if not culled:
            assert _pixels(got) == union


def test_tmesh_registers_with_a_swap_in_the_middle():
    """v0 v1 v2 swap v3 v4: triangles (0,1,2), (2,1,3) -> after the swap the
    pointer selects R0 again ... computed by the register model."""
    _window()
    subpixel(TRUE)
    _check_tmesh_counts(_MESH_POINTS, [0, 1, 2, "swap", 3, 4, 5])


_MESH_POINTS = [(3, 3), (3, 28), (14, 4), (16, 26), (28, 10), (29, 29)]


def _check_tmesh_counts(pts, events):
    """Draw one tmesh of ``events`` (vertex indices into pts, or "swap")
    additively and compare each pixel's count with the register model's
    triangles."""
    sets = [ref.triangle_pixels(*[pts[i] for i in t], W, H)
            for t in ref.tmesh_triangles(events)]
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(1)
    bgntmesh()
    for e in events:
        if e == "swap":
            swaptmesh()
        else:
            v2f(pts[e])
    endtmesh()
    np.testing.assert_array_equal((_read() & 0xFF).astype(int), _count_array(sets))
    blendfunction(BF_ONE, BF_ZERO)


def test_same_tmesh_table_with_and_without_a_swap_in_turn():
    """The same primitive table (one tmesh of six vertices) drawn in turn
    without and with a swaptmesh: the assembled triangles, which the
    geometry keeps per table for replayed display lists, follow the swap
    every time (the register model computes each)."""
    _window()
    subpixel(TRUE)
    for events in ([0, 1, 2, 3, 4, 5], [0, 1, 2, "swap", 3, 4, 5]) * 2:
        _check_tmesh_counts(_MESH_POINTS, events)


def test_trailing_swaptmesh_does_not_leak_into_the_next_tmesh():
    """The fan idiom 'v; swaptmesh()' may end a tmesh with a swap; the next
    tmesh starts with fresh registers and pointer, so with backface(TRUE) its
    CCW triangle still draws (and both tmeshes are in one batch)."""
    _window()
    subpixel(TRUE)
    backface(TRUE)
    a = [(2, 2), (12, 2), (10, 10), (2, 12)]     # fan around (2, 2)
    b = [(16, 16), (30, 16), (16, 30)]           # CCW second tmesh
    events = [0, 1] + [e for k in range(2, len(a)) for e in ("swap", k)] + ["swap"]
    tris_a = [[a[i] for i in t] for t in ref.tmesh_triangles(events)]
    assert tris_a == [[a[0], a[1], a[2]], [a[0], a[2], a[3]]]
    assert {ref.winding(*t) for t in tris_a} == {"ccw"}
    assert ref.winding(*b) == "ccw"
    _blank()
    cpack(0xFFFFFFFF)
    bgntmesh()
    v2f(a[0])
    v2f(a[1])
    for p in a[2:]:
        swaptmesh()
        v2f(p)
    swaptmesh()                                  # trailing swap
    endtmesh()
    bgntmesh()
    for p in b:
        v2f(p)
    endtmesh()
    expected = set().union(*(ref.triangle_pixels(*t, W, H) for t in tris_a)) | \
        ref.triangle_pixels(*b, W, H)
    assert _pixels(_read()) == expected


def test_trailing_swaptmesh_at_the_end_of_a_batch():
    _window()
    subpixel(TRUE)
    a = [(2, 2), (12, 2), (10, 10)]
    _blank()
    cpack(0xFFFFFFFF)
    bgntmesh()
    v2f(a[0])
    v2f(a[1])
    swaptmesh()
    v2f(a[2])
    swaptmesh()
    endtmesh()
    assert _pixels(_read()) == ref.triangle_pixels(*a, W, H)


def test_swaptmesh_before_the_second_vertex_does_not_crash():
    """bgntmesh; v0; swaptmesh; v1; v2; v3: with the register model of
    docs/semantics.md §3, v1 replaces v0 in R0 and only (v1, v2, v3) is drawn.  At
    the least the flush must not crash, and a polygon of the same batch must
    still be drawn."""
    _window()
    subpixel(TRUE)
    pts = [(2, 2), (14, 3), (3, 14), (15, 15)]
    tris = ref.tmesh_triangles([0, "swap", 1, 2, 3])
    assert tris == [(1, 2, 3)]
    _blank()
    cpack(0xFFFFFFFF)
    bgntmesh()
    v2f(pts[0])
    swaptmesh()
    for p in pts[1:]:
        v2f(p)
    endtmesh()
    sq = [(20, 20), (30, 20), (30, 30), (20, 30)]
    _polygon(sq)
    got = _pixels(_read())
    assert ref.rect_pixels(20, 29, 20, 29) <= got
    assert got == ref.triangle_pixels(*[pts[i] for i in tris[0]], W, H) | \
        ref.rect_pixels(20, 29, 20, 29)


@pytest.mark.parametrize("bf", [FALSE, TRUE])
def test_qstrip_quads_and_culling(bf):
    _window()
    subpixel(TRUE)
    backface(bf)
    # bottom row then top row, left to right: quads (0,1,3,2) run clockwise
    pts = [(2, 3), (2, 20), (11, 2), (12, 22), (21, 4), (22, 19), (30, 3), (29, 23)]
    quads = [[pts[k] for k in q] for q in ref.qstrip_quads(len(pts))]
    assert len(quads) == 3
    assert {ref.winding(*q[:3]) for q in quads} == {"cw"}
    expected = set().union(*(ref.polygon_pixels(q, W, H) for q in quads))
    _blank()
    cpack(0xFFFFFFFF)
    bgnqstrip()
    for p in pts:
        v2f(p)
    endqstrip()
    assert _pixels(_read()) == (set() if bf else expected)


# --------------------------------------------------------------------------
# shading

def _colour(img, p):
    v = int(img[p[1], p[0]])
    return v & 0xFF, (v >> 8) & 0xFF, (v >> 16) & 0xFF


def test_flat_polygon_takes_the_last_vertex_colour():
    """docs/semantics.md §3: FLAT, a polygon takes the colour of its last vertex."""
    _window()
    shademodel(FLAT)
    _blank()
    vs = [(3, 3), (25, 4), (27, 26), (5, 24)]
    cols = [(200, 0, 0), (0, 200, 0), (0, 0, 200), (10, 120, 230)]
    bgnpolygon()
    for v, c in zip(vs, cols):
        c3i(c)
        v2f(v)
    endpolygon()
    img = _read()
    cover = ref.polygon_pixels(vs, W, H)
    assert _pixels(img) == cover
    assert {_colour(img, p) for p in cover} == {cols[-1]}


def test_flat_tmesh_each_triangle_takes_its_last_vertex():
    _window()
    subpixel(TRUE)
    shademodel(FLAT)
    _blank()
    cols = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0), (0, 255, 255),
            (255, 0, 255), (128, 64, 32), (32, 64, 128)]
    bgntmesh()
    for p, c in zip(ZIGZAG, cols):
        c3i(c)
        v2f(p)
    endtmesh()
    img = _read()
    for t in ref.tmesh_triangles(_strip_events(len(ZIGZAG))):
        pix = ref.triangle_pixels(*[ZIGZAG[i] for i in t], W, H)
        assert pix
        assert {_colour(img, p) for p in pix} == {cols[t[2]]}, t


def test_gouraud_is_barycentric_at_pixel_centres():
    _window()
    subpixel(TRUE)
    shademodel(GOURAUD)
    _blank()
    vs = [(1.25, 2.5), (30.75, 6.0), (11.5, 30.25)]
    cols = [(255, 0, 40), (0, 255, 100), (30, 60, 255)]
    bgnpolygon()
    for v, c in zip(vs, cols):
        c3i(c)
        v2f(v)
    endpolygon()
    img = _read()
    placed = ref.place(vs)
    pix = ref.triangle_pixels(*placed, W, H)
    assert _pixels(img) == pix
    for (x, y) in pix:
        wts = ref.barycentric(*placed, x, y)
        want = [float(sum(wt * c[k] for wt, c in zip(wts, cols))) for k in range(3)]
        got = _colour(img, (x, y))
        for g, e in zip(got, want):
            assert abs(g - e) <= 1.0, ((x, y), got, want)


# --------------------------------------------------------------------------
# subpixel(FALSE) snapping (docs/semantics.md §1)

def test_snapping_rounds_to_nearest_pixel_centre():
    _window()
    vs = [(10.4, 5.4), (20.6, 5.4), (20.6, 12.6), (10.4, 12.6)]
    # default subpixel(FALSE): 10.4 -> 10, 20.6 -> 21, 5.4 -> 5, 12.6 -> 13
    assert _alone(vs) == ref.rect_pixels(10, 20, 5, 12)
    subpixel(TRUE)
    assert _alone(vs) == ref.rect_pixels(11, 20, 6, 12)


def test_snapping_moves_a_thin_sliver_onto_pixel_centres():
    """A sliver between x = 10.4 and 10.6 covers no centre with subpixel(TRUE),
    and one column (x = 10 .. 11 snapped) without."""
    _window()
    vs = [(10.4, 2.2), (10.6, 2.2), (10.6, 20.8), (10.4, 20.8)]
    assert _alone(vs) == ref.rect_pixels(10, 10, 2, 20)
    subpixel(TRUE)
    assert _alone(vs) == set()


# --------------------------------------------------------------------------
# concave polygons

L_SHAPE = [(4, 4), (20, 4), (20, 10), (10, 10), (10, 24), (4, 24)]


@pytest.mark.parametrize("reverse", [False, True])
def test_concave_l_shape_equals_union_of_two_rectangles(reverse):
    _window()
    concave(TRUE)
    vs = L_SHAPE[::-1] if reverse else L_SHAPE
    expected = ref.rect_pixels(4, 19, 4, 9) | ref.rect_pixels(4, 9, 10, 23)
    assert ref.polygon_pixels([(4, 4), (20, 4), (20, 10), (4, 10)], W, H) | \
        ref.polygon_pixels([(4, 10), (10, 10), (10, 24), (4, 24)], W, H) == expected
    assert _alone(vs) == expected
    counts = _counts([vs])
    assert counts.max() == 1 and _pixels(counts) == expected


def test_concave_subpixel_l_shape():
    _window()
    concave(TRUE)
    subpixel(TRUE)
    vs = [(3.5, 2.25), (27.75, 2.25), (27.75, 9.5), (9.25, 9.5), (9.25, 29.75), (3.5, 29.75)]
    expected = (ref.polygon_pixels(ref.place([(3.5, 2.25), (27.75, 2.25), (27.75, 9.5),
                                              (3.5, 9.5)]), W, H)
                | ref.polygon_pixels(ref.place([(3.5, 9.5), (9.25, 9.5), (9.25, 29.75),
                                                (3.5, 29.75)]), W, H))
    counts = _counts([vs])
    assert counts.max() == 1
    assert _pixels(counts) == expected


# --------------------------------------------------------------------------
# old-style fills

@pytest.mark.parametrize("call", [rectf, rectfi, rectfs])
def test_rectf_forms(call):
    _window()
    _blank()
    cpack(0xFFFFFFFF)
    call(2, 3, 10, 8)
    assert _pixels(_read()) == ref.polygon_pixels([(2, 3), (10, 3), (10, 8), (2, 8)], W, H)
    assert _pixels(_read()) == ref.rect_pixels(2, 9, 3, 7)


def test_rectf_float_corners_snap():
    _window()
    _blank()
    cpack(0xFFFFFFFF)
    rectf(2.4, 3.6, 10.6, 8.4)          # snapped: (2, 4) - (11, 8)
    assert _pixels(_read()) == ref.rect_pixels(2, 10, 4, 7)


def test_polf_forms():
    _window()
    tri = [(3, 2), (25, 9), (8, 27)]
    expected = ref.triangle_pixels(*tri, W, H)
    for call, pts in ((polf, [(x, y, 0.0) for x, y in tri]), (polf2, tri),
                      (polf2i, tri), (polf2s, tri)):
        _blank()
        cpack(0xFFFFFFFF)
        call(3, pts)
        assert _pixels(_read()) == expected, call.__name__


# --------------------------------------------------------------------------
# lines and points (docs/semantics.md §1)

def test_snapped_lines_are_closed():
    _window()
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(1)
    bgnline()
    v2f((3, 5))
    v2f((3, 9))
    v2f((8, 9))
    endline()
    got = (_read() & 0xFF).astype(int)
    expected = np.zeros_like(got)
    for y in range(5, 10):
        expected[y, 3] += 1
    for x in range(3, 9):
        expected[9, x] += 1
    # both segments draw the joint (3, 9); both ends of the polyline drawn
    assert expected[9, 3] == 2
    np.testing.assert_array_equal(got, expected)


def test_subpixel_lines_are_half_open():
    _window()
    subpixel(TRUE)
    _blank()
    cpack(0xFFFFFFFF)
    bgnline()
    v2f((0, 0))
    v2f((0, 2))
    endline()
    assert _pixels(_read()) == {(0, 0), (0, 1)}


def test_subpixel_polyline_joint_drawn_once():
    _window()
    subpixel(TRUE)
    _blank()
    blendfunction(BF_ONE, BF_ONE)
    cpack(1)
    bgnline()
    for p in ((3, 5), (3, 9), (8, 9)):
        v2f(p)
    endline()
    got = (_read() & 0xFF).astype(int)
    expected = _count_array([set(ref.line_pixels((3, 5), (3, 9), False)),
                             set(ref.line_pixels((3, 9), (8, 9), False))])
    assert expected.max() == 1 and expected[9, 8] == 0
    np.testing.assert_array_equal(got, expected)


@pytest.mark.parametrize("subpix", [False, True])
@pytest.mark.parametrize("p0,p1", [((2, 3), (27, 14)), ((27, 14), (2, 3)),
                                   ((5, 28), (9, 1)), ((30, 2), (1, 11))])
def test_diagonal_line_takes_nearest_minor_pixel(subpix, p0, p1):
    _window()
    subpixel(TRUE if subpix else FALSE)
    _blank()
    cpack(0xFFFFFFFF)
    bgnline()
    v2f(p0)
    v2f(p1)
    endline()
    assert _pixels(_read()) == set(ref.line_pixels(p0, p1, closed=not subpix))


def test_closedline_and_move_draw():
    _window()
    _blank()
    cpack(0xFFFFFFFF)
    bgnclosedline()
    for p in ((4, 4), (13, 4), (13, 10)):
        v2f(p)
    endclosedline()
    # (13, 10) -> (4, 4): 9 steps in x, an odd count: no tie on the minor axis
    expected = (set(ref.line_pixels((4, 4), (13, 4), True))
                | set(ref.line_pixels((13, 4), (13, 10), True))
                | set(ref.line_pixels((13, 10), (4, 4), True)))
    assert _pixels(_read()) == expected
    _blank()
    cpack(0xFFFFFFFF)
    move2i(20, 20)
    draw2i(28, 20)
    draw2i(28, 26)
    assert _pixels(_read()) == set(ref.line_pixels((20, 20), (28, 20), True)) | \
        set(ref.line_pixels((28, 20), (28, 26), True))


@pytest.mark.parametrize("subpix", [False, True])
def test_points_fill_the_nearest_pixel(subpix):
    _window()
    subpixel(TRUE if subpix else FALSE)
    _blank()
    cpack(0xFFFFFFFF)
    pnt2(5.3, 7.6)
    bgnpoint()
    v2f((20.7, 3.2))
    v2f((0.0, 31.0))
    v2f((-3.0, 4.0))          # off the window: nothing, no crash
    v2f((31.4, 40.0))
    endpoint()
    assert _pixels(_read()) == {(5, 8), (21, 3), (0, 31)}


def test_flat_line_segments_take_their_last_vertex_colour():
    """docs/semantics.md §3: each segment of a FLAT polyline has the colour of its end
    vertex.  Sub-pixel (half-open) segments do not share pixels."""
    _window()
    subpixel(TRUE)
    shademodel(FLAT)
    _blank()
    pts = [(3, 5), (3, 12), (15, 12), (15, 20)]
    cols = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)]
    bgnline()
    for p, c in zip(pts, cols):
        c3i(c)
        v2f(p)
    endline()
    img = _read()
    for k in range(3):
        seg = ref.line_pixels(pts[k], pts[k + 1], closed=False)
        assert {_colour(img, p) for p in seg} == {cols[k + 1]}, k


def test_constant_colour_looks_only_at_used_vertices_front_and_back():
    """WindowWork.constant_colour (Gouraud over one colour runs the flat
    variant): every vertex a triangle uses, front and back colours; an
    unused vertex (a clipped original) does not count."""
    from vgx_emulator.geometry import WindowWork
    c = np.tile([10.0, 20.0, 30.0, 255.0], (5, 1))
    c[4] = (0.0, 0.0, 0.0, 0.0)                       # not used
    w = WindowWork(klass=0, C=c, CB=c, tris=np.array([[0, 1, 2], [0, 2, 3]]))
    assert w.constant_colour()
    c2 = c.copy()
    c2[3, 1] = 21.0
    assert not WindowWork(klass=0, C=c2, CB=c2, tris=w.tris).constant_colour()
    back = c.copy()
    back[2, 3] = 0.0
    assert not WindowWork(klass=0, C=c, CB=back, tris=w.tris).constant_colour()


@pytest.mark.parametrize("field", ["ztest", "zwrite", "color", "gouraud", "cmode", "twoside",
                                   "stencil", "blend", "logic", "atest", "pattern",
                                   "cmask", "texture", "dual"])
def test_kernel_variants_have_distinct_cache_keys(field):
    """A variant kernel's disk-cache entries are keyed on its raster key
    (jit.kernel(variant=key)), not on its closure cells: two variants that
    differ in any one field of the key must have different cache tags, or
    the second would load the first's compiled code from the disk cache."""
    from vgx_emulator import jit
    from vgx_emulator.raster.blend import GENERIC
    from vgx_emulator.raster.variants import RasterKey
    from vgx_emulator.scan import lines, spans, triangles
    base = RasterKey(True, True, True, True, False, False, 2, 0, False, False, False,
                     False, False, False)
    other = base._replace(**{field: GENERIC if field == "blend" else
                             (1 if field == "stencil" else not getattr(base, field))})
    if not isinstance(getattr(triangles._make_triangle_kernel(*base), "_cache", None),
                      jit._KeyedCache):
        pytest.skip("kernels are not disk-cached in this run (NUMBA_DISABLE_JIT or cache off)")

    def tag(kernel):
        return kernel._cache._tag
    for make in (triangles._make_triangle_kernel, lines._make_line_kernel,
                 lines._make_point_kernel, spans._make_pixel_kernel):
        a, b = tag(make(*base)), tag(make(*other))
        assert a != b
        assert a.startswith(jit.KERNEL_SOURCE_HASH) and repr(tuple(base)) in a


def _setup_inputs(seed, t, cull_some):
    """Window fixed-point vertices (scan.fixed SHIFT bits), colours and
    triangles for setup_triangles; with ``cull_some`` a third of the
    triangles clockwise (culled under CULL_BACK) and some degenerate."""
    from vgx_emulator.scan.fixed import SHIFT
    rng = np.random.default_rng(seed)
    nv = 3 * t
    X = (rng.uniform(0, 60, nv) * (1 << SHIFT)).astype(np.int64)
    Y = (rng.uniform(0, 40, nv) * (1 << SHIFT)).astype(np.int64)
    Z = rng.uniform(0, 1000, nv)
    C = rng.uniform(0, 255, (nv, 4))
    tris = np.arange(nv, dtype=np.int64).reshape(t, 3)
    if cull_some:
        tris[::3] = tris[::3, ::-1].copy()           # some reversed
        tris[1::7, 2] = tris[1::7, 1]                # some degenerate
    return X, Y, Z, C, C, tris[:, 2].copy(), tris


def test_setup_records_kept_for_batches_of_other_sizes(monkeypatch):
    """scan.triangles._records: a batch takes the first rows of the
    shortest free kept array long enough (the passes of a multipass frame
    differ in size), a held one never, and the arrays kept stay within
    _SPARE_BYTES (the newest always kept)."""
    from vgx_emulator.scan import triangles as T
    monkeypatch.setattr(T, "_spare", [])
    big = T._records(1000)
    small = T._records(100)                  # big is held: a new one
    assert not np.shares_memory(big, small) and len(T._spare) == 2
    addr = (big.ctypes.data, small.ctypes.data)
    del big, small
    again = T._records(80)                   # the shortest free one, 100 rows
    assert again.shape == (80, T.T_COLUMNS) and again.ctypes.data == addr[1]
    other = T._records(600)                  # 100 is held, 1000 free
    assert other.ctypes.data == addr[0] and len(other) == 600
    del again, other
    monkeypatch.setattr(T, "_SPARE_BYTES", 1500 * T.T_COLUMNS * 8)
    T._records(2000)                         # beyond the bound: the oldest go
    assert [len(a) for a in T._spare] == [2000]


def test_setup_records_reused_only_when_free_and_as_if_new():
    """setup_triangles takes the last batch's records when nothing holds
    them (scan.triangles._records) and writes every record a drawn triangle
    has: a batch set up into the records of another (different triangles,
    culled ones, FLAT after Gouraud) equals the same batch set up into new
    ones, row for row where drawn."""
    from vgx_emulator.scan import triangles as T
    t = 500
    a = T.setup_triangles(*_setup_inputs(1, t, False), T.CULL_NONE, 0, 63, 0, 47,
                          interp=True)
    held = a[0]
    b = T.setup_triangles(*_setup_inputs(2, t, True), T.CULL_BACK, 0, 63, 0, 47)
    assert b[0] is not held                          # a still holds its records
    del a, b, held
    T._spare.clear()
    fresh = T.setup_triangles(*_setup_inputs(2, t, True), T.CULL_BACK, 0, 63, 0, 47)
    T._spare.clear()
    first = T.setup_triangles(*_setup_inputs(1, t, False), T.CULL_NONE, 0, 63, 0, 47,
                              interp=True)
    mark = first[0].ctypes.data                      # (an address: no reference)
    del first
    again = T.setup_triangles(*_setup_inputs(2, t, True), T.CULL_BACK, 0, 63, 0, 47)
    assert again[0].ctypes.data == mark              # the free records were taken
    drawn = fresh[2][:, 0] <= fresh[2][:, 1]
    assert 0 < drawn.sum() < t
    np.testing.assert_array_equal(again[2], fresh[2])
    np.testing.assert_array_equal(again[0][drawn], fresh[0][drawn])
    np.testing.assert_array_equal(again[1][drawn], fresh[1][drawn])
