"""Matrix stacks and the matrices the IRIS GL calls build (docs/semantics.md §1, §2).

Row-vector convention: a point ``p = [x y z w]`` is transformed as ``p . M``;
the translation lives in row 3, the perspective-divide column is column 3.
Every modelling or viewing call builds ``T`` and *premultiplies* the current
matrix: ``C <- T . C``.  Matrices are stored as float32, as IRIS GL's
``Matrix`` is ``float[4][4]``; products are formed in float64 and rounded back
to float32 once.
"""
import math

import numpy as np

from ..errors import fp_quiet, fp_restore

MSINGLE, MPROJECTION, MVIEWING, MTEXTURE = 0, 1, 2, 3
STACK_DEPTH = 32           # MATRIXSTACKDEPTH

IDENTITY = np.eye(4, dtype=np.float32)


def as_matrix(m):
    """A C ``Matrix`` argument (m[row][col]) as a float32 4x4 array."""
    return np.array(m, dtype=np.float32).reshape(4, 4)


def premultiply(t, c):
    """``T . C`` in float64, stored as float32."""
    token = fp_quiet()          # non-finite matrices are reported at the flush
    try:
        return (np.asarray(t, np.float64) @ np.asarray(c, np.float64)).astype(np.float32)
    finally:
        fp_restore(token)


#: the float64 identity the modelling matrices start from (a copy of it and
#: a few element stores: a third of np.eye's time, 0.7 against 2.2 us)
_EYE64 = np.eye(4)


def translation(x, y, z):
    """translate(3G): identity with row 3 = (x, y, z, 1)."""
    m = _EYE64.copy()
    m[3, 0] = x
    m[3, 1] = y
    m[3, 2] = z
    return m


def scaling(x, y, z):
    """scale(3G): diag(x, y, z, 1)."""
    m = _EYE64.copy()
    m[0, 0] = x
    m[1, 1] = y
    m[2, 2] = z
    return m


_ROTATION_AXES = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}


def rotation(degrees, axis):
    """rot(3G)/rotate(3G): right-hand rotation about 'x', 'y' or 'z' (row vectors).
    A non-finite angle gives a NaN matrix, like any non-finite matrix call:
    the primitives drawn under it are dropped with a warning (porting
    conventions 5), where math.cos(inf) would raise ValueError."""
    a = math.radians(degrees)
    c, s = (math.cos(a), math.sin(a)) if math.isfinite(a) else (math.nan, math.nan)
    m = _EYE64.copy()
    i, j = _ROTATION_AXES[axis]
    m[i, i] = c
    m[i, j] = s
    m[j, i] = -s
    m[j, j] = c
    return m


def ortho(l, r, b, t, n, f):
    """ortho(3G) (and ortho2 with n = -1, f = 1)."""
    m = np.zeros((4, 4))
    m[0, 0] = 2.0 / (r - l)
    m[1, 1] = 2.0 / (t - b)
    m[2, 2] = -2.0 / (f - n)
    m[3] = (-(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n), 1.0)
    return m


def frustum(l, r, b, t, n, f):
    """window(3G): the perspective frustum."""
    m = np.zeros((4, 4))
    m[0, 0] = 2.0 * n / (r - l)
    m[1, 1] = 2.0 * n / (t - b)
    m[2] = ((r + l) / (r - l), (t + b) / (t - b), -(f + n) / (f - n), -1.0)
    m[3, 2] = -2.0 * f * n / (f - n)
    return m


def perspective(fovy_tenths, aspect, n, f):
    """perspective(3G): fovy in tenths of degrees, aspect = width / height.

    Written from cot(fovy/2) rather than through ``frustum``, so that
    near = 0, which programs of the time passed (the man page says near is
    "always positive" but lists no error), gives the degenerate matrix the
    library computed: every z maps to the far end of the depth range."""
    c = 1.0 / math.tan(math.radians(fovy_tenths / 20.0))
    m = np.zeros((4, 4))
    m[0, 0] = c / aspect
    m[1, 1] = c
    m[2, 2] = -(f + n) / (f - n)
    m[2, 3] = -1.0
    m[3, 2] = -2.0 * f * n / (f - n)
    return m


