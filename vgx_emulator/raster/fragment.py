"""Per-fragment operations of the Raster Subsystem, in VGX order.

Order (docs/semantics.md §6 "Order of the pixel operations", §7, §8):

1. scissor: viewport ∩ scrmask ∩ window (the walkers' pixel ranges)
2. pattern: a 0 bit protects the pixel in every bank (filled primitives)
3. afunction: a failing alpha changes nothing
4. stencil test ``(ref & mask) FUNC (stored & mask)``:
   fails -> ``fail`` op, nothing else written
5. z test (zbuffer on): fails -> stencil ``pass`` op, nothing else written;
   passes -> stencil ``zpass`` op, z written under zwritemask.
   z-buffer off and stencil passes -> ``pass`` op (stencil(3G); docs/semantics.md §6)
6. blend (blendfunction) or logicop, per colour buffer against its own pixel
7. colour writemask, then every enabled colour buffer

``planes`` is the tuple of banks kernels take, in this order:
(colour target 0, colour target 1, z, stencil, pattern rows: the pattern's
bits aligned in x to the window, raster.variants.pattern_rows).  Absent banks
are 1x1 dummies that the kernel variant never touches.  ``ip`` is the int64
parameter vector whose slots are the P_* names below (filled by
:func:`pack`, from the state by raster.variants.choose); kernels copy it once
into a tuple of scalars (``params``) so that the per-pixel code reads
registers, not memory that might alias the banks.  Which stages run is
decided by the kernel's compile-time flags (raster/variants.py); their
parameters (functions, references, masks, factors) are runtime values.

``stage_function(flags)`` is the one implementation of the stages: for
the flags of a kernel variant, a pure function of the incoming and stored
values, written as selects on int32 masks rather than early returns.
Every stage computes its verdict and the stores keep the old value where
the fragment was rejected: the result is the same as testing stage by
stage, and a span loop around it compiles to vector code (z, stencil and
plain colour writes).
"""
import functools
import math

import numpy as np

from ..jit import helper, inline
from . import blend as _blend
from . import depth
from . import stencil as _stencil

# slots of the integer parameter vector (pack() fills them)
(P_SX0, P_SX1, P_SY0, P_SY1,                 # scissor: viewport ∩ scrmask ∩ window
 P_ZFUNC, P_ZMASK, P_ZLO, P_ZHI,             # zfunction, zwritemask (-1: all 24 bits), lsetdepth
 P_SFUNC, P_SREF, P_SMASK, P_SWMASK, P_SMAX,  # stencil(3G), swritemask, 2**planes - 1
 P_FX, P_FK, P_FA,                           # the stencil fail op as stencil.op_terms
 P_PX, P_PK, P_PA,                           # ... the pass (z fails) op
 P_ZX, P_ZK, P_ZA,                           # ... the zpass op
 P_CMASK, P_AFUNC, P_AREF, P_LOGICOP,        # colour writemask, afunction, logicop
 P_PATSIZE, P_ORGY,                          # defpattern size, the window's screen origin y
                                            # (x is in the pattern rows: variants.pattern_rows)
 P_BS0, P_BS1, P_BS2, P_BS3, P_BS4, P_BS5,   # blend factors as blend.factor_terms (the
 P_BD0, P_BD1, P_BD2, P_BD3, P_BD4, P_BD5,   # generic blend kernel reads them)
 P_ZMAX,                                     # 1: spans may be skipped against the z maxima
 P_PADSPAN,                                  # spans shorter than this run over whole vectors
 P_ZCHANGED,                                 # out: the triangle walker changed a stored z
 NPARAMS) = range(44)
#: the slots kernels read as int32 (params): the stencil arithmetic on the
#: 8-bit planes then runs in 32-bit vector lanes
STENCIL_SLOTS = range(P_SREF, P_ZA + 1)


