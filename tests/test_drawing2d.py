"""Circles and arcs, pmv/pdr/pclos, relative moves and draws, sbox, splf,
polymode, normal, gl_sincos, getgpos, displacepolygon (circ(3G), arc(3G),
pmv(3G), rpmv(3G), rmv(3G), sbox(3G), splf(3G), polymode(3G), getgpos(3G))."""
import math
import os

import numpy as np
import pytest

from irisgl import *
from irisgl._current import machine

import banks

W, H = 64, 48


@pytest.fixture
def win(open_window):
    banks.pixel_window(open_window, W, H)


def lit():
    return banks.lit(W, H)


def wipe():
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)


def near(img, x, y):
    """Whether a pixel within one of (x, y) is lit (a polygonal circle
    strays up to a pixel from the rounded ideal point)."""
    x, y = int(round(x)), int(round(y))
    return img[max(y - 1, 0):y + 2, max(x - 1, 0):x + 2].any()


def dist(cx, cy):
    ys, xs = np.mgrid[0:H, 0:W]
    return np.hypot(xs - cx, ys - cy), np.degrees(np.arctan2(ys - cy, xs - cx)) % 360


# -- circles ------------------------------------------------------------------------
def test_circ_outline_lies_on_the_radius(win):
    circ(30, 24, 10)
    img = lit()
    d, _ = dist(30, 24)
    assert img.any()
    assert (np.abs(d[img] - 10) <= 1.0).all()
    ys, xs = np.nonzero(img)
    assert (xs.min(), xs.max(), ys.min(), ys.max()) == (20, 40, 14, 34)
    assert not img[24, 30]


def test_circf_fills_the_disc(win):
    circf(30, 24, 10)
    img = lit()
    d, _ = dist(30, 24)
    assert img[d <= 9.5].all()
    assert not img[d >= 10.5].any()
    assert abs(img.sum() - math.pi * 100) < 0.03 * math.pi * 100


def test_circ_forms_agree(win):
    circfi(30, 24, 10)
    a = lit()
    wipe()
    circfs(30, 24, 10)
    assert (lit() == a).all()
    with pytest.raises(GLError, match="^circi"):
        circi(float("nan"), 2, 3)           # a float is truncated as C does; NaN has no value


def test_circle_goes_through_the_matrix(win):
    translate(10.0, 5.0, 0.0)
    scale(2.0, 2.0, 1.0)
    circf(10, 10, 5)                 # centre (30, 25), radius 10 on the screen
    img = lit()
    d, _ = dist(30, 25)
    assert img[d <= 9.5].all() and not img[d >= 10.5].any()


def test_circle_segments_follow_the_screen_radius(win):
    from irisgl.drawing2d import segments_for
    w = machine.current
    small, big = segments_for(w, 0, 0, 2), segments_for(w, 0, 0, 200)
    assert 8 <= small < big <= 256
    # sagitta of the chosen chords stays within a quarter pixel
    assert 200 * (1 - math.cos(math.pi / big)) <= 0.25


# -- arcs ---------------------------------------------------------------------------
def test_arcf_is_a_pie_slice(win):
    arcf(30, 24, 15, 0, 900)         # the first quadrant
    img = lit()
    d, ang = dist(30, 24)
    inside = (d <= 14.5) & (ang > 3) & (ang < 87)
    assert img[inside].all()
    ys, xs = np.nonzero(img)
    assert xs.min() >= 30 and ys.min() >= 24
    assert img[30, 36] and not img[30, 24] and not img[18, 36]


def test_arc_runs_counter_clockwise_from_start_to_end(win):
    arc(30, 24, 20, 450, 0)          # everything but 0..45 degrees
    img = lit()
    d, ang = dist(30, 24)
    ring = np.abs(d - 20) <= 1.0
    for a in range(50, 360, 10):
        assert near(img, 30 + 20 * math.cos(math.radians(a)), 24 + 20 * math.sin(math.radians(a)))
    assert not img[ring & (ang > 8) & (ang < 37)].any()
    assert not (img & ~ring).any()


def test_arc_endpoints(win):
    arci(30, 24, 10, 0, 900)
    img = lit()
    assert img[24, 40] and img[34, 30]          # (r, 0) and (0, r)
    assert not img[14, 30] and not img[24, 20]


