"""Geometry extras: scrbox/getscrbox, screenspace, xfpt*, blendcolor,
bbox2 culling in objects, callfunc, newtag/deltag, curveit, and the
fog_cutaway demo (docs/clip-planes-fog-and-extras.md)."""
import math
from pathlib import Path

import numpy as np
import pytest

from irisgl import (ENDTAG, GD_BLENDCOLOR, GD_SCRBOX, GD_XPMAX, GD_YPMAX, GLError, SB_HOLD,
                    SB_RESET, SB_TRACK, STARTTAG, bbox2, bbox2i, bbox2s, bgnline, bgnpoint,
                    blendcolor, callfunc, callobj, clear, closeobj, cpack, crv, curvebasis,
                    curveit, curveprecision, defbasis, deltag, editobj, endline, endpoint,
                    getgdesc, getscrbox, getviewport, istag, lrectread, makeobj, maketag,
                    move, multmatrix, newtag, objreplace, pnt2, popmatrix, prefposition,
                    pushmatrix, rectf, screenspace, scrbox, scrmask, translate,
                    v2f, winopen, RGBmode, gconfig, xfpt, xfpt2, xfpt2i, xfpt2s, xfpt4, xfpt4i,
                    xfpt4s, xfpti, xfpts, linewidth)

W, H = 64, 48
WHITE = 0xFFFFFFFF


def _lit():
    return (lrectread(0, 0, W - 1, H - 1) & 0xFFFFFF) != 0


def _black():
    cpack(0)
    clear()


def _drawn_box(lit):
    ys, xs = np.nonzero(lit)
    return xs.min(), xs.max(), ys.min(), ys.max()


# -- scrbox ---------------------------------------------------------------------
def test_scrbox_tracks_a_rectangle_exactly(open_window):
    assert getgdesc(GD_SCRBOX) == 1
    open_window(W, H)
    _black()
    scrbox(SB_TRACK)
    cpack(WHITE)
    rectf(10, 5, 20, 15)
    box = getscrbox()
    assert box == (10, 20, 5, 15)
    l, r, b, t = _drawn_box(_lit())
    assert box[0] <= l and r <= box[1] and box[2] <= b and t <= box[3]


def test_scrbox_grows_and_holds(open_window):
    open_window(W, H)
    _black()
    scrbox(SB_TRACK)
    cpack(WHITE)
    rectf(10, 5, 20, 15)
    bgnline()
    v2f([30, 30])
    v2f([40, 44])
    endline()
    assert getscrbox() == (10, 40, 5, 44)
    scrbox(SB_HOLD)
    rectf(50, 1, 60, 2)                    # drawn, not tracked
    bgnpoint()
    v2f([2, 46])
    endpoint()
    assert getscrbox() == (10, 40, 5, 44)
    scrbox(SB_TRACK)                       # tracking again grows the held box
    bgnpoint()
    v2f([2, 46])
    endpoint()
    assert getscrbox() == (2, 40, 5, 46)


def test_scrbox_reset_and_clears(open_window):
    open_window(W, H)
    l, r, b, t = getscrbox()               # initial: reset, nothing drawn
    assert l > r and b > t
    scrbox(SB_TRACK)
    cpack(WHITE)
    clear()                                # clears do not count
    l, r, b, t = getscrbox()
    assert l > r and b > t
    rectf(3, 4, 5, 6)
    assert getscrbox() == (3, 5, 4, 6)
    scrbox(SB_RESET)
    rectf(30, 4, 35, 6)                    # reset also stops tracking
    l, r, b, t = getscrbox()
    assert l > r and b > t


def test_scrbox_is_limited_to_what_is_scan_converted(open_window):
    """Geometry beyond the window or the scrmask is not scan converted."""
    open_window(W, H)
    scrbox(SB_TRACK)
    cpack(WHITE)
    rectf(-40, 10, 30, 100)
    assert getscrbox() == (0, 30, 10, H - 1)
    scrbox(SB_RESET)
    scrbox(SB_TRACK)
    scrmask(5, 40, 0, 20)
    rectf(0, 0, 63, 47)
    assert getscrbox() == (5, 40, 0, 20)


