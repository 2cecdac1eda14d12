"""Errors: GLError naming the call, no state change, lenient mode, clamping
(docs/porting.md §4; docs/semantics.md §14, §1)."""
import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

ZMIN, ZMAX = -0x800000, 0x7FFFFF


def machine():
    from irisgl._current import machine as m
    return m


# -- a deep, comparable picture of every piece of state ------------------------------
def _freeze(o):
    if isinstance(o, np.ndarray):
        return ("nd", o.dtype.str, o.shape, o.tobytes())
    if isinstance(o, dict):
        return ("dict", tuple(sorted((repr(k), _freeze(v)) for k, v in o.items())))
    if isinstance(o, (list, tuple)):
        return (type(o).__name__, tuple(_freeze(v) for v in o))
    if isinstance(o, (set, frozenset)):
        return ("set", tuple(sorted(repr(v) for v in o)))
    if hasattr(o, "__dict__"):
        # (the state <-> batch links are cycles: each side is frozen on its own)
        return (type(o).__name__, _freeze({k: v for k, v in vars(o).items()
                                           if k not in ("events", "owner")}))
    if hasattr(type(o), "__slots__"):
        return (type(o).__name__, tuple(_freeze(getattr(o, s, None)) for s in type(o).__slots__))
    return o


def snapshot():
    """Window state, banks, batch, definitions, queue, colour map."""
    m = machine()
    out = {"defs": _freeze(m.defs), "events": _freeze(list(m.events.entries)),
           "colormap": _freeze(m.colormap), "current": m.current and m.current.gid,
           "windows": tuple(m.windows)}
    w = m.current
    if w is not None:
        w.st.colour                         # the current attributes brought up to date
        b = w.batch
        out.update(st=_freeze(w.st), front=_freeze(w.fb.front), back=_freeze(w.fb.back),
                   z=_freeze(w.fb.z), stencil=_freeze(w.fb.stencil),
                   batch=_freeze((b.pos, b.ev, b.attrs, b.prims, b.open, b.swaps, b.vblocks)),
                   readsource=w.readsource)
        if b.open is None:                  # queries are not allowed inside bgn/end
            out["api"] = (_freeze(np.asarray(getmatrix())), tuple(getviewport()), getmmode(),
                          tuple(getscrmask()))
    return out


def assert_error(call_name, fn, *args):
    """fn(*args) raises GLError("<call>: <what>; <allowed>") and changes nothing."""
    before = snapshot()
    with pytest.raises(GLError) as e:
        fn(*args)
    msg = str(e.value)
    assert msg.startswith(call_name + ":"), msg
    assert ";" in msg, msg                  # what was wrong; what is allowed
    after = snapshot()
    for k in before:
        assert before[k] == after[k], f"{call_name}: state {k!r} changed"
    return msg


@pytest.fixture
def win(open_window):
    """A 16x12 RGB window with something drawn in every bank."""
    gid = open_window(16, 12)
    ortho2(-0.5, 15.5, -0.5, 11.5)
    czclear(0xFF102030, 1234)
    zbuffer(TRUE)
    cpack(0xFF0000FF)
    pnt2i(3, 4)
    machine().flush()
    return gid


# -- unknown tokens -------------------------------------------------------------------
def test_zfunction_unknown(win):
    assert_error("zfunction", zfunction, 99)


def test_mmode_unknown(win):
    assert_error("mmode", mmode, 9)


def test_shademodel_unknown(win):
    assert_error("shademodel", shademodel, 5)


def test_lmbind_bad_target(win):
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.5, 0.5, 0.5, LMNULL])
    assert_error("lmbind", lmbind, 999, 1)


def test_lmdef_unknown_property(win):
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.5, 0.5, 0.5, LMNULL])
    assert_error("lmdef", lmdef, DEFMATERIAL, 1, 0, [SPECULAR, 1, 1, 1, 999, 1, LMNULL])
    assert_error("lmdef", lmdef, DEFMATERIAL, 2, 0, [LCOLOR, 1, 1, 1, LMNULL])  # a light's


def test_lmdef_bad_deftype(win):
    assert_error("lmdef", lmdef, 7, 1, 0, [LMNULL])


def test_lmdef_index_0(win):
    assert_error("lmdef", lmdef, DEFMATERIAL, 0, 0, [DIFFUSE, 1, 0, 0, LMNULL])
    assert_error("lmdef", lmdef, DEFLIGHT, 0, 0, [LCOLOR, 1, 0, 0, LMNULL])


def test_lmdef_missing_lmnull(win):
    assert_error("lmdef", lmdef, DEFMATERIAL, 3, 0, [DIFFUSE, 1, 0, 0])


