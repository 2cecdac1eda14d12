"""Defects found by fuzzing from outside, each reproduced in a few lines:
every misuse a GLError naming the call, with the state unchanged."""
import numpy as np
import pytest

from irisgl import *
from irisgl._current import machine


def test_pixel_writes_with_empty_viewport_do_nothing(open_window):
    """viewport ∩ scrmask ∩ window empty: lrectwrite and rectcopy write no
    pixel (they raised TypeError before)."""
    open_window(32, 32)
    cpack(0xFF112233)
    clear()
    before = lrectread(0, 0, 31, 31).copy()
    viewport(40, 50, 40, 50)
    lrectwrite(0, 0, 1, 1, np.full(4, 0xFFFFFFFF, np.uint32))
    rectcopy(0, 0, 3, 3, 5, 5)
    assert np.array_equal(lrectread(0, 0, 31, 31), before)


def test_queries_in_an_open_object_answer_at_once(open_window):
    open_window(40, 30)
    makeobj(3)
    assert getsize() == (40, 30)
    assert getmmode() == MSINGLE
    assert getzbuffer() == 0
    assert getviewport() == (0, 39, 0, 29)
    assert getmatrix().shape == (4, 4)
    closeobj()
    assert not any(it[1].startswith("get") for it in machine.objects[3].items
                   if it[0] == "call")


def test_gexit_closes_an_open_object(open_window):
    open_window(16, 16)
    makeobj(5)
    cpack(0xFF0000FF)
    gexit()
    open_window(16, 16)
    assert getopenobj() == -1
    cpack(0xFF00FF00)                 # goes to the window, not into object 5
    clear()
    assert int(lrectread(0, 0, 0, 0)[0, 0]) == 0xFF00FF00
    assert isobj(5)


def test_recursive_object_raises_before_anything_runs(open_window):
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    makeobj(9)
    translate(1, 0, 0)
    cpack(0xFFFFFFFF)
    rectf(0, 0, 3, 3)
    callobj(9)
    closeobj()
    m = getmatrix().copy()
    with pytest.raises(GLError, match="^callobj: object 9 calls itself"):
        callobj(9)
    assert np.array_equal(getmatrix(), m)
    assert not lrectread(0, 0, 15, 15).any()


def test_mutual_recursion_is_found_too(open_window):
    open_window(8, 8)
    makeobj(1)
    callobj(2)
    closeobj()
    makeobj(2)
    callobj(1)
    closeobj()
    with pytest.raises(GLError, match="^callobj: object 1 calls itself"):
        callobj(1)


def test_nesting_within_the_limit_runs(open_window):
    open_window(8, 8)
    for o in range(1, 11):
        makeobj(o)
        if o > 1:
            callobj(o - 1)
        else:
            translate(1, 0, 0)
        closeobj()
    m0 = getmatrix().copy()
    callobj(10)
    got = getmatrix().copy()
    loadmatrix(m0)
    translate(1, 0, 0)
    assert np.array_equal(got, getmatrix())


def test_setdepth_and_getdepth_errors_name_themselves(open_window):
    open_window(8, 8)
    with pytest.raises(GLError, match="^setdepth: "):
        setdepth("near", 0)
    setdepth(-100, 100)
    assert getdepth() == (-100, 100)


def test_nan_colour_then_clear_warns_and_clears_nothing(open_window):
    import warnings
    open_window(8, 8)
    cpack(0xFF123456)
    clear()
    c3f([float("nan"), 0, 0])
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        clear()
    assert any(str(x.message).startswith("clear:") for x in w)
    assert (lrectread(0, 0, 7, 7) == 0xFF123456).all()


@pytest.mark.parametrize("call, args, name", [
    (lambda: polf(3, None), (), "polf"),
    (lambda: rectzoom("abc", 1), (), "rectzoom"),
    (lambda: lrectread(0, 0, 2 ** 70, 3), (), "lrectread"),
    (lambda: lrectread(0, 0, 10 ** 4, 10 ** 4), (), "lrectread"),
    (lambda: rectcopy(0, 0, 3, 3, 2 ** 70, 0), (), "rectcopy"),
])
def test_bad_arguments_are_glerrors_naming_the_call(open_window, call, args, name):
    open_window(8, 8)
    zoom = machine.current.st.zoom
    with pytest.raises(GLError, match=f"^{name}: "):
        call()
    assert machine.current.st.zoom == zoom


def test_getgdesc_of_a_non_integer_inquiry_is_minus_one():
    assert getgdesc(float("inf")) == -1
    assert getgdesc("x") == -1


