"""Curves and patches (docs/semantics.md §17): defbasis, curvebasis,
curveprecision, crv, crvn, rcrv, rcrvn, patchbasis, patchcurves,
patchprecision, patch, rpatch.

Curves and patch webs are drawn as ordinary line strips through the current
matrices (colour, z-buffer and the rest apply as for bgnline).  The basis
and precisions must be defined first.  ``vgx_emulator.surfaces`` adds the
emulator's own shaded-surface form of the same patches.
"""
import numpy as np

from vgx_emulator.errors import fail
from vgx_emulator.geometry import curves as C
from vgx_emulator.geometry.assemble import LINE

from ._current import glcall, integer, machine, win

__all__ = ["defbasis", "curvebasis", "curveprecision", "crv", "crvn", "rcrv", "rcrvn",
           "patchbasis", "patchcurves", "patchprecision", "patch", "rpatch", "curveit"]


def _state():
    m = machine
    if m.curve_state is None:
        m.curve_state = {"bases": {}, "curvebasis": None, "curveprecision": None,
                         "patchbasis": None, "patchcurves": None, "patchprecision": None}
    return m.curve_state


def _matrix(call, m, shape=(4, 4), what="matrix"):
    try:
        a = np.array(m, dtype=np.float64)
    except (TypeError, ValueError):
        fail(call, f"{what} is not numeric", f"a {shape} array of numbers")
    need = int(np.prod(shape))
    if a.size < need:
        fail(call, f"{what} has {a.size} elements", f"it takes {shape[0]}x{shape[1]}")
    # a longer C array (crv(&geom[i-2][0]) into a bigger table) is read from
    # its first elements, as C reads them
    return a.reshape(-1)[:need].reshape(shape)


@glcall
def defbasis(id, mat):
    """defbasis(3G): store basis matrix ``mat`` under ``id`` (immediate)."""
    i = integer("defbasis", id, "basis id")
    _state()["bases"][i] = _matrix("defbasis", mat)


def _basis(call, i):
    b = _state()["bases"].get(i)
    if b is None:
        fail(call, f"basis {i} is not defined", "defbasis it first")
    return b


@glcall
def curvebasis(id):
    """curvebasis(3G): the basis (a defbasis id) of the curves that follow."""
    i = integer("curvebasis", id, "basis id")
    _basis("curvebasis", i)
    _state()["curvebasis"] = i


@glcall
def curveprecision(n):
    """curveprecision(3G): each curve segment is drawn as n straight lines."""
    n = integer("curveprecision", n, "precision")
    if n < 1:
        fail("curveprecision", f"{n} segments", "at least 1")
    _state()["curveprecision"] = n


def _curve_setup(call):
    s = _state()
    if s["curvebasis"] is None or s["curveprecision"] is None:
        fail(call, "no curve basis or precision", "call curvebasis and curveprecision first")
    return _basis(call, s["curvebasis"]), s["curveprecision"]


def _draw_polylines(call, lines, moves=False):
    """Draw the polylines; ``moves``: the graphics position ends at the last
    point drawn (crv and its family).  [S] crv(3G) calls the position
    undefined afterwards; a program that draws on from it (Haeberli's
    curved.c: move2, crv, draw2) continues from the curve's end, where a
    pen drawing the curve would be."""
    w = win(call)
    pts = []
    for ln in lines:
        a = np.asarray(ln, np.float64)
        if a.shape[1] == 3:
            a = np.concatenate((a, np.ones((len(a), 1))), axis=1)
        pts.append([tuple(p) for p in a.tolist()])
    for p in pts:
        machine.polyline_vertices(w, LINE, p, call)
    if moves and pts and pts[-1]:
        w.st.gpos = pts[-1][-1]


@glcall
def crv(geom):
    """crv(3G): one curve segment from 4 control points (x, y, z)."""
    b, n = _curve_setup("crv")
    _draw_polylines("crv", [C.curve_points(b, _matrix("crv", geom, (4, 3), "geometry"), n)],
                    moves=True)


@glcall
def rcrv(geom):
    """rcrv(3G): rational curve from 4 homogeneous control points."""
    b, n = _curve_setup("rcrv")
    _draw_polylines("rcrv", [C.curve_points(b, _matrix("rcrv", geom, (4, 4), "geometry"), n)],
                    moves=True)


def _npoints(call, n, geom, k):
    n = integer(call, n, "n")
    g = _matrix(call, geom, (len(geom), k) if hasattr(geom, "__len__") else (0, k), "geometry")
    if n < 4 or n > len(g):
        fail(call, f"n = {n} with {len(g)} points", "4 <= n <= number of points")
    return g[:n]


