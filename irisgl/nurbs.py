"""NURBS curves and trimmed NURBS surfaces: bgncurve, endcurve, nurbscurve,
bgnsurface, endsurface, bgntrim, endtrim, pwlcurve, setnurbsproperty,
getnurbsproperty (docs/nurbs.md).

A definition is collected between bgn*/end* and drawn at endcurve /
endsurface: curves as line strips, surfaces as triangles (or their edges,
patch outlines or isolines, per N_DISPLAY) through the current matrices, so
lighting, the z-buffer, stencil, patterns and texture apply as to any
polygon.  Control points and knots are copied at the call, as C copies them.
Offsets are in bytes, as in C: the element size is that of C's ``double``
(8), or the itemsize of a float32/float64 numpy array given as ctlarray.
"""
import math

import numpy as np

from vgx_emulator.errors import fail, warn
from vgx_emulator.geometry import nurbs as G

from . import constants as K
from ._current import glcall, integer, machine, num, win

__all__ = ["bgncurve", "endcurve", "nurbscurve", "bgnsurface", "nurbssurface", "endsurface",
           "bgntrim", "endtrim", "pwlcurve", "setnurbsproperty", "getnurbsproperty"]

#: getgdesc(GD_NURBS_ORDER) on the VGX; the lowest order drawn is 2 (linear)
MAX_ORDER = 8
#: trimming-loop closure tolerance (the Programming Guide's "10E-6")
CLOSE_TOL = 1e-5

_PROPS = {K.N_PIXEL_TOLERANCE: "N_PIXEL_TOLERANCE", K.N_CULLING: "N_CULLING",
          K.N_DISPLAY: "N_DISPLAY", K.N_ERRORCHECKING: "N_ERRORCHECKING",
          K.N_SUBDIVISIONS: "N_SUBDIVISIONS", K.N_S_STEPS: "N_S_STEPS",
          K.N_T_STEPS: "N_T_STEPS", K.N_TILES: "N_TILES"}
_DEFAULTS = {K.N_PIXEL_TOLERANCE: 50.0, K.N_CULLING: 0.0, K.N_DISPLAY: K.N_FILL,
             K.N_ERRORCHECKING: 0.0, K.N_SUBDIVISIONS: 0.0, K.N_S_STEPS: 0.0,
             K.N_T_STEPS: 0.0, K.N_TILES: 0.0}
_DISPLAY = {K.N_FILL: "N_FILL", K.N_OUTLINE_POLY: "N_OUTLINE_POLY",
            K.N_OUTLINE_PATCH: "N_OUTLINE_PATCH", K.N_ISOLINE_S: "N_ISOLINE_S"}

_SPACE = {K.N_V3D: "N_V3D", K.N_V3DR: "N_V3DR"}
_TRIM = {K.N_P2D: "N_P2D", K.N_P2DR: "N_P2DR"}
_SURF = {K.N_V3D: "N_V3D", K.N_V3DR: "N_V3DR", K.N_C4D: "N_C4D", K.N_C4DR: "N_C4DR",
         K.N_T2D: "N_T2D", K.N_T2DR: "N_T2DR"}
_ROLE = {K.N_V3D: "geom", K.N_V3DR: "geom", K.N_C4D: "colour", K.N_C4DR: "colour",
         K.N_T2D: "tex", K.N_T2DR: "tex"}


def _dims(type_):
    """Coordinates per control point: gl.h packs them in bits 2-5 of the type."""
    return (type_ >> 2) & 0xF


def _rational(type_):
    return bool(type_ & 1)


def _state(w):
    s = getattr(w, "nurbs", None)
    if s is None:
        s = w.nurbs = {"props": dict(_DEFAULTS), "open": None}
    return s


