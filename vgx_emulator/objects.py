"""Display lists (objects): recording, compiling, replay (docs/semantics.md §12).

Between ``makeobj`` and ``closeobj`` the IRIS GL calls are recorded, not
executed (queries and immediate-only calls still execute, see
``irisgl.objects.IMMEDIATE``).  An object is a list of items:

- ``("call", name, fn, args)``: a recorded call, replayed through the same
  validated function (so errors and lenient mode behave as in immediate mode);
- ``("tag", t)``: a ``maketag`` marker for ``objreplace``/``objinsert``/
  ``objdelete``.

When an object is closed its items are compiled once: every maximal run of
geometry calls (bgn*/end*, v*, n3f, t*, c*, cpack, RGBcolor, color, swaptmesh) of
one primitive class becomes a :class:`GeometryRun` holding its positions,
attribute states and primitive table as arrays.  ``callobj`` appends a run to
the window's batch with list/array operations only, so replay costs no
Python work per vertex.  Attributes not set inside a run (the colour or
normal before its first c*/n3f) are taken from the state at ``callobj``
time, as the calls themselves would; after the run the state holds the
run's last colour and normal, as after executing the calls.
A run that cannot be compiled (unbalanced bgn/end, a bad argument) is kept
as plain calls, which raise their GLError when replayed.
"""
from collections import OrderedDict

import numpy as np

from .geometry.assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH
from .geometry.batch import CLASS_OF, COLOUR_SINCE_BIND, LAST_WAS_NORMAL, RECORD, Transform

BGN = {"bgnpolygon": POLYGON, "bgntmesh": TMESH, "bgnqstrip": QSTRIP, "bgnline": LINE,
       "bgnclosedline": CLOSEDLINE, "bgnpoint": POINT}
END = {"end" + k[3:]: v for k, v in BGN.items()}
VERTEX = {f"v{n}{t}": n for n in (2, 3, 4) for t in "sifd"}
COLOUR = {"c3f", "c4f", "c3i", "c4i", "c3s", "c4s", "cpack", "RGBcolor", "color"}
TEXCOORD = {f"t{n}{t}": n for n in (2, 3, 4) for t in "sifd"}
GEOMETRY = set(BGN) | set(END) | set(VERTEX) | set(TEXCOORD) | COLOUR | {"n3f", "swaptmesh"}
MAX_DEPTH = 64      # nesting of callobj during replay


class NotCompilable(Exception):
    pass


#: replay_run keeps the records of this many states per run: an object drawn
#: in every pass of a multipass frame, under another state in each, finds
#: its records again in the next frame (and the batch arrays made of them
#: stay the same arrays: geometry.AssemblyCache.vertices)
MEMO_STATES = 8


class GeometryRun:
    """Compiled geometry of one primitive class, as arrays: replay builds its
    attribute records with a few whole-array operations."""

    __slots__ = ("klass", "pos", "akey", "states", "table", "swaps", "rgb", "final",
                 "nverts", "tmpl", "no_normal", "no_colour", "no_tc", "last", "coloured",
                 "memo")

    def __init__(self, klass, pos, akey, states, table, swaps, rgb, final):
        self.klass = klass
        self.pos = np.array(pos, np.float64).reshape(-1, 4)    # (N, 4) x y z w
        self.akey = akey            # (N,) int64: index into states
        self.states = states        # [(normal|None, colour|None, last|None, coloured, tc|None)]
        self.table = table          # (P, 4) int64 [kind, start, count, concave]
        self.swaps = swaps          # (S,) int64 vertex indices
        self.rgb = rgb              # True: RGB colour calls; False: color(); None: neither
        self.final = final          # (normal|None, colour|None, last|None, tc|None)
        self.nverts = len(akey)
        # records with the values the run sets; what it leaves unset (None)
        # comes from the window state at callobj time
        tmpl = np.zeros((len(states), RECORD))
        for i, (normal, colour, _, _, tc) in enumerate(states):
            tmpl[i, 0:3] = normal or 0.0
            tmpl[i, 3:7] = colour or 0.0
            tmpl[i, 9:13] = tc or 0.0
        self.tmpl = tmpl
        self.no_normal = np.array([st[0] is None for st in states], bool)
        self.no_colour = np.array([st[1] is None for st in states], bool)
        self.no_tc = np.array([st[4] is None for st in states], bool)
        self.last = np.array([-1 if st[2] is None else int(st[2] == "n") for st in states],
                             np.int64)
        self.coloured = np.array([st[3] for st in states], bool)
        self.memo = OrderedDict()   # replay_run: state key -> records, the last MEMO_STATES


