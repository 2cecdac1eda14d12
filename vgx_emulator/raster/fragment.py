"""Per-fragment operations of the Raster Subsystem, in VGX order.

Order (reference section 6, "Pipeline order"; stages not yet emulated are
marked and will slot in here, in this order):

1. scissor: viewport ∩ scrmask ∩ window (done by the walkers' pixel ranges)
2. pattern                                             (issue: raster subsystem)
3. afunction                                           (issue: raster subsystem)
4. stencil test                                        (issue: raster subsystem)
5. z test (zbuffer/zfunction); a failing fragment changes nothing
6. z write under zwritemask
7. blend / logicop                                     (issue: raster subsystem)
8. colour writemask, then every enabled colour buffer (frontbuffer/backbuffer)

``planes`` is the tuple of banks kernels take, defined once in
Framebuffer.planes(): (colour target 0, colour target 1, z).  ``ip`` is the
int64 parameter vector whose slots are the P_* names below.
"""
import math

from ..jit import njit
from . import depth

# slots of the integer parameter vector
P_SX0, P_SX1, P_SY0, P_SY1, P_ZFUNC, P_ZMASK, P_ZLO, P_ZHI, P_NCB = range(9)
NPARAMS = 9


@njit
def pack_rgba(r, g, b, a):
    """0..255 floats -> 0xAABBGGRR, rounded to nearest and clamped."""
    ri = int(math.floor(min(max(r, 0.0), 255.0) + 0.5))
    gi = int(math.floor(min(max(g, 0.0), 255.0) + 0.5))
    bi = int(math.floor(min(max(b, 0.0), 255.0) + 0.5))
    ai = int(math.floor(min(max(a, 0.0), 255.0) + 0.5))
    return (ai << 24) | (bi << 16) | (gi << 8) | ri


@njit
def colour_word(cmode, r, g, b, a):
    if cmode:
        return int(math.floor(r + 0.5)) & 0xFFF
    return pack_rgba(r, g, b, a)


@njit
def fragment(ztest, zwrite, color, cmode, x, y, z, r, g, b, a, planes, ip):
    """One fragment at window (x, y): z test, z write, colour write."""
    cb0, cb1, zb = planes
    if ztest:
        zq = depth.quantize(z, ip[P_ZLO], ip[P_ZHI])
        stored = zb[y, x]
        if not depth.compare(ip[P_ZFUNC], zq, stored):
            return
        if zwrite:
            zb[y, x] = depth.masked_write(stored, zq, ip[P_ZMASK])
    if color:
        word = colour_word(cmode, r, g, b, a)
        n = ip[P_NCB]
        if n >= 1:
            cb0[y, x] = word
        if n >= 2:
            cb1[y, x] = word
