"""The per-fragment helpers of the raster and scan kernels, alone, on small
literal planes: stencil.apply (stencil(3G), swritemask(3G)), depth.compare
(zfunction(3G), the SF_* and AF_* functions), blend.blend_words
(blendfunction(3G)) and the triangle walker's edge_dda/edge_step.  Each
helper runs inside a tiny compiled loop over the plane, as the kernels run
it; the expected planes are written out or computed exactly (Fraction) from
the man pages' rules."""
from fractions import Fraction

import numba
import numpy as np
import pytest

from vgx_emulator.raster import blend, depth, stencil
from vgx_emulator.scan.fixed import SHIFT
from vgx_emulator.scan.triangles import edge_dda, edge_step


@numba.njit
def _stencil_plane(terms, plane, smax, wmask):
    x, k, a = terms
    out = np.empty_like(plane)
    for i in range(plane.shape[0]):
        for j in range(plane.shape[1]):
            out[i, j] = stencil.apply(np.int32(x), np.int32(k), np.int32(a), plane[i, j],
                                      np.int32(smax), np.int32(wmask))
    return out


@numba.njit
def _compare_row(func, a, b):
    out = np.empty(a.shape[0], np.int32)
    for i in range(a.shape[0]):
        out[i] = depth.compare(func, a[i], b[i])
    return out


@numba.njit
def _blend_plane(ts, td, src, dst, generic=False):
    out = np.empty_like(src)
    for i in range(src.shape[0]):
        for j in range(src.shape[1]):
            out[i, j] = blend.blend_words(ts, td, src[i, j], dst[i, j], generic)
    return out


@numba.njit
def _edge_rows(A, c, S, n):
    q, m, D, sq, sm = edge_dda(A, c, S)
    qs = np.empty(n, np.int64)
    ms = np.empty(n, np.int64)
    for r in range(n):
        qs[r] = q
        ms[r] = m
        q, m = edge_step(q, m, D, sq, sm)
    return qs, ms, D


# -- stencil.apply -------------------------------------------------------------------
STORED = np.array([[0, 1, 2, 3],
                   [127, 128, 129, 200],
                   [253, 254, 255, 5]], np.int32)


@pytest.mark.parametrize("op, ref, expected", [
    (stencil.ST_KEEP, 9, STORED),
    (stencil.ST_ZERO, 9, np.zeros((3, 4), np.int32)),
    (stencil.ST_REPLACE, 9, np.full((3, 4), 9, np.int32)),
    (stencil.ST_INCR, 9, np.array([[1, 2, 3, 4],
                                   [128, 129, 130, 201],
                                   [254, 255, 255, 6]], np.int32)),      # saturates at 255
    (stencil.ST_DECR, 9, np.array([[0, 0, 1, 2],
                                   [126, 127, 128, 199],
                                   [252, 253, 254, 4]], np.int32)),      # stops at 0
    (stencil.ST_INVERT, 9, np.array([[255, 254, 253, 252],
                                     [128, 127, 126, 55],
                                     [2, 1, 0, 250]], np.int32)),
])
def test_stencil_ops_on_eight_planes(op, ref, expected):
    out = _stencil_plane(stencil.op_terms(op, ref, 255), STORED, 255, 0xFF)
    assert np.array_equal(out, expected)


def test_stencil_ops_with_three_planes_and_a_write_mask():
    """3 planes (max 7): INCR saturates at 7, INVERT flips three bits; the
    write mask 0b101 keeps bit 1 of the stored value."""
    s = np.array([[0, 1, 2, 3], [4, 5, 6, 7]], np.int32)
    incr = _stencil_plane(stencil.op_terms(stencil.ST_INCR, 0, 7), s, 7, 0b111)
    assert np.array_equal(incr, [[1, 2, 3, 4], [5, 6, 7, 7]])
    inv = _stencil_plane(stencil.op_terms(stencil.ST_INVERT, 0, 7), s, 7, 0b111)
    assert np.array_equal(inv, [[7, 6, 5, 4], [3, 2, 1, 0]])
    masked = _stencil_plane(stencil.op_terms(stencil.ST_INVERT, 0, 7), s, 7, 0b101)
    # (s & ~0b101) | (~s & 0b101): bits 0 and 2 flipped, bit 1 kept
    assert np.array_equal(masked, [[5, 4, 7, 6], [1, 0, 3, 2]])
    rep = _stencil_plane(stencil.op_terms(stencil.ST_REPLACE, 6, 7), s, 7, 0b011)
    # (s & 0b100) | (6 & 0b011): bit 2 kept, bits 1..0 := 0b10
    assert np.array_equal(rep, [[2, 2, 2, 2], [6, 6, 6, 6]])


# -- depth.compare ---------------------------------------------------------------------
A = np.array([-5, 0, 3, 3, 7, -0x800000, 0x7FFFFF], np.int64)
B = np.array([0, 0, 3, 9, 2, 0x7FFFFF, 0x7FFFFF], np.int64)
P, F = -1, 0


@pytest.mark.parametrize("func, expected", [
    (depth.ZF_NEVER, [F, F, F, F, F, F, F]),
    (depth.ZF_LESS, [P, F, F, P, F, P, F]),
    (depth.ZF_EQUAL, [F, P, P, F, F, F, P]),
    (depth.ZF_LEQUAL, [P, P, P, P, F, P, P]),
    (depth.ZF_GREATER, [F, F, F, F, P, F, F]),
    (depth.ZF_NOTEQUAL, [P, F, F, P, P, P, F]),
    (depth.ZF_GEQUAL, [F, P, P, F, P, F, P]),
    (depth.ZF_ALWAYS, [P, P, P, P, P, P, P]),
])
def test_compare_is_a_FUNC_b_as_a_mask(func, expected):
    """``a FUNC b`` (incoming FUNC stored for z; ref FUNC stored for the
    stencil, ref on the left): -1 passes, 0 fails."""
    assert _compare_row(func, A, B).tolist() == expected


