"""Atmospheric fog: fogvertex (fogvertex(3G)).

FG_VTX_EXP / FG_VTX_EXP2 take [density, r, g, b], FG_VTX_LIN takes
[start, end, r, g, b] (colours 0.0..1.0); a definition is used once FG_ON
enables fog, until FG_OFF.  The fog factor is computed per vertex from the
eye-space distance and blended into the lit colour in the geometry stage
(vgx_emulator/geometry/fog.py), then Gouraud shading interpolates it.  The
VGX has no per-pixel fog (getgdesc(GD_FOGPIXEL) is 0): FG_PIX_* definitions
are accepted and computed per vertex.  Fog applies in RGB mode only.
See docs/clip-planes-fog-and-extras.md.
"""
from vgx_emulator.errors import fail, warn
from vgx_emulator.geometry import fog as F

from . import constants as K
from ._current import glcall, machine, num, token, win

__all__ = ["fogvertex"]

_MODES = {K.FG_OFF: "FG_OFF", K.FG_ON: "FG_ON", K.FG_VTX_EXP: "FG_VTX_EXP (FG_DEFINE)",
          K.FG_VTX_LIN: "FG_VTX_LIN", K.FG_PIX_EXP: "FG_PIX_EXP", K.FG_PIX_LIN: "FG_PIX_LIN",
          K.FG_VTX_EXP2: "FG_VTX_EXP2", K.FG_PIX_EXP2: "FG_PIX_EXP2"}
_KIND = {K.FG_VTX_EXP: F.EXP, K.FG_PIX_EXP: F.EXP, K.FG_VTX_EXP2: F.EXP2,
         K.FG_PIX_EXP2: F.EXP2, K.FG_VTX_LIN: F.LIN, K.FG_PIX_LIN: F.LIN}


def _params(call, params, n, what):
    try:
        have = len(params)
    except TypeError:
        fail(call, f"params is not an array of {n} floats", what)
    if have < n:
        fail(call, f"params has {have} elements", what)
    return [num(call, params[i], "parameter") for i in range(n)]


def _colour(call, rgb):
    """Fog colour components 0.0..1.0 (clamped, as colours are) -> 0..255."""
    out = []
    for c in rgb:
        if c != c:
            fail(call, "a fog colour component is NaN", "numbers 0.0 through 1.0")
        out.append(min(max(c, 0.0), 1.0) * 255.0)
    return tuple(out)


@glcall
def fogvertex(mode, params=None):
    """fogvertex(3G): define fog (FG_VTX_EXP/EXP2 [density, r, g, b],
    FG_VTX_LIN [start, end, r, g, b]; FG_PIX_* likewise, computed per vertex
    on the VGX) or turn it on (FG_ON) or off (FG_OFF).  [S] FG_ON before any
    definition uses density 0 (no visible fog); a negative density is taken
    as 0 with a warning."""
    m = token("fogvertex", mode, _MODES, "mode")
    w = win("fogvertex")
    fs = w.st.fog
    if m in (K.FG_ON, K.FG_OFF):
        on = m == K.FG_ON
        if on != fs.on:
            machine.state_change(w)
        fs.on = on
        return
    kind = _KIND[m]
    if kind == F.LIN:
        start, end, r, g, b = _params("fogvertex", params, 5,
                                      "FG_*_LIN takes [start, end, red, green, blue]")
        density = 0.0
        if not (abs(start) < float("inf") and abs(end) < float("inf")):
            fail("fogvertex", "start or end is not finite", "finite eye-space distances")
    else:
        density, r, g, b = _params("fogvertex", params, 4,
                                   "FG_*_EXP and FG_*_EXP2 take [density, red, green, blue]")
        start, end = 0.0, 1.0
        if density != density:
            fail("fogvertex", "density is NaN", "a density >= 0.0")
        if density < 0.0:
            warn("fogvertex", f"density {density} < 0 taken as 0 (no fog)")
            density = 0.0
    colour = _colour("fogvertex", (r, g, b))
    if fs.on:
        machine.state_change(w)       # what was drawn keeps the old fog
    fs.define(m, kind, density, start, end, colour)
