"""Pop-up menus: defpup, newpup, addtopup, dopup, freepup, setpup
(defpup(3G), addtopup(3G), dopup(3G), setpup(3G)), the scripted answers
(vgx_emulator.menus.script, vgx-run --menu) and the text_menus demo."""
from pathlib import Path

import numpy as np
import pytest

import vgx_emulator
from irisgl import (GLError, PUP_CHECK, PUP_GREY, PUP_NONE, RIGHTMOUSE, addtopup, closeobj,
                    defpup, dopup, freepup, makeobj, newpup, qdevice, qenter, qread, qtest,
                    setpup)
from vgx_emulator import menus as M
from vgx_emulator.runner import main as vgx_run, run_program

from test_text import text_pixels

DEMO = Path(__file__).resolve().parent.parent / "programs" / "demos" / "text_menus.py"


def menu(pid):
    from irisgl._current import machine
    return machine.menus.menus[pid]


def answer(pid, *answers):
    """dopup's result for each scripted answer."""
    M.script(list(answers))
    return [dopup(pid) for _ in answers]


def test_items_titles_values_lines():
    m = defpup("Tools %t|cut|copy %x10 %l|paste|")
    mm = menu(m)
    assert mm.title == "Tools"
    assert [(i.label, i.value, i.line) for i in mm.items] == \
        [("cut", 1, False), ("copy", 10, True), ("paste", 3, False)]
    assert answer(m, 1, 2, 3) == [1, 10, 3]


def test_functions_in_order():
    calls = []

    def menufunc(v):
        calls.append(("F", v))
        return v * 100

    def itemfunc(v):
        calls.append(("f", v))
        return v + 1

    def bypass(v):
        calls.append(("n", v))
        return -v

    m = defpup("Demo %t %F|one|two %f|three %n|four %x7", menufunc, itemfunc, bypass)
    assert answer(m, 1) == [100]
    assert answer(m, 2) == [300]          # %f's result goes to %F
    assert answer(m, 3) == [-3]           # %n: %F is not called
    assert answer(m, 4) == [700]
    assert calls == [("F", 1), ("f", 2), ("F", 3), ("n", 3), ("F", 7)]


def test_submenu_paths():
    seen = []
    sub = defpup("Colour %t %F|red|green %x20", lambda v: seen.append(v) or v + 1000)
    m = defpup("Main %t %F|file|colour %m|quit", lambda v: v * 2, sub)
    assert answer(m, "2.1") == [2002]      # sub's %F, then the parent's %F
    assert answer(m, (2, 2)) == [2040]
    assert answer(m, 2) == [-1]            # released on the submenu entry
    assert answer(m, 3) == [6]
    assert seen == [1, 20]


def test_no_choice_is_minus_one():
    m = defpup("a|b")
    assert dopup(m) == -1                  # nothing scripted
    assert answer(m, 0, -1, 3) == [-1, -1, -1]
    M.script("2")
    assert dopup(m) == 2 and dopup(m) == -1


def test_setpup_grey_entry_cannot_be_chosen():
    hits = []
    m = defpup("T %t|a %f|b", hits.append)
    setpup(m, 1, PUP_GREY)
    assert answer(m, 1, 2) == [-1, 2] and hits == []
    setpup(m, 1, PUP_NONE)
    assert answer(m, 1) == [1] and hits == [1]
    setpup(m, 2, PUP_CHECK)
    assert menu(m).items[1].mode == PUP_CHECK and answer(m, 2) == [2]
    with pytest.raises(GLError, match="^setpup: entry 3"):
        setpup(m, 3, PUP_GREY)
    with pytest.raises(GLError, match="^setpup: mode"):
        setpup(m, 1, 64)


def test_addtopup_and_newpup():
    m = newpup()
    addtopup(m, "Edit %t", 0)
    addtopup(m, "undo|redo")
    addtopup(m, "clear %f", lambda v: v + 50)
    assert [i.label for i in menu(m).items] == ["undo", "redo", "clear"]
    assert answer(m, 1, 3) == [1, 53]
    before = list(menu(m).items)
    with pytest.raises(GLError, match="^addtopup: 2 flags need an argument"):
        addtopup(m, "x %f|y %f", print)
    with pytest.raises(GLError, match="^addtopup: menu 99 does not exist"):
        addtopup(99, "x", 0)
    assert menu(m).items == before


def test_defpup_errors_define_nothing():
    m0 = newpup()
    with pytest.raises(GLError, match="^defpup: %f in 'b %f' has no argument left"):
        defpup("a|b %f")
    with pytest.raises(GLError, match="^defpup: the argument of %F .* not callable"):
        defpup("T %t %F|a", 5)
    with pytest.raises(GLError, match="^defpup: submenu 42 does not exist"):
        defpup("a %m", 42)
    assert newpup() == m0 + 1               # no id was used up


