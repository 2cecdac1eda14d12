"""The accumulation buffer and acbuf(3G) (reference section 10, Decision 10).

16 bits per component, signed (-32768..32767), RGBA, as (h, w, 4) int16 in
R, G, B, A order.  Every operation is bounded by viewport ∩ scrmask ∩ window.

=================== =========================================================
AC_CLEAR            every component := round(value), clamped to the range
AC_ACCUMULATE       += round(component * value), value clamped to -256..256,
                    pixels read from readsource; overflow wraps (Decision 10)
AC_CLEAR_ACCUMULATE clear to 0, then AC_ACCUMULATE
AC_RETURN           clamp(round(acc * value), 0, 255) with value clamped to
                    0..1, written to every enabled colour buffer under the
                    colour writemask; z, stencil, blend, logicop ignored
AC_MULT             component := round(component * value), wraps
AC_ADD              component += round(value) (0..255 pixel units), wraps
=================== =========================================================

Reading SRC_ZBUFFER into the buffer takes the low 24 bits of each z word as
R, G, B bytes ([S]: the man page only says "rescale to 0..255").
"""
import math

import numpy as np

from ..jit import njit

AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, AC_MULT, AC_ADD = range(6)


@njit
def _wrap16(v):
    v = v & 0xFFFF
    if v >= 0x8000:
        v -= 0x10000
    return v


@njit
def accumulate(acc, src, op, value, x0, x1, y0, y1):
    """AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_MULT, AC_ADD."""
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            for k in range(4):
                a = int(acc[y, x, k])
                if op == 0:
                    v = int(math.floor(value + 0.5))
                    a = min(max(v, -32768), 32767)
                elif op == 1 or op == 2:
                    if op == 2:
                        a = 0
                    c = (np.int64(src[y, x]) >> (8 * k)) & 0xFF
                    a = _wrap16(a + int(math.floor(c * value + 0.5)))
                elif op == 4:
                    a = _wrap16(int(math.floor(a * value + 0.5)))
                else:
                    a = _wrap16(a + int(math.floor(value + 0.5)))
                acc[y, x, k] = a


@njit
def give_back(acc, dst, value, mask, cmode, x0, x1, y0, y1):
    """AC_RETURN into one colour bank under the colour writemask."""
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            word = 0
            for k in range(4):
                c = int(math.floor(acc[y, x, k] * value + 0.5))
                c = min(max(c, 0), 255)
                word |= c << (8 * k)
            if cmode:
                word &= 0xFFF
            old = np.int64(dst[y, x])
            dst[y, x] = (old & ~mask) | (word & mask)
