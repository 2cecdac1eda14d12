"""Depth cueing (depthcue(3G)): the colour of each vertex from its screen z.

After clipping and the viewport transform, every vertex's window z is
mapped linearly from [znear, zfar] onto the ramp of lshaderange(3G)
(colour-map mode: highin at znear, lowin at zfar) or lRGBrange(3G) (RGB
mode: the maxima at znear, the minima at zfar); z beyond either end takes
that end's value.  The colours then go through the usual interpolation
(the machine turns Gouraud on for depth-cued passes), so a line spanning a
range of z spans the range of colours.  Clipped vertices get the colour of
their own z.  Alpha is kept.
"""
import numpy as np

from .batch import FILLED, LINES


def ramp_t(z, znear, zfar):
    """0 at znear, 1 at zfar, clamped; znear == zfar: 0 on the near side
    (z <= znear), 1 beyond ([S])."""
    z = np.asarray(z, np.float64)
    if znear == zfar:
        return np.where(z <= znear, 0.0, 1.0)
    with np.errstate(all="ignore"):
        return np.clip((z - znear) / float(zfar - znear), 0.0, 1.0)


def cue(colours, z, st, rgb):
    """colours (N, 4) with columns 0..2 replaced from z (N,)."""
    out = np.array(colours, np.float64, copy=True)
    if rgb:
        rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar = st.rgbrange
        t = ramp_t(z, znear, zfar)[:, None]
        hi = np.array((rmax, gmax, bmax), np.float64)
        lo = np.array((rmin, gmin, bmin), np.float64)
        out[:, 0:3] = hi + t * (lo - hi)
    else:
        low, high, znear, zfar = st.shaderange
        t = ramp_t(z, znear, zfar)
        out[:, 0] = high + t * (low - high)
    return out


def apply(work, st):
    """Depth-cue a WindowWork in place (st.rgb: which ramp)."""
    rgb = st.rgb
    if work.klass == FILLED:
        if work.C is None or len(work.C) == 0:
            return
        work.C = cue(work.C, work.Z, st, rgb)
        work.CB = work.C
    elif work.klass == LINES:
        if work.seg0 is None or len(work.seg0) == 0:
            return
        for rows in (work.seg0, work.seg1):
            rows[:, 3:7] = cue(rows[:, 3:7], rows[:, 2], st, rgb)
        work.segflat = np.ascontiguousarray(work.seg1[:, 3:7])
    elif work.points is not None and len(work.points):
        work.points[:, 3:7] = cue(work.points[:, 3:7], work.points[:, 2], st, rgb)