def test_scrbox_wide_lines_and_points(open_window):
    open_window(W, H)
    _black()
    scrbox(SB_TRACK)
    cpack(WHITE)
    linewidth(3)
    bgnline()
    v2f([10, 20])
    v2f([40, 20])
    endline()
    box = getscrbox()
    l, r, b, t = _drawn_box(_lit())
    assert box[0] <= l and r <= box[1] and box[2] <= b and t <= box[3]
    assert (box[2], box[3]) == (19, 21)       # a 3-wide x-major line: rows 19..21
    linewidth(1)
    pnt2(50, 40)
    assert getscrbox() == (box[0], 50, 19, 40)


def test_scrbox_tracks_characters(open_window):
    from irisgl import charstr, cmov2i
    open_window(W, H)
    _black()
    scrbox(SB_TRACK)
    cpack(WHITE)
    cmov2i(5, 10)
    charstr("Hi")
    box = getscrbox()
    l, r, b, t = _drawn_box(_lit())
    assert box == (l, r, b, t)                   # glyph pixels: the box is exact


def test_scrbox_errors(open_window):
    open_window(W, H)
    scrbox(SB_TRACK)
    with pytest.raises(GLError, match="scrbox: unknown arg"):
        scrbox(3)
    cpack(WHITE)
    rectf(1, 1, 2, 2)
    assert getscrbox() == (1, 2, 1, 2)         # still tracking


# -- screenspace, xfpt, blendcolor -------------------------------------------------
def test_screenspace_maps_absolute_screen_pixels():
    prefposition(100, 100 + W - 1, 200, 200 + H - 1)
    winopen("ss")
    RGBmode()
    gconfig()
    screenspace()
    xp, yp = getgdesc(GD_XPMAX), getgdesc(GD_YPMAX)
    assert getviewport() == (-100, xp - 100, -200, yp - 200)
    cpack(0)
    clear()
    cpack(WHITE)
    pnt2(105, 207)                         # screen pixel -> window pixel (5, 7)
    lit = _lit()
    assert lit.sum() == 1 and lit[7, 5]


@pytest.mark.parametrize("call, args", [(xfpt, (1, 2, 3)), (xfpti, (1, 2, 3)),
                                        (xfpts, (1, 2, 3)), (xfpt2, (1, 2)),
                                        (xfpt2i, (1, 2)), (xfpt2s, (1, 2)),
                                        (xfpt4, (1, 2, 3, 1)), (xfpt4i, (1, 2, 3, 1)),
                                        (xfpt4s, (1, 2, 3, 1))])
def test_xfpt_is_not_emulated(call, args):
    with pytest.raises(GLError, match=rf"^{call.__name__}: not emulated: .*feedback"):
        call(*args)


def test_blendcolor_is_not_on_the_vgx():
    assert getgdesc(GD_BLENDCOLOR) == 0
    with pytest.raises(GLError, match="^blendcolor: not emulated: .*VGX"):
        blendcolor(1.0, 0.5, 0.25, 1.0)


# -- bbox2 -----------------------------------------------------------------------
def _boxed_object(obj, xmin, ymin, box, call=bbox2):
    makeobj(obj)
    cpack(WHITE)
    call(xmin, ymin, *box)
    rectf(box[0], box[1], box[2], box[3])
    closeobj()


def test_bbox2_culls_small_and_keeps_large(open_window):
    open_window(W, H)
    _black()
    _boxed_object(1, 8, 8, (10, 10, 15, 15))      # 5 x 5 pixels: smaller than 8 x 8
    callobj(1)
    assert _lit().sum() == 0
    _boxed_object(2, 4, 4, (10, 10, 15, 15))      # larger than 4 x 4
    callobj(2)
    assert _lit().sum() > 0
    _black()
    _boxed_object(3, 8, 2, (10, 10, 15, 15))      # small in x, not in y: drawn
    callobj(3)
    assert _lit().sum() > 0


def test_bbox2_prunes_outside_the_viewport(open_window):
    open_window(W, H)
    _black()
    _boxed_object(1, 0, 0, (10, 10, 20, 20), bbox2i)
    pushmatrix()
    translate(100.0, 0.0, 0.0)                    # wholly right of the viewport
    callobj(1)
    popmatrix()
    assert _lit().sum() == 0
    pushmatrix()
    translate(50.0, 0.0, 0.0)                     # partly inside: drawn
    callobj(1)
    popmatrix()
    assert _lit().sum() > 0


