"""Helpers of the numerical-stability tests (tests/test_stability_*.py, one
file per group of rows of docs/stability.md): windows, the region checks
with their unsure band, the vectorised fill-rule model, shared sizes."""
import math

import numpy as np

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from banks import colour, new_window, z_bank

ZMIN, ZMAX = -0x800000, 0x7FFFFF
F32MAX = float(np.finfo(np.float32).max)
MYZERO = 128                            # Heidmann's stencil zero
PW = PH = 128                           # the planar-shadow window
PS = 8.0                                # its top view sees the ground x, z in [-8, 8]
LW, LH = 64, 48                         # the hostile-input windows


def fresh():
    """Forget every window (several renders in one test; conftest resets the
    machine around each test)."""
    from irisgl._current import machine
    machine.reset()


def pixel_window(w, h, planes=0):
    """A fresh machine and a window whose ortho2 puts pixel (i, j)'s centre
    at object (i, j)."""
    fresh()
    new_window(w, h, planes=planes, pixels=True, name="stability")


def polygon(vs, call=v3f):
    bgnpolygon()
    for v in vs:
        call(v)
    endpolygon()


def sure_and_maybe(inside, xs, ys, eps=0.02):
    """(surely inside, possibly inside) pixel masks of a region given by the
    vectorised predicate ``inside(x, y)``: the centre and four points ``eps``
    pixels away must agree, else the pixel is on an edge that the 1/256 grid
    may move."""
    probes = [inside(xs + dx, ys + dy)
              for dx, dy in ((0, 0), (eps, 0), (-eps, 0), (0, eps), (0, -eps))]
    return np.logical_and.reduce(probes), np.logical_or.reduce(probes)


def assert_region(got, sure, maybe, max_unsure=0.05):
    """Drawn pixels contain every sure pixel and nothing outside the maybe
    set; the unsure band stays thin so that the check means something."""
    assert not (sure & ~got).any(), f"{(sure & ~got).sum()} pixels missing"
    assert not (got & ~maybe).any(), f"{(got & ~maybe).sum()} stray pixels"
    assert (maybe & ~sure).sum() <= max(16, max_unsure * sure.sum())


def assert_banks_sane(colours, untouched=None):
    """No garbage anywhere: every colour word is one of ``colours``, every z
    in the signed 24-bit range; pixels of ``untouched`` (mask) still hold the
    clear colour 0 and GD_ZMAX."""
    c = colour()
    assert set(np.unique(c).tolist()) <= set(colours)
    from irisgl._current import machine
    z = machine.current.fb.z
    if z is not None:
        zb = z_bank()
        assert ZMIN <= zb.min() and zb.max() <= ZMAX
        if untouched is not None:
            assert (zb[untouched] == ZMAX).all()
    if untouched is not None:
        assert (c[untouched] == 0).all()


def cover(tri, w, h, sub=True):
    """Vectorised fill-rule model (the rule of tests/reference/raster.py on
    the 1/256 grid, int64 edge functions): coverage mask (h, w) of one
    triangle given in window coordinates, no clipping (vertices within the
    guard band); ``sub`` False: vertices snapped to pixel centres."""
    if sub:
        p = [(math.floor(x * 256 + 0.5), math.floor(y * 256 + 0.5)) for x, y in tri]
    else:
        p = [(math.floor(x + 0.5) * 256, math.floor(y + 0.5) * 256) for x, y in tri]
    a, b, c = p
    area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if area == 0:
        return np.zeros((h, w), bool)
    if area < 0:
        b, c = c, b
    ys, xs = np.mgrid[0:h, 0:w].astype(np.int64) * 256
    out = np.ones((h, w), bool)
    for (px, py), (qx, qy) in ((a, b), (b, c), (c, a)):
        e = (qx - px) * (ys - py) - (qy - py) * (xs - px)
        owned = qy < py or (qy == py and qx > px)
        out &= (e > 0) | ((e == 0) & owned)
    return out


def top_view():
    """ModelView looking straight down on the ground: eye = (x, -z, y - 10)."""
    return [[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, -10, 1]]
