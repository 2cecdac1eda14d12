"""RasterKey: the pipeline state that selects a compiled kernel variant.

Kernels are specialised on which stages a pass *enables*, not on the values
those stages take (z function, masks, ...: those are runtime integers).  The
one exception is the pair of blend factors: the per-component factor
arithmetic is the costliest per-fragment work, and with the factors known
at compile time it folds to what the pair needs.  That is done for the
common pairs of blend.FOLDED; every other pair shares one generic kernel
that reads the factors at run time, so the variants stay few.  So
a depth-only pass compiles to a loop with no colour work, a scene without a
z-buffer never touches z memory, and the set of variants stays small (each
field is a bool; only the combinations a program uses are compiled).

Every kernel variant is compiled through ``jit.kernel(variant=key)``: its disk
cache is keyed on the key and on the source of every module it inlines
(docs/architecture.md, Kernels).
"""
from collections import namedtuple

import numpy as np

from .. import config
from ..framebuffer import layers
from . import blend, depth, fragment
from . import stencil as _stencil

#: Fields of the raster key, in kernel-factory argument order.
#: ``blend``: 0, or blend.key_code(sfactr, dfactr): a folded pair, or GENERIC.
#: ``stencil``: 0 off, 1 tested only (every op ST_KEEP or swritemask 0: the
#: triangle walker then never stores the bank), 2 tested and written.
#: ``dual``: drawing goes to two colour buffers (frontbuffer and backbuffer
#: both enabled), so that the common one-buffer loop has no per-pixel test.
RasterKey = namedtuple("RasterKey", "ztest zwrite color gouraud cmode twoside "
                                    "stencil blend logic atest pattern cmask texture dual")


_DUMMY_C = np.zeros((1, 1), np.uint32)
_DUMMY_Z = np.zeros((1, 1), np.int32)
_DUMMY_S = np.zeros((1, 1), np.uint8)
_SOLID = np.ones((1, 1), np.uint8)


