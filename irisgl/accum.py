"""Accumulation buffer calls (docs/semantics.md §10)."""
from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, machine, num, token, win

__all__ = ["acbuf"]

_AC = {K.AC_CLEAR: "AC_CLEAR", K.AC_ACCUMULATE: "AC_ACCUMULATE",
       K.AC_CLEAR_ACCUMULATE: "AC_CLEAR_ACCUMULATE", K.AC_RETURN: "AC_RETURN",
       K.AC_MULT: "AC_MULT", K.AC_ADD: "AC_ADD"}


@glcall
def acbuf(op, value):
    """acbuf(3G): operate on the accumulation buffer over viewport ∩ scrmask.
    Needs acsize(16) + gconfig() and RGB mode."""
    w = win("acbuf")
    o = token("acbuf", op, _AC, "operation")
    v = num("acbuf", value, "value")
    if not w.fb.has("accum"):
        fail("acbuf", "no accumulation buffer is configured", "acsize(16) then gconfig()")
    if not w.st.rgb:
        fail("acbuf", "accumulation in colour-map mode", "RGB mode only")
    if v != v:
        fail("acbuf", "value is NaN", "a finite number")
    machine.acbuf(w, o, v)
