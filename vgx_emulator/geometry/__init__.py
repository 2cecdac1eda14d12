"""The Geometry Subsystem: one batch of primitives, vectorised.

``process_batch`` reads like the VGX geometry pipeline, top to bottom:

1. transform   object -> eye (ModelView) -> clip (Projection), per vertex run
2. light       the lighting equation on lit vertices (lighting.py)
3. assemble    polygons, meshes, strips, lines, points -> index arrays
4. clip        homogeneous clipping, including w <= 0 (clip.py)
5. divide      perspective divide, viewport and depth-range mapping,
               snapping (viewport.py)

It returns the window-space work for the scan converter.  Non-finite input
never crashes: a primitive touching a non-finite position, normal, colour or
transformed vertex is dropped with a warning naming the calls.
"""
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from ..errors import warn
from ..jit import njit
from . import assemble, clip, depthcue, fog, lighting, lines2d, viewport
from .assemble import CLOSEDLINE, POLYGON, QSTRIP, TMESH
from .batch import FILLED, LAST_WAS_NORMAL, LINES, POINTS
from .stack import MVIEWING


@dataclass
class WindowWork:
    """What the scan converter needs, all in window coordinates."""
    klass: int
    X: np.ndarray = None           # (V,) int64 fixed point
    Y: np.ndarray = None
    Z: np.ndarray = None           # (V,) float64 window z
    C: np.ndarray = None           # (V, 4) front colours 0..255 (index in [:,0])
    CB: np.ndarray = None          # (V, 4) back colours (two-sided lighting)
    tris: np.ndarray = None        # (T, 3)
    prov: np.ndarray = None        # (T,) provoking vertex
    seg0: np.ndarray = None        # (S, 7) x, y, z, r, g, b, a
    seg1: np.ndarray = None
    segflat: np.ndarray = None     # (S, 4)
    points: np.ndarray = None      # (P, 7)
    TC: np.ndarray = None          # (V, 3) s/w, t/w, q/w when texturing
    hollow: bool = False           # polymode(PYM_HOLLOW) outlines: no stencil (machine)
    box: tuple = None              # pixels x0, x1, y0, y1 the triangles may cover (None: any)
    twoside: bool = False
    dropped: int = 0
    extra: dict = field(default_factory=dict)

    def constant_colour(self):
        """True when every vertex a triangle uses has the same front and back
        colour: Gouraud shading then draws what FLAT draws."""
        if self.tris is None or len(self.tris) == 0 or self.C is None:
            return False
        return _same_rows(self.C, self.tris) and \
            (self.CB is self.C or _same_rows(self.CB, self.tris))


@njit
def _same_rows(C, tris):
    """Whether every row of C that the triangles use equals the first one
    (a loop that stops at the first difference)."""
    first = C[tris[0, 0]]
    for i in range(tris.shape[0]):
        for k in range(3):
            row = C[tris[i, k]]
            for j in range(C.shape[1]):
                if row[j] != first[j]:
                    return False
    return True


def lighting_active(st, defs):
    """Lighting is computed only while MATERIAL != 0 and LMODEL != 0, in
    MVIEWING (lmbind(3G), docs/semantics.md §9)."""
    return (st.material != 0 and st.lmodel != 0 and st.matrices.mode == MVIEWING
            and st.material in defs[lighting.DEFMATERIAL]
            and st.lmodel in defs[lighting.DEFLMODEL])


#: rows per matrix product in _transform: an (n, 4) x (4, 4) product of at
#: most 4096 rows is 65,536 multiply-adds, under the size from which
#: OpenBLAS hands a product to its threads (waking them on a busy 2-core
#: machine cost up to 10 ms a batch); one BLAS call per chunk is still
#: 8-10x faster than einsum, which does not use BLAS
_PRODUCT_ROWS = 4096
#: at most this many runs of one transform are multiplied run by run;
#: more (a matrix change every few vertices) go through one einsum
_MAX_RUNS = 64


