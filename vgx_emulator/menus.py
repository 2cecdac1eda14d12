"""Pop-up menus: item strings, menu objects and the scripted dopup answers.

defpup(3G)/addtopup(3G) strings hold items separated by ``|``; flags in an
item: ``%t`` title, ``%F`` menu-wide function, ``%f`` item function, ``%n``
item function that bypasses ``%F``, ``%m`` submenu, ``%l`` separator line
under the item, ``%xN`` item value N.  Flags that need an argument (``%F``
``%f`` ``%n`` ``%m``) take the next one in order.  Items are numbered from 1
without the title; an item's default value is its number.

Every menu keeps its title, items, separators, submenus and entry modes
(setpup(3G)) in :class:`Menu`, for a real window to draw later.  Headless,
dopup(3G) takes its answer from a script (:func:`script`, ``vgx-run
--menu``): one answer per dopup call, each naming an item by its number, a
path through submenus written ``2.1`` (item 2, then item 1 of its submenu).
With no answer left, dopup returns -1.
"""
import inspect
import re
from collections import deque

from .errors import fail, warn

PUP_NONE, PUP_GREY, PUP_BOX, PUP_CHECK = 0, 1, 2, 4

_FLAG = re.compile(r"%([tFfnml])|%x\s*(-?\d+)")
_TAKES_ARG = {"F", "f", "n", "m"}


class Item:
    """One entry: its label, value, function and how it is shown."""
    __slots__ = ("label", "value", "fn", "bypass", "submenu", "line", "mode")

    def __init__(self, label, value):
        self.label = label
        self.value = value
        self.fn = None             # %f or %n function
        self.bypass = False        # %n: the menu function is not called
        self.submenu = None        # %m: menu id
        self.line = False          # %l: separator line under the item
        self.mode = PUP_NONE       # setpup: PUP_NONE / PUP_GREY / PUP_BOX / PUP_CHECK bits

    def __repr__(self):
        return f"Item({self.label!r}, value={self.value})"


class Menu:
    """A pop-up menu: title, menu-wide function (%F), items."""

    def __init__(self):
        self.title = None
        self.fn = None
        self.items = []


def parse(call, text, args):
    """The items of a defpup/addtopup string: a list of (kind, label, flags)
    where flags is a list of (flag, argument); ``args`` is consumed in order.
    Raises GLError (nothing changed) for a missing or wrong argument."""
    if not isinstance(text, str):
        fail(call, f"item string {text!r} is not a str", "pass the menu text as a str")
    args = list(args)
    out = []
    for part in text.split("|"):
        flags = []
        for m in _FLAG.finditer(part):
            if m.group(2) is not None:
                flags.append(("x", int(m.group(2))))
                continue
            f = m.group(1)
            arg = None
            if f in _TAKES_ARG:
                if not args:
                    if f == "n":           # old GL: %n marks a plain item, no argument
                        flags.append(("n", None))
                        continue
                    fail(call, f"%{f} in {part.strip()!r} has no argument left",
                         "pass one function or menu id per %F, %f, %n and %m, in order")
                arg = args.pop(0)
                if f == "m":
                    arg = _menu_arg(call, arg)
                elif not callable(arg):
                    fail(call, f"the argument of %{f} in {part.strip()!r} is not callable",
                         "pass a function")
            flags.append((f, arg))
        label = " ".join(_FLAG.sub(" ", part).split())
        if not flags and not label:
            continue                       # an empty piece (a trailing "|")
        out.append((label, flags))
    return out


def _menu_arg(call, arg):
    try:
        pid = int(arg)
    except (TypeError, ValueError):
        fail(call, f"submenu {arg!r} is not a menu id", "pass an id from defpup or newpup")
    return pid


