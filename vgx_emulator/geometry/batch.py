"""The vertex stream of one window.

Immediate mode leaves two flat Python lists, appended to by one C call each:

* ``pos``: x, y, z, w of every vertex (``v*`` calls extend it by 4 floats);
* ``ev``: attribute events of ``EVW`` numbers ``[at, kind, a, b, c, d]``:
  the value applies from the vertex whose x is ``pos[at]`` on (``at`` is
  ``len(pos)`` when the call came).  ``n3f``, the colour calls and ``t*``
  append their values as given (a colour is clamped, scaled or unpacked
  here, vectorised, not in the call); any other change of what a vertex
  carries (matrices, ``lmbind``, ``lmcolor``, ``drawmode``,
  ``popattributes``) makes a whole attribute record (`record_attributes`)
  and an ``EV_REC`` event naming it.  The window state's current
  attributes are read through `sync`, which takes the newest events.

No Python runs per vertex at the flush: `arrays` converts the lists with
struct (`_packed`, `_events`) and replays the events over the vertices in
one compiled pass (`per_vertex`).  Display-list
replay, NURBS and curveit append whole blocks of positions and records
(`add_vertices`); the immediate lists then continue after them.  Vertex
numbers in primitives and swaps are global over blocks + lists.  A batch
holds one class of primitive (filled, line or point) so that drawing order
between classes is kept by flushing on a change.
"""
import functools
import struct

import numpy as np

from ..errors import fp_quiet, fp_restore
from ..jit import helper, njit
from .assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH

FILLED, LINES, POINTS = 0, 1, 2
CLASS_OF = {POLYGON: FILLED, TMESH: FILLED, QSTRIP: FILLED,
            LINE: LINES, CLOSEDLINE: LINES, POINT: POINTS}

#: the columns of an attribute record (float64): normal, colour (0..255, or
#: index, 0, 0, 0), flags, transform index (into ``xforms``), s t r q, material
#: index (into ``mats``)
R_NORMAL = slice(0, 3)
R_COLOUR = slice(3, 7)
R_FLAGS = 7
R_XFORM = 8
R_STRQ = slice(9, 13)
R_MATERIAL = 13
RECORD = 14

# R_FLAGS bits
LAST_WAS_NORMAL = 1
COLOUR_SINCE_BIND = 2

#: attribute event kinds and width.  Colour events: EV_COLOUR final 0..255
#: RGBA (or an index); EV_UNIT c3f/c4f components 0.0-1.0 (clamped, times
#: 255); EV_BYTE c3i/c3s/c4i/c4s/RGBcolor components 0-255 (clamped);
#: EV_CPACK a 0xAABBGGRR word
EV_REC, EV_NORMAL, EV_TEX, EV_COLOUR, EV_UNIT, EV_BYTE, EV_CPACK = range(7)
COLOUR_KINDS = (EV_COLOUR, EV_UNIT, EV_BYTE, EV_CPACK)
EVW = 6


@helper
def colour_component(kind, k, a, v):
    """Component ``k`` (0..3: R, G, B, A) of a colour event as a 0..255
    float (c3f(3G), cpack(3G) ...): ``v`` the event's k-th value, ``a`` its
    first (the cpack word).  EV_UNIT and EV_BYTE values are clamped; NaN
    and +-inf pass (the flush drops the primitive with a warning).  One
    definition for both users: compiled into per_vertex's pass, and as
    plain Python (``py_func``) in colour_value."""
    if kind == EV_CPACK:
        return float((int(a) >> (8 * k)) & 0xFF)
    v = float(v)
    finite = v - v == 0.0
    if kind == EV_UNIT:
        return (min(max(v, 0.0), 1.0) if finite else v) * 255.0
    if kind == EV_BYTE and finite:
        return min(max(v, 0.0), 255.0)
    return v


def colour_value(kind, a, b, c, d):
    """The 0..255 RGBA floats of one colour event (colour_component)."""
    one = colour_component.py_func
    return tuple(one(kind, k, a, v) for k, v in enumerate((a, b, c, d)))


class Transform:
    """Matrices in force for a run of vertices (float64)."""

    __slots__ = ("modelview", "projection", "clip")

    def __init__(self, modelview, projection):
        self.modelview = modelview
        self.projection = projection
        token = fp_quiet()
        try:
            self.clip = modelview @ projection
        finally:
            fp_restore(token)


