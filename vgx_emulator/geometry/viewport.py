"""Perspective divide and the viewport / depth-range mapping.

Reference section 2 (viewport), Decisions 4 and 5:

- ``xw = left - 0.5 + (x/w + 1) / 2 * (right - left + 1)``, same for y, so
  that pixel (i, j) has its centre at window coordinates (i, j).
- ``zw = (far + near) / 2 + (z/w) * (far - near) / 2`` for the lsetdepth
  range (near -> GD_ZMIN by default); rounded and clamped in the raster.
- subpixel(FALSE), the VGX default, snaps x and y to the nearest pixel
  centre; subpixel(TRUE) keeps them to 1/2**SUBPIXEL_BITS of a pixel.
"""
import numpy as np

from .. import config

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


def guard_factors(viewport):
    """Clip-space guard-band factors (gx, gy) >= 1 for the viewport."""
    l, r, b, t = viewport
    hw = max((r - l + 1) * 0.5, 0.5)
    hh = max((t - b + 1) * 0.5, 0.5)
    g = config.GUARD_BAND_PIXELS
    return max(1.0, g / hw), max(1.0, g / hh)
