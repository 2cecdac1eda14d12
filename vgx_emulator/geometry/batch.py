"""The immediate-mode vertex stream of one window.

``v*`` calls append a position and a key into a small table of attribute
records (normal, colour, flags, transform); a new record is made only when a
normal, colour or matrix call changed something since the last vertex, so a
vertex costs two list appends.  Display-list replay appends whole numpy
blocks of vertices and records instead (``add_vertices``/``add_records``);
the immediate lists hold what came after the last block, and indices
(``akey`` values, primitive starts, swaps) are global over blocks + lists.
Primitives are (kind, start, count, seq, flags) records.  A batch holds one
class of primitive (filled, line or point) so that drawing order between
classes is kept by flushing on a change.
"""
import numpy as np

from .assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH

FILLED, LINES, POINTS = 0, 1, 2
CLASS_OF = {POLYGON: FILLED, TMESH: FILLED, QSTRIP: FILLED,
            LINE: LINES, CLOSEDLINE: LINES, POINT: POINTS}

# attribute record flags
#: floats per attribute record: normal (3), colour (4), flags, transform, s t r q,
#: material (an index into VertexBatch.mats)
RECORD = 14

LAST_WAS_NORMAL = 1
COLOUR_SINCE_BIND = 2


class Transform:
    """Matrices in force for a run of vertices (float64)."""

    __slots__ = ("modelview", "projection", "clip")

    def __init__(self, modelview, projection):
        self.modelview = modelview
        self.projection = projection
        with np.errstate(all="ignore"):
            self.clip = modelview @ projection


class VertexBatch:
    def __init__(self):
        self.open = None            # (kind, call name) of the primitive being built
        self.reset()

    def reset(self):
        self.pos = []               # flat x, y, z, w floats after the last vertex block
        self.akey = []              # per vertex: global index of its attribute record
        self.vblocks = []           # earlier vertices: [(pos (n, 4), akey (n,))]
        self.vbase = 0              # vertices in vblocks
        self.cap = 1 << 62          # len(akey) at which the open polygon is full
        self.attrs = []             # flat records after the last record block
        self.ablocks = []           # earlier records: [(m, RECORD) float64]
        self.abase = 0              # records in ablocks
        self.xforms = []
        self.mats = []              # (material, backmaterial, lmcolor overrides) in force
        self.prims = []             # (kind, start, count, concave) of immediate primitives
        self.blocks = []            # earlier primitives as (P, 4) int64 arrays, in order
        self.swaps = []             # global vertex indices with a swaptmesh before them
        self.calls = set()          # the calls whose primitives are in the batch (warnings)
        self.klass = None
        self.start = 0              # len(akey) where the open primitive starts
        self.cur = -1
        self.dirty = True           # attributes changed since the last record
        self.xf_dirty = True        # matrices changed since the last Transform

    def __len__(self):
        return len(self.prims) + sum(len(b) for b in self.blocks)

    @property
    def nverts(self):
        """Vertices so far: the global index of the next one."""
        return self.vbase + len(self.akey)

    def add_vertices(self, pos, akey):
        """Append (n, 4) positions whose records are akey (global indices)
        as one block, after the immediate vertices (no primitive is open)."""
        if self.akey:
            self.vblocks.append((np.array(self.pos, np.float64).reshape(-1, 4),
                                 np.array(self.akey, np.int64)))
            self.vbase += len(self.akey)
            self.pos, self.akey = [], []
        self.vblocks.append((pos, akey))
        self.vbase += len(akey)
        self.start = 0

    def add_records(self, recs):
        """Append (m, RECORD) attribute records; returns the global index of the first."""
        if self.attrs:
            a = np.array(self.attrs, np.float64).reshape(-1, RECORD)
            self.ablocks.append(a)
            self.abase += len(a)
            self.attrs = []
        self.ablocks.append(recs)
        self.abase += len(recs)
        self.dirty = True
        return self.abase - len(recs)

    def add_block(self, table, call="callobj"):
        """Append primitives (P, 4) [kind, start, count, concave] as one block
        (display-list replay, NURBS, curveit: ``call`` names it in warnings),
        after the immediate ones already recorded."""
        if self.prims:
            self.blocks.append(np.array(self.prims, np.int64).reshape(-1, 4))
            self.prims = []
        self.blocks.append(table)
        self.calls.add(call)

    def prim_table(self):
        """Every primitive of the batch in submission order, (P, 4) int64."""
        parts = list(self.blocks)
        if self.prims:
            parts.append(np.array(self.prims, np.int64).reshape(-1, 4))
        if not parts:
            return np.zeros((0, 4), np.int64)
        return parts[0] if len(parts) == 1 else np.concatenate(parts)

    def record_attributes(self, st):
        """Make the attribute record for the following vertices."""
        if self.xf_dirty or not self.xforms:
            mv, pr = st.matrices.vertex_matrices()
            self.xforms.append(Transform(mv, pr))
            self.xf_dirty = False
        flags = (LAST_WAS_NORMAL if st.last_was_normal else 0) | \
                (COLOUR_SINCE_BIND if st.colour_since_bind else 0)
        self.attrs += st.normal + st.colour + (flags, len(self.xforms) - 1) + st.texcoord + \
            (self.material_ref(st),)
        self.cur = self.abase + len(self.attrs) // RECORD - 1
        self.dirty = False

    def material_ref(self, st):
        """Index of the bound material state (lmbind MATERIAL/BACKMATERIAL and
        the lmcolor overrides) in ``mats``: binding another material between
        primitives needs no flush, the lighting stage reads it per vertex."""
        m = self.mats[-1] if self.mats else None
        if m is None or m[0] != st.material or m[1] != st.backmaterial or \
                m[2] is not st.mat_override:
            self.mats.append((st.material, st.backmaterial, st.mat_override))
        return len(self.mats) - 1

    def keep_open_primitive(self):
        """After a flush inside bgn/end: keep only the open primitive's vertices
        (and every record: they are few, and the primitive's keys point into them)."""
        first = self.vbase + self.start
        pos = self.pos[4 * self.start:]
        akey = self.akey[self.start:]
        swaps = [s - first for s in self.swaps if s >= first]
        keep = (self.attrs, self.ablocks, self.abase, self.xforms, self.mats, self.klass)
        cap = self.cap - self.start
        calls = {self.open[1]} if self.open else set()
        self.reset()
        self.calls = calls
        self.cap = cap
        self.pos, self.akey, self.swaps = pos, akey, swaps
        self.attrs, self.ablocks, self.abase, self.xforms, self.mats, self.klass = keep
        self.cur = self.abase + len(self.attrs) // RECORD - 1
        self.dirty = True
        self.xf_dirty = True

    def arrays(self):
        """(positions (N, 4), attributes (N, RECORD)) as float64 arrays."""
        pos = [p for p, _ in self.vblocks]
        keys = [k for _, k in self.vblocks]
        if self.akey:
            pos.append(np.array(self.pos, np.float64).reshape(-1, 4))
            keys.append(np.array(self.akey, np.int64))
        recs = list(self.ablocks)
        if self.attrs:
            recs.append(np.array(self.attrs, np.float64).reshape(-1, RECORD))
        if not pos:
            return np.zeros((0, 4)), np.zeros((0, RECORD))
        pos = pos[0] if len(pos) == 1 else np.concatenate(pos)
        keys = keys[0] if len(keys) == 1 else np.concatenate(keys)
        recs = recs[0] if len(recs) == 1 else np.concatenate(recs)
        return pos, recs[keys]
