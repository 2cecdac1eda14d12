"""The geometry calls: mmode, matrix stacks, transformations, projections,
viewing, viewport (docs/semantics.md §1, §2).

Row vectors, premultiplication (``C <- T . C``), angles in tenths of degrees
for ``Angle`` arguments and float degrees for ``rot``.
"""
import math

import numpy as np

from vgx_emulator.errors import fail, warn
from vgx_emulator.geometry import stack as S

from . import constants as K
from ._current import angle, axis, glcall, integer, machine, num, screen_z, win

__all__ = ["mmode", "getmmode", "loadmatrix", "multmatrix", "getmatrix", "pushmatrix",
           "popmatrix", "translate", "scale", "rot", "rotate", "perspective", "ortho",
           "ortho2", "window", "lookat", "polarview", "viewport", "getviewport",
           "reshapeviewport", "pushviewport", "popviewport", "scrmask", "getscrmask",
           "lsetdepth", "lgetdepth", "setdepth", "getdepth"]

_MODES = {K.MSINGLE: "MSINGLE", K.MPROJECTION: "MPROJECTION", K.MVIEWING: "MVIEWING",
          K.MTEXTURE: "MTEXTURE"}


def _matrix_arg(call, m):
    """A C ``Matrix`` (float[4][4]): 16 numbers read in C's row-major order,
    so a flat list of 16 (the same memory) is accepted too (docs/decisions.md)."""
    try:
        a = np.array(m, dtype=np.float64)
    except (TypeError, ValueError):
        fail(call, "matrix is not numeric", "pass a 4x4 array of numbers")
    if a.ndim == 0:
        fail(call, f"matrix {m!r} is not an array", "pass a 4x4 array of numbers")
    if a.size != 16:
        fail(call, f"matrix has {a.size} elements", "a Matrix is 4x4 (16 floats)")
    return a.reshape(4, 4)


def _premultiply(call, t):
    w = win(call)
    ms = w.st.matrices
    ms.set_current(S.premultiply(t, ms.current()))
    machine.matrices_changed(w)


@glcall
def mmode(m):
    """mmode(3G): entering or leaving MSINGLE resets every matrix to identity
    and empties the stacks; moving among the multi-matrix modes keeps them."""
    w = win("mmode")
    m = integer("mmode", m, "matrix mode")
    if m not in _MODES:
        fail("mmode", f"unknown matrix mode {m}", "MSINGLE, MPROJECTION, MVIEWING, MTEXTURE")
    ms = w.st.matrices
    if (m == S.MSINGLE) != (ms.mode == S.MSINGLE):
        machine.state_change(w)     # lighting needs MVIEWING: draw what came before
        ms.reset()
    ms.mode = m
    machine.matrices_changed(w)


@glcall
def getmmode():
    """getmmode(3G): the matrix mode (MSINGLE, MPROJECTION, MVIEWING, MTEXTURE)."""
    return win("getmmode").st.matrices.mode


@glcall
def loadmatrix(m):
    """loadmatrix(3G): C <- m."""
    a = _matrix_arg("loadmatrix", m)
    w = win("loadmatrix")
    w.st.matrices.set_current(a.astype(np.float32))
    machine.matrices_changed(w)


@glcall
def multmatrix(m):
    """multmatrix(3G): C <- m . C."""
    _premultiply("multmatrix", _matrix_arg("multmatrix", m))


@glcall
def getmatrix(m=None):
    """getmatrix(3G): the current matrix of the mode (MPROJECTION: Projection).
    Given a writable 4x4 array (numpy, or lists as a port of C ``float m[4][4]``),
    fills it in place; else returns a new Matrix."""
    from .types import Matrix
    cur = win("getmatrix").st.matrices.current()
    if m is None:
        return Matrix(cur)
    if isinstance(m, np.ndarray) and m.size == 16 and m.flags.writeable:
        m[...] = cur.reshape(m.shape)
        return None
    if isinstance(m, list):               # C ``float m[4][4]`` ported as lists
        if len(m) == 4 and all(isinstance(r, list) and len(r) >= 4 for r in m):
            for i in range(4):
                m[i][:4] = [float(x) for x in cur[i]]
            return None
        if len(m) >= 16 and not any(isinstance(x, (list, tuple, np.ndarray)) for x in m):
            m[:16] = [float(x) for x in cur.ravel()]
            return None
    fail("getmatrix", "the array to fill is not a writable 4x4 array",
         "pass a 4x4 numpy array, 4 lists of 4 numbers, a list of 16, or nothing")


