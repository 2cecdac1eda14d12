"""User clipping planes (clipplane(3G)): exact cuts of polygons, lines and
points by planes defined in object coordinates and stored in eye space.

The default projection of a window maps pixel centres to integer
coordinates (ortho2(-0.5, w - 0.5, -0.5, h - 0.5)), so a plane
x - 20.5 >= 0 keeps exactly the pixel columns 21..w-1.  Most tests draw
with subpixel(TRUE), so that the vertices the cut makes stay exactly on the
plane (with the VGX default they snap to a pixel centre, which is where
the frustum's cut vertices go too).
"""
import numpy as np
import pytest

from irisgl import (CP_DEFINE, CP_OFF, CP_ON, GD_CLIPPLANES, GLError, MVIEWING, bgnline,
                    bgnpoint, callobj, clear, clipplane, closeobj, cpack, endline, endpoint,
                    getgdesc, lrectread, makeobj, mmode, ortho, popmatrix, pushmatrix, rectf,
                    rotate, scale, subpixel, translate, v2f, v3f, bgnpolygon, endpolygon)

W, H = 64, 48
RED = 0xFF0000FF


def _lit():
    """(H, W) bool: the pixels that are not black."""
    return (lrectread(0, 0, W - 1, H - 1) & 0xFFFFFF) != 0


def _full_quad():
    cpack(RED)
    rectf(-1, -1, W, H)


def _fresh():
    cpack(0)
    clear()


def _open(open_window):
    open_window(W, H)
    subpixel(1)


def test_vertical_plane_keeps_exact_columns(open_window):
    open_window(W, H)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    _full_quad()
    lit = _lit()
    assert lit[:, 21:].all()
    assert not lit[:, :21].any()
    assert lit.sum() == (W - 21) * H


def test_diagonal_plane_cuts_along_its_line(open_window):
    """x + y - 40.5 >= 0 with sub-pixel vertices: exactly the pixel centres
    with x + y > 40.5 are drawn (no centre lies on the line)."""
    _open(open_window)
    _fresh()
    clipplane(3, CP_DEFINE, [1.0, 1.0, 0.0, -40.5])
    clipplane(3, CP_ON, [0, 0, 0, 0])
    _full_quad()
    y, x = np.mgrid[0:H, 0:W]
    expect = (x + y) > 40.5
    lit = _lit()
    assert (lit == expect).all()
    assert lit.sum() == expect.sum()        # pixel counts either side
    assert (~lit).sum() == (~expect).sum()


def test_negated_plane_keeps_the_other_side(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [-1.0, 0.0, 0.0, 20.5])     # x <= 20.5
    clipplane(0, CP_ON, [0, 0, 0, 0])
    _full_quad()
    lit = _lit()
    assert lit.sum() == 21 * H and lit[:, :21].all()


def test_plane_is_taken_to_eye_space_at_define_time(open_window):
    """clipplane(3G): the object-space plane goes through the inverse of the
    ModelView current at CP_DEFINE; later matrix changes do not move it."""
    _open(open_window)
    _fresh()
    pushmatrix()
    translate(10.0, 0.0, 0.0)
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -10.5])    # object x >= 10.5 -> eye x >= 20.5
    popmatrix()
    clipplane(0, CP_ON, [0, 0, 0, 0])
    pushmatrix()
    translate(-30.0, 0.0, 0.0)                          # moves the quad, not the plane
    rectf(-1 + 30, -1, W + 30, H)
    popmatrix()
    lit = _lit()
    assert lit.sum() == 0                              # black: the colour is still 0
    cpack(RED)
    pushmatrix()
    translate(-30.0, 0.0, 0.0)
    rectf(-1 + 30, -1, W + 30, H)
    popmatrix()
    lit = _lit()
    assert lit.sum() == (W - 21) * H and lit[:, 21:].all()


def test_rotated_modelview_plane(open_window):
    """A plane defined under a 90 degree rotation about z: object x >= 5.5
    becomes eye y >= 5.5."""
    _open(open_window)
    _fresh()
    pushmatrix()
    rotate(900, 'z')
    clipplane(1, CP_DEFINE, [1.0, 0.0, 0.0, -5.5])
    popmatrix()
    clipplane(1, CP_ON, [0, 0, 0, 0])
    _full_quad()
    lit = _lit()
    assert lit[6:, :].all() and not lit[:6, :].any()