def _product(pos, m, out):
    """out = pos @ m, chunked (_PRODUCT_ROWS)."""
    for s in range(0, len(pos), _PRODUCT_ROWS):
        np.matmul(pos[s:s + _PRODUCT_ROWS], m, out=out[s:s + _PRODUCT_ROWS])


def _transform(pos, attrs, xforms, xf=None):
    """Eye and clip coordinates of every vertex under its run's matrices
    (row vectors times the modelview and modelview x projection); ``xf``
    the transform column of ``attrs`` as int64, when the caller has it."""
    if xf is None:
        xf = attrs[:, 8].astype(np.int64)
    eye, clp = np.empty((len(pos), 4)), np.empty((len(pos), 4))
    if not len(pos):
        return eye, clp, xf
    cut = np.flatnonzero(xf[1:] != xf[:-1]) + 1
    if len(cut) >= _MAX_RUNS:
        mv = np.stack([t.modelview for t in xforms])
        cm = np.stack([t.clip for t in xforms])
        return np.einsum("ni,nij->nj", pos, mv[xf]), np.einsum("ni,nij->nj", pos, cm[xf]), xf
    bounds = [0] + cut.tolist() + [len(pos)]
    for s, e in zip(bounds[:-1], bounds[1:]):
        t = xforms[xf[s]]
        _product(pos[s:e], t.modelview, eye[s:e])
        _product(pos[s:e], t.clip, clp[s:e])
    return eye, clp, xf


def _materials(st, defs, mats):
    """Front and back material dicts of each (material, backmaterial,
    lmcolor overrides, lmcolor mode) state the batch's vertices refer to."""
    mdefs = defs[lighting.DEFMATERIAL]
    front, back = [], []
    for m, bm, override, _ in mats:
        mat = mdefs.get(m) or mdefs[st.material]
        if override:
            mat = dict(mat)
            mat.update(override)
        front.append(mat)
        back.append(mdefs.get(bm, mat) if bm else mat)
    return front, back


def _light(st, defs, eye4, attrs, xf, xforms, mats):
    """Front and back colours of every vertex (docs/semantics.md §9).  Each vertex is
    lit with the material and lmcolor mode in force when it was sent
    (attribute column 13: its entry in ``mats``).  Under LMC_COLOR a vertex
    whose last call was a colour, not a normal, takes that colour unlit."""
    if not lighting_active(st, defs):
        return attrs[:, 3:7].copy(), None
    modes = np.array([m[3] for m in mats] or [st.lmcolor], np.int64)
    colour_mode = modes == lighting.LMC_COLOR
    lit = None                              # (None: every vertex is lit)
    if colour_mode.any():
        after_normal = (attrs[:, 7].astype(np.int64) & LAST_WAS_NORMAL) != 0
        lit = after_normal if colour_mode.all() else \
            ~colour_mode[attrs[:, 13].astype(np.int64)] | after_normal
        if lit.all():                       # (n3f before every vertex, the common case)
            lit = None
    # (colours the RGB pass writes for every vertex need no copy first)
    col = np.empty((len(attrs), 4)) if lit is None and st.rgb else attrs[:, 3:7].copy()
    if lit is None:
        idx = np.arange(len(col))
    else:
        idx = np.nonzero(lit)[0]
        if not len(idx):
            return col, None
    nm = [lighting.normal_matrix(t.modelview) for t in xforms]
    front, back_mats = _materials(st, defs, mats)
    model = defs[lighting.DEFLMODEL][st.lmodel]
    ldefs = defs[lighting.DEFLIGHT]
    lights = [(ldefs[b.index] if b.index in ldefs else lighting.defaults(lighting.DEFLIGHT), b)
              for _, b in sorted(st.lights.items())]
    if not st.rgb:
        mid = attrs[idx, 13].astype(np.int64) if len(front) > 1 else None
        mats_n = np.stack([m for m, _ in nm])
        ortho = np.array([o for _, o in nm])
        n_eye = np.einsum("ni,nij->nj", attrs[idx, 0:3], mats_n[xf[idx]])
        renorm = (st.nmode == 1) | ~ortho[xf[idx]]
        ln = np.sqrt((n_eye * n_eye).sum(axis=1, keepdims=True))
        safe = np.divide(n_eye, ln, out=np.zeros_like(n_eye), where=ln > 0)
        n_eye = np.where(renorm[:, None], safe, n_eye)
        w = eye4[idx, 3:4]
        eye = np.divide(eye4[idx, :3], w, out=np.zeros((len(idx), 3)), where=w != 0)
        col[idx] = lighting.shade_index(eye, n_eye, front, lights, model, mid)
        return col, None
    geom = (idx, eye4, attrs, np.ascontiguousarray(np.stack([m for m, _ in nm])),
            np.array([st.nmode == 1 or not o for _, o in nm]))
    lighting.shade_rgb(geom, front, lights, model, col, modes)
    if model[lighting.TWOSIDE][0] == 0.0:
        return col, None
    back = np.empty((len(attrs), 4)) if lit is None else attrs[:, 3:7].copy()
    lighting.shade_rgb(geom, back_mats, lights, model, back, modes, sign=-1.0)
    return col, back


