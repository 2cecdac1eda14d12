"""The screen box (scrbox(3G)): window-coordinate bounds of what is scan
converted while tracking.

The bounds of a batch come from its window-space geometry after clipping,
before any pixel test (scrbox(3G): it "may precede the framebuffer", and
must bound the modified region but may exceed it): the vertices of the
kept triangles, the clipped segment ends and the points (wide lines and
large points are already their one-pixel copies, geometry/lines2d.py), and
the glyph pixels of charstr, rounded outward to whole pixels and
limited to the scissor rectangle (viewport, scrmask and window), outside
which nothing is scan converted.  Vectorised: a few min/max per batch.
"""
import numpy as np

from . import viewport as V


def _xy_bounds(xy):
    xy = xy[np.isfinite(xy).all(axis=1)]
    if not len(xy):
        return None
    lo = np.floor(xy.min(axis=0))
    hi = np.ceil(xy.max(axis=0))
    return lo[0], hi[0], lo[1], hi[1]


def batch_bounds(work):
    """(left, right, bottom, top) of the batch's scan-converted geometry
    (before the scissor), or None when it has none."""
    if work.tris is not None:
        if not len(work.tris):
            return None
        used = np.unique(work.tris)
        xy = np.stack((work.X[used], work.Y[used]), axis=1) / float(V.ONE)
        return _xy_bounds(xy)
    if work.seg0 is not None:
        if not len(work.seg0):
            return None
        xy = np.concatenate((work.seg0[:, :2], work.seg1[:, :2]))
        return _xy_bounds(xy)
    if work.points is not None and len(work.points):
        return _xy_bounds(work.points[:, :2])
    return None


def track(st, work, scissor):
    """Grow ``st.scrbox`` by what ``work`` scan converts inside ``scissor``
    (x0, x1, y0, y1)."""
    _grow(st, batch_bounds(work), scissor)


def track_xy(st, xy, scissor):
    """Grow ``st.scrbox`` by pixels at window positions ``xy`` (N, 2): the
    glyph pixels of charstr."""
    _grow(st, _xy_bounds(np.asarray(xy, np.float64)) if len(xy) else None, scissor)


def _grow(st, b, scissor):
    if b is None or scissor is None:
        return
    l, r, bo, t = b
    l, r = max(l, scissor[0]), min(r, scissor[1])
    bo, t = max(bo, scissor[2]), min(t, scissor[3])
    if l > r or bo > t:
        return
    L, R, B, T = st.scrbox
    st.scrbox = (min(L, int(l)), max(R, int(r)), min(B, int(bo)), max(T, int(t)))
