"""C habits that ported programs rely on: longer C arrays read from their
first elements, display lists that record values, perspective with near = 0
(docs/porting.md)."""
import warnings

import numpy as np
import pytest

from irisgl import (GLError, RGBcolor, bgnpolygon, c3f, callobj, closeobj, cpack, endpolygon,
                    getmatrix, lrectread, makeobj, n3f, ortho2, perspective, v2f, v3f,
                    clear)


def _square(v, x0, y0, x1, y1):
    """The four corners through one scratch array, as a C program with one
    ``float v[4]`` does."""
    bgnpolygon()
    for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
        v[0], v[1] = x, y
        v3f(v)
    endpolygon()


def test_v3f_reads_the_first_three_of_a_float4_row(open_window):
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    cpack(0xFF0000FF)
    row = np.array([2.0, 2.0, 0.0, 1.0], np.float32)
    _square(row, 2, 2, 9, 9)
    img = lrectread(0, 0, 15, 15)
    assert int((img == 0xFF0000FF).sum()) == 7 * 7


def test_short_array_is_still_an_error(open_window):
    open_window(8, 8)
    bgnpolygon()
    with pytest.raises(GLError, match="^v3f: vertex has 2 elements"):
        v3f((1.0, 2.0))
    endpolygon()


def test_n3f_and_c3f_read_the_first_elements(open_window):
    open_window(8, 8)
    n3f([0.0, 0.0, 1.0, 99.0])
    c3f([1.0, 0.0, 0.0, 0.5])       # a float[4] colour passed to c3f: alpha stays 255
    from irisgl._current import machine
    assert machine.current.st.colour == (255.0, 0.0, 0.0, 255.0)
    assert machine.current.st.normal == (0.0, 0.0, 1.0)


def test_object_built_from_a_scratch_array_replays_what_was_sent(open_window):
    """makeobj(3G) compiles the values sent: changing the scratch array
    afterwards must not change the object (it drew nothing before the fix)."""
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    v = [0.0, 0.0, 0.0]
    makeobj(7)
    RGBcolor(0, 255, 0)
    _square(v, 1, 1, 5, 5)          # leaves v = [1, 5, 0]
    _square(v, 8, 8, 12, 12)
    closeobj()
    v[0] = v[1] = 100.0             # the scratch array moves far away
    cpack(0)
    clear()
    callobj(7)
    img = lrectread(0, 0, 15, 15)
    green = img == 0xFF00FF00
    assert int(green.sum()) == 2 * 4 * 4
    assert green[1:5, 1:5].all() and green[8:12, 8:12].all()


def test_object_copies_numpy_arguments(open_window):
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    v = np.zeros(2)
    makeobj(3)
    cpack(0xFFFFFFFF)
    bgnpolygon()
    for x, y in ((0, 0), (4, 0), (4, 4), (0, 4)):
        v[:] = x, y
        v2f(v)
    endpolygon()
    closeobj()
    v[:] = 50
    callobj(3)
    assert int((lrectread(0, 0, 15, 15) == 0xFFFFFFFF).sum()) == 16


def test_perspective_near_zero_warns_and_loads_the_degenerate_matrix(open_window):
    """perspective(3G) lists only fovy <= 2 as an error; near = 0 was passed by
    programs of the time: the matrix maps every eye z to the far plane."""
    open_window(8, 8)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        perspective(900, 1.0, 0.0, 10.0)
    assert any("perspective" in str(x.message) for x in w)
    m = getmatrix()
    assert m[0, 0] == pytest.approx(1.0) and m[1, 1] == pytest.approx(1.0)
    assert m[2, 2] == pytest.approx(-1.0) and m[2, 3] == -1.0 and m[3, 2] == 0.0
    for z in (-0.5, -3.0, -9.0):
        clip = np.array([0.0, 0.0, z, 1.0]) @ m
        assert clip[2] / clip[3] == pytest.approx(1.0)


def test_perspective_fovy_error_stays(open_window):
    open_window(8, 8)
    before = getmatrix().copy()
    with pytest.raises(GLError, match="^perspective: fovy"):
        perspective(2, 1.0, 1.0, 10.0)
    assert (getmatrix() == before).all()