def texture_coordinates(st, pos, eye4, attrs, xf, xforms):
    """(N, 3) texture coordinates s, t, q: t*() values, texgen replacements,
    the texture matrix (docs/semantics.md §16).  The division by q is made
    per pixel, as the division by w is: the rasterizer interpolates s/w,
    t/w and q/w, so a projected texture (q varying over a polygon) lands
    where the projection puts it.  A q of 0 counts as 1."""
    tc = attrs[:, 9:13].copy()
    for coord, (mode, plane, enabled) in st.texgen.items():
        if not enabled:
            continue
        if mode == 3:                                   # TG_LINEAR: object coordinates
            tc[:, coord] = pos @ plane
        elif mode == 2:                                 # TG_CONTOUR: eye coordinates
            tc[:, coord] = eye4 @ plane
        elif mode == 4 and coord in (0, 1):             # TG_SPHEREMAP
            nm = [lighting.normal_matrix(t.modelview)[0] for t in xforms]
            n = np.einsum("ni,nij->nj", attrs[:, 0:3], np.stack(nm)[xf])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
            u = eye4[:, :3] / np.maximum(np.linalg.norm(eye4[:, :3], axis=1, keepdims=True),
                                         1e-30)
            r = u - 2.0 * n * (n * u).sum(axis=1, keepdims=True)
            m = 2.0 * np.sqrt(r[:, 0] ** 2 + r[:, 1] ** 2 + (r[:, 2] + 1.0) ** 2)
            m = np.maximum(m, 1e-30)
            tc[:, coord] = r[:, coord] / m + 0.5
    tc = tc @ st.matrices.texture.astype(np.float64)
    tc[:, 3] = np.where(tc[:, 3] != 0, tc[:, 3], 1.0)
    return tc[:, (0, 1, 3)]


