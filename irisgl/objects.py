"""Display lists: makeobj, closeobj, callobj, genobj, isobj, delobj, editobj,
maketag, gentag, istag, objreplace, objinsert, objdelete (objects(3G),
editobj(3G); docs/semantics.md §12).

While an object is open, calls are recorded instead of executed, except the
queries and immediate-only calls listed in ``IMMEDIATE`` ([S] where the
man pages leave it open: every ``get*`` query, readers, window and
configuration calls, defpattern, mapcolor, the event queue and the object
calls themselves run immediately).  ``callobj`` replays; geometry is replayed
as arrays (see vgx_emulator/objects.py).  Editing: ``editobj`` reopens an
object with the edit point at its end; ``objreplace(t)`` replaces what
follows tag t up to the next tag, ``objinsert(t)`` inserts after tag t,
``objdelete(t1, t2)`` removes what lies between the two tags, and
``closeobj`` ends the editing.
"""
import numpy as np

from vgx_emulator import objects as O
from vgx_emulator.errors import fail, warn

from . import constants as K
from ._current import IMMEDIATE, glcall, integer, machine, num, win

__all__ = ["makeobj", "closeobj", "callobj", "genobj", "isobj", "delobj", "editobj",
           "maketag", "gentag", "istag", "objreplace", "objinsert", "objdelete", "getopenobj",
           "newtag", "deltag", "bbox2", "bbox2i", "bbox2s", "callfunc"]

IMMEDIATE.update({
    "makeobj", "closeobj", "genobj", "isobj", "delobj", "editobj", "gentag", "istag",
    "objreplace", "objinsert", "objdelete", "maketag", "getopenobj", "newtag", "deltag",
    "winopen", "winclose", "winset", "winget", "prefsize", "prefposition", "keepaspect",
    "foreground", "noport", "winconstraints", "gbegin", "RGBmode", "cmode", "doublebuffer",
    "singlebuffer", "stensize", "acsize", "zbsize", "gconfig", "gexit", "ginit", "greset",
    "swapbuffers", "gflush", "finish", "defpattern", "mapcolor", "qdevice", "unqdevice",
    "qenter", "qreset", "qread", "qtest", "isqueued", "tie", "readsource", "lrectread",
    "rectread", "getgdesc", "gRGBcolor", "lgetdepth", "defbasis"})


class _Object:
    __slots__ = ("items", "ops", "cursor", "replacing", "_callees")

    def __init__(self):
        self.items = []
        self.ops = []
        self.cursor = 0
        self.replacing = False            # objreplace: new routines overwrite, one for one
        self._callees = (None, ())

    def callees(self):
        """The objects this one calls (callobj arguments, in order), from its
        items as last compiled: kept until closeobj compiles it again (its
        ``ops`` are then a new list), so callobj checks nesting without
        walking every item each time."""
        ops, out = self._callees
        if ops is not self.ops:
            out = []
            for it in self.items:
                if it[0] == "call" and it[1] == "callobj" and it[3]:
                    try:
                        out.append(int(it[3][0]))
                    except (TypeError, ValueError):
                        continue
            self._callees = (self.ops, out)
        return out


def record(name, fn, args):
    """Called by the glcall wrapper while an object is open.  The arguments
    are copied now, as C copies the values at the call: a program that
    reuses one scratch array while it builds an object replays what it sent
    (makeobj(3G) compiles values, not references)."""
    rec = machine.recording
    obj = machine.objects[rec]
    item = ("call", name, fn, tuple(_value(a) for a in args))
    if obj.replacing:                     # objreplace(3G): overwrite the next routine
        while obj.cursor < len(obj.items) and obj.items[obj.cursor][0] == "tag":
            obj.cursor += 1               # tags mark places; they are not overwritten
        if obj.cursor < len(obj.items):
            obj.items[obj.cursor] = item
            obj.cursor += 1
            return
    obj.items.insert(obj.cursor, item)
    obj.cursor += 1


