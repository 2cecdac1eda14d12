"""The z-buffer (docs/semantics.md §5).

Depths are produced with ``ortho(-0.5, w-0.5, -0.5, h-0.5, -1, 1)``, whose z
row gives normalized z ``zn = -z`` (docs/semantics.md §2, ortho), and the lsetdepth
range maps ``zn`` to ``zs = (far+near)/2 + zn*(far-near)/2`` rounded to
nearest (docs/semantics.md §5).  Expected values are computed here from those rules;
z is read back with ``readsource(SRC_ZBUFFER)`` + ``lrectread``.
"""
import math
import operator
from fractions import Fraction

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import (FALSE, GD_ZMAX, GD_ZMIN, SRC_FRONT, SRC_ZBUFFER, TRUE, ZF_ALWAYS,
                    ZF_EQUAL, ZF_GEQUAL, ZF_GREATER, ZF_LEQUAL, ZF_LESS, ZF_NEVER,
                    ZF_NOTEQUAL, RGBmode, bgnpolygon, clear, cpack, czclear,
                    endpolygon, gconfig, getgdesc, lgetdepth, lrectread, lsetdepth, ortho,
                    prefsize, readsource, scrmask, subpixel, v3f, viewport, winopen, wmpack,
                    zbuffer, zclear, zfunction, zwritemask)
from banks import new_window
from reference import raster as ref

W, H = 32, 32
ZMIN, ZMAX = -0x800000, 0x7FFFFF
RED, GREEN, BLUE = 0xFF0000FF, 0xFF00FF00, 0xFFFF0000


def _window():
    """A W x H window whose ortho maps pixel centres to integers, z in -1..1."""
    new_window(W, H)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)


def _quad(zn, colour, x0=-0.5, x1=W - 0.5, y0=-0.5, y1=H - 0.5):
    """A rectangle at normalized depth zn (object z = -zn) in one colour."""
    cpack(colour)
    bgnpolygon()
    for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
        v3f((x, y, -zn))
    endpolygon()


def _z():
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, W - 1, H - 1)
    readsource(SRC_FRONT)
    return z


def _c():
    readsource(SRC_FRONT)
    return lrectread(0, 0, W - 1, H - 1)


def _zs(zn, near=ZMIN, far=ZMAX):
    """docs/semantics.md §5, exactly, rounded to nearest (no ties in these tests)."""
    v = Fraction(far + near, 2) + Fraction(zn) * Fraction(far - near, 2)
    assert v - math.floor(v) != Fraction(1, 2), "tie: pick another zn"
    return math.floor(v + Fraction(1, 2))


def _sign24(v):
    v &= 0xFFFFFF
    return v - 0x1000000 if v & 0x800000 else v


def _uniform(a, value):
    vals = np.unique(a)
    assert vals.tolist() == [value], vals[:8]


# --------------------------------------------------------------------------

def test_gd_z_range_is_signed_24_bit():
    assert getgdesc(GD_ZMIN) == ZMIN
    assert getgdesc(GD_ZMAX) == ZMAX


def test_zbuffer_off_no_test_no_write():
    _window()
    czclear(0, 100)
    zbuffer(FALSE)
    _quad(0.5, RED)             # zs far beyond 100: would fail ZF_LEQUAL
    _uniform(_c(), RED)
    _uniform(_z(), 100)


def test_zbuffer_on_tests_and_writes():
    _window()
    zbuffer(TRUE)
    czclear(0, 100)
    _quad(0.5, RED)             # 4194303 > 100: fails the default ZF_LEQUAL
    _uniform(_c(), 0)
    _uniform(_z(), 100)
    _quad(-0.5, GREEN)          # passes
    _uniform(_c(), GREEN)
    _uniform(_z(), _zs(-0.5))


def test_default_zfunction_is_lequal():
    _window()
    zbuffer(TRUE)
    zclear()
    _quad(0.25, RED)
    _quad(0.25, GREEN)          # equal: passes LEQUAL (not LESS)
    _uniform(_c(), GREEN)
    _quad(0.375, BLUE)          # farther: fails
    _uniform(_c(), GREEN)


RULES = {ZF_NEVER: lambda a, b: False, ZF_LESS: operator.lt, ZF_EQUAL: operator.eq,
         ZF_LEQUAL: operator.le, ZF_GREATER: operator.gt, ZF_NOTEQUAL: operator.ne,
         ZF_GEQUAL: operator.ge, ZF_ALWAYS: lambda a, b: True}


