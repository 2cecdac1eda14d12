"""The 32-bit integer helpers of vgx_emulator.jit: compiled code (one i32
instruction) and plain Python (NUMBA_DISABLE_JIT) wrap the same way; and no
kernel is compiled with numba's parallel lowering."""
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


def test_no_kernel_uses_numbas_parallel_lowering():
    """Work in shares runs on the project's own threads (pipeline.in_shares,
    the walker's bands): no kernel is compiled with ``parallel=True``.
    Under numba's OpenMP threading layer a parallel region leaves its
    pool's threads spinning, and they took the core the program's thread
    needed (docs/architecture.md, Parallelism)."""
    import sys
    import irisgl  # noqa: F401  (imports the machine's modules)
    from vgx_emulator.framebuffer import accum  # noqa: F401
    from vgx_emulator.scan import triangles
    from numba.core.registry import CPUDispatcher
    kernels = [getattr(m, name) for mod, m in list(sys.modules.items())
               if mod.startswith("vgx_emulator") and m is not None
               for name in dir(m) if isinstance(getattr(m, name, None), CPUDispatcher)]
    kernels.append(triangles.walker((True,) * 2 + (True, True, False, False, 2, 0, 0, False,
                                     False, 0xFFFFFFFF, False, False)))
    names = {k.py_func.__qualname__ for k in kernels}
    assert {"_accumulate_rows", "_give_back_rows", "fill", "fill_z"} <= names
    assert [k.py_func.__qualname__ for k in kernels if k.targetoptions.get("parallel")] == []
