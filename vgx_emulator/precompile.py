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

Having saved the walker, the second process lowers its priority and goes
on (:func:`exercise`) to compile what the program is likely to need next:
the general variants of the walker, lines, points and pixel writes
(vgx_emulator/specialise.py), on which a raster state whose own kernel is
not compiled yet runs at once, and the kernels of the primitives four
spheres does not draw (lines, points, rectangles, text, pixel writes).

It runs once per cache (a warm cache starts nothing), only with more than
one core, and never from itself; ``VGX_PRECOMPILE=0`` turns it off (the
compile-cost benchmark does, to time each kernel apart).  It outlives the
program when the program ends first (what it saves serves the next
process), but not a cache directory that is removed (:func:`stop_with_cache`).
"""
import os
import subprocess
import sys
import threading
import time

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


def stop_with_cache(period=0.2):
    """In a second process (this module's, or specialise.serve's): end it
    as soon as the directory of ``NUMBA_CACHE_DIR`` it fills is removed (a
    test's or benchmark's temporary cache, deleted once its own process is
    done).  Left alone, such a process compiled on for nobody and numba
    made the directory again to save into it.  The directory is held open
    and watched from a thread (a removed directory has no links left, even
    if a directory of the same name is made again); the default cache,
    beside the sources, is not watched.  Returns the thread, or None."""
    import numba
    root = numba.config.CACHE_DIR
    if not root:
        return None
    try:
        fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:                     # already gone (or unreadable): nothing to fill
        os._exit(0)

    def watch():
        while True:
            try:
                gone = os.fstat(fd).st_nlink == 0
            except OSError:
                gone = True
            if gone:
                os._exit(0)
            time.sleep(period)

    t = threading.Thread(target=watch, name="vgx-cache-watch", daemon=True)
    t.start()
    return t


def running():
    """Whether the second process of this cold start is still compiling."""
    return bool(_started and _started[0] is not None and _started[0].poll() is None)


def common_key():
    """The raster key of a z-buffered, Gouraud-shaded RGB pass with colour
    and z writes (raster.variants.RasterKey)."""
    from .raster.variants import RasterKey
    return RasterKey(ztest=True, zwrite=True, color=True, gouraud=True, cmode=False,
                     twoside=False, stencil=0, blend=0, logic=False, atest=False,
                     pattern=False, cmask=False, texture=False, dual=False)


def warm(keys=None):
    """Compile the walker of each raster key (by default the common one)
    with the argument types a pass gives it (one triangle, not drawn, in an
    8 x 8 bank set), so that it is saved to the disk cache; then, by
    default, :func:`exercise`."""
    from .framebuffer import Framebuffer
    from .geometry import WindowWork
    from .geometry.batch import FILLED
    from .raster import variants
    from . import scan, specialise
    from .state import WindowState
    stop_with_cache()
    specialise.MODE = "0"               # each key's own walker
    fb = Framebuffer(8, 8)
    if keys is None:
        specialise.lower_priority()
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
    if keys is None:
        exercise()


def exercise():
    """Draw, in a small window and with every pass on its family's general
    variant (specialise.MODE "always"), what programs draw soon after their
    first picture: a Gouraud and a flat z-buffered polygon, lines, points,
    lrectwrite, rectcopy, text, a stencil clear, a blended polygon and
    line, a textured polygon, then the same in colour-map mode.  That
    compiles the general variants of the walker, of lines, points and
    pixel writes (RGB, blended, textured and colour map), on which a
    raster state whose own kernels are not compiled yet runs
    (vgx_emulator/specialise.py), and the kernels of those primitives that
    four spheres does not use, with the argument types of real calls."""
    import irisgl as gl
    from . import specialise
    specialise.MODE = "always"
    gl.prefsize(16, 16)
    gl.winopen("precompile")
    gl.RGBmode()
    gl.stensize(8)
    gl.gconfig()
    _exercise_window(gl, lambda i: gl.c3f([(1, 0, 0), (0, 1, 0), (0, 0, 1)][i]))
    gl.sclear(0)
    gl.shademodel(gl.GOURAUD)           # the default, and what lit programs use
    gl.blendfunction(gl.BF_SA, gl.BF_MSA)     # the general variant with blending
    gl.bgnpolygon()
    for v in ((1, 1), (14, 2), (5, 13)):
        gl.v2f(v)
    gl.endpolygon()
    gl.move2(1, 1)                      # (smoothed lines blend: linesmooth(3G))
    gl.draw2(12, 9)
    gl.blendfunction(gl.BF_ONE, gl.BF_ZERO)
    gl.texdef2d(1, 4, 2, 2, np.full(4, 0xffffffff, np.uint32), 0, [gl.TX_NULL])
    gl.tevdef(1, 0, [gl.TV_MODULATE, gl.TV_NULL])
    gl.texbind(gl.TX_TEXTURE_0, 1)
    gl.tevbind(gl.TV_ENV0, 1)
    gl.bgnpolygon()
    for s, t in ((0, 0), (1, 0), (1, 1)):
        gl.t2f((s, t))
        gl.v2f((1 + 12 * s, 1 + 12 * t))
    gl.endpolygon()
    gl.texbind(gl.TX_TEXTURE_0, 0)
    gl.lrectread(0, 0, 0, 0)
    gl.cmode()
    gl.gconfig()
    _exercise_window(gl, lambda i: gl.color(3 + i))
    gl.gexit()


def _exercise_window(gl, colour):
    """exercise's drawing in one mode; ``colour(i)``: vertex i's colour call."""
    gl.ortho2(-0.5, 15.5, -0.5, 15.5)
    gl.zbuffer(1)
    gl.czclear(0, gl.getgdesc(gl.GD_ZMAX))
    for shade in (gl.GOURAUD, gl.FLAT):
        gl.shademodel(shade)
        gl.bgnpolygon()
        for i, v in enumerate(((1, 1), (14, 2), (5, 13))):
            colour(i)
            gl.v2f(v)
        gl.endpolygon()
        gl.rectf(2, 2, 9, 9)
        gl.move2(1, 1)
        gl.draw2(12, 9)
        gl.bgnpoint()
        gl.v2f((3, 3))
        gl.endpoint()
        gl.gflush()
    gl.lrectwrite(0, 0, 1, 1, np.zeros(4, np.uint32))
    gl.rectcopy(0, 0, 3, 3, 8, 8)
    gl.cmov2(2, 2)
    gl.charstr("Ab")
    gl.gflush()
    gl.lrectread(0, 0, 0, 0)


def _no_setup(work, key, ip):
    """The walker's setup argument without compiling the setup kernel: the
    arrays setup_triangles makes, for a triangle that is not drawn."""
    from .scan.triangles import T_COLUMNS
    rows = np.array([[1, 0]], np.int32)
    return np.zeros((1, T_COLUMNS), np.int64), np.zeros(1), rows