@pytest.mark.parametrize("func", sorted(RULES))
@pytest.mark.parametrize("z2", [-0.625, 0.25, 0.75])
def test_zfunction_incoming_func_stored(func, z2):
    """zfunction(3G): the fragment passes when ``incoming FUNC stored``."""
    _window()
    zbuffer(TRUE)
    zclear()
    z1 = 0.25
    _quad(z1, RED)                      # stored z1 (< ZMAX: passes ZF_LEQUAL)
    s1 = _zs(z1)
    _uniform(_z(), s1)
    zfunction(func)
    _quad(z2, GREEN)
    s2 = _zs(z2)
    passes = RULES[func](s2, s1)
    _uniform(_c(), GREEN if passes else RED)
    _uniform(_z(), s2 if passes else s1)


def test_zwritemask_zero_tests_but_does_not_write():
    _window()
    zbuffer(TRUE)
    czclear(0, 0)
    zwritemask(0)
    _quad(-0.5, RED)                    # passes (< 0), z not written
    _uniform(_c(), RED)
    _uniform(_z(), 0)
    _quad(-0.25, GREEN)                 # nearer than the stored 0, farther than RED's
    _uniform(_c(), GREEN)               # passes: the stored value is still 0
    _quad(0.25, BLUE)                   # fails against 0: the test still runs
    _uniform(_c(), GREEN)
    _uniform(_z(), 0)


@pytest.mark.parametrize("stored,mask,zn", [
    (-1000, 0x0F0F0F, 0.125),
    (0x123456, 0xFF0000, -0.875),
    (ZMAX, 0x00FFFF, -0.75),
    (0, 0x800000, -0.3125),
    (-5, 0xFFFFFE, 0.0625),
])
def test_zwritemask_per_bit(stored, mask, zn):
    """VGX: per-bit zwritemask; only the 1-bits of the 24-bit value change."""
    _window()
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    czclear(0, stored)
    zwritemask(mask)
    _quad(zn, RED)
    new = _zs(zn)
    _uniform(_z(), _sign24((stored & ~mask) | (new & mask)))


# --------------------------------------------------------------------------
# clears

def test_zclear_writes_gd_zmax():
    _window()
    czclear(0, -77)
    zclear()
    _uniform(_z(), getgdesc(GD_ZMAX))


@pytest.mark.parametrize("mask", [0xFFFFFF, 0, 0x00FF00, 0xF00000])
def test_zclear_honours_zwritemask_viewport_and_scrmask(mask):
    _window()
    czclear(0x11111111, -1234)
    viewport(4, 27, 2, 29)
    scrmask(6, 20, 5, 25)               # inside the viewport
    zwritemask(mask)
    zclear()
    z = _z()
    expected = np.full((H, W), -1234, np.int64)
    expected[5:26, 6:21] = _sign24((-1234 & ~mask) | (ZMAX & mask))
    np.testing.assert_array_equal(z, expected)
    _uniform(_c(), 0x11111111)          # colour untouched


def test_zclear_bounded_by_the_viewport():
    _window()
    czclear(0, 5)
    viewport(10, 19, 0, 7)
    zclear()
    expected = np.full((H, W), 5, np.int64)
    expected[0:8, 10:20] = ZMAX
    np.testing.assert_array_equal(_z(), expected)


def test_czclear_colour_then_z_ignoring_writemasks():
    _window()
    zwritemask(0)
    wmpack(0)
    czclear(0x80FF8040, 1234)           # colour first, then z
    _uniform(_c(), 0x80FF8040)
    _uniform(_z(), 1234)
    czclear(0x01020304, -4321)
    _uniform(_c(), 0x01020304)
    _uniform(_z(), -4321)


@pytest.mark.parametrize("zval,expected", [(0x7FFFFFFF, ZMAX), (ZMAX + 1, ZMAX),
                                           (-0x7FFFFFFF, ZMIN), (ZMIN - 1, ZMIN),
                                           (ZMIN, ZMIN), (ZMAX, ZMAX)])
def test_czclear_clamps_z(zval, expected):
    _window()
    czclear(0, zval)
    _uniform(_z(), expected)


def test_czclear_bounded_by_viewport_and_scrmask():
    _window()
    czclear(0, 0)
    viewport(3, 12, 4, 30)
    scrmask(5, 12, 4, 9)
    czclear(RED, 77)
    inside = np.zeros((H, W), bool)
    inside[4:10, 5:13] = True
    np.testing.assert_array_equal(_z(), np.where(inside, 77, 0))
    np.testing.assert_array_equal(_c(), np.where(inside, RED, 0).astype(np.uint32))


def test_clear_leaves_z_alone():
    _window()
    czclear(0, 42)
    cpack(GREEN)
    clear()
    _uniform(_z(), 42)
    _uniform(_c(), GREEN)


# --------------------------------------------------------------------------
# depth range

@pytest.mark.parametrize("near,far", [(ZMIN, ZMAX), (0, 1000), (-3000, 9001),
                                      (0, 0x7FFFFF), (5000, -5000), (ZMAX, ZMIN)])