class AssemblyCache:
    """Assembled triangles of the last ``size`` primitive tables (see
    :meth:`triangles`), and the vertex arrays of the last batches made of
    replayed blocks (:meth:`vertices`).  It holds program state (what the
    program drew), so the machine owns one and a reset() drops it with the
    rest."""

    #: vertices keeps batches of at most this many bytes of arrays in all
    VERTEX_BYTES = 64 << 20

    def __init__(self, size=64):
        self.size = size
        self.entries = OrderedDict()
        self.vertex_entries = OrderedDict()
        self.vertex_bytes = 0

    def vertices(self, batch):
        """(pos (N, 4), attrs (N, RECORD), bad (N,) bool: a non-finite
        position or attribute, xf (N,) int64: each vertex's transform) of
        the batch (input_vertices).  A batch of replayed blocks
        only (display lists: the same run arrays, and the same records in
        the same state, frame after frame) is looked up by the identity of
        its blocks, so that a scene redrawn every pass is concatenated and
        checked once; the arrays are read, never written, downstream.
        Immediate-mode vertices, and blocks made anew at each call
        (NURBS, array calls), are converted anew."""
        blocks = batch.vblocks
        if batch.pos or not blocks or not batch.kept:
            return input_vertices(batch)
        arrays = [a for block in blocks for a in block]
        key = tuple(map(id, arrays))
        hit = self.vertex_entries.get(key)
        if hit is not None:
            # (the entry holds its arrays: their ids are theirs while it lives)
            self.vertex_entries.move_to_end(key)
            return hit[1]
        out = input_vertices(batch)
        size = sum(a.nbytes for a in out)
        if size <= self.VERTEX_BYTES:
            self.vertex_entries[key] = (arrays, out)
            self.vertex_bytes += size
            while self.vertex_bytes > self.VERTEX_BYTES:
                _, (_, old) = self.vertex_entries.popitem(last=False)
                self.vertex_bytes -= sum(a.nbytes for a in old)
        return out

    def triangles(self, batch, pos, table):
        """Triangles of every filled primitive, in submission order.
        Without concave polygons the result depends only on the primitive
        table and the swaptmesh marks, so it is kept: a display list
        replayed every frame (or every pass) is assembled once, as a
        compiled display list would be."""
        if table[:, 3].any():
            return assemble_triangles(batch, pos, table)
        key = (table.tobytes(), tuple(batch.swaps))
        hit = self.entries.get(key)
        if hit is None:
            hit = self.entries[key] = assemble_triangles(batch, pos, table)
            if len(self.entries) > self.size:
                self.entries.popitem(last=False)
        else:
            self.entries.move_to_end(key)
        return hit


def input_vertices(batch):
    """(pos, attrs, bad, xf) of a batch: its vertex arrays, which vertices
    have a non-finite position or attribute, and each vertex's transform
    (attrs column 8 as int64) (AssemblyCache.vertices)."""
    pos, attrs = batch.arrays()
    bad = np.zeros(len(pos), bool)
    clip.mark_nonfinite(pos, 4, bad)
    clip.mark_nonfinite(attrs, 7, bad)
    return pos, attrs, bad, attrs[:, 8].astype(np.int64)


