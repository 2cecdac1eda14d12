"""The accumulation buffer and acbuf(3G) (docs/semantics.md §10).

16 bits per component, signed (-32768..32767), RGBA, as (h, w, 4) int16 in
R, G, B, A order.  Every operation is bounded by viewport ∩ scrmask ∩ window.

=================== =========================================================
AC_CLEAR            every component := round(value), clamped to the range
AC_ACCUMULATE       += round(component * value), value clamped to -256..256,
                    pixels read from readsource; overflow wraps (docs/semantics.md §10)
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

from .. import pipeline
from ..jit import njit

AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, AC_MULT, AC_ADD = range(6)


@njit
def _wrap16(v):
    v = v & 0xFFFF
    if v >= 0x8000:
        v -= 0x10000
    return v


#: a share of an accumulation-buffer operation has at least this many rows
SHARE_ROWS = 64


def accumulate(acc, src, op, value, x0, x1, y0, y1):
    """AC_CLEAR, AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_MULT, AC_ADD over
    the rectangle, its rows in shares on the threads free for them
    (pipeline.in_shares)."""
    pipeline.in_shares(lambda lo, hi: _accumulate_rows(acc, src, op, value, x0, x1,
                                                       y0 + lo, y0 + hi - 1),
                       y1 - y0 + 1, SHARE_ROWS)


def give_back(acc, dst, value, mask, cmode, x0, x1, y0, y1):
    """AC_RETURN into one colour bank under the colour writemask, its rows
    in shares on the threads free for them (pipeline.in_shares)."""
    pipeline.in_shares(lambda lo, hi: _give_back_rows(acc, dst, value, mask, cmode, x0, x1,
                                                      y0 + lo, y0 + hi - 1),
                       y1 - y0 + 1, SHARE_ROWS)


@njit
def _accumulate_rows(acc, src, op, value, x0, x1, y0, y1):
    """accumulate() on rows y0..y1.  AC_ACCUMULATE adds ``lut[c]`` =
    round(c * value) of each source byte c, looked up in a 256-entry int32
    table made once per call (the same rounding as per pixel, without a
    multiply and floor per component; |lut| <= 255 * 256); the int16 store
    of the int32 sum wraps as _wrap16 does."""
    lut = np.empty(256, np.int32)
    for c in range(256):
        lut[c] = np.int32(math.floor(c * value + 0.5))
    v = int(math.floor(value + 0.5))
    cleared = min(max(v, -32768), 32767)
    for y in range(y0, y1 + 1):
        row = acc[y]
        if op == AC_ACCUMULATE:
            srow = src[y]
            for x in range(x0, x1 + 1):
                u = np.uint64(x)
                w = srow[u]
                row[u, 0] = np.int16(np.int32(row[u, 0]) + lut[w & 0xFF])
                row[u, 1] = np.int16(np.int32(row[u, 1]) + lut[(w >> 8) & 0xFF])
                row[u, 2] = np.int16(np.int32(row[u, 2]) + lut[(w >> 16) & 0xFF])
                row[u, 3] = np.int16(np.int32(row[u, 3]) + lut[(w >> 24) & 0xFF])
        elif op == AC_CLEAR_ACCUMULATE:
            srow = src[y]
            for x in range(x0, x1 + 1):
                u = np.uint64(x)
                w = srow[u]
                row[u, 0] = np.int16(lut[w & 0xFF])
                row[u, 1] = np.int16(lut[(w >> 8) & 0xFF])
                row[u, 2] = np.int16(lut[(w >> 16) & 0xFF])
                row[u, 3] = np.int16(lut[(w >> 24) & 0xFF])
        elif op == AC_CLEAR:
            for x in range(x0, x1 + 1):
                for k in range(4):
                    row[x, k] = cleared
        elif op == AC_MULT:
            for x in range(x0, x1 + 1):
                for k in range(4):
                    row[x, k] = _wrap16(int(math.floor(row[x, k] * value + 0.5)))
        else:
            for x in range(x0, x1 + 1):
                for k in range(4):
                    row[x, k] = _wrap16(np.int64(row[x, k]) + v)


@njit
def _give_back_rows(acc, dst, value, mask, cmode, x0, x1, y0, y1):
    """give_back() on rows y0..y1."""
    for y in range(y0, y1 + 1):
        arow = acc[y]
        drow = dst[y]
        for x in range(x0, x1 + 1):
            word = 0
            for k in range(4):
                c = int(math.floor(arow[x, k] * value + 0.5))
                c = min(max(c, 0), 255)
                word |= c << (8 * k)
            if cmode:
                word &= 0xFFF
            old = np.int64(drow[x])
            drow[x] = (old & ~mask) | (word & mask)