def pack(*, scissor, zfunc, zmask, zrange, stencil, cmask, afunction, logicop, blend,
         pattern_size, origin, zmax=False, padspan=0):
    """The parameter vector of a pass, each value in its slot.

    ``scissor``: (x0, x1, y0, y1) inclusive; ``zmask``: the 24-bit
    zwritemask; ``zrange``: (lo, hi) of the stored z; ``stencil``: (func,
    ref, mask, writemask, max, fail terms, pass terms, zpass terms);
    ``afunction``: (ref, func); ``blend``: (source terms, destination terms);
    ``origin``: the window's screen origin, which patterns are aligned to
    (its y here; its x is in the pattern rows the kernels take)."""
    ip = np.zeros(NPARAMS, np.int64)
    ip[P_SX0], ip[P_SX1], ip[P_SY0], ip[P_SY1] = scissor
    ip[P_ZFUNC] = zfunc
    ip[P_ZMASK] = -1 if zmask == 0xFFFFFF else zmask
    ip[P_ZLO], ip[P_ZHI] = zrange
    sfunc, sref, smask, swmask, smax, fail, zfail, zpass = stencil
    ip[P_SFUNC], ip[P_SREF], ip[P_SMASK], ip[P_SWMASK], ip[P_SMAX] = \
        sfunc, sref, smask, swmask, smax
    ip[P_FX:P_FA + 1] = fail
    ip[P_PX:P_PA + 1] = zfail
    ip[P_ZX:P_ZA + 1] = zpass
    ip[P_CMASK] = cmask
    ip[P_AREF], ip[P_AFUNC] = afunction
    ip[P_LOGICOP] = logicop
    ip[P_BS0:P_BS5 + 1] = blend[0]
    ip[P_BD0:P_BD5 + 1] = blend[1]
    ip[P_PATSIZE] = pattern_size
    ip[P_ORGY] = origin[1]
    ip[P_ZMAX] = zmax
    ip[P_PADSPAN] = padspan
    return ip


@helper
def params(ip):
    """The parameter vector as a tuple of scalars, in slot order (read once
    per kernel); the STENCIL_SLOTS as int32."""
    i32 = np.int32
    return (ip[P_SX0], ip[P_SX1], ip[P_SY0], ip[P_SY1],
            ip[P_ZFUNC], ip[P_ZMASK], ip[P_ZLO], ip[P_ZHI],
            ip[P_SFUNC], i32(ip[P_SREF]), i32(ip[P_SMASK]), i32(ip[P_SWMASK]), i32(ip[P_SMAX]),
            i32(ip[P_FX]), i32(ip[P_FK]), i32(ip[P_FA]),
            i32(ip[P_PX]), i32(ip[P_PK]), i32(ip[P_PA]),
            i32(ip[P_ZX]), i32(ip[P_ZK]), i32(ip[P_ZA]),
            ip[P_CMASK], ip[P_AFUNC], ip[P_AREF], ip[P_LOGICOP],
            ip[P_PATSIZE], ip[P_ORGY],
            ip[P_BS0], ip[P_BS1], ip[P_BS2], ip[P_BS3], ip[P_BS4], ip[P_BS5],
            ip[P_BD0], ip[P_BD1], ip[P_BD2], ip[P_BD3], ip[P_BD4], ip[P_BD5],
            ip[P_ZMAX], ip[P_PADSPAN])


@helper
def blend_terms(blend, folded, prm):
    """The blend factor terms a kernel uses: its compiled-in ``folded`` ones,
    or for the generic kernel (blend.GENERIC) the parameter vector's."""
    if blend < 0:
        return ((prm[P_BS0], prm[P_BS1], prm[P_BS2], prm[P_BS3], prm[P_BS4], prm[P_BS5]),
                (prm[P_BD0], prm[P_BD1], prm[P_BD2], prm[P_BD3], prm[P_BD4], prm[P_BD5]))
    return folded


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


@inline
def colour_out(old, word, blend, logic, cmask, cmode, bterms, prm):
    """The value a colour buffer receives: blend or logicop against the
    stored ``old``, then the writemask."""
    old = np.int64(old)
    new = np.int64(word)
    # (a logicop other than LO_SRC replaces blending: variants.choose never
    # keys both; the general variant has both, one of them neutral)
    if logic:
        new = _blend.logic_op(prm[P_LOGICOP], new, old)
    if blend and not cmode:
        new = _blend.blend_words(bterms[0], bterms[1], new, old, blend < 0)
    if cmask:
        m = prm[P_CMASK]
        new = (old & ~m) | (new & m)
    if cmode:
        new &= 0xFFF
    return new


