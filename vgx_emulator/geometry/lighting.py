"""Lighting: definitions (lmdef), bindings (lmbind) and the lighting equation.

docs/semantics.md §9.  Per vertex, in eye space, RGB mode::

    C = Em + Am*Alm + sum_i Att_i * Spot_i * (Am*Ali + Dm*Ci*max(N.Li, 0)
                                              + Sm*Ci*max(N.Hi, 0)**sh)
    alpha = material ALPHA

Em/Am/Dm/Sm: material EMISSION/AMBIENT/DIFFUSE/SPECULAR; Alm: model AMBIENT;
Ali: light AMBIENT; Ci: light LCOLOR; sh: SHININESS (0 turns the specular term
off, docs/semantics.md §9).  Li is the unit vector to the light (its direction when
POSITION has w = 0); Hi = normalize(Li + V), V = (0, 0, 1) unless LOCALVIEWER.
Att_i = 1 / (k0 + k1 d + k2 d^2) for local lights only (model ATTENUATION,
ATTENUATION2); Spot_i = max(-Li.D, 0)**exponent inside the spread, 0 outside,
1 for spread 180 or an infinite light.  Components are clamped to [0, 1].
Choice where the sources are silent (documented in docs/decisions.md): the
specular term is 0 where N.Li <= 0, as in the GL Programming Guide's form.
TWOSIDE lights back faces with -N and BACKMATERIAL (MATERIAL when none bound).
Colour-map lighting (docs/semantics.md §9): index = amb + (diff-amb)*D + (spec-diff)*S
with D, S the summed diffuse and specular intensities, clamped to spec.
"""
import math

import numpy as np

from .. import pipeline
from ..errors import fail
from . import shade
from .batch import COLOUR_SINCE_BIND

DEFMATERIAL, DEFLIGHT, DEFLMODEL = 0, 100, 200
EMISSION, AMBIENT, DIFFUSE, SPECULAR, SHININESS, COLORINDEXES, ALPHA = 1, 2, 3, 4, 5, 6, 7
LCOLOR, POSITION, SPOTDIRECTION, SPOTLIGHT = 101, 102, 103, 104
LOCALVIEWER, ATTENUATION, ATTENUATION2, TWOSIDE = 201, 202, 203, 204
MATERIAL, BACKMATERIAL, LIGHT0, LMODEL = 1000, 1001, 1100, 1200     # lmbind targets
LMC_COLOR, LMC_EMISSION, LMC_AMBIENT, LMC_DIFFUSE, LMC_SPECULAR, LMC_AD, LMC_NULL = range(7)

#: property token -> (number of floats, default), one table per category.
PROPERTIES = {
    DEFMATERIAL: {EMISSION: (3, (0.0, 0.0, 0.0)), AMBIENT: (3, (0.2, 0.2, 0.2)),
                  DIFFUSE: (3, (0.8, 0.8, 0.8)), SPECULAR: (3, (0.0, 0.0, 0.0)),
                  SHININESS: (1, (0.0,)), COLORINDEXES: (3, (0.0, 127.5, 255.0)),
                  ALPHA: (1, (1.0,))},
    DEFLIGHT: {LCOLOR: (3, (1.0, 1.0, 1.0)), AMBIENT: (3, (0.0, 0.0, 0.0)),
               POSITION: (4, (0.0, 0.0, 1.0, 0.0)), SPOTDIRECTION: (3, (0.0, 0.0, -1.0)),
               SPOTLIGHT: (2, (0.0, 180.0))},
    DEFLMODEL: {AMBIENT: (3, (0.2, 0.2, 0.2)), LOCALVIEWER: (1, (0.0,)),
                ATTENUATION: (2, (1.0, 0.0)), ATTENUATION2: (1, (0.0,)),
                TWOSIDE: (1, (0.0,))},
}
CATEGORY_NAMES = {DEFMATERIAL: "DEFMATERIAL", DEFLIGHT: "DEFLIGHT", DEFLMODEL: "DEFLMODEL"}


def defaults(deftype):
    return {tok: tuple(d) for tok, (_, d) in PROPERTIES[deftype].items()}


def _is_number(v):
    try:
        float(v)
        return True
    except (TypeError, ValueError):
        return False


