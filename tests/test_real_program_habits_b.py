"""Habits of real IRIS GL programs of 1988-1993, ported line by line, that
irisgl once got wrong.  Each expectation comes from the IRIX man page of
the call (cited per test), not from the program that showed the problem."""
import numpy as np
import pytest

import irisgl
from irisgl import *
from irisgl._current import machine


# -- lmdef(3G): C passes NULL, often written 0, for "defaults" -----------------
def test_lmdef_props_zero_is_null_and_gives_the_defaults(open_window):
    """lmdef(DEFLIGHT, 1, 0, 0): props is a NULL pointer; the definition gets
    the default light (white, from +z at infinity), as lmdef(3G) says of an
    empty property list.  A lit face toward the light is then as bright as
    with the default light defined through None."""
    def lit_pixel(props):
        machine.reset()
        open_window(16, 16)
        mmode(MVIEWING)
        ortho(-1, 1, -1, 1, -1, 1)
        lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 1.0, 0.0, 0.0, LMNULL])
        lmdef(DEFLIGHT, 1, 0, props)
        lmdef(DEFLMODEL, 1, 0, props)
        lmbind(MATERIAL, 1)
        lmbind(LIGHT0, 1)
        lmbind(LMODEL, 1)
        cpack(0)
        clear()
        bgnpolygon()
        for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            n3f((0.0, 0.0, 1.0))
            v3f((x, y, 0.0))
        endpolygon()
        return int(lrectread(8, 8, 8, 8)[0, 0])
    with_zero = lit_pixel(0)
    with_none = lit_pixel(None)
    assert with_zero == with_none
    # default light (LCOLOR 1,1,1 from +z) on diffuse 1,0,0 facing it: full
    # red; green and blue get only the small ambient term (material ambient
    # 0.2 times light-model ambient 0.2)
    r, g, b = with_zero & 0xFF, (with_zero >> 8) & 0xFF, (with_zero >> 16) & 0xFF
    assert r == 255 and g == b and 0 < g < 26


def test_lmdef_props_other_integer_is_still_an_error(open_window):
    open_window(8, 8)
    with pytest.raises(GLError, match="^lmdef"):
        lmdef(DEFLIGHT, 1, 0, 5)


# -- minsize(3G)/maxsize/keepaspect shape a window opened without prefsize ------
def test_minsize_bounds_the_window_winopen_gives():
    """minsize(3G): the window manager does not let a window be smaller than
    the minimum; a program that asks minsize(512, 512) and then winopen
    without prefsize must get at least 512 x 512."""
    minsize(512, 512)
    winopen("min")
    w, h = getsize()
    assert w >= 512 and h >= 512


def test_maxsize_bounds_the_window_winopen_gives():
    maxsize(300, 200)
    winopen("max")
    w, h = getsize()
    assert w <= 300 and h <= 200


def test_keepaspect_shapes_the_window_winopen_gives():
    """keepaspect(3G): the window's width:height is x:y."""
    keepaspect(1, 1)
    winopen("square")
    w, h = getsize()
    assert w == h


def test_prefsize_wins_over_minsize():
    """prefsize(3G) fixes the size; the constraints only bound later reshapes."""
    minsize(512, 512)
    prefsize(100, 80)
    winopen("pref")
    assert getsize() == (100, 80)


# -- the runner: no expose a real window would not get --------------------------
SINGLE_BUFFERED_CLICK = '''
from irisgl import *
prefsize(40, 30)
winopen("click")
qdevice(LEFTMOUSE)
setvaluator(MOUSEX, 10, 0, 1279)
setvaluator(MOUSEY, 12, 0, 1023)
qenter(LEFTMOUSE, 1)
while TRUE:
    dev, val = qread()
    if dev == REDRAW:
        reshapeviewport()
        color(BLACK)
        clear()
    elif dev == LEFTMOUSE and val:
        color(GREEN)
        pnt2i(getvaluator(MOUSEX), getvaluator(MOUSEY))
'''