def _value(a):
    """A copy of an argument that later changes to the caller's array cannot
    reach: arrays and sequences are copied (recursively), scalars, strings
    and callables are kept."""
    if isinstance(a, np.ndarray):
        return a.copy()
    if isinstance(a, (list, tuple)):
        return type(a)(_value(x) for x in a) if type(a) in (list, tuple) else a
    if isinstance(a, (bytearray, memoryview)):
        return bytes(a)
    if isinstance(a, dict):
        return {k: _value(v) for k, v in a.items()}
    return a


def _obj_id(call, obj):
    o = integer(call, obj, "object")
    if not 0 < o <= 0x7FFFFFFF:
        fail(call, f"object {o}", "a positive Object number")
    return o


@glcall
def makeobj(obj):
    """makeobj(3G): start recording into obj (its old contents are deleted).
    An object still open is closed first, as SGI's library does (flight's
    makemtn ends with ``closeobj;``, no call, and makes the next object)."""
    o = _obj_id("makeobj", obj)
    _close_open()
    machine.objects[o] = _Object()
    machine.recording = o


@glcall
def editobj(obj):
    """editobj(3G): reopen obj for editing, the edit point at its end (an
    object still open is closed first, as makeobj does)."""
    o = _obj_id("editobj", obj)
    if o not in machine.objects:
        fail("editobj", f"object {o} is not defined", "makeobj it first")
    _close_open()
    ob = machine.objects[o]
    ob.cursor = len(ob.items)
    ob.replacing = False
    machine.recording = o


@glcall
def closeobj():
    """closeobj(3G): end recording; the object's geometry is packed for
    replay.  "If no object is open, closeobj is ignored"."""
    _close_open()


def _close_open():
    """Close the object open for recording or editing, if there is one."""
    if machine.recording is None:
        return
    ob = machine.objects[machine.recording]
    ob.ops = O.compile_items(ob.items)
    ob.replacing = False
    machine.recording = None


@glcall
def getopenobj():
    """getopenobj(3G): the object open for recording or editing, -1 if none."""
    return machine.recording if machine.recording is not None else -1


@glcall
def genobj():
    """genobj(3G): a unique object number, never handed out before nor in use.
    So numbers taken by genobj calls in a row, before any makeobj, differ
    (``a = genobj(); b = genobj()``)."""
    return _generate("obj", machine.objects)


def _generate(kind, in_use):
    """The next number after the last one genobj (``kind`` "obj") or gentag
    ("tag") handed out that is not in ``in_use``, 1..2**31-1 (31-bit
    numbers, genobj(3G), gentag(3G)); [S] past 2**31-1 it starts again at 1."""
    n = machine.generated[kind]
    while True:
        n = n + 1 if n < 0x7FFFFFFF else 1
        if n not in in_use:
            machine.generated[kind] = n
            return n


@glcall
def isobj(obj):
    """isobj(3G): TRUE when obj is a defined object."""
    return int(integer("isobj", obj, "object") in machine.objects)


@glcall
def delobj(obj):
    """delobj(3G): free obj (an undefined object is ignored)."""
    o = integer("delobj", obj, "object")
    if machine.recording == o:
        fail("delobj", f"object {o} is open", "closeobj first")
    machine.objects.pop(o, None)


def _replay(obj, depth):
    if depth > O.MAX_DEPTH:
        fail("callobj", f"objects nested deeper than {O.MAX_DEPTH}", "no recursive objects")
    ob = machine.objects.get(obj)
    if ob is None:
        warn("callobj", f"object {obj} is not defined; nothing drawn")
        return
    w = machine.current
    for op in ob.ops:
        if op[0] == "run":
            if w is not None and O.replay_run(machine, w, op[1]):
                continue
            for _, fn, a in op[2]:
                fn(*a)
        elif op[1] is callobj:
            _replay(integer("callobj", op[2][0], "object"), depth + 1)
        elif op[1] in _BBOX:
            if op[1](*op[2]):
                return                # bbox2(3G): culled or pruned, the rest is skipped
        else:
            op[1](*op[2])