@functools.lru_cache(maxsize=None)
def stage_function(ztest, zwrite, stencil, blend, logic, atest, cmask, cmode):
    """``stages(patbit, zq, zold, sold, c0, c1, word, bterms, prm)``: every
    stage that these flags enable, for one fragment (inlined by numba into
    its caller).  The flags are constants of the closure, so numba prunes
    the disabled stages before it copies the function into a kernel (a
    module-level function taking the flags as arguments was copied whole,
    then pruned: 0.35 s of the walker's compile, against 0.09 s)."""

    @inline
    def stages(patbit, zq, zold, sold, c0, c1, word, bterms, prm):
        """Every enabled stage for one fragment, as a pure function of scalars.

        ``patbit``: the pattern bit under the pixel (1 without a pattern);
        ``zq``: the quantized window z; ``zold``, ``sold``, ``c0``, ``c1``: the
        stored z, stencil and colour values; ``word``: the packed incoming colour
        (0xAABBGGRR, or the index in colour-map mode); ``bterms``: the blend
        factors' terms (blend_terms: constants of a folded kernel).  Returns (colour passes,
        new z, new stencil, new c0, new c1); a stage that rejects leaves the
        stored values as they were.  The callers do the loads and stores: no
        array crosses this call, so it inlines into the span loop (an array
        argument costs reference counting on every call)."""
        i32 = np.int32     # numba widens int32 operations to int64: narrow each step
        ok = i32(-i32(patbit))         # verdicts are int32 masks (depth.compare)
        if atest:
            ok = i32(ok & depth.compare(prm[P_AFUNC], i32((word >> 24) & 0xFF), i32(prm[P_AREF])))
        zpass = i32(-1)
        if ztest:
            zpass = depth.compare(prm[P_ZFUNC], zq, zold)
        snew = sold
        if stencil:
            m = prm[P_SMASK]
            spass = depth.compare(prm[P_SFUNC], i32(prm[P_SREF] & m), i32(sold & m))
            # stencil(3G): without a z-buffer a passing fragment takes the pass op
            zp = zpass if ztest else i32(0)
            # the three ops' results, then selections of int32 values by masks (a
            # selection of their terms widened the vector lanes to 64 bits)
            smax = prm[P_SMAX]
            wm = prm[P_SWMASK]
            s_zpass = _stencil.apply(prm[P_ZX], prm[P_ZK], prm[P_ZA], sold, smax, wm)
            s_zfail = _stencil.apply(prm[P_PX], prm[P_PK], prm[P_PA], sold, smax, wm)
            s_fail = _stencil.apply(prm[P_FX], prm[P_FK], prm[P_FA], sold, smax, wm)
            s_pass = i32(i32(s_zpass & zp) | i32(s_zfail & ~zp))
            s_op = i32(i32(s_pass & spass) | i32(s_fail & ~spass))
            snew = i32(i32(s_op & ok) | i32(sold & ~ok))
            ok = i32(ok & spass)
        ok = i32(ok & zpass)
        znew = zold
        if zwrite:
            # the verdict folds into the write mask, so that the stored value is
            # not a select against the loaded one (LLVM would store it with a
            # masked store, vpmaskmovd, which is slow on AMD Zen: fill-z 41 ->
            # 35 ms with this form)
            znew = depth.masked_write(zold, zq, i32(prm[P_ZMASK]) & ok)
        n0 = word
        n1 = word
        if blend or logic or cmask:
            n0 = colour_out(c0, word, blend, logic, cmask, cmode, bterms, prm)
            n1 = colour_out(c1, word, blend, logic, cmask, cmode, bterms, prm)
        passed = ok != i32(0)
        return passed, znew, snew, (n0 if passed else c0), (n1 if passed else c1)

    return stages


@functools.lru_cache(maxsize=None)
def fragment_function(ztest, zwrite, color, cmode, stencil, blend, logic, atest, pattern,
                      cmask, dual):
    """``fragment(bterms, x, y, z, r, g, b, a, planes, ip)``: one fragment
    given as floats (window z, colour 0..255) on whole banks: quantize and
    pack, load, the stages of these flags, store.  Lines and points use
    this entry; the triangle walker does the same per span on row views."""
    stages = stage_function(ztest, zwrite, stencil, blend, logic, atest, cmask, cmode)

    @helper
    def fragment(bterms, x, y, z, r, g, b, a, planes, ip):
        cb0, cb1, zb, sb, pat = planes
        prm = params(ip)
        zq = depth.quantize(z, prm[P_ZLO], prm[P_ZHI]) if ztest else 0
        word = colour_word(cmode, r, g, b, a)
        patbit = 1
        if pattern:
            n = prm[P_PATSIZE]
            patbit = pat[(y + prm[P_ORGY]) % n, x]    # (variants.pattern_rows)
        zold = np.int64(zb[y, x]) if ztest else 0
        sold = np.int32(sb[y, x]) if stencil else np.int32(0)
        c0 = np.int64(cb0[y, x]) if color else 0
        c1 = np.int64(cb1[y, x]) if (color and dual) else 0
        ok, znew, snew, n0, n1 = stages(patbit, zq, zold, sold, c0, c1, word, bterms, prm)
        if stencil:
            sb[y, x] = snew
        if zwrite:
            zb[y, x] = znew
        if color:
            cb0[y, x] = n0
            if dual:
                cb1[y, x] = n1

    return fragment
