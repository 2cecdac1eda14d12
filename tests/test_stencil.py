"""stencil(3G), swritemask(3G), sclear(3G), stensize(3G) (docs/semantics.md §6).

Expectations come from a small independent model of the man-page rules
(``st_test``/``st_op`` below), never from the library's kernels.
"""
from functools import partial

import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import new_window, box, stencil_bank, z_bank, colour


# -- fixtures and helpers -------------------------------------------------------
open_win = partial(new_window, planes=8, pixels=True)   # pixel (i, j)'s centre at (i, j)



def set_columns(values, h=None):
    """sclear each column x to values[x] through scrmask (API only)."""
    w, hh = getsize()
    for x, v in enumerate(values):
        scrmask(x, x, 0, hh - 1)
        sclear(v)
    scrmask(0, w - 1, 0, hh - 1)


# -- the independent model ----------------------------------------------------
FUNCS = {
    SF_NEVER: lambda a, b: False,
    SF_LESS: lambda a, b: a < b,
    SF_EQUAL: lambda a, b: a == b,
    SF_LEQUAL: lambda a, b: a <= b,
    SF_GREATER: lambda a, b: a > b,
    SF_NOTEQUAL: lambda a, b: a != b,
    SF_GEQUAL: lambda a, b: a >= b,
    SF_ALWAYS: lambda a, b: True,
}


def st_test(func, ref, stored, mask, planes=8):
    smax = (1 << planes) - 1
    ref = min(max(ref, 0), smax)                     # docs/semantics.md §6: clamp
    return FUNCS[func](ref & mask, stored & mask)    # ref on the left


def st_op(op, s, ref, planes=8, wm=0xFF):
    smax = (1 << planes) - 1
    ref = min(max(ref, 0), smax)
    if op == ST_KEEP:
        v = s
    elif op == ST_ZERO:
        v = 0
    elif op == ST_REPLACE:
        v = ref
    elif op == ST_INCR:
        v = min(s + 1, smax)
    elif op == ST_DECR:
        v = max(s - 1, 0)
    elif op == ST_INVERT:
        v = (~s) & smax
    else:
        raise AssertionError(op)
    wm &= smax
    return ((s & ~wm) | (v & wm)) & smax


RED = 0xFF0000FF


# -- configuration ---------------------------------------------------------------
def test_getgdesc_stencil_bits_is_8():
    assert getgdesc(GD_BITS_STENCIL) == 8


def test_stensize_range():
    prefsize(4, 4)
    winopen("s")
    with pytest.raises(GLError):
        stensize(9)
    with pytest.raises(GLError):
        stensize(-1)
    stensize(3)
    gconfig()
    assert getgconfig(GC_BITS_STENCIL) == 3


def test_stencil_without_planes_raises_and_changes_nothing():
    prefsize(4, 4)
    winopen("s")
    RGBmode()
    gconfig()
    ortho2(-0.5, 3.5, -0.5, 3.5)
    with pytest.raises(GLError) as e:
        stencil(TRUE, 1, SF_NEVER, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    assert str(e.value).startswith("stencil")
    # disabling is always allowed
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    # nothing changed: drawing is not stencil-tested (SF_NEVER would block it)
    cpack(RED)
    box(0, 0, 3, 3)
    assert (colour() == RED).all()


def test_stencil_bad_tokens_raise():
    open_win(4, 4)
    with pytest.raises(GLError):
        stencil(TRUE, 0, 8, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    with pytest.raises(GLError):
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, 6, ST_KEEP, ST_KEEP)
    with pytest.raises(GLError):
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, -1)


def test_stencil_disabled_ignores_arguments():
    """enable FALSE: the other arguments are ignored, even illegal ones."""
    open_win(4, 4)
    stencil(FALSE, 999, 99, 0, 99, 99, 99)
    cpack(RED)
    box(0, 0, 3, 3)
    assert (colour() == RED).all()
    assert (stencil_bank() == 0).all()


# -- the comparison --------------------------------------------------------------
STORED = [0, 1, 5, 6, 7, 8, 200, 255]


