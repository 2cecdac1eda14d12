"""z-buffer calls (docs/semantics.md §5, §1)."""

from . import constants as K
from ._current import boolean, glcall, integer, machine, screen_z, token, ulong, win

__all__ = ["zbuffer", "getzbuffer", "zfunction", "zwritemask", "zclear", "czclear"]

_ZF = {K.ZF_NEVER: "ZF_NEVER", K.ZF_LESS: "ZF_LESS", K.ZF_EQUAL: "ZF_EQUAL",
       K.ZF_LEQUAL: "ZF_LEQUAL", K.ZF_GREATER: "ZF_GREATER", K.ZF_NOTEQUAL: "ZF_NOTEQUAL",
       K.ZF_GEQUAL: "ZF_GEQUAL", K.ZF_ALWAYS: "ZF_ALWAYS"}


@glcall
def zbuffer(b):
    """zbuffer(3G): TRUE enables the z test and z writes (the z bank is
    created on first use)."""
    w = win("zbuffer")
    v = boolean("zbuffer", b)
    machine.state_change(w)
    w.st.zbuffer = v
    if v:
        w.fb.ensure_z(queued=True)


@glcall
def getzbuffer():
    """getzbuffer(3G): TRUE while z-buffering is on."""
    return int(win("getzbuffer").st.zbuffer)


@glcall
def zfunction(func):
    """zfunction(3G): pass when ``incoming FUNC stored``; default ZF_LEQUAL."""
    w = win("zfunction")
    f = token("zfunction", func, _ZF, "z function")
    if w.st.zfunc != f:
        machine.state_change(w)
        w.st.zfunc = f


@glcall
def zwritemask(mask):
    """zwritemask(3G): 1-bits of the 24-bit z are writable (per bit on VGX);
    applies to z writes and zclear."""
    w = win("zwritemask")
    m = ulong(integer("zwritemask", mask, "mask")) & 0xFFFFFF
    if w.st.zwritemask != m:
        machine.state_change(w)
        w.st.zwritemask = m


@glcall
def zclear(*ignored):
    """zclear(3G): z := GD_ZMAX over viewport ∩ scrmask, under zwritemask.
    One extra argument (Heidmann's listing) is accepted and ignored
    (docs/semantics.md §1)."""
    from vgx_emulator.errors import fail
    if len(ignored) > 1:
        fail("zclear", f"{len(ignored)} arguments", "zclear takes none (one is tolerated)")
    machine.zclear(win("zclear"))


@glcall
def czclear(cval, zval):
    """czclear(3G): colour (packed, or an index in cmode) then z, over
    viewport ∩ scrmask; ignores every writemask; z a C long clamped to the z
    range (_current.screen_z: ``czclear(c, 0xff800000)`` clears to GD_ZMIN)."""
    c = ulong(integer("czclear", cval, "colour"))
    z = screen_z("czclear", zval, "z")
    machine.czclear(win("czclear"), c, z)
