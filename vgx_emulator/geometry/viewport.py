"""Perspective divide and the viewport / depth-range mapping.

docs/semantics.md §2 (viewport), §5 (depth) and §1 (snapping):

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
#: |window z| a placed vertex stays below: clipping at the near and far
#: planes keeps z inside the lsetdepth range (24-bit), so only a vertex the
#: divide cannot place reaches it; the walker relies on it to take
#: quantized z in 32-bit lanes (scan/triangles.py)
Z_LIMIT = float(1 << 30)


@njit(error_model="numpy")
def _place(x, y, z, w, viewport, depth_range, snap):
    """One clip-space vertex -> window x, y, z (float64): the mapping above,
    the one formula of both to_window and window_fixed."""
    l, r, b, t = viewport
    near, far = depth_range
    xw = (l - 0.5) + (x / w + 1.0) * 0.5 * float(r - l + 1)
    yw = (b - 0.5) + (y / w + 1.0) * 0.5 * float(t - b + 1)
    zw = (far + near) * 0.5 + (z / w) * ((far - near) * 0.5)
    if snap:
        xw = math.floor(xw + 0.5)
        yw = math.floor(yw + 0.5)
    return xw, yw, zw


def to_window(v, viewport, depth_range, snap):
    """Clip-space (N, 4) -> window x, y (float64), z (float64)."""
    out = np.empty((3, len(v)))
    _to_window(np.ascontiguousarray(v, np.float64), _ints(viewport), _floats(depth_range),
               bool(snap), out)
    return out[0], out[1], out[2]


@njit(error_model="numpy")
def _to_window(v, viewport, depth_range, snap, out):
    for i in range(v.shape[0]):
        out[0, i], out[1, i], out[2, i] = _place(v[i, 0], v[i, 1], v[i, 2], v[i, 3],
                                                 viewport, depth_range, snap)


def _ints(viewport):
    return tuple(int(c) for c in viewport)


def _floats(depth_range):
    return float(depth_range[0]), float(depth_range[1])


def placed(rows):
    """Per window row (x, y, z, ...): whether the divide placed it, by the
    rule of window_fixed (finite, |x|, |y| below the fixed-point range, |z|
    below Z_LIMIT).  A line or point cut from a vertex of 1e38 can lose its
    clip w to cancellation (0/0 gives NaN); such a row is dropped."""
    limit = FIXED_LIMIT / ONE
    with np.errstate(invalid="ignore"):
        return (np.abs(rows[:, 0]) < limit) & (np.abs(rows[:, 1]) < limit) & \
            (np.abs(rows[:, 2]) < Z_LIMIT)


def window_fixed(v, tris, viewport, depth_range, snap):
    """to_window, then the fixed point the rasterizer takes, in one pass over
    the vertices (N, 4) that the triangles (T, 3) use.  A vertex is placed
    (``ok``) when its window coordinates are finite and |x|, |y| are below
    2**24 in fixed point (the range scan/fixed.py's edge functions are exact
    for; the guard band keeps clipped vertices far inside it) and |z| below
    Z_LIMIT.  Only a
    vertex the divide cannot place fails: 0/0 from a clip-space vertex at
    (0, 0, 0, 0), or a clip cut point that cancellation threw out of that
    range (edges between vertices of 1e20 and more).  x and y are rounded
    to nearest with SUBPIXEL_BITS fractional bits.  Returns (X, Y int64,
    Z float64 window z, ok (N,), lost (T,) a triangle with a vertex that is
    not placed, box: the pixels x0, x1, y0, y1 whose centres the placed
    vertices' extent may cover, x0 > x1 when none is placed); unused and
    unplaced vertices get 0.  (The arrays are made here: with an empty
    cache numba's np.zeros in a kernel costs its own compile.)"""
    n = len(v)
    box = np.array([FIXED_LIMIT, -FIXED_LIMIT, FIXED_LIMIT, -FIXED_LIMIT], np.int64)
    out = (np.zeros(n, np.int64), np.zeros(n, np.int64), np.zeros(n), np.zeros(n, bool),
           np.zeros(len(tris), bool), np.zeros(n, bool), box)
    _window_fixed(v, tris, _ints(viewport), _floats(depth_range), bool(snap), out)
    shift = config.SUBPIXEL_BITS
    return out[:5] + ((int(box[0] >> shift), int(box[1] >> shift),
                       int(box[2] >> shift), int(box[3] >> shift)),)


@njit(error_model="numpy")
def _window_fixed(v, tris, viewport, depth_range, snap, out):
    X, Y, Z, ok, lost, used, box = out
    limit = FIXED_LIMIT / ONE
    for i in range(tris.shape[0]):
        used[tris[i, 0]] = True
        used[tris[i, 1]] = True
        used[tris[i, 2]] = True
    for i in range(v.shape[0]):
        if not used[i]:
            continue
        xw, yw, zw = _place(v[i, 0], v[i, 1], v[i, 2], v[i, 3], viewport, depth_range, snap)
        if abs(zw) < Z_LIMIT and abs(xw) < limit and abs(yw) < limit:
            ok[i] = True
            X[i] = np.int64(math.floor(xw * ONE + 0.5))
            Y[i] = np.int64(math.floor(yw * ONE + 0.5))
            Z[i] = zw
            box[0] = min(box[0], X[i])
            box[1] = max(box[1], X[i])
            box[2] = min(box[2], Y[i])
            box[3] = max(box[3], Y[i])
    for i in range(tris.shape[0]):
        lost[i] = not (ok[tris[i, 0]] and ok[tris[i, 1]] and ok[tris[i, 2]])


def guard_factors(viewport):
    """Clip-space guard-band factors (gx, gy) >= 1 for the viewport."""
    l, r, b, t = viewport
    hw = max((r - l + 1) * 0.5, 0.5)
    hh = max((t - b + 1) * 0.5, 0.5)
    g = config.GUARD_BAND_PIXELS
    return max(1.0, g / hw), max(1.0, g / hh)