def test_bbox2_skips_only_the_rest_of_its_object(open_window):
    open_window(W, H)
    _black()
    makeobj(5)
    cpack(WHITE)
    rectf(1, 1, 3, 3)                               # before bbox2: drawn
    bbox2s(50, 50, 10, 10, 12, 12)
    rectf(10, 10, 12, 12)                           # skipped
    closeobj()
    makeobj(6)
    callobj(5)
    cpack(WHITE)
    rectf(30, 30, 33, 33)                           # the caller goes on
    closeobj()
    callobj(6)
    lit = _lit()
    assert lit[2, 2] and lit[31, 31] and not lit[10:13, 10:13].any()


def test_bbox2_immediate_draws_nothing_and_validates(open_window):
    open_window(W, H)
    _black()
    bbox2(100, 100, 0, 0, 1, 1)
    cpack(WHITE)
    rectf(1, 1, 3, 3)                               # nothing to skip outside objects
    assert _lit().sum() > 0
    with pytest.raises(GLError, match="bbox2"):
        bbox2(float("inf"), 2, 0, 0, 1, 1)     # a finite float is truncated, as C does


# -- callfunc ---------------------------------------------------------------------
def test_callfunc_immediate_and_in_objects(open_window):
    open_window(W, H)
    seen = []
    callfunc(seen.append, 1, "now")
    assert seen == ["now"]
    makeobj(4)
    callfunc(seen.append, 1, "replay")
    callfunc(lambda a, b: seen.append(a + b), 2, 20, 22, "ignored")
    closeobj()
    assert seen == ["now"]                           # recorded, not called
    callobj(4)
    callobj(4)
    assert seen == ["now", "replay", 42, "replay", 42]


def test_callfunc_errors(open_window):
    open_window(W, H)
    with pytest.raises(GLError, match="callfunc: .*not a function"):
        callfunc(42, 0)
    with pytest.raises(GLError, match="callfunc: nargs 2"):
        callfunc(print, 2, "only one")


# -- newtag / deltag ----------------------------------------------------------------
def test_newtag_places_a_tag_after_routines(open_window):
    open_window(W, H)
    seen = []
    makeobj(1)
    maketag(10)
    callfunc(seen.append, 1, "a")
    callfunc(seen.append, 1, "b")
    callfunc(seen.append, 1, "c")
    closeobj()
    editobj(1)
    newtag(11, 10, 2)                 # after "a" and "b"
    assert istag(11)
    objreplace(11)                    # replaces "c" (up to the end)
    callfunc(seen.append, 1, "C")
    closeobj()
    callobj(1)
    assert seen == ["a", "b", "C"]


def test_newtag_errors_leave_the_object(open_window):
    open_window(W, H)
    makeobj(1)
    maketag(10)
    callfunc(print, 0)
    with pytest.raises(GLError, match="newtag: offset 2"):
        newtag(11, 10, 2)
    with pytest.raises(GLError, match="already"):
        newtag(10, 10, 0)
    with pytest.raises(GLError, match="tag 99 is not"):
        newtag(11, 99, 0)
    assert not istag(11)
    closeobj()
    with pytest.raises(GLError, match="newtag"):
        newtag(12, 10, 0)                       # no object open


def test_deltag(open_window):
    open_window(W, H)
    seen = []
    makeobj(1)
    maketag(1)
    callfunc(seen.append, 1, "x")
    maketag(2)
    callfunc(seen.append, 1, "y")
    deltag(1)
    assert not istag(1) and istag(2)
    with pytest.raises(GLError, match="deltag: STARTTAG"):
        deltag(STARTTAG)
    with pytest.raises(GLError, match="deltag"):
        deltag(ENDTAG)
    with pytest.raises(GLError, match="tag 1 is not"):
        deltag(1)
    callfunc(seen.append, 1, "z")                  # the edit point is still at the end
    closeobj()
    callobj(1)
    assert seen == ["x", "y", "z"]                 # the routines stay


# -- curveit ----------------------------------------------------------------------
BEZIER = [[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]]
GEOM = [[5.0, 5.0, 0.0], [20.0, 44.0, 0.0], [44.0, 44.0, 0.0], [60.0, 5.0, 0.0]]