def parse_properties(call, deftype, np_count, props):
    """Read an lmdef property list up to LMNULL; returns {token: values}.

    ``np_count`` is the C ``np``, the number of floats including LMNULL.
    lmdef(3G) makes it a hint ("if np is zero, it is ignored"; a correct np
    only makes a network connection faster), so the list is read to LMNULL
    whatever np says: SGI's programs passed np too small (11 for a list of
    15) and too large (sizeof(array), in bytes).  A negative np is refused.
    Raises GLError for an unknown token, a short list or a missing LMNULL;
    nothing is changed by the caller in that case.
    """
    table = PROPERTIES[deftype]
    try:
        vals = [float(v) for v in props]
    except (TypeError, ValueError):
        bad = next(v for v in props if not _is_number(v))
        fail(call, f"property list holds {bad!r}, not a number",
             "tokens and their values as numbers, ending with LMNULL")
    if np_count < 0:
        fail(call, f"np = {np_count}", "np counts the floats including LMNULL, or is 0")
    out = {}
    i = 0
    while True:
        if i >= len(vals):
            fail(call, "property list does not end with LMNULL", "end it with LMNULL")
        tok = vals[i]
        if tok == 0.0:
            return out
        itok = int(tok)
        if itok != tok or itok not in table:
            fail(call, f"unknown {CATEGORY_NAMES[deftype]} property {tok:g}",
                 "allowed: " + ", ".join(str(t) for t in sorted(table)))
        n = table[itok][0]
        if i + 1 + n > len(vals):
            fail(call, f"property {itok} needs {n} values", "give them before LMNULL")
        v = tuple(vals[i + 1:i + 1 + n])
        if not np.all(np.isfinite(v)):
            fail(call, f"property {itok} has a non-finite value", "finite floats only")
        out[itok] = v
        i += 1 + n


def normal_matrix(mv):
    """3x3 matrix that takes object normals (row vectors) to eye space: the
    inverse transpose of ModelView's upper 3x3 (nmode(3G)).  A singular
    matrix (scale(1, 0, 1)) gets its cofactor matrix, which keeps a defined
    direction instead of NaN; a nearly singular one gets the cofactor matrix
    times the sign of the determinant, the direction of the inverse
    transpose, so a mirror stays a mirror (scale(1, 1, -1e-13) lights like
    scale(1, 1, -1)).  Returns (matrix, orthonormal?)."""
    m = np.ascontiguousarray(np.asarray(mv, np.float64)[:3, :3])
    key = m.tobytes()
    hit = _normal_cache.get(key)
    if hit is None:
        if len(_normal_cache) > 256:
            _normal_cache.clear()
        hit = _normal_cache[key] = _normal_matrix(m)
    return hit


_normal_cache = {}


def _normal_matrix(m):
    # rows of the cofactor matrix: the cross products of the other two rows
    cof = np.cross(m[[1, 2, 0]], m[[2, 0, 1]])
    det = float(np.dot(m[0], cof[0]))
    scale = np.abs(m).max() ** 3 if np.isfinite(m).all() else 0.0
    if scale > 0 and abs(det) > 1e-12 * scale:
        nm = cof / det
    elif det < 0:
        nm = -cof
    else:
        nm = cof
    ortho = bool(np.allclose(m @ m.T, np.eye(3), atol=1e-6))
    nm.setflags(write=False)
    return nm, ortho


class LightBinding:
    """A light definition bound to LIGHTi, with its position and spot
    direction in eye space as of the lmbind (or later lmdef) call."""

    __slots__ = ("index", "eye_position", "eye_spot")

    def __init__(self, index, props, modelview):
        self.index = index
        self.place(props, modelview)

    def place(self, props, modelview):
        mv = np.asarray(modelview, np.float64)
        self.eye_position = np.asarray(props[POSITION], np.float64) @ mv
        nm, _ = normal_matrix(mv)
        d = np.asarray(props[SPOTDIRECTION], np.float64) @ nm
        n = math.sqrt(float(d @ d))         # (what np.linalg.norm computes, without its checks)
        self.eye_spot = d / n if n > 0 else d


def _normalize(v):
    n = np.sqrt((v * v).sum(axis=1, keepdims=True))
    return np.divide(v, n, out=np.zeros_like(v), where=n > 0)


def _per_vertex(mats, mid, prop, n):
    """(n, k) values of a material property: one material (mid None) or the
    material of each vertex (mats[mid[i]])."""
    if mid is None:
        return np.broadcast_to(np.asarray(mats[0][prop], np.float64), (n, len(mats[0][prop])))
    return np.array([m[prop] for m in mats], np.float64)[mid]


def _shininess(mats, mid, n):
    """SHININESS: one scalar for one material, else (n,) per vertex."""
    if mid is None:
        return mats[0][SHININESS][0]
    return _per_vertex(mats, mid, SHININESS, n)[:, 0]


