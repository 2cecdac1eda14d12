"""NURBS evaluation and tessellation for irisgl.nurbs (nurbscurve(3G),
nurbssurface(3G), bgntrim(3G)); see docs/nurbs.md.

Everything here works on whole arrays: the B-spline basis is computed for
all sample parameters at once (Cox-de Boor over a dense (samples, knots)
table), surfaces are two matrix products, trim tests are one
(points, edges) crossing table.  The results go into the window's vertex
batch as array blocks (``feed``), so the ordinary pipeline (matrices,
lighting, z-buffer, stencil, patterns, texture) draws them.
"""
import numpy as np

from .assemble import CLOSEDLINE, LINE, POLYGON
from .batch import CLASS_OF, COLOUR_SINCE_BIND, LAST_WAS_NORMAL, RECORD, Transform

#: caps on the segments of one knot span, of one curve, and of one
#: direction of a surface
MAX_PER_SPAN = 256
MAX_CURVE_SAMPLES = 1024
MAX_SAMPLES = 128
#: segments per knot span when the screen size cannot be estimated
#: (a control point behind the eye) and for trimming curves (parameter space)
FALLBACK_PER_SPAN = 8
TRIM_CURVE_PER_SPAN = 32
#: a trimmed surface is sampled at least this finely (pixels), since its
#: cells are kept or dropped whole (docs/nurbs.md)
TRIM_PIXELS = 4.0
TRIM_MAX_SAMPLES = 192
#: at most this many trimming-loop coordinates are added to each direction's
#: samples (straight trims along s or t then fall on cell edges)
TRIM_EXTRA = 128


# -- B-spline basis -----------------------------------------------------------
def domain(knots, order):
    """The parameter range [knots[order-1], knots[n]] of n = len - order points."""
    n = len(knots) - order
    return float(knots[order - 1]), float(knots[n])


def spans(knots, order):
    """Indices j of the non-empty knot spans [knots[j], knots[j+1]) of the domain."""
    n = len(knots) - order
    j = np.arange(order - 1, n)
    return j[knots[j] < knots[j + 1]]


def basis(knots, order, t, deriv=False):
    """The n = len(knots) - order basis functions of the given order at every
    parameter of t: (len(t), n); with ``deriv`` also their derivatives."""
    U = np.asarray(knots, np.float64)
    t = np.asarray(t, np.float64)
    K = len(U)
    n = K - order
    valid = spans(U, order)
    idx = np.clip(np.searchsorted(U[valid], t, side="right") - 1, 0, len(valid) - 1)
    N = np.zeros((len(t), K - 1))
    N[np.arange(len(t)), valid[idx]] = 1.0
    tt = t[:, None]
    prev = N
    with np.errstate(divide="ignore", invalid="ignore"):
        for p in range(2, order + 1):
            j = np.arange(K - p)
            d1 = U[j + p - 1] - U[j]
            d2 = U[j + p] - U[j + 1]
            a = np.where(d1 > 0, (tt - U[j]) / np.where(d1 > 0, d1, 1.0), 0.0)
            b = np.where(d2 > 0, (U[j + p] - tt) / np.where(d2 > 0, d2, 1.0), 0.0)
            if p == order:
                lower = prev
            prev = a * prev[:, :-1] + b * prev[:, 1:]
        if not deriv:
            return prev[:, :n]
        if order == 1:
            return prev[:, :n], np.zeros((len(t), n))
        k = order
        j = np.arange(n)
        d1 = U[j + k - 1] - U[j]
        d2 = U[j + k] - U[j + 1]
        c1 = np.where(d1 > 0, (k - 1) / np.where(d1 > 0, d1, 1.0), 0.0)
        c2 = np.where(d2 > 0, (k - 1) / np.where(d2 > 0, d2, 1.0), 0.0)
        dN = c1 * lower[:, j] - c2 * lower[:, j + 1]
    return prev[:, :n], dN


# -- sampling -----------------------------------------------------------------
def params(knots, order, per_span):
    """Sample parameters: ``per_span[i]`` equal steps over the i-th non-empty
    span (knot values themselves are always samples)."""
    U = np.asarray(knots, np.float64)
    sp = spans(U, order)
    per = np.broadcast_to(np.asarray(per_span, np.int64), (len(sp),))
    parts = [np.linspace(U[j], U[j + 1], int(m) + 1)[:-1] for j, m in zip(sp, per)]
    parts.append(U[sp[-1] + 1:sp[-1] + 2])
    return np.concatenate(parts)


