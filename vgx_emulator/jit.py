"""The project's numba entry points, with the flags of :mod:`config`.

* :func:`njit`: a self-contained kernel (serial), cached on disk by numba
  against its own file.
* :func:`kernel`: a kernel that inlines helpers of other files, cached on
  disk against the source of every such file (``KERNEL_SOURCE_HASH``) and,
  for a kernel variant, its raster key (``kernel(variant=key)``).
* :func:`helper` and :func:`inline`: the small functions kernels inline
  (never cached on their own).

``NUMBA_DISABLE_JIT=1`` runs the kernels as plain Python for coverage and
debugging.
"""
import hashlib
import sys
from pathlib import Path

import numba
import numpy as np
from numba.core import caching, types
from numba.extending import intrinsic, overload

from . import config

_opts = dict(config.JIT_OPTIONS)
_PKG = Path(__file__).resolve().parent


def _skip_blas_probe():
    """numba's first registry refresh of a process (before a compile)
    imports numba.np.arraymath, which probes for BLAS by importing
    scipy.linalg (0.2-0.6 s; ``import numba`` has already imported scipy
    itself).  No kernel of the emulator uses numba's linear algebra, so
    arraymath is imported with scipy.linalg hidden: numba then records
    that it has no BLAS, and scipy.linalg stays importable for everything
    else."""
    if "scipy.linalg" in sys.modules or "numba.np.arraymath" in sys.modules:
        return
    hidden = [m for m in ("scipy.linalg", "scipy.linalg.cython_blas") if m not in sys.modules]
    for m in hidden:
        sys.modules[m] = None
    try:
        import numba.np.arraymath  # noqa: F401
    finally:
        for m in hidden:
            if sys.modules.get(m, 0) is None:
                del sys.modules[m]


def _lean_cache_loads():
    """numba refreshes its whole typing and target registries before it
    loads a kernel from the disk cache: at a process's first load that
    imports and installs every implementation numba has (cffi and pycparser
    among them), 0.3-0.45 s of a 1.5 s filled-cache start.  Machine code read
    from the cache needs none of it, only the NRT runtime's symbols, which a
    load here initialises.  A compile still refreshes everything (numba's
    compiler does so itself), and that refresh skips the BLAS probe
    (:func:`_skip_blas_probe`).  Loads are left as numba has them if its
    cache class lacks the methods this relies on."""
    from numba.core import cpu
    from numba.core.runtime import nrt
    cls = caching.Cache
    if getattr(cls, "_vgx_lean", False):
        return
    cls._vgx_lean = True
    load_registries = cpu.CPUContext.load_additional_registries

    def load_additional_registries(self):
        _skip_blas_probe()
        load_registries(self)

    cpu.CPUContext.load_additional_registries = load_additional_registries
    if not all(hasattr(cls, m) for m in ("_load_overload", "_guard_against_spurious_io_errors")):
        return

    def load_overload(self, sig, target_context):
        nrt.rtsys.initialize(target_context)
        with self._guard_against_spurious_io_errors():
            return self._load_overload(sig, target_context)
        # None (a miss) when the guard swallowed a spurious I/O error

    cls.load_overload = load_overload


_lean_cache_loads()


_cache_warned = []


def cache_trouble(what):
    """One VGXWarning per process the first time numba's disk cache cannot
    be used; the kernels are compiled instead (issue 19: a cache never stops
    a run)."""
    if not _cache_warned:
        import warnings
        from .errors import VGXWarning
        _cache_warned.append(what)
        warnings.warn(f"numba cache: {what}; kernels are compiled in this process instead",
                      VGXWarning, stacklevel=2)


def _key_number(key):
    """The data-file number of a cache entry: from its key, so that two
    entries never share a file whichever processes save them."""
    import pickle
    return int(hashlib.sha1(pickle.dumps(key, protocol=4)).hexdigest()[:12], 16)