# -- argument readers ------------------------------------------------------------
def _knots(call, count, knots, order, what):
    n = integer(call, count, f"{what} knot count")
    o = integer(call, order, f"{what} order")
    if not 2 <= o <= MAX_ORDER:
        fail(call, f"{what} order {o}", f"2 <= order <= {MAX_ORDER} (GD_NURBS_ORDER)")
    if n < 2 * o:
        fail(call, f"{n} {what} knots for order {o} ({n - o} control points)",
             "knot count = control points + order, with at least order control points")
    try:
        k = np.asarray(knots, np.float64).ravel()
    except (TypeError, ValueError):
        fail(call, f"{what} knot array is not numeric", "pass an array of numbers")
    if k.size < n:
        fail(call, f"{what} knot array has {k.size} values", f"the count says {n}")
    k = k[:n].copy()
    if np.any(np.diff(k) < 0):
        fail(call, f"{what} knots decrease", "knots must be non-decreasing")
    if np.all(np.isfinite(k)) and not k[o - 1] < k[n - o]:
        fail(call, f"empty {what} parameter range [{k[o - 1]}, {k[n - o]}]",
             "knot[order-1] < knot[count-order]")
    return k, o


def _controls(call, ctlarray, offsets, counts, dims):
    """C control array -> (counts..., dims) float64, honouring byte offsets."""
    a = ctlarray
    if isinstance(a, np.ndarray) and a.dtype in (np.float32, np.float64):
        size = a.dtype.itemsize
        flat = a.ravel().astype(np.float64)
    else:
        size = 8                                   # C double
        try:
            flat = np.asarray(a, np.float64).ravel()
        except (TypeError, ValueError):
            fail(call, "ctlarray is not an array of numbers", "pass numbers")
    steps = []
    for off, what in offsets:
        o = integer(call, off, what)
        if o <= 0 or o % size:
            fail(call, f"{what} {o}", f"a positive multiple of {size} bytes (the element size)")
        steps.append(o // size)
    need = sum((c - 1) * s for c, s in zip(counts, steps)) + dims
    if flat.size < need:
        fail(call, f"ctlarray has {flat.size} values", f"the counts and offsets read {need}")
    idx = np.zeros((), np.int64)
    for c, s in zip(counts, steps):
        idx = idx[..., None] + np.arange(c) * s
    idx = idx[..., None] + np.arange(dims)
    return flat[idx]


# -- properties --------------------------------------------------------------------
@glcall
def setnurbsproperty(property, value):
    """setnurbsproperty(3G): set a NURBS display property of the current
    window (N_PIXEL_TOLERANCE, N_DISPLAY, N_CULLING, N_ERRORCHECKING)."""
    w = win("setnurbsproperty")
    p = integer("setnurbsproperty", property, "property")
    if p not in _PROPS:
        fail("setnurbsproperty", f"unknown property {property!r}",
             "allowed: " + ", ".join(_PROPS[k] for k in sorted(_PROPS)))
    v = num("setnurbsproperty", value, "value")
    if not math.isfinite(v):
        fail("setnurbsproperty", f"{_PROPS[p]} value {v}", "a finite number")
    if p == K.N_PIXEL_TOLERANCE and not v > 0:
        fail("setnurbsproperty", f"N_PIXEL_TOLERANCE {v}", "a length in pixels > 0")
    if p == K.N_DISPLAY and v not in _DISPLAY:
        fail("setnurbsproperty", f"N_DISPLAY value {v}",
             "N_FILL, N_OUTLINE_POLY, N_OUTLINE_PATCH or N_ISOLINE_S")
    _state(w)["props"][p] = float(np.float32(v))


@glcall
def getnurbsproperty(property):
    """getnurbsproperty(3G): ``value = getnurbsproperty(property)`` (a float)."""
    w = win("getnurbsproperty")
    p = integer("getnurbsproperty", property, "property")
    if p not in _PROPS:
        fail("getnurbsproperty", f"unknown property {property!r}",
             "allowed: " + ", ".join(_PROPS[k] for k in sorted(_PROPS)))
    return _state(w)["props"][p]


# -- curves ------------------------------------------------------------------------
def _open(call, kinds):
    w = win(call)
    s = _state(w)
    o = s["open"]
    if o is None or o["kind"] not in kinds:
        where = f"inside bgn{o['kind']}" if o else "outside any NURBS definition"
        fail(call, where, f"call it after bgn{kinds[0]}")
    return w, s, o


@glcall
def bgncurve():
    """bgncurve(3G): start a NURBS curve definition (only nurbscurve until endcurve)."""
    w = win("bgncurve")
    s = _state(w)
    if s["open"] is not None:
        fail("bgncurve", f"inside bgn{s['open']['kind']}", f"end{s['open']['kind']} first")
    s["open"] = {"kind": "curve", "curves": []}


@glcall
def nurbscurve(knot_count, knot_list, offset, ctlarray, order, type):
    """nurbscurve(3G): a NURBS curve: N_V3D/N_V3DR in space between
    bgncurve/endcurve, N_P2D/N_P2DR in parameter space inside bgntrim."""
    w = win("nurbscurve")
    s = _state(w)
    o = s["open"]
    trim = o is not None and o["kind"] == "trim"
    if o is None or o["kind"] not in ("curve", "trim"):
        fail("nurbscurve", "outside bgncurve/endcurve and bgntrim/endtrim",
             "a space curve goes in bgncurve, a trimming curve in bgntrim")
    t = integer("nurbscurve", type, "type")
    allowed = _TRIM if trim else _SPACE
    if t not in allowed:
        fail("nurbscurve", f"type {type!r} " + ("in a trimming loop" if trim else "in bgncurve"),
             "allowed: " + ", ".join(allowed.values()))
    k, order = _knots("nurbscurve", knot_count, knot_list, order, "curve")
    n = len(k) - order
    ctl = _controls("nurbscurve", ctlarray, [(offset, "offset")], [n], _dims(t))
    item = (k, order, ctl, _rational(t))
    if trim:
        if not (np.all(np.isfinite(k)) and np.all(np.isfinite(ctl))):
            warn("nurbscurve", "non-finite knot or control point: trimming curve dropped")
            return
        o["pieces"].append(_trim_piece(item))
    else:
        o["curves"].append(item)


@glcall
def endcurve():
    """endcurve(3G): draw the curve(s) as line strips with the current colour."""
    w, s, o = _open("endcurve", ("curve",))
    strips = []
    for k, order, ctl, rational in o["curves"]:
        h = G.homogeneous(ctl, rational)
        if not (np.all(np.isfinite(h)) and np.all(np.isfinite(k))):
            warn("nurbscurve", "non-finite knot or control point: curve not drawn")
            continue
        clipm = _clipm(w)
        if _culled(s, h, clipm):
            continue
        sc = G.screen_points(h, clipm, w.st.viewport)
        lengths = None if sc is None else np.linalg.norm(np.diff(sc, axis=0), axis=-1)
        m = G.cap(G.span_steps(k, order, lengths, s["props"][K.N_PIXEL_TOLERANCE]),
                  G.MAX_CURVE_SAMPLES)
        p = G.curve_points(k, order, h, G.params(k, order, m))
        strips.append(_euclid(p))
    s["open"] = None
    if strips:
        G.feed(machine, w, G.LINE, np.concatenate(strips),
               G.strip_prims([len(p) for p in strips]))


# -- surfaces ---------------------------------------------------------------------
@glcall
def bgnsurface():
    """bgnsurface(3G): start a NURBS surface definition."""
    w = win("bgnsurface")
    s = _state(w)
    if s["open"] is not None:
        fail("bgnsurface", f"inside bgn{s['open']['kind']}", f"end{s['open']['kind']} first")
    s["open"] = {"kind": "surface", "geom": None, "colour": None, "tex": None, "loops": []}


@glcall
def nurbssurface(scount, sknot, tcount, tknot, s_offset, t_offset, ctlarray,
                 sorder, torder, type):
    """nurbssurface(3G): the surface's shape (N_V3D/N_V3DR, exactly one) and
    optionally its colours (N_C4D/N_C4DR) and texture coordinates
    (N_T2D/N_T2DR), before or after the trimming loops."""
    w, s, o = _open("nurbssurface", ("surface",))
    t = integer("nurbssurface", type, "type")
    if t not in _SURF:
        fail("nurbssurface", f"type {type!r}", "allowed: " + ", ".join(_SURF.values()))
    role = _ROLE[t]
    if o[role] is not None:
        fail("nurbssurface", f"a second {_SURF[t]} surface",
             "one geometry, one colour and one texture surface per bgnsurface")
    if role == "colour" and not w.st.rgb:
        fail("nurbssurface", "an RGBA colour surface in colour-map mode", "use RGBmode")
    sk, so = _knots("nurbssurface", scount, sknot, sorder, "s")
    tk, to = _knots("nurbssurface", tcount, tknot, torder, "t")
    ctl = _controls("nurbssurface", ctlarray,
                    [(s_offset, "s_offset"), (t_offset, "t_offset")],
                    [len(sk) - so, len(tk) - to], _dims(t))
    o[role] = (sk, so, tk, to, ctl, _rational(t))


@glcall
def bgntrim():
    """bgntrim(3G): start a trimming loop (pwlcurve/nurbscurve pieces, head to tail).
    [S] Loops may come before or after the surface's nurbssurface calls, in
    any order until endsurface (bgnsurface(3G) lists no order; SGI's sgiflag
    trims first): they live in parameter space, apart from the shape."""
    w, s, o = _open("bgntrim", ("surface",))
    s["open"] = {"kind": "trim", "surface": o, "pieces": []}


@glcall
def pwlcurve(n, data_array, offset, type):
    """pwlcurve(3G): a piecewise linear trimming curve of n (s, t) points (N_ST)."""
    w, s, o = _open("pwlcurve", ("trim",))
    t = integer("pwlcurve", type, "type")
    if t != K.N_ST:
        fail("pwlcurve", f"type {type!r}", "N_ST")
    count = integer("pwlcurve", n, "n")
    if count < 2:
        fail("pwlcurve", f"{count} points", "at least 2")
    pts = _controls("pwlcurve", data_array, [(offset, "offset")], [count], 2)
    o["pieces"].append(pts)


def _trim_piece(item):
    k, order, ctl, rational = item
    m = np.full(len(G.spans(k, order)), G.TRIM_CURVE_PER_SPAN)
    p = G.curve_points(k, order, ctl, G.params(k, order, m))
    if rational:
        with np.errstate(all="ignore"):
            p = p[:, :2] / p[:, 2:3]
    return p


@glcall
def endtrim():
    """endtrim(3G): close the trimming loop.  With N_ERRORCHECKING on, pieces
    that do not join head to tail, or a loop that does not close, are an error."""
    w, s, o = _open("endtrim", ("trim",))
    pieces = o["pieces"]
    if not pieces:
        fail("endtrim", "an empty trimming loop", "give pwlcurve or nurbscurve pieces")
    check = s["props"][K.N_ERRORCHECKING] != 0
    parts = [pieces[0]]
    for prev, nxt in zip(pieces, pieces[1:]):
        gap = float(np.abs(nxt[0] - prev[-1]).max())
        if check and not gap <= CLOSE_TOL:
            fail("endtrim", f"trimming curves do not join (gap {gap:g})",
                 "the last point of each piece is the first of the next")
        parts.append(nxt[1:] if gap <= CLOSE_TOL else nxt)
    loop = np.concatenate(parts)
    gap = float(np.abs(loop[-1] - loop[0]).max())
    if check and not gap <= CLOSE_TOL:
        fail("endtrim", f"the trimming loop is not closed (gap {gap:g})",
             "repeat the first point at the end")
    if gap <= CLOSE_TOL and len(loop) > 1:
        loop = loop[:-1]
    surf = o["surface"]
    if not np.all(np.isfinite(loop)):
        warn("pwlcurve", "non-finite trimming point: trimming loop dropped")
    elif len(loop) >= 3:
        surf["loops"].append(loop)
    s["open"] = surf


@glcall
def endsurface():
    """endsurface(3G): draw the (trimmed) surface per N_DISPLAY, with normals
    from the surface's derivatives."""
    w, s, o = _open("endsurface", ("surface",))
    if o["geom"] is None:
        fail("endsurface", "no nurbssurface of type N_V3D or N_V3DR",
             "a surface needs exactly one geometry nurbssurface")
    work = _tessellate(w, s, o)
    s["open"] = None
    for kind, args in work:
        G.feed(machine, w, kind, *args)


# -- tessellation --------------------------------------------------------------------
def _clipm(w):
    mv, pr = w.st.matrices.vertex_matrices()
    return mv @ pr


def _culled(s, h, clipm):
    """N_CULLING: the whole definition lies outside one clipping plane (the
    convex hull of the control points is outside the viewport)."""
    if s["props"][K.N_CULLING] == 0:
        return False
    with np.errstate(all="ignore"):
        c = h.reshape(-1, 4) @ clipm
    x, y, z, cw = c[:, 0], c[:, 1], c[:, 2], c[:, 3]
    return any(np.all(v) for v in (x < -cw, x > cw, y < -cw, y > cw, z < -cw, z > cw))


def _euclid(h):
    with np.errstate(all="ignore"):
        p = h[:, :3] / h[:, 3:4]
    return np.concatenate((p, np.ones((len(p), 1))), axis=1)


def _at(surf, s, t):
    """An attribute surface at the geometry's parameters (clamped to its range)."""
    sk, so, tk, to, ctl, rational = surf
    s = np.clip(s, *G.domain(sk, so))
    t = np.clip(t, *G.domain(tk, to))
    v = G.surface(sk, so, tk, to, ctl, s, t)
    if rational:
        with np.errstate(all="ignore"):
            v = v[..., :-1] / v[..., -1:]
    return v.reshape(-1, v.shape[-1])


def _with_trim_vertices(sp, tp, loops):
    """Add the coordinates of the trimming edges that run along t (constant
    s) to the s samples, and those along s to the t samples (when they are
    few), so that straight trims along s or t are exact."""
    a = np.concatenate(loops)
    b = np.concatenate([np.roll(lp, -1, axis=0) for lp in loops])
    out = []
    for grid, ax in ((sp, 0), (tp, 1)):
        v = a[a[:, ax] == b[:, ax], ax]
        v = np.unique(v[(v > grid[0]) & (v < grid[-1])])
        out.append(np.union1d(grid, v) if len(v) <= G.TRIM_EXTRA else grid)
    return out


def _tessellate(w, s, o):
    """Everything endsurface draws, as [(kind, feed arguments)], computed
    before any state changes."""
    sk, so, tk, to, ctl, rational = o["geom"]
    h = G.homogeneous(ctl, rational)
    parts = [o[r] for r in ("geom", "colour", "tex") if o[r] is not None]
    if not all(np.all(np.isfinite(a)) for p in parts for a in (p[0], p[2], p[4])):
        warn("nurbssurface", "non-finite knot or control point: surface not drawn")
        return []
    clipm = _clipm(w)
    if _culled(s, h, clipm):
        return []
    props = s["props"]
    loops = o["loops"]
    tol, limit = props[K.N_PIXEL_TOLERANCE], G.MAX_SAMPLES
    mode = props[K.N_DISPLAY]
    if loops and mode != K.N_OUTLINE_POLY:
        # cells are kept or dropped whole: sample finely (N_OUTLINE_POLY
        # shows the tessellation at N_PIXEL_TOLERANCE itself)
        tol, limit = min(tol, G.TRIM_PIXELS), G.TRIM_MAX_SAMPLES
    sc = G.screen_points(h, clipm, w.st.viewport)
    ls = lt = None
    if sc is not None:
        ls = np.linalg.norm(np.diff(sc, axis=0), axis=-1).max(axis=1)
        lt = np.linalg.norm(np.diff(sc, axis=1), axis=-1).max(axis=0)
    sp = G.params(sk, so, G.cap(G.span_steps(sk, so, ls, tol), limit))
    tp = G.params(tk, to, G.cap(G.span_steps(tk, to, lt, tol), limit))
    if loops:
        sp, tp = _with_trim_vertices(sp, tp, loops)
    hh, hs, ht = G.surface(sk, so, tk, to, h, sp, tp, deriv=True)
    p, nrm = G.positions_normals(hh, hs, ht)
    ns, nt = len(sp), len(tp)
    pos = np.concatenate((p.reshape(-1, 3), np.ones((ns * nt, 1))), axis=1)
    nrm = nrm.reshape(-1, 3)
    S, T = np.meshgrid(sp, tp, indexing="ij")
    uv = np.stack((S.ravel(), T.ravel()), axis=1)
    col = tex = None
    if o["colour"] is not None:
        col = np.clip(_at(o["colour"], sp, tp), 0.0, 1.0) * 255.0
    if o["tex"] is not None:
        st2 = _at(o["tex"], sp, tp)
        tex = np.concatenate((st2, np.zeros((len(st2), 1)), np.ones((len(st2), 1))), axis=1)

    def pick(idx):
        """Feed arguments for vertex indices idx (P, k): one primitive per row."""
        flat = idx.ravel()
        k = idx.shape[1]
        prims = np.stack((np.arange(len(idx)) * k, np.full(len(idx), k)), axis=1)
        return (pos[flat], prims, nrm[flat], None if col is None else col[flat],
                None if tex is None else tex[flat], True)

    if mode in (K.N_FILL, K.N_OUTLINE_POLY):
        tri = G.grid_triangles(ns, nt)
        if loops:
            tri = tri[G.visible(uv[tri].mean(axis=1), loops)]
        return [(G.POLYGON if mode == K.N_FILL else G.CLOSEDLINE, pick(tri))]
    # line modes: grid segments (a, b), kept where their midpoint is visible
    grid = np.arange(ns * nt).reshape(ns, nt)
    if mode == K.N_ISOLINE_S:
        segs = [np.stack((grid[:, :-1].ravel(), grid[:, 1:].ravel()), axis=1)]
    else:                                       # N_OUTLINE_PATCH: knot lines
        si = np.nonzero(np.isin(sp, sk))[0]
        ti = np.nonzero(np.isin(tp, tk))[0]
        segs = [np.stack((grid[si, :-1].ravel(), grid[si, 1:].ravel()), axis=1),
                np.stack((grid[:-1, ti].ravel(), grid[1:, ti].ravel()), axis=1)]
    seg = np.concatenate(segs)
    if loops:
        seg = seg[G.visible(uv[seg].mean(axis=1), loops)]
    work = [(G.LINE, pick(seg))] if len(seg) else []
    if mode == K.N_OUTLINE_PATCH and loops:
        # the trimming curves, mapped onto the surface
        ds = (sp[-1] - sp[0]) / max(1, ns - 1)
        dt = (tp[-1] - tp[0]) / max(1, nt - 1)
        loops = [G.densify(lp, ds, dt) for lp in loops]
        q = np.concatenate(loops)
        s_, t_ = np.clip(q[:, 0], *G.domain(sk, so)), np.clip(q[:, 1], *G.domain(tk, to))
        bs, dbs = G.basis(sk, so, s_, True)
        bt, dbt = G.basis(tk, to, t_, True)
        hq = np.einsum("mi,mj,ijd->md", bs, bt, h)
        hsq = np.einsum("mi,mj,ijd->md", dbs, bt, h)
        htq = np.einsum("mi,mj,ijd->md", bs, dbt, h)
        pq, nq = G.positions_normals(hq[:, None], hsq[:, None], htq[:, None])
        posq = np.concatenate((pq[:, 0], np.ones((len(q), 1))), axis=1)
        prims = G.strip_prims([len(lp) for lp in loops])
        work.append((G.CLOSEDLINE, (posq, prims, nq[:, 0], None, None, True)))
    return work