def attribute_record(st, xform, material):
    """The RECORD floats of the current attributes of ``st``."""
    flags = (LAST_WAS_NORMAL if st.last_was_normal else 0) | \
            (COLOUR_SINCE_BIND if st.colour_since_bind else 0)
    return st.normal + st.colour + (flags, xform) + st.texcoord + (material,)


def per_vertex(ev, recs, n, mats):
    """The (n, RECORD) attributes of vertices 0..n-1 from the events ``ev``
    (m, EVW) and the records ``recs`` the EV_REC events name: a vertex takes
    its last record, with the normal, colour and texture coordinate of any
    later n3f/colour/t* event; LAST_WAS_NORMAL follows the later of the last
    normal and colour (lmcolor(3G)), COLOUR_SINCE_BIND is set by a colour
    sent while a material is bound.  One compiled pass over the vertices
    and the events in stream order (an event applies from the vertex whose
    x was ``pos[at]`` on).  Also returns the row of the newest normal,
    texture and colour event in ``ev`` ((3,) int64, -1 for none: what
    VertexBatch.sync gives the window state)."""
    out = np.zeros((n, RECORD))         # (events before vertex 0's record read zeros)
    last = np.full(3, -1, np.int64)
    if n:
        first = np.flatnonzero(ev[:, 1] == EV_REC)[:1]
        if not len(first) or ev[first[0], 0] > 0:
            raise AssertionError("a vertex before any attribute record")
    bound = np.array([m[0] != 0 for m in mats] or [False], np.bool_)
    _replay(np.ascontiguousarray(ev), np.ascontiguousarray(recs), bound, out, last)
    return out, last


@njit
def _replay(ev, recs, bound, out, last):
    """per_vertex's pass: the current attributes, updated event by event,
    copied to each vertex (the colour kinds converted by colour_component);
    then the newest event of each group, from the end.  Written with scalar
    loops only: whole-row assignments, np.zeros and np.isfinite made numba
    compile its array helpers too (3.5 s of a cold start against 0.6 s;
    benchmarks/compile_cost.py)."""
    nc = out.shape[1]
    j = 0
    m = ev.shape[0]
    for i in range(out.shape[0]):
        row = out[i]
        if i:                           # (vertex 0 always has a record: per_vertex)
            for k in range(nc):
                row[k] = out[i - 1, k]
        while j < m and ev[j, 0] <= 4 * i:
            kind = int(ev[j, 1])
            if kind == EV_REC:
                src = int(ev[j, 2])
                for k in range(nc):
                    row[k] = recs[src, k]
            elif kind == EV_NORMAL:
                row[0] = ev[j, 2]
                row[1] = ev[j, 3]
                row[2] = ev[j, 4]
                row[R_FLAGS] = (int(row[R_FLAGS]) & COLOUR_SINCE_BIND) | LAST_WAS_NORMAL
            elif kind == EV_TEX:
                for k in range(4):
                    row[9 + k] = ev[j, 2 + k]
            else:
                for k in range(4):
                    row[3 + k] = colour_component(kind, k, ev[j, 2], ev[j, 2 + k])
                since = COLOUR_SINCE_BIND if bound[int(row[R_MATERIAL])] else 0
                row[R_FLAGS] = (int(row[R_FLAGS]) & COLOUR_SINCE_BIND) | since
            j += 1
    found = 0
    j = m - 1
    while j >= 0 and found < 3:
        kind = int(ev[j, 1])
        g = 0 if kind == EV_NORMAL else 1 if kind == EV_TEX else 2 if kind >= EV_COLOUR else -1
        if g >= 0 and last[g] < 0:
            last[g] = j
            found += 1
        j -= 1


#: sync: from this many new events the kinds are searched as one array
#: (a list.index over a kind never sent scans every event, once per kind)
_SEARCH_ARRAY = 64


def _newest(back, kinds):
    """The first position in ``back`` (event kinds, newest first: a list, or
    an array when there are many) holding one of ``kinds``; len(back) when
    none does."""
    if isinstance(back, list):
        hit = len(back)
        for k in kinds:
            try:
                hit = min(hit, back.index(k, 0, hit))
            except ValueError:
                pass
        return hit
    found = (back >= kinds[0]) & (back <= kinds[-1])     # kinds: consecutive numbers
    return int(np.argmax(found)) if found.any() else len(back)


