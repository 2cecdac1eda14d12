"""Immediate mode: the per-vertex calls' fast path (irisgl/primitives.py,
geometry/batch.py) gives the pictures, values and errors the man pages ask
for, whichever path a call takes.

The reference for pictures is the same drawing from a display list
(makeobj/callobj), which builds its attribute records its own way
(vgx_emulator/objects.py); every comparison is exact: the two paths feed the
same transform, lighting and rasterizer with the same numbers."""
import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import colour

W, H = 48, 40


def _scene():
    """Lit and unlit primitives with normals, colours (every colour call)
    and texture coordinates interleaved with the vertices."""
    ortho(-1, 1, -1, 1, -1, 1)
    bgntmesh()
    for i in range(12):
        x = -0.9 + 0.15 * i
        n3f((0.1 * i - 0.6, 0.3, 0.8))
        c3f((0.1 * i, 1.5, -0.5))              # clamped to 0..1
        v3f((x, -0.9, 0.1 * (i % 3)))
        if i % 4 == 0:
            swaptmesh()
        cpack(0x80402010 + i)
        t2f((0.5, 0.25))
        v2f((x, -0.5))
    endtmesh()
    bgnpolygon()
    c4f((1, 0, 0, 0.5))
    v3f((0.0, 0.0, 0.0))
    c4i((0, 300, 0, 255))                      # clamped to 255
    v3f((0.8, 0.0, 0.0))
    RGBcolor(10, 20, 30)
    v4f((0.8, 0.8, 0.0, 1.0))
    c3s((7, 8, 9))
    v2f((0.0, 0.8))
    endpolygon()
    bgnline()
    c3i((255, 255, 0))
    v2i((0, 0))
    v2s((1, 1))
    endline()
    bgnpoint()
    for i in range(5):
        RGBcolor(50 * i, 0, 255)
        v2d((-0.8 + 0.1 * i, 0.9))
    endpoint()


def _lighting():
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.8, 0.6, 0.3, LMNULL])
    lmdef(DEFLIGHT, 1, 0, [POSITION, 0.3, 0.4, 1.0, 0.0, LMNULL])
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)


def _draw_both(open_window, setup, scene):
    """(immediate picture, display-list picture) of ``scene`` after ``setup``."""
    out = []
    for use_object in (False, True):
        open_window(W, H)
        cpack(0)
        clear()
        setup()
        if use_object:
            ob = genobj()
            makeobj(ob)
            scene()
            closeobj()
            callobj(ob)
        else:
            scene()
        out.append(colour())
        gexit()
    return out


def test_unlit_scene_equals_its_display_list(open_window):
    a, b = _draw_both(open_window, lambda: None, _scene)
    assert (a != 0).sum() > 300                      # the scene drew
    assert np.array_equal(a, b)


@pytest.mark.parametrize("lmc", ["LMC_COLOR", "LMC_DIFFUSE", "LMC_AD", "LMC_EMISSION"])
def test_lit_scene_equals_its_display_list(open_window, lmc):
    # lmcolor(3G): a colour after the material bind replaces a material property;
    # the flags LAST_WAS_NORMAL / COLOUR_SINCE_BIND come from the events' order
    def setup():
        _lighting()
        lmbind(MATERIAL, 1)
        lmcolor(globals()[lmc])
    a, b = _draw_both(open_window, setup, _scene)
    assert (a != 0).sum() > 300
    assert np.array_equal(a, b)


@pytest.mark.parametrize("lit", [False, True])
def test_a_batch_flushed_as_it_grows_draws_the_same(open_window, monkeypatch, lit):
    # an end* that brings the batch to config.FLUSH_VERTICES flushes it (the
    # raster thread draws while the program goes on): the picture, z and the
    # current attributes are those of one batch flushed at the end
    from irisgl._current import machine
    from vgx_emulator import config

    def draw(limit):
        monkeypatch.setattr(config, "FLUSH_VERTICES", limit)
        open_window(W, H)
        zbuffer(1)
        cpack(0)
        clear()
        zclear()
        if lit:
            mmode(MVIEWING)
            _lighting()
            lmbind(MATERIAL, 1)
            lmcolor(LMC_AD)
        ortho(-1, 1, -1, 1, -1, 1)
        bgntmesh()
        for i in range(12):
            n3f((0.1 * i - 0.6, 0.3, 0.8))
            c3f((0.1 * i, 0.5, 0.2))
            v3f((-0.9 + 0.15 * i, -0.9, 0.1 * (i % 3)))
            v3f((-0.9 + 0.15 * i, -0.2, -0.1 * (i % 2)))
        endtmesh()
        flushed = len(machine.current.batch) == 0
        _scene()
        out = (colour(), machine.current.fb.z.copy(), gRGBcolor(), flushed)
        gexit()
        return out

    one = draw(1 << 30)
    many = draw(8)
    assert not one[3] and many[3]                    # the small limit flushed at endtmesh
    assert (one[0] != 0).sum() > 300
    assert np.array_equal(one[0], many[0])
    assert np.array_equal(one[1], many[1])
    assert one[2] == many[2]