@glcall
def pushmatrix():
    """pushmatrix(3G): duplicate the top of the current stack (32 deep)."""
    w = win("pushmatrix")
    st = w.st.matrices.stack()
    if st is None:
        fail("pushmatrix", "MPROJECTION and MTEXTURE have no stack",
             "push in MSINGLE or MVIEWING")
    if len(st) >= K.MATRIXSTACKDEPTH:
        fail("pushmatrix", f"matrix stack is full (depth {len(st)})",
             f"at most {K.MATRIXSTACKDEPTH} matrices")
    st.append(st[-1].copy())


@glcall
def popmatrix():
    """popmatrix(3G): discard the top of the current stack."""
    w = win("popmatrix")
    ms = w.st.matrices
    st = ms.stack()
    if st is None:
        fail("popmatrix", "MPROJECTION and MTEXTURE have no stack",
             "pop in MSINGLE or MVIEWING")
    if len(st) <= 1:
        fail("popmatrix", "matrix stack is empty (depth 1)", "pop only what was pushed")
    st.pop()
    ms.serial += 1
    machine.matrices_changed(w)


@glcall
def translate(x, y, z):
    """translate(3G): premultiply the current matrix by a translation."""
    _premultiply("translate", S.translation(num("translate", x), num("translate", y),
                                            num("translate", z)))


@glcall
def scale(x, y, z):
    """scale(3G): negative factors mirror (and reverse polygon winding)."""
    _premultiply("scale", S.scaling(num("scale", x), num("scale", y), num("scale", z)))


@glcall
def rot(a, ax):
    """rot(3G): float degrees about 'x', 'y' or 'z' (right-hand rule)."""
    _premultiply("rot", S.rotation(num("rot", a, "angle"), axis("rot", ax)))


@glcall
def rotate(a, ax):
    """rotate(3G): Angle in tenths of degrees (a C short: _current.angle)."""
    _premultiply("rotate", S.rotation(angle("rotate", a) / 10.0, axis("rotate", ax)))


def _load_projection(call, m):
    w = win(call)
    if machine.picking is not None and machine.picking.multiplies(w):
        machine.picking.load_projection(w.st.matrices, m)   # times the pick matrix
    else:
        w.st.matrices.load_projection(m)
    machine.matrices_changed(w)


@glcall
def perspective(fovy, aspect, near, far):
    """perspective(3G): fovy in tenths of degrees (> 2 and < 1800); loads
    the projection (MSINGLE: the top of the single stack)."""
    fovy = angle("perspective", fovy, "fovy")
    aspect = num("perspective", aspect, "aspect")
    near = num("perspective", near, "near")
    far = num("perspective", far, "far")
    if not 2 < fovy < 1800:
        fail("perspective", f"fovy {fovy:g}", "fovy is in tenths of degrees, > 2 and < 1800")
    if not (math.isfinite(aspect) and aspect != 0):
        fail("perspective", f"aspect {aspect:g}", "a finite, non-zero width/height")
    if near == far or not math.isfinite(near + far):
        fail("perspective", f"near {near:g}, far {far:g}", "finite and different")
    if not (near > 0 and far > 0):
        # perspective(3G): near and far are "always positive", but no error is
        # listed and programs passed near = 0: computed as the library did
        warn("perspective", f"near {near:g}, far {far:g}: the man page asks for both > 0; "
             "the degenerate projection is loaded")
    _load_projection("perspective", S.perspective(fovy, aspect, near, far))


def _box(call, l, r, b, t, n=-1.0, f=1.0):
    vals = [num(call, v) for v in (l, r, b, t, n, f)]
    l, r, b, t, n, f = vals
    if not all(math.isfinite(v) for v in vals) or l == r or b == t or n == f:
        fail(call, "degenerate or non-finite volume", "left != right, bottom != top, "
             "near != far, all finite")
    return l, r, b, t, n, f


@glcall
def ortho(left, right, bottom, top, near, far):
    """ortho(3G): a parallel projection of the box; loaded as the projection
    (MSINGLE: the top of the stack)."""
    _load_projection("ortho", S.ortho(*_box("ortho", left, right, bottom, top, near, far)))


@glcall
def ortho2(left, right, bottom, top):
    """ortho2(3G): ortho with near = -1, far = 1."""
    _load_projection("ortho2", S.ortho(*_box("ortho2", left, right, bottom, top)))


@glcall
def window(left, right, bottom, top, near, far):
    """window(3G): perspective frustum."""
    l, r, b, t, n, f = _box("window", left, right, bottom, top, near, far)
    _load_projection("window", S.frustum(l, r, b, t, n, f))


