"""Habits of real IRIS GL programs of the era, as a line-by-line Python port
writes them (SGI demo programs: window placement from XMAXSCREEN arithmetic,
float values passed to integer parameters, ``float m[4][4]`` filled by
getmatrix).  Expectations follow the man pages and C's argument conversion."""
import math

import numpy as np
import pytest

from irisgl import (GLError, XMAXSCREEN, YMAXSCREEN, circfs, clear, color, getcolor,
                    getmatrix, getsize, loadmatrix, lrectread, mapcolor, getmcolor, mmode,
                    MVIEWING, ortho2, prefposition, rectfi, translate, winopen, cmode,
                    gconfig, RGBcolor, cpack)


def _ident():
    return [[float(i == j) for j in range(4)] for i in range(4)]


# -- float arguments of integer parameters: C converts them, truncating -------------
def test_prefposition_from_screen_fractions():
    """``prefposition(XMAXSCREEN/4, XMAXSCREEN*3/4, ...)``: in C the integer
    division gives 319 and 959; ported with ``/`` the floats 319.75 and 959.25
    are converted as C converts a float argument to a long: toward zero.
    prefposition(3G) gives the window x2 - x1 + 1 by y2 - y1 + 1 pixels."""
    prefposition(XMAXSCREEN / 4, XMAXSCREEN * 3 / 4, YMAXSCREEN / 4, YMAXSCREEN * 3 / 4)
    winopen("t")
    x1, x2 = int(XMAXSCREEN / 4), int(XMAXSCREEN * 3 / 4)
    y1, y2 = int(YMAXSCREEN / 4), int(YMAXSCREEN * 3 / 4)
    assert getsize() == (x2 - x1 + 1, y2 - y1 + 1) == (641, 513)


def test_rectfi_with_float_corners_is_the_truncated_rectangle(open_window):
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    cpack(0xFFFFFFFF)
    rectfi(2, 3, 9, 7)
    ints = lrectread(0, 0, 15, 15).copy()
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    rectfi(2.2, 3.9, 9.99, 7.5)            # truncates to 2, 3, 9, 7 as C would
    floats = lrectread(0, 0, 15, 15)
    assert (floats == ints).all()
    assert int((ints == 0xFFFFFFFF).sum()) > 0
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    rectfi(2, 4, 10, 8)                    # rounding instead would draw this: different
    assert not (lrectread(0, 0, 15, 15) == floats).all()


def test_circfs_with_a_float_radius(open_window):
    """circfs(3G) takes Scoord (short) arguments: radius 3.7 is radius 3."""
    open_window(32, 32)
    ortho2(-0.5, 31.5, -0.5, 31.5)
    cpack(0xFFFFFFFF)
    circfs(15, 15, 3)
    ints = lrectread(0, 0, 31, 31).copy()
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    circfs(15.0, 15.9, 3.7)
    assert (lrectread(0, 0, 31, 31) == ints).all()


def test_colour_index_and_mapcolor_from_float_arithmetic(open_window):
    """color(3G) takes a Colorindex and mapcolor(3G) shorts: a ported
    ``mapcolor(i, 255*f, ...)`` or ``color(base + 2.6)`` truncates."""
    open_window(8, 8, rgb=False)
    mapcolor(20.0, 255 * 0.5, 255 * 0.999, 10.9)
    assert getmcolor(20) == (127, 254, 10)
    color(19.6 + 0.5)                       # 20.1 -> 20
    assert getcolor() == 20
    clear()
    assert lrectread(0, 0, 0, 0)[0, 0] & 0xFFF == 20


def test_rgbcolor_from_float_products(open_window):
    open_window(8, 8)
    RGBcolor(255 * 0.5, 100.99, 0.4)
    clear()
    assert int(lrectread(0, 0, 0, 0)[0, 0]) & 0xFFFFFF == (0 << 16) | (100 << 8) | 127


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "3", None])
def test_non_numbers_and_non_finite_stay_errors(open_window, bad):
    """NaN and infinity have no integer value; a string is not a number: the
    call raises GLError naming itself and the colour stays as it was."""
    open_window(8, 8, rgb=False)
    color(5)
    with pytest.raises(GLError, match="^color: "):
        color(bad)
    assert getcolor() == 5


# -- getmatrix into the C array the program declared ----------------------------------
def test_getmatrix_fills_a_nested_list(open_window):
    """A port of ``float view[4][4]; ... getmatrix(view);`` keeps ``view`` as
    four lists: getmatrix(3G) copies the current matrix into it, rows as in C
    (the translation of translate(3G) in row 3, points being row vectors)."""
    open_window(16, 16)
    mmode(MVIEWING)
    loadmatrix(_ident())
    translate(1.0, 2.0, 3.0)
    view = _ident()
    keep = view[2]
    assert getmatrix(view) is None
    assert view[3] == [1.0, 2.0, 3.0, 1.0]
    assert view[0] == [1.0, 0.0, 0.0, 0.0]
    assert view[2] is keep                  # filled in place, as C writes the array


def test_getmatrix_fills_a_flat_list_and_a_transposed_array(open_window):
    open_window(16, 16)
    mmode(MVIEWING)
    loadmatrix(_ident())
    translate(4.0, 5.0, 6.0)
    flat = [0.0] * 16
    getmatrix(flat)
    assert flat[12:16] == [4.0, 5.0, 6.0, 1.0]
    a = np.zeros((4, 4), np.float32).T       # not contiguous: still filled element-wise
    getmatrix(a)
    assert list(a[3]) == [4.0, 5.0, 6.0, 1.0]


def test_getmatrix_too_small_an_array_is_an_error(open_window):
    open_window(16, 16)
    short = [[0.0] * 4 for _ in range(3)]
    with pytest.raises(GLError, match="^getmatrix: "):
        getmatrix(short)
    assert short == [[0.0] * 4 for _ in range(3)]


