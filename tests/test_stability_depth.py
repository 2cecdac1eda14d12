"""Depth precision and shadow-map acne (docs/stability.md): the near/far
ratio against 16- and 24-bit z, and self-shadowing against bias at grazing
light.  Expected z from the depth mapping of docs/semantics.md §5."""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from banks import colour
from stability_helpers import (ZMIN, ZMAX, fresh, polygon)


# 4. depth precision: near/far ratio and 16- versus 24-bit z
DFAR, DFOV = 1000.0, 400
DCOLS, DPHASES = 128, 16
DREL = np.logspace(-8, 1, DCOLS)          # relative separations, one per column
RATIOS = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7]


def z_range(bits):
    """24 bits: the VGX's signed range; 16 bits: lsetdepth(0, 0xFFFF), the
    65536 levels a 16-bit z-buffer holds (the VGX itself has only 24)."""
    return (ZMIN, ZMAX) if bits == 24 else (0, 0xFFFF)


def depth_constant(near, bits):
    """K of zw = const - K / d (d = eye depth), perspective(3G) + docs/semantics.md §5."""
    lo, hi = z_range(bits)
    return DFAR * near * (hi - lo) / (DFAR - near)


def one_level(near, bits, d):
    """Relative separation s/d that moves zw by exactly one level at depth d
    (K (1/d - 1/(d + s)) = 1); inf when d .. far spans less than one level."""
    K = depth_constant(near, bits)
    rel = d / (K - d) if K > d else math.inf
    return rel if d * (1 + rel) < DFAR else math.inf


def _cell(j, k, d):
    """A quad at eye depth d covering pixel (j, k) of the DCOLS x DPHASES window."""
    c = 1.0 / math.tan(math.radians(DFOV / 20.0))

    def eye(v, n, aspect):
        return ((v + 0.5) / n * 2 - 1) * aspect / c * d
    x0, x1 = eye(j - 0.4, DCOLS, DCOLS / DPHASES), eye(j + 0.4, DCOLS, DCOLS / DPHASES)
    y0, y1 = eye(k - 0.4, DPHASES, 1.0), eye(k + 0.4, DPHASES, 1.0)
    polygon([(x0, y0, -d), (x1, y0, -d), (x1, y1, -d), (x0, y1, -d)])


