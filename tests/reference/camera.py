"""The reference's viewing matrices rebuilt in float64, independent of the
library (reference section 2; row vectors, p' = p . M)."""
import math

import numpy as np


def lookat_matrix(v, p):
    """lookat(3G) with twist 0: T(-v) . R."""
    v, p = np.asarray(v, float), np.asarray(p, float)
    f = (p - v) / np.linalg.norm(p - v)
    s = np.cross(f, (0.0, 1.0, 0.0))
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    r = np.identity(4)
    r[:3, 0], r[:3, 1], r[:3, 2] = s, u, -f
    t = np.identity(4)
    t[3, :3] = -v
    return t @ r


def perspective_matrix(fovy, aspect, n, f):
    """perspective(3G), fovy in tenths of degrees."""
    c = 1.0 / math.tan(math.radians(fovy / 20.0))
    return np.array([[c / aspect, 0, 0, 0], [0, c, 0, 0],
                     [0, 0, -(f + n) / (f - n), -1], [0, 0, -2 * f * n / (f - n), 0]])
