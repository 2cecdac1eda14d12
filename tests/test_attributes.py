"""pushattributes(3G) / popattributes(3G): what is saved, depth, misuse."""
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import GLError
from irisgl.attributes import SAVED

RED, GREEN, BLUE = 0xFF0000FF, 0xFF00FF00, 0xFFFF0000


def state():
    from irisgl._current import machine
    return machine.current


def test_saved_fields_cover_the_man_page_list():
    # pushattributes(3G): backbuffer, frontbuffer, color, RGB color, writemask,
    # RGB writemask, pattern, shademodel, linestyle, linewidth, lsrepeat, font, drawmode
    for f in ("colour", "cmask", "front_enabled", "back_enabled", "pattern", "gouraud",
              "linestyle", "linewidth", "lsrepeat", "font", "drawmode"):
        assert f in SAVED


def test_colour_restored_and_used_by_next_primitive(open_window):
    open_window(8, 8)
    cpack(RED)
    pushattributes()
    cpack(GREEN)
    rectfi(0, 0, 3, 7)
    popattributes()
    rectfi(4, 0, 7, 7)
    img = lrectread(0, 0, 7, 0)
    # pixels well inside each rectangle (the edge rule is not tested here)
    assert img[0, 1] == GREEN and img[0, 5] == RED


def test_writemask_buffers_shademodel_pattern_restored(open_window):
    open_window(8, 8, double=True)
    wmpack(0x00FF00FF)
    frontbuffer(TRUE)
    shademodel(FLAT)
    defpattern(1, 16, [0x5555] * 16)
    setpattern(1)
    pushattributes()
    wmpack(0xFFFFFFFF)
    frontbuffer(FALSE)
    backbuffer(FALSE)
    shademodel(GOURAUD)
    setpattern(0)
    popattributes()
    st = state().st
    assert st.cmask == 0x00FF00FF
    assert st.front_enabled and st.back_enabled
    assert st.gouraud is False
    assert st.pattern == 1


def test_popped_pattern_applies_to_clear(open_window):
    open_window(16, 1)
    defpattern(1, 16, [0x5555] * 16)
    cpack(0)
    clear()
    pushattributes()
    setpattern(1)
    popattributes()
    cpack(RED)
    clear()                                # solid again: the pop restored pattern 0
    assert (lrectread(0, 0, 15, 0) == RED).all()


def test_depth_is_attribstackdepth_and_overflow_changes_nothing(open_window):
    open_window(4, 4)
    for i in range(ATTRIBSTACKDEPTH - 1):
        cpack(i)
        pushattributes()
    cpack(0x77)
    with pytest.raises(GLError) as e:
        pushattributes()
    assert str(e.value).startswith("pushattributes")
    assert len(state().attrib_stack) == ATTRIBSTACKDEPTH - 1
    for i in reversed(range(ATTRIBSTACKDEPTH - 1)):
        popattributes()
        assert state().st.colour[0] == i
    with pytest.raises(GLError) as e:
        popattributes()
    assert str(e.value).startswith("popattributes")


def test_lenient_overflow_is_ignored(open_window, capsys):
    import vgx_emulator
    open_window(4, 4)
    for _ in range(ATTRIBSTACKDEPTH - 1):
        pushattributes()
    vgx_emulator.errors.set_error_mode("lenient")
    pushattributes()                      # "ignored if the stack is full"
    assert len(state().attrib_stack) == ATTRIBSTACKDEPTH - 1
    assert "GL: pushattributes" in capsys.readouterr().err


def test_stack_is_per_window(open_window):
    a = open_window(4, 4)
    pushattributes()
    open_window(4, 4)
    with pytest.raises(GLError):
        popattributes()
    winset(a)
    popattributes()


def test_absent_fields_are_skipped(open_window):
    open_window(4, 4)
    pushattributes()
    saved = state().attrib_stack[-1]
    st = state().st
    assert set(saved) == {f for f in SAVED if hasattr(st, f)}


def test_recorded_in_objects(open_window):
    open_window(8, 2)
    makeobj(1)
    pushattributes()
    cpack(GREEN)
    rectfi(0, 0, 3, 1)
    popattributes()
    closeobj()
    cpack(RED)
    callobj(1)
    rectfi(4, 0, 7, 1)
    img = lrectread(0, 0, 7, 0)
    assert img[0, 1] == GREEN and img[0, 5] == RED
