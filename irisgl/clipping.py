"""User clipping planes: clipplane (clipplane(3G)).

Up to six planes (GD_CLIPPLANES) besides the frustum.  CP_DEFINE takes an
object-space plane [A, B, C, D] and stores it in eye space through the
inverse of the ModelView matrix in force; CP_ON/CP_OFF enable and disable
it.  A vertex is inside when its eye coordinates dotted with the plane are
>= 0.  The cut is made by the homogeneous clipper (geometry/clip.py) for
polygons, lines and points alike.  See docs/clip-planes-fog-and-extras.md.
"""
import numpy as np

from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, integer, machine, num, token, win

__all__ = ["clipplane"]

_MODES = {K.CP_OFF: "CP_OFF", K.CP_ON: "CP_ON", K.CP_DEFINE: "CP_DEFINE"}


def _plane(call, params):
    """The first four numbers of a C float[] (a longer array is read from its
    first elements, as C reads it)."""
    try:
        n = len(params)
    except TypeError:
        fail(call, "params is not an array of 4 floats", "pass [A, B, C, D]")
    if n < 4:
        fail(call, f"params has {n} elements", "a plane takes 4 floats [A, B, C, D]")
    return np.array([num(call, params[i], "plane coefficient") for i in range(4)],
                    np.float64)


@glcall
def clipplane(index, mode, params=None):
    """clipplane(3G): define (CP_DEFINE, object coordinates taken to eye
    coordinates by the inverse ModelView), enable (CP_ON) or disable (CP_OFF)
    user clipping plane ``index`` (0..5).  [S] enabling a plane never defined
    uses (0, 0, 0, 0), which clips nothing."""
    i = integer("clipplane", index, "index")
    if not 0 <= i < 6:
        fail("clipplane", f"index {i}", "0 through 5 (GD_CLIPPLANES is 6)")
    m = token("clipplane", mode, _MODES, "mode")
    w = win("clipplane")
    st = w.st
    plane, on = st.clipplanes[i]
    if m == K.CP_DEFINE:
        p = _plane("clipplane", params)
        mv = st.matrices.modelview_matrix()
        try:
            with np.errstate(all="ignore"):
                inv = np.linalg.inv(mv)
        except np.linalg.LinAlgError:
            fail("clipplane", "the ModelView matrix is singular",
                 "define the plane under an invertible ModelView")
        eye = inv @ p                 # obj . p = eye . (M^-1 p)  (eye = obj M)
        if not np.isfinite(eye).all():
            fail("clipplane", "the plane is not finite in eye coordinates",
                 "finite coefficients and an invertible ModelView")
        new = (eye, on)
    else:
        new = (plane, m == K.CP_ON)
    if new[1] or on:
        machine.state_change(w)       # primitives so far: clipped as they were
    st.clipplanes = st.clipplanes[:i] + [new] + st.clipplanes[i + 1:]
    enabled = [p if p is not None else np.zeros(4) for p, e in st.clipplanes if e]
    st.user_planes = np.array(enabled, np.float64) if enabled else None
