"""Pop-up menus: defpup, newpup, addtopup, dopup, freepup, setpup
(docs/text-and-menus.md).

Item strings and selection follow defpup(3G): ``|`` separates items; ``%t``
title, ``%F`` menu function, ``%f`` item function, ``%n`` item function that
bypasses ``%F``, ``%m`` submenu, ``%l`` line under the item, ``%xN`` value N;
functions and submenu ids are the extra arguments, in order.  None of these
calls goes into a display list.  Headless, dopup answers from the script of
``vgx_emulator.menus.script`` / ``vgx-run --menu`` (-1 when there is none);
the menus are kept in ``vgx_emulator.menus.Menu`` for a real window to draw.
"""
from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, integer, machine

__all__ = ["defpup", "newpup", "addtopup", "dopup", "freepup", "setpup"]

_MODES = K.PUP_GREY | K.PUP_BOX | K.PUP_CHECK


@glcall(immediate=True)
def newpup():
    """newpup(3G): a new, empty menu; returns its (positive) id."""
    return machine.menus.new()


@glcall(immediate=True)
def defpup(text, *args):
    """defpup(3G): a menu from an item string; the functions and submenu
    ids its %F, %f, %n and %m flags name follow in order.  Returns its id."""
    t = machine.menus
    pid = t.new()
    try:
        t.add("defpup", pid, text, args)
    except BaseException:
        del t.menus[pid]                   # a call that raises defines nothing
        t.next_id = pid
        raise
    return pid


@glcall(immediate=True)
def addtopup(pup, text, arg=None):
    """addtopup(3G): append the items of ``text`` to menu pup; ``arg`` is
    the function or submenu id of its one %F, %f, %n or %m flag."""
    machine.menus.add("addtopup", pup, text, () if arg is None else (arg,), max_args=1)


@glcall(immediate=True)
def freepup(pup):
    """freepup(3G): delete menu pup."""
    machine.menus.free("freepup", pup)


@glcall(immediate=True)
def setpup(pup, entry, mode):
    """setpup(3G): the display mode of entry (1-based, title not counted):
    PUP_NONE, PUP_GREY (cannot be chosen), PUP_BOX, PUP_CHECK."""
    e = integer("setpup", entry, "entry")
    m = integer("setpup", mode, "mode")
    if m & ~_MODES:
        fail("setpup", f"mode {mode!r}", "PUP_NONE, PUP_GREY, PUP_BOX, PUP_CHECK (or'ed)")
    machine.menus.set_mode("setpup", pup, e, m)


@glcall(immediate=True)
def dopup(pup):
    """dopup(3G): pop up menu pup; returns the chosen item's value after its
    %f/%n function, submenus and the %F function ran, or -1 when nothing
    is chosen.  Headless the choice is the next scripted answer, and the
    RIGHTMOUSE release that ends the selection leaves the queue."""
    t = machine.menus
    t.menu("dopup", pup)
    answer = t.next_answer() if t.chooser is None else t.chooser(int(pup))
    _take_release()
    if answer is None or answer in ((0,), (-1,)):
        return -1
    return t.select(int(pup), answer)


def _take_release():
    """Remove the first queued RIGHTMOUSE release: the button release that
    chooses the item belongs to dopup (dopup(3G)), with the valuators tied
    to the button that came with it (tie(3G): one group)."""
    ev = machine.events
    q = ev.entries
    for i, (dev, val) in enumerate(q):
        if dev == K.RIGHTMOUSE and val == 0:
            del q[i]
            for v in ev.ties.get(K.RIGHTMOUSE, ()):
                if v and i < len(q) and q[i][0] == v:
                    del q[i]
            return