def test_freepup():
    sub = defpup("x|y")
    m = defpup("s %m|t", sub)
    freepup(sub)
    with pytest.raises(GLError, match="^dopup: menu"):
        dopup(sub)
    assert answer(m, "1.1", 2) == [-1, 2]   # a freed submenu offers nothing
    with pytest.raises(GLError, match="^freepup: menu"):
        freepup(sub)


def test_dopup_takes_the_rightmouse_release():
    qdevice(RIGHTMOUSE)
    m = defpup("a|b")
    qenter(RIGHTMOUSE, 1)
    qenter(RIGHTMOUSE, 0)
    assert qread() == (RIGHTMOUSE, 1)
    M.script("2")
    assert dopup(m) == 2
    assert qtest() == 0                     # the release belonged to the menu


def test_dopup_takes_the_release_with_its_tied_valuators(open_window):
    """RIGHTMOUSE tied to MOUSEX and MOUSEY: the window system queues the
    release as one group (tie(3G)), and dopup takes the whole group, so no
    stray MOUSEX/MOUSEY entries follow a menu choice; later entries stay."""
    from irisgl import KEYBD, MOUSEX, MOUSEY, qreset, setvaluator, tie
    from irisgl._current import machine
    open_window()
    qreset()                                # (winopen's INPUTCHANGE and REDRAW)
    qdevice(RIGHTMOUSE)
    tie(RIGHTMOUSE, MOUSEX, MOUSEY)
    setvaluator(MOUSEX, 100, 0, 1279)
    setvaluator(MOUSEY, 200, 0, 1023)
    m = defpup("a|b")
    ev = machine.events
    ev.device_input(RIGHTMOUSE, 1)
    ev.device_input(RIGHTMOUSE, 0)
    qenter(KEYBD, 65)
    assert [qread() for _ in range(3)] == [(RIGHTMOUSE, 1), (MOUSEX, 100), (MOUSEY, 200)]
    M.script("1")
    assert dopup(m) == 1
    assert list(ev.entries) == [(KEYBD, 65)]


def test_not_recorded_in_objects(open_window):
    open_window()
    makeobj(3)
    m = defpup("a|b")
    M.script([1])
    assert dopup(m) == 1
    closeobj()
    from irisgl._current import machine
    assert machine.objects[3].items == []


def test_parse_answers():
    assert M.parse_answers("3, 2.1") == [(3,), (2, 1)]
    assert M.parse_answers([3, "2.1", (1, 2, 3)]) == [(3,), (2, 1), (1, 2, 3)]
    assert M.parse_answers(4) == [(4,)]
    with pytest.raises(ValueError):
        M.parse_answers("two")
    vgx_emulator.script_menus("1,2")
    assert M.pending() == 2


# -- the demo -------------------------------------------------------------------
W, H = 320, 240
TITLE = "IRIS GL text and pop-up menus"


def rows_up(img):
    """(h, w) packed 0xRRGGBB, row 0 at the bottom."""
    a = img[::-1].astype(np.int64)
    return (a[..., 0] << 16) | (a[..., 1] << 8) | a[..., 2]


def shown(img, colour):
    ys, xs = np.nonzero(rows_up(img) == colour)
    return set(zip(xs.tolist(), ys.tolist()))


def check_text(img, text, x, y, colour):
    want = text_pixels(text, x, y)
    got = shown(img, colour)
    region = {(px, py) for px, py in got if y - 3 <= py <= y + 11 and x <= px < x + 9 * len(text)}
    assert region == want, text


def test_demo_start_figure():
    img = run_program(DEMO, frames=1)
    assert img.shape == (H, W, 3)
    check_text(img, TITLE, (W - 9 * len(TITLE)) // 2, H - 5 - 15 + 3, 0xFFFFFF)
    check_text(img, "shape: square   colour: red", 10, 13, 0xFFFF00)
    up = rows_up(img)
    assert up[120, 160] == 0xFF0000 and up[120 + 55, 160 + 55] == 0xFF0000


@pytest.mark.parametrize("how", ["argv", "keyword"])
def test_demo_menu_changes_the_picture(how):
    if how == "argv":
        img = run_program(DEMO, frames=1, argv=["--menu", "1.2,3"])
    else:
        img = run_program(DEMO, frames=1, menu="1.2,3")
    up = rows_up(img)
    assert up[120, 160] == 0x00FF00                       # green
    assert up[120 + 55, 160 + 55] == 0x102040             # outside the circle
    assert up[120, 160 + 58] == 0x00FF00                  # inside it (r = 60)
    check_text(img, "shape: circle   colour: green", 10, 13, 0xFFFF00)
    check_text(img, TITLE, (W - 9 * len(TITLE)) // 2, H - 5 - 15 + 3, 0xFFFFFF)


def test_demo_quit_and_vgx_run_option(tmp_path):
    img = run_program(DEMO, frames=1, menu="5")           # Quit (%n): the program ends
    assert img is not None
    out = tmp_path / "m.png"
    assert vgx_run([str(DEMO), "--out", str(out), "--menu", "4"]) == 0
    assert out.stat().st_size > 0
