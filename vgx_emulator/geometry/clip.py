"""Homogeneous clipping of triangles, segments and points.

A vertex (x, y, z, w) in clip space is inside when every plane distance is
>= 0 (docs/semantics.md §2, "geometry behind the eye never wraps"):

=====  ==============  ======================================
plane  distance        why
=====  ==============  ======================================
0, 1   g_x w +- x      guard band (config.GUARD_BAND_PIXELS)
2, 3   g_y w +- y      guard band
4      w + z           near plane
5      w - z           far plane
6      w - eps         w > 0: nothing behind the eye survives
7..12  u_k             user clip planes (clipplane(3G)), see below
=====  ==============  ======================================

User clip planes: the distance of a vertex to enabled plane k is the dot
product of its eye coordinates with the eye-space plane (clipplane(3G));
it is linear in the vertex, so it is carried as an extra column ``u_k`` of
the clipped vertex rows, interpolated like every attribute, and the cut is
made where it reaches 0 exactly as for the frustum planes.

x and y are clipped only against the guard band (g >= 1); the rasterizer's
scissor trims the rest exactly, so most triangles are never cut.  Vertices
made by clipping are computed from the inside vertex towards the outside one,
so an edge shared by two triangles is cut at bit-identical points (the mesh
stays watertight after clipping).
"""
import numpy as np

from ..jit import njit

NPLANES = 7
W_EPSILON = 1e-30


#: user clip planes (clipplane(3G): GD_CLIPPLANES)
MAX_USER_PLANES = 6


def distances(v, gx, gy, user=None):
    """(N, 7 + K) plane distances of clip-space vertices (N, 4); ``user``
    (N, K) are the vertices' distances to the K enabled user planes."""
    x, y, z, w = v[:, 0], v[:, 1], v[:, 2], v[:, 3]
    d = np.stack((gx * w + x, gx * w - x, gy * w + y, gy * w - y,
                  w + z, w - z, w - W_EPSILON), axis=1)
    return d if user is None or user.shape[1] == 0 else np.concatenate((d, user), axis=1)


def user_distances(eye4, planes):
    """(N, K) distances of eye-space vertices (N, 4) to eye-space planes (K, 4),
    or None without planes."""
    if planes is None or len(planes) == 0:
        return None
    return np.ascontiguousarray(np.einsum("ni,ji->nj", eye4, np.asarray(planes, np.float64)))


def outcodes(v, gx, gy, user=None):
    """(N,) int64: bit p set when the vertex (row of v (N, 4)) is outside
    plane p; non-finite -> all bits.  The distances are those of
    ``distances``; bit 7 + k is user plane k (``user`` (N, K)).  (Arrays are
    made outside the kernels of this module: with an empty cache numba's
    np.zeros costs its own compile.)"""
    codes = np.empty(len(v), np.int64)
    _outcodes(v, gx, gy, codes)
    if user is not None and user.shape[1]:
        k = user.shape[1]
        with np.errstate(invalid="ignore"):
            out = ~(user >= 0)                  # NaN counts as outside
        codes |= (out.astype(np.int64) << (NPLANES + np.arange(k))).sum(axis=1)
        bad = ~np.isfinite(user).all(axis=1)
        codes[bad] = (1 << (NPLANES + k)) - 1
    return codes


@njit(error_model="numpy")
def _outcodes(v, gx, gy, codes):
    for i in range(v.shape[0]):
        x = v[i, 0]
        y = v[i, 1]
        z = v[i, 2]
        w = v[i, 3]
        if not (np.isfinite(x) and np.isfinite(y) and np.isfinite(z) and np.isfinite(w)):
            codes[i] = (1 << NPLANES) - 1
            continue
        c = 0
        for p in range(NPLANES):
            if _dist(v[i], p, gx, gy, 0) < 0:
                c |= 1 << p
        codes[i] = c


@njit
def mark_nonfinite(a, ncols, bad):
    """bad[i] |= a non-finite value among the first ``ncols`` columns of row i."""
    for i in range(a.shape[0]):
        for k in range(ncols):
            if not np.isfinite(a[i, k]):
                bad[i] = True
                break


#: classify: what becomes of each assembled triangle
DROPPED, INSIDE, OUTSIDE, CROSSING = 0, 1, 2, 3


def classify(tris, prov, bad, codes):
    """(T,) int8 per triangle: DROPPED (a vertex or its provoking vertex is
    non-finite), OUTSIDE (every vertex outside one plane), INSIDE (no vertex
    outside any plane) or CROSSING (clip_triangles cuts it)."""
    out = np.empty(len(tris), np.int8)
    _classify(tris, prov, bad, codes, out)
    return out


@njit
def _classify(tris, prov, bad, codes, out):
    for i in range(tris.shape[0]):
        a = tris[i, 0]
        b = tris[i, 1]
        c = tris[i, 2]
        if bad[a] or bad[b] or bad[c] or bad[prov[i]]:
            out[i] = DROPPED
        elif (codes[a] | codes[b] | codes[c]) == 0:
            out[i] = INSIDE
        elif (codes[a] & codes[b] & codes[c]) != 0:
            out[i] = OUTSIDE
        else:
            out[i] = CROSSING


