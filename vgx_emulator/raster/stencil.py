"""Stencil operations (stencil(3G), swritemask(3G); docs/semantics.md §6).

With n planes and max = 2**n - 1:

========== ===================================
ST_KEEP    s
ST_ZERO    0
ST_REPLACE ref (clamped to 0..max by the caller)
ST_INCR    min(s + 1, max)   (saturating, VGX)
ST_DECR    max(s - 1, 0)     (saturating, VGX)
ST_INVERT  ~s within the n planes
========== ===================================

The result is written only in the planes swritemask enables:
``s' = (s & ~wm) | (op(s) & wm)``.
"""
import numpy as np

from ..jit import helper

ST_KEEP, ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT = range(6)


def op_terms(op, ref, smax):
    """ST_* as three integers (x, k, a) with op(s) = clamp(((s ^ x) & k) + a,
    0, smax): KEEP (0, -1, 0), ZERO (0, 0, 0), REPLACE (0, 0, ref), INCR
    (0, -1, 1), DECR (0, -1, -1), INVERT (smax, -1, 0).  Computed once per
    pass, so a fragment applies any op with the same few integer operations
    (no branch on the op, and the span loop vectorises)."""
    return {ST_KEEP: (0, -1, 0), ST_ZERO: (0, 0, 0), ST_REPLACE: (0, 0, ref),
            ST_INCR: (0, -1, 1), ST_DECR: (0, -1, -1), ST_INVERT: (smax, -1, 0)}[op]


@helper
def apply(x, k, a, s, smax, wmask):
    """The op given by its terms (op_terms) on the stored value ``s``, written
    only in the planes of the write mask.  Every step is int32, so that a
    span loop runs eight stencil values per AVX2 vector, not four."""
    i32 = np.int32     # numba widens int32 operations to int64: narrow each step
    v = min(max(i32(i32(i32(s ^ x) & k) + a), i32(0)), smax)
    return i32(i32(s & ~wmask) | i32(v & wmask))