#: _events packs this many events at a time: at and kind as int64, the four
#: values as doubles (struct takes a list of Python numbers to doubles in
#: about half of np.fromiter's time, where both fields are ints)
_EV_CHUNK = 256
_EV_RECORD = np.dtype([("at", "<i8"), ("kind", "<i8"), ("v", "<f8", (4,))])


@functools.lru_cache(maxsize=None)
def _event_packers(k):
    """The struct packers of k events (k <= _EV_CHUNK): at and kind as int64
    and the values as doubles, and all six as doubles.  (A last chunk packs
    only its own events: padding it to a whole chunk cost a one-triangle
    batch 256 events' packing.)"""
    return struct.Struct("<" + "qq4d" * k), struct.Struct("<" + "6d" * k)


#: _packed: the struct code of each array type it makes
_PACK_CODES = {np.float64: "d", np.int64: "q"}


def _packed(values, dtype):
    """A list of Python numbers as a new ``dtype`` (float64 or int64) array:
    one struct pack; np.fromiter where struct refuses a value, which then
    raises as before."""
    n = len(values)
    buf = bytearray(8 * n)
    try:
        struct.pack_into(f"<{n}{_PACK_CODES[dtype]}", buf, 0, *values)
    except (struct.error, OverflowError, TypeError):
        return np.fromiter(values, dtype, n)
    return np.frombuffer(buf, dtype)


def _events(ev):
    """The flat event list as an (m, EVW) float64 array, packed in chunks of
    _EV_CHUNK events; a chunk whose at or kind is not an int (events made
    from an array: machine.py) is packed as doubles throughout."""
    m = len(ev) // EVW
    width = 8 * EVW                     # bytes an event
    buf = bytearray(width * m)
    doubles = []                        # (first, end) events packed as doubles
    try:
        for lo in range(0, m, _EV_CHUNK):
            hi = min(lo + _EV_CHUNK, m)
            ints, floats = _event_packers(hi - lo)
            part = ev[lo * EVW:hi * EVW]
            try:
                ints.pack_into(buf, lo * width, *part)
            except struct.error:
                floats.pack_into(buf, lo * width, *part)
                doubles.append((lo, hi))
    except (struct.error, OverflowError, TypeError):
        return np.fromiter(ev, np.float64, len(ev)).reshape(-1, EVW)
    rec = np.frombuffer(buf, _EV_RECORD, m)
    out = np.empty((m, EVW))
    out[:, 0] = rec["at"]
    out[:, 1] = rec["kind"]
    out[:, 2:] = rec["v"]
    for lo, hi in doubles:
        out[lo:hi] = np.frombuffer(buf, np.float64, EVW * (hi - lo), lo * width).reshape(-1, EVW)
    return out