def assemble_triangles(batch, pos, table):
    """Triangles (T, 3) and provoking vertices of every filled primitive of
    a batch's primitive table, in submission order (polygons as fans,
    concave ones triangulated, qstrips, tmeshes with their swaptmesh marks;
    docs/semantics.md §3)."""
    kinds, starts, counts = table[:, 0], table[:, 1], table[:, 2]
    concave = table[:, 3] != 0
    seq = np.arange(len(table))
    parts, provs, orders = [], [], []
    sel = (kinds == POLYGON) & ~concave
    if sel.any():
        t, p = assemble.polygons(starts[sel], counts[sel])
        parts.append(t)
        provs.append(p)
        orders.append(np.repeat(seq[sel], np.maximum(counts[sel] - 2, 0)))
    sel = kinds == QSTRIP
    if sel.any():
        t, p = assemble.qstrips(starts[sel], counts[sel])
        parts.append(t)
        provs.append(p)
        orders.append(np.repeat(seq[sel], 2 * np.maximum((counts[sel] - 2) // 2, 0)))
    sel = kinds == TMESH
    if sel.any():
        swap = np.zeros(len(pos), bool)
        for s in batch.swaps:
            if s < len(pos):
                swap[s] = ~swap[s]
        t, p, src = assemble.tmeshes(starts[sel], counts[sel], swap)
        parts.append(t)
        provs.append(p)
        orders.append(seq[sel][src])
    for i in np.nonzero((kinds == POLYGON) & concave)[0]:
        s, n = starts[i], counts[i]
        if n < 3:
            continue
        xy = assemble.plane_coordinates(pos[s:s + n, :3] / pos[s:s + n, 3:4])
        loc = np.array(assemble.triangulate_concave(xy), np.int64).reshape(-1, 3)
        parts.append(loc + s)
        provs.append(np.full(len(loc), s + n - 1, np.int64))
        orders.append(np.full(len(loc), i))
    if not parts:
        z = np.zeros((0, 3), np.int64)
        return z, np.zeros(0, np.int64)
    tris = np.concatenate(parts)
    prov = np.concatenate(provs)
    order = np.argsort(np.concatenate(orders), kind="stable")
    return tris[order], prov[order]


def _callers(batch):
    """The calls a dropped-primitive warning names: those whose primitives
    the batch holds (``v*/n3f/c*/t*`` for the bgn/end pairs' vertices)."""
    names = {"v*/n3f/c*/t*" if c.startswith("bgn") else c for c in batch.calls}
    return "/".join(sorted(names)) or "v*/n3f/c*/t*"


def process_batch(batch, st, defs, snap, viewport_rect, texturing=False, shade=True,
                  linestyles=None, assembled=None):
    """Run the geometry pipeline over ``batch``; returns a WindowWork.
    ``shade`` False (the pass uses no colour): vertex colours pass through
    unlit.  ``assembled``: the machine's AssemblyCache (None: assemble
    anew)."""
    pos, attrs, bad, xf = (assembled.vertices(batch) if assembled is not None
                           else input_vertices(batch))
    bad = bad.copy()                    # (the input's marks may be kept: AssemblyCache)
    # (one errstate for the per-vertex stages: non-finite input, normals
    # or matrices are dropped with a VGXWarning below; 2 us a context)
    with np.errstate(all="ignore"):
        eye4, clp, xf = _transform(pos, attrs, batch.xforms, xf)
        tc = texture_coordinates(st, pos, eye4, attrs, xf, batch.xforms) if texturing else None
        col, back = _light(st, defs, eye4, attrs, xf, batch.xforms, batch.mats) if shade else \
            (attrs[:, 3:7].copy(), None)
        if shade and st.rgb and st.fog.on:
            col, back = fog.apply(st.fog, eye4, col, back)  # fogvertex(3G): after lighting
        # clipplane(3G): distances to the enabled user planes (eye space)
        ud = clip.user_distances(eye4, st.user_planes)
    nuser = 0 if ud is None else ud.shape[1]
    for a, k in ((clp, 4), (col, 4)) + (((tc, 3),) if tc is not None else ()):
        clip.mark_nonfinite(a, k, bad)
    gx, gy = viewport.guard_factors(viewport_rect)
    work = WindowWork(klass=batch.klass, twoside=back is not None)
    table = batch.prim_table()
    near_far = st.depth_range
    mode = lines2d.fill_mode(st, batch.klass == FILLED)     # polymode(3G)
    if mode in ("line", "point"):
        work.klass = LINES if mode == "line" else POINTS
        work.hollow = st.polymode == lines2d.PYM_HOLLOW
    if mode == "fill":
        tris, prov = (assembled.triangles(batch, pos, table) if assembled is not None
                      else assemble_triangles(batch, pos, table))
        codes = clip.outcodes(clp, gx, gy, ud)
        fate = clip.classify(tris, prov, bad, codes)
        work.dropped = int(np.count_nonzero(fate == clip.DROPPED))
        inside = fate == clip.INSIDE
        cross = np.nonzero(fate == clip.CROSSING)[0]
        # (every triangle inside, the common case: the assembled arrays
        # themselves, which nothing after assembly writes)
        work.tris, work.prov = (tris, prov) if inside.all() else (tris[inside], prov[inside])
        extra = ([back] if back is not None else []) + ([tc] if tc is not None else [])
        if len(cross):
            verts = np.concatenate([clp, col] + extra + ([ud] if nuser else []), axis=1)
            newv, nt, npv, src = clip.clip_triangles(verts, tris[cross], prov[cross], codes,
                                                     gx, gy, nuser)
            verts = np.concatenate((verts, newv))
            # pieces keep the place of their source
            order = np.argsort(np.concatenate((np.nonzero(inside)[0], cross[src])),
                               kind="stable")
            work.tris = np.concatenate((work.tris, nt))[order]
            work.prov = np.concatenate((work.prov, npv))[order]
            clp = np.ascontiguousarray(verts[:, :4])
            col = np.ascontiguousarray(verts[:, 4:8])
            k = 8
            if back is not None:
                back = np.ascontiguousarray(verts[:, 8:12])
                k = 12
            if tc is not None:
                tc = verts[:, k:k + 3]
        # only vertices that a kept triangle uses are converted: an original
        # vertex replaced by clipping may lie at w <= 0 or far outside the band
        work.X, work.Y, work.Z, ok, lost, work.box = viewport.window_fixed(
            clp, work.tris, viewport_rect, near_far, snap)
        if lost.any():
            # a kept triangle with a vertex the divide cannot place: the clip
            # vertex (0, 0, 0, 0) (v4f of zeros, a vertex at the light of a
            # planar shadow matrix) gives 0/0; drop it rather than draw it
            # to window (0, 0) or overflow the fixed point
            work.dropped += int(lost.sum())
            work.tris, work.prov = work.tris[~lost], work.prov[~lost]
        work.C = col
        work.CB = back if back is not None else col
        if tc is not None:
            w = np.where(ok & (clp[:, 3] != 0), clp[:, 3], 1.0)
            work.TC = np.ascontiguousarray(tc / w[:, None])     # s/w, t/w, q/w
    elif work.klass == LINES:
        # segments (or polygon outlines), clipping, then linestyle and width
        work.seg0, work.seg1, work.segflat, work.dropped = lines2d.line_work(
            batch, st, table, pos, clp, col, bad, gx, gy, ud, viewport_rect, near_far,
            snap, mode == "line", snap, linestyles)
    else:
        idx = assemble._ranges(table[:, 1], table[:, 2])[0]
        drop = bad[idx]
        work.dropped = int(drop.sum())
        idx = idx[~drop]
        codes = clip.outcodes(clp[idx], gx, gy, ud[idx] if nuser else None)
        idx = idx[codes == 0]
        rows = _window_rows(np.concatenate((clp[idx], col[idx]), axis=1), viewport_rect,
                            near_far, snap)
        ok = viewport.placed(rows)
        if not ok.all():                # the divide cannot place it (viewport.placed)
            work.dropped += int((~ok).sum())
            rows = rows[ok]
        work.points = lines2d.grow_points(rows, lines2d.used_point_size(st.pntsize))
    if shade and st.depthcue:
        depthcue.apply(work, st)        # depthcue(3G): colour from window z
    lines2d.smooth(work, st, snap, mode == "line")   # linesmooth/pntsmooth(3G) coverage
    if work.dropped:
        unit = {FILLED: "triangle(s)", LINES: "line segment(s)"}.get(work.klass, "point(s)")
        warn(_callers(batch), f"{work.dropped} {unit} with a non-finite vertex, "
             "normal, colour, texture coordinate or transformed position (or one the "
             f"perspective divide cannot place) dropped; first: "
             f"{_offending(pos, attrs, clp, col, bad)}")
    return work


def _offending(pos, attrs, clp, col, bad):
    """The first offending value of a batch, for its warning: the first
    vertex with a non-finite position, normal, colour or transformed value."""
    idx = np.flatnonzero(bad)
    if not len(idx):
        return "a vertex the perspective divide cannot place (clip w = 0)"
    i = idx[0]
    for what, row in (("vertex", pos[i]), ("normal", attrs[i, 0:3]),
                      ("colour", attrs[i, 3:7]), ("transformed vertex", clp[i]),
                      ("lit colour", col[i])):
        if not np.all(np.isfinite(row)):
            return f"{what} ({', '.join(f'{float(v):g}' for v in row)})"
    return "texture coordinate"


def _window_rows(rows, vp, near_far, snap):
    """Clip-space rows (x, y, z, w, r, g, b, a) -> window rows (x, y, z, r, g, b, a)."""
    out = np.empty((len(rows), 7))
    if len(rows):
        out[:, 0], out[:, 1], out[:, 2] = viewport.to_window(rows[:, :4], vp, near_far, snap)
        out[:, 3:7] = rows[:, 4:8]
    return out
