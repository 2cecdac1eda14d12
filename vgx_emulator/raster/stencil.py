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
    s = int(s)
    if op == ST_KEEP:
        return s
    if op == ST_INCR:
        v = s + 1 if s < smax else smax
    elif op == ST_DECR:
        v = s - 1 if s > 0 else 0
    elif op == ST_ZERO:
        v = 0
    elif op == ST_REPLACE:
        v = ref
    else:
        v = ~s & smax
    return ((s & ~wmask) | (v & wmask)) & smax