@glcall
def lookat(vx, vy, vz, px, py, pz, twist):
    """lookat(3G): eye at v looking at p, twist in tenths of degrees (an
    Angle: _current.angle).  eye == reference point raises GLError
    (docs/semantics.md §2)."""
    v = [num("lookat", a) for a in (vx, vy, vz, px, py, pz)] + [angle("lookat", twist, "twist")]
    if not all(math.isfinite(a) for a in v):
        fail("lookat", "non-finite argument", "finite coordinates and twist")
    if v[0:3] == v[3:6]:
        fail("lookat", "the viewpoint and the reference point are the same",
             "they must differ")
    _premultiply("lookat", S.lookat(*v))


@glcall
def polarview(dist, azim, inc, twist):
    """polarview(3G): translate(0,0,-dist) rotate(-twist,'z')
    rotate(-inc,'x') rotate(-azim,'z'); azim, inc and twist are Angles
    (_current.angle)."""
    _premultiply("polarview", S.polarview(num("polarview", dist), angle("polarview", azim),
                                          angle("polarview", inc), angle("polarview", twist)))


# -- viewport ----------------------------------------------------------------
def _rect(call, l, r, b, t):
    l, r, b, t = (integer(call, v) for v in (l, r, b, t))
    if not (-32768 <= min(l, b) and max(r, t) <= 32767):
        fail(call, "coordinates outside the Screencoord range", "-32768..32767")
    if l > r or b > t:
        fail(call, f"({l}, {r}, {b}, {t}) is empty", "left <= right, bottom <= top")
    return (l, r, b, t)


@glcall
def viewport(left, right, bottom, top):
    """viewport(3G): x1, x2, y1, y2 inclusive; also resets scrmask to it."""
    r = _rect("viewport", left, right, bottom, top)
    w = win("viewport")
    machine.state_change(w)
    w.st.viewport = r
    w.st.scrmask = r


@glcall
def getviewport():
    """getviewport(3G): ``left, right, bottom, top = getviewport()``."""
    return win("getviewport").st.viewport


@glcall
def reshapeviewport():
    """reshapeviewport(3G): viewport and scrmask := the whole window."""
    w = win("reshapeviewport")
    machine.state_change(w)
    w.st.viewport = w.st.scrmask = (0, w.width - 1, 0, w.height - 1)


@glcall
def scrmask(left, right, bottom, top):
    """scrmask(3G): drawing and clears are bounded by viewport ∩ scrmask."""
    r = _rect("scrmask", left, right, bottom, top)
    w = win("scrmask")
    machine.state_change(w)
    w.st.scrmask = r


@glcall
def getscrmask():
    """getscrmask(3G): the screen mask as (left, right, bottom, top)."""
    return win("getscrmask").st.scrmask


@glcall
def pushviewport():
    """pushviewport(3G): save viewport, scrmask and depth range (8 deep)."""
    w = win("pushviewport")
    st = w.st
    if len(st.viewport_stack) >= K.VPSTACKDEPTH - 1:
        fail("pushviewport", "viewport stack is full", f"at most {K.VPSTACKDEPTH} entries")
    st.viewport_stack.append((st.viewport, st.scrmask, st.depth_range))


@glcall
def popviewport():
    """popviewport(3G): restore the viewport, screen mask and depth range
    pushviewport saved."""
    w = win("popviewport")
    st = w.st
    if not st.viewport_stack:
        fail("popviewport", "viewport stack is empty", "pop only what was pushed")
    machine.state_change(w)
    st.viewport, st.scrmask, st.depth_range = st.viewport_stack.pop()


def _setdepth(call, near, far):
    n = screen_z(call, near, "near")
    f = screen_z(call, far, "far")
    w = win(call)
    machine.state_change(w)
    w.st.depth_range = (n, f)


@glcall
def lsetdepth(near, far):
    """lsetdepth(3G): window z of the near and far clip planes; values are
    taken as C longs and clamped to GD_ZMIN..GD_ZMAX (_current.screen_z);
    near > far is allowed (reversed depth)."""
    _setdepth("lsetdepth", near, far)


@glcall
def setdepth(near, far):
    """setdepth(3G): the old Screencoord form of lsetdepth(3G)."""
    _setdepth("setdepth", near, far)


@glcall
def lgetdepth():
    """lgetdepth(3G): ``near, far = lgetdepth()``."""
    return win("lgetdepth").st.depth_range


@glcall
def getdepth():
    """getdepth(3G): the old form of lgetdepth(3G): ``near, far = getdepth()``."""
    return win("getdepth").st.depth_range
