"""The RGB lighting equation (docs/semantics.md §9, see lighting.py) as one numba
loop over a batch's lit vertices.

The numpy form of the same equation cost a dozen whole-array temporaries
per light and about 4 ms for five thousand vertices; this loop does the
normal transform, the divide by w and every light for one vertex at a time
in registers (0.2 ms).  Tables are built once per batch by
:func:`lighting.shade_rgb` from the lmdef property dicts:

- materials ``mtab`` (M, 14): Em (3), Am (3), Dm (3), Sm (3), ALPHA, SHININESS;
- lights ``ltab`` (L, 16): eye POSITION (4), LCOLOR (3), AMBIENT (3),
  eye SPOTDIRECTION (3), exponent, cos(spread), 1 when a spot (spread != 180);
- model ``lm`` (7): AMBIENT (3), LOCALVIEWER, k0, k1, k2 (ATTENUATION,
  ATTENUATION2).

``redirect`` (M,) is, per material row, the lmcolor(3G) target of a
vertex's colour when its COLOUR_SINCE_BIND flag is set: bit 0 emission,
1 ambient, 2 diffuse, 3 specular, 4 alpha (LMC_DIFFUSE and LMC_AD take
the colour's alpha).
"""
import math

from ..jit import njit

M_EM, M_AM, M_DM, M_SM, M_ALPHA, M_SH = 0, 3, 6, 9, 12, 13
MCOLS = 14
L_POS, L_COL, L_AMB, L_SPOT, L_EXPO, L_COS, L_ISSPOT = 0, 4, 7, 10, 13, 14, 15
LCOLS = 16
R_EM, R_AM, R_DM, R_SM, R_ALPHA = 1, 2, 4, 8, 16


@njit
def _byte(x):
    """[0, 1] -> [0, 255]; NaN stays NaN (the vertex is dropped with a warning)."""
    if x != x:
        return x
    return min(max(x, 0.0), 1.0) * 255.0


@njit
def _power(x, e):
    """x ** e; an integral exponent up to 128 (SHININESS is usually one) by
    repeated squaring, half the cost of the libm pow that was half of the
    lighting loop.  The product differs from pow in the last bits only."""
    n = int(e)
    if n == e and 0 < n <= 128:
        r = 1.0
        while n:
            if n & 1:
                r *= x
            x *= x
            n >>= 1
        return r
    return x ** e


