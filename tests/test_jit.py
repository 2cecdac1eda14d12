"""The 32-bit integer helpers of vgx_emulator.jit: compiled code (one i32
instruction) and plain Python (NUMBA_DISABLE_JIT) wrap the same way."""
import numpy as np
import pytest

import numba

from vgx_emulator.jit import add32, sra32

EDGES = [0, 1, -1, 2**31 - 1, -2**31, 2**31 - 2, -2**31 + 1, 12345678, -87654321, 0xFFFF << 16]


@numba.njit(cache=False)
def _compiled(a, b, n):
    return add32(np.int32(a), np.int32(b)), sra32(np.int32(a), n)


def _wrapped(v):
    return (v + 2**31) % 2**32 - 2**31


@pytest.mark.parametrize("a", EDGES)
@pytest.mark.parametrize("b", EDGES)
def test_add32_wraps_like_int32(a, b):
    a, b = _wrapped(a), _wrapped(b)
    want = _wrapped(a + b)
    assert add32(np.int32(a), np.int32(b)) == want
    assert _compiled(a, b, 0)[0] == want


@pytest.mark.parametrize("a", EDGES)
@pytest.mark.parametrize("n", [0, 1, 16, 30, 31])
def test_sra32_is_an_arithmetic_shift(a, n):
    a = _wrapped(a)
    want = a >> n              # Python's >> on ints is arithmetic (floor)
    assert sra32(np.int32(a), n) == want
    assert _compiled(a, 0, n)[1] == want
    assert isinstance(_compiled(a, 0, n)[1], (int, np.integer))