def _colour_of(name, args):
    """The RGBA (0..255) a colour call sets, or the index for color()."""
    a = args[0] if len(args) == 1 else args
    if name == "cpack":
        c = int(a) & 0xFFFFFFFF
        return (float(c & 0xFF), float((c >> 8) & 0xFF), float((c >> 16) & 0xFF),
                float((c >> 24) & 0xFF))
    if name == "RGBcolor":
        r, g, b = (min(max(int(v), 0), 255) for v in args)
        return (float(r), float(g), float(b), 255.0)
    if name == "color":
        return (float(int(a) & 0xFFF), 0.0, 0.0, 0.0)
    vals = [float(v) for v in a]
    n = 3 if name[1] == "3" else 4
    if len(vals) != n:
        raise NotCompilable
    if name.endswith("f"):
        vals = [min(max(v, 0.0), 1.0) * 255.0 if -1e300 < v < 1e300 else v for v in vals]
    else:
        vals = [min(max(v, 0.0), 255.0) if -1e300 < v < 1e300 else v for v in vals]
    return tuple(vals) if n == 4 else tuple(vals) + (255.0,)


def compile_run(calls):
    """Compile geometry calls [(name, args)] of one primitive class."""
    normal = colour = last = tc = None
    coloured = False
    states, index = [], {}
    pos, akey, prims, swaps = [], [], [], []
    open_kind, start, klass, rgb = None, 0, None, None
    for name, args in calls:
        if name in VERTEX:
            if open_kind is None:
                raise NotCompilable
            n = VERTEX[name]
            v = [float(x) for x in args[0]]
            if len(v) != n:
                raise NotCompilable
            v = v + [0.0] * (3 - n) + [1.0] if n < 4 else v
            key = (normal, colour, last, coloured, tc)
            k = index.get(key)
            if k is None:
                k = index[key] = len(states)
                states.append(key)
            pos += v
            akey.append(k)
            if open_kind == POLYGON and len(akey) - start > 256:
                raise NotCompilable
        elif name == "n3f":
            v = tuple(float(x) for x in args[0])
            if len(v) != 3:
                raise NotCompilable
            normal, last = v, "n"
        elif name in TEXCOORD:
            n = TEXCOORD[name]
            v = tuple(float(x) for x in args[0])
            if len(v) != n:
                raise NotCompilable
            tc = v + (0.0, 1.0)[n - 2:] if n < 4 else v      # t*(3G): r = 0, q = 1
        elif name in COLOUR:
            mode_rgb = name != "color"
            if rgb is not None and rgb != mode_rgb:
                raise NotCompilable
            rgb = mode_rgb
            colour, last, coloured = _colour_of(name, args), "c", True
        elif name in BGN:
            if open_kind is not None:
                raise NotCompilable
            open_kind = BGN[name]
            if klass is not None and CLASS_OF[open_kind] != klass:
                raise NotCompilable
            klass = CLASS_OF[open_kind]
            start = len(akey)
        elif name in END:
            if open_kind != END[name]:
                raise NotCompilable
            if open_kind == TMESH:
                swaps = [s for s in swaps if s < len(akey)]
            if len(akey) > start:
                prims.append((open_kind, start, len(akey) - start, 0))
            open_kind = None
        elif name == "swaptmesh":
            if open_kind != TMESH:
                raise NotCompilable
            swaps.append(len(akey))
    if open_kind is not None:
        raise NotCompilable
    swaps = [s for s in swaps if s < len(akey)]
    table = np.array(prims, np.int64).reshape(-1, 4)
    return GeometryRun(klass, pos, np.array(akey, np.int64), states, table,
                       np.array(swaps, np.int64), rgb, (normal, colour, last, tc))


def compile_items(items):
    """Items -> replay ops: ("call", fn, args) and ("run", GeometryRun | None, calls).

    Runs are split where the primitive class changes; colour/normal calls
    between primitives stay in the run of the primitives around them."""
    ops = []
    pending = []          # (name, fn, args) of the current geometry run
    klass = None

    def close():
        nonlocal pending, klass
        if pending:
            calls = [(n, a) for n, _, a in pending]
            try:
                run = compile_run(calls) if klass is not None else None
            except (NotCompilable, TypeError, ValueError, OverflowError):
                run = None
            if run is not None:
                ops.append(("run", run, pending))
            else:
                ops.extend(("call", fn, a) for _, fn, a in pending)
        pending = []
        klass = None

    for item in items:
        if item[0] != "call":
            continue
        _, name, fn, args = item
        if name in GEOMETRY:
            if name in BGN:
                k = CLASS_OF[BGN[name]]
                if klass is not None and k != klass:
                    close()
                klass = k
            pending.append((name, fn, args))
        else:
            close()
            ops.append(("call", fn, args))
    close()
    return ops