def test_runner_keeps_what_a_single_buffered_program_drew_on_input(tmp_path):
    """A single-buffered colour-map program (no swapbuffers, no gflush) that
    clears on REDRAW and draws a point on LEFTMOUSE: a REDRAW comes only
    when the window system exposes the window (qdevice(3G)), so the point
    drawn on the click must still be there when the program ends."""
    from vgx_emulator import run_program
    prog = tmp_path / "click.py"
    prog.write_text(SINGLE_BUFFERED_CLICK)
    img = run_program(prog, frames=3)
    assert img.shape == (30, 40, 3)
    lit = np.argwhere(img.sum(axis=-1) > 0)
    assert [tuple(p) for p in lit] == [(30 - 1 - 12, 10)]     # row from the top
    assert tuple(img[30 - 1 - 12, 10]) == (0, 255, 0)


# -- mapw(3G): the line from the near to the far point covers one pixel ----------
def test_mapw_line_projects_to_the_window_point():
    """mapw(3G) gives the world points on the near and far clipping planes
    under a window point; drawn with the same transformation, the line
    between them covers exactly that pixel."""
    prefsize(64, 64)
    winopen("mapw")
    color(BLACK)
    clear()
    perspective(440, 1.0, 1.0, 1500.0)
    makeobj(6)
    perspective(440, 1.0, 1.0, 1500.0)
    closeobj()
    wx1, wy1, wz1, wx2, wy2, wz2 = mapw(6, 13, 50)
    assert wz1 == pytest.approx(-1.0, abs=1e-4)
    assert wz2 == pytest.approx(-1500.0, rel=1e-3)
    color(GREEN)
    move(wx1, wy1, wz1)
    draw(wx2, wy2, wz2)
    img = lrectread(0, 0, 63, 63)
    assert [tuple(p) for p in np.argwhere(img != 0)] == [(50, 13)]


# -- lmdef(3G): np counted in bytes (sizeof(array)) ------------------------------
def test_lmdef_np_larger_than_the_list_reads_up_to_lmnull(open_window):
    """4Dgifts programs call lmdef(DEFMATERIAL, 1, sizeof(array), array):
    np is then four times the float count, and the C library still stops
    reading at LMNULL (lmdef(3G): props ends with LMNULL).  The definition
    is the same as with np = 0."""
    def red_of(np_):
        machine.reset()
        open_window(8, 8)
        mmode(MVIEWING)
        ortho(-1, 1, -1, 1, -1, 1)
        props = [DIFFUSE, 0.5, 0.0, 0.0, AMBIENT, 0.0, 0.0, 0.0, LMNULL]
        lmdef(DEFMATERIAL, 1, np_, props)
        lmdef(DEFLIGHT, 1, 0, None)
        lmdef(DEFLMODEL, 1, 0, None)
        lmbind(MATERIAL, 1)
        lmbind(LIGHT0, 1)
        lmbind(LMODEL, 1)
        cpack(0)
        clear()
        bgnpolygon()
        for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            n3f((0.0, 0.0, 1.0))
            v3f((x, y, 0.0))
        endpolygon()
        return int(lrectread(4, 4, 4, 4)[0, 0]) & 0xFF
    assert red_of(4 * 9) == red_of(0) == round(0.5 * 255)
    # too small (showring.c: 11 for a list of 15): a hint too, read to LMNULL
    assert red_of(3) == red_of(1) == round(0.5 * 255)


def test_lmdef_np_past_a_list_without_lmnull_is_still_an_error(open_window):
    open_window(8, 8)
    with pytest.raises(GLError, match="^lmdef: .*LMNULL"):
        lmdef(DEFMATERIAL, 1, 40, [DIFFUSE, 0.5, 0.0, 0.0])


# -- gversion(3G): C fills a char buffer ----------------------------------------
def test_gversion_fills_a_byte_buffer_as_c_does():
    """gversion(3G) writes the NUL-terminated version string into the
    caller's buffer; the string starts with GL4D on an IRIS-4D."""
    buf = bytearray(12)
    assert gversion(buf) == 0
    s = bytes(buf).split(b"\0")[0].decode()
    assert s == gversion()[1] and s.startswith("GL4DVGX")


def test_gversion_refuses_an_immutable_str():
    with pytest.raises(GLError, match="^gversion"):
        gversion("")