def choose(st, fb, targets, *, bits, scissor, origin, pattern=None, twoside=False,
           hollow=False):
    """The kernel variant and parameter vector of a pass: ``(RasterKey, ip)``.

    ``st``: the window's state (state.WindowState); ``fb``: its Framebuffer;
    ``targets``: the colour banks drawing goes to (frontbuffer(3G),
    backbuffer(3G), drawmode(3G), zdraw(3G)); ``bits``: the bits a colour
    word may hold (0xFFFFFFFF in RGB mode, 2**planes - 1 in colour-map
    mode); ``scissor``: viewport ∩ scrmask ∩ window; ``origin``: the
    window's screen origin, which patterns align to; ``pattern``: (size,
    bits) of the defpattern(3G) a filled primitive is drawn with, or None;
    ``twoside``: the batch carries back colours (lmodel TWOSIDE);
    ``hollow``: polymode(PYM_HOLLOW) outlines, which the stencil does not
    gate or change ([S] the VGX's hollow fill used the stencil planes
    itself and left them as it found them: SGI's hollowcube-vgx.c and NCSA
    isovis enable stencil(TRUE, 1, SF_EQUAL, 1, ...) on never-cleared
    planes for it, and drew their outlines).

    A stage is in the key when the state *enables* it: zbuffer(3G) in the
    normal framebuffer (the pop-up, overlay and underlay planes have no z
    or stencil), stencil(3G) with a stencil bank, blendfunction(3G) other
    than (BF_ONE, BF_ZERO) in RGB mode, logicop(3G) other than LO_SRC (it
    replaces blending), afunction(3G) other than AF_ALWAYS, a pattern, a
    writemask(3G)/wmpack(3G) that keeps some bits.  Its values (functions,
    references, masks, factors) go to the parameter vector."""
    normal = st.drawmode == layers.NORMALDRAW
    ztest = st.zbuffer and normal
    zmask = st.zwritemask & 0xFFFFFF
    cmask = st.cmask & bits
    color = len(targets) > 0 and cmask != 0
    smax = (1 << fb.stencil_planes) - 1
    stencil = 0
    if st.stencil_on and fb.has("stencil") and normal and not hollow:
        # 1: the bank is only read (every op ST_KEEP, or swritemask 0)
        keep = all(op == _stencil.ST_KEEP for op in st.stencil[3:6])
        stencil = 1 if keep or st.swritemask & smax == 0 else 2
    logic = color and st.logicop != blend.LO_SRC
    key = RasterKey(ztest=ztest, zwrite=ztest and zmask != 0, color=color,
                    gouraud=st.gouraud or st.depthcue, cmode=not st.rgb, twoside=twoside,
                    stencil=stencil,
                    blend=blend.key_code(*st.blendfunc) if (
                        color and st.rgb and not logic and st.blendfunc != blend.REPLACE) else 0,
                    logic=logic, atest=st.rgb and st.afunc[1] != depth.AF_ALWAYS,
                    pattern=pattern is not None,
                    cmask=color and (cmask != bits or not normal),
                    texture=False, dual=color and len(targets) >= 2)
    ref, func, mask, sfail, spass, szpass = st.stencil
    ref = min(ref, smax)         # stencil(3G): the reference is clamped to the planes
    ops = tuple(_stencil.op_terms(op, ref, smax) for op in (sfail, spass, szpass))
    near, far = st.depth_range
    ip = fragment.pack(
        scissor=scissor, zfunc=st.zfunc, zmask=zmask, zrange=(min(near, far), max(near, far)),
        stencil=(func, ref, mask & smax, st.swritemask & smax, smax) + ops,
        cmask=cmask, afunction=st.afunc, logicop=st.logicop,
        blend=(blend.factor_terms(st.blendfunc[0], True),
               blend.factor_terms(st.blendfunc[1], False)),
        pattern_size=pattern[0] if pattern is not None else 1, origin=origin,
        padspan=config.PAD_SPAN)
    return key, ip


def pattern_rows(pattern, orgx, width):
    """The bits of a defpattern(3G) ``(size, bits)`` laid out for a window
    ``width`` pixels wide whose screen origin is at column ``orgx``:
    ``rows[r, x]`` is the pattern bit of window column x in pattern row r
    (setpattern(3G): the pattern is aligned to the screen, so column x
    reads pattern column (x + orgx) mod size).  The kernels then read a
    row's bits at the pixel's own index, a contiguous load a span loop
    vectorises, instead of a modulo per pixel; the row is still
    (y + orgy) mod size."""
    n, bits = pattern
    return np.ascontiguousarray(bits[:, (np.arange(width) + orgx) % n])


def banks(key, fb, targets, pattern=None, origin=(0, 0)):
    """The banks tuple kernels take (raster.fragment): the colour targets,
    z, stencil and pattern rows (pattern_rows), with 1 x 1 dummies for what
    ``key`` does not use.  The z bank is made at its first use.  The banks
    are taken without waiting for queued raster work (Framebuffer.queued):
    the pass they are for is queued after it."""
    return (targets[0] if targets else _DUMMY_C,
            targets[1] if len(targets) > 1 else _DUMMY_C,
            fb.ensure_z(queued=True) if key.ztest else _DUMMY_Z,
            fb.queued("stencil") if key.stencil else _DUMMY_S,
            pattern_rows(pattern, origin[0], fb.width) if key.pattern else _SOLID)