def test_colour_values_as_the_man_pages_give_them(open_window):
    open_window(W, H)
    c3f((2.0, -1.0, 0.5))
    assert gRGBcolor() == (255, 0, 128)              # 0.5 * 255 = 127.5 rounds to 128
    c4i((300, -5, 7, 1000))
    assert gRGBcolor() == (255, 0, 7)
    cpack(0x00332211)
    assert gRGBcolor() == (0x11, 0x22, 0x33)
    RGBcolor(300, -3, 5.9)                           # C converts 5.9 to 5
    assert gRGBcolor() == (255, 0, 5)
    cpack(2 ** 40 + 0x0000FF)                        # an unsigned long: modulo 2**32
    assert gRGBcolor() == (255, 0, 0)
    clear()                                          # clear(3G) uses the current colour
    assert (colour() == 0x000000FF).all()            # alpha 0: the word's high byte


def test_pushattributes_restores_a_colour_set_by_a_fast_call(open_window):
    open_window(W, H)
    c3f((0, 1, 0))
    pushattributes()
    c3f((1, 0, 0))
    popattributes()
    assert gRGBcolor() == (0, 255, 0)
    clear()
    assert (colour() == 0xFF00FF00).all()


def test_scratch_array_is_copied_at_the_call(open_window):
    # C passes a pointer and the call copies the values: a program that
    # refills one scratch array per vertex draws what it passed each time
    def scratch():
        ortho2(0, W, 0, H)
        p = [0.0, 0.0]
        c = np.zeros(3)
        bgnpolygon()
        for x, y in ((4, 4), (40, 4), (40, 30), (4, 30)):
            c[:] = (x / W, y / H, 0.5)
            c3f(c)
            p[0], p[1] = x, y
            v2f(p)
        endpolygon()

    def fresh():
        ortho2(0, W, 0, H)
        bgnpolygon()
        for x, y in ((4, 4), (40, 4), (40, 30), (4, 30)):
            c3f((x / W, y / H, 0.5))
            v2f((x, y))
        endpolygon()
    a, _ = _draw_both(open_window, lambda: None, scratch)
    b, _ = _draw_both(open_window, lambda: None, fresh)
    assert (a != 0).sum() > 500
    assert np.array_equal(a, b)


def test_longer_c_arrays_are_read_from_their_first_elements(open_window):
    def longer():
        ortho2(0, W, 0, H)
        bgnpolygon()
        c3f(np.array([1.0, 0.5, 0.25, 99.0]))
        for p in ((4, 4, 0, 7), (40, 4, 0, 7), (40, 30, 0, 7)):
            v2f(p)
        endpolygon()

    def exact():
        ortho2(0, W, 0, H)
        bgnpolygon()
        c3f((1.0, 0.5, 0.25))
        for p in ((4, 4), (40, 4), (40, 30)):
            v2f(p)
        endpolygon()
    a, _ = _draw_both(open_window, lambda: None, longer)
    b, _ = _draw_both(open_window, lambda: None, exact)
    assert (a != 0).sum() > 300
    assert np.array_equal(a, b)


def _state(w):
    from irisgl._current import machine
    b = machine.current.batch
    st = machine.current.st
    return (tuple(b.pos), tuple(b.ev), b.open, st.colour, st.normal, st.texcoord,
            st.last_was_normal)


@pytest.mark.parametrize("call, args, message", [
    (v3f, ((1, "x", 2),), r"^v3f: vertex holds something that is not a number"),
    (v3f, ((1, 2),), r"^v3f: vertex has 2 elements"),
    (v3f, (1, 2, 3), r"^v3f: 3 arguments given; the call is v3f\(v\)"),
    (v2f, (), r"^v2f: 0 arguments given"),
    (n3f, (None,), r"^n3f: normal is not a sequence"),
    (c3f, ((1, 2),), r"^c3f: colour has 2 elements"),
    (cpack, ("red",), r"^cpack: colour 'red' is not an integer"),
    (RGBcolor, (1, 2), r"^RGBcolor: 2 arguments given"),
    (t2f, ((0.5,),), r"^t2f: texture coordinate has 1 elements"),
    (bgnpolygon, (), r"^bgnpolygon: "),
    (endtmesh, (), r"^endtmesh: "),
])
def test_a_bad_call_is_a_glerror_and_changes_nothing(open_window, call, args, message):
    w = open_window(W, H)
    bgnpolygon()
    v2f((1, 1))
    n3f((0, 0, 1))
    before = _state(w)
    with pytest.raises(GLError, match=message):
        call(*args)
    assert _state(w) == before


