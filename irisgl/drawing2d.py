"""The old-style and 2-D drawing calls: circles and arcs, point-by-point
polygons (pmv/pdr/pclos), relative moves and draws, screen-aligned boxes,
shaded polygons, polygon modes, and a few old names (normal, gl_sincos,
getgpos).  Reference section 3.3; docs/drawing-2d-and-lines.md.

Circles and arcs lie in the z = 0 plane of object space and go through the
current matrices like any primitive: circ/arc are line strips (the line
width and style apply), circf/arcf polygons (polymode and pattern apply).
"""
import math

import numpy as np

from vgx_emulator.errors import fail
from vgx_emulator.geometry.assemble import CLOSEDLINE, LINE, POLYGON

from . import constants as K
from ._current import glcall, integer, machine, not_emulated, num, token, vec, win

__all__ = []


def _export(f):
    __all__.append(f.__name__)
    return f


_CONV = {"": num, "i": integer, "s": integer}


# -- circles and arcs ------------------------------------------------------------
#: segments of a full circle: enough that the polygon strays at most this
#: far (pixels) from the true circle, within [MIN_SEGMENTS, MAX_SEGMENTS]
SAGITTA = 0.25
MIN_SEGMENTS, MAX_SEGMENTS = 8, 256


def _screen_radius(w, x, y, r):
    """The radius in window pixels of a circle of radius r at (x, y) in the
    z = 0 plane, through the current matrices (the larger of its x and y
    extents; 0 when the matrices do not place it)."""
    st = w.st
    mv, pr = st.matrices.vertex_matrices()
    m = mv @ pr
    p = np.array([[x, y, 0.0, 1.0], [x + r, y, 0.0, 1.0], [x, y + r, 0.0, 1.0]]) @ m
    with np.errstate(all="ignore"):
        ndc = p[:, :2] / p[:, 3:4]
        l, rt, b, t = st.viewport
        px = ndc * 0.5 * np.array([rt - l + 1.0, t - b + 1.0])
        d = np.hypot(*(px[1:] - px[0]).T)
    d = d[np.isfinite(d)]
    return float(d.max()) if len(d) else 0.0


def segments_for(w, x, y, r, sweep=3600):
    """Number of chords of an arc of ``sweep`` tenths of degrees: the full
    circle gets ceil(pi / acos(1 - SAGITTA / r_px)) chords, clamped to
    [MIN_SEGMENTS, MAX_SEGMENTS], and an arc its share (at least 1)."""
    rp = _screen_radius(w, x, y, r)
    if rp > SAGITTA:
        a = math.acos(1.0 - SAGITTA / rp)     # 0 for a radius of 1e38 pixels
        n = math.ceil(math.pi / a) if a > 0 else MAX_SEGMENTS
    else:
        n = MIN_SEGMENTS
    n = min(max(n, MIN_SEGMENTS), MAX_SEGMENTS)
    return max(1, math.ceil(n * sweep / 3600.0))


def _arc_points(x, y, r, start, sweep, n):
    """n + 1 points from angle ``start`` over ``sweep`` (tenths of degrees),
    counter-clockwise, as (n + 1, 4) rows in z = 0."""
    a = np.radians((start + sweep * np.arange(n + 1) / n) / 10.0)
    out = np.zeros((n + 1, 4))
    out[:, 0] = x + r * np.cos(a)
    out[:, 1] = y + r * np.sin(a)
    out[:, 3] = 1.0
    return out


def _sweep(startang, endang):
    """arc(3G): counter-clockwise from startang to endang, so 100 -> 50 is
    almost a full circle.  The span is reduced to (0, 3600]; equal angles
    give no span (the arc is its start point)."""
    d = endang - startang
    if d == 0:
        return 0
    d %= 3600
    return 3600 if d == 0 else d


def _circle_args(call, conv, x, y, radius):
    x, y, r = (float(conv(call, v)) for v in (x, y, radius))
    if not all(math.isfinite(v) for v in (x, y, r)):
        fail(call, "a coordinate or radius is not finite", "finite numbers")
    return x, y, abs(r)


