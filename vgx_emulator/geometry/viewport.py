"""Perspective divide and the viewport / depth-range mapping.

Reference section 2 (viewport), Decisions 4 and 5:

- ``xw = left - 0.5 + (x/w + 1) / 2 * (right - left + 1)``, same for y, so
  that pixel (i, j) has its centre at window coordinates (i, j).
- ``zw = (far + near) / 2 + (z/w) * (far - near) / 2`` for the lsetdepth
  range (near -> GD_ZMIN by default); rounded and clamped in the raster.
- subpixel(FALSE), the VGX default, snaps x and y to the nearest pixel
  centre; subpixel(TRUE) keeps them to 1/2**SUBPIXEL_BITS of a pixel.
"""
import math

import numpy as np

from .. import config
from ..jit import njit

ONE = 1 << config.SUBPIXEL_BITS
FIXED_LIMIT = 1 << 24          # |fixed-point coordinate| the rasterizer takes


def to_window(v, viewport, depth_range, snap):
    """Clip-space (N, 4) -> window x, y (float64), z (float64)."""
    l, r, b, t = viewport
    near, far = depth_range
    w = v[:, 3]
    xw = (l - 0.5) + (v[:, 0] / w + 1.0) * 0.5 * (r - l + 1)
    yw = (b - 0.5) + (v[:, 1] / w + 1.0) * 0.5 * (t - b + 1)
    zw = (far + near) * 0.5 + (v[:, 2] / w) * ((far - near) * 0.5)
    if snap:
        xw = np.floor(xw + 0.5)
        yw = np.floor(yw + 0.5)
    return xw, yw, zw


def to_fixed(xw):
    """Window coordinate -> fixed point with SUBPIXEL_BITS fractional bits
    (round to nearest).  Callers guarantee |xw| within the guard band."""
    return np.floor(xw * ONE + 0.5).astype(np.int64)


def representable(xw, yw, zw):
    """Window coordinates the rasterizer can take: finite, and |x|, |y|
    below 2**24 in fixed point (the range scan/fixed.py's edge functions are
    exact for; the guard band keeps clipped vertices far inside it).  Only a
    vertex the divide cannot place fails: 0/0 from a clip-space vertex at
    (0, 0, 0, 0), or a clip cut point that cancellation threw out of that
    range (edges between vertices of 1e20 and more)."""
    limit = FIXED_LIMIT / ONE
    with np.errstate(invalid="ignore"):
        return np.isfinite(zw) & (np.abs(xw) < limit) & (np.abs(yw) < limit)


def window_fixed(v, tris, viewport, depth_range, snap):
    """to_window, representable and to_fixed in one pass over the vertices
    (N, 4) that the triangles (T, 3) use, with the same arithmetic.
    Returns (X, Y int64 fixed point, Z float64 window z, ok (N,) vertex
    representable, lost (T,) a triangle with a vertex that is not); unused
    and unrepresentable vertices get 0.  (The arrays are made here: with an
    empty cache numba's np.zeros in a kernel costs its own compile.)"""
    n = len(v)
    out = (np.zeros(n, np.int64), np.zeros(n, np.int64), np.zeros(n), np.zeros(n, bool),
           np.zeros(len(tris), bool), np.zeros(n, bool))
    _window_fixed(v, tris, viewport, depth_range, snap, out)
    return out[:5]


@njit(error_model="numpy")
def _window_fixed(v, tris, viewport, depth_range, snap, out):
    X, Y, Z, ok, lost, used = out
    l, r, b, t = viewport
    near, far = depth_range
    sx = float(r - l + 1)
    sy = float(t - b + 1)
    zmid = (far + near) * 0.5
    zscale = (far - near) * 0.5
    limit = FIXED_LIMIT / ONE
    n = v.shape[0]
    for i in range(tris.shape[0]):
        used[tris[i, 0]] = True
        used[tris[i, 1]] = True
        used[tris[i, 2]] = True
    for i in range(n):
        if not used[i]:
            continue
        w = v[i, 3]
        xw = (l - 0.5) + (v[i, 0] / w + 1.0) * 0.5 * sx
        yw = (b - 0.5) + (v[i, 1] / w + 1.0) * 0.5 * sy
        zw = zmid + (v[i, 2] / w) * zscale
        if snap:
            xw = math.floor(xw + 0.5)
            yw = math.floor(yw + 0.5)
        if np.isfinite(zw) and abs(xw) < limit and abs(yw) < limit:
            ok[i] = True
            X[i] = np.int64(math.floor(xw * ONE + 0.5))
            Y[i] = np.int64(math.floor(yw * ONE + 0.5))
            Z[i] = zw
    for i in range(tris.shape[0]):
        lost[i] = not (ok[tris[i, 0]] and ok[tris[i, 1]] and ok[tris[i, 2]])


def guard_factors(viewport):
    """Clip-space guard-band factors (gx, gy) >= 1 for the viewport."""
    l, r, b, t = viewport
    hw = max((r - l + 1) * 0.5, 0.5)
    hh = max((t - b + 1) * 0.5, 0.5)
    g = config.GUARD_BAND_PIXELS
    return max(1.0, g / hw), max(1.0, g / hh)
