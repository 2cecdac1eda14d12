"""The single njit alias of the project, with the flags of :mod:`config`.

Every kernel is compiled through :func:`njit` (serial) or :func:`pnjit`
(``parallel=True``, when enabled).  ``NUMBA_DISABLE_JIT=1`` runs the kernels
as plain Python for coverage and debugging.
"""
import types as types_module

import numba
import numpy as np
from numba.core import types
from numba.extending import intrinsic, overload

from . import config

_opts = dict(config.JIT_OPTIONS)


def _tolerate_damaged_cache():
    """A damaged file in numba's disk cache (a truncated index, a garbled
    data file: a disk filled up, two processes killed while writing) counts
    as missing: the kernel is compiled again and the file written anew.
    Without this, numba raises UnpicklingError (or EOFError ...) from every
    later run that loads the file, and the emulator cannot start."""
    from numba.core import caching
    cls = caching.IndexDataCacheFile
    if getattr(cls, "_vgx_tolerant", False):
        return
    load_index, load_data = cls._load_index, cls._load_data

    def _load_index(self):
        try:
            return load_index(self)
        except OSError:
            raise
        except Exception:           # unreadable: as if there were no index yet
            return {}

    def _load_data(self, name):
        try:
            return load_data(self, name)
        except OSError:
            raise
        except Exception as e:      # numba's load() treats OSError as a missing file
            raise OSError(f"damaged numba cache file {name}: {e}") from e

    cls._load_index, cls._load_data, cls._vgx_tolerant = _load_index, _load_data, True


_tolerate_damaged_cache()


def njit(fn=None, **extra):
    """numba.njit with the project's options (cache on, fastmath off)."""
    opts = dict(_opts, **extra)
    if fn is None:
        return lambda f: numba.njit(**opts)(f)
    return numba.njit(**opts)(fn)


def helper(fn):
    """A small function inlined into kernels.  Not cached on its own: numba's
    cache of a function is keyed on its own file only, so a cached helper
    would keep old code inside kernels after an edit.  Kernels that use
    helpers are built by factories whose closure holds KERNEL_SOURCE_HASH
    (raster/variants.py), which keys their cache on every helper's source.
    Helpers are called from compiled code only, so they are compiled without
    the CPython and C wrappers (each helper's compile costs about 40 % less;
    the cold start compiles some twenty of them)."""
    opts = dict(_opts, cache=False, no_cpython_wrapper=True, no_cfunc_wrapper=True)
    return numba.njit(**opts)(fn)


def inline(fn):
    """A per-fragment helper inlined by numba into its caller's IR
    (``inline="always"``) before compilation.  The stage flags a kernel
    passes it are then constants of the kernel, so the disabled stages
    vanish and the span loop around it can be vectorised; left to LLVM, a
    helper holding every stage is too big to inline and costs a call per
    pixel."""
    opts = dict(_opts, cache=False, inline="always")
    return numba.njit(**opts)(fn)


def pnjit(fn):
    """A kernel with a ``prange`` loop (numba threads; the accumulation
    buffer's rows).  The triangle walker uses Python threads instead
    (scan.triangles.run_bands)."""
    return numba.njit(parallel=config.PARALLEL, **_opts)(fn)


prange = numba.prange


# --------------------------------------------------------------------------
# 32-bit integer arithmetic.  numba types int32 op int32 as int64, so a
# loop-carried int32 value (a colour DDA) reaches LLVM as sign-extended
# 64-bit arithmetic, and LLVM's induction-variable widening then keeps it in
# 64-bit vector lanes (4 per AVX2 register instead of 8).  These functions
# are that arithmetic as single i32 instructions in compiled code, and the
# same wrapped result in plain Python (NUMBA_DISABLE_JIT).

def _wrap32(v):
    return np.int32(((int(v) + (1 << 31)) & 0xFFFFFFFF) - (1 << 31))


def add32(a, b):
    """``a + b`` wrapped to int32."""
    return _wrap32(int(a) + int(b))


def sra32(a, n):
    """``a >> n`` (arithmetic) of ``a`` taken as int32."""
    return np.int32(int(_wrap32(a)) >> int(n))


def _i32_binary(op):
    @intrinsic
    def _op(typingctx, a, b):
        if not (isinstance(a, types.Integer) and isinstance(b, types.Integer)):
            return None

        def codegen(context, builder, sig, args):
            x = context.cast(builder, args[0], sig.args[0], types.int32)
            y = context.cast(builder, args[1], sig.args[1], types.int32)
            return getattr(builder, op)(x, y)
        return types.int32(a, b), codegen
    return _op


_add32 = _i32_binary("add")
_sra32 = _i32_binary("ashr")


@overload(add32)
def _add32_impl(a, b):
    return lambda a, b: _add32(a, b)


@overload(sra32)
def _sra32_impl(a, n):
    return lambda a, n: _sra32(a, n)


def bind_globals(fn, **names):
    """``fn`` with ``names`` added to its globals, for a kernel factory to
    hand its kernel the dispatchers made for its variant (the per-fragment
    stages).  Not through the closure: numba's disk cache keys a closure on
    the pickled contents of its cells, and a dispatcher pickles with an id
    drawn anew in every process, so such a kernel would be compiled again by
    every process.  The names must be determined by the closure's other
    cells (the variant's flags), which the cache key does hold."""
    f = types_module.FunctionType(fn.__code__, dict(fn.__globals__, **names), fn.__name__,
                                  fn.__defaults__, fn.__closure__)
    f.__qualname__ = fn.__qualname__
    f.__doc__ = fn.__doc__
    return f
