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
replaces blending ([S], reference 7).
"""
import math

from ..jit import helper


@helper
def _factor(f, is_src, sc, dc, sa, da):
    """The factor for one component: sc, dc = this component of source and
    destination; sa, da = alphas (all 0..1)."""
    if f == 0:
        return 0.0
    if f == 1:
        return 1.0
    if f == 2:                 # BF_DC as source, BF_SC as destination
        return dc if is_src else sc
    if f == 3:                 # BF_MDC / BF_MSC
        return 1.0 - dc if is_src else 1.0 - sc
    if f == 4:
        return sa
    if f == 5:
        return 1.0 - sa
    if f == 6:
        return da
    if f == 7:
        return 1.0 - da
    return min(sa, 1.0 - da)    # BF_MIN_SA_MDA


@helper
def blend_words(fs, fd, src, dst):
    sa = ((src >> 24) & 0xFF) / 255.0
    da = ((dst >> 24) & 0xFF) / 255.0
    out = 0
    for k in range(4):
        sh = 8 * k
        sc = ((src >> sh) & 0xFF) / 255.0
        dc = ((dst >> sh) & 0xFF) / 255.0
        v = sc * _factor(fs, True, sc, dc, sa, da) + dc * _factor(fd, False, sc, dc, sa, da)
        iv = int(math.floor(min(max(v, 0.0), 1.0) * 255.0 + 0.5))
        out |= iv << sh
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