def _material_table(mats):
    """(M, shade.MCOLS) rows of material property dicts (the columns in
    shade's order: Em, Am, Dm, Sm, ALPHA, SHININESS)."""
    rows = [(*m[EMISSION], *m[AMBIENT], *m[DIFFUSE], *m[SPECULAR], m[ALPHA][0],
             m[SHININESS][0]) for m in mats]
    return np.array(rows, np.float64).reshape(len(mats), shade.MCOLS)


def _light_table(lights):
    """(L, shade.LCOLS) rows of [(props, LightBinding)] (the columns in
    shade's order: eye POSITION, LCOLOR, AMBIENT, eye SPOTDIRECTION,
    exponent, cos(spread), spot or not)."""
    rows = []
    for props, bind in lights:
        expo, spread = props[SPOTLIGHT]
        rows.append((*bind.eye_position, *props[LCOLOR], *props[AMBIENT], *bind.eye_spot,
                     expo, math.cos(math.radians(spread)), float(spread != 180.0)))
    return np.array(rows, np.float64).reshape(len(lights), shade.LCOLS)


def _model_row(model):
    k0, k1 = model[ATTENUATION]
    return np.array([*model[AMBIENT], model[LOCALVIEWER][0], k0, k1, model[ATTENUATION2][0]],
                    np.float64)


_REDIRECT = {LMC_EMISSION: shade.R_EM, LMC_AMBIENT: shade.R_AM,
             LMC_DIFFUSE: shade.R_DM | shade.R_ALPHA, LMC_SPECULAR: shade.R_SM,
             LMC_AD: shade.R_AM | shade.R_DM | shade.R_ALPHA}


def shade_rgb(geom, mats, lights, model, out, lmcolor=(LMC_COLOR,), sign=1.0):
    """The lighting equation for the vertices ``idx``: their (N, 4) colours
    in 0..255 are written into ``out`` rows idx.

    geom = (idx (n,) the lit vertices, eye4 (N, 4) eye-space positions,
    recs (N, RECORD) attribute records (normal, colour, flags, transform,
    material index into mats: batch.py), normal matrices (X, 3, 3),
    renormalise (X,) bool); mats: material property dicts; lights:
    [(props, LightBinding)]; model: light-model property dict.  A colour
    sent since the bind (COLOUR_SINCE_BIND) is redirected by ``lmcolor``,
    the lmcolor mode of each entry of mats (a vertex's material index);
    sign -1 lights -N (TWOSIDE back faces).  One numba loop
    (geometry/shade.py).
    """
    idx, eye4, recs, nmats, renorm = geom
    redirect = np.array([_REDIRECT.get(int(m), 0) for m in lmcolor], np.int64)
    if len(redirect) < len(mats):
        redirect = np.resize(redirect, len(mats))
    tables = (_material_table(mats), COLOUR_SINCE_BIND, redirect, _light_table(lights),
              _model_row(model), float(sign), out)
    # a large batch: shares of the lit vertices on the walker's threads
    pipeline.in_shares(lambda lo, hi: shade.light_vertices(idx[lo:hi], eye4, recs, nmats,
                                                           renorm, *tables),
                       len(idx), LIGHT_SHARE)


#: shade_rgb lights a batch of at least twice this many vertices in shares
#: of at least this many on the walker's threads (pipeline.in_shares)
LIGHT_SHARE = 4096


def shade_index(eye, normals, mats, lights, model, mid=None):
    """Colour-map lighting (docs/semantics.md §9): an index per vertex, in column 0.
    mats: material property dicts; mid (N,) each vertex's index in mats, or
    None when there is one."""
    n = len(eye)
    amb, dif, spe = _per_vertex(mats, mid, COLORINDEXES, n).T
    sh = _shininess(mats, mid, n)
    shiny = sh != 0.0
    dsum = np.zeros(n)
    ssum = np.zeros(n)
    v = np.broadcast_to((0.0, 0.0, 1.0), (n, 3))
    for props, bind in lights:
        p = bind.eye_position
        l = np.broadcast_to(_normalize(p[None, :3]), (n, 3))
        ndotl = (normals * l).sum(axis=1)
        dsum += np.maximum(ndotl, 0.0)
        if np.any(shiny):
            h = _normalize(l + v)
            ssum += np.where((ndotl > 0) & shiny,
                             np.maximum((normals * h).sum(axis=1), 0.0) ** sh, 0.0)
    idx = amb + (dif - amb) * np.minimum(dsum, 1.0) + (spe - dif) * np.minimum(ssum, 1.0)
    out = np.zeros((n, 4))
    out[:, 0] = np.minimum(idx, spe)
    return out
