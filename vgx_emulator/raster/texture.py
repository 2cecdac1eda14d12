"""Texture sampling and the texture environment, per fragment (texdef2d(3G), tevdef(3G);
docs/semantics.md §16).

Sampling: texel (i, j) covers s in [i/W, (i+1)/W); POINT takes the texel
under (s, t); BILINEAR weights the four nearest texel centres.  TX_REPEAT
keeps the fractional part (texel indices modulo the size), TX_CLAMP smears
the edge texels.  Environments (Cin shaded colour, Ctex texel, 0..1):

========  =========================================  ==================
MODULATE  Cin.rgb * Ctex.rgb                          Ain * Atex
DECAL     Cin.rgb * (1 - Atex) + Ctex.rgb * Atex       Ain
BLEND     Cin.rgb * (1 - I) + Cconst.rgb * I           Ain * Atex
========  =========================================  ==================

With texels stored as (I, I, I, 255) / (I, I, I, A) / (R, G, B, 255) /
(R, G, B, A) these reproduce the table of docs/semantics.md §16 per component count
(DECAL is only defined for 3 and 4 components, BLEND for 1 and 2; the
machine substitutes MODULATE elsewhere).
"""
import math

from ..jit import helper

# slots of the texture parameter vector
T_WRAPS, T_WRAPT, T_ENV, T_CR, T_CG, T_CB, T_CA = range(7)
ENV_MODULATE, ENV_DECAL, ENV_BLEND = 0, 1, 2


@helper
def _wrap(i, n, repeat):
    if repeat:
        i = i % n
        if i < 0:
            i += n
        return i
    if i < 0:
        return 0
    if i >= n:
        return n - 1
    return i


@helper
def sample(texels, info, level, bilinear, s, t, rs, rt):
    """RGBA (0..255 floats) of level ``level`` at (s, t)."""
    off = info[1 + 3 * level]
    w = info[2 + 3 * level]
    h = info[3 + 3 * level]
    if not rs:
        s = min(max(s, 0.0), 1.0)
    if not rt:
        t = min(max(t, 0.0), 1.0)
    if not bilinear:
        i = _wrap(int(math.floor(s * w)), w, rs)
        j = _wrap(int(math.floor(t * h)), h, rt)
        k = off + j * w + i
        return (float(texels[k, 0]), float(texels[k, 1]), float(texels[k, 2]),
                float(texels[k, 3]))
    u = s * w - 0.5
    v = t * h - 0.5
    i0 = int(math.floor(u))
    j0 = int(math.floor(v))
    fu = u - i0
    fv = v - j0
    i1 = _wrap(i0 + 1, w, rs)
    j1 = _wrap(j0 + 1, h, rt)
    i0 = _wrap(i0, w, rs)
    j0 = _wrap(j0, h, rt)
    k00 = off + j0 * w + i0
    k10 = off + j0 * w + i1
    k01 = off + j1 * w + i0
    k11 = off + j1 * w + i1
    out = [0.0, 0.0, 0.0, 0.0]
    for c in range(4):
        a = texels[k00, c] * (1 - fu) + texels[k10, c] * fu
        b = texels[k01, c] * (1 - fu) + texels[k11, c] * fu
        out[c] = a * (1 - fv) + b * fv
    return out[0], out[1], out[2], out[3]


@helper
def environment(env, r, g, b, a, tr, tg, tb, ta, cr, cg, cb):
    """The texture environment; colours 0..255, constant colour 0..1."""
    if env == ENV_DECAL:
        f = ta / 255.0
        return r * (1 - f) + tr * f, g * (1 - f) + tg * f, b * (1 - f) + tb * f, a
    if env == ENV_BLEND:
        f = tr / 255.0
        return (r * (1 - f) + cr * 255.0 * f, g * (1 - f) + cg * 255.0 * f,
                b * (1 - f) + cb * 255.0 * f, a * ta / 255.0)
    return r * tr / 255.0, g * tg / 255.0, b * tb / 255.0, a * ta / 255.0