@pytest.mark.parametrize("zn", [-1.0, -0.8125, -0.375, 0.3, 0.6875, 1.0])
def test_lsetdepth_mapping(near, far, zn):
    """docs/semantics.md §5: zs = (far+near)/2 + zn*(far-near)/2, rounded to nearest."""
    _window()
    lsetdepth(near, far)
    assert tuple(lgetdepth()) == (near, far)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    v = Fraction(far + near, 2) + Fraction(zn) * Fraction(far - near, 2)
    if v - math.floor(v) == Fraction(1, 2):
        pytest.skip("a rounding tie")
    _quad(zn, RED)
    z = _z()
    expected = _zs(zn, near, far)
    # 0.3 is not a binary fraction: allow for its float error only at a near-tie
    if abs(float(v) - math.floor(float(v)) - 0.5) < 1e-3:
        assert abs(int(z[0, 0]) - float(v)) <= 0.5 + 1e-3
    else:
        _uniform(z, expected)


def test_depth_range_defaults_to_the_full_signed_range():
    _window()
    assert tuple(lgetdepth()) == (ZMIN, ZMAX)


def test_lsetdepth_near_and_far_planes():
    _window()
    lsetdepth(-100, 300)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    _quad(-1.0, RED)
    _uniform(_z(), -100)
    _quad(1.0, RED)
    _uniform(_z(), 300)


def test_a_z_outside_the_vgx_range_is_clamped_with_a_warning():
    """An AIX-style lsetdepth(0xC00000, 0x3FFFFF) (unsigned 24-bit z) is
    outside GD_ZMIN..GD_ZMAX: clamped, and said, at the program's line."""
    import warnings
    _window()
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        lsetdepth(0xC00000, 0x3FFFFF)
        lsetdepth(0, ZMAX)                          # in range: nothing said
    assert tuple(lgetdepth()) == (0, ZMAX)
    assert [str(x.message).split(":")[0] for x in w] == ["lsetdepth"]
    assert "near 12582912 is outside" in str(w[0].message) and w[0].filename == __file__


def test_z_arguments_are_c_longs():
    """lsetdepth(3G) and czclear(3G) take C longs: a hex constant past
    2**31 is the 32-bit value C passes (0xff800000 = -0x800000, GD_ZMIN).
    A Personal IRIS program's reversed depth with GEQUAL, cleared that way,
    draws its surfaces."""
    _window()
    lsetdepth(0xff800000, 0x7fffff)
    assert tuple(lgetdepth()) == (ZMIN, ZMAX)
    lsetdepth(0x7fffff, 0x0ff)
    zbuffer(TRUE)
    zfunction(ZF_GEQUAL)
    czclear(0, 0xff800000)
    _uniform(_z(), ZMIN)
    _quad(0.0, RED)
    _uniform(_c(), RED)


@pytest.mark.parametrize("order", ["near-first", "far-first"])
def test_reversed_depth_range_with_gequal(order):
    """lsetdepth(ZMAX, ZMIN) + ZF_GEQUAL + clear to ZMIN: the nearer surface
    wins whatever the drawing order (docs/semantics.md §5, the documented idiom)."""
    _window()
    lsetdepth(ZMAX, ZMIN)
    zbuffer(TRUE)
    zfunction(ZF_GEQUAL)
    czclear(0, ZMIN)
    near_z, far_z = -0.5, 0.5
    if order == "near-first":
        _quad(near_z, RED)
        _quad(far_z, GREEN)
    else:
        _quad(far_z, GREEN)
        _quad(near_z, RED)
    _uniform(_c(), RED)
    expected = _zs(near_z, ZMAX, ZMIN)
    assert expected > _zs(far_z, ZMAX, ZMIN)
    _uniform(_z(), expected)


# --------------------------------------------------------------------------
# reading z back (docs/semantics.md §5)

def test_lrectread_z_is_signed_int32():
    _window()
    czclear(0, -1234567)
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, W - 1, H - 1)
    assert z.dtype == np.int32
    assert z.shape == (H, W)
    _uniform(z, -1234567)


def test_lrectread_z_into_a_given_array_gives_twos_complement_words():
    _window()
    czclear(0, -2)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    _quad(0.5, RED, x0=-0.5, x1=9.5)            # columns 0..9 at zs(0.5)
    readsource(SRC_ZBUFFER)
    buf = np.zeros(W * H, np.uint32)
    n = lrectread(0, 0, W - 1, H - 1, buf)
    assert n == W * H
    img = buf.reshape(H, W)
    assert (img[:, 10:] == (-2) & 0xFFFFFFFF).all()
    assert (img[:, :10] == _zs(0.5)).all()