def test_arc_full_turn_and_empty_span(win):
    arc(30, 24, 10, 0, 3600)                 # a whole turn: the full circle
    full = lit()
    wipe()
    circ(30, 24, 10)
    assert (full == lit()).all()
    wipe()
    arci(30, 24, 10, 900, 900)               # no span: the start point only
    assert list(zip(*np.nonzero(lit()))) == [(34, 30)]


# -- pmv / pdr / pclos ----------------------------------------------------------------
TRI = [(5, 5), (40, 8), (20, 30)]


def test_pmv_pdr_pclos_fill_like_polf(win):
    polf2i(3, TRI)
    ref = lit()
    wipe()
    pmv2i(*TRI[0])
    pdr2i(*TRI[1])
    pdr2i(*TRI[2])
    pclos()
    assert (lit() == ref).all() and ref.sum() > 100


def test_rpmv_rpdr_are_relative(win):
    pmv2i(*TRI[0])
    pdr2i(*TRI[1])
    pdr2i(*TRI[2])
    pclos()
    ref = lit()
    wipe()
    move2i(0, 0)
    rpmv2i(5, 5)
    rpdr2i(35, 3)
    rpdr2i(-20, 22)
    pclos()
    assert (lit() == ref).all()


def test_pmv_3d_and_colour_per_point(win):
    shademodel(FLAT)
    pmv(5.0, 5.0, 0.0)
    cpack(0xFF0000FF)
    pdr(40.0, 8.0, 0.0)
    cpack(0xFF00FF00)
    pdr(20.0, 30.0, 0.0)
    pclos()
    img = lrectread(0, 0, W - 1, H - 1)
    assert img[12, 20] == 0xFF00FF00          # FLAT: the last vertex's colour


def test_pdr_and_pclos_need_pmv(win):
    with pytest.raises(GLError, match="^pdr2i"):
        pdr2i(3, 4)
    with pytest.raises(GLError, match="^pclos"):
        pclos()
    bgnline()
    with pytest.raises(GLError, match="^pdr"):
        pdr(1.0, 2.0, 0.0)
    with pytest.raises(GLError, match="^pmv"):
        pmv(1.0, 2.0, 0.0)
    endline()
    assert not lit().any()


def test_spclos_closes_like_pclos(win):
    pmv2i(*TRI[0])
    pdr2i(*TRI[1])
    pdr2i(*TRI[2])
    spclos()
    assert lit().sum() > 100


# -- relative move / draw, getgpos ---------------------------------------------------
def test_rmv_rdr(win):
    move2i(10, 10)
    rmv2i(5, 0)
    rdr2i(20, 0)                      # (15, 10) - (35, 10)
    rdr2i(0, 10)                      # (35, 10) - (35, 20)
    img = lit()
    assert img[10, 15:36].all() and not img[10, 14] and not img[10, 36]
    assert img[10:21, 35].all() and img.sum() == 21 + 10


def test_getgpos_is_the_transformed_position(win):
    move2(10.0, 20.0)
    x, y, z, w = getgpos()
    # ortho2(-0.5, 63.5, -0.5, 47.5): clip x = (10 + 0.5) / 64 * 2 - 1
    assert x == pytest.approx(10.5 / 32 - 1) and y == pytest.approx(20.5 / 24 - 1)
    assert (z, w) == (pytest.approx(0.0), pytest.approx(1.0))
    rmv2(5.0, 0.0)
    assert getgpos()[0] == pytest.approx(15.5 / 32 - 1)


# -- screen-aligned boxes --------------------------------------------------------------
def test_sboxf_matches_rectf_without_rotation(win):
    rectfi(2, 3, 12, 9)
    ref = lit()
    wipe()
    sboxfi(2, 3, 12, 9)
    assert (lit() == ref).all() and ref.sum() == 10 * 6     # rectf's own fill rule


def test_sbox_stays_screen_aligned_under_rotation(win):
    translate(32.0, 24.0, 0.0)
    rotate(300, "z")
    sboxf(-10.0, -5.0, 10.0, 5.0)
    img = lit()
    ys, xs = np.nonzero(img)
    # an axis-aligned rectangle: it fills its bounding box
    assert img.sum() == (xs.max() - xs.min() + 1) * (ys.max() - ys.min() + 1)
    a = math.radians(30)
    cx, cy = 32 + (-10 * math.cos(a) + 5 * math.sin(a)), 24 + (-10 * math.sin(a) - 5 * math.cos(a))
    ex, ey = 32 + (10 * math.cos(a) - 5 * math.sin(a)), 24 + (10 * math.sin(a) + 5 * math.cos(a))
    assert abs(xs.min() - min(cx, ex)) <= 1.5 and abs(xs.max() - max(cx, ex)) <= 1.5
    assert abs(ys.min() - min(cy, ey)) <= 1.5 and abs(ys.max() - max(cy, ey)) <= 1.5