def general(key):
    """The general variant of ``key``'s family: every per-fragment stage
    compiled in (z test and write, stencil test and write, logicop,
    afunction, pattern, writemask), with the fields that change what setup
    computes or how a colour is made kept as ``key`` has them (Gouraud,
    colour-map mode, two-sided, texture), and two that cost much when
    neutral: blending (the generic blend when ``key`` blends, none when it
    does not: its factor arithmetic made a neutral BF_ONE, BF_ZERO cost
    some 15 ns a fragment, twenty times a pass's) and the second colour
    buffer (the first buffer given twice defeats the span loop's
    vectorisation: 4.5 ns a fragment).  Run with the banks and parameters
    of :func:`neutral`, it draws exactly what ``key``'s own variant draws:
    one compiled kernel serves the raster states of the family while a
    state's own is compiled elsewhere (vgx_emulator/specialise.py)."""
    rgb = not key.cmode
    return key._replace(ztest=True, zwrite=True, color=True,
                        gouraud=key.gouraud and key.color, stencil=2,
                        blend=blend.GENERIC if rgb and key.blend else 0, logic=True,
                        atest=rgb, pattern=True, cmask=True)


_scratch = {}


def _scratch_bank(shape, dtype, fill=0):
    """A bank the general variant reads and writes back unchanged in place
    of one ``key`` does not use (its contents never matter), or the
    all-ones pattern row (``fill`` 1)."""
    k = (tuple(shape), np.dtype(dtype).str, fill)
    bank = _scratch.get(k)
    if bank is None:
        if len(_scratch) >= 8:           # a few window sizes at a time
            _scratch.clear()
        bank = _scratch[k] = np.full(shape, fill, dtype)
    return bank


def neutral(key, planes, ip, shape):
    """``(banks, parameters)`` with which the :func:`general` variant of
    ``key`` draws exactly what ``key``'s variant draws with ``planes`` and
    ``ip``: each stage ``key`` leaves off passes every fragment and
    changes nothing.  z: ZF_ALWAYS, zwritemask 0, on a scratch bank when
    ``key`` tests no z (and the stencil's zpass op is its pass op:
    stencil(3G), without a z-buffer a passing fragment takes the pass op);
    stencil: SF_ALWAYS, swritemask 0, on a scratch bank when off; colour:
    writemask 0 on a scratch bank when ``key`` writes none, all ones when
    it masks nothing; logicop LO_SRC; afunction AF_ALWAYS; an all-ones
    pattern (blending and the second colour buffer are as ``key`` has
    them: :func:`general`).  ``shape``:
    the window's (rows, columns), the size of the scratch banks and of the
    row the padded spans stay inside."""
    cb0, cb1, zb, sb, pat = planes
    p = ip.copy()
    if not key.color:
        cb0 = _scratch_bank(shape, np.uint32)
        p[fragment.P_CMASK] = 0
    elif not key.cmask:
        p[fragment.P_CMASK] = -1
    if not key.ztest:
        zb = _scratch_bank(shape, np.int32)
        p[fragment.P_ZFUNC] = depth.ZF_ALWAYS
        p[fragment.P_ZMAX] = 0
        p[fragment.P_ZX:fragment.P_ZA + 1] = p[fragment.P_PX:fragment.P_PA + 1]
    if not key.zwrite:
        p[fragment.P_ZMASK] = 0
    if not key.stencil:
        sb = _scratch_bank(shape, np.uint8)
        p[fragment.P_SFUNC] = depth.SF_ALWAYS
    if key.stencil != 2:
        p[fragment.P_SWMASK] = 0
    if not key.logic:
        p[fragment.P_LOGICOP] = blend.LO_SRC
    if not key.atest:
        p[fragment.P_AFUNC] = depth.AF_ALWAYS
    if not key.pattern:
        pat = _scratch_bank((1, shape[1]), np.uint8, 1)
        p[fragment.P_PATSIZE] = 1
    return (cb0, cb1, zb, sb, pat), p


def bank_shape(key, planes):
    """(rows, columns) of the window from a bank ``key`` uses, or None when
    it uses none (such a pass draws nothing)."""
    for used, bank in ((key.color, planes[0]), (key.ztest, planes[2]),
                       (key.stencil, planes[3])):
        if used:
            return bank.shape
    return None