def _circ_call(name, fill_, conv):
    def c(x, y, radius):
        w = win(name)
        x, y, r = _circle_args(name, conv, x, y, radius)
        n = segments_for(w, x, y, r)
        pts = _arc_points(x, y, r, 0, 3600, n)[:-1]
        machine.primitive_array(w, POLYGON if fill_ else CLOSEDLINE, pts, name)
        w.st.gpos = None                     # the graphics position is undefined after it
    c.__name__ = name
    c.__doc__ = (f"{name}(3G): {'filled' if fill_ else 'outlined'} circle of the given "
                 "radius about (x, y) in the z = 0 plane, through the current matrices.")
    return _export(glcall(c))


def _arc_call(name, fill_, conv):
    def a(x, y, radius, startang, endang):
        w = win(name)
        x, y, r = _circle_args(name, conv, x, y, radius)
        s = integer(name, startang, "startang")
        sweep = _sweep(s, integer(name, endang, "endang"))
        n = segments_for(w, x, y, r, sweep) if sweep else 1
        pts = _arc_points(x, y, r, s, sweep, n)
        if fill_:
            pts = _arc_points(x, y, r, s, sweep, min(n, 254))   # + centre <= 256
            pts = np.vstack(([[x, y, 0.0, 1.0]], pts))      # a pie slice: the centre first
            machine.primitive_array(w, POLYGON, pts, name)
        else:
            machine.primitive_array(w, LINE, pts, name)
        w.st.gpos = None
    a.__name__ = name
    a.__doc__ = (f"{name}(3G): {'filled (pie slice)' if fill_ else 'outlined'} arc "
                 "counter-clockwise from startang to endang (tenths of degrees from "
                 "the x axis), z = 0, through the current matrices.")
    return _export(glcall(a))


circ, circi, circs = (_circ_call("circ" + s, False, _CONV[s]) for s in ("", "i", "s"))
circf, circfi, circfs = (_circ_call("circf" + s, True, _CONV[s]) for s in ("", "i", "s"))
arc, arci, arcs = (_arc_call("arc" + s, False, _CONV[s]) for s in ("", "i", "s"))
arcf, arcfi, arcfs = (_arc_call("arcf" + s, True, _CONV[s]) for s in ("", "i", "s"))


# -- point-by-point polygons, relative moves and draws ------------------------------
def _coords(call, conv, args, dim):
    if len(args) != dim:
        fail(call, f"{len(args)} coordinates", f"it takes {dim}")
    c = [float(conv(call, a)) for a in args]
    return (c[0], c[1], c[2] if dim == 3 else 0.0, 1.0)


def _gpos(w):
    g = w.st.gpos
    return g if g is not None else (0.0, 0.0, 0.0, 1.0)


def _rel(w, d):
    g = _gpos(w)
    return (g[0] + d[0], g[1] + d[1], g[2] + d[2], 1.0)


def _in_pmv(call, w):
    b = w.batch
    if b.open is None or b.open[0] != POLYGON:
        fail(call, "no polygon started", "start it with pmv (or rpmv)")


def _family(prefix, maker):
    for dim in (3, 2):
        for s in ("", "i", "s"):
            name = f"{prefix}{'2' if dim == 2 else ''}{s}"
            globals()[name] = _export(maker(name, dim, _CONV[s]))


def _pmv(name, dim, conv, relative=False):
    def f(*args):
        w = win(name)
        d = _coords(name, conv, args, dim)
        p = _rel(w, d) if relative else d
        machine.begin(w, POLYGON, name)
        machine.vertex(w, *p, name)
        w.st.gpos = p
    f.__name__ = name
    f.__doc__ = (f"{name}(3G): start a filled polygon at "
                 f"{'the graphics position + (dx, dy[, dz])' if relative else '(x, y[, z])'};"
                 " pdr adds points, pclos closes it.")
    return glcall(f)


def _pdr(name, dim, conv, relative=False):
    def f(*args):
        w = win(name)
        d = _coords(name, conv, args, dim)
        _in_pmv(name, w)
        p = _rel(w, d) if relative else d
        machine.vertex(w, *p, name)
        w.st.gpos = p
    f.__name__ = name
    f.__doc__ = (f"{name}(3G): the next point of the polygon started by pmv"
                 f"{' (relative to the graphics position)' if relative else ''}.")
    return glcall(f, inside=True)


_family("pmv", _pmv)
_family("pdr", _pdr)
_family("rpmv", lambda n, d, c: _pmv(n, d, c, True))
_family("rpdr", lambda n, d, c: _pdr(n, d, c, True))


def _close(name):
    def f():
        w = win(name)
        _in_pmv(name, w)
        machine.end(w, POLYGON, name)
    f.__name__ = name
    return f


