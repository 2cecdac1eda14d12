"""Stencil calls (docs/semantics.md §6)."""
from vgx_emulator.errors import fail

from . import constants as K
from ._current import boolean, glcall, integer, machine, token, ulong, win

__all__ = ["stencil", "sclear", "swritemask", "getstensize"]

_SF = {K.SF_NEVER: "SF_NEVER", K.SF_LESS: "SF_LESS", K.SF_EQUAL: "SF_EQUAL",
       K.SF_LEQUAL: "SF_LEQUAL", K.SF_GREATER: "SF_GREATER", K.SF_NOTEQUAL: "SF_NOTEQUAL",
       K.SF_GEQUAL: "SF_GEQUAL", K.SF_ALWAYS: "SF_ALWAYS"}
_ST = {K.ST_KEEP: "ST_KEEP", K.ST_ZERO: "ST_ZERO", K.ST_REPLACE: "ST_REPLACE",
       K.ST_INCR: "ST_INCR", K.ST_DECR: "ST_DECR", K.ST_INVERT: "ST_INVERT"}


@glcall
def stencil(enable, ref, func, mask, fail_, pass_, zpass):
    """stencil(3G): enable the stencil test; the pixel passes when
    ``(ref & mask) FUNC (stencil & mask)``.  ``fail_`` applies when it fails,
    ``pass_`` when it passes and the z test fails (or the z-buffer is off),
    ``zpass`` when both pass.  With ``enable`` FALSE the rest is ignored.
    ref is clamped to 2**planes - 1 when drawing (docs/semantics.md §6)."""
    w = win("stencil")
    on = boolean("stencil", enable)
    if not on:
        if w.st.stencil_on:
            machine.state_change(w)
            w.st.stencil_on = False
        return
    if not w.fb.has("stencil"):
        fail("stencil", "no stencil planes are configured", "stensize(n > 0) then gconfig()")
    r = ulong(integer("stencil", ref, "ref"))
    f = token("stencil", func, _SF, "stencil function")
    m = ulong(integer("stencil", mask, "mask"))
    ops = tuple(token("stencil", o, _ST, f"{nm} operation")
                for o, nm in ((fail_, "fail"), (pass_, "pass"), (zpass, "zpass")))
    new = (r, f, m) + ops
    if w.st.stencil_on and w.st.stencil == new:
        return                            # nothing changes: no flush
    machine.state_change(w)
    w.st.stencil_on = True
    w.st.stencil = new


@glcall
def sclear(sval):
    """sclear(3G): stencil := sval over viewport ∩ scrmask, under swritemask."""
    machine.sclear(win("sclear"), ulong(integer("sclear", sval, "value")))


@glcall
def swritemask(mask):
    """swritemask(3G): 1-bits of the stencil planes are writable (operations
    and sclear)."""
    w = win("swritemask")
    m = ulong(integer("swritemask", mask, "mask"))
    machine.state_change(w)
    w.st.swritemask = m


@glcall
def getstensize():
    """The stencil planes configured (stensize(3G); getgconfig(GC_BITS_STENCIL))."""
    return win("getstensize").fb.stencil_planes