def _nesting(obj):
    """How deep the objects called from obj nest (obj alone: 0), or None
    when obj reaches itself (a recursive object)."""
    depth, path = {}, set()

    def walk(o):
        if o in path:
            return None
        if o in depth:
            return depth[o]
        ob = machine.objects.get(o)
        if ob is None:
            return 0
        path.add(o)
        d = 0
        for c in ob.callees():
            inner = walk(c)
            if inner is None:
                return None
            d = max(d, inner + 1)
        path.discard(o)
        depth[o] = d
        return d
    return walk(obj)


@glcall
def callobj(obj):
    """callobj(3G): execute obj (objects may call objects).  A recursive
    object, or one nesting deeper than the machine's limit, raises GLError
    before anything of it runs (nothing drawn, no matrix changed)."""
    win("callobj")
    o = integer("callobj", obj, "object")
    d = _nesting(o)
    if d is None:
        fail("callobj", f"object {o} calls itself (directly or through other objects)",
             "objects may call other objects, not themselves")
    if d > O.MAX_DEPTH:
        fail("callobj", f"objects nested {d} deep", f"at most {O.MAX_DEPTH}")
    _replay(o, 0)


@glcall
def maketag(t):
    """maketag(3G): a tag at the edit point of the open object (moved there if it has it).
    A tag number the object already has moves here: "if you later define a
    tag with the same value, the first tag is lost" (gentag(3G))."""
    if machine.recording is None:
        fail("maketag", "no object is open", "makeobj or editobj first")
    ob = machine.objects[machine.recording]
    t = integer("maketag", t, "tag")
    _lose_tag(ob, t)
    ob.items.insert(ob.cursor, ("tag", t))
    ob.cursor += 1


def _lose_tag(ob, t):
    """Removes tag t from ob if it is there."""
    for i, it in enumerate(ob.items):
        if it[0] == "tag" and it[1] == t:
            _drop_tag(ob, i)
            return


def _drop_tag(ob, i):
    """Removes the tag at ob.items[i] (the routines stay), the edit point
    kept on the same routine."""
    del ob.items[i]
    if i < ob.cursor:
        ob.cursor -= 1


def _tag_index(call, t):
    if machine.recording is None:
        fail(call, "no object is being edited", "editobj first")
    ob = machine.objects[machine.recording]
    t = integer(call, t, "tag")
    if t == K.STARTTAG:
        return ob, -1
    if t == K.ENDTAG:
        return ob, len(ob.items)
    for i, it in enumerate(ob.items):
        if it[0] == "tag" and it[1] == t:
            return ob, i
    fail(call, f"tag {t} is not in object {machine.recording}", "use a tag made by maketag")


@glcall
def gentag():
    """gentag(3G): a unique tag number, never handed out before nor in the open object."""
    ob = machine.objects.get(machine.recording) if machine.recording is not None else None
    return _generate("tag", {it[1] for it in ob.items if it[0] == "tag"} if ob else ())


@glcall
def istag(t):
    """istag(3G): TRUE when tag t is in the object open for editing."""
    t = integer("istag", t, "tag")
    if machine.recording is None:
        return 0
    ob = machine.objects[machine.recording]
    return int(any(it[0] == "tag" and it[1] == t for it in ob.items))


@glcall
def objinsert(t):
    """objinsert(3G): the edit point moves just after tag t."""
    ob, i = _tag_index("objinsert", t)
    ob.cursor = i + 1
    ob.replacing = False


@glcall
def objreplace(t):
    """objreplace(3G): the routines that follow overwrite, one for one, those
    after tag t, until closeobj, objinsert, objdelete or objreplace; tags on
    the way stay, and past the object's end the new routines are added."""
    ob, i = _tag_index("objreplace", t)
    ob.cursor = i + 1
    ob.replacing = True


@glcall
def objdelete(t1, t2):
    """objdelete(3G): delete what lies between tags t1 and t2 (tags kept).
    "If no object is open for editing, objdelete is ignored"."""
    if machine.recording is None:
        return
    ob, i = _tag_index("objdelete", t1)
    _, j = _tag_index("objdelete", t2)
    if j < i:
        i, j = j, i
    del ob.items[i + 1:j]
    ob.cursor = min(ob.cursor, len(ob.items))
    ob.replacing = False


