"""A raster state a process has not drawn before, without waiting for its
kernel to compile: the general variants, and the specialised ones compiled
by a second process.

Every kernel variant (raster/variants.py) is compiled for the stages its
raster state enables; compiling one costs 0.7-1.7 s of numba type inference
(benchmarks/compile_cost.py), which a program would wait for at the first
pass of each new state.  When the pass's own variant is neither compiled in
this process nor in the disk cache, :func:`choose` instead runs the
*general* variant of its family (``variants.general``: every stage compiled
in), with banks and parameters that make the stages the state leaves off
pass every fragment and change nothing (``variants.neutral``): the same
pixels, bit for bit, for the cost of loading one kernel that serves every
state of the family.  Meanwhile a second Python process compiles the
state's own variant into the shared disk cache (:func:`request`,
:func:`serve`), with the argument types this process would have called it
with (pickled numba types); once that process has finished, the next pass
of the state loads it from the cache and runs at full speed.

When the general variant is not available either (an empty cache: the first
run ever), the pass compiles its own variant as before, and the second
process compiles the general one for the next new state.  Nothing but the
disk cache passes between the processes, so a failure of the second costs
only time.

``VGX_GENERAL`` chooses: ``1`` (the default) as above; ``0`` always the
state's own variant, compiled here (as do one core, and a process without
JIT); ``always`` the general variant for every state whose own variant
differs from it, compiled here if need be, never a second process (the
tests draw every figure that way and compare).
"""
import os
import pickle
import subprocess
import sys
import threading
from collections import Counter

import numba

from . import config, precompile

#: "1", "0" or "always" (module docstring); tests set it directly
MODE = os.environ.get("VGX_GENERAL", "1")

_lock = threading.RLock()
_ready = set()          # (kind, key) whose own variant is compiled or cached
_requested = set()      # (kind, key) sent to (or queued for) a second process
_queue = []             # [(kind, key, argument types)] not yet sent
_child = []             # the running second process, if any
_uses = Counter()       # (kind, key): passes drawn on the general variant


def dispatcher(kind, key):
    """The numba dispatcher of one kernel variant: ``kind`` "walk" (the
    triangle walker), "line", "point" or "pixel" (lrectwrite, rectcopy)."""
    from .scan import lines, spans, triangles
    if kind == "walk":
        return triangles.walker(key)
    return {"line": lines.line_kernel, "point": lines.point_kernel,
            "pixel": spans.pixel_kernel}[kind](key)


def available(disp):
    """Whether ``disp`` runs without compiling: compiled in this process, or
    an entry of its variant (jit.kernel's tag) for this machine in the disk
    cache."""
    if disp.overloads:
        return True
    cache = getattr(disp, "_cache", None)
    tag = getattr(cache, "_tag", None)
    if tag is None:
        return False
    try:
        index = cache._cache_file._load_index()
        magic = disp.targetctx.codegen().magic_tuple()
    except Exception:                   # unreadable: as if missing (jit.py)
        return False
    return any(isinstance(k, tuple) and len(k) == 4 and k[3] == tag and k[1] == magic
               for k in index)


def background():
    """Whether a second process may compile (more than one core, JIT on,
    not inside such a process)."""
    return (os.cpu_count() or 1) > 1 and not numba.config.DISABLE_JIT and \
        os.environ.get("VGX_SPECIALISE_CHILD") != "1"


def choose(kind, key, planes, ip, types):
    """``(key, planes, ip)`` a pass of ``kind`` runs with: its own variant's
    when that one is available (compiled or cached), else the general
    variant's with neutral banks and parameters (module docstring), while a
    second process compiles the own one.  ``types()`` gives the numba types
    of the own variant's arguments (called only for a request)."""
    if MODE == "0" or numba.config.DISABLE_JIT or (kind, key) in _ready:
        return key, planes, ip
    from .raster import variants
    g = variants.general(key)
    if kind == "pixel":                 # (no z, stencil or pattern: machine.write_pixels)
        g = g._replace(ztest=False, zwrite=False, stencil=False, pattern=False)
    shape = variants.bank_shape(key, planes)
    if g == key or shape is None:
        return key, planes, ip
    if MODE == "always":
        return (g,) + variants.neutral(key, planes, ip, shape)
    with _lock:
        poll()
        # a state already on the general variant whose own is not asked for
        # yet, or still being compiled, does not read the cache index again
        known = (kind, key) in _uses and ((kind, key) not in _requested or pending())
        if not known:
            if available(dispatcher(kind, key)):
                _ready.add((kind, key))
                return key, planes, ip
            if not background():
                return key, planes, ip
            if not available(dispatcher(kind, g)):
                # no general variant yet: this pass compiles its own, a
                # second process the general one for the next new state
                # (unless the cold start's is making them: precompile.exercise)
                if not precompile.running():
                    request(kind, g, types)
                return key, planes, ip
        _uses[(kind, key)] += 1
        if _uses[(kind, key)] >= config.SPECIALISE_AFTER:
            request(kind, key, types)    # a state drawn again and again
    return (g,) + variants.neutral(key, planes, ip, shape)


def request(kind, key, types):
    """Have a second process compile ``kind``'s variant of ``key`` for the
    argument types ``types()`` into the disk cache (once per process)."""
    with _lock:
        if (kind, key) in _requested:
            return
        _requested.add((kind, key))
        _queue.append((kind, tuple(key), types()))
        poll()


def poll():
    """Start the second process on the queued requests when none is
    running (one at a time: each compiles all that was queued)."""
    with _lock:
        if _child and _child[0].poll() is None:
            return
        _child.clear()
        if not _queue:
            return
        work = pickle.dumps(list(_queue), protocol=4)
        del _queue[:]
        env = dict(os.environ, VGX_PRECOMPILE="0", VGX_SPECIALISE_CHILD="1",
                   VGX_GENERAL="0", NUMBA_NUM_THREADS="1")
        try:
            p = subprocess.Popen(
                [sys.executable, "-c", "from vgx_emulator.specialise import serve; serve()"],
                env=env, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL, start_new_session=True)
            p.stdin.write(work)
            p.stdin.close()
        except OSError:
            return
        _child.append(p)


def pending():
    """Whether a second process is compiling (for tests and benchmarks)."""
    with _lock:
        return bool(_queue) or bool(_child and _child[0].poll() is None)


def wait(timeout=120.0):
    """Wait until every request has been compiled (tests, benchmarks)."""
    import time
    end = time.monotonic() + timeout
    while pending() and time.monotonic() < end:
        poll()
        time.sleep(0.05)


def lower_priority():
    """The second process gives way to the program's (nice 5): its frames
    come first, the compile uses what CPU is left."""
    try:
        os.nice(5)
    except OSError:
        pass


def serve(stream=None):
    """The second process: compile each ``(kind, key, types)`` read
    (pickled) from stdin into the disk cache.  A failing one is skipped."""
    from .raster.variants import RasterKey
    precompile.stop_with_cache()
    lower_priority()
    for kind, key, types in pickle.load(stream or sys.stdin.buffer):
        try:
            dispatcher(kind, RasterKey(*key)).compile(types)
        except Exception:
            continue
