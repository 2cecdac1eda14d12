"""Primitive assembly: bgn/end streams -> triangle, segment and point indices.

docs/semantics.md §3.  Everything is vectorised over the batch:

- polygon with n vertices: fan (0, i, i+1); provoking vertex = the polygon's
  last vertex (FLAT shading takes its colour).
- tmesh: two registers and a replace pointer; every vertex after the first two
  draws (R0, R1, new), then replaces the register the pointer selects and the
  pointer toggles; ``swaptmesh`` toggles it without a vertex.  Provoking
  vertex = the new one.
- qstrip: quad k is the polygon (2k, 2k+1, 2k+3, 2k+2); provoking 2k+2.
- line / closedline: segments (i, i+1) [+ (n-1, 0)]; provoking = segment end.
- point: each vertex.
"""
import numpy as np

from ..jit import njit

POLYGON, TMESH, QSTRIP, LINE, CLOSEDLINE, POINT = range(6)


def _ranges(starts, counts):
    """Concatenated aranges: for each (s, c), s + 0..c-1 (vectorised)."""
    counts = np.asarray(counts, np.int64)
    total = int(counts.sum())
    if total == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    group = np.repeat(np.arange(len(counts)), counts)
    first = np.cumsum(counts) - counts
    offs = np.arange(total) - first[group]
    return np.asarray(starts, np.int64)[group] + offs, group


def polygons(starts, counts):
    """Fan triangulation of convex polygons; returns (tris (T, 3), provoking (T,))."""
    starts = np.asarray(starts, np.int64)
    counts = np.asarray(counts, np.int64)
    ntri = np.maximum(counts - 2, 0)
    first, group = _ranges(np.zeros(len(starts), np.int64), ntri)
    s = starts[group]
    tris = np.stack((s, s + first + 1, s + first + 2), axis=1)
    prov = s + counts[group] - 1
    return tris, prov


def qstrips(starts, counts):
    starts = np.asarray(starts, np.int64)
    nq = np.maximum((np.asarray(counts, np.int64) - 2) // 2, 0)
    k, group = _ranges(np.zeros(len(starts), np.int64), nq)
    b = starts[group] + 2 * k
    t1 = np.stack((b, b + 1, b + 3), axis=1)
    t2 = np.stack((b, b + 3, b + 2), axis=1)
    tris = np.empty((2 * len(b), 3), np.int64)
    tris[0::2] = t1
    tris[1::2] = t2
    prov = np.repeat(b + 2, 2)
    return tris, prov


@njit
def _tmesh_kernel(starts, counts, swap_before):
    total = 0
    for i in range(starts.shape[0]):
        if counts[i] > 2:
            total += counts[i] - 2
    tris = np.empty((total, 3), np.int64)
    src = np.empty(total, np.int64)
    k = 0
    for i in range(starts.shape[0]):
        r0 = -1
        r1 = -1
        ptr = 0
        for j in range(counts[i]):
            v = starts[i] + j
            if swap_before[v]:
                ptr = 1 - ptr
            if r0 >= 0 and r1 >= 0:
                tris[k, 0] = r0
                tris[k, 1] = r1
                tris[k, 2] = v
                src[k] = i
                k += 1
            if ptr == 0:
                r0 = v
            else:
                r1 = v
            ptr = 1 - ptr
    return tris[:k], src[:k]


def tmeshes(starts, counts, swap_before):
    """Triangles of triangle meshes; ``swap_before[v]`` counts (mod 2) the
    swaptmesh calls issued just before vertex v.  Returns (tris, provoking,
    source mesh of each triangle): a swap can leave a register empty, so a
    mesh may give fewer than n - 2 triangles."""
    tris, src = _tmesh_kernel(np.asarray(starts, np.int64), np.asarray(counts, np.int64),
                              np.asarray(swap_before, np.bool_))
    return tris, tris[:, 2].copy(), src


def polylines(starts, counts, closed):
    """Segments of open/closed polylines; returns (segs (S, 2), provoking (S,))."""
    starts = np.asarray(starts, np.int64)
    counts = np.asarray(counts, np.int64)
    closed = np.asarray(closed, bool)
    nseg = np.where(counts >= 2, counts - 1 + (closed & (counts >= 3)), 0)
    k, group = _ranges(np.zeros(len(starts), np.int64), nseg)
    s = starts[group]
    a = s + k
    b = np.where(k + 1 < counts[group], a + 1, s)
    segs = np.stack((a, b), axis=1)
    return segs, b.copy()


def triangulate_concave(xy):
    """Ear clipping of one simple polygon given as (n, 2) points in its own
    plane; returns local index triples with the polygon's winding.  Used only
    for polygons drawn with concave(TRUE) (not a hot path)."""
    n = len(xy)
    idx = list(range(n))
    area = 0.5 * sum(xy[i, 0] * xy[(i + 1) % n, 1] - xy[(i + 1) % n, 0] * xy[i, 1]
                     for i in range(n))
    sign = 1.0 if area >= 0 else -1.0
    out = []
    guard = 0
    while len(idx) > 3 and guard < 10 * n * n:
        guard += 1
        m = len(idx)
        for k in range(m):
            a, b, c = idx[k - 1], idx[k], idx[(k + 1) % m]
            pa, pb, pc = xy[a], xy[b], xy[c]
            cross = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0])
            if cross * sign <= 0:
                continue
            ok = True
            for o in idx:
                if o in (a, b, c):
                    continue
                p = xy[o]
                d1 = (pb[0] - pa[0]) * (p[1] - pa[1]) - (pb[1] - pa[1]) * (p[0] - pa[0])
                d2 = (pc[0] - pb[0]) * (p[1] - pb[1]) - (pc[1] - pb[1]) * (p[0] - pb[0])
                d3 = (pa[0] - pc[0]) * (p[1] - pc[1]) - (pa[1] - pc[1]) * (p[0] - pc[0])
                if d1 * sign >= 0 and d2 * sign >= 0 and d3 * sign >= 0:
                    ok = False
                    break
            if ok:
                out.append((a, b, c))
                del idx[k]
                break
        else:
            break       # no ear: self-intersecting; draw the rest as a fan
    if len(idx) >= 3:
        out.extend((idx[0], idx[i], idx[i + 1]) for i in range(1, len(idx) - 1))
    return out


def plane_coordinates(p):
    """Project 3-D polygon points onto the plane of their Newell normal."""
    p = np.asarray(p, np.float64)
    q = np.roll(p, -1, axis=0)
    nrm = np.array([((p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2])).sum(),
                    ((p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0])).sum(),
                    ((p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1])).sum()])
    ax = int(np.argmax(np.abs(nrm)))
    keep = [i for i in range(3) if i != ax]
    xy = p[:, keep]
    if nrm[ax] < 0:
        xy = xy[:, ::-1]
    return xy