def _forward_difference_matrix(n):
    """The Programming Guide's E (precision n) times the Bezier basis times
    the geometry: the matrix curveit iterates."""
    e = np.array([[6.0 / n ** 3, 0, 0, 0], [6.0 / n ** 3, 2.0 / n ** 2, 0, 0],
                  [1.0 / n ** 3, 1.0 / n ** 2, 1.0 / n, 0], [0, 0, 0, 1]])
    g = np.concatenate((np.array(GEOM), np.ones((4, 1))), axis=1)
    return e @ np.array(BEZIER, float) @ g


def test_curveit_draws_what_crv_draws(open_window):
    n = 12
    open_window(W, H)
    _black()
    defbasis(1, BEZIER)
    curvebasis(1)
    curveprecision(n)
    cpack(WHITE)
    crv(GEOM)
    want = _lit()
    _black()
    cpack(WHITE)
    pushmatrix()
    multmatrix(_forward_difference_matrix(n))
    move(0.0, 0.0, 0.0)
    curveit(n)
    popmatrix()
    got = _lit()
    assert got.sum() > 40
    assert (got == want).all()
    ys, xs = np.nonzero(got)
    assert (xs.min(), xs.max()) == (5, 60)
    # the top of the Bezier: y(1/2) = (5 + 3 * 44 + 3 * 44 + 5) / 8 = 34.25
    assert ys.max() == 34


def test_curveit_iterates_a_copy_and_validates(vgx, open_window):
    open_window(W, H)
    _black()
    m = _forward_difference_matrix(4)
    pushmatrix()
    multmatrix(m)
    from irisgl import getmatrix
    before = getmatrix().copy()
    cpack(WHITE)
    curveit(0)
    assert _lit().sum() == 0
    curveit(4)
    assert (getmatrix() == before).all()
    with pytest.raises(GLError, match="curveit: count -1"):
        curveit(-1)
    popmatrix()
    assert _lit().sum() > 0


# -- the demo ---------------------------------------------------------------------
DEMO = Path(__file__).resolve().parents[1] / "programs" / "demos" / "fog_cutaway.py"
FOG = (153, 153, 204)


def _screen(x, y, z):
    """Window pixel (column, row from the top) of eye point (x, y, z) under
    perspective(450, 4/3) in a 400 x 300 window."""
    s = 150.0 / math.tan(math.radians(22.5))
    return int(round(200 + s * x / -z)), 299 - int(math.floor(150 + s * y / -z))


def _fogged(f, c):
    return np.array([f * a + (1 - f) * b for a, b in zip(c, FOG)])


def test_demo_fog_and_cutaway():
    from vgx_emulator.runner import run_program
    img = run_program(DEMO, 1, []).astype(int)
    assert img.shape == (300, 400, 3)
    assert tuple(img[10, 10]) == FOG                     # sky: cleared to the fog colour
    # the ball: its left half is there, its right half is cut away (sky shows)
    c, r = _screen(-1.0, 0.0, -12.0 + 2.3)
    assert img[r, c, 0] > 150 and img[r, c, 1] < 120 and img[r, c, 2] < 60
    c, r = _screen(1.0, 0.3, -12.0 + 2.3)
    assert tuple(img[r, c]) == FOG
    # posts at depth 20 and 50: linear fog start 5, end 60
    c, r = _screen(6.0, -0.5, -20.0)
    assert np.abs(img[r, c] - _fogged(40 / 55, (255, 255, 0))).max() <= 1
    c, r = _screen(6.0, -0.5, -50.0)
    assert np.abs(img[r, c] - _fogged(10 / 55, (255, 255, 0))).max() <= 1
    # the bottom row lies in the first row of squares (depth 3..7): its near
    # vertices are unfogged, its far ones at f = 53/55, so it is almost green
    greens = np.array([(0x60, 0xC0, 0x60), (0x20, 0x80, 0x20)])
    assert np.abs(greens - img[299, 100]).max(axis=1).min() <= 4
    # far ground (squares beyond depth 60) is fog coloured
    c, r = _screen(0.0, -2.0, -70.0)
    assert np.abs(img[r - 1, c] - FOG).max() <= 3


def test_demo_exp2_haze():
    from vgx_emulator.runner import run_program
    img = run_program(DEMO, 1, ["exp2"]).astype(int)
    assert tuple(img[10, 10]) == FOG
    c, r = _screen(6.0, -0.5, -20.0)
    f = 255.0 ** -((0.03 * 20.0) ** 2)
    assert np.abs(img[r, c] - _fogged(f, (255, 255, 0))).max() <= 1