class MenuTable:
    """Every menu of the machine and the scripted answers of dopup."""

    def __init__(self):
        self.menus = {}
        self.next_id = 1
        self.answers = deque()
        #: a real window's menu: ``chooser(pup) -> path or None`` pops the
        #: menu up and returns what the user chose; None: the script answers
        self.chooser = None

    # -- definitions -------------------------------------------------------
    def new(self):
        pid = self.next_id
        self.next_id += 1
        self.menus[pid] = Menu()
        return pid

    def menu(self, call, pup):
        try:
            pid = int(pup)
        except (TypeError, ValueError, OverflowError):      # OverflowError: int(inf)
            fail(call, f"menu {pup!r} is not a menu id", "pass an id from defpup or newpup")
        m = self.menus.get(pid)
        if m is None:
            fail(call, f"menu {pid} does not exist", "pass an id from defpup or newpup")
        return m

    def add(self, call, pup, text, args, max_args=None):
        """Append the items of ``text`` to menu ``pup`` (all checks first)."""
        m = self.menu(call, pup)
        if max_args is not None and isinstance(text, str):
            used = sum(1 for f in _FLAG.findall(text) if f[0] in _TAKES_ARG)
            if used > max_args:
                fail(call, f"{used} flags need an argument", "addtopup takes one: at most "
                     "one of %F, %f, %n, %m per call")
        parsed = parse(call, text, args)
        for _, flags in parsed:
            for f, a in flags:
                if f == "m" and a not in self.menus:
                    fail(call, f"submenu {a} does not exist", "define it with defpup first")
        for label, flags in parsed:
            kinds = [f for f, _ in flags]
            if "F" in kinds:
                m.fn = dict(flags)["F"]
            if "t" in kinds:
                m.title = label
                continue
            if kinds == ["F"] and not label:
                continue                   # "%F" alone: only the menu function
            item = Item(label, len(m.items) + 1)
            for f, a in flags:
                if f == "x":
                    item.value = a
                elif f in ("f", "n"):
                    item.fn = a
                    item.bypass = f == "n"
                elif f == "m":
                    item.submenu = a
                elif f == "l":
                    item.line = True
            m.items.append(item)

    def free(self, call, pup):
        self.menu(call, pup)
        del self.menus[int(pup)]

    def set_mode(self, call, pup, entry, mode):
        m = self.menu(call, pup)
        if not 1 <= entry <= len(m.items):
            fail(call, f"entry {entry} of menu {int(pup)}",
                 f"entries are 1..{len(m.items)} (the title is not counted)")
        m.items[entry - 1].mode = mode

    # -- selection -----------------------------------------------------------
    def select(self, pup, path):
        """The value dopup returns when the user picks ``path`` (item numbers
        through submenus) in menu ``pup``: -1 for nothing chosen."""
        m = self.menus.get(pup)
        if m is None or not path:
            return -1
        n = path[0]
        if not 1 <= n <= len(m.items):
            return -1                      # released outside the menu
        item = m.items[n - 1]
        if item.mode & PUP_GREY:
            return -1                      # a greyed entry cannot be chosen
        if item.submenu is not None:
            if len(path) == 1:
                return -1                  # [S] released on the entry, submenu not entered
            v = self.select(item.submenu, path[1:])
            if v == -1:
                return -1
        else:
            if len(path) > 1:
                warn("dopup", f"item {n} of menu {pup} has no submenu; "
                     f"the rest of the answer {'.'.join(map(str, path))} is ignored")
            v = item.value
            if item.fn is not None:
                v = _result(_handler(item.fn, v), v)
                if item.bypass:
                    return v
            elif item.bypass:
                return v
        if m.fn is not None:
            v = _result(_handler(m.fn, v), v)
        return v

    def next_answer(self):
        return self.answers.popleft() if self.answers else None


def _handler(fn, v):
    """Call a %f/%F/%n handler with the value, or with nothing when it takes no
    argument: a K&R C handler declared ``f()`` ignores the value it is passed,
    and a line-by-line port writes it ``def f():``."""
    try:
        inspect.signature(fn).bind(v)
    except TypeError:
        try:
            inspect.signature(fn).bind()
        except TypeError:
            return fn(v)                   # let the call itself report the mismatch
        return fn()
    except ValueError:                     # no signature to inspect (some builtins)
        pass
    return fn(v)


def _result(r, given):
    """A handler's value: what it returned ([S] None passes ``given`` on)."""
    if r is None:
        return given
    try:
        return int(r)
    except (TypeError, ValueError):
        return r


def parse_answers(answers):
    """Scripted answers as tuples of item numbers: ``"3,2.1"``, ``[3, "2.1"]``,
    ``[3, (2, 1)]`` all give ``[(3,), (2, 1)]``; 0 or -1 chooses nothing."""
    if isinstance(answers, str):
        answers = [a for a in answers.split(",") if a.strip()]
    elif isinstance(answers, (int, tuple)):
        answers = [answers]
    out = []
    for a in answers:
        if isinstance(a, str):
            try:
                path = tuple(int(p) for p in a.strip().split("."))
            except ValueError:
                raise ValueError(f"menu answer {a!r}: write item numbers, "
                                 "a submenu path as 2.1") from None
        elif isinstance(a, (tuple, list)):
            path = tuple(int(p) for p in a)
        else:
            path = (int(a),)
        out.append(path)
    return out


def script(answers, machine=None):
    """Queue the answers the next dopup calls take, one per call (replacing
    any left): item numbers, submenu paths ``"2.1"``, or a comma-separated
    string ``"3,2.1"``.  Not IRIS GL: the headless stand-in for the user."""
    if machine is None:
        from irisgl._current import machine
    machine.menus.answers = deque(parse_answers(answers))


def pending(machine=None):
    """How many scripted answers are left."""
    if machine is None:
        from irisgl._current import machine
    return len(machine.menus.answers)