@njit
def light_vertices(idx, eye4, recs, nmats, renorm, mtab, override_flag, redirect,
                   ltab, lm, sign, out):
    """out[i] = the lit RGBA (0..255) of each vertex i in idx.  eye4: (N, 4)
    eye-space positions; recs: (N, RECORD) attribute records (batch.py):
    the object-space normal (0:3), transformed by nmats[transform] and
    renormalised where renorm[transform]; the colour (3:7), redirected by
    lmcolor (redirect[material row]) when the flags (7) have
    ``override_flag``; the transform (8) and the material's row in mtab
    (13).  sign -1.0 lights the back (-N)."""
    local_viewer = lm[3] != 0.0
    k0 = lm[4]
    k1 = lm[5]
    k2 = lm[6]
    for i in idx:
        xf = int(recs[i, 8])
        # normal in eye space
        m = nmats[xf]
        ox = recs[i, 0]
        oy = recs[i, 1]
        oz = recs[i, 2]
        nx = ox * m[0, 0] + oy * m[1, 0] + oz * m[2, 0]
        ny = ox * m[0, 1] + oy * m[1, 1] + oz * m[2, 1]
        nz = ox * m[0, 2] + oy * m[1, 2] + oz * m[2, 2]
        if renorm[xf]:
            ln = math.sqrt(nx * nx + ny * ny + nz * nz)
            if ln > 0.0:
                nx /= ln
                ny /= ln
                nz /= ln
            else:
                nx = ny = nz = 0.0
        nx *= sign
        ny *= sign
        nz *= sign
        # position in eye space
        w = eye4[i, 3]
        if w != 0.0:
            px = eye4[i, 0] / w
            py = eye4[i, 1] / w
            pz = eye4[i, 2] / w
        else:
            px = py = pz = 0.0
        # material, with the lmcolor redirection
        mrow = int(recs[i, 13])
        t = mtab[mrow]
        redir = redirect[mrow]
        er, eg, eb = t[M_EM], t[M_EM + 1], t[M_EM + 2]
        ar, ag, ab = t[M_AM], t[M_AM + 1], t[M_AM + 2]
        dr, dg, db = t[M_DM], t[M_DM + 1], t[M_DM + 2]
        sr, sg, sb = t[M_SM], t[M_SM + 1], t[M_SM + 2]
        alpha = t[M_ALPHA]
        sh = t[M_SH]
        if redir != 0 and (int(recs[i, 7]) & override_flag) != 0:
            cr = recs[i, 3] / 255.0
            cg = recs[i, 4] / 255.0
            cb = recs[i, 5] / 255.0
            if redir & R_EM:
                er, eg, eb = cr, cg, cb
            if redir & R_AM:
                ar, ag, ab = cr, cg, cb
            if redir & R_DM:
                dr, dg, db = cr, cg, cb
            if redir & R_SM:
                sr, sg, sb = cr, cg, cb
            if redir & R_ALPHA:
                alpha = recs[i, 6] / 255.0
        r = er + ar * lm[0]
        g = eg + ag * lm[1]
        b = eb + ab * lm[2]
        # the viewer direction
        vx, vy, vz = 0.0, 0.0, 1.0
        if local_viewer:
            lv = math.sqrt(px * px + py * py + pz * pz)
            if lv > 0.0:
                vx, vy, vz = -px / lv, -py / lv, -pz / lv
            else:
                vx = vy = vz = 0.0
        # a light adds nothing to a vertex whose material (after lmcolor)
        # has no diffuse and no specular colour, unless the light has an
        # ambient colour and the material too: the ambient pass of a
        # multipass program, drawn with every light bound, skips them
        unlit = dr == 0.0 and dg == 0.0 and db == 0.0 and sr == 0.0 and sg == 0.0 and sb == 0.0
        no_ambient = ar == 0.0 and ag == 0.0 and ab == 0.0
        for j in range(ltab.shape[0]):
            L = ltab[j]
            if unlit and (no_ambient or (L[L_AMB] == 0.0 and L[L_AMB + 1] == 0.0
                                         and L[L_AMB + 2] == 0.0)):
                continue
            factor = 1.0
            if L[L_POS + 3] == 0.0:
                lx, ly, lz = L[L_POS], L[L_POS + 1], L[L_POS + 2]
                ll = math.sqrt(lx * lx + ly * ly + lz * lz)
                if ll > 0.0:
                    lx, ly, lz = lx / ll, ly / ll, lz / ll
                else:
                    lx = ly = lz = 0.0
            else:
                q = L[L_POS + 3]
                lx = L[L_POS] / q - px
                ly = L[L_POS + 1] / q - py
                lz = L[L_POS + 2] / q - pz
                d = math.sqrt(lx * lx + ly * ly + lz * lz)
                if d > 0.0:
                    lx, ly, lz = lx / d, ly / d, lz / d
                else:
                    lx = ly = lz = 0.0
                denom = k0 + k1 * d + k2 * d * d
                factor = 1.0 / denom if denom > 0.0 else 0.0
                if L[L_ISSPOT] != 0.0:
                    cosang = -(lx * L[L_SPOT] + ly * L[L_SPOT + 1] + lz * L[L_SPOT + 2])
                    if cosang >= L[L_COS]:
                        factor *= max(cosang, 0.0) ** L[L_EXPO]
                    else:
                        factor = 0.0
            ndotl = nx * lx + ny * ly + nz * lz
            diff = max(ndotl, 0.0)
            tr = ar * L[L_AMB] + dr * L[L_COL] * diff
            tg = ag * L[L_AMB + 1] + dg * L[L_COL + 1] * diff
            tb = ab * L[L_AMB + 2] + db * L[L_COL + 2] * diff
            if sh != 0.0 and ndotl > 0.0:
                hx, hy, hz = lx + vx, ly + vy, lz + vz
                hl = math.sqrt(hx * hx + hy * hy + hz * hz)
                if hl > 0.0:
                    hx, hy, hz = hx / hl, hy / hl, hz / hl
                else:
                    hx = hy = hz = 0.0
                spec = _power(max(nx * hx + ny * hy + nz * hz, 0.0), sh)
                tr += sr * L[L_COL] * spec
                tg += sg * L[L_COL + 1] * spec
                tb += sb * L[L_COL + 2] * spec
            r += factor * tr
            g += factor * tg
            b += factor * tb
        out[i, 0] = _byte(r)
        out[i, 1] = _byte(g)
        out[i, 2] = _byte(b)
        out[i, 3] = _byte(alpha)