# -- defpup handlers written as K&R C functions of no parameters --------------------
def test_item_functions_declared_without_parameters(open_window):
    """defpup(3G): a %f item calls its function with the item's value.  A K&R
    handler ``normal_mode() { ... }`` ignores that argument; ported as
    ``def normal_mode():`` it still runs, and dopup returns the item value
    (the handler returns nothing)."""
    from irisgl import defpup, dopup
    from vgx_emulator import menus as M
    open_window(32, 32)
    ran = []

    def normal_mode():
        ran.append("normal")

    def depthcued_mode(value):
        ran.append(("depthcued", value))
        return 40 + value

    m = defpup("Display %t|normal %f|depthcued %f", normal_mode, depthcued_mode)
    M.script("1,2")
    assert dopup(m) == 1
    assert dopup(m) == 42
    assert ran == ["normal", ("depthcued", 2)]


def test_menu_function_without_parameters(open_window):
    """%F: the menu function gets the chosen value; one of no parameters runs
    and the value passes through."""
    from irisgl import defpup, dopup
    from vgx_emulator import menus as M
    open_window(32, 32)
    seen = []
    m = defpup("Colour %t %F|red|green", lambda: seen.append(1))
    M.script("2")
    assert dopup(m) == 2
    assert seen == [1]


def test_handler_that_fails_inside_is_not_retried(open_window):
    """A handler taking the value that raises TypeError itself is called once,
    and the error reaches the program as it would from any Python call."""
    from irisgl import defpup, dopup
    from vgx_emulator import menus as M
    open_window(32, 32)
    calls = []

    def broken(value):
        calls.append(value)
        raise TypeError("inside the handler")

    m = defpup("M %t|one %f", broken)
    M.script("1")
    with pytest.raises(TypeError, match="inside the handler"):
        dopup(m)
    assert calls == [1]


# -- a call given the wrong number of arguments --------------------------------------
def test_missing_argument_is_a_glerror_naming_the_call(open_window):
    """A K&R program's ``qenter(REDRAW)`` (no value) ported as is: like any
    misuse it raises GLError starting with the call's name and saying how the
    call reads, and enters nothing into the queue."""
    from irisgl import REDRAW, qenter, qtest, qreset
    open_window(16, 16)
    qreset()
    with pytest.raises(GLError, match=r"^qenter: 1 argument given; the call is qenter\(dev, val\)"):
        qenter(REDRAW)
    assert qtest() == 0
    with pytest.raises(GLError, match=r"^rectfi: 5 arguments given"):
        rectfi(0, 0, 3, 3, 9)


def test_missing_argument_in_lenient_mode_is_reported_and_skipped(open_window, capsys):
    """The lenient mode prints the error and goes on, as the original library
    did for old programs."""
    import vgx_emulator
    from irisgl import REDRAW, qenter, qtest, qreset
    open_window(16, 16)
    qreset()
    vgx_emulator.errors.set_error_mode("lenient")
    assert qenter(REDRAW) is None
    assert "qenter: 1 argument given" in capsys.readouterr().err
    assert qtest() == 0


# -- objreplace overwrites routine for routine ---------------------------------------
def test_objreplace_overwrites_only_as_many_routines_as_are_sent(open_window):
    """objreplace(3G): the routines that follow overwrite existing ones, one
    for one (the new routine is the same length as the one it replaces).  A
    flight-simulator style edit, a tagged rotate followed by a whole compass
    drawing, replaces the rotate and keeps the drawing after it."""
    from irisgl import callfunc, callobj, closeobj, editobj, makeobj, maketag, objreplace
    open_window(16, 16)
    seen = []
    makeobj(5)
    maketag(10)
    callfunc(seen.append, 1, "rotate 0")
    for k in range(3):
        callfunc(seen.append, 1, f"compass {k}")
    closeobj()
    editobj(5)
    objreplace(10)
    callfunc(seen.append, 1, "rotate 90")
    closeobj()
    callobj(5)
    assert seen == ["rotate 90", "compass 0", "compass 1", "compass 2"]


def test_objreplace_runs_over_tags_and_past_the_end(open_window):
    """Replacing more routines than follow the tag: tags on the way stay where
    they are (they mark places, they are not routines) and the rest is added
    at the end; closeobj ends the replacement, so a later edit appends."""
    from irisgl import callfunc, callobj, closeobj, editobj, makeobj, maketag, objreplace, objinsert
    open_window(16, 16)
    seen = []
    makeobj(6)
    maketag(10)
    callfunc(seen.append, 1, "a")
    maketag(11)
    callfunc(seen.append, 1, "b")
    closeobj()
    editobj(6)
    objreplace(10)
    for lab in ("A", "B", "C"):
        callfunc(seen.append, 1, lab)
    objinsert(11)                         # ends the replacement: inserts after tag 11
    callfunc(seen.append, 1, "ins")
    closeobj()
    callobj(6)
    assert seen == ["A", "ins", "B", "C"]
    seen.clear()
    editobj(6)
    objreplace(11)
    callfunc(seen.append, 1, "I")
    closeobj()
    callobj(6)
    assert seen == ["A", "I", "B", "C"]


def test_qenter_keyboard_character_constant(open_window):
    """qenter(3G) takes a short value; C's ``qenter(KEYBD, 't')`` passes the
    character code of 't', which qread returns with KEYBD."""
    from irisgl import KEYBD, qenter, qread, qreset
    open_window(16, 16)
    qreset()
    qenter(KEYBD, 't')
    assert qread() == (KEYBD, ord('t'))
    with pytest.raises(GLError, match="^qenter: "):
        qenter(KEYBD, "tt")                 # not a character constant
