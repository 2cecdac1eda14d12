"""The attribute stack: pushattributes(3G) / popattributes(3G).

pushattributes saves the attributes its man page lists: backbuffer,
frontbuffer, cmode or RGBmode colour, color / RGB color, drawmode,
linestyle, linewidth, lsrepeat, pattern, font, writemask / RGB writemask,
shademodel.  They are saved by their WindowState field names (``SAVED``); a
field that does not exist yet (another group's) is skipped, so it joins
once its calls add it.  The stack is ATTRIBSTACKDEPTH (10) deep, counting
the attributes in force (as the viewport stack does).
"""
import copy

from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, machine, win

__all__ = ["pushattributes", "popattributes"]

#: WindowState fields pushattributes(3G) saves (colour: index or RGB, as
#: the mode uses it; cmask: writemask and RGBwritemask; gouraud: shademodel)
SAVED = ("colour", "cmask", "front_enabled", "back_enabled", "pattern", "gouraud",
         "drawmode", "linestyle", "linewidth", "lsrepeat", "lsbackup", "resetls", "font")


@glcall
def pushattributes():
    """pushattributes(3G): push a copy of the attributes in force; a full
    stack (ATTRIBSTACKDEPTH levels) is an error (lenient mode: ignored, as
    the man page says)."""
    w = win("pushattributes")
    if len(w.attrib_stack) >= K.ATTRIBSTACKDEPTH - 1:
        fail("pushattributes", "attribute stack is full",
             f"at most {K.ATTRIBSTACKDEPTH} levels (ATTRIBSTACKDEPTH)")
    st = w.st
    w.attrib_stack.append({n: copy.deepcopy(getattr(st, n)) for n in SAVED if hasattr(st, n)})


@glcall
def popattributes():
    """popattributes(3G): restore the attributes of the last pushattributes."""
    w = win("popattributes")
    if not w.attrib_stack:
        fail("popattributes", "attribute stack is empty", "pop only what was pushed")
    machine.state_change(w)
    saved = w.attrib_stack.pop()
    for n, v in saved.items():
        setattr(w.st, n, v)
    machine.attributes_changed(w)   # the next vertex takes the restored colour
