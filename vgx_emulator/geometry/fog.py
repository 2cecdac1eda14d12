"""Per-vertex fog (fogvertex(3G)), in the geometry stage.

Each vertex colour (after lighting) is blended toward the fog colour by the
fog factor f of its eye-space distance z (the depth in front of the eye,
-z_eye / w_eye); the rasterizer then Gouraud-shades the fogged colours::

    C' = f * C + (1 - f) * C_fog        (red, green, blue; alpha unchanged)

    FG_*_LIN    f = (end - z) / (end - start)
    FG_*_EXP    f = 255 ** -(density * z)
    FG_*_EXP2   f = 255 ** -((density * z) ** 2)

clamped to [0, 1].  fogvertex(3G) normalises density so that 1.0 makes the
fog "completely opaque at a distance of 1.0": the emulator reads that as
f = 1/255 there, where the object's own colour contributes less than one
step of an 8-bit component (a choice: the man page gives no formula).  The
VGX has no per-pixel fog (GD_FOGPIXEL 0): the FG_PIX_* modes are computed
per vertex (see docs/clip-planes-fog-and-extras.md).
"""
import numpy as np

LIN, EXP, EXP2 = 0, 1, 2
LN255 = float(np.log(255.0))


class FogState:
    """The fog definition of a window and whether it is on."""

    __slots__ = ("on", "kind", "density", "start", "end", "colour", "mode")

    def __init__(self):
        self.on = False
        self.mode = 2                          # FG_VTX_EXP, density 0: no fog
        self.kind = EXP
        self.density = 0.0
        self.start = 0.0
        self.end = 1.0
        self.colour = (0.0, 0.0, 0.0)          # 0..255

    def define(self, mode, kind, density, start, end, colour):
        self.mode, self.kind = mode, kind
        self.density, self.start, self.end = density, start, end
        self.colour = colour


def factor(fs, z):
    """Fog factor (N,) of eye-space distances z (N,), in [0, 1]; NaN -> 1."""
    if fs.kind == LIN:
        span = fs.end - fs.start
        if span == 0.0:
            f = np.where(z < fs.start, 1.0, 0.0)
        else:
            f = (fs.end - z) / span
    elif fs.kind == EXP:
        f = np.exp(-LN255 * fs.density * np.maximum(z, 0.0))
    else:
        dz = fs.density * np.maximum(z, 0.0)
        f = np.exp(-LN255 * dz * dz)
    f = np.clip(f, 0.0, 1.0)
    return np.where(np.isnan(f), 1.0, f)


def eye_distance(eye4):
    """-z_eye / w_eye of eye-space vertices (N, 4) (0 where w is 0)."""
    w = eye4[:, 3]
    return np.divide(-eye4[:, 2], w, out=np.zeros(len(w)), where=w != 0)


def apply(fs, eye4, col, back):
    """Fogged copies of the front (and back) colours (N, 4), 0..255."""
    f = factor(fs, eye_distance(eye4))[:, None]
    fogc = np.asarray(fs.colour, np.float64)[None, :]
    out = col.copy()
    out[:, :3] = f * col[:, :3] + (1.0 - f) * fogc
    if back is not None:
        b = back.copy()
        b[:, :3] = f * back[:, :3] + (1.0 - f) * fogc
        back = b
    return out, back
