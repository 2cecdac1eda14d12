"""Per-fragment operations of the Raster Subsystem, in VGX order.

Order (reference section 6 "Pipeline order", 7, 8; Decisions 1, 2):

1. scissor: viewport ∩ scrmask ∩ window (the walkers' pixel ranges)
2. pattern: a 0 bit protects the pixel in every bank (filled primitives)
3. afunction: a failing alpha changes nothing
4. stencil test ``(ref & mask) FUNC (stored & mask)``:
   fails -> ``fail`` op, nothing else written
5. z test (zbuffer on): fails -> stencil ``pass`` op, nothing else written;
   passes -> stencil ``zpass`` op, z written under zwritemask.
   z-buffer off and stencil passes -> ``pass`` op (Decision 1)
6. blend (blendfunction) or logicop, per colour buffer against its own pixel
7. colour writemask, then every enabled colour buffer

``planes`` is the tuple of banks kernels take, in this order:
(colour target 0, colour target 1, z, stencil, pattern bits).  Absent banks
are 1x1 dummies that the kernel variant never touches.  ``ip`` is the int64
parameter vector whose slots are the P_* names below.  Which stages run is
decided by the kernel's compile-time flags (raster/variants.py); their
parameters (functions, references, masks, factors) are runtime values.
"""
import math

import numpy as np

from ..jit import helper
from . import blend as _blend
from . import depth
from . import stencil as _stencil

# slots of the integer parameter vector
(P_SX0, P_SX1, P_SY0, P_SY1, P_ZFUNC, P_ZMASK, P_ZLO, P_ZHI, P_NCB,
 P_SFUNC, P_SREF, P_SMASK, P_SFAIL, P_SPASS, P_SZPASS, P_SWMASK, P_SMAX,
 P_CMASK, P_BSRC, P_BDST, P_AFUNC, P_AREF, P_LOGICOP,
 P_PATSIZE, P_ORGX, P_ORGY) = range(26)
NPARAMS = 26


@helper
def pack_rgba(r, g, b, a):
    """0..255 floats -> 0xAABBGGRR, rounded to nearest and clamped."""
    ri = int(math.floor(min(max(r, 0.0), 255.0) + 0.5))
    gi = int(math.floor(min(max(g, 0.0), 255.0) + 0.5))
    bi = int(math.floor(min(max(b, 0.0), 255.0) + 0.5))
    ai = int(math.floor(min(max(a, 0.0), 255.0) + 0.5))
    return (ai << 24) | (bi << 16) | (gi << 8) | ri


@helper
def colour_word(cmode, r, g, b, a):
    if cmode:
        return int(math.floor(r + 0.5)) & 0xFFF
    return pack_rgba(r, g, b, a)


@helper
def write_colour(cb, y, x, word, blend, logic, cmask, cmode, ip):
    """Blend or logicop against this buffer's pixel, then the writemask."""
    old = np.int64(cb[y, x])
    new = np.int64(word)
    if logic:
        new = _blend.logic_op(ip[P_LOGICOP], word, old)
    elif blend and not cmode:
        new = _blend.blend_words(ip[P_BSRC], ip[P_BDST], word, old)
    if cmask:
        m = ip[P_CMASK]
        new = (old & ~m) | (new & m)
    if cmode:
        new &= 0xFFF
    cb[y, x] = new


@helper
def fragment(ztest, zwrite, color, cmode, stencil, blend, logic, atest, pattern, cmask,
             x, y, z, r, g, b, a, planes, ip):
    """One fragment at window (x, y) through every enabled stage."""
    cb0, cb1, zb, sb, pat = planes
    if pattern:
        n = ip[P_PATSIZE]
        if pat[(y + ip[P_ORGY]) % n, (x + ip[P_ORGX]) % n] == 0:
            return
    if atest:
        ai = int(math.floor(min(max(a, 0.0), 255.0) + 0.5))
        if not depth.compare(ip[P_AFUNC], ai, ip[P_AREF]):
            return
    if stencil:
        s = sb[y, x]
        m = ip[P_SMASK]
        if not depth.compare(ip[P_SFUNC], ip[P_SREF] & m, s & m):
            sb[y, x] = _stencil.apply(ip[P_SFAIL], s, ip[P_SREF], ip[P_SMAX], ip[P_SWMASK])
            return
        if ztest:
            zq = depth.quantize(z, ip[P_ZLO], ip[P_ZHI])
            stored = zb[y, x]
            if not depth.compare(ip[P_ZFUNC], zq, stored):
                sb[y, x] = _stencil.apply(ip[P_SPASS], s, ip[P_SREF], ip[P_SMAX],
                                          ip[P_SWMASK])
                return
            sb[y, x] = _stencil.apply(ip[P_SZPASS], s, ip[P_SREF], ip[P_SMAX], ip[P_SWMASK])
            if zwrite:
                zb[y, x] = depth.masked_write(stored, zq, ip[P_ZMASK])
        else:
            sb[y, x] = _stencil.apply(ip[P_SPASS], s, ip[P_SREF], ip[P_SMAX], ip[P_SWMASK])
    elif ztest:
        zq = depth.quantize(z, ip[P_ZLO], ip[P_ZHI])
        stored = zb[y, x]
        if not depth.compare(ip[P_ZFUNC], zq, stored):
            return
        if zwrite:
            zb[y, x] = depth.masked_write(stored, zq, ip[P_ZMASK])
    if color:
        word = colour_word(cmode, r, g, b, a)
        n = ip[P_NCB]
        if blend or logic or cmask:
            if n >= 1:
                write_colour(cb0, y, x, word, blend, logic, cmask, cmode, ip)
            if n >= 2:
                write_colour(cb1, y, x, word, blend, logic, cmask, cmode, ip)
        else:
            if n >= 1:
                cb0[y, x] = word
            if n >= 2:
                cb1[y, x] = word