@pytest.mark.parametrize("call", [lambda: mapcolor(1, 2, 3, 4),
                                  lambda: texdef2d(1, 4, 1, 1, [0], 0, [0]),
                                  lambda: tevdef(1, 0, [0])])
def test_definitions_before_winopen_are_errors(call):
    with pytest.raises(GLError, match="no window is open"):
        call()


def test_a_string_in_an_lmdef_list_is_a_glerror(open_window):
    open_window(8, 8)
    with pytest.raises(GLError, match="^lmdef: property list holds 'a'"):
        lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, "a", 0, 0, LMNULL])
    assert 1 not in machine.defs[lighting_index()]


def lighting_index():
    from vgx_emulator.geometry import lighting
    return lighting.DEFMATERIAL


@pytest.mark.parametrize("words", [np.zeros(4), np.full(4, np.nan), [0.5, 1, 2, 3]])
def test_lrectwrite_of_floats_is_a_glerror(open_window, words):
    open_window(8, 8)
    cpack(0xFF445566)
    clear()
    with pytest.raises(GLError, match="^lrectwrite: parray is not an array of integer"):
        lrectwrite(0, 0, 1, 1, words)
    assert (lrectread(0, 0, 7, 7) == 0xFF445566).all()


def test_read_only_output_array_is_a_glerror(open_window):
    open_window(8, 8)
    ro = np.zeros(4, np.uint32)
    ro.flags.writeable = False
    with pytest.raises(GLError, match="^lrectread: parray is a read-only array"):
        lrectread(0, 0, 1, 1, ro)


def test_lrectread_fills_a_strided_array_in_place(open_window):
    open_window(8, 8)
    cpack(0xFF010203)
    clear()
    big = np.zeros((4, 4), np.uint32)
    view = big[:, ::2]                     # 8 elements, not contiguous
    assert lrectread(0, 0, 1, 3, view) == 8
    assert (big[:, ::2] == 0xFF010203).all() and (big[:, 1::2] == 0).all()


def test_dropped_primitive_warning_names_the_call_that_drew_it(open_window):
    import warnings
    open_window(16, 16)
    ortho2(-0.5, 15.5, -0.5, 15.5)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        rectf(0, 0, float("nan"), 5)
        gflush()
    assert [str(x.message).split(":")[0] for x in w] == ["rectf"]
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        bgnpolygon()
        v3f((float("nan"), 0, 0))
        v3f((1, 1, 0))
        v3f((2, 0, 0))
        endpolygon()
        gflush()
    assert [str(x.message).split(":")[0] for x in w] == ["v*/n3f/c*/t*"]


def test_a_warning_is_shown_at_the_programs_line(open_window):
    """A VGXWarning points at the program's line that made the call (here
    this file), not into the emulator, whether it comes from the call
    itself (perspective's near 0), from an object's replay (an undefined
    object) or from the flush that dropped a primitive (gflush's line);
    so Python's default filter shows it once per line of the program."""
    import inspect
    import warnings
    open_window(16, 16)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        here = inspect.currentframe().f_lineno
        perspective(450, 1.0, 0.0, 10.0)               # here + 1
        makeobj(5)
        callobj(999)
        closeobj()
        callobj(5)                                     # here + 5: the replay warns
        ortho2(-0.5, 15.5, -0.5, 15.5)
        rectf(0, 0, float("nan"), 5)
        gflush()                                       # here + 8: the flush drops it
    got = [(str(x.message).split(":")[0], x.filename, x.lineno) for x in w]
    assert got == [("perspective", __file__, here + 1), ("callobj", __file__, here + 5),
                   ("rectf", __file__, here + 8)]


# -- issue 19, second part: found by vgx_emulator.fuzz ------------------------
def _snapshot():
    """Matrices, modes and banks of the current window, the machine's
    definitions and its physical state, for 'state unchanged' checks."""
    from vgx_emulator.fuzz import fingerprint
    return fingerprint(machine)


@pytest.mark.parametrize("call", [lambda: circ(0, 0, 1e38), lambda: arc(0, 0, 1e38, 0, 900),
                                  lambda: circf(0, 0, 3e38), lambda: arcf(0, 0, 1e38, 0, 900)])
def test_a_huge_radius_draws_at_most_the_largest_circle(open_window, call):
    """circ(3G) of radius 1e38 (far beyond the screen): chords are counted
    as for the largest circle, not a ZeroDivisionError."""
    open_window(16, 16)
    call()
    gflush()