def test_sbox_outline(win):
    sboxi(10, 10, 20, 15)
    img = lit()
    assert img.sum() == 2 * 11 + 2 * 4
    assert not img[12, 15]


# -- splf -------------------------------------------------------------------------------
def test_splf_shades_colour_indices(open_window):
    open_window(W, H, rgb=False)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    color(0)
    clear()
    splf2i(4, [(0, 0), (63, 0), (63, 10), (0, 10)], [16, 79, 79, 16])
    img = lrectread(0, 0, W - 1, H - 1)
    r = img[5]
    assert list(r[:63]) == list(range(16, 79))        # one index step per pixel
    x, y, z, w = getgpos()                       # the first point
    assert x == pytest.approx(0.5 / 32 - 1) and y == pytest.approx(0.5 / 24 - 1)


def test_splf_errors(win):
    with pytest.raises(GLError, match="^splf2"):
        splf2(3, [(0, 0), (10, 0), (0, 10)], [1, 2, 3])     # RGB mode
    with pytest.raises(GLError, match="^splf"):
        splf(3, [(0, 0, 0), (10, 0, 0)], [1, 2, 3])         # too few points
    assert not lit().any()


# -- polymode ----------------------------------------------------------------------------
def test_polymode_line_outlines_filled_primitives(win):
    polymode(PYM_LINE)
    rectfi(10, 10, 20, 20)
    img = lit()
    assert img.sum() == 40 and not img[15, 15] and img[10, 15] and img[15, 20]
    wipe()
    circf(40, 24, 6)
    img = lit()
    d, _ = dist(40, 24)
    assert not img[d < 4.5].any() and (np.abs(d[img] - 6) <= 1.0).all()


def test_polymode_point_and_fill(win):
    polymode(PYM_POINT)
    rectfi(10, 10, 20, 20)
    assert list(zip(*np.nonzero(lit()))) == [(10, 10), (10, 20), (20, 10), (20, 20)]
    wipe()
    polymode(PYM_FILL)
    rectfi(10, 10, 20, 20)
    assert lit().sum() == 100                           # rectf's own fill rule


def test_polymode_line_takes_width_and_style_hollow_does_not(win):
    polymode(PYM_LINE)
    linewidth(3)
    rectfi(10, 10, 30, 30)
    assert list(np.nonzero(lit()[:, 20])[0]) == [9, 10, 11, 29, 30, 31]
    wipe()
    polymode(PYM_HOLLOW)
    deflinestyle(1, 0x00FF)
    setlinestyle(1)
    rectfi(10, 10, 30, 30)
    assert lit().sum() == 80


def test_hollow_outlines_are_not_gated_by_the_stencil(open_window):
    """[S] The VGX's hollow fill used the stencil planes itself and left them
    as it found them: SGI's hollowcube-vgx.c (and NCSA isovis) set
    stensize(1) and stencil(TRUE, 1, SF_EQUAL, 1, ST_KEEP x3) on planes never
    cleared to 1, and drew their outlines.  Hollow outlines are drawn whatever
    the stencil test and change no stencil; filled polygons keep the test."""
    open_window(W, H, pixels=True, cleared=True, planes=1)
    sclear(0)
    stencil(TRUE, 1, SF_EQUAL, 1, ST_KEEP, ST_KEEP, ST_INVERT)
    polymode(PYM_HOLLOW)
    rectfi(10, 10, 30, 30)
    assert lit().sum() == 80
    polymode(PYM_FILL)
    rectfi(40, 10, 50, 20)                               # stencil 0 != 1: not drawn
    assert lit().sum() == 80
    stencil(FALSE, 0, SF_ALWAYS, 0, ST_KEEP, ST_KEEP, ST_KEEP)
    assert not machine.current.fb.stencil.any()         # the outline left the planes alone


def test_polymode_line_on_tmesh_draws_triangle_edges(win):
    polymode(PYM_LINE)
    bgntmesh()
    for p in ((10, 10), (30, 10), (10, 30), (30, 30)):
        v2i(p)
    endtmesh()
    img = lit()
    assert img[10, 10:31].all() and img[30, 10:31].all()
    assert img[20, 20]                                  # the shared diagonal
    assert img[15, 25] and img[25, 15]                  # on the diagonal x + y = 40
    assert not img[15, 15] and not img[25, 25]


