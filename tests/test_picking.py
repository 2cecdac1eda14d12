"""pick/gselect, the name stack, mapw/mapw2 and feedback (docs/picking.md).

Expectations come from the man pages: a hit record is the stack depth then
the names, bottom first (endpick(3G)); a hit is recorded only when the name
stack was touched since the last recorded hit, the first hit always
(pick(3G)); the picking region is picksize(3G) pixels (default 10 x 10)
around the cursor; nothing is drawn while picking or selecting.
"""
import math
from pathlib import Path

import numpy as np
import pytest

from irisgl import *
from vgx_emulator.runner import run_program

DEMO = Path(__file__).resolve().parents[1] / "programs" / "demos" / "picking.py"


def _cursor(x, y):
    qenter(MOUSEX, x)
    qenter(MOUSEY, y)


def _records(n, buf):
    out, i = [], 0
    for _ in range(abs(n)):
        d = int(buf[i])
        out.append([int(v) for v in buf[i + 1:i + 1 + d]])
        i += 1 + d
    return out


def _three_rects():
    initnames()
    loadname(1)
    rectf(10, 10, 40, 40)
    loadname(2)
    rectf(60, 60, 90, 90)
    pushname(7)
    rectf(20, 20, 30, 30)


# -- picking -------------------------------------------------------------------
def test_pick_fills_the_buffer_in_place(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    buf = np.full(20, -9, np.int16)
    pick(buf, 20)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    _three_rects()
    n = endpick(buf)
    # loadname(2) touched the stack but its rectangle is far away: no record;
    # pushname(7) touched it again and the small rectangle is under the cursor
    assert n == 2
    assert list(buf[:5]) == [1, 1, 2, 2, 7]
    assert list(buf[5:]) == [-9] * 15          # the rest of the C buffer is untouched


def test_pick_without_buffer_returns_count_and_new_array(open_window):
    open_window(100, 100, pixels=True)
    _cursor(75, 75)
    pick(16)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    _three_rects()
    n, buf = endpick()
    assert n == 1
    assert buf.dtype == np.int16 and buf.shape == (16,)
    assert _records(n, buf) == [[2]]
    assert not buf[2:].any()


def test_nothing_is_drawn_while_picking(open_window):
    open_window(100, 100, pixels=True)
    cpack(0x00FF00)
    _cursor(25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    initnames()
    loadname(1)
    clear()
    rectf(0, 0, 99, 99)
    lrectwrite(0, 0, 3, 3, np.full(16, 0xFFFFFFFF, np.uint32))
    n, buf = endpick()
    assert not lrectread(0, 0, 99, 99).any()
    assert n == 1 and _records(n, buf) == [[1]]
    rectf(0, 0, 99, 99)                     # after endpick drawing works again
    assert lrectread(50, 50, 50, 50)[0, 0] == 0x0000FF00


def test_clear_is_a_hit(open_window):
    """pick(3G) (AIX GL): clear causes hits like the drawing routines."""
    open_window(100, 100, pixels=True)
    _cursor(50, 50)
    pick(10)
    clear()
    loadname(3)
    n, buf = endpick()
    assert _records(n, buf) == [[]]          # recorded with the empty stack


@pytest.mark.parametrize("size, hit", [(None, True), (12, True), (8, False), (2, False)])
def test_picksize_region(open_window, size, hit):
    """The region is size x size pixels centred on the cursor pixel: with the
    cursor at x = 25 a rectangle from x = 29.5 is reached by half widths > 4.5."""
    open_window(100, 100, pixels=True)
    if size is not None:
        picksize(size, size)
    _cursor(25, 50)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(1)
    rectf(29.5, 0, 40, 99)
    n, _ = endpick()
    assert n == (1 if hit else 0)


def test_cursor_is_in_screen_coordinates(open_window):
    prefposition(300, 399, 200, 299)
    winopen("placed")
    RGBmode()
    gconfig()
    _cursor(300 + 25, 200 + 25)                  # window pixel (25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    _three_rects()
    n, buf = endpick()
    assert _records(n, buf) == [[1], [2, 7]]


def test_points_and_lines(open_window):
    open_window(100, 100, pixels=True)
    _cursor(50, 50)
    pick(20)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(1)
    bgnpoint()
    v2f((10, 10))                           # far from the cursor
    endpoint()
    loadname(2)
    bgnpoint()
    v2f((52, 48))                           # inside the 10 x 10 region
    endpoint()
    loadname(3)
    bgnline()
    v2f((0, 51))                            # both ends outside, crosses the region
    v2f((99, 49))
    endline()
    loadname(4)
    bgnline()
    v2f((0, 0))
    v2f((20, 0))
    endline()
    n, buf = endpick()
    assert _records(n, buf) == [[2], [3]]


def test_non_finite_vertices_are_dropped(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(1)
    with pytest.warns(UserWarning, match="non-finite"):
        bgnpolygon()
        for v in ((20, 20), (math.nan, 30), (30, 30)):
            v2f(v)
        endpolygon()
        loadname(2)
    with pytest.warns(UserWarning, match="non-finite"):
        rectf(20, 20, math.inf, 30)
        loadname(3)
    rectf(20, 20, 30, 30)
    n, buf = endpick()
    assert _records(n, buf) == [[3]]


def test_records_follow_the_touch_rule(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    pick(40)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(5)
    rectf(20, 20, 30, 30)
    rectf(21, 21, 29, 29)                  # same names, no touch: no new record
    loadname(5)                             # touched, same contents: a new record
    rectf(20, 20, 30, 30)
    pushname(6)
    pushname(8)
    rectf(20, 20, 30, 30)
    popname()
    popname()
    rectf(20, 20, 30, 30)
    n, buf = endpick()
    assert _records(n, buf) == [[5], [5], [5, 6, 8], [5]]


def test_overflow_gives_negative_count(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    buf = np.zeros(5, np.int16)
    pick(buf, 5)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    for name in (1, 2, 3):
        loadname(name)
        rectf(20, 20, 30, 30)
    n = endpick(buf)
    # [1, 1] and [1, 2] fill 4 of the 5 shorts; the third record does not fit
    assert n == -2
    assert list(buf) == [1, 1, 1, 2, 0]


def test_pick_in_perspective_with_mviewing(open_window):
    open_window(101, 101)
    mmode(MVIEWING)
    perspective(450, 1.0, 1.0, 20.0)
    lookat(0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 0)

    def scene():
        initnames()
        for name, x in ((1, -3.0), (2, 3.0)):
            loadname(name)
            bgnpolygon()
            for dx, dy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                v3f((x + dx, dy, 0.0))
            endpolygon()

    # where x = 3 (z = 0, eye 10 away) lands: NDC 3 / (10 tan 22.5 deg)
    ndc = 3.0 / (10.0 * math.tan(math.radians(22.5)))
    sx = round(-0.5 + (ndc + 1) / 2 * 101)
    for cursor, expect in (((sx, 50), [[2]]), ((100 - sx, 50), [[1]]), ((50, 50), [])):
        _cursor(*cursor)
        pick(10)
        perspective(450, 1.0, 1.0, 20.0)     # restated: times the picking matrix
        scene()
        n, buf = endpick()
        assert _records(n, buf) == expect, cursor


def test_projection_is_restated_around_pick(open_window):
    """Programming Guide 12.1.1: pick changes no matrix (without a restated
    projection every visible object is picked); the restated projection
    is loaded times the picking matrix, and endpick leaves that product."""
    open_window(100, 100, pixels=True)
    plain = getmatrix()
    _cursor(75, 75)
    pick(10)
    assert np.array_equal(getmatrix(), plain)
    _three_rects()                           # not restated: all three are hit
    n, buf = endpick()
    assert _records(n, buf) == [[1], [2], [2, 7]]
    assert np.array_equal(getmatrix(), plain)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    picked = getmatrix()
    # the 10 x 10 region at (75, 75) fills the clip volume: x' = (x - 75) / 5
    assert np.allclose(np.array([75.0, 75.0, 0.0, 1.0]) @ picked, (0, 0, 0, 1), atol=1e-5)
    assert np.allclose(np.array([80.0, 70.0, 0.0, 1.0]) @ picked, (1, -1, 0, 1), atol=1e-5)
    _three_rects()
    endpick()
    assert np.array_equal(getmatrix(), picked)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    assert np.array_equal(getmatrix(), plain)


def test_objects_carry_the_names(open_window):
    open_window(100, 100, pixels=True)
    makeobj(10)
    loadname(1)
    rectf(10, 10, 40, 40)
    loadname(2)
    rectf(60, 60, 90, 90)
    closeobj()
    _cursor(75, 75)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    initnames()
    callobj(10)
    n, buf = endpick()
    assert _records(n, buf) == [[2]]


def test_initnames_leaves_the_slot_loadname_replaces(open_window):
    """initnames then two pushes (SGI's tutorial programs read the names at
    buffer[2] and buffer[3]) records (0, a, b); initnames then loadname
    records the loaded name alone, as the Programming Guide's examples."""
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    buf = np.zeros(12, np.int16)
    pick(buf, 12)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    initnames()
    pushname(1)
    pushname(7)
    rectf(20, 20, 30, 30)
    initnames()
    loadname(3)
    rectf(20, 20, 30, 30)
    assert endpick(buf) == 2
    assert list(buf[:6]) == [3, 0, 1, 7, 1, 3]


# -- name stack outside the modes, errors -----------------------------------------
def test_name_calls_are_ignored_outside_pick_and_select(open_window):
    open_window(100, 100, pixels=True)
    popname()                               # no error: ignored
    pushname(4)
    loadname(5)
    initnames()
    _cursor(25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    rectf(20, 20, 30, 30)
    n, buf = endpick()
    assert _records(n, buf) == [[]]         # nothing was pushed before pick


def test_name_stack_misuse(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    pick(10)
    with pytest.raises(GLError, match="^popname: the name stack is empty"):
        popname()
    for i in range(NAMESTACKDEPTH):
        pushname(i)
    with pytest.raises(GLError, match="^pushname: the name stack is full"):
        pushname(1)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    popname()
    rectf(20, 20, 30, 30)
    n, buf = endpick()
    assert n == 0                           # 1 + 1024 names do not fit in 10 shorts


def test_loadname_wraps_to_a_short(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(40000)
    rectf(20, 20, 30, 30)
    n, buf = endpick()
    assert _records(n, buf) == [[40000 - 65536]]


def test_mode_errors_change_nothing(open_window):
    open_window(100, 100, pixels=True)
    with pytest.raises(GLError, match="^endpick: not picking"):
        endpick()
    with pytest.raises(GLError, match="^pick: the buffer has 4 elements"):
        pick(np.zeros(4, np.int16), 8)
    with pytest.raises(GLError, match="^endselect: not picking"):
        endselect()                         # the failed pick did not start picking
    _cursor(25, 25)
    pick(10)
    with pytest.raises(GLError, match="^gselect: already in picking mode"):
        gselect(10)
    with pytest.raises(GLError, match="^endselect: in picking mode"):
        endselect()
    with pytest.raises(GLError, match="^endpick: the buffer has 3 elements"):
        endpick(np.zeros(3, np.int16))
    ortho2(-0.5, 99.5, -0.5, 99.5)
    loadname(1)
    rectf(20, 20, 30, 30)
    n, buf = endpick()                      # still picking after the errors
    assert _records(n, buf) == [[1]]
    with pytest.raises(GLError, match="^picksize"):
        picksize(0, 10)


# -- selecting -----------------------------------------------------------------------
def test_gselect_uses_the_viewing_volume(open_window):
    open_window(100, 100, pixels=True)
    buf = np.zeros(20, np.int16)
    gselect(buf, 20)
    ortho(0.0, 10.0, 0.0, 10.0, -1.0, 1.0)
    initnames()
    loadname(1)
    rectf(2, 2, 3, 3)                       # inside
    loadname(2)
    rectf(20, 2, 30, 3)                     # right of the volume
    loadname(3)
    rectf(9, 9, 12, 12)                     # reaches in
    loadname(4)
    bgnpolygon()                            # behind the far plane (z = -1 .. 1 kept)
    for x, y in ((2, 2), (3, 2), (3, 3)):
        v3f((x, y, -5.0))
    endpolygon()
    n = endselect(buf)
    assert _records(n, buf) == [[1], [3]]
    assert not lrectread(0, 0, 99, 99).any()


# -- hitcode, feedback -----------------------------------------------------------------
def test_hitcode_is_zero_on_the_vgx(open_window):
    open_window(100, 100, pixels=True)
    _cursor(25, 25)
    pick(10)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    rectf(0, 0, 99, 99)                     # clipped by all four side planes
    endpick()
    assert gethitcode() == 0
    clearhitcode()
    assert gethitcode() == 0


def test_feedback_is_not_emulated(open_window):
    open_window(100, 100, pixels=True)
    with pytest.raises(GLError, match="^feedback: not emulated: .*gl/feed.h"):
        feedback(np.zeros(100, np.int16), 100)
    with pytest.raises(GLError, match="^endfeedback: not emulated"):
        endfeedback(np.zeros(100, np.int16))


# -- mapw / mapw2 ------------------------------------------------------------------------
def test_mapw_gives_the_line_under_the_cursor(open_window):
    open_window(101, 81)
    makeobj(5)
    perspective(600, 101 / 81, 2.0, 12.0)
    lookat(1.0, 2.0, 10.0, 1.0, 2.0, 0.0, 0)
    closeobj()
    # the centre pixel is on the line of sight: the near and far points
    p = mapw(5, 50, 40)
    assert p == pytest.approx((1.0, 2.0, 8.0, 1.0, 2.0, -2.0), abs=1e-5)
    # pixel 0's centre: NDC -1 + 1/101; at distance d the half width is
    # d tan(30 deg) * aspect
    xn = -1 + 1 / 101
    half = math.tan(math.radians(30)) * 101 / 81
    wx1, wy1, wz1, wx2, wy2, wz2 = mapw(5, 0, 40)
    assert (wx1, wz1) == pytest.approx((1.0 + xn * 2.0 * half, 8.0), abs=1e-4)
    assert (wx2, wz2) == pytest.approx((1.0 + xn * 12.0 * half, -2.0), abs=1e-4)
    assert wy1 == pytest.approx(2.0) and wy2 == pytest.approx(2.0)


def test_mapw_leaves_the_window_state_alone(open_window):
    open_window(100, 100, pixels=True)
    before = getmatrix()
    makeobj(6)
    viewport(0, 49, 0, 49)
    ortho2(0.0, 10.0, 0.0, 20.0)
    cpack(0x0000FF)
    rectf(0, 0, 10, 20)                     # not a viewing call: not executed
    closeobj()
    wx, wy = mapw2(6, 25, 0)
    # viewport 50 x 50: pixel 25 is at NDC 2 * 25.5 / 50 - 1, pixel 0 at -1 + 1/50
    assert wx == pytest.approx(10.0 * 25.5 / 50, abs=1e-5)
    assert wy == pytest.approx(20.0 * 0.5 / 50, abs=1e-5)
    assert np.array_equal(getmatrix(), before)
    assert getviewport() == (0, 99, 0, 99)
    assert not lrectread(0, 0, 99, 99).any()
    with pytest.raises(GLError, match="^mapw: object 99 is not defined"):
        mapw(99, 0, 0)


# -- the demo -------------------------------------------------------------------------------
def _block_centre_x(x):
    """Window x of a block's front-face centre (x, 0, 0.8) seen from z = 8
    with perspective(400, 4/3, ...) in a 400 x 300 window."""
    ndc = x / (7.2 * math.tan(math.radians(20.0)) * 400 / 300)
    return round(-0.5 + (ndc + 1) / 2 * 400)


def _pixel(img, x, y):
    return tuple(int(c) for c in img[img.shape[0] - 1 - y, x])


def test_demo_picks_the_block_under_the_cursor(capsys):
    xs = [_block_centre_x(x) for x in (-2.5, 0.0, 2.5)]
    img = run_program(DEMO, frames=2, argv=["pick", str(xs[2]), "150"])
    assert capsys.readouterr().out.splitlines() == ["picked: 3"]
    assert _pixel(img, xs[2], 150) == (255, 255, 0)          # yellow
    assert _pixel(img, xs[0], 150) == (192, 0, 0)            # red, as drawn
    assert _pixel(img, xs[1], 150) == (0, 192, 0)
    img = run_program(DEMO, frames=2, argv=["pick", str(xs[1]), "150"])
    assert capsys.readouterr().out.splitlines() == ["picked: 2"]
    assert _pixel(img, xs[1], 150) == (255, 255, 0)
    assert _pixel(img, xs[2], 150) == (0, 0, 192)


def test_demo_picks_nothing_in_empty_space(capsys):
    img = run_program(DEMO, frames=2, argv=["pick", "20", "20"])
    assert capsys.readouterr().out.splitlines() == ["picked: nothing"]
    xs = [_block_centre_x(x) for x in (-2.5, 0.0, 2.5)]
    assert [_pixel(img, x, 150) for x in xs] == [(192, 0, 0), (0, 192, 0), (0, 0, 192)]


def test_demo_selects_the_blocks_in_the_box(capsys):
    img = run_program(DEMO, frames=2, argv=["select"])
    assert capsys.readouterr().out.splitlines() == ["selected: 1", "selected: 2"]
    xs = [_block_centre_x(x) for x in (-2.5, 0.0, 2.5)]
    assert [_pixel(img, x, 150) for x in xs] == [(0, 255, 255), (0, 255, 255), (0, 0, 192)]


def test_cmov_under_the_cursor_is_a_hit(open_window):
    """pick(3G): cmov causes hits, like drawing; one outside the region does not."""
    open_window(100, 100, pixels=True)
    _cursor(50, 50)
    buf = np.zeros(20, np.int16)
    pick(buf, 20)
    ortho2(-0.5, 99.5, -0.5, 99.5)
    initnames()
    loadname(4)
    cmov2(90, 10)                 # far from the cursor: no hit
    loadname(5)
    cmov2(50, 51)                 # inside the 10 x 10 region
    n = endpick(buf)
    assert _records(n, buf) == [[5]]