def _one_argument_calls():
    """Every per-vertex call that takes one array argument (v*, n3f, c3*/c4*, t*)."""
    import irisgl
    names = [f"v{n}{t}" for n in (2, 3, 4) for t in "sifd"] + ["n3f"] + \
        [f"c{n}{t}" for n in (3, 4) for t in "fis"] + [f"t{n}{t}" for n in (2, 3, 4) for t in "sifd"]
    size = {"v": None, "n": 3, "c": None, "t": None}
    out = []
    for name in names:
        k = int(name[1]) if size[name[0]] is None else size[name[0]]
        out.append((getattr(irisgl, name), [1] * k))
    return out


@pytest.mark.parametrize("call, arg", _one_argument_calls(), ids=lambda c: getattr(c, "__name__", ""))
def test_an_extra_argument_inside_bgn_end_is_a_glerror(open_window, call, arg):
    """Inside bgn*/end* (where the fast path runs) a second argument is refused
    like any other wrong arity: GLError naming the call, nothing recorded."""
    w = open_window(W, H)
    bgnpolygon()
    v2f((1, 1))
    before = _state(w)
    with pytest.raises(GLError, match=rf"^{call.__name__}: 2 arguments given; the call is "
                                      rf"{call.__name__}\("):
        call(arg, 5)
    assert _state(w) == before


def test_vertex_outside_bgn_end_and_before_winopen():
    with pytest.raises(GLError, match=r"^v3f: no window is open"):
        v3f((1, 2, 3))
    with pytest.raises(GLError, match=r"^n3f: no window is open"):
        n3f((1, 2, 3))
    with pytest.raises(GLError, match=r"^bgnpolygon: no window is open"):
        bgnpolygon()


def test_vertex_outside_bgn_end(open_window):
    open_window(W, H)
    with pytest.raises(GLError, match=r"^v3f: vertex outside bgn/end"):
        v3f((1, 2, 3))
    n3f((0, 1, 0))                                   # legal outside bgn/end
    c3f((1, 1, 1))


def test_rgb_calls_in_colour_map_mode(open_window):
    open_window(W, H, rgb=False)
    for call, arg in ((c3f, (1, 0, 0)), (c4f, (1, 0, 0, 1)), (cpack, 0xFF)):
        with pytest.raises(GLError, match="colour-map mode"):
            call(arg)
    with pytest.raises(GLError, match="colour-map mode"):
        RGBcolor(1, 2, 3)


def test_lenient_mode_prints_and_goes_on(open_window, capsys):
    import vgx_emulator
    open_window(W, H)
    vgx_emulator.set_error_mode("lenient")
    try:
        v3f((1, 2, 3))                               # outside bgn/end
        bgnpolygon()
        bgnpolygon()
        v3f(("a", 2, 3))
        v3f((1, 2, 3))
        endpolygon()
    finally:
        vgx_emulator.set_error_mode("strict")
    err = capsys.readouterr().err
    assert "GL: v3f: vertex outside bgn/end" in err
    assert "GL: bgnpolygon: " in err
    assert "GL: v3f: vertex holds" in err
    from irisgl._current import machine
    assert machine.current.batch.open is None and len(machine.current.batch) == 1


def test_polygon_of_257_vertices_is_an_error_at_endpolygon(open_window):
    open_window(W, H)
    ortho2(0, W, 0, H)
    cpack(0xFFFFFFFF)
    bgnpolygon()
    for a in np.linspace(0, 2 * np.pi, 257, endpoint=False):
        v2f((24 + 10 * np.cos(a), 20 + 10 * np.sin(a)))
    with pytest.raises(GLError, match=r"^endpolygon: 257 vertices"):
        endpolygon()
    assert (colour() == 0).all()
    bgnpolygon()                                     # the pair was closed
    v2f((1, 1))
    endpolygon()


