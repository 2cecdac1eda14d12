"""Stencil operations (stencil(3G), swritemask(3G); reference 6, Decision 2).

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
from ..jit import helper

ST_KEEP, ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT = range(6)


@helper
def apply(op, s, ref, smax, wmask):
    """``op`` on the stored value ``s`` under the write mask.  Written as
    selects, not branches, so that span loops vectorise."""
    s = int(s)
    v = s
    v = min(s + 1, smax) if op == ST_INCR else v
    v = max(s - 1, 0) if op == ST_DECR else v
    v = 0 if op == ST_ZERO else v
    v = ref if op == ST_REPLACE else v
    v = (~s & smax) if op == ST_INVERT else v
    return ((s & ~wmask) | (v & wmask)) & smax
