"""Picking and selecting: the hit test that replaces drawing (docs/picking.md).

While a window is in picking (pick(3G)) or selecting (gselect(3G)) mode,
a flush of its batch runs the geometry only: transformation, assembly and
homogeneous clipping against the exact viewing volume (no guard band),
vectorised over the batch, and tells whether any primitive survived.  No
pixel is touched.  In picking mode the volume is the picksize(3G) region
around the cursor: the projection calls issued while picking load their
matrix times a picking matrix that maps that region onto the whole clip
volume (Programming Guide 12.1.1).

Hits follow endpick(3G)/endselect(3G): a hit is recorded only if the name
stack was touched (loadname, pushname, popname) since the last recorded
hit, and the first hit after pick/gselect always is.  Each record is the
stack depth followed by the names, bottom first.  The batch is flushed at
every name-stack call, so every primitive is tested under the names that
were loaded when it was issued.
"""
import numpy as np

from . import geometry
from .errors import warn
from .geometry import assemble, clip
from .geometry.batch import FILLED, LINES

PICK, SELECT = "pick", "select"
NAMESTACKDEPTH = 1025              # gl.h


def pick_matrix(viewport, cx, cy, dx, dy):
    """The clip-space matrix (row vectors, applied after the projection)
    that maps the dx x dy pixel region centred on window pixel (cx, cy)
    onto the whole clip volume.  Window x of NDC x is
    ``left - 0.5 + (x + 1) / 2 * (right - left + 1)`` (geometry/viewport.py),
    so the region's centre is NDC ``2 (cx - left + 0.5) / W - 1`` and its
    half width dx / W."""
    l, r, b, t = viewport
    W, H = float(r - l + 1), float(t - b + 1)
    xc = 2.0 * (cx - l + 0.5) / W - 1.0
    yc = 2.0 * (cy - b + 0.5) / H - 1.0
    sx, sy = W / dx, H / dy
    m = np.eye(4)
    m[0, 0], m[1, 1] = sx, sy
    m[3, 0], m[3, 1] = -xc * sx, -yc * sy
    return m


def batch_hits(batch, st):
    """Whether any primitive of ``batch`` survives clipping to the viewing
    volume (points: the vertex; lines: the width-1 segment; filled
    primitives: the triangles), user clip planes included.  Vertices that
    are not finite drop their primitive, as when drawing."""
    pos, attrs = batch.arrays()
    if not len(pos):
        return False
    with np.errstate(all="ignore"):
        eye4, clp, _ = geometry._transform(pos, attrs, batch.xforms)
        planes = getattr(st, "user_planes", None)
        ud = clip.user_distances(eye4, planes) if hasattr(clip, "user_distances") else None
    nuser = 0 if ud is None else ud.shape[1]
    bad = np.zeros(len(pos), bool)
    clip.mark_nonfinite(pos, 4, bad)
    clip.mark_nonfinite(np.ascontiguousarray(clp), 4, bad)
    if bad.any():
        warn("v*", f"{int(bad.sum())} non-finite vertex position(s) while picking or "
             "selecting: their primitives are dropped (no hit)")
    table = batch.prim_table()
    if not len(table):
        return False
    extra = () if ud is None else (ud,)
    if batch.klass == FILLED:
        tris, prov = geometry.assemble_triangles(batch, pos, table)
        if not len(tris):
            return False
        codes = clip.outcodes(clp, 1.0, 1.0, *extra)
        fate = clip.classify(tris, prov, bad, codes)
        if (fate == clip.INSIDE).any():
            return True
        cross = np.nonzero(fate == clip.CROSSING)[0]
        if not len(cross):
            return False
        verts = np.ascontiguousarray(np.concatenate((clp,) + extra, axis=1))
        args = (nuser,) if hasattr(clip, "user_distances") else ()
        nt = clip.clip_triangles(verts, tris[cross], prov[cross], codes, 1.0, 1.0, *args)[1]
        return len(nt) > 0
    if batch.klass == LINES:
        segs, _ = assemble.polylines(table[:, 1], table[:, 2],
                                     table[:, 0] == assemble.CLOSEDLINE)
        segs = segs[~bad[segs].any(axis=1)]
        if not len(segs):
            return False
        kept = clip.clip_segments(clp, np.zeros((len(clp), 0)), segs, 1.0, 1.0, *extra)[2]
        return len(kept) > 0
    idx = assemble._ranges(table[:, 1], table[:, 2])[0]
    idx = idx[~bad[idx]]
    if not len(idx):
        return False
    codes = clip.outcodes(np.ascontiguousarray(clp[idx]), 1.0, 1.0,
                          *((ud[idx],) if ud is not None else ()))
    return bool((codes == 0).any())