def test_lrectread_z_sub_rectangle_rows_from_the_bottom():
    _window()
    czclear(0, 0)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    _quad(-0.5, RED, y0=-0.5, y1=3.5)           # rows 0..3
    readsource(SRC_ZBUFFER)
    z = lrectread(2, 2, 5, 6)
    assert z.shape == (5, 4)
    want = np.array([[_zs(-0.5)] * 4] * 2 + [[0] * 4] * 3)
    np.testing.assert_array_equal(z, want)


# --------------------------------------------------------------------------
# interpolation and hidden surfaces

def _assert_z_exact(z, placed, vz):
    """Every pixel of the placed triangle holds its exact screen-linear z
    (vertex values vz) rounded to nearest, with 1/100 of slack for the
    fixed-point planes; every other pixel still holds GD_ZMAX."""
    pix = ref.triangle_pixels(*placed, W, H)
    for x in range(W):
        for y in range(H):
            if (x, y) in pix:
                wts = ref.barycentric(*placed, x, y)
                exact = sum(wt * zz for wt, zz in zip(wts, vz))
                assert abs(int(z[y, x]) - exact) <= Fraction(1, 2) + Fraction(1, 100), (x, y)
            else:
                assert z[y, x] == ZMAX


def _draw_exact_triangle(vs):
    """One triangle of (x, y, zn) vertices with sub-pixel positions, the
    range lsetdepth(-1000000, 1000000) and ZF_ALWAYS.  Returns the z bank,
    the placed vertices and the exact vertex z values."""
    _window()
    subpixel(TRUE)
    lsetdepth(-1000000, 1000000)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    cpack(RED)
    bgnpolygon()
    for x, y, zn in vs:
        v3f((x, y, -zn))
    endpolygon()
    placed = ref.place([(x, y) for x, y, _ in vs])
    return _z(), placed, [Fraction(zn) * 1000000 for _, _, zn in vs]


def test_z_interpolated_linearly_in_screen_space():
    z, placed, vz = _draw_exact_triangle([(1.25, 2.5, -0.9), (30.75, 6.0, 0.7),
                                          (11.5, 30.25, 0.1)])
    _assert_z_exact(z, placed, vz)


def test_sliver_z_exact_where_the_z_plane_overflows():
    """A diagonal needle 1/256 pixel wide whose third vertex is far away in
    z: its z gradient is so steep that the walker's fixed-point plane over
    the needle's 30 x 30 pixel box does not fit 2**62 (checked here from
    the plane equation), so each span start is evaluated from the exact edge
    values (scan.triangles.plane_fixed).  z stays exact at every pixel."""
    z, placed, vz = _draw_exact_triangle([(1.0, 1.0, -0.5), (30.0, 30.0, 0.5),
                                          (30.0 + 1 / 256, 30.0, 0.9)])
    (x0, y0), (x1, y1), (x2, y2) = placed
    det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    gx = ((vz[1] - vz[0]) * (y2 - y0) - (vz[2] - vz[0]) * (y1 - y0)) / det
    gy = ((vz[2] - vz[0]) * (x1 - x0) - (vz[1] - vz[0]) * (x2 - x0)) / det
    assert (abs(gx) * 30 + abs(gy) * 30) * 2 ** 30 > 2 ** 62      # the premise
    assert len(ref.triangle_pixels(*placed, W, H)) >= 20
    _assert_z_exact(z, placed, vz)


def test_hidden_surface_independent_of_order():
    """Two interpenetrating triangles: the image with ZF_LEQUAL is the same in
    both drawing orders, and each pixel shows the nearer surface."""
    _window()
    subpixel(TRUE)
    zbuffer(TRUE)
    a = [(2.0, 2.0, -0.8), (29.0, 3.0, 0.8), (15.0, 29.0, 0.0)]
    b = [(3.0, 28.0, 0.6), (28.0, 27.0, -0.6), (16.0, 1.0, 0.1)]

    def tri(vs, colour):
        cpack(colour)
        bgnpolygon()
        for x, y, zn in vs:
            v3f((x, y, -zn))
        endpolygon()

    images = []
    for first, second in (((a, RED), (b, GREEN)), ((b, GREEN), (a, RED))):
        czclear(0, ZMAX)
        tri(*first)
        tri(*second)
        images.append(_c())
    np.testing.assert_array_equal(images[0], images[1])
    img = images[0]
    pa, pb = (ref.place([(x, y) for x, y, _ in t]) for t in (a, b))
    sa, sb = ref.triangle_pixels(*pa, W, H), ref.triangle_pixels(*pb, W, H)
    checked = 0
    for (x, y) in sa & sb:
        za = sum(w * Fraction(t[2]) for w, t in zip(ref.barycentric(*pa, x, y), a))
        zb = sum(w * Fraction(t[2]) for w, t in zip(ref.barycentric(*pb, x, y), b))
        if abs(za - zb) < Fraction(1, 1000):
            continue
        assert img[y, x] == (RED if za < zb else GREEN), (x, y)
        checked += 1
    assert checked > 50