def depth_separation(ratio, bits, d):
    """Plane A at depth d_k (row k: 16 phases across one z level) in red,
    then B at d_k (1 + DREL[j]) in green, ZF_LEQUAL: green shows where the
    two quantize alike.  Returns (green mask, predicted mask, measured
    relative separation from which every column is separable in every row)."""
    near = DFAR / ratio
    fresh()
    prefsize(DCOLS, DPHASES)
    winopen("depth")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(DFOV, DCOLS / DPHASES, near, DFAR)
    lo, hi = z_range(bits)
    if bits == 16:
        lsetdepth(lo, hi)
    subpixel(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    K = depth_constant(near, bits)
    finite = math.isfinite(one_level(near, bits, d))
    dk = np.array([1 / (1 / d - k / DPHASES / K) if finite else d * (1 + k * 1e-3)
                   for k in range(DPHASES)])
    cpack(0xFF0000FF)
    for k in range(DPHASES):
        for j in range(DCOLS):
            _cell(j, k, dk[k])
    dB = dk[:, None] * (1 + DREL[None, :])
    drawn = dB < DFAR * 0.9999
    cpack(0xFF00FF00)
    for k, j in zip(*np.nonzero(drawn)):
        _cell(j, k, dB[k, j])
    green = (colour() & 0xFFFFFF) == 0x00FF00
    mmode(MPROJECTION)
    P = np.asarray(getmatrix(), np.float64)      # the float32 matrix the pipeline uses
    mmode(MVIEWING)

    def q(depth):
        zw = (hi + lo) / 2 + (-depth * P[2, 2] + P[3, 2]) / depth * (hi - lo) / 2
        return np.clip(np.floor(zw + 0.5), lo, hi)
    kept = (-dB * P[2, 3] + P[3, 3]) - (-dB * P[2, 2] + P[3, 2]) >= 0    # far: w - z >= 0
    predicted = drawn & kept & (q(dB) <= q(dk[:, None]))
    bad = np.nonzero(green.any(axis=0))[0]
    measured = DREL[0] if len(bad) == 0 else (
        DREL[bad[-1] + 1] if bad[-1] + 1 < DCOLS and drawn[:, bad[-1] + 1].all() else math.inf)
    return green, predicted, measured


@pytest.mark.parametrize("bits", [24, 16])
@pytest.mark.parametrize("ratio", RATIOS)
def test_depth_separation_is_the_z_quantum(ratio, bits):
    """Two planes at depth d = far/10 and d (1 + s): which cells z-fight is
    exactly what the depth mapping and round-to-nearest predict, and the
    smallest separation that is safe whatever the phase is one z level
    (within one column step of the log grid)."""
    d = DFAR / 10
    green, predicted, measured = depth_separation(ratio, bits, d)
    assert (green == predicted).all(), (green != predicted).sum()
    level = one_level(DFAR / ratio, bits, d)
    step = DREL[1] / DREL[0]
    if math.isfinite(level):     # else less than a level lies between d and far
        assert level * (1 - 1 / DPHASES) / step <= measured <= level * step


def floor_fight(ratio, bits, sub, s=0.01, h=1.0, w=160, hgt=120):
    """A floor h below the eye and a second one s below it, drawn after it
    (ZF_LEQUAL): (floor pixels, pixels where the lower floor shows).  For the
    doc's table; each row of the floor has one depth, so rows fight whole."""
    fresh()
    prefsize(w, hgt)
    winopen("floor")
    RGBmode()
    gconfig()
    subpixel(sub)
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(DFOV, w / hgt, DFAR / ratio, DFAR)
    if bits == 16:
        lsetdepth(*z_range(16))
    czclear(0, getgdesc(GD_ZMAX))
    g = 2 * DFAR
    for y, word in ((-h, 0xFF0000FF), (-h - s, 0xFF00FF00)):
        cpack(word)
        polygon([(-g, y, 0), (g, y, 0), (g, y, -g), (-g, y, -g)])
    img = colour() & 0xFFFFFF
    return int(((img == 0x0000FF) | (img == 0x00FF00)).sum()), int((img == 0x00FF00).sum())


# 5. self-shadowing acne versus bias at grazing light angles
LS = 128                                 # the light's depth image
GR = 4.0                                 # the ground square is [-4, 4]^2


def light_depth(elev_deg, azim_deg=30.0):
    """The ground drawn from an infinite light (ortho, lookat) into the z-buffer
    only; returns (ModelView.Projection, light z image)."""
    from programs import shadowbuf as sb
    fresh()
    prefsize(LS, LS)
    winopen("light")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    e, a = math.radians(elev_deg), math.radians(azim_deg)
    to_light = np.array([math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a)])
    ext, dist = GR * math.sqrt(2), 20.0
    ortho(-ext, ext, -ext, ext, dist - 2 * ext, dist + 2 * ext)
    lookat(*(dist * to_light), 0.0, 0.0, 0.0, 0)
    subpixel(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    wmpack(0)
    polygon([(-GR, 0, -GR), (-GR, 0, GR), (GR, 0, GR), (GR, 0, -GR)])
    wmpack(0xFFFFFFFF)
    return sb.current_mvp(), sb.read_depth(LS, LS)


def acne(elev_deg, biases, n=160):
    """Fraction of ground points (random, seen by the light) that the shadow
    test ``z - bias > light z`` (nearest sample, Williams) wrongly puts in
    shadow, per bias; and the slope bound b* = 0.5 (|dz/dx| + |dz/dy|) + 0.5
    of the plane in light-window units (half a texel of slope plus half a z
    level), past which no point can be acne.  ``biases``: a list, or a
    function of b* giving one."""
    from programs import shadowbuf as sb
    mvp, zl = light_depth(elev_deg)
    x0, y0, z0 = sb.world_to_window(np.array([[1.0, 0, 0], [0, 0, 1.0], [0, 0, 0]]), mvp, LS, LS)
    J = np.array([[x0[0] - x0[2], x0[1] - x0[2]], [y0[0] - y0[2], y0[1] - y0[2]]])
    g = np.linalg.solve(J.T, np.array([z0[0] - z0[2], z0[1] - z0[2]]))
    bound = 0.5 * (abs(g[0]) + abs(g[1])) + 0.5
    rng = np.random.default_rng(7)
    m = 0.9 * GR
    p = np.stack((rng.uniform(-m, m, n * n), np.zeros(n * n), rng.uniform(-m, m, n * n)), -1)
    x, y, zp = sb.world_to_window(p, mvp, LS, LS)
    zs = sb.light_depth_at(zl, x, y)
    biases = biases(bound) if callable(biases) else biases
    return [float(np.mean(zp - b > zs)) for b in biases], bound


@pytest.mark.parametrize("elev", [60.0, 30.0, 10.0, 3.0, 1.0])
def test_acne_versus_bias_at_grazing_angles(elev):
    """No bias: about half the ground shadows itself (the nearest light
    sample is as often in front as behind).  A slope-scaled bias just past
    the bound removes every false shadow at every angle; half of it leaves
    many; the constant bias that is just enough at 60 degrees fails more and
    more towards grazing angles: b* - 1/2 grows as cot(elevation)."""
    _, bound60 = acne(60.0, [])
    (zero, half, enough, const60), bound = acne(
        elev, lambda b: [0.0, 0.5 * b, 1.01 * b, 1.01 * bound60])
    assert 0.35 <= zero <= 0.6
    assert half > 0.1
    assert enough == 0.0
    if elev <= 10.0:
        assert const60 > 0.3
    cot = math.tan(math.radians(60.0)) / math.tan(math.radians(elev))
    assert abs((bound - 0.5) / (bound60 - 0.5) / cot - 1) < 0.02
