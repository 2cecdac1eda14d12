"""Curves and patches of the old IRIS GL (docs/semantics.md §17).

Curve segment (curvebasis, curveprecision, crv/rcrv)::

    P(t) = [t^3 t^2 t 1] . Mb . G,  t = 0..1,  G = the 4 control points as rows

drawn as ``n = curveprecision`` straight lines through the points t = k/n.
IRIS GL computes those points by forward differencing (M = E . Mb . G with
the E of curveprecision(3G)); this module evaluates the same cubic directly, which
gives the same points up to float rounding (forward differencing
accumulates error, direct evaluation does not).

Patch (patchbasis, patchcurves, patchprecision, patch/rpatch)::

    P(u, v) = [v^3 v^2 v 1] . Bv . G . Bu^T . [u^3 u^2 u 1]^T

one matrix G per coordinate (rows <-> v, columns <-> u).  Drawn as a web of
curves: ``ucurves`` curves along u at v = k/(ucurves-1) and ``vcurves``
curves along v at u = k/(vcurves-1) (edges included), each curve a line strip
with a segment count that is the smallest multiple of (the other direction's
curve count - 1) not below its precision, so the curves cross at vertices
(docs/semantics.md §17, the [S] reading of patchcurves/patchprecision).

Beyond IRIS GL, :func:`patch_surface` tessellates the same patch into a grid
of points with unit normals (from the u and v derivatives) so that programs
can draw it as a shaded, lit surface that casts and receives shadows.
"""
import numpy as np

BEZIER = np.array([[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]], np.float64)
CARDINAL = np.array([[-.5, 1.5, -1.5, .5], [1, -2.5, 2, -.5], [-.5, 0, .5, 0], [0, 1, 0, 0]],
                    np.float64)
BSPLINE = np.array([[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 0, 3, 0], [1, 4, 1, 0]],
                   np.float64) / 6.0


def powers(t):
    """(len(t), 4) rows [t^3, t^2, t, 1]."""
    t = np.asarray(t, np.float64)
    return np.stack((t ** 3, t ** 2, t, np.ones_like(t)), axis=1)


def curve_points(basis, geom, n):
    """The n+1 points (homogeneous rows as given) of one curve segment."""
    return powers(np.arange(n + 1) / n) @ (np.asarray(basis) @ np.asarray(geom, np.float64))


def curve_segments(basis, geom, n):
    """crvn/rcrvn: a polyline per 4-point window (points i..i+3)."""
    g = np.asarray(geom, np.float64)
    return [curve_points(basis, g[i:i + 4], n) for i in range(len(g) - 3)]


def segment_count(precision, other_curves):
    """Smallest multiple of (other_curves - 1) that is >= precision."""
    m = max(other_curves - 1, 1)
    return max(m, -(-int(precision) // m) * m)


def patch_points(ubasis, vbasis, coords, u, v):
    """P(u, v) for arrays u (U,), v (V,): returns (V, U, k) for k coordinate
    matrices (x, y, z[, w])."""
    pu = powers(u)                       # (U, 4)
    pv = powers(v)                       # (V, 4)
    out = [pv @ vbasis @ np.asarray(g, np.float64) @ ubasis.T @ pu.T for g in coords]
    return np.stack(out, axis=-1)


def patch_curves(ubasis, vbasis, coords, ucurves, vcurves, uprec, vprec):
    """The web of curves of patch(3G): a list of (npoints, k) polylines."""
    lines = []
    if ucurves >= 1:
        vs = np.linspace(0.0, 1.0, ucurves) if ucurves > 1 else np.zeros(1)
        nu = segment_count(uprec, vcurves)
        grid = patch_points(ubasis, vbasis, coords, np.arange(nu + 1) / nu, vs)
        lines += [grid[i] for i in range(len(vs))]
    if vcurves >= 1:
        us = np.linspace(0.0, 1.0, vcurves) if vcurves > 1 else np.zeros(1)
        nv = segment_count(vprec, ucurves)
        grid = patch_points(ubasis, vbasis, coords, us, np.arange(nv + 1) / nv)
        lines += [grid[:, j] for j in range(len(us))]
    return lines


def patch_surface(ubasis, vbasis, gx, gy, gz, usegs, vsegs):
    """Emulator extension: ((vsegs+1, usegs+1, 3) points, unit normals).

    Normals are cross(dP/du, dP/dv); where that vanishes (a degenerate edge,
    like the teapot lid's pole) a neighbouring row's normal is used."""
    u = np.arange(usegs + 1) / usegs
    v = np.arange(vsegs + 1) / vsegs
    pu, pv = powers(u), powers(v)
    du = np.stack((3 * u ** 2, 2 * u, np.ones_like(u), np.zeros_like(u)), axis=1)
    dv = np.stack((3 * v ** 2, 2 * v, np.ones_like(v), np.zeros_like(v)), axis=1)
    g = [np.asarray(m, np.float64) for m in (gx, gy, gz)]
    p = np.stack([pv @ vbasis @ m @ ubasis.T @ pu.T for m in g], axis=-1)
    tu = np.stack([pv @ vbasis @ m @ ubasis.T @ du.T for m in g], axis=-1)
    tv = np.stack([dv @ vbasis @ m @ ubasis.T @ pu.T for m in g], axis=-1)
    n = np.cross(tu, tv)
    ln = np.linalg.norm(n, axis=-1)
    scale = max(float(np.abs(p).max()), 1e-30)
    bad = ln <= 1e-9 * scale * scale
    if bad.any():
        # take the normal of the nearest good row or column (poles)
        for axis in (0, 1):
            if not bad.any():
                break
            fwd = np.roll(n, -1, axis=axis)
            bwd = np.roll(n, 1, axis=axis)
            lf = np.linalg.norm(fwd, axis=-1)
            lb = np.linalg.norm(bwd, axis=-1)
            cand = np.where((lf >= lb)[..., None], fwd, bwd)
            n = np.where(bad[..., None], cand, n)
            ln = np.linalg.norm(n, axis=-1)
            bad = ln <= 1e-9 * scale * scale
    n = np.divide(n, ln[..., None], out=np.zeros_like(n), where=ln[..., None] > 0)
    return p, n


def forward_differences(m, n):
    """curveit(3G): the n + 1 points (rows 4) that iterating the rows of the
    forward-difference matrix ``m`` n times puts in its last row (row i +=
    row i-1 for i = 3, 2, 1 each step), starting with the last row itself;
    as cumulative sums, in the order the iteration adds."""
    m = np.asarray(m, np.float64)
    r0, r1, r2, r3 = m
    k = np.arange(n)[:, None]
    row1 = r1 + k * r0                                             # r1 before step k+1
    row2 = r2 + np.concatenate((np.zeros((1, 4)), np.cumsum(row1, axis=0)))[:n]
    row3 = r3 + np.concatenate((np.zeros((1, 4)), np.cumsum(row2, axis=0)))
    return row3