def _cross(a, b):
    """a x b of 3-vectors as tuples of floats (np.cross's formula)."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0])


def _length(a):
    """|a| of a 3-vector, summed in the order numpy's norm sums it."""
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def _unit(a):
    """a / |a| of a 3-vector; NaNs when |a| is 0 (a direction whose squares
    underflow: the matrix is then non-finite, and what is drawn under it
    dropped with a warning, as numpy's division made it)."""
    n = _length(a)
    if n == 0.0:
        return (math.nan, math.nan, math.nan)
    return (a[0] / n, a[1] / n, a[2] / n)


def lookat(vx, vy, vz, px, py, pz, twist_tenths):
    """lookat(3G) as ``T(-v) . R . Rz(-twist)`` (docs/semantics.md §2).

    A line of sight parallel to Y takes -Z as the up reference.  (The
    vectors are Python floats: numpy's norm and cross on 3-vectors cost
    20 us of bookkeeping a call, and lookat is called per pass.)
    """
    fwd = _unit((px - vx, py - vy, pz - vz))
    side = _cross(fwd, (0.0, 1.0, 0.0))
    if _length(side) < 1e-12 * max(1.0, abs(fwd[0]), abs(fwd[1]), abs(fwd[2])):
        side = _cross(fwd, (0.0, 0.0, -1.0))
    side = _unit(side)
    upv = _cross(side, fwd)
    r = _EYE64.copy()
    r[:3, 0] = side
    r[:3, 1] = upv
    r[:3, 2] = (-fwd[0], -fwd[1], -fwd[2])
    return translation(-vx, -vy, -vz) @ r @ rotation(-twist_tenths / 10.0, "z")


def polarview(dist, azim, inc, twist):
    """polarview(3G): translate(0,0,-dist); rotate(-twist,'z'); rotate(-inc,'x');
    rotate(-azim,'z') issued in that order (each premultiplies)."""
    m = translation(0, 0, -dist)
    for ang, ax in ((-twist, "z"), (-inc, "x"), (-azim, "z")):
        m = rotation(ang / 10.0, ax) @ m
    return m


class MatrixState:
    """The matrices of one window and the mmode(3G) rules.

    MSINGLE uses one stack whose top is the whole transformation; the
    multi-matrix modes use a ModelView stack plus single Projection and
    Texture matrices.  ``serial`` changes whenever a matrix that reaches the
    vertices changes, so the batcher knows when to record a new transform.
    """

    def __init__(self):
        self.mode = MSINGLE
        self.reset()

    def reset(self):
        """Every stack emptied, every matrix identity (mmode(3G), docs/semantics.md §2)."""
        self.single = [IDENTITY.copy()]
        self.modelview = [IDENTITY.copy()]
        self.projection = IDENTITY.copy()
        self.texture = IDENTITY.copy()
        self.serial = getattr(self, "serial", 0) + 1

    # -- the current matrix per mode -------------------------------------
    def current(self):
        if self.mode == MSINGLE:
            return self.single[-1]
        if self.mode == MVIEWING:
            return self.modelview[-1]
        if self.mode == MPROJECTION:
            return self.projection
        return self.texture

    def set_current(self, m):
        m = np.asarray(m, np.float32)
        if self.mode == MSINGLE:
            self.single[-1] = m
        elif self.mode == MVIEWING:
            self.modelview[-1] = m
        elif self.mode == MPROJECTION:
            self.projection = m
        else:
            self.texture = m
        self.serial += 1

    def stack(self):
        """The pushable stack of the current mode, or None (MPROJECTION/MTEXTURE)."""
        if self.mode == MSINGLE:
            return self.single
        if self.mode == MVIEWING:
            return self.modelview
        return None

    def load_projection(self, m):
        """perspective/ortho/window: load the single stack's top in MSINGLE,
        replace Projection in every multi-matrix mode."""
        m = np.asarray(m, np.float32)
        if self.mode == MSINGLE:
            self.single[-1] = m
        else:
            self.projection = m
        self.serial += 1

    # -- what the geometry engines use -----------------------------------
    def vertex_matrices(self):
        """(modelview, projection) as float64; MSINGLE gives (top, identity)."""
        if self.mode == MSINGLE:
            return self.single[-1].astype(np.float64), np.eye(4)
        return self.modelview[-1].astype(np.float64), self.projection.astype(np.float64)

    def modelview_matrix(self):
        """The matrix that takes object coordinates to eye coordinates."""
        return self.vertex_matrices()[0]