pclos = _export(glcall(_close("pclos"), inside=True))
pclos.__doc__ = "pclos(3G): close and draw the polygon started by pmv."
spclos = _export(glcall(_close("spclos"), inside=True))
spclos.__doc__ = ("spclos(3G): obsolete; closes the polygon started by pmv as pclos "
                  "does (its per-vertex colours are Gouraud-shaded as usual).")


def _rmove(name, dim, conv):
    def f(*args):
        w = win(name)
        machine.move(w, _rel(w, _coords(name, conv, args, dim)))
    f.__name__ = name
    f.__doc__ = f"{name}(3G): move the graphics position by (dx, dy[, dz])."
    return glcall(f)


def _rdraw(name, dim, conv):
    def f(*args):
        w = win(name)
        machine.draw(w, _rel(w, _coords(name, conv, args, dim)), name)
    f.__name__ = name
    f.__doc__ = (f"{name}(3G): a line from the graphics position to the graphics "
                 "position + (dx, dy[, dz]), which becomes the graphics position.")
    return glcall(f)


_family("rmv", _rmove)
_family("rdr", _rdraw)


@_export
@glcall
def getgpos():
    """getgpos(3G): ``fx, fy, fz, fw = getgpos()``, the graphics position
    transformed by the current matrices (clip coordinates, with w); the
    origin when move/draw have not set it or a call left it undefined."""
    w = win("getgpos")
    mv, pr = w.st.matrices.vertex_matrices()
    with np.errstate(all="ignore"):
        p = np.asarray(_gpos(w), np.float64) @ (mv @ pr)
    return tuple(float(v) for v in p)


# -- screen-aligned boxes ---------------------------------------------------------
def _sbox_call(name, fill_, conv):
    def f(x1, y1, x2, y2):
        w = win(name)
        c = [float(conv(name, v)) for v in (x1, y1, x2, y2)]
        pts = _screen_box(w, c)
        if pts is None:
            return
        machine.primitive_array(w, POLYGON if fill_ else CLOSEDLINE, pts, name)
        w.st.gpos = None
    f.__name__ = name
    f.__doc__ = (f"{name}(3G): {'filled' if fill_ else 'outlined'} rectangle whose "
                 "sides stay parallel to the screen axes: the corners (x1, y1) and "
                 "(x2, y2), z = 0, go through the current matrices; the rectangle "
                 "between them cannot be rotated.")
    return _export(glcall(f))


def _screen_box(w, c):
    """Four object-space corners (4, 4) of the screen-aligned box with the
    given opposite corners: the corners are taken to normalised device
    coordinates, the box is built there and mapped back (None when the
    matrices cannot be inverted or a corner cannot be placed)."""
    mv, pr = w.st.matrices.vertex_matrices()
    m = mv @ pr
    a = np.array([[c[0], c[1], 0.0, 1.0], [c[2], c[3], 0.0, 1.0]]) @ m
    with np.errstate(all="ignore"):
        if not np.all(np.isfinite(a)) or np.any(a[:, 3] == 0):
            return None
        n = a / a[:, 3:4]
        z = n[0, 2]
        ndc = np.array([[n[0, 0], n[0, 1], z, 1.0], [n[1, 0], n[0, 1], z, 1.0],
                        [n[1, 0], n[1, 1], z, 1.0], [n[0, 0], n[1, 1], z, 1.0]])
        try:
            inv = np.linalg.inv(m)
        except np.linalg.LinAlgError:
            return None
        obj = ndc @ inv
    return obj if np.all(np.isfinite(obj)) else None


sbox, sboxi, sboxs = (_sbox_call("sbox" + s, False, _CONV[s]) for s in ("", "i", "s"))
sboxf, sboxfi, sboxfs = (_sbox_call("sboxf" + s, True, _CONV[s]) for s in ("", "i", "s"))


# -- shaded polygons ------------------------------------------------------------------
def _points(call, parray, n, dim):
    try:
        rows = list(parray)[:n]
    except TypeError:
        fail(call, "parray is not a sequence of points", f"pass n {dim}-D points")
    if len(rows) < n:
        fail(call, f"n = {n} but parray has {len(rows)} points", "n <= len(parray)")
    out = np.zeros((n, 4))
    out[:, 3] = 1.0
    for i, r in enumerate(rows):            # C reads the first dim values of each row
        try:
            v = [float(x) for x in list(r)[:dim]]
        except (TypeError, ValueError):
            fail(call, f"point {i} is not {dim} numbers", f"{dim} numbers per point")
        if len(v) < dim:
            fail(call, f"point {i} has {len(v)} coordinates", f"it takes {dim}")
        out[i, :dim] = v
    return out