def screen_points(h, clipm, viewport):
    """Control points (..., 4) homogeneous -> window pixels (..., 2), or None
    when one of them is at or behind the eye (or not finite)."""
    with np.errstate(all="ignore"):
        c = h @ clipm
        if not np.all(np.isfinite(c)) or np.any(c[..., 3] <= 0):
            return None
        ndc = c[..., :2] / c[..., 3:4]
    x0, x1, y0, y1 = viewport
    return np.stack(((ndc[..., 0] + 1) * 0.5 * (x1 - x0 + 1),
                     (ndc[..., 1] + 1) * 0.5 * (y1 - y0 + 1)), axis=-1)


def span_steps(knots, order, lengths, tol):
    """Segments per non-empty span from the pixel lengths of the control
    polygon's edges (``lengths[a]`` = |P[a+1] - P[a]|, the maximum over the
    other direction): a span's length bound is the sum over the order-1
    edges of its control points, its segments ceil(bound / tol)."""
    sp = spans(np.asarray(knots, np.float64), order)
    if lengths is None:
        return np.full(len(sp), FALLBACK_PER_SPAN)
    c = np.concatenate(([0.0], np.cumsum(lengths)))
    first = sp - (order - 1)                 # first control point of span j
    bound = c[first + order - 1] - c[first]
    m = np.clip(np.ceil(bound / tol), 1, MAX_PER_SPAN).astype(np.int64)
    return m