def replay_run(machine, win, run):
    """Append a compiled run to the window's batch as array blocks (no Python
    work per vertex or per attribute state).  Returns False when the calls
    must be replayed one by one instead (colour mode mismatch, or inside
    bgn/end)."""
    st = win.st
    if run.rgb is not None and run.rgb != st.rgb:
        return False                      # wrong mode: replay the calls instead
    b = win.batch
    if b.open is not None:
        return False
    if len(b) and b.klass != run.klass:
        machine._flush(win)
    b.klass = run.klass
    if b.xf_dirty or not b.xforms:
        mv, pr = st.matrices.vertex_matrices()
        b.xforms.append(Transform(mv, pr))
        b.xf_dirty = False
    # the records depend on the run and on this state only: a replay in the
    # same state (the same object drawn again in a multipass frame) takes the
    # records of the last one (the batch never writes into them)
    xform = len(b.xforms) - 1
    mat = b.material_ref(st)
    key = (st.normal, st.colour, st.texcoord, st.last_was_normal, st.colour_since_bind,
           st.material != 0, xform, mat)
    rec = run.memo.get(key)
    if rec is not None:
        run.memo.move_to_end(key)
    else:
        rec = run.tmpl.copy()
        rec[run.no_normal, 0:3] = st.normal
        rec[run.no_colour, 3:7] = st.colour
        rec[run.no_tc, 9:13] = st.texcoord
        lw = np.where(run.last < 0, st.last_was_normal, run.last == 1)
        since = st.colour_since_bind | (run.coloured & (st.material != 0))
        rec[:, 7] = np.where(lw, LAST_WAS_NORMAL, 0) | np.where(since, COLOUR_SINCE_BIND, 0)
        rec[:, 8] = xform
        rec[:, 13] = mat
        rec = rec[run.akey]               # per vertex
        run.memo[key] = rec
        if len(run.memo) > MEMO_STATES:
            run.memo.popitem(last=False)
    v0 = b.nverts
    b.add_vertices(run.pos, rec, kept=True)
    if len(run.swaps):
        b.swaps += (run.swaps + v0).tolist()
    table = run.table.copy()
    table[:, 1] += v0
    if st.concave:
        table[:, 3] = table[:, 0] == POLYGON
    b.add_block(table)
    # the state the calls would have left
    normal, colour, last, tc = run.final
    if tc is not None:
        st.texcoord = tc
    if normal is not None:
        st.normal = normal
    if colour is not None:
        st.colour = colour
        if st.material:
            st.colour_since_bind = True
    if last is not None:
        st.last_was_normal = last == "n"
    b.dirty = True
    return True


def bbox_culled(st, xmin, ymin, x1, y1, x2, y2):
    """bbox2(3G): whether the box (x1, y1)-(x2, y2), z = 0, through the
    current matrices and the viewport, lies wholly outside the viewport
    (every corner outside one side of the clip volume in x or y, or behind
    the eye) or projects smaller than xmin and than ymin pixels."""
    mv, pr = st.matrices.vertex_matrices()
    corners = np.array([[x1, y1, 0.0, 1.0], [x2, y1, 0.0, 1.0],
                        [x2, y2, 0.0, 1.0], [x1, y2, 0.0, 1.0]])
    with np.errstate(all="ignore"):
        c = corners @ (mv @ pr)
        x, y, w = c[:, 0], c[:, 1], c[:, 3]
        if not np.isfinite(c).all():
            return False
        if (w <= 0).all() or (x > w).all() or (x < -w).all() or (y > w).all() or \
                (y < -w).all():
            return True                   # pruned: outside the viewport
        if (w <= 0).any():
            return False
        l, r, b, t = st.viewport
        sx = np.ptp(x / w) * (r - l + 1) / 2.0
        sy = np.ptp(y / w) * (t - b + 1) / 2.0
    return bool(sx < xmin and sy < ymin)   # culled: smaller than the feature size
