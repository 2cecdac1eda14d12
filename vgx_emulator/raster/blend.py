"""blendfunction(3G) and logicop(3G) on packed 0xAABBGGRR words (reference 7).

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

#: Each factor as terms in units of 1/255: (constant, own component of the
#: source, own component of the destination, source alpha, destination
#: alpha, min flag).  factor*255 = k0 + k1 Cs + k2 Cd + k3 As + k4 Ad, or
#: min(As, 255 - Ad) when the min flag is set.
_SRC_TERMS = {0: (0, 0, 0, 0, 0, 0), 1: (255, 0, 0, 0, 0, 0),
              2: (0, 0, 1, 0, 0, 0), 3: (255, 0, -1, 0, 0, 0),
              4: (0, 0, 0, 1, 0, 0), 5: (255, 0, 0, -1, 0, 0),
              6: (0, 0, 0, 0, 1, 0), 7: (255, 0, 0, 0, -1, 0),
              8: (0, 0, 0, 0, 0, 1)}
_DST_TERMS = {**_SRC_TERMS, 2: (0, 1, 0, 0, 0, 0), 3: (255, -1, 0, 0, 0, 0)}


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
FOLDED = {(1, 1), (4, 5), (1, 5), (2, 0), (0, 2)}
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
        return factor_terms(1, True), factor_terms(0, False)
    return factor_terms((code - 1) >> 4, True), factor_terms((code - 1) & 15, False)


@helper
def _factor(t, cs, cd, sa, da):
    """factor * 255 for one component from its terms (all 0..255 ints)."""
    lin = t[0] + t[1] * cs + t[2] * cd + t[3] * sa + t[4] * da
    return min(sa, 255 - da) if t[5] != 0 else lin


@inline
def blend_words(ts, td, src, dst):
    """Blend the packed words ``src`` (incoming) and ``dst`` (stored) with the
    source and destination factor terms.  Per component, exactly:
    round(clamp(Cs * S + Cd * D, 0, 1) * 255) with C, S, D in 0..1 is
    ``min((2 (cs S' + cd D') + 255) // 510, 255)`` in integers (cs, S', ...
    scaled by 255), so the result does not depend on float rounding, and
    the loop vectorises."""
    sa = (src >> 24) & 0xFF
    da = (dst >> 24) & 0xFF
    out = 0
    for k in range(4):
        sh = 8 * k
        cs = (src >> sh) & 0xFF
        cd = (dst >> sh) & 0xFF
        num = cs * _factor(ts, cs, cd, sa, da) + cd * _factor(td, cs, cd, sa, da)
        out |= min((2 * num + 255) // 510, 255) << sh
    return out


@helper
def logic_op(op, s, d):
    if op == 0:
        r = 0
    elif op == 1:
        r = s & d
    elif op == 2:
        r = s & ~d
    elif op == 3:
        r = s
    elif op == 4:
        r = ~s & d
    elif op == 5:
        r = d
    elif op == 6:
        r = s ^ d
    elif op == 7:
        r = s | d
    elif op == 8:
        r = ~(s | d)
    elif op == 9:
        r = ~(s ^ d)
    elif op == 10:
        r = ~d
    elif op == 11:
        r = s | ~d
    elif op == 12:
        r = ~s
    elif op == 13:
        r = ~s | d
    elif op == 14:
        r = ~(s & d)
    else:
        r = -1
    return r & 0xFFFFFFFF
