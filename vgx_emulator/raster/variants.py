"""RasterKey: the pipeline state that selects a compiled kernel variant.

Kernels are specialised on which stages a pass *enables*, not on the values
those stages take (z function, masks, ...: those are runtime integers).  The
one exception is the pair of blend factors: the per-component factor
arithmetic is the costliest per-fragment work, and with the factors known
at compile time it folds to what the pair needs.  That is done for the
common pairs of blend.FOLDED; every other pair shares one generic kernel
that reads the factors at run time, so the variants stay few.  So
a depth-only pass compiles to a loop with no colour work, a scene without a
z-buffer never touches z memory, and the set of variants stays small (each
field is a bool; only the combinations a program uses are compiled).

``KERNEL_SOURCE_HASH`` hashes the source of every module a kernel inlines;
it is a closure constant of each factory-built kernel, so numba's disk cache
(keyed on closure values) is invalidated when any of them changes
(docs/architecture.md, Kernels).
"""
import hashlib
from collections import namedtuple
from pathlib import Path

_PKG = Path(__file__).resolve().parent.parent


def _source_hash():
    h = hashlib.sha1()
    for sub in ("scan", "raster"):
        for f in sorted((_PKG / sub).glob("*.py")):
            h.update(f.read_bytes())
    h.update((_PKG / "config.py").read_bytes())
    h.update((_PKG / "jit.py").read_bytes())
    h.update((_PKG / "framebuffer" / "zmax.py").read_bytes())
    return h.hexdigest()[:16]


KERNEL_SOURCE_HASH = _source_hash()

#: Fields of the raster key, in kernel-factory argument order.
#: ``blend``: 0, or blend.key_code(sfactr, dfactr): a folded pair, or GENERIC.
#: ``stencil``: 0 off, 1 tested only (every op ST_KEEP or swritemask 0: the
#: triangle walker then never stores the bank), 2 tested and written.
#: ``dual``: drawing goes to two colour buffers (frontbuffer and backbuffer
#: both enabled), so that the common one-buffer loop has no per-pixel test.
RasterKey = namedtuple("RasterKey", "ztest zwrite color gouraud cmode twoside "
                                    "stencil blend logic atest pattern cmask texture dual")


def cache_tag(*key):
    """The closure constant that keys a kernel variant's disk cache: the
    source hash and every field of its key.  numba keys a cached closure on
    its cells, and a kernel whose body no longer names a flag (the stages
    reach it through jit.bind_globals) would otherwise share its cache entry
    with the variant that differs only in that flag."""
    return KERNEL_SOURCE_HASH + repr(tuple(key))