@njit
def _dist(v, p, gx, gy, ucol):
    if p >= NPLANES:
        return v[ucol + p - NPLANES]       # a user plane: its distance column
    x = v[0]
    y = v[1]
    z = v[2]
    w = v[3]
    if p == 0:
        return gx * w + x
    if p == 1:
        return gx * w - x
    if p == 2:
        return gy * w + y
    if p == 3:
        return gy * w - y
    if p == 4:
        return w + z
    if p == 5:
        return w - z
    return w - W_EPSILON


@njit
def clip_triangles(verts, tris, prov, codes, gx, gy, nuser):
    """Sutherland-Hodgman against the planes each triangle crosses.

    verts: (N, C) rows = clip x, y, z, w then attributes (interpolated
    linearly in clip space); the last ``nuser`` columns are the distances
    to the enabled user planes (planes 7..).  Returns (new_verts (M, C), tris (Q, 3), prov
    (Q,), source (Q,)); new vertex indices start at N; source is the row of
    ``tris`` each piece came from.  The provoking index is kept (the
    original vertex still holds the flat colour).
    """
    t = tris.shape[0]
    c = verts.shape[1]
    nplanes = NPLANES + nuser
    ucol = c - nuser
    # each plane adds at most 2 vertices and 1 side to the convex piece
    newv = np.empty((t * 2 * nplanes, c))
    outt = np.empty((t * (nplanes + 1), 3), np.int64)
    outp = np.empty(t * (nplanes + 1), np.int64)
    outs = np.empty(t * (nplanes + 1), np.int64)
    nv = 0
    nt = 0
    base = verts.shape[0]
    poly = np.empty(3 + nplanes, np.int64)
    tmp = np.empty(3 + nplanes, np.int64)
    for i in range(t):
        a = tris[i, 0]
        b = tris[i, 1]
        d = tris[i, 2]
        cross = codes[a] | codes[b] | codes[d]
        n = 3
        poly[0] = a
        poly[1] = b
        poly[2] = d
        for p in range(nplanes):
            if not (cross >> p) & 1:
                continue
            m = 0
            for k in range(n):
                ia = poly[k]
                ib = poly[(k + 1) % n]
                va = verts[ia] if ia < base else newv[ia - base]
                vb = verts[ib] if ib < base else newv[ib - base]
                da = _dist(va, p, gx, gy, ucol)
                db = _dist(vb, p, gx, gy, ucol)
                if da >= 0:
                    tmp[m] = ia
                    m += 1
                if (da >= 0) != (db >= 0):
                    # cut from the inside vertex towards the outside one
                    if da >= 0:
                        vin, vout, din, dout = va, vb, da, db
                    else:
                        vin, vout, din, dout = vb, va, db, da
                    s = din / (din - dout)
                    for q in range(c):
                        newv[nv, q] = vin[q] + s * (vout[q] - vin[q])
                    tmp[m] = base + nv
                    nv += 1
                    m += 1
            n = m
            for k in range(n):
                poly[k] = tmp[k]
            if n < 3:
                break
        for k in range(1, n - 1):
            outt[nt, 0] = poly[0]
            outt[nt, 1] = poly[k]
            outt[nt, 2] = poly[k + 1]
            outp[nt] = prov[i]
            outs[nt] = i
            nt += 1
    return newv[:nv].copy(), outt[:nt].copy(), outp[:nt].copy(), outs[:nt].copy()


def clip_segments(v, attrs, segs, gx, gy, user=None):
    """Liang-Barsky in homogeneous coordinates for segments (S, 2), against
    the frustum planes and the user planes (``user``: (N, K) distances).

    Returns (p0 (S', 4+K), p1 (S', 4+K), keep index into segs): the clipped
    endpoints with attributes interpolated."""
    a = np.concatenate((v, attrs), axis=1)
    p0 = a[segs[:, 0]]
    p1 = a[segs[:, 1]]
    u0 = user[segs[:, 0]] if user is not None else None
    u1 = user[segs[:, 1]] if user is not None else None
    d0 = distances(p0[:, :4], gx, gy, u0)
    d1 = distances(p1[:, :4], gx, gy, u1)
    with np.errstate(invalid="ignore", divide="ignore"):
        finite = np.isfinite(p0[:, :4]).all(axis=1) & np.isfinite(p1[:, :4]).all(axis=1)
        if u0 is not None:
            finite &= np.isfinite(u0).all(axis=1) & np.isfinite(u1).all(axis=1)
        t0 = np.zeros(len(segs))
        t1 = np.ones(len(segs))
        keep = finite & ~((d0 < 0) & (d1 < 0)).any(axis=1)
        for p in range(d0.shape[1]):
            a0, a1 = d0[:, p], d1[:, p]
            enter = (a0 < 0) & (a1 >= 0)
            leave = (a0 >= 0) & (a1 < 0)
            s = a0 / (a0 - a1)
            t0 = np.where(enter, np.maximum(t0, s), t0)
            t1 = np.where(leave, np.minimum(t1, s), t1)
        keep &= t0 <= t1
    idx = np.nonzero(keep)[0]
    q0, q1 = p0[idx], p1[idx]
    s0, s1 = t0[idx][:, None], t1[idx][:, None]
    return q0 + s0 * (q1 - q0), q0 + s1 * (q1 - q0), idx
