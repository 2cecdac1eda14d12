"""blendfunction(3G) and logicop(3G) on packed 0xAABBGGRR words (docs/semantics.md §7).

Blend, per component (0..255 scaled to 0..1, 0 and 255 exact)::

    C = clamp(Cs * S + Cd * D, 0, 255), rounded to nearest

with S and D the factors below (s = source/incoming, d = destination):

==============  ===  ====================  ==============
name            val  factor                legal as
==============  ===  ====================  ==============
BF_ZERO          0   0                     s, d
BF_ONE           1   1                     s, d
BF_DC / BF_SC    2   dest / source RGBA    DC: s, SC: d
BF_MDC / BF_MSC  3   1 - dest / 1 - source MDC: s, MSC: d
BF_SA            4   source alpha          s, d
BF_MSA           5   1 - source alpha      s, d
BF_DA            6   dest alpha            s, d
BF_MDA           7   1 - dest alpha        s, d
BF_MIN_SA_MDA    8   min(SA, 1 - DA)       s
==============  ===  ====================  ==============

logicop: s = incoming word, d = stored word, bitwise on all 32 bits (RGB
mode) or on the index (colour-map mode); a logicop other than LO_SRC
replaces blending (left open by logicop(3G): docs/semantics.md §7).
"""
from ..jit import helper, inline

BF_ZERO, BF_ONE, BF_DC, BF_MDC, BF_SA, BF_MSA, BF_DA, BF_MDA, BF_MIN_SA_MDA = range(9)
BF_SC, BF_MSC = BF_DC, BF_MDC           # the same values as destination factors
(LO_ZERO, LO_AND, LO_ANDR, LO_SRC, LO_ANDI, LO_DST, LO_XOR, LO_OR,
 LO_NOR, LO_XNOR, LO_NDST, LO_ORR, LO_NSRC, LO_ORI, LO_NAND, LO_ONE) = range(16)

#: Each factor as terms in units of 1/255: (constant, own component of the
#: source, own component of the destination, source alpha, destination
#: alpha, min flag).  factor*255 = k0 + k1 Cs + k2 Cd + k3 As + k4 Ad, or
#: min(As, 255 - Ad) when the min flag is set.
_SRC_TERMS = {BF_ZERO: (0, 0, 0, 0, 0, 0), BF_ONE: (255, 0, 0, 0, 0, 0),
              BF_DC: (0, 0, 1, 0, 0, 0), BF_MDC: (255, 0, -1, 0, 0, 0),
              BF_SA: (0, 0, 0, 1, 0, 0), BF_MSA: (255, 0, 0, -1, 0, 0),
              BF_DA: (0, 0, 0, 0, 1, 0), BF_MDA: (255, 0, 0, 0, -1, 0),
              BF_MIN_SA_MDA: (0, 0, 0, 0, 0, 1)}
_DST_TERMS = {**_SRC_TERMS, BF_SC: (0, 1, 0, 0, 0, 0), BF_MSC: (255, -1, 0, 0, 0, 0)}


def factor_terms(code, is_src):
    """The terms of blendfunction factor ``code`` as a source (sfactr) or
    destination (dfactr) factor: BF_DC/BF_MDC as source and BF_SC/BF_MSC as
    destination share the values 2 and 3 (blendfunction(3G))."""
    return (_SRC_TERMS if is_src else _DST_TERMS)[code]


#: The pairs kernels are compiled for, so that their factor arithmetic folds
#: to what the pair needs: additive (Heidmann's lit passes), transparency,
#: premultiplied transparency, and the two modulations.  Any other pair runs
#: the generic kernel, which reads the terms from the parameter vector: the
#: number of compiled variants stays small whatever a program (or the test
#: suite, which tries every pair) uses.
FOLDED = {(BF_ONE, BF_ONE), (BF_SA, BF_MSA), (BF_ONE, BF_MSA), (BF_DC, BF_ZERO),
          (BF_ZERO, BF_SC)}
#: blendfunction(BF_ONE, BF_ZERO): the incoming colour replaces the stored one
#: (the default; no blend stage)
REPLACE = (BF_ONE, BF_ZERO)
GENERIC = -1


def key_code(sfactr, dfactr):
    """The RasterKey ``blend`` field of blendfunction(sfactr, dfactr) when
    blending is on: a folded pair's code, or GENERIC."""
    if (sfactr, dfactr) in FOLDED:
        return 1 + (sfactr << 4) + dfactr
    return GENERIC


def key_terms(code):
    """(source terms, destination terms) compiled into a kernel for a
    RasterKey ``blend`` field (placeholders for off and GENERIC)."""
    if code <= 0:
        return factor_terms(BF_ONE, True), factor_terms(BF_ZERO, False)
    return factor_terms((code - 1) >> 4, True), factor_terms((code - 1) & 15, False)


@helper
def _factor(t, cs, cd, sa, da):
    """factor * 255 for one component from its terms (all 0..255 ints)."""
    lin = t[0] + t[1] * cs + t[2] * cd + t[3] * sa + t[4] * da
    return min(sa, 255 - da) if t[5] != 0 else lin


#: x // 510 is (x * _DIV510) >> 32 for 0 <= x < 2**19 (the error, under
#: 2**-13, is less than the 1/510 by which x / 510 misses the next integer)
_DIV510 = -(-(1 << 32) // 510)


@inline
def blend_words(ts, td, src, dst, generic=False):
    """Blend the packed words ``src`` (incoming) and ``dst`` (stored) with the
    source and destination factor terms.  Per component, exactly:
    round(clamp(Cs * S + Cd * D, 0, 1) * 255) with C, S, D in 0..1 is
    ``min((2 (cs S' + cd D') + 255) // 510, 255)`` in integers (cs, S', ...
    scaled by 255), so the result does not depend on float rounding, and
    the loop vectorises.  ``generic`` (a constant: terms read at run time,
    the generic kernel) divides by a multiply and a shift (_DIV510): with
    the division its span loop did not vectorise (10.5 -> 1.3 ns a
    fragment), while a folded pair's is faster with it (LLVM narrows it,
    knowing the factors)."""
    sa = (src >> 24) & 0xFF
    da = (dst >> 24) & 0xFF
    out = 0
    for k in range(4):
        sh = 8 * k
        cs = (src >> sh) & 0xFF
        cd = (dst >> sh) & 0xFF
        num = cs * _factor(ts, cs, cd, sa, da) + cd * _factor(td, cs, cd, sa, da)
        x = 2 * num + 255
        out |= min((x * _DIV510) >> 32 if generic else x // 510, 255) << sh
    return out


@helper
def logic_op(op, s, d):
    """logicop(3G) ``op`` of the incoming ``s`` and stored ``d``, on 32 bits."""
    if op == LO_ZERO:
        r = 0
    elif op == LO_AND:
        r = s & d
    elif op == LO_ANDR:
        r = s & ~d
    elif op == LO_SRC:
        r = s
    elif op == LO_ANDI:
        r = ~s & d
    elif op == LO_DST:
        r = d
    elif op == LO_XOR:
        r = s ^ d
    elif op == LO_OR:
        r = s | d
    elif op == LO_NOR:
        r = ~(s | d)
    elif op == LO_XNOR:
        r = ~(s ^ d)
    elif op == LO_NDST:
        r = ~d
    elif op == LO_ORR:
        r = s | ~d
    elif op == LO_NSRC:
        r = ~s
    elif op == LO_ORI:
        r = ~s | d
    elif op == LO_NAND:
        r = ~(s & d)
    else:
        r = -1
    return r & 0xFFFFFFFF