NONFINITE = [float("nan"), float("inf"), -float("inf"), 1e38, -1e38, 3e38]


def _all_kinds(v):
    """Every primitive kind, once with a vertex holding v and once with w = v."""
    kinds = [(bgnpoint, endpoint), (bgnline, endline), (bgnclosedline, endclosedline),
             (bgnpolygon, endpolygon), (bgntmesh, endtmesh), (bgnqstrip, endqstrip)]
    for bgn, end in kinds:
        for bad in ([v, 0.3, 0, 1], [0.2, 0.1, 0, v], [0.5, 0.5, 0, -1.0], [0, 0, 0, 0.0]):
            bgn()
            n3f([0, 0, 1])
            for p in ([0, 0, 0, 1], [1, 0, 0, 1], bad, [0, 1, 0, 1]):
                c4f([1, v if bad[0] == v else 0, 0, 1])
                v4f(p)
            end()
            gflush()
    for draw2d in (lambda: rectf(0, 0, v, 1), lambda: sboxf(0, 0, v, 1),
                   lambda: polf(3, [[0, 0, 0], [v, 1, 0], [1, 0, 0]]), lambda: pnt(v, 0, 0),
                   lambda: (move(0, 0, 0), draw(v, 1, 0)), lambda: circ(0, 0, v)):
        try:
            draw2d()
        except GLError:
            pass
        gflush()


