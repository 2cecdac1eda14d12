"""Line width, linestyles, repeat, reset, backup, point size (linewidth(3G),
deflinestyle(3G), setlinestyle(3G), lsrepeat(3G), resetls(3G),
lsbackup(3G), pntsize(3G), linesmooth(3G), pntsmooth(3G))."""
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


def row(y):
    return lit()[y]


def expected_style(pattern, counters, factor=1):
    """On/off of pixels whose linestyle counters are given (bit 0 first)."""
    c = np.asarray(counters)
    return ((pattern >> ((c // factor) % 16)) & 1).astype(bool)


# -- width -------------------------------------------------------------------------
def test_default_width_is_one_pixel(win):
    assert getlwidth() == 1
    move2i(5, 20)
    draw2i(50, 25)
    assert lit()[:, 20].sum() == 1


@pytest.mark.parametrize("n", [2, 3, 5])
def test_xmajor_width_covers_n_pixels_in_y(win, n):
    linewidth(n)
    assert getlwidth() == n
    move2i(5, 20)
    draw2i(50, 25)
    img = lit()
    for x in range(5, 51):
        ys = np.nonzero(img[:, x])[0]
        yc = int(np.floor(20 + 5 * (x - 5) / 45 + 0.5))
        lo = yc - (n - 1) // 2
        assert list(ys) == list(range(lo, lo + n)), x
    assert not img[:, 4].any() and not img[:, 51].any()


@pytest.mark.parametrize("y, rows", [(10.7, [10, 11]), (10.3, [10, 11]), (20.6, [20, 21])])
def test_an_even_subpixel_width_is_centred_on_the_line(win, y, rows):
    """linewidth(3G): "wide lines are centered as nearly as possible on the
    infinitely thin mathematical line": a 2-pixel sub-pixel line covers the
    two rows nearest its exact y (at 10.7, rows 10 and 11: 10.2..11.2), not
    its rounded row and the one above.  Snapped lines keep whole-pixel
    offsets (the test above)."""
    subpixel(TRUE)
    linewidth(2)
    bgnline()
    v2f((5.0, y))
    v2f((50.0, y))
    endline()
    img = lit()
    for x in range(6, 50):
        assert list(np.nonzero(img[:, x])[0]) == rows, x


def test_ymajor_width_covers_n_pixels_in_x(win):
    linewidth(4)
    move2i(30, 2)
    draw2i(33, 40)
    img = lit()
    for y in range(2, 41):
        xs = np.nonzero(img[y])[0]
        assert len(xs) == 4 and xs[-1] - xs[0] == 3, y
    assert img.sum() == 4 * 39


def test_linewidth_zero_draws_one_and_float_rounds(win):
    linewidth(0)
    assert getlwidth() == 0                  # the value given is retained
    move2i(0, 10)
    draw2i(20, 10)
    assert lit()[:, 10].sum() == 1
    linewidthf(2.6)
    assert getlwidth() == 3
    move2i(0, 30)
    draw2i(20, 30)
    assert list(np.nonzero(lit()[:, 10])[0]) == [10, 29, 30, 31]


def test_width_errors_change_nothing(win):
    linewidth(3)
    with pytest.raises(GLError, match="^linewidth"):
        linewidth(-1)
    with pytest.raises(GLError, match="^linewidthf"):
        linewidthf(float("nan"))
    assert getlwidth() == 3


def test_wide_lines_apply_to_closed_lines_and_rect(win):
    linewidth(3)
    recti(10, 10, 30, 30)
    img = lit()
    # the bottom edge (x-major) is 3 rows thick, the left edge 3 columns
    assert list(np.nonzero(img[:, 20])[0]) == [9, 10, 11, 29, 30, 31]
    assert list(np.nonzero(img[20])[0]) == [9, 10, 11, 29, 30, 31]


# -- linestyles -------------------------------------------------------------------
def test_linestyle_least_significant_bit_first(win):
    deflinestyle(1, 0x00FF)
    setlinestyle(1)
    assert getlstyle() == 1
    move2i(0, 10)
    draw2i(63, 10)
    assert (row(10) == expected_style(0x00FF, range(64))).all()
    assert row(10)[:8].all() and not row(10)[8:16].any()


def test_lsrepeat_stretches_each_bit(win):
    deflinestyle(2, 0x5555)
    setlinestyle(2)
    lsrepeat(3)
    assert getlsrepeat() == 3
    move2i(0, 10)
    draw2i(63, 10)
    assert (row(10) == expected_style(0x5555, range(64), 3)).all()
    assert list(row(10)[:9]) == [1, 1, 1, 0, 0, 0, 1, 1, 1]


def test_style_continues_through_a_polyline(win):
    deflinestyle(3, 0x0F0F)
    setlinestyle(3)
    bgnline()
    for x in (0, 13, 27, 50):
        v2i((x, 10))
    endline()
    r = row(10)
    assert (r[:51] == expected_style(0x0F0F, range(51))).all()


def test_resetls_true_restarts_each_line(win):
    deflinestyle(1, 0x0007)
    setlinestyle(1)
    assert getresetls() == 1
    move2i(0, 10)
    draw2i(10, 10)
    move2i(20, 10)
    draw2i(40, 10)
    r = row(10)
    assert (r[0:11] == expected_style(0x0007, range(11))).all()
    assert (r[20:41] == expected_style(0x0007, range(21))).all()


def test_resetls_false_carries_the_pattern_on(win):
    deflinestyle(1, 0x0007)
    setlinestyle(1)
    resetls(FALSE)
    assert getresetls() == 0
    move2i(0, 10)
    draw2i(10, 10)                    # 10 pixel steps
    move2i(20, 10)
    draw2i(40, 10)
    r = row(10)
    assert (r[0:11] == expected_style(0x0007, range(11))).all()
    assert (r[20:41] == expected_style(0x0007, range(10, 31))).all()
    # ... and across flushes: the next line starts at counter 30
    cpack(0x00FF00FF)
    move2i(0, 30)
    draw2i(20, 30)
    assert (row(30)[0:21] == expected_style(0x0007, range(30, 51))).all()


def test_resetls_leaves_graphics_position_undefined(win):
    move2i(10, 10)
    resetls(TRUE)
    assert machine.current.st.gpos is None


def test_lsbackup_colours_last_two_pixels(win):
    deflinestyle(4, 0x0001)
    setlinestyle(4)
    lsbackup(TRUE)
    assert getlsbackup() == 1
    move2i(0, 10)
    draw2i(20, 10)
    assert list(np.nonzero(row(10))[0]) == [0, 16, 19, 20]
    lsbackup(FALSE)
    move2i(0, 12)
    draw2i(20, 12)
    assert list(np.nonzero(row(12))[0]) == [0, 16]


def test_styled_diagonal_keeps_the_solid_line_pixels(win):
    move2i(3, 4)
    draw2i(60, 33)
    solid = lit()
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    deflinestyle(1, 0x3333)
    setlinestyle(1)
    move2i(3, 4)
    draw2i(60, 33)
    styled = lit()
    assert (styled <= solid).all()
    xs = np.arange(3, 61)
    on = expected_style(0x3333, xs - 3)
    assert (styled[:, xs].any(axis=0) == on).all()


def test_clipped_line_keeps_its_pattern_phase(win):
    deflinestyle(1, 0x00FF)
    setlinestyle(1)
    move2i(-20, 10)
    draw2i(63, 10)
    r = row(10)
    assert (r == expected_style(0x00FF, np.arange(64) + 20)).all()


def test_wide_and_styled_together(win):
    deflinestyle(1, 0x0F0F)
    setlinestyle(1)
    linewidth(3)
    move2i(0, 20)
    draw2i(40, 20)
    img = lit()
    on = expected_style(0x0F0F, range(41))
    for y in (19, 20, 21):
        assert (img[y, :41] == on).all()
    assert not img[18].any() and not img[22].any()


def test_linestyle_errors_change_nothing(win):
    with pytest.raises(GLError, match="^deflinestyle"):
        deflinestyle(0, 0x00FF)
    with pytest.raises(GLError, match="^setlinestyle"):
        setlinestyle(77)
    with pytest.raises(GLError, match="^lsrepeat"):
        lsrepeat(0)
    with pytest.raises(GLError, match="^lsrepeat"):
        lsrepeat(256)
    assert getlstyle() == 0 and getlsrepeat() == 1
    move2i(0, 10)
    draw2i(63, 10)
    assert row(10).all()


def test_linestyles_are_shared_by_windows(open_window):
    open_window(16, 16)
    deflinestyle(9, 0x1234)
    open_window(16, 16)
    setlinestyle(9)                  # defined while the other window was current
    assert getlstyle() == 9


def test_redefining_a_style_keeps_lines_already_drawn(win):
    deflinestyle(1, 0xFFFF)
    setlinestyle(1)
    move2i(0, 10)
    draw2i(31, 10)
    deflinestyle(1, 0x0000)          # the line above is already issued
    assert row(10)[:32].all()


def test_line_modes_record_into_objects(win):
    makeobj(1)
    linewidth(3)
    deflinestyle(5, 0x00FF)         # immediate: runs now, not recorded
    setlinestyle(5)
    move2i(0, 20)
    draw2i(40, 20)
    closeobj()
    assert getlwidth() == 1 and getlstyle() == 0
    callobj(1)
    assert getlwidth() == 3 and getlstyle() == 5
    img = lit()
    on = expected_style(0x00FF, range(41))
    assert (img[19:22, :41] == on).all()


# -- points ---------------------------------------------------------------------------
@pytest.mark.parametrize("n,lo", [(1, 10), (2, 10), (3, 9), (4, 9)])
def test_pntsize_draws_a_square(win, n, lo):
    pntsize(n)
    pnt2i(10, 10)
    ys, xs = np.nonzero(lit())
    assert sorted(set(xs)) == list(range(lo, lo + n))
    assert sorted(set(ys)) == list(range(lo, lo + n))
    assert len(xs) == n * n


def test_pntsizef_rounds_and_errors(win):
    pntsizef(2.4)
    pnt2i(30, 30)
    assert lit().sum() == 4
    with pytest.raises(GLError, match="^pntsize"):
        pntsize(-2)
    assert machine.current.st.pntsize == 2.4


# -- smoothing: kept as state ----------------------------------------------------------
def test_linesmooth_and_pntsmooth_state(win):
    linesmooth(SML_ON + SML_SMOOTHER + SML_END_CORRECT)
    assert machine.current.st.linesmooth == SML_ON | SML_SMOOTHER | SML_END_CORRECT
    with pytest.raises(GLError, match="^linesmooth"):
        linesmooth(SML_SMOOTHER)            # a modifier without SML_ON
    assert machine.current.st.linesmooth == 7
    smoothline(FALSE)
    assert machine.current.st.linesmooth == SML_OFF
    pntsmooth(SMP_ON)
    assert machine.current.st.pntsmooth == SMP_ON
    with pytest.raises(GLError, match="^pntsmooth"):
        pntsmooth(8)
    assert machine.current.st.pntsmooth == SMP_ON


# -- antialiasing -----------------------------------------------------------------------
def test_linesmooth_rgb_shares_coverage_across_the_minor_axis(win):
    blendfunction(BF_SA, BF_MSA)
    linesmooth(SML_ON)
    cpack(0xFFFFFFFF)
    move2i(0, 10)
    draw2i(40, 20)                    # y = 10 + x / 4
    img = lrectread(0, 0, W - 1, H - 1)
    red = (img & 0xFF).astype(int)
    for x in range(0, 41):
        y = 10 + x / 4
        lo = int(np.floor(y))
        f = y - lo
        col = red[:, x]
        assert abs(col[lo] - 255 * (1 - f)) <= 1.5, x
        if f:
            assert abs(col[lo + 1] - 255 * f) <= 1.5, x
        others = np.delete(col, [lo, lo + 1])
        assert not others.any(), x
    # half coverage at x = 2 (y = 10.5): both pixels about half bright
    assert 120 <= red[10, 2] <= 135 and 120 <= red[11, 2] <= 135


def test_linesmooth_cmode_puts_coverage_in_the_low_bits(open_window):
    open_window(W, H, rgb=False)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    color(0)
    clear()
    linesmooth(SML_ON)
    color(0x30)                        # the ramp 0x30..0x3F
    move2i(0, 10)
    draw2i(40, 20)
    img = lrectread(0, 0, W - 1, H - 1)
    assert img[10, 0] == 0x3F and img[11, 0] == 0          # on the line: full coverage
    assert img[10, 2] == 0x38 and img[11, 2] == 0x38       # y = 10.5: half each
    assert img[10, 1] == 0x30 | 11 and img[11, 1] == 0x30 | 4   # y = 10.25


def test_linesmooth_off_draws_aliased(win):
    linesmooth(SML_ON)
    linesmooth(SML_OFF)
    move2i(0, 10)
    draw2i(40, 20)
    assert lit().sum() == 41


def test_pntsmooth_spreads_a_subpixel_point(win):
    subpixel(TRUE)
    blendfunction(BF_SA, BF_MSA)
    pntsmooth(SMP_ON)
    pnt2(10.25, 20.5)
    img = lrectread(0, 0, W - 1, H - 1) & 0xFF
    assert abs(int(img[20, 10]) - 255 * 0.75 * 0.5) <= 1.5
    assert abs(int(img[20, 11]) - 255 * 0.25 * 0.5) <= 1.5
    assert abs(int(img[21, 10]) - 255 * 0.75 * 0.5) <= 1.5
    assert abs(int(img[21, 11]) - 255 * 0.25 * 0.5) <= 1.5
    assert np.count_nonzero(img) == 4


def test_styled_half_open_subpixel_line(win):
    subpixel(TRUE)
    deflinestyle(1, 0x00FF)
    setlinestyle(1)
    move2i(0, 10)
    draw2i(32, 10)                     # half-open: pixels 0..31
    r = row(10)
    assert (r[:32] == expected_style(0x00FF, range(32))).all() and not r[32:].any()


def test_wide_line_in_colour_map_mode(open_window):
    open_window(W, H, rgb=False)
    ortho2(-0.5, W - 0.5, -0.5, H - 0.5)
    color(0)
    clear()
    color(7)
    linewidth(2)
    move2i(0, 10)
    draw2i(40, 10)
    img = lrectread(0, 0, W - 1, H - 1)
    assert (img[10:12, :41] == 7).all() and img.sum() == 7 * 2 * 41


def test_polygon_outlines_style_restarts_per_polygon(win):
    polymode(PYM_LINE)
    deflinestyle(1, 0x000F)
    setlinestyle(1)
    rectfi(2, 2, 30, 12)
    rectfi(2, 20, 30, 30)
    img = lit()
    # both bottom edges start the pattern at their first corner
    assert (img[2, 2:31] == expected_style(0x000F, range(29))).all()
    assert (img[20, 2:31] == expected_style(0x000F, range(29))).all()
