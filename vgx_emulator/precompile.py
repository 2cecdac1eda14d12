"""A cold start's longest compiles, made in a second process meanwhile.

With an empty numba cache the first picture waits for every kernel it uses
to be compiled, one after the other (numba compiles under one lock per
process): the geometry kernels first, then triangle setup, then the
triangle walker, the longest (benchmarks/compile_cost.py).  When
``import vgx_emulator`` finds the cache cold (no triangle setup kernel of
the current sources in it), it starts a Python process running :func:`warm`:
that process compiles the walker of the commonest raster state (z-buffered,
Gouraud, RGB: four_spheres' and most lit programs') and saves it to the
shared disk cache, while this process compiles the geometry kernels and
triangle setup.  By the time this process needs the walker it loads
it from the cache (numba looks there before compiling a new signature);
had the other process not finished, this one compiles it as it would have.
Nothing but the disk cache passes between them, so a failure of the
second process costs only its time.

It runs once per cache (a warm cache starts nothing), only with more than
one core, and never from itself; ``VGX_PRECOMPILE=0`` turns it off (the
compile-cost benchmark does, to time each kernel apart).
"""
import os
import subprocess
import sys

import numpy as np

from . import config

_started = []


def cache_is_cold():
    """Whether numba's disk cache holds no triangle setup kernel compiled
    from the current kernel sources (jit.KERNEL_SOURCE_HASH)."""
    from .scan import triangles as T
    cache = getattr(T._setup_kernel, "_cache", None)
    tag = getattr(cache, "_tag", None)
    if tag is None:                     # caching off, or no place for a cache
        return False
    try:
        index = cache._cache_file._load_index()
    except Exception:                   # unreadable: jit.py treats it as missing too
        return True
    return not any(isinstance(k, tuple) and k and k[-1] == tag for k in index)


def start_if_cold():
    """Start the second process when the cache is cold (module docstring);
    returns its Popen, or None."""
    if _started or os.environ.get("VGX_PRECOMPILE", "1") == "0" or \
            os.environ.get("NUMBA_DISABLE_JIT", "0") == "1" or (os.cpu_count() or 1) < 2:
        return None
    _started.append(None)
    if not cache_is_cold():
        return None
    env = dict(os.environ, VGX_PRECOMPILE="0")
    try:
        p = subprocess.Popen([sys.executable, "-c", "from vgx_emulator.precompile import warm; warm()"],
                             env=env,
                             stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL, start_new_session=True)
    except OSError:
        return None
    _started[0] = p
    return p


def common_key():
    """The raster key of a z-buffered, Gouraud-shaded RGB pass with colour
    and z writes (raster.variants.RasterKey)."""
    from .raster.variants import RasterKey
    return RasterKey(ztest=True, zwrite=True, color=True, gouraud=True, cmode=False,
                     twoside=False, stencil=0, blend=0, logic=False, atest=False,
                     pattern=False, cmask=False, texture=False, dual=False)


def warm(keys=None):
    """Compile the walker of each raster key with the argument types a pass
    gives it (one triangle in an 8 x 8 bank set), so that it is saved to the
    disk cache.  (Not triangle setup: the first process compiles it before
    this one could, as it needs it first.)"""
    from .framebuffer import Framebuffer
    from .geometry import WindowWork
    from .geometry.batch import FILLED
    from .raster import variants
    from . import scan
    from .state import WindowState
    fb = Framebuffer(8, 8)
    st = WindowState(8, 8)
    targets = [fb.queued("front")]
    X = np.array([1, 7, 1], np.int64) << config.SUBPIXEL_BITS
    Y = np.array([1, 1, 7], np.int64) << config.SUBPIXEL_BITS
    C = np.full((3, 4), 128.0)
    work = WindowWork(klass=FILLED, X=X, Y=Y, Z=np.zeros(3), C=C, CB=C,
                      tris=np.array([[0, 1, 2]], np.int64), prov=np.array([2], np.int64))
    _, ip = variants.choose(st, fb, targets, bits=0xFFFFFFFF, scissor=(0, 7, 0, 7),
                            origin=(0, 0))
    for key in keys or [common_key()]:
        planes = variants.banks(key, fb, targets)
        scan.scan_batch(work, key, planes, ip, 0, False, None, None,
                        _no_setup(work, key, ip))


def _no_setup(work, key, ip):
    """The walker's setup argument without compiling the setup kernel: the
    arrays setup_triangles makes, for a triangle that is not drawn."""
    from .scan.triangles import T_COLUMNS
    rows = np.array([[1, 0]], np.int32)
    return np.zeros((1, T_COLUMNS), np.int64), np.zeros(1), rows