def test_readsource_unknown(win):
    assert_error("readsource", readsource, 99)


@pytest.mark.parametrize("ax", ["w", "xy", "", 1, None])
def test_bad_axis_letter(win, ax):
    assert_error("rot", rot, 90, ax)
    assert_error("rotate", rotate, 900, ax)


def test_stensize_acsize_out_of_range(win):
    assert_error("stensize", stensize, 9)
    assert_error("stensize", stensize, -1)
    assert_error("acsize", acsize, 8)


# -- wrong array lengths --------------------------------------------------------------
def test_v3f_too_short(win):
    """A C array shorter than the call reads is an error; a longer one is
    read from its first elements (tests/test_c_habits.py)."""
    bgnpolygon()
    v3f((0, 0, 0))
    assert_error("v3f", v3f, (1, 2))
    assert_error("v2f", v2f, (1,))
    assert_error("v4f", v4f, (1, 2, 3))
    endpolygon()


def test_n3f_too_short(win):
    assert_error("n3f", n3f, (1, 2))


def test_c3f_too_short(win):
    assert_error("c3f", c3f, (1, 0))
    assert_error("c4f", c4f, (1, 0, 0))


def test_multmatrix_3x3(win):
    assert_error("multmatrix", multmatrix, np.eye(3))
    assert_error("multmatrix", multmatrix, [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    assert_error("loadmatrix", loadmatrix, np.eye(3))


# -- stacks ---------------------------------------------------------------------------
def test_popmatrix_on_empty_stack(win):
    msg = assert_error("popmatrix", popmatrix)
    assert "empty" in msg


def test_pushmatrix_beyond_32(win):
    for _ in range(31):
        pushmatrix()
    assert_error("pushmatrix", pushmatrix)


def test_popviewport_empty(win):
    assert_error("popviewport", popviewport)


# -- bgn/end rules --------------------------------------------------------------------
def test_vertex_outside_bgn_end(win):
    for name in ("v2f", "v3f", "v4f", "v2i", "v3s", "v3d"):
        fn = globals()[name]
        assert_error(name, fn, (0, 0, 0, 1)[:int(name[1])])


def test_bgnpolygon_inside_bgnline(win):
    bgnline()
    v2f((0, 0))
    assert_error("bgnpolygon", bgnpolygon)
    v2f((5, 5))
    endline()


def test_end_without_bgn(win):
    assert_error("endpolygon", endpolygon)
    bgnline()
    assert_error("endpolygon", endpolygon)
    endline()


@pytest.mark.parametrize("call, args", [("zbuffer", (FALSE,)), ("clear", ()),
                                        ("translate", (1, 0, 0)), ("pushmatrix", ()),
                                        ("shademodel", (FLAT,)), ("swapbuffers", ()),
                                        ("ortho2", (0, 1, 0, 1)), ("getmatrix", ())])
def test_call_not_allowed_inside_bgnpolygon(win, call, args):
    bgnpolygon()
    v2f((0, 0))
    assert_error(call, globals()[call], *args)
    endpolygon()
    assert getzbuffer() == 1


def test_allowed_calls_inside_bgnpolygon(win):
    bgnpolygon()
    c3f((1, 0, 0))
    cpack(0xFF00FF00)
    RGBcolor(1, 2, 3)
    n3f((0, 0, 1))
    v2f((0, 0))
    v2f((3, 0))
    v2f((3, 3))
    endpolygon()


def test_257_vertex_polygon_is_an_error_at_endpolygon(win):
    # GD_NVERTEX_POLY is 256: the check is at endpolygon (docs/decisions.md), so
    # v2f stays a few bytecodes; the polygon is not drawn and the pair is closed
    cpack(0xFFFFFFFF)
    zbuffer(FALSE)

    def ring(n):
        bgnpolygon()
        for i in range(n):
            v2f((2 + 4 * np.cos(2 * np.pi * i / n), 2 + 4 * np.sin(2 * np.pi * i / n)))
    before = lrectread(2, 2, 2, 2)[0, 0]
    assert before != 0xFFFFFFFF
    ring(257)
    with pytest.raises(GLError, match=r"^endpolygon: 257 vertices in a polygon"):
        endpolygon()
    assert lrectread(2, 2, 2, 2)[0, 0] == before       # nothing was drawn
    ring(256)                                          # the pair was closed: bgn works again
    endpolygon()
    assert lrectread(2, 2, 2, 2)[0, 0] == 0xFFFFFFFF   # 256 vertices are drawn


def test_polf_more_than_256(win):
    pts = [(np.cos(a), np.sin(a), 0) for a in np.linspace(0, 6.28, 257)]
    assert_error("polf", polf, 257, pts)


# -- calls before winopen ------------------------------------------------------------------
@pytest.mark.parametrize("call, args", [("v3f", ((0, 0, 0),)), ("clear", ()), ("getsize", ()),
                                        ("gconfig", ()), ("RGBmode", ()), ("translate", (1, 2, 3)),
                                        ("cpack", (0xFF,)), ("n3f", ((0, 0, 1),)),
                                        ("pushmatrix", ()), ("bgnpolygon", ()),
                                        ("zbuffer", (TRUE,)), ("swapbuffers", ()),
                                        ("lrectread", (0, 0, 1, 1)), ("c3f", ((1, 0, 0),))])
def test_calls_before_winopen(call, args):
    assert_error(call, globals()[call], *args)


def test_getgdesc_and_pref_calls_before_winopen():
    assert getgdesc(GD_XPMAX) == 1280
    prefsize(10, 10)
    qdevice(LEFTMOUSE)


# -- projections and viewing ----------------------------------------------------------
@pytest.mark.parametrize("fovy", [2, 1, 0, -450, 1.9])
def test_perspective_fovy_too_small(win, fovy):
    assert_error("perspective", perspective, fovy, 1.0, 1.0, 10.0)


def test_perspective_fovy_just_above_2(win):
    perspective(3, 1.0, 1.0, 10.0)
    f = 1 / np.tan(np.radians(0.15))
    assert getmatrix()[1][1] == pytest.approx(f, rel=1e-5)


def test_lookat_eye_equals_reference(win):
    assert_error("lookat", lookat, 1, 2, 3, 1, 2, 3, 0)


def test_ortho_degenerate(win):
    assert_error("ortho2", ortho2, 1, 1, 0, 1)
    assert_error("ortho", ortho, 0, 1, 0, 1, 2, 2)


# -- mode mismatches ----------------------------------------------------
def test_rgb_colour_in_cmode(open_window):
    open_window(8, 8, rgb=False)
    assert_error("RGBcolor", RGBcolor, 1, 2, 3)
    assert_error("cpack", cpack, 0xFF)
    assert_error("c3f", c3f, (1, 0, 0))
    assert_error("wmpack", wmpack, 0)


# -- lenient mode ---------------------------------------------------------------------
@pytest.mark.parametrize("call, args", [("popmatrix", ()), ("zfunction", (99,)), ("mmode", (9,)),
                                        ("shademodel", (5,)), ("v3f", ((0, 0, 0),)),
                                        ("multmatrix", (np.eye(3),)), ("lookat", (0,) * 7),
                                        ("perspective", (2, 1, 1, 10))])
def test_lenient_prints_and_ignores(win, capsys, call, args):
    vgx_emulator.set_error_mode("lenient")
    capsys.readouterr()
    before = snapshot()
    assert globals()[call](*args) is None
    err = capsys.readouterr().err
    assert err.startswith(f"GL: {call}: "), err
    assert err.count("\n") == 1
    assert snapshot() == before


def test_lenient_inside_polygon(win, capsys):
    vgx_emulator.set_error_mode("lenient")
    cpack(0xFF00FF00)
    zbuffer(FALSE)
    bgnpolygon()
    v2f((0, 0))
    v3f((1, 2))                          # wrong length: ignored
    zbuffer(TRUE)                        # not allowed inside: ignored
    v2f((15, 0))
    v2f((15, 11))
    v2f((0, 11))
    endpolygon()
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("GL: v3f: ") and err[1].startswith("GL: zbuffer: ")
    assert getzbuffer() == 0
    assert np.all(lrectread(1, 1, 13, 9) == 0xFF00FF00)     # the four good vertices drawn


def test_lenient_before_winopen(capsys):
    vgx_emulator.set_error_mode("lenient")
    assert clear() is None
    assert v3f((0, 0, 0)) is None
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("GL: clear: ") and err[1].startswith("GL: v3f: ")


def test_error_mode_switch():
    vgx_emulator.set_error_mode("lenient")
    assert vgx_emulator.error_mode() == "lenient"
    vgx_emulator.set_error_mode("strict")
    assert vgx_emulator.error_mode() == "strict"
    with pytest.raises(ValueError):
        vgx_emulator.set_error_mode("loud")


# -- clamping instead of refusing -------------------------------------------------------
def test_rgbcolor_clamps(win):
    zbuffer(FALSE)
    RGBcolor(300, -5, 10)
    assert gRGBcolor() == (255, 0, 10)
    pnt2i(5, 5)
    assert lrectread(5, 5, 5, 5)[0, 0] == 0xFF0A00FF


def test_c3f_and_c3i_clamp(win):
    zbuffer(FALSE)
    c3f((2.0, -1.0, 0.2))               # 0.2 * 255 = 51
    pnt2i(1, 1)
    c3i((1000, -3, 7))
    pnt2i(2, 1)
    row = lrectread(1, 1, 2, 1)[0]
    assert row[0] == 0xFF3300FF
    assert row[1] == 0xFF0700FF


@pytest.mark.parametrize("zval, expect", [(2 ** 30, ZMAX), (-2 ** 30, ZMIN), (ZMAX + 1, ZMAX),
                                          (ZMIN - 1, ZMIN), (ZMAX, ZMAX), (-5, -5),
                                          # a C long: 32-bit two's complement first
                                          (0xff800000, ZMIN), (0xffffffff, -1),
                                          (2 ** 32 + 5, 5), (0x80000000, ZMIN)])
def test_czclear_clamps_z(win, zval, expect):
    """czclear(3G)'s zval is a C long: a hex constant such as 0xff800000 (a
    Personal IRIS program's GD_ZMIN) is the 32-bit value C passes, then the
    z range clamps it."""
    czclear(0xFF000000, zval)
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, 15, 11)
    assert z.dtype == np.int32
    assert np.all(z == expect)
    readsource(SRC_FRONT)
    assert np.all(lrectread(0, 0, 15, 11) == 0xFF000000)


def test_nine_digit_zwritemask_accepted(win):
    czclear(0, 0)
    zwritemask(0xfffffffff)             # Heidmann's listing: reduced mod 2**32 = all ones
    zclear()
    readsource(SRC_ZBUFFER)
    assert np.all(lrectread(0, 0, 15, 11) == ZMAX)


def test_wide_zwritemask_reduced_modulo_2_32(win):
    czclear(0, 0)
    zwritemask(0x100000000)             # mod 2**32 = 0: nothing writable
    zclear()
    readsource(SRC_ZBUFFER)
    assert np.all(lrectread(0, 0, 15, 11) == 0)
    zwritemask(0x1000000FF)             # mod 2**32 = 0xFF
    zclear()
    assert np.all(lrectread(0, 0, 15, 11) == 0xFF)


def test_nine_digit_wmpack_accepted(win):
    wmpack(0xfffffffff)
    cpack(0xFF123456)
    clear()
    assert np.all(lrectread(0, 0, 15, 11) == 0xFF123456)
    czclear(0, 0)
    wmpack(0x1000000FF)                 # mod 2**32: red only
    cpack(0xFFFFFFFF)
    clear()
    assert np.all(lrectread(0, 0, 15, 11) == 0x000000FF)


def test_cpack_wider_than_32_bits(win):
    zbuffer(FALSE)
    cpack(0x7FF0000FF)                  # mod 2**32 = 0xFF0000FF
    pnt2i(0, 0)
    assert lrectread(0, 0, 0, 0)[0, 0] == 0xFF0000FF


def test_very_wide_masks_reduced_exactly(win):
    zbuffer(FALSE)
    cpack((0xABC << 64) | 0xFF00FF00)   # mod 2**32 = 0xFF00FF00
    pnt2i(0, 0)
    assert lrectread(0, 0, 0, 0)[0, 0] == 0xFF00FF00


def test_zclear_with_extra_argument(win):
    czclear(0, 0)
    zclear(getgdesc(GD_ZMAX))           # Heidmann: one extra argument, ignored
    readsource(SRC_ZBUFFER)
    assert np.all(lrectread(0, 0, 15, 11) == ZMAX)
    czclear(0, 0)
    zclear(0)                           # ignored even when it is not GD_ZMAX
    assert np.all(lrectread(0, 0, 15, 11) == ZMAX)


def test_numpy_error_state_is_quiet_inside_a_call_and_restored_after(open_window):
    """Every wrapped call runs with numpy's floating-point warnings off
    (errors.fp_quiet) and leaves the program's own numpy error state as it
    was, also when the call raises GLError or a nested call ran inside it."""
    import numpy as np
    from irisgl import translate
    from vgx_emulator import errors
    open_window(16, 16)
    seen = []
    with np.errstate(all="raise"):
        before = np.geterr()
        token = errors.fp_quiet()
        seen.append(np.geterr())
        errors.fp_quiet()                  # a nested quiet (a call inside a call)
        errors.fp_restore(token)
        assert np.geterr() == before
        translate(1e308, 1e308, 1e308)     # overflows in the product: no FloatingPointError
        assert np.geterr() == before
        with pytest.raises(GLError):
            translate("a", 0, 0)
        assert np.geterr() == before
    assert set(seen[0].values()) == {"ignore"} and set(before.values()) == {"raise"}