def test_two_planes_intersect(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(5, CP_DEFINE, [0.0, 1.0, 0.0, -10.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    clipplane(5, CP_ON, [0, 0, 0, 0])
    _full_quad()
    lit = _lit()
    assert lit.sum() == (W - 21) * (H - 11)
    assert lit[11:, 21:].all()


def test_all_six_planes_at_once(open_window):
    """GD_CLIPPLANES planes together: a box 10..29 x 5..24 cut out of a quad."""
    assert getgdesc(GD_CLIPPLANES) == 6
    _open(open_window)
    _fresh()
    planes = [[1, 0, 0, -9.5], [-1, 0, 0, 29.5], [0, 1, 0, -4.5], [0, -1, 0, 24.5],
              [1, 1, 0, -10.0], [-1, -1, 0, 200.0]]
    for i, p in enumerate(planes):
        clipplane(i, CP_DEFINE, p)
        clipplane(i, CP_ON, p)
    _full_quad()
    lit = _lit()
    assert lit.sum() == 20 * 20
    assert lit[5:25, 10:30].all()


def test_cp_off_disables_and_cp_on_restores(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    clipplane(0, CP_OFF, [0, 0, 0, 0])
    _full_quad()
    assert _lit().sum() == W * H
    _fresh()
    clipplane(0, CP_ON, [9, 9, 9, 9])          # params insignificant for CP_ON
    _full_quad()
    assert _lit().sum() == (W - 21) * H


def test_primitives_before_enable_are_not_clipped(open_window):
    """The batch drawn before CP_ON keeps its look (state_change flush)."""
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    cpack(RED)
    rectf(-1, -1, W, 9.5)                      # rows 0..9, whole width
    clipplane(0, CP_ON, [0, 0, 0, 0])
    rectf(-1, 9.5, W, H)
    lit = _lit()
    assert lit[:10].all()
    assert lit[10:, 21:].all() and not lit[10:, :21].any()


def test_lines_are_cut_at_the_plane(open_window):
    """A horizontal line keeps exactly its pixels with x >= 21."""
    _open(open_window)
    _fresh()
    cpack(RED)
    bgnline()
    v2f([0, 20])
    v2f([63, 20])
    endline()
    whole = _lit()
    _fresh()
    clipplane(2, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(2, CP_ON, [0, 0, 0, 0])
    cpack(RED)
    bgnline()
    v2f([0, 20])
    v2f([63, 20])
    endline()
    cut = _lit()
    keep = whole.copy()
    keep[:, :21] = False
    assert cut.sum() > 0
    assert (cut == keep).all()


def test_diagonal_line_stays_inside_both_planes(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(1, CP_DEFINE, [0.0, -1.0, 0.0, 30.5])     # y <= 30.5
    clipplane(0, CP_ON, [0, 0, 0, 0])
    clipplane(1, CP_ON, [0, 0, 0, 0])
    cpack(RED)
    bgnline()
    v2f([0, 0])
    v2f([63, 47])
    endline()
    ys, xs = np.nonzero(_lit())
    assert len(xs) > 0
    assert xs.min() == 21 and ys.max() <= 31
    # the kept part spans x 21 .. 40 (y = 47/63 x reaches 30.5 at x = 40.9)
    assert xs.max() in (40, 41)


def test_points_outside_are_dropped(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    cpack(RED)
    bgnpoint()
    for x in range(0, 64, 4):
        v2f([x, 20])
    endpoint()
    ys, xs = np.nonzero(_lit())
    assert sorted(xs.tolist()) == list(range(24, 64, 4))
    assert set(ys.tolist()) == {20}


def test_plane_in_eye_depth_under_mviewing(open_window):
    """In MVIEWING the plane is applied in eye space: -z_eye - 19.5 >= 0 keeps
    what lies at depth >= 19.5 of a quad whose depth grows along x
    (depth = x + 1 at pixel column x)."""
    _open(open_window)
    mmode(MVIEWING)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, 0.0, 100.0)
    _fresh()
    clipplane(0, CP_DEFINE, [0.0, 0.0, -1.0, -19.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    cpack(RED)
    bgnpolygon()
    v3f([-1, -1, 0.0])
    v3f([W, -1, -(W + 1.0)])
    v3f([W, H, -(W + 1.0)])
    v3f([-1, H, 0.0])
    endpolygon()
    lit = _lit()
    assert lit[:, 19:].all() and not lit[:, :19].any()


def test_recorded_in_objects(open_window):
    _open(open_window)
    _fresh()
    makeobj(7)
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    _full_quad()
    closeobj()
    assert _lit().sum() == 0                   # recorded, not drawn
    callobj(7)
    assert _lit().sum() == (W - 21) * H


def test_errors_change_nothing(vgx, open_window):
    _open(open_window)
    st = vgx.current.st
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    before = (list(st.clipplanes), st.user_planes)
    with pytest.raises(GLError, match="clipplane"):
        clipplane(6, CP_ON, [0, 0, 0, 0])
    with pytest.raises(GLError, match="clipplane"):
        clipplane(-1, CP_DEFINE, [0, 0, 0, 0])
    with pytest.raises(GLError, match="clipplane: unknown mode"):
        clipplane(0, 7, [0, 0, 0, 0])
    with pytest.raises(GLError, match="4 floats"):
        clipplane(1, CP_DEFINE, [1.0, 2.0, 3.0])
    with pytest.raises(GLError, match="not a number"):
        clipplane(1, CP_DEFINE, [1.0, "x", 3.0, 4.0])
    pushmatrix()
    scale(0.0, 1.0, 1.0)
    with pytest.raises(GLError, match="singular"):
        clipplane(0, CP_DEFINE, [0.0, 1.0, 0.0, 0.0])
    popmatrix()
    with pytest.raises(GLError, match="not finite"):
        clipplane(0, CP_DEFINE, [float("nan"), 0.0, 0.0, 0.0])
    assert st.clipplanes[0][0] is before[0][0][0]
    assert [e for _, e in st.clipplanes] == [e for _, e in before[0]]
    assert st.user_planes is before[1] is None
    # the plane kept: still x >= 20.5 once enabled
    _fresh()
    clipplane(0, CP_ON, [0, 0, 0, 0])
    _full_quad()
    assert _lit().sum() == (W - 21) * H


def test_longer_params_read_first_four(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, np.array([1.0, 0.0, 0.0, -20.5, 99.0, 99.0]))
    clipplane(0, CP_ON, [0, 0, 0, 0])
    _full_quad()
    assert _lit().sum() == (W - 21) * H


def test_nonfinite_vertex_with_plane_does_not_crash(open_window):
    _open(open_window)
    _fresh()
    clipplane(0, CP_DEFINE, [1.0, 0.0, 0.0, -20.5])
    clipplane(0, CP_ON, [0, 0, 0, 0])
    cpack(RED)
    with pytest.warns(Warning):
        bgnpolygon()
        v2f([0, 0])
        v2f([float("inf"), 0])
        v2f([10, 40])
        endpolygon()
        lit = _lit()
    assert lit.sum() == 0