def test_colours_sent_inside_a_dropped_polygon_stay_current(open_window):
    # c3f(3G) sets the current colour whether or not the polygon it was sent
    # in is drawn: after the 257-vertex polygon is refused, the next one
    # (a square with no colour call of its own, preceded by a drawn red one
    # so that the stream already holds vertices) takes the last colour of
    # the dropped one, green; its own vertices come after the dropped ones
    open_window(W, H)
    ortho2(0, W, 0, H)
    cpack(0xFF0000FF)
    rectf(0, 0, 4, 4)                                # red, 4x4 pixels
    bgnpolygon()
    for i, a in enumerate(np.linspace(0, 2 * np.pi, 257, endpoint=False)):
        c3f((0, 1, 0) if i == 256 else (0, 0, 1))
        v2f((24 + 10 * np.cos(a), 20 + 10 * np.sin(a)))
    with pytest.raises(GLError, match=r"^endpolygon: 257 vertices"):
        endpolygon()
    bgnpolygon()
    for x, y in ((10, 10), (20, 10), (20, 20), (10, 20)):
        v2f((x, y))
    endpolygon()
    c = colour()
    assert (c == 0xFF0000FF).sum() == 16
    assert (c == 0xFF00FF00).sum() == 100            # [10, 20) x [10, 20): green
    assert (c == 0xFFFF0000).sum() == 0              # nothing blue


def test_fast_calls_are_recorded_in_an_open_object(open_window):
    open_window(W, H)
    ob = genobj()
    makeobj(ob)
    bgnpolygon()
    c3f((1, 0, 0))
    v2f((-1, -1))
    v2f((1, -1))
    v2f((1, 1))
    endpolygon()
    closeobj()
    assert (colour() == 0).all()                     # nothing drawn while recording
    ortho2(-1.5, 1.5, -1.5, 1.5)
    callobj(ob)
    assert (colour() == 0xFF0000FF).sum() > 200


def test_a_flush_inside_bgn_end_keeps_the_open_primitive(open_window):
    # lmdef inside bgn/end (allowed there) draws what was issued first; the
    # open polygon continues with its earlier vertices and attributes
    def scene(flush):
        ortho2(0, W, 0, H)
        bgnpolygon()
        c3f((1, 0, 0))
        v2f((4, 4))
        c3f((0, 1, 0))
        v2f((40, 4))
        if flush:
            lmdef(DEFMATERIAL, 7, 0, [DIFFUSE, 0.1, 0.2, 0.3, LMNULL])
        c3f((0, 0, 1))
        v2f((40, 30))
        v2f((4, 30))
        endpolygon()
    a, _ = _draw_both(open_window, lambda: None, lambda: scene(True))
    b, _ = _draw_both(open_window, lambda: None, lambda: scene(False))
    assert (a != 0).sum() > 500
    assert np.array_equal(a, b)


def test_vertices_go_to_the_current_window(open_window):
    one = open_window(W, H)
    two = open_window(W, H)
    for gid, rgb in ((one, (1, 0, 0)), (two, (0, 0, 1))):
        winset(gid)
        ortho2(0, W, 0, H)
        bgnpolygon()
        c3f(rgb)
        v2f((0, 0))
        v2f((W, 0))
        v2f((W, H))
        v2f((0, H))
        endpolygon()
    winset(one)
    assert (colour() == 0xFF0000FF).all()
    winset(two)
    assert (colour() == 0xFFFF0000).all()


def test_a_nan_colour_drops_its_primitive_with_a_warning(open_window):
    open_window(W, H)
    ortho2(0, W, 0, H)
    bgnpolygon()
    c3f((float("nan"), 0, 0))
    v2f((0, 0))
    v2f((W, 0))
    v2f((W, H))
    endpolygon()
    with pytest.warns(Warning, match="non-finite"):
        finish()
    assert (colour() == 0).all()


@pytest.mark.parametrize("flush", [False, True])
@pytest.mark.parametrize("count", [3, 200])
def test_current_attributes_are_the_newest_events(open_window, flush, count):
    # the window state takes the newest normal, colour and texture coordinate
    # of the events sent since it last looked (VertexBatch.sync: a few events
    # searched as a list, many as an array, at a flush the flush's own):
    # gRGBcolor and the state read after `count` vertices give the last ones
    from irisgl._current import machine
    open_window(W, H)
    bgnpoint()
    for i in range(count):
        n3f((0.0, 0.1 * (i % 7), 1.0))
        c3i((i % 256, 7, 9))
        if i % 3 == 0:
            t2f((0.25 * i, 0.5))
        v2f((1 + i % 40, 1 + i % 30))
    cpack(0xFF332211)                                # after the last vertex: current too
    n3f((0.5, 0.25, 0.125))
    endpoint()
    if flush:
        machine.flush()                              # the batch's events go with it
    st = machine.current.st
    assert gRGBcolor() == (0x11, 0x22, 0x33)
    assert st.normal == (0.5, 0.25, 0.125)
    last_t = 0.25 * (3 * ((count - 1) // 3))
    assert st.texcoord[:2] == (last_t, 0.5)
    assert st.last_was_normal                        # n3f came after the colour