@pytest.mark.parametrize("lit", [False, True])
def test_nonfinite_geometry_gives_no_numpy_warning(open_window, lit):
    """NaN, infinities, 1e38 and w <= 0 through every primitive kind, with
    every warning an error: only VGXWarnings (docs/porting.md §4), never
    numpy's RuntimeWarning (sboxf(inf) gave 'invalid value in matmul')."""
    import warnings
    from vgx_emulator.errors import VGXWarning
    open_window(32, 32)
    mmode(MVIEWING)
    perspective(400, 1, 1, 50)
    lookat(0, 0, 5, 0, 0, 0, 0)
    zbuffer(TRUE)
    if lit:
        lmdef(DEFMATERIAL, 1, 0, [LMNULL])
        lmdef(DEFLIGHT, 1, 0, [LMNULL])
        lmdef(DEFLMODEL, 1, 0, [LMNULL])
        lmbind(MATERIAL, 1)
        lmbind(LIGHT0, 1)
        lmbind(LMODEL, 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", VGXWarning)
        for v in NONFINITE:
            _all_kinds(v)


def test_one_warning_per_dropped_batch_naming_the_call_and_value(open_window):
    """Three bad rectangles in one batch: one VGXWarning, naming rectf, what
    was dropped (6 triangles) and the first offending value."""
    import warnings
    open_window(16, 16)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        rectf(0, 0, float("inf"), 5)
        rectf(0, 0, float("nan"), 5)
        rectf(0, 0, 1, 1)
        rectf(0, 0, float("nan"), 5)
        gflush()
    assert len(w) == 1
    msg = str(w[0].message)
    assert msg.startswith("rectf: 6 triangle(s) with a non-finite")
    assert msg.endswith("first: vertex (inf, 0, 0, 1)")


@pytest.mark.parametrize("call, name", [
    (lambda: lrectwrite(0, 0, 0, 0, 2 ** 70), "lrectwrite"),
    (lambda: rectwrite(0, 0, 0, 0, 2 ** 70), "rectwrite"),
    (lambda: texdef2d(1, 1, 1, 1, 2 ** 70, 0, [0]), "texdef2d"),
    (lambda: qcontrol(1, 1, object(), 0), "qcontrol"),
    (lambda: winmove(2 ** 70, 1), "winmove"),
    (lambda: winposition(2 ** 40, 2 ** 40 + 10, 0, 10), "winposition"),
    (lambda: lampon(None), "lampon"),
    (lambda: lampoff("abc"), "lampoff"),
])
def test_fuzzed_misuse_is_a_glerror_with_the_state_unchanged(open_window, call, name):
    """Found by the misuse fuzz: OverflowError (a 2**70 pixel word, window
    origin or texture word), TypeError (qcontrol of an object), a lamp
    state created by a refused call, loadmatrix(None) read as a 1-element matrix."""
    open_window(8, 8)
    cpack(0xFF123456)
    clear()
    before = _snapshot()
    with pytest.raises(GLError, match=f"^{name}: "):
        call()
    assert _snapshot() == before
    rectf(0, 0, 3, 3)                  # the window still draws
    gflush()


def test_pixel_words_of_any_size_are_reduced_as_c_converts_them(open_window):
    """A Python int beyond 32 bits in an lrectwrite or writeRGB array keeps
    its low bits, as C's unsigned long / Colorindex conversion (docs/semantics.md §1),
    instead of an OverflowError."""
    open_window(8, 8)
    lrectwrite(0, 0, 1, 0, [2 ** 70 + 0xFF0000FF, 0xFF00FF00])
    assert list(lrectread(0, 0, 1, 0).reshape(-1)) == [0xFF0000FF, 0xFF00FF00]
    cmov2i(0, 1)
    writeRGB(2, [2 ** 40 + 7, 8], [1, 2], [3, 4])
    assert list(lrectread(0, 1, 1, 1).reshape(-1)) == [0xFF030107, 0xFF040208]


def test_loadmatrix_reads_a_flat_16_as_c_memory(open_window):
    """loadmatrix(3G) takes a Matrix, float[4][4]; a flat list of 16 is the
    same memory in C's row-major order and loads the same matrix."""
    open_window(8, 8)
    m = [[1, 2, 3, 4], [5, 6, 7, 8], [9, 10, 11, 12], [13, 14, 15, 16]]
    loadmatrix(sum(m, []))
    flat = getmatrix().copy()
    loadmatrix(m)
    assert np.array_equal(flat, getmatrix())
    with pytest.raises(GLError, match="^loadmatrix: matrix has 15 elements"):
        loadmatrix(list(range(15)))
    with pytest.raises(GLError, match="^loadmatrix: matrix None is not an array"):
        loadmatrix(None)                # was 'matrix has 1 elements'
    with pytest.raises(GLError, match="^multmatrix: matrix 2.0 is not an array"):
        multmatrix(2.0)


def test_a_line_cut_point_lost_to_cancellation_is_dropped_with_a_warning(open_window):
    """A line from x = 1.2e38 (clip space) clipped to the frustum: the cut
    point computed in float64 is (0, 0.885, 0, 0), and 0/0 placed it at
    NaN, which reached the line kernel as -2**63 (found by the fuzz, seed
    19).  It is dropped and warned about, like such a triangle."""
    import warnings
    open_window(20, 90)
    mmode(MSINGLE)
    loadmatrix(np.eye(4))
    viewport(2, 15, 55, 82)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        bgnline()
        v4f([1.2185495338472165e+38, 0.4359100398072116, 1.0388427707360037e+37,
             1.0095711797475814e+37])
        v4f([2.3996994481858458, 0.8854088796291958, 2.8553304747028552, 3.8841288383800241])
        endline()
        gflush()
    assert [str(x.message).split(" with ")[0] for x in w] == ["v*/n3f/c*/t*: 1 line segment(s)"]


@pytest.mark.parametrize("call, name", [
    (lambda: dopup(float("inf")), "dopup"),
    (lambda: addtopup(-float("inf"), "x"), "addtopup"),
    (lambda: freepup(float("inf")), "freepup"),
    (lambda: setpup(float("inf"), 1, 0), "setpup"),
    (lambda: istag(object()), "istag"),
    (lambda: readpixels(1, object()), "readpixels"),
    (lambda: readRGB(1, None, 1j, None), "readRGB"),
    (lambda: writeRGB(1, 1j, 1, 1), "writeRGB"),
])
def test_fuzzed_misuse_of_full_values_is_a_glerror(open_window, call, name):
    """The full misuse run (infinities, objects, complex numbers): each
    raised OverflowError or was accepted silently before."""
    open_window(8, 8)
    before = _snapshot()
    with pytest.raises(GLError, match=f"^{name}: "):
        call()
    assert _snapshot() == before


def test_invalid_screens_and_registers_answer_minus_one():
    """getvideo(3G), scrnselect(3G), scrnattach(3G) answer -1 for an
    invalid register or screen, infinity included (OverflowError before)."""
    assert getvideo(float("inf")) == -1
    assert scrnselect(-float("inf")) == -1
    assert scrnattach(float("inf")) == -1


def test_readpixels_fills_a_list(open_window):
    """readpixels(3G) fills the caller's array; a list ported from C's
    array is filled in place like a numpy array."""
    open_window(8, 8, rgb=False)
    color(5)
    clear()
    cmov2i(0, 0)
    got = [0, 0, 0]
    readpixels(2, got)
    assert got == [5, 5, 0]