@pytest.mark.parametrize("func", sorted(FUNCS))
@pytest.mark.parametrize("ref,mask,stored", [
    (6, 0xFF, STORED),
    # mask applied to both sides: 0x16 & 0x0F == 6
    (0x16, 0x0F, [0x00, 0x25, 0x26, 0x27, 0xF6, 0x05, 0x17, 0x3F]),
])
def test_stencil_function_ref_on_left(func, ref, mask, stored):
    open_win(8, 2)
    set_columns(stored)
    czclear(0, 0)
    # z-buffer off: fail -> INVERT, pass -> INCR (docs/semantics.md §6)
    stencil(TRUE, ref, func, mask, ST_INVERT, ST_INCR, ST_ZERO)
    cpack(RED)
    box(0, 0, 7, 1)
    s = stencil_bank()
    c = colour()
    for x, v in enumerate(stored):
        ok = st_test(func, ref, v, mask)
        want_s = st_op(ST_INCR if ok else ST_INVERT, v, ref)
        assert (s[:, x] == want_s).all(), (x, v, ok)
        assert (c[:, x] == (RED if ok else 0)).all(), (x, v, ok)


def test_sf_less_means_ref_less_than_stored():
    """docs/semantics.md §6 spelled out: SF_LESS passes where ref < stored."""
    open_win(3, 1)
    set_columns([4, 5, 6])
    stencil(TRUE, 5, SF_LESS, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    cpack(RED)
    box(0, 0, 2, 0)
    assert list(colour()[0]) == [0, 0, RED]


def test_ref_is_clamped_not_wrapped_in_comparison():
    """ref 300 with 8 planes compares as 255 (300 & 255 would be 44)."""
    open_win(3, 1)
    set_columns([44, 255, 254])
    stencil(TRUE, 300, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    cpack(RED)
    box(0, 0, 2, 0)
    assert list(colour()[0]) == [0, RED, 0]


# -- the operations ----------------------------------------------------------------
OPS = [ST_KEEP, ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT]


@pytest.mark.parametrize("planes", [8, 3, 1])
@pytest.mark.parametrize("op", OPS)
def test_stencil_operations_saturate_within_planes(op, planes):
    smax = (1 << planes) - 1
    stored = sorted({0, 1, smax // 2, max(smax - 1, 0), smax})
    refs = [smax // 2 + 1 if smax > 1 else 1, smax + 100]   # in range, and clamped
    for ref in refs:
        open_win(len(stored), 1, planes=planes)
        set_columns(stored)
        stencil(TRUE, ref, SF_ALWAYS, 0xFF, ST_KEEP, op, ST_KEEP)   # z off -> pass
        box(0, 0, len(stored) - 1, 0)
        got = list(stencil_bank()[0])
        want = [st_op(op, v, ref, planes) for v in stored]
        assert got == want, (ref, stored)
        winclose(winget())


def test_incr_saturates_after_many_passes_with_fewer_planes():
    open_win(2, 1, planes=3)
    sclear(0)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)
    for _ in range(12):
        box(0, 0, 1, 0)
    assert list(stencil_bank()[0]) == [7, 7]
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_DECR, ST_KEEP)
    for _ in range(12):
        box(0, 0, 0, 0)
    assert list(stencil_bank()[0]) == [0, 7]


def test_replace_writes_ref_clamped_to_planes():
    open_win(1, 1, planes=3)
    stencil(TRUE, 10, SF_ALWAYS, 0xFF, ST_KEEP, ST_REPLACE, ST_KEEP)
    box(0, 0, 0, 0)
    assert stencil_bank()[0, 0] == 7          # clamped, not 10 & 7 == 2


def test_invert_stays_within_planes():
    open_win(2, 1, planes=4)
    set_columns([0, 5])
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INVERT, ST_KEEP)
    box(0, 0, 1, 0)
    assert list(stencil_bank()[0]) == [15, 10]


@pytest.mark.parametrize("wm", [0x0F, 0xF0, 0x00, 0x55, 0x1FF])
@pytest.mark.parametrize("op", [ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT])
def test_swritemask_limits_changed_bits(op, wm):
    stored = [0x00, 0x0F, 0x10, 0x7F, 0xA5, 0xFF]
    ref = 0x3C
    open_win(len(stored), 1)
    set_columns(stored)
    swritemask(wm)
    stencil(TRUE, ref, SF_ALWAYS, 0xFF, ST_KEEP, op, ST_KEEP)
    box(0, 0, len(stored) - 1, 0)
    got = list(stencil_bank()[0])
    assert got == [st_op(op, v, ref, 8, wm) for v in stored]


def test_swritemask_applies_to_fail_op_too():
    open_win(2, 1)
    set_columns([0x0F, 0xF0])
    swritemask(0x0F)
    stencil(TRUE, 0, SF_NEVER, 0xFF, ST_ZERO, ST_KEEP, ST_KEEP)
    box(0, 0, 1, 0)
    assert list(stencil_bank()[0]) == [0x00, 0xF0]


# -- the three outcomes --------------------------------------------------------------
def test_three_outcomes_with_zbuffer_on():
    """Columns 0-3: stencil passes (stored 3 == ref); 4-7 fail (stored 4).
    Rows 0-3: stored z = ZMIN (incoming z 0 fails ZF_LEQUAL); rows 4-7: ZMAX."""
    open_win(8, 8)
    zmin, zmax = getgdesc(GD_ZMIN), getgdesc(GD_ZMAX)
    czclear(0, zmax)
    scrmask(0, 7, 0, 3)
    czclear(0, zmin)
    scrmask(0, 7, 0, 7)
    set_columns([3] * 4 + [4] * 4)
    zbuffer(TRUE)
    stencil(TRUE, 3, SF_EQUAL, 0xFF, ST_INVERT, ST_INCR, ST_DECR)
    cpack(RED)
    box(0, 0, 7, 7)
    s, c, z = stencil_bank(), colour(), z_bank()
    # stencil fails -> fail op, no colour, no z
    assert (s[:, 4:] == 255 - 4).all()
    assert (c[:, 4:] == 0).all()
    assert (z[:4, 4:] == zmin).all() and (z[4:, 4:] == zmax).all()
    # stencil passes, z fails -> pass op, no colour, no z
    assert (s[:4, :4] == 4).all()
    assert (c[:4, :4] == 0).all()
    assert (z[:4, :4] == zmin).all()
    # both pass -> zpass op, colour and z written
    assert (s[4:, :4] == 2).all()
    assert (c[4:, :4] == RED).all()
    assert (z[4:, :4] != zmax).all()
    assert (abs(z[4:, :4]) <= 1).all()       # z = 0 plane maps to the middle of the range


def test_zbuffer_off_applies_pass_not_zpass_and_writes_colour():
    """docs/semantics.md §6: with the z-buffer off, a passing stencil test applies
    ``pass`` (zpass is not significant) and the colour is written."""
    open_win(4, 4)
    sclear(10)
    stencil(TRUE, 10, SF_EQUAL, 0xFF, ST_ZERO, ST_INCR, ST_DECR)
    cpack(RED)
    box(0, 0, 3, 3)
    assert (stencil_bank() == 11).all()
    assert (colour() == RED).all()


def test_stencil_fail_does_not_write_z_with_zbuffer_on():
    open_win(2, 2)
    zbuffer(TRUE)
    zclear()
    sclear(0)
    stencil(TRUE, 1, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    cpack(RED)
    box(0, 0, 1, 1)
    assert (z_bank() == getgdesc(GD_ZMAX)).all()
    assert (colour() == 0).all()


# -- sclear --------------------------------------------------------------------------
def test_sclear_honours_swritemask():
    open_win(2, 2)
    sclear(0xF0)
    swritemask(0x3C)
    sclear(0x0F)
    assert (stencil_bank() == ((0xF0 & ~0x3C) | (0x0F & 0x3C))).all()


def test_sclear_value_within_planes():
    open_win(2, 2, planes=3)
    sclear(0x1D)
    assert (stencil_bank() == (0x1D & 7)).all()


def test_sclear_bounded_by_viewport_and_scrmask():
    open_win(8, 8)
    sclear(1)
    viewport(2, 6, 1, 5)
    scrmask(0, 4, 3, 7)
    sclear(9)
    s = stencil_bank()
    want = np.ones((8, 8), np.int64)
    want[3:6, 2:5] = 9                    # rows 3..5, columns 2..4
    assert (s == want).all()


def test_sclear_leaves_colour_and_z():
    open_win(2, 2)
    czclear(RED, 1234)
    sclear(77)
    assert (colour() == RED).all()
    assert (z_bank() == 1234).all()


def test_gconfig_resets_swritemask():
    open_win(2, 2)
    swritemask(0)
    gconfig()
    sclear(5)
    assert (stencil_bank() == 5).all()


# -- exact counts over shared edges ----------------------------------------------------
def _inside_convex(poly, px, py):
    """Signed distances of (px, py) to every edge of a CCW convex polygon:
    returns min distance (positive inside)."""
    d = np.inf
    n = len(poly)
    for i in range(n):
        (x0, y0), (x1, y1) = poly[i], poly[(i + 1) % n]
        ex, ey = x1 - x0, y1 - y0
        cross = ex * (py - y0) - ey * (px - x0)
        d = min(d, cross / np.hypot(ex, ey))
    return d


def _convex_ring(cx, cy, r, n, phase):
    return [(cx + r * np.cos(phase + 2 * np.pi * k / n),
             cy + r * np.sin(phase + 2 * np.pi * k / n)) for k in range(n)]


def _fan_case(ring, centre, snapped, zmode):
    W = H = 32
    open_win(W, H)
    subpixel(FALSE if snapped else TRUE)
    sclear(0)
    if zmode:
        zbuffer(TRUE)
        zclear()
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)
    else:
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)
    wmpack(0)
    n = len(ring)
    for k in range(n):
        bgnpolygon()
        v2f(centre)
        v2f(ring[k])
        v2f(ring[(k + 1) % n])
        endpolygon()
    s = stencil_bank()
    poly = [(round(x), round(y)) for x, y in ring] if snapped else ring
    assert s.max() <= 1, "a pixel on a shared edge was counted twice"
    ys, xs = np.mgrid[0:H, 0:W]
    dist = np.vectorize(lambda px, py: _inside_convex(poly, px, py))(xs, ys)
    assert (s[dist > 1e-6] == 1).all(), "a pixel inside the fan was missed"
    assert (s[dist < -1e-6] == 0).all(), "a pixel outside the fan was counted"
    # the fan covers the same pixels as the whole polygon drawn at once
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    if zmode:
        zbuffer(FALSE)
    wmpack(0xFFFFFFFF)
    cpack(RED)
    bgnpolygon()
    for p in ring:
        v2f(p)
    endpolygon()
    assert ((colour() == RED) == (s == 1)).all()


@pytest.mark.parametrize("zmode", [False, True], ids=["zoff-pass", "zon-zpass"])
@pytest.mark.parametrize("snapped", [False, True], ids=["subpixel", "snapped"])
def test_fan_counts_each_pixel_once_integer_vertices(snapped, zmode):
    """Vertices on pixel centres: many pixel centres lie exactly on the
    shared spokes."""
    ring = [(4, 4), (20, 2), (28, 12), (26, 26), (12, 29), (3, 18)]
    _fan_case(ring, (15, 15), snapped, zmode)


@pytest.mark.parametrize("zmode", [False, True], ids=["zoff-pass", "zon-zpass"])
@pytest.mark.parametrize("snapped", [False, True], ids=["subpixel", "snapped"])
def test_fan_counts_each_pixel_once_fractional_vertices(snapped, zmode):
    ring = _convex_ring(15.7, 15.3, 13.1, 11, 0.3)
    # keep snapping unambiguous: no coordinate within 0.05 of a half
    ring = [(x + 0.1 if abs((x % 1) - 0.5) < 0.05 else x,
             y + 0.1 if abs((y % 1) - 0.5) < 0.05 else y) for x, y in ring]
    _fan_case(ring, (15.25, 16.125), snapped, zmode)


def test_fan_around_a_ring_vertex_horizontal_and_vertical_spokes():
    """A fan from vertex 0 of an axis-aligned octagon: shared edges that are
    horizontal, vertical and diagonal all pass through pixel centres."""
    ring = [(8, 2), (20, 2), (26, 8), (26, 20), (20, 26), (8, 26), (2, 20), (2, 8)]
    W = H = 32
    open_win(W, H)
    subpixel(TRUE)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)
    wmpack(0)
    for k in range(1, len(ring) - 1):
        bgnpolygon()
        v2f(ring[0])
        v2f(ring[k])
        v2f(ring[k + 1])
        endpolygon()
    s = stencil_bank()
    assert s.max() == 1
    ys, xs = np.mgrid[0:H, 0:W]
    dist = np.vectorize(lambda px, py: _inside_convex(ring, px, py))(xs, ys)
    assert (s[dist > 1e-6] == 1).all()
    assert (s[dist < -1e-6] == 0).all()


