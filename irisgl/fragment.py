"""Writemasks, blending, alpha test, logic op, dither (docs/semantics.md §7)."""
from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, integer, machine, token, ulong, win

__all__ = ["wmpack", "RGBwritemask", "writemask", "blendfunction", "afunction", "logicop",
           "dither", "getwritemask"]

_BF_SRC = {K.BF_ZERO: "BF_ZERO", K.BF_ONE: "BF_ONE", K.BF_DC: "BF_DC", K.BF_MDC: "BF_MDC",
           K.BF_SA: "BF_SA", K.BF_MSA: "BF_MSA", K.BF_DA: "BF_DA", K.BF_MDA: "BF_MDA",
           K.BF_MIN_SA_MDA: "BF_MIN_SA_MDA"}
_BF_DST = {K.BF_ZERO: "BF_ZERO", K.BF_ONE: "BF_ONE", K.BF_SC: "BF_SC", K.BF_MSC: "BF_MSC",
           K.BF_SA: "BF_SA", K.BF_MSA: "BF_MSA", K.BF_DA: "BF_DA", K.BF_MDA: "BF_MDA"}
_AF = {K.AF_NEVER: "AF_NEVER", K.AF_LESS: "AF_LESS", K.AF_EQUAL: "AF_EQUAL",
       K.AF_LEQUAL: "AF_LEQUAL", K.AF_GREATER: "AF_GREATER", K.AF_NOTEQUAL: "AF_NOTEQUAL",
       K.AF_GEQUAL: "AF_GEQUAL", K.AF_ALWAYS: "AF_ALWAYS"}
_LO = {getattr(K, n): n for n in ("LO_ZERO", "LO_AND", "LO_ANDR", "LO_SRC", "LO_ANDI",
                                 "LO_DST", "LO_XOR", "LO_OR", "LO_NOR", "LO_XNOR", "LO_NDST",
                                 "LO_ORR", "LO_NSRC", "LO_ORI", "LO_NAND", "LO_ONE")}


def _rgb_only(call):
    w = win(call)
    if not w.st.rgb:
        fail(call, "RGB writemask in colour-map mode", "use writemask() in cmode")
    return w


def _set_mask(w, m):
    if w.st.cmask != m:
        machine.state_change(w)
        w.st.cmask = m


@glcall
def wmpack(mask):
    """wmpack(3G): RGBA writemask packed like cpack; wmpack(0) writes no colour."""
    w = _rgb_only("wmpack")
    _set_mask(w, ulong(integer("wmpack", mask, "mask")))


@glcall
def RGBwritemask(r, g, b):
    """RGBwritemask(3G): 8-bit masks (bits 8-15 ignored); alpha all ones."""
    w = _rgb_only("RGBwritemask")
    r, g, b = (integer("RGBwritemask", v, "mask") & 0xFF for v in (r, g, b))
    _set_mask(w, 0xFF000000 | (b << 16) | (g << 8) | r)


@glcall
def writemask(mask):
    """writemask(3G): colour-map index writemask (12 planes on the VGX)."""
    w = win("writemask")
    m = integer("writemask", mask, "mask")
    if w.st.rgb:
        fail("writemask", "colour-map writemask in RGB mode", "use wmpack/RGBwritemask")
    _set_mask(w, m & 0xFFF)


@glcall
def getwritemask():
    """getwritemask(3G): the writemask of the current drawmode's framebuffer;
    in colour-map mode only its planes' bits (12, 8 in multimap mode)."""
    from vgx_emulator.framebuffer.layers import index_bits
    w = win("getwritemask")
    return w.st.cmask & index_bits(w)


@glcall
def blendfunction(sfactr, dfactr):
    """blendfunction(3G): C = clamp(Cs*S + Cd*D); default (BF_ONE, BF_ZERO).
    BF_DC/BF_MDC/BF_MIN_SA_MDA are source factors only, BF_SC/BF_MSC
    destination factors only."""
    w = win("blendfunction")
    s = token("blendfunction", sfactr, _BF_SRC, "source factor")
    d = token("blendfunction", dfactr, _BF_DST, "destination factor")
    if not w.st.rgb:
        fail("blendfunction", "blending in colour-map mode", "RGB mode only")
    if w.st.blendfunc != (s, d):
        machine.state_change(w)
        w.st.blendfunc = (s, d)


@glcall
def afunction(ref, func):
    """afunction(3G): fragments pass when ``alpha FUNC ref`` (0..255)."""
    w = win("afunction")
    r = integer("afunction", ref, "ref")
    f = token("afunction", func, _AF, "alpha function")
    machine.state_change(w)
    w.st.afunc = (min(max(r, 0), 255), f)


@glcall
def logicop(opcode):
    """logicop(3G): bitwise op of incoming s and stored d; default LO_SRC.
    Any other op replaces blending ([S])."""
    w = win("logicop")
    o = token("logicop", opcode, _LO, "logic op")
    machine.state_change(w)
    w.st.logicop = o


@glcall
def dither(mode):
    """dither(3G): accepted and recorded; the emulator does not dither ([S])."""
    w = win("dither")
    w.st.dither = bool(token("dither", mode, {K.DT_OFF: "DT_OFF", K.DT_ON: "DT_ON"}, "mode"))