def test_polymode_line_on_a_tmesh_fan(win):
    polymode(PYM_LINE)
    bgntmesh()
    v2i((32, 24))                    # c
    v2i((50, 24))                    # a
    swaptmesh()
    v2i((32, 40))                    # b: triangle (c, a, b)
    swaptmesh()
    v2i((14, 30))                    # d: triangle (c, b, d), a fan about c
    endtmesh()
    img = lit()
    assert img[24, 45] and img[32, 32] and img[32, 41]   # c-a, c-b, a-b
    assert img[27, 23]                                   # c-d: only a fan has it
    assert not img[25, 44]                               # a strip's a-d edge is not there
    assert not img[28, 38] and not img[30, 26]           # inside the two triangles


def test_polymode_errors_change_nothing(win):
    polymode(PYM_LINE)
    with pytest.raises(GLError, match="^polymode"):
        polymode(0)
    assert machine.current.st.polymode == PYM_LINE


def test_polysmooth_state(win):
    polysmooth(PYSM_ON)
    assert machine.current.st.polysmooth == PYSM_ON
    with pytest.raises(GLError, match="^polysmooth"):
        polysmooth(7)
    assert machine.current.st.polysmooth == PYSM_ON


# -- old names -------------------------------------------------------------------------------
def test_normal_is_n3f(win):
    normal((0.0, 1.0, 0.0))
    assert machine.current.st.normal == (0.0, 1.0, 0.0)
    with pytest.raises(GLError, match="^normal"):
        normal((1.0, 2.0))


def test_gl_sincos():
    s, c = gl_sincos(900)
    assert s == pytest.approx(1.0) and c == pytest.approx(0.0, abs=1e-7)
    s, c = gl_sincos(300)
    assert s == pytest.approx(0.5, abs=1e-7) and c == pytest.approx(math.sqrt(3) / 2, abs=1e-7)


def test_displacepolygon_is_not_emulated(win):
    with pytest.raises(GLError, match="^displacepolygon: not emulated.*VGX"):
        displacepolygon(1.0)


def test_circles_record_into_objects(win):
    circf(30, 24, 8)
    ref = lit()
    wipe()
    makeobj(3)
    circf(30, 24, 8)
    closeobj()
    assert not lit().any()
    callobj(3)
    assert (lit() == ref).all()


# -- the demo ----------------------------------------------------------------------------------
def test_drawing2d_demo_draws_what_it_says():
    from vgx_emulator.runner import run_program
    path = os.path.join(os.path.dirname(__file__), "..", "programs", "demos", "drawing2d.py")
    img = run_program(path, 1, [])
    h, w, _ = img.shape
    assert (h, w) == (300, 400)

    def px(x, y):                       # window (x, y), y up
        return tuple(int(c) for c in img[h - 1 - y, x])

    bg = (0, 0, 0)
    # the red disc: centre and a point 34 pixels out are red, 42 out is background
    assert px(70, 230) == (255, 0, 0) and px(70 + 34, 230) == (255, 0, 0)
    assert px(70 + 42, 230) == bg
    # the green circle: on the 40-pixel radius, not inside
    green = (img == (0, 255, 0)).all(axis=2)[::-1]      # row 0 = bottom
    for a in np.linspace(0, 2 * math.pi, 24, endpoint=False):
        assert near(green, 200 + 40 * math.cos(a), 230 + 40 * math.sin(a))
    assert not green[230, 175:226].any() and not green[205:256, 200].any()
    assert px(200, 230) == bg
    # the yellow pie slice 0..90 degrees: inside its quadrant only
    assert px(330 + 15, 230 + 15) == (255, 255, 0) and px(330 - 15, 230 + 15) == bg
    # the dashed line at y = 150: 0x0F0F with lsrepeat 2 -> 8 on, 8 off
    runs = [px(x, 150) != bg for x in range(20, 84)]
    assert runs == [((x // 2) % 16) % 8 < 4 for x in range(64)]
    # the 5-pixel wide line at y = 120: rows 118..122 lit, 117 and 123 not
    assert all(px(200, y) == (0, 255, 255) for y in range(118, 123))
    assert px(200, 117) == bg and px(200, 123) == bg
    # the pmv/pdr/pclos triangle and the sboxf
    assert px(80, 60) == (255, 0, 255)
    assert px(300, 50) == (255, 255, 255) and px(300, 90) == bg