@glcall
def newtag(newtg, oldtg, offst):
    """newtag(3G): tag ``newtg`` placed ``offst`` routines beyond tag
    ``oldtg`` in the object open for editing (immediate).  [S] the offset
    counts recorded calls, not tags; beyond the end of the object is an error.
    A ``newtg`` the object already has moves to the new place, as maketag's
    does (gentag(3G): "the first tag is lost"); ``newtg`` equal to ``oldtg``,
    STARTTAG or ENDTAG is an error."""
    n = integer("newtag", newtg, "tag")
    off = integer("newtag", offst, "offset")
    ob, i = _tag_index("newtag", oldtg)
    if n in (K.STARTTAG, K.ENDTAG) or n == integer("newtag", oldtg, "tag"):
        fail("newtag", f"tag {n} is already in object {machine.recording} as the reference "
             "tag or one of its ends", "a new tag number (gentag)")
    j = i + 1
    seen = 0
    while seen < off and j < len(ob.items):
        if ob.items[j][0] == "call":
            seen += 1
        j += 1
    if off < 0 or seen < off:
        fail("newtag", f"offset {off} beyond tag {integer('newtag', oldtg, 'tag')}",
             f"0..{seen} routines follow it")
    ob.items.insert(j, ("tag", n))
    if j <= ob.cursor:
        ob.cursor += 1
    for k, it in enumerate(ob.items):
        if it[0] == "tag" and it[1] == n and k != j:
            _drop_tag(ob, k)
            break


@glcall
def deltag(t):
    """deltag(3G): remove tag ``t`` from the object open for editing (the
    routines stay); STARTTAG and ENDTAG cannot be deleted."""
    if integer("deltag", t, "tag") in (K.STARTTAG, K.ENDTAG):
        fail("deltag", "STARTTAG and ENDTAG cannot be deleted", "a tag made by maketag/newtag")
    _drop_tag(*_tag_index("deltag", t))


def _bbox(call, xmin, ymin, x1, y1, x2, y2):
    """bbox2(3G) at replay: True when the box (x1, y1)-(x2, y2) at z = 0,
    through the current matrices and viewport, lies wholly outside the
    viewport (pruned) or is smaller than xmin by ymin pixels (culled).
    [S] a box with a corner at or behind the eye (w <= 0) is never culled
    by size; it is pruned only when every corner is behind the eye."""
    sx = integer(call, xmin, "xmin")
    sy = integer(call, ymin, "ymin")
    c = [num(call, v, "corner") for v in (x1, y1, x2, y2)]
    return O.bbox_culled(win(call).st, sx, sy, *c)


@glcall
def bbox2(xmin, ymin, x1, y1, x2, y2):
    """bbox2(3G): in an object, skip the rest of the object when the box is
    outside the viewport or smaller than xmin by ymin pixels (culling and
    pruning); in immediate mode there is nothing to skip."""
    return _bbox("bbox2", xmin, ymin, x1, y1, x2, y2)


@glcall
def bbox2i(xmin, ymin, x1, y1, x2, y2):
    """bbox2i(3G): bbox2 with Icoord corners."""
    return _bbox("bbox2i", xmin, ymin, x1, y1, x2, y2)


@glcall
def bbox2s(xmin, ymin, x1, y1, x2, y2):
    """bbox2s(3G): bbox2 with Scoord corners."""
    return _bbox("bbox2s", xmin, ymin, x1, y1, x2, y2)


_BBOX = (bbox2, bbox2i, bbox2s)


@glcall
def callfunc(fctn, nargs, *args):
    """callfunc(3G): call ``fctn`` with ``nargs`` arguments; compiled into an
    object, the call happens each time the object is replayed.  [S] the
    function is called as fctn(arg1, ..., argn) (Python has no varargs
    count to pass); extra arguments beyond nargs are ignored, as C ignores
    them."""
    if not callable(fctn):
        fail("callfunc", f"{fctn!r} is not a function", "pass a Python callable")
    n = integer("callfunc", nargs, "nargs")
    if n < 0 or n > len(args):
        fail("callfunc", f"nargs {n} with {len(args)} arguments given",
             "nargs <= the number of arguments that follow")
    fctn(*args[:n])
