"""irisgl: the IRIS GL calls, with their C names, argument order and values.

``from irisgl import *`` gives every IRIS GL call (the names of
:mod:`irisgl.names`), every constant of gl.h / device.h / get.h and the C
types (docs/porting.md).  The calls validate their arguments, convert units
and drive the emulated VGX in :mod:`vgx_emulator`; anything that is not IRIS
GL (PNG output, error mode, the runner) lives there.  ``irisgl._current.API``
says for each call whether it is implemented, kept as state for a real
display, or not emulated (docs/api.md).
"""
from vgx_emulator.errors import GLError

from . import (accum, attributes, clipping, colormap, constants, cursor, curves, depth,
               depthcue, drawing2d, drawmode, events, fog, fragment, lighting, lines, mapping,
               matrix, menus, nurbs, objects, pattern, picking, pixels, primitives, stencil,
               system, text, texture, types, window)
from . import not_emulated     # last: the calls no module above provides

_MODULES = (constants, types, window, matrix, primitives, lighting, depth, events, colormap,
            pixels, fragment, pattern, stencil, accum, objects, curves, texture, text, menus,
            drawing2d, lines, depthcue, drawmode, picking, cursor, attributes, system,
            clipping, fog, mapping, nurbs, not_emulated)

__all__ = ["GLError"]
for _m in _MODULES:
    for _n in _m.__all__:
        globals()[_n] = getattr(_m, _n)
    __all__ += _m.__all__
__all__ = sorted(set(__all__))
del _m, _n