# -- blend.blend_words -----------------------------------------------------------------
def _word(r, g, b, a):
    return r | (g << 8) | (b << 16) | (a << 24)


SRC = np.array([[_word(0, 0, 255, 128), _word(200, 100, 50, 255)],
                [_word(255, 255, 255, 0), _word(10, 20, 30, 64)]], np.int64)
DST = np.array([[_word(255, 0, 0, 255), _word(100, 200, 250, 0)],
                [_word(1, 2, 3, 4), _word(250, 240, 230, 220)]], np.int64)


def _factor(code, is_src, cs, cd, sa, da):
    """The factor of blendfunction(3G) in 0..1 as a Fraction."""
    f = Fraction
    own = f(cs, 255) if not is_src else f(cd, 255)   # DC for a source, SC for a destination
    return {blend.BF_ZERO: f(0), blend.BF_ONE: f(1), blend.BF_DC: own,
            blend.BF_MDC: 1 - own, blend.BF_SA: f(sa, 255), blend.BF_MSA: 1 - f(sa, 255),
            blend.BF_DA: f(da, 255), blend.BF_MDA: 1 - f(da, 255),
            blend.BF_MIN_SA_MDA: min(f(sa, 255), 1 - f(da, 255))}[code]


def _expected_blend(sf, df, src, dst):
    """round(clamp(Cs S + Cd D, 0, 1) * 255) per component, exactly."""
    out = np.empty_like(src)
    for idx in np.ndindex(src.shape):
        s, d = int(src[idx]), int(dst[idx])
        sa, da = s >> 24, d >> 24
        word = 0
        for k in range(4):
            cs, cd = (s >> 8 * k) & 255, (d >> 8 * k) & 255
            c = Fraction(cs, 255) * _factor(sf, True, cs, cd, sa, da) + \
                Fraction(cd, 255) * _factor(df, False, cs, cd, sa, da)
            c = min(max(c, Fraction(0)), Fraction(1)) * 255
            word |= int(c + Fraction(1, 2)) << 8 * k
        out[idx] = word
    return out


def test_blend_words_literal_transparency():
    """(BF_SA, BF_MSA) of half-transparent blue over opaque red, written out:
    R 255 * 127/255 = 127, B 255 * 128/255 = 128, A 128 * 128/255 + 127 = 191."""
    ts, td = blend.factor_terms(blend.BF_SA, True), blend.factor_terms(blend.BF_MSA, False)
    out = _blend_plane(ts, td, SRC[:1, :1], DST[:1, :1])
    assert int(out[0, 0]) == _word(127, 0, 128, 191)


@pytest.mark.parametrize("sf", [blend.BF_ZERO, blend.BF_ONE, blend.BF_DC, blend.BF_MDC,
                                blend.BF_SA, blend.BF_MSA, blend.BF_DA, blend.BF_MDA,
                                blend.BF_MIN_SA_MDA])
@pytest.mark.parametrize("df", [blend.BF_ZERO, blend.BF_ONE, blend.BF_SC, blend.BF_MSC,
                                blend.BF_SA, blend.BF_MSA, blend.BF_DA, blend.BF_MDA])
@pytest.mark.parametrize("generic", [False, True])
def test_blend_words_every_factor_pair(sf, df, generic):
    """Both divisions by 510 (a folded pair's and the generic kernel's
    multiply and shift) give the man page's rounded blend."""
    ts, td = blend.factor_terms(sf, True), blend.factor_terms(df, False)
    assert np.array_equal(_blend_plane(ts, td, SRC, DST, generic),
                          _expected_blend(sf, df, SRC, DST))


def test_additive_blend_saturates():
    ts, td = blend.factor_terms(blend.BF_ONE, True), blend.factor_terms(blend.BF_ONE, False)
    out = _blend_plane(ts, td, SRC, DST)
    assert int(out[0, 0]) == _word(255, 0, 255, 255)
    assert int(out[1, 1]) == _word(255, 255, 255, 255)
    assert int(out[1, 0]) == _word(255, 255, 255, 4)


# -- edge_dda / edge_step ------------------------------------------------------------
@pytest.mark.parametrize("A, c, S", [(3, 1000, 700), (-5, -1234, 999), (1, -7, -300),
                                     (7, 0, 256), (-2, 5000, -1)])
def test_edge_walk_gives_the_exact_floor_quotient_each_row(A, c, S):
    """Row r's covered pixels begin (A > 0) or end (A < 0) at the floor of
    (c + r S) / D, D = |A| << SHIFT, with remainder 0 <= m < D: the walk
    divides once and steps exactly."""
    n = 40
    qs, ms, D = _edge_rows(A, c, S, n)
    assert D == abs(A) << SHIFT
    for r in range(n):
        assert qs[r] == (c + r * S) // D and ms[r] == (c + r * S) % D


def test_edge_walk_literal_rows():
    """A = 1 (D = 256 with 8 sub-pixel bits), c = -300, S = 200: the first
    rows' quotients and remainders, written out."""
    assert SHIFT == 8
    qs, ms, D = _edge_rows(1, -300, 200, 5)
    assert D == 256
    assert qs.tolist() == [-2, -1, 0, 1, 1]
    assert ms.tolist() == [212, 156, 100, 44, 244]


def test_edge_with_A_zero_divides_by_one():
    """A horizontal edge (A = 0): q is c itself, every x of a row is on the
    same side."""
    qs, ms, D = _edge_rows(0, -3, 2, 4)
    assert D == 1 and qs.tolist() == [-3, -1, 1, 3] and ms.tolist() == [0, 0, 0, 0]