def test_quad_grid_counts_once_on_shared_edges():
    W = H = 16
    open_win(W, H)
    subpixel(TRUE)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)
    wmpack(0)
    xs = [1, 5, 9.5, 14]
    ys = [2, 7.25, 13]
    for i in range(len(xs) - 1):
        for j in range(len(ys) - 1):
            rectf(xs[i], ys[j], xs[i + 1], ys[j + 1])
    s = stencil_bank()
    assert s.max() == 1
    # interior points well inside the union
    assert (s[3:12, 2:13] == 1).all()
    assert (s[14:, :] == 0).all() and (s[:2, :] == 0).all()
    assert (s[:, 15] == 0).all() and (s[:, 0] == 0).all()


def _read_counts_via_stencil_test(values):
    """Heidmann-style readback through the API: for each possible count k
    paint colour k where the stencil equals k."""
    w, h = getsize()
    wmpack(0xFFFFFFFF)
    czclear(0xFFFFFFFF, getgdesc(GD_ZMAX))
    zbuffer(FALSE)
    for k in values:
        stencil(TRUE, k, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
        cpack(k)
        box(0, 0, w - 1, h - 1)
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    return colour()


def test_heidmann_myzero_counting_incr_decr():
    """sclear(MYZERO=128); front quads INCR, back quads DECR (z on, zpass
    slot); the stencil holds 128 + (#incr - #decr) covering each pixel."""
    MYZERO = 128
    W, H = 24, 16
    open_win(W, H)
    subpixel(TRUE)
    zbuffer(TRUE)
    zclear()
    sclear(MYZERO)
    wmpack(0)
    zwritemask(0)          # shadow volume pass: z is tested, not written
    quads = [  # (x1, y1, x2, y2) in window coordinates (pixel-centre units), op
        ((1.5, 1.5, 12, 10.5), ST_INCR),
        ((12, 1.5, 20.5, 10.5), ST_INCR),      # shares x = 12 with the first
        ((6.3, 4.7, 16.2, 14.6), ST_INCR),
        ((3.0, 3.0, 9.0, 6.0), ST_DECR),       # edges through pixel centres
        ((9.0, 3.0, 15.0, 6.0), ST_DECR),      # shares x = 9
        ((0.2, 8.0, 23.8, 12.0), ST_DECR),
    ]
    for (x1, y1, x2, y2), op in quads:
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, op)
        rectf(x1, y1, x2, y2)
    zwritemask(0xFFFFFF)
    counts = stencil_bank()
    expected_cov = np.full((H, W), MYZERO, np.int64)
    for (x1, y1, x2, y2), op in quads:
        sign = 1 if op == ST_INCR else -1
        for y in range(H):
            for x in range(W):
                if x1 < x < x2 and y1 < y < y2:
                    expected_cov[y, x] += sign
    # pixels whose centres are on a quad edge depend on the fill rule: check
    # only the unambiguous ones, and that no shared edge double counts
    amb = np.zeros((H, W), bool)
    for (x1, y1, x2, y2), _ in quads:
        for y in range(H):
            for x in range(W):
                onx = (x in (x1, x2)) and y1 <= y <= y2
                ony = (y in (y1, y2)) and x1 <= x <= x2
                amb[y, x] |= onx or ony
    assert (counts[~amb] == expected_cov[~amb]).all()
    # column x = 12 (shared edge of the two INCR quads at y 2..10) is inside
    # exactly one of them whichever way the rule goes
    for y in range(2, 11):
        others = MYZERO
        for (x1, y1, x2, y2), op in quads[2:]:
            if x1 < 12 < x2 and y1 < y < y2:
                others += 1 if op == ST_INCR else -1
            elif (12 in (x1, x2) and y1 <= y <= y2) or (y in (y1, y2) and x1 <= 12 <= x2):
                others = None
                break
        if others is not None:
            assert counts[y, 12] == others + 1, y
    # the API readback (Heidmann's way) agrees with the bank
    readback = _read_counts_via_stencil_test(sorted(set(counts.ravel().tolist())))
    assert (readback == counts).all()