class Session:
    """One pick/gselect ... endpick/endselect: the name stack, the hits and
    (picking) the picking matrix."""

    def __init__(self, mode, win, numnames, buffer, region=None):
        self.mode = mode
        self.win = win
        self.numnames = numnames       # shorts the hit records may fill
        self.buffer = buffer           # the array given to pick/gselect, or None
        self.region = region           # picking: (x0, x1, y0, y1) window coordinates
        self.names = []
        self.pending = True            # the first hit is always recorded
        self.hits = []
        self.used = 0
        self.overflow = False
        self.pick_matrix = None        # picking: clip-space matrix after the projection

    # -- hits ------------------------------------------------------------
    def hit(self):
        """Something intersected the volume: record the name stack if it
        was touched since the last recorded hit.  A record that does not
        fit in numnames ends the recording (the count comes back negative)."""
        if not self.pending:
            return
        self.pending = False
        if self.overflow:
            return
        need = 1 + len(self.names)
        if self.used + need > self.numnames:
            self.overflow = True
            return
        self.hits.append(tuple(self.names))
        self.used += need

    def test_batch(self, batch, st):
        if batch_hits(batch, st):
            self.hit()

    def test_point(self, x, y, z, w):
        """A clip-space point (cmov/cmov2 cause hits, pick(3G)): a hit when
        it lies inside the picking or selecting volume."""
        if w > 0 and abs(x) <= w and abs(y) <= w and abs(z) <= w:
            self.hit()

    def clear_hit(self, rect):
        """clear/czclear in picking or selecting mode draw nothing; a clear
        is a hit when its rectangle (viewport ∩ scrmask) meets the pick
        region (picking) or is not empty (selecting)."""
        if rect is None:
            return
        if self.mode == PICK:
            x0, x1, y0, y1 = self.region
            if rect[0] - 0.5 > x1 or rect[1] + 0.5 < x0 or \
                    rect[2] - 0.5 > y1 or rect[3] + 0.5 < y0:
                return
        self.hit()

    def count(self):
        """endpick/endselect's return value: the records stored, negative
        when some did not fit."""
        return -len(self.hits) if self.overflow else len(self.hits)

    def words(self):
        """The hit records as the C buffer holds them: depth, then names."""
        out = []
        for names in self.hits:
            out.append(len(names))
            out.extend(names)
        return out

    # -- the name stack ---------------------------------------------------
    def initnames(self):
        """initnames(3G): the stack holds one name, 0, the slot loadname
        replaces.  [S] The Programming Guide calls a push before the first
        loadname unpredictable; SGI's own tutorial programs (gouraud,
        curve) do initnames(); pushname(a); pushname(b) and read a and b
        as the second and third names of the hit, which this layout gives.
        Programs that call loadname first see no difference; a hit before
        any loadname records the name 0."""
        self.names = [0]

    def loadname(self, name):
        if self.names:
            self.names[-1] = name
        else:
            self.names.append(name)
        self.pending = True

    def pushname(self, name):
        self.names.append(name)
        self.pending = True

    def popname(self):
        self.names.pop()
        self.pending = True

    # -- the pick matrix ----------------------------------------------------
    def multiplies(self, win):
        """Whether projection calls in win take the pick matrix."""
        return self.mode == PICK and win is self.win

    def load_projection(self, ms, t):
        """A projection call while picking (Programming Guide 12.1.1): the
        product of the projection and the picking matrix is loaded where
        the projection goes (the single stack's top in MSINGLE, Projection
        otherwise).  pick itself changes no matrix, and endpick leaves the
        product in place: programs restate their projection after both."""
        ms.load_projection(np.asarray(t, np.float64) @ self.pick_matrix)