def _splf_call(name, dim, conv):
    def f(n, parray, iarray):
        w = win(name)
        n = integer(name, n, "n")
        if n < 0 or n > 256:
            fail(name, f"n = {n}", "0..256 points (GD_NVERTEX_POLY)")
        pts = _points(name, parray, n, dim)
        if conv is integer and not np.all(pts[:, :dim] == np.round(pts[:, :dim])):
            fail(name, "parray holds non-integer coordinates", "integers for this form")
        try:
            idx = [integer(name, v, "colour index") for v in list(iarray)[:n]]
        except TypeError:
            fail(name, "iarray is not a sequence", "n colour indices")
        if len(idx) < n:
            fail(name, f"iarray has {len(idx)} indices", f"it takes n = {n}")
        if w.st.rgb:
            fail(name, "a colour-index polygon in RGB mode", "use splf in cmode")
        cols = [(float(i & 0xFFF), 0.0, 0.0, 0.0) for i in idx]
        if n:
            machine.primitive_array(w, POLYGON, pts, name, colours=cols)
            w.st.gpos = tuple(pts[0])
    f.__name__ = name
    f.__doc__ = (f"{name}(3G): a Gouraud-shaded filled polygon of n {dim}-D points, "
                 "point i in colour index iarray[i] (colour-map mode); the graphics "
                 "position becomes the first point.")
    return _export(glcall(f))


for _d in (3, 2):
    for _s in ("", "i", "s"):
        _c = _splf_call(f"splf{'2' if _d == 2 else ''}{_s}", _d, _CONV[_s])
        globals()[_c.__name__] = _c


# -- polygon modes and old names --------------------------------------------------------
_PYM = {K.PYM_FILL: "PYM_FILL", K.PYM_POINT: "PYM_POINT", K.PYM_LINE: "PYM_LINE",
        K.PYM_HOLLOW: "PYM_HOLLOW", K.PYM_LINE_FAST: "PYM_LINE_FAST"}


@_export
@glcall
def polymode(mode):
    """polymode(3G): how filled primitives are drawn: PYM_FILL, PYM_POINT (a
    point at each vertex), PYM_LINE/PYM_LINE_FAST (the outline, with line
    width and style), PYM_HOLLOW (a one-pixel solid outline; see
    docs/drawing-2d-and-lines.md for how it differs from the VGX's)."""
    w = win("polymode")
    m = token("polymode", mode, _PYM, "polygon mode")
    machine.state_change(w)
    w.st.polymode = m


_PYSM = {K.PYSM_OFF: "PYSM_OFF", K.PYSM_ON: "PYSM_ON", K.PYSM_SHRINK: "PYSM_SHRINK"}


@_export
@glcall
def polysmooth(mode):
    """polysmooth(3G): PYSM_OFF, PYSM_ON or PYSM_SHRINK.  The mode is kept;
    polygons are drawn aliased (docs/drawing-2d-and-lines.md)."""
    w = win("polysmooth")
    m = token("polysmooth", mode, _PYSM, "polysmooth mode")
    machine.state_change(w)
    w.st.polysmooth = m


@_export
@glcall(inside=True)
def normal(narray):
    """normal(3G): the old name of n3f: the current normal."""
    from .primitives import n3f
    n3f(vec("normal", list(narray)[:3] if _seq(narray) else narray, 3, "normal"))


def _seq(x):
    try:
        len(x)
        return True
    except TypeError:
        return False


@_export
@glcall(immediate=True)
def gl_sincos(ang):
    """gl_sincos(3G): ``s, c = gl_sincos(ang)``, the sine and cosine of an
    Angle in tenths of degrees (as single-precision floats)."""
    a = math.radians(integer("gl_sincos", ang, "angle") / 10.0)
    return float(np.float32(math.sin(a))), float(np.float32(math.cos(a)))


displacepolygon = _export(not_emulated(
    "displacepolygon", "displacepolygon(3G) says IRIS-4D G, GT, GTX, VGX and VGXT models "
    "do not support it"))