def _tolerate_damaged_cache():
    """A damaged, read-only or foreign numba disk cache never stops a run:

    * a damaged file (a truncated index, a garbled data file: a disk filled
      up, two processes killed while writing; a file of another numba) counts
      as missing: the kernel is compiled again and the file written anew
      (numba raised UnpicklingError, EOFError ... from every later run);
    * a file that cannot be written (a read-only cache or install) is not
      written: numba raised PermissionError from the first new kernel;
    * no writable place for a cache at all: the kernel is not cached (numba
      raised RuntimeError 'no locator available' at import);
    * two processes saving kernels of one function at once (``--jobs 2`` of
      the fuzzer, parallel test runs): numba named a new entry's data file
      by the first free number of the index it had read, and saved the
      index before the data, so two processes could give two variants one
      data file, and a later process loaded one variant's machine code for
      the other (different pixels, found by the fuzz).  Here the data file's
      name comes from the entry's key, the data is written before the index
      names it, and the index is read again just before it is written.

    Each trouble warns once (:func:`cache_trouble`)."""
    from numba.core import dispatcher
    cls = caching.IndexDataCacheFile
    if getattr(cls, "_vgx_tolerant", False):
        return
    load_index, load_data = cls._load_index, cls._load_data

    def _load_index(self):
        try:
            return load_index(self)
        except OSError:
            raise
        except Exception as e:      # unreadable: as if there were no index yet
            cache_trouble(f"damaged index {self._index_path} ({type(e).__name__})")
            return {}

    def _load_data(self, name):
        try:
            return load_data(self, name)
        except OSError:
            raise
        except Exception as e:      # numba's load() treats OSError as a missing file
            cache_trouble(f"damaged data file {name} ({type(e).__name__})")
            raise OSError(f"damaged numba cache file {name}: {e}") from e

    def _save(self, key, data):
        try:
            name = self._load_index().get(key) or self._data_name(_key_number(key))
            self._save_data(name, data)          # before any index names it
            overloads = self._load_index()       # what other processes saved meanwhile
            overloads[key] = name
            self._save_index(overloads)
        except OSError as e:
            cache_trouble(f"cannot write {self._index_path} ({e.strerror or e})")

    enable = dispatcher.Dispatcher.enable_caching

    def _enable_caching(self):
        try:
            enable(self)
        except RuntimeError as e:   # no locator: nowhere to keep a cache
            cache_trouble(str(e))
            self._cache = caching.NullCache()

    cls._load_index, cls._load_data, cls.save = _load_index, _load_data, _save
    dispatcher.Dispatcher.enable_caching = _enable_caching
    cls._vgx_tolerant = True


_tolerate_damaged_cache()


def njit(fn=None, **extra):
    """numba.njit with the project's options (cache on, fastmath off), for a
    kernel that calls no helper of another file."""
    opts = dict(_opts, **extra)
    if fn is None:
        return lambda f: numba.njit(**opts)(f)
    return numba.njit(**opts)(fn)


#: the files whose source every kernel of :func:`kernel` may inline
KERNEL_SOURCES = ("scan/*.py", "raster/*.py", "config.py", "jit.py", "framebuffer/zmax.py")


def _source_hash():
    h = hashlib.sha1()
    for pattern in KERNEL_SOURCES:
        for f in sorted(_PKG.glob(pattern)):
            h.update(f.read_bytes())
    return h.hexdigest()[:16]


KERNEL_SOURCE_HASH = _source_hash()


class _KeyedCache(caching.FunctionCache):
    """numba's disk cache of one kernel, its entries keyed on a tag (the
    kernel sources' hash and the variant) instead of the closure's cells.
    numba keys a closure on its pickled cells, and a cell holding a
    dispatcher (a variant's per-fragment stages) pickles with an id drawn
    anew in every process: such a kernel was compiled again by every
    process.  The tag names everything the cells hold (they are made from
    the variant's key and the hashed sources)."""

    def __init__(self, py_func, tag):
        self._tag = tag
        super().__init__(py_func)

    def _index_key(self, sig, codegen):
        code = hashlib.sha256(self._py_func.__code__.co_code).hexdigest()
        return (sig, codegen.magic_tuple(), code, self._tag)


def kernel(fn=None, *, variant=()):
    """A kernel that inlines helpers (:func:`helper`, :func:`inline`) of other
    files: :func:`njit`, with its disk cache keyed on KERNEL_SOURCE_HASH, so
    that an edit of any helper compiles it again (numba keys a function's
    cache on its own file only), and on ``variant`` (a kernel factory's
    RasterKey: each variant has its own cache entries whatever its closure
    holds).  ``kernel(f)``, ``@kernel`` or ``@kernel(variant=key)``."""
    if fn is None:
        return lambda f: kernel(f, variant=variant)
    disp = numba.njit(**_opts)(fn)
    if _opts.get("cache") and isinstance(disp, numba.core.registry.CPUDispatcher) and \
            not isinstance(disp._cache, caching.NullCache):
        try:
            disp._cache = _KeyedCache(fn, KERNEL_SOURCE_HASH + repr(tuple(variant)))
        except RuntimeError as e:   # no locator (see _tolerate_damaged_cache)
            cache_trouble(str(e))
    return disp


def helper(fn):
    """A small function inlined into kernels.  Not cached on its own: numba's
    cache of a function is keyed on its own file only, so a cached helper
    would keep old code inside kernels after an edit.  Kernels that use
    helpers are compiled through :func:`kernel`, whose cache is keyed on
    every helper's source.  Helpers are called from compiled code only, so
    they are compiled without the CPython and C wrappers (each helper's
    compile costs about 40 % less; the cold start compiles some twenty of
    them)."""
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