# -- lrectread/lrectwrite(3G) with C-sized buffers --------------------------------
def test_lrectread_fills_a_python_list_and_the_first_words_of_a_larger_buffer(open_window):
    """lrectread(3G) stores (x2-x1+1)*(y2-y1+1) words into parray: a
    `buf = [0] * n` list is filled in place, a larger buffer in its first
    words (the rest untouched), left to right, bottom to top."""
    open_window(8, 8)
    cpack(0xFF0000FF)
    clear()
    cpack(0xFF00FF00)
    pnt2i(1, 0)                      # bottom row, second pixel
    buf = [7] * 6
    assert lrectread(0, 0, 1, 1, buf) == 4
    assert buf == [0xFF0000FF, 0xFF00FF00, 0xFF0000FF, 0xFF0000FF, 7, 7]
    big = np.full(10, 3, np.uint32)
    assert lrectread(0, 0, 1, 1, big) == 4
    assert list(big) == [0xFF0000FF, 0xFF00FF00, 0xFF0000FF, 0xFF0000FF] + [3] * 6
    with pytest.raises(GLError, match="^lrectread"):
        lrectread(0, 0, 1, 1, [0] * 3)


def test_lrectwrite_reads_the_first_words_of_a_larger_array(open_window):
    """lrectwrite(3G) reads (x2-x1+1)*(y2-y1+1) words from parray; a C
    image buffer larger than the rectangle is read from its start."""
    open_window(8, 8)
    cpack(0)
    clear()
    image = [0xFF000001, 0xFF000002, 0xFF000003, 0xFF000004] + [0xFFFFFFFF] * 60
    lrectwrite(2, 3, 3, 4, image)
    got = lrectread(2, 3, 3, 4)
    assert got.tolist() == [[0xFF000001, 0xFF000002], [0xFF000003, 0xFF000004]]
    assert int(lrectread(4, 3, 4, 3)[0, 0]) == 0        # nothing written past x2
    with pytest.raises(GLError, match="^lrectwrite"):
        lrectwrite(2, 3, 3, 4, image[:3])


POLLING_LOOP = '''
from irisgl import *
prefposition(10, 49, 10, 39)
gid = winopen("poll")
qdevice(ESCKEY)
qdevice(REDRAW)
qenter(REDRAW, gid)
while TRUE:
    if qtest():
        dev, val = qread()
        if dev == ESCKEY:
            gexit()
        elif dev == REDRAW:
            reshapeviewport()
            color(BLUE)
            clear()
'''


def test_runner_ends_a_loop_that_only_polls_qtest(tmp_path):
    """GL reference examples (curve1.c) loop on `if (qtest())` and draw only
    on REDRAW, single-buffered, never marking a frame.  qtest(3G) does not
    wait, so with nothing left to come the runner must still end the
    program (docs/porting.md: a program waiting for input must not
    hang headless), keeping what it drew."""
    from vgx_emulator import run_program
    prog = tmp_path / "poll.py"
    prog.write_text(POLLING_LOOP)
    img = run_program(prog, frames=3)
    assert img.shape == (30, 40, 3)
    assert np.all(img == (0, 0, 255))


# -- crv(3G) on a pointer into a larger table -------------------------------------
def test_crv_reads_the_first_four_points_of_a_longer_table(open_window):
    """crv(3G) takes the 4 control points of one segment; curve editors pass
    &geom[i][0], a pointer into a longer table (Python: geom[i:]), and C
    reads the first 4 rows from there.  The curve drawn is the one of those
    4 points; fewer than 4 points is still an error."""
    bezier = [[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]]
    table = [[5.0, 5.0, 0.0], [10.0, 50.0, 0.0], [50.0, 50.0, 0.0], [55.0, 5.0, 0.0],
             [60.0, 60.0, 0.0], [0.0, 60.0, 0.0]]

    def drawn(geom):
        cpack(0)
        clear()
        cpack(0xFFFFFFFF)
        crv(geom)
        return lrectread(0, 0, 63, 63)

    open_window(64, 64)
    defbasis(1, bezier)
    curvebasis(1)
    curveprecision(16)
    whole = drawn(table)
    first4 = drawn(table[:4])
    assert np.array_equal(whole, first4) and (first4 != 0).sum() > 40
    # the Bezier segment ends at points 0 and 3 (crv(3G) with a Bezier basis)
    assert first4[5, 5] != 0 and first4[5, 55] != 0
    with pytest.raises(GLError, match="^crv"):
        crv(table[:3])