class VertexBatch:
    """One window's vertex stream (see the module docstring)."""

    __slots__ = ("pos", "extend", "ev", "ev_array", "ev_last", "synced", "attrs", "owner",
                 "open", "vblocks", "vbase", "xforms", "mats", "prims", "blocks", "swaps", "calls", "klass", "start",
                 "dirty", "xf_dirty", "kept")

    def __init__(self):
        self.pos = []               # flat x, y, z, w after the last vertex block
        self.extend = self.pos.extend   # (the v* calls' handle inside bgn/end: VGX.begin)
        self.ev = []                # flat attribute events (EVW numbers) for ``pos``
        self.ev_array = None        # ev as the last flush converted it
        self.ev_last = None         # with it, the newest normal, texture, colour event (sync)
        self.synced = 0             # len(ev) when the window state last took them (sync)
        self.attrs = []             # flat records the EV_REC events name
        self.owner = None           # the WindowState whose current attributes ev updates
        self.open = None            # (kind, call name) of the primitive being built
        self.reset()

    def reset(self):
        # ``pos`` and ``ev`` are emptied in place: irisgl's per-vertex calls
        # hold their bound methods (machine.VGX.rebind)
        self.sync_owner()
        del self.pos[:]
        del self.ev[:]
        del self.attrs[:]
        self.ev_array = None
        self.synced = 0
        self.vblocks = []           # earlier vertices: [(pos (n, 4), records (n, RECORD))]
        self.vbase = 0              # vertices in vblocks
        self.kept = True            # every vblock is kept by a display list (add_vertices)
        self.xforms = []
        self.mats = []              # (material, backmaterial, lmcolor overrides, lmcolor mode)
        self.prims = []             # flat kind, start, count, concave of immediate primitives
        self.blocks = []            # earlier primitives as (P, 4) int64 arrays, in order
        self.swaps = []             # global vertex numbers with a swaptmesh before them
        self.calls = set()          # the calls whose primitives are in the batch (warnings)
        self.klass = None
        self.start = 0              # global number of the open primitive's first vertex
        self.dirty = True           # attributes changed since the last record
        self.xf_dirty = True        # matrices changed since the last Transform

    def __len__(self):
        """Primitives so far (``if batch:`` asks it at every bgn* and flush)."""
        n = len(self.prims) // 4
        return n + sum(map(len, self.blocks)) if self.blocks else n

    @property
    def nverts(self):
        """Vertices so far: the global number of the next one."""
        return self.vbase + (len(self.pos) >> 2)

    # -- appending -----------------------------------------------------------
    def record_attributes(self, st):
        """An EV_REC event: the following vertices carry the attributes of
        ``st`` with the matrices and material in force now."""
        if self.xf_dirty or not self.xforms:
            mv, pr = st.matrices.vertex_matrices()
            self.xforms.append(Transform(mv, pr))
            self.xf_dirty = False
        self.ev += (len(self.pos), EV_REC, len(self.attrs) // RECORD, 0.0, 0.0, 0.0)
        self.attrs += attribute_record(st, len(self.xforms) - 1, self.material_ref(st))
        self.dirty = False

    def record_row(self, st):
        """The current attributes as one (RECORD,) array (for array blocks)."""
        if self.xf_dirty or not self.xforms:
            mv, pr = st.matrices.vertex_matrices()
            self.xforms.append(Transform(mv, pr))
            self.xf_dirty = False
        return np.array(attribute_record(st, len(self.xforms) - 1, self.material_ref(st)))

    def material_ref(self, st):
        """Index of the bound material state (lmbind MATERIAL/BACKMATERIAL,
        the lmcolor overrides and the lmcolor mode) in ``mats``: binding
        another material or changing lmcolor between primitives needs no
        flush, the lighting stage reads them per vertex."""
        m = self.mats[-1] if self.mats else None
        if m is None or m[0] != st.material or m[1] != st.backmaterial or \
                m[2] is not st.mat_override or m[3] != st.lmcolor:
            self.mats.append((st.material, st.backmaterial, st.mat_override, st.lmcolor))
        return len(self.mats) - 1

    def add_vertices(self, pos, recs, kept=False):
        """Append (n, 4) positions with their (n, RECORD) records as one
        block, after the immediate vertices (no primitive is open).
        ``kept``: arrays a display list keeps and hands again when replayed
        in the same state (geometry.AssemblyCache.vertices)."""
        self._seal()
        self.kept = self.kept and kept
        self.vblocks.append((pos, recs))
        self.vbase += len(pos)
        self.dirty = True

    def add_block(self, table, call="callobj"):
        """Append primitives (P, 4) [kind, start, count, concave] as one block
        (display-list replay, NURBS, curveit: ``call`` names it in warnings),
        after the immediate ones already recorded."""
        if self.prims:
            self.blocks.append(_packed(self.prims, np.int64).reshape(-1, 4))
            self.prims = []
        self.blocks.append(table)
        self.calls.add(call)

    def drop_open_primitive(self):
        """Forget the open primitive's vertices (endpolygon of too many)."""
        first = self.start - self.vbase
        if first < 0:                      # it began before a flush: nothing else is kept
            self.vblocks, self.vbase, first = [], 0, 0
            self.start = 0
        del self.pos[4 * first:]
        # the attribute calls among the dropped vertices still set the
        # current normal, colour and texture coordinate: their events now
        # apply from the next vertex (per_vertex reads ``at`` in order)
        ev, top = self.ev, 4 * first
        j = len(ev) - EVW
        while j >= 0 and ev[j] > top:
            ev[j] = top
            j -= EVW
        self.swaps = [s for s in self.swaps if s < self.start]
        self.dirty = True

    # -- reading -------------------------------------------------------------
    def _tail(self):
        """(positions (n, 4), records (n, RECORD)) of the immediate lists."""
        n = len(self.pos) >> 2
        pos = _packed(self.pos, np.float64).reshape(n, 4)
        ev = self.ev_array = _events(self.ev)
        recs = np.array(self.attrs, np.float64).reshape(-1, RECORD)
        out, self.ev_last = per_vertex(ev, recs, n, self.mats)
        return pos, out

    def sync(self, st):
        """Give ``st`` the newest normal, colour, texture coordinate and
        their flags among the events since the last sync: right after a
        flush converted the events, the newest of each group its replay
        found (``ev_last``); otherwise a C-speed search of the kinds.  Then
        a few Python steps."""
        ev, first = self.ev, self.synced
        self.synced = len(ev)             # before the writes below: they sync too
        last = {}                         # group -> index among the new events
        if self.ev_array is not None and EVW * len(self.ev_array) == len(ev):
            for group, j in zip((EV_NORMAL, EV_TEX, EV_COLOUR), self.ev_last.tolist()):
                if EVW * j >= first:
                    last[group] = j - first // EVW
        else:
            if len(ev) - first < EVW * _SEARCH_ARRAY:
                back = ev[len(ev) - EVW + 1:first:-EVW]       # the kinds, newest first
            else:
                back = np.fromiter(ev[len(ev) - EVW + 1:first:-EVW], np.float64)
            for group, kinds in ((EV_NORMAL, (EV_NORMAL,)), (EV_TEX, (EV_TEX,)),
                                 (EV_COLOUR, COLOUR_KINDS)):
                hit = _newest(back, kinds)
                if hit < len(back):
                    last[group] = len(back) - 1 - hit
        d = st.__dict__
        if EV_NORMAL in last:
            j = first + EVW * last[EV_NORMAL]
            d["_normal"] = (float(ev[j + 2]), float(ev[j + 3]), float(ev[j + 4]))
        if EV_TEX in last:
            j = first + EVW * last[EV_TEX]
            d["_texcoord"] = tuple(float(v) for v in ev[j + 2:j + 6])
        if EV_COLOUR in last:
            j = first + EVW * last[EV_COLOUR]
            d["_colour"] = colour_value(*ev[j + 1:j + 6])
            if st.material:
                d["_colour_since_bind"] = True
        if EV_NORMAL in last or EV_COLOUR in last:
            d["_last_was_normal"] = last.get(EV_NORMAL, -1) > last.get(EV_COLOUR, -1)

    def sync_owner(self):
        """Sync the window state these events belong to, before they go."""
        st = self.owner
        if st is not None and st.events is self and self.synced != len(self.ev):
            self.sync(st)

    def _seal(self):
        """Turn the immediate lists into a vertex block (their events are
        consumed: the next vertices need a new record, ``dirty``)."""
        self.sync_owner()
        if self.pos:
            self.vblocks.append(self._tail())
            self.vbase += len(self.pos) >> 2
            self.kept = False
            del self.pos[:]
        del self.ev[:]
        del self.attrs[:]
        self.ev_array = None
        self.synced = 0
        self.dirty = True

    def keep_open_primitive(self, st):
        """After a flush inside bgn/end: keep only the open primitive's
        vertices, as a block; the next ones continue it with the attributes
        of ``st``."""
        self._seal()
        first = self.start
        pos = np.concatenate([p for p, _ in self.vblocks])[first:] if self.vblocks else None
        recs = np.concatenate([r for _, r in self.vblocks])[first:] if self.vblocks else None
        swaps = [s - first for s in self.swaps if s >= first]
        keep = (self.xforms, self.mats, self.klass, self.open)
        calls = {self.open[1]} if self.open else set()
        self.reset()
        self.xforms, self.mats, self.klass, self.open = keep
        self.calls, self.swaps = calls, swaps
        if pos is not None and len(pos):
            self.vblocks.append((pos, recs))
            self.vbase = len(pos)
            self.kept = False
        self.xf_dirty = True
        self.record_attributes(st)

    def arrays(self):
        """(positions (N, 4), attributes (N, RECORD)) as float64 arrays."""
        parts = list(self.vblocks)
        if self.pos:
            parts.append(self._tail())
        if not parts:
            return np.zeros((0, 4)), np.zeros((0, RECORD))
        if len(parts) == 1:
            return parts[0]
        return (np.concatenate([p for p, _ in parts]), np.concatenate([r for _, r in parts]))

    def prim_table(self):
        """Every primitive of the batch in submission order, (P, 4) int64."""
        parts = list(self.blocks)
        if self.prims:
            parts.append(_packed(self.prims, np.int64).reshape(-1, 4))
        if not parts:
            return np.zeros((0, 4), np.int64)
        return parts[0] if len(parts) == 1 else np.concatenate(parts)