@glcall
def crvn(n, geom):
    """crvn(3G): n points, n-3 segments from points (i .. i+3)."""
    b, prec = _curve_setup("crvn")
    _draw_polylines("crvn", C.curve_segments(b, _npoints("crvn", n, geom, 3), prec),
                    moves=True)


@glcall
def rcrvn(n, geom):
    """rcrvn(3G): a rational curve through n homogeneous control points
    (n - 3 segments in the current basis)."""
    b, prec = _curve_setup("rcrvn")
    _draw_polylines("rcrvn", C.curve_segments(b, _npoints("rcrvn", n, geom, 4), prec),
                    moves=True)


@glcall
def patchbasis(uid, vid):
    """patchbasis(3G): the bases (defbasis ids) of patches in u and in v."""
    u = integer("patchbasis", uid, "basis id")
    v = integer("patchbasis", vid, "basis id")
    _basis("patchbasis", u)
    _basis("patchbasis", v)
    _state()["patchbasis"] = (u, v)


@glcall
def patchcurves(ucurves, vcurves):
    """patchcurves(3G): how many curves a patch is drawn with in u and in v."""
    u = integer("patchcurves", ucurves)
    v = integer("patchcurves", vcurves)
    if u < 0 or v < 0 or u + v == 0:
        fail("patchcurves", f"({u}, {v}) curves", "non-negative, not both zero")
    _state()["patchcurves"] = (u, v)


@glcall
def patchprecision(usegments, vsegments):
    """patchprecision(3G): the least number of lines per patch curve in u and
    in v (rounded up to a multiple of the other direction's curve count)."""
    u = integer("patchprecision", usegments)
    v = integer("patchprecision", vsegments)
    if u < 1 or v < 1:
        fail("patchprecision", f"({u}, {v}) segments", "at least 1 each")
    _state()["patchprecision"] = (u, v)


def patch_setup(call):
    """(ubasis, vbasis, ucurves, vcurves, uprec, vprec) or GLError."""
    s = _state()
    if s["patchbasis"] is None or s["patchcurves"] is None or s["patchprecision"] is None:
        fail(call, "patch basis, curves or precision not set",
             "call patchbasis, patchcurves and patchprecision first")
    u, v = s["patchbasis"]
    return (_basis(call, u), _basis(call, v)) + s["patchcurves"] + s["patchprecision"]


def patch_bases(call):
    """(ubasis, vbasis) of the current patchbasis, or GLError."""
    s = _state()
    if s["patchbasis"] is None:
        fail(call, "no patch basis", "call patchbasis first")
    u, v = s["patchbasis"]
    return _basis(call, u), _basis(call, v)


@glcall
def patch(gx, gy, gz):
    """patch(3G): the web of curves of a bicubic patch (one matrix per coordinate)."""
    ub, vb, uc, vc, up, vp = patch_setup("patch")
    coords = [_matrix("patch", g) for g in (gx, gy, gz)]
    _draw_polylines("patch", C.patch_curves(ub, vb, coords, uc, vc, up, vp))


@glcall
def rpatch(gx, gy, gz, gw):
    """rpatch(3G): rational patch (homogeneous coordinates)."""
    ub, vb, uc, vc, up, vp = patch_setup("rpatch")
    coords = [_matrix("rpatch", g) for g in (gx, gy, gz, gw)]
    _draw_polylines("rpatch", C.patch_curves(ub, vb, coords, uc, vc, up, vp))


@glcall
def curveit(count):
    """curveit(3G): iterate the current matrix as a forward-difference matrix
    ``count`` times, drawing a line segment to its last row after each
    iteration (rows i = 3..1: row i += row i-1).  The top of the ModelView
    stack (MSINGLE: the single matrix) is iterated and the points go through
    the projection; the strip starts at row 3, where the move(0, 0, 0) that
    programs issue first puts the current point.  [S] the matrix itself is
    left unchanged (the hardware iterated a copy)."""
    n = integer("curveit", count, "count")
    if not 0 <= n <= 32767:
        fail("curveit", f"count {n}", "a count 0..32767 (a C short)")
    w = win("curveit")
    if n == 0:
        return
    mv, pr = w.st.matrices.vertex_matrices()
    pts = C.forward_differences(mv, n)
    machine.polyline_eye_vertices(w, LINE, pr, pts, "curveit")