def cap(m, limit):
    """Scale the per-span counts down so that they sum to at most limit."""
    total = int(m.sum())
    if total <= limit:
        return m
    return np.maximum(1, (m * limit) // total)


# -- curves and surfaces ---------------------------------------------------------
def homogeneous(ctl, rational):
    """Control points (..., d) -> homogeneous (..., 4)."""
    if rational:
        return ctl
    return np.concatenate((ctl, np.ones(ctl.shape[:-1] + (1,))), axis=-1)


def curve_points(knots, order, ctl, t):
    """Points of a curve at t: (len(t), d) in the control points' coordinates."""
    return basis(knots, order, t) @ ctl


def surface(sk, so, tk, to, ctl, s, t, deriv=False):
    """Surface values at the grid s x t: (len(s), len(t), d); with ``deriv``
    also the partial derivatives along s and along t."""
    ns, nt, d = ctl.shape
    if not deriv:
        bs, bt = basis(sk, so, s), basis(tk, to, t)
        a = (bs @ ctl.reshape(ns, nt * d)).reshape(len(s), nt, d)
        return np.einsum("bj,ajd->abd", bt, a)
    bs, dbs = basis(sk, so, s, True)
    bt, dbt = basis(tk, to, t, True)
    flat = ctl.reshape(ns, nt * d)
    a = (bs @ flat).reshape(len(s), nt, d)
    da = (dbs @ flat).reshape(len(s), nt, d)
    return (np.einsum("bj,ajd->abd", bt, a), np.einsum("bj,ajd->abd", bt, da),
            np.einsum("bj,ajd->abd", dbt, a))


def positions_normals(h, hs, ht):
    """Euclidean points and unit normals dS/ds x dS/dt from homogeneous
    values and derivatives (..., 4)."""
    with np.errstate(all="ignore"):
        w = h[..., 3:4]
        p = h[..., :3] / w
        ps = (hs[..., :3] - p * hs[..., 3:4]) / w
        pt = (ht[..., :3] - p * ht[..., 3:4]) / w
        n = np.cross(ps, pt)
        ln = np.linalg.norm(n, axis=-1, keepdims=True)
        bad = ~(ln[..., 0] > 1e-12 * (1 + np.abs(p).max()))
        if bad.any() and p.shape[0] > 1 and p.shape[1] > 1:
            # a degenerate point (a pole): the normal of the sample grid there
            gs = np.gradient(p, axis=0)
            gt = np.gradient(p, axis=1)
            fd = np.cross(gs, gt)
            n[bad] = fd[bad]
            ln = np.linalg.norm(n, axis=-1, keepdims=True)
        n = np.where(ln > 0, n / np.where(ln > 0, ln, 1.0), np.array([0.0, 0.0, 1.0]))
    return p, n


# -- trimming --------------------------------------------------------------------
def winding(q, loops):
    """Winding number of every point of q (M, 2) about the closed polylines."""
    if not loops:
        return np.zeros(len(q), np.int64)
    a = np.concatenate([lp for lp in loops])
    b = np.concatenate([np.roll(lp, -1, axis=0) for lp in loops])
    out = np.zeros(len(q), np.int64)
    step = max(1, 4_000_000 // max(1, len(a)))
    for i in range(0, len(q), step):
        qs = q[i:i + step]
        qx, qy = qs[:, 0:1], qs[:, 1:2]
        cross = (b[:, 0] - a[:, 0]) * (qy - a[:, 1]) - (qx - a[:, 0]) * (b[:, 1] - a[:, 1])
        up = (a[:, 1] <= qy) & (b[:, 1] > qy) & (cross > 0)
        down = (a[:, 1] > qy) & (b[:, 1] <= qy) & (cross < 0)
        out[i:i + step] = up.sum(axis=1) - down.sum(axis=1)
    return out


def densify(lp, ds, dt):
    """A closed polyline with every edge split into pieces at most ds long
    in s and dt long in t (trimming curves mapped onto a surface)."""
    b = np.roll(lp, -1, axis=0)
    d = np.abs(b - lp)
    k = np.maximum(1, np.ceil(np.maximum(d[:, 0] / ds, d[:, 1] / dt))).astype(np.int64)
    e = np.repeat(np.arange(len(lp)), k)
    f = (np.arange(len(e)) - np.repeat(np.cumsum(k) - k, k)) / np.repeat(k, k)
    return lp[e] + (b[e] - lp[e]) * f[:, None]


def signed_area(lp):
    x, y = lp[:, 0], lp[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def visible(q, loops):
    """bgntrim(3G): the region to the left of every loop.  A point is kept
    when its winding number, plus one for each clockwise loop that no other
    loop encloses (the region left of it runs out to the domain's edge), is
    positive."""
    if not loops:
        return np.ones(len(q), bool)
    extra = 0
    for i, lp in enumerate(loops):
        if signed_area(lp) < 0:
            others = loops[:i] + loops[i + 1:]
            if not others or winding(lp[:1], others)[0] == 0:
                extra += 1
    return winding(q, loops) + extra > 0


# -- feeding the batch -------------------------------------------------------------
def feed(machine, win, kind, pos, prims, normals=None, colours=None, tex=None,
         lit_normals=False):
    """Append vertices pos (N, 4) with per-vertex normals/colours/texture
    coordinates (None: the current ones) and primitives ``prims`` (P, 2)
    [start, count] of one kind to the window's batch, as array blocks."""
    if len(prims) == 0:
        return
    st = win.st
    b = win.batch
    klass = CLASS_OF[kind]
    if len(b) and b.klass != klass:
        machine._flush(win)
    b.klass = klass
    if b.xf_dirty or not b.xforms:
        mv, pr = st.matrices.vertex_matrices()
        b.xforms.append(Transform(mv, pr))
        b.xf_dirty = False
    n = len(pos)
    rec = np.empty((n, RECORD))
    rec[:, 0:3] = st.normal if normals is None else normals
    rec[:, 3:7] = st.colour if colours is None else colours
    last = lit_normals or (normals is None and st.last_was_normal)
    since = st.colour_since_bind or (colours is not None and st.material != 0)
    rec[:, 7] = (LAST_WAS_NORMAL if last else 0) | (COLOUR_SINCE_BIND if since else 0)
    rec[:, 8] = len(b.xforms) - 1
    rec[:, 9:13] = st.texcoord if tex is None else tex
    rec[:, 13] = b.material_ref(st)
    v0 = b.nverts
    b.add_vertices(np.ascontiguousarray(pos, np.float64), rec)
    table = np.zeros((len(prims), 4), np.int64)
    table[:, 0] = kind
    table[:, 1] = np.asarray(prims)[:, 0] + v0
    table[:, 2] = np.asarray(prims)[:, 1]
    b.add_block(table, "endsurface" if kind != LINE else "endcurve/endsurface")
    b.dirty = True


def strip_prims(lengths):
    """[start, count] of consecutive strips of the given lengths."""
    lengths = np.asarray(lengths, np.int64)
    starts = np.concatenate(([0], np.cumsum(lengths)[:-1]))
    return np.stack((starts, lengths), axis=1)


def grid_triangles(ns, nt):
    """Vertex indices (2 (ns-1)(nt-1), 3) of the triangles of an ns x nt
    grid (index i * nt + j), counter-clockwise in the (s, t) plane."""
    i, j = np.meshgrid(np.arange(ns - 1), np.arange(nt - 1), indexing="ij")
    v00 = (i * nt + j).ravel()
    v10 = v00 + nt
    v11 = v10 + 1
    v01 = v00 + 1
    return np.concatenate((np.stack((v00, v10, v11), 1), np.stack((v00, v11, v01), 1)))


__all__ = ["domain", "spans", "basis", "params", "screen_points", "span_steps", "cap",
           "homogeneous", "curve_points", "surface", "positions_normals", "winding",
           "visible", "feed", "strip_prims", "grid_triangles", "POLYGON", "LINE",
           "CLOSEDLINE"]
