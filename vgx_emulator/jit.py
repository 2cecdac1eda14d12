"""The single njit alias of the project, with the flags of :mod:`config`.

Every kernel is compiled through :func:`njit` (serial) or :func:`pnjit`
(``parallel=True``, when enabled).  ``NUMBA_DISABLE_JIT=1`` runs the kernels
as plain Python for coverage and debugging.
"""
import numba

from . import config

_opts = dict(config.JIT_OPTIONS)


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
    (raster/variants.py), which keys their cache on every helper's source."""
    opts = dict(_opts, cache=False)
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
