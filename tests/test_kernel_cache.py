"""numba's disk cache: every kernel is served from it in the next process,
and a damaged cache is compiled again, not fatal."""
import subprocess
import sys

#: a numba listener that records the qualified name of every kernel a
#: process compiles (a load from the disk cache is not a compile)
LISTEN = r"""
import numba.core.event as ev
import numpy as np


class Compiled(ev.Listener):
    def __init__(self):
        self.names = []

    def on_start(self, event):
        self.names.append(event.data["dispatcher"].py_func.__qualname__)

    def on_end(self, event):
        pass


compiled = Compiled()
ev.register("numba:compile", compiled)
"""

SCRIPT = LISTEN + r"""
from irisgl import *
prefsize(32, 32); winopen("x"); RGBmode(); doublebuffer(); stensize(4); gconfig()
ortho2(-0.5, 31.5, -0.5, 31.5)
cpack(0xff00ff00); clear()
zbuffer(TRUE); czclear(0, getgdesc(GD_ZMAX))
shademodel(GOURAUD)
bgnpolygon(); c3f((1, 0, 0)); v2f((1, 1)); c3f((0, 1, 0)); v2f((30, 2)); c3f((0, 0, 1)); v2f((9, 28))
endpolygon()
move2(1, 1); draw2(20, 25)                              # a line
bgnpoint(); v2f((3, 3)); endpoint()                     # a point
lrectwrite(0, 0, 1, 1, np.zeros(4, np.uint32))          # pixel writes
rectcopy(0, 0, 3, 3, 10, 10)
sclear(0); stencil(TRUE, 1, SF_ALWAYS, 0xf, ST_KEEP, ST_KEEP, ST_INCR)
rectf(2, 2, 12, 12)                                     # stencil counting
stencil(FALSE, 0, SF_ALWAYS, 0xf, ST_KEEP, ST_KEEP, ST_KEEP)
blendfunction(BF_SA, BF_MSA); rectf(4, 4, 20, 20); blendfunction(BF_ONE, BF_ZERO)
defpattern(1, 16, [0x5555, 0xaaaa] * 8); setpattern(1); rectf(0, 0, 31, 31); setpattern(0)
cmov2(2, 2); charstr("Ab")
gflush()
print(int(lrectread(5, 5, 5, 5)[0, 0]))
import sys
print("refreshed:", "numba.misc.cffiimpl" in sys.modules, "scipy.linalg" in sys.modules)
print("compiled:", " ".join(compiled.names))
"""


def _run(cache_dir):
    import os
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    r = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True,
                       timeout=900, env=env)
    assert r.returncode == 0, r.stderr[-3000:]
    pixel, refreshed, compiled = r.stdout.strip().split("\n")[-3:]
    return pixel, compiled.split()[1:], refreshed.split()[1:]


def test_the_next_process_compiles_nothing(tmp_path):
    """Every kernel a process compiled is served from numba's disk cache in
    the next process: triangles (Gouraud, z), lines, points, lrectwrite,
    rectcopy, stencil, blend, a pattern, text.  (A kernel whose cache key
    differed between processes, e.g. a closure cell that pickled with a
    fresh id, was compiled again by every process.)"""
    first_pixel, first, refreshed = _run(tmp_path)
    assert first                               # the first process did compile
    assert refreshed == ["True", "False"]      # numba's registries, not its BLAS probe
    pixel, again, refreshed = _run(tmp_path)
    assert again == []
    assert pixel == first_pixel
    assert refreshed == ["False", "False"]     # loads alone refresh nothing (jit._lean_cache_loads)


def test_a_compile_after_cache_loads_refreshes_numba(tmp_path):
    """A process whose kernels all came from the disk cache (so numba's
    registries were never refreshed, jit._lean_cache_loads) still compiles
    a new function, with numba's full registries (np.linalg needs them)."""
    _run(tmp_path)
    script = DRAW + r"""
import sys, numba, numpy as np
assert "numba.misc.cffiimpl" not in sys.modules
f = numba.njit(lambda a: np.sum(a * 2.0) + len(str(3)))
print(f(np.arange(4.0)))
"""
    import os
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       timeout=600, env=env)
    assert r.returncode == 0, r.stderr[-3000:]
    assert r.stdout.split()[-1] == "13.0"


DRAW = r"""
from irisgl import *
prefsize(16, 16); winopen("x"); RGBmode(); gconfig()
ortho2(-0.5, 15.5, -0.5, 15.5)
cpack(0xffffffff); clear(); move2(1, 1); draw2(10, 12); rectf(2, 2, 5, 5); gflush()
print(int(lrectread(3, 3, 3, 3)[0, 0]))
"""


def _draw(cache_dir):
    import os
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    return subprocess.run([sys.executable, "-c", DRAW], capture_output=True, text=True,
                          timeout=600, env=env)


def test_a_damaged_cache_is_compiled_again_not_fatal(tmp_path):
    """Garbage in every index and data file of the cache: the next run
    compiles again and draws the same, instead of dying with UnpicklingError."""
    first = _draw(tmp_path)
    assert first.returncode == 0, first.stderr
    files = [p for p in tmp_path.rglob("*") if p.suffix in (".nbi", ".nbc")]
    assert files
    for p in files:
        data = p.read_bytes()
        p.write_bytes(data[:len(data) // 3] + b"\x80garbage")
    again = _draw(tmp_path)
    assert again.returncode == 0, again.stderr[-2000:]
    assert again.stdout == first.stdout


READ_ONLY = r"""
import builtins, os, sys, tempfile
CACHE = os.environ["NUMBA_CACHE_DIR"]
_open = builtins.open


def read_only_open(f, mode="r", *a, **k):
    # a read-only cache (root is not stopped by file modes): nothing under it is written
    if any(c in mode for c in "wax+") and os.path.abspath(str(f)).startswith(CACHE):
        raise PermissionError(30, "Read-only file system", str(f))
    return _open(f, mode, *a, **k)


def no_place(*a, **k):
    # nowhere writable at all: every cache locator numba tries fails
    raise PermissionError(30, "Read-only file system")


builtins.open = read_only_open
if sys.argv[1] == "nowhere":
    tempfile.TemporaryFile = no_place
import warnings
warnings.simplefilter("always")
"""

MORE = r"""
blendfunction(BF_SA, BF_MSA); rectf(4, 4, 9, 9); gflush()      # a kernel not cached yet
print(int(lrectread(5, 5, 5, 5)[0, 0]))
"""


def _read_only(cache_dir, how):
    import os
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    return subprocess.run([sys.executable, "-c", READ_ONLY + DRAW + MORE, how],
                          capture_output=True, text=True, timeout=900, env=env)


def test_a_read_only_cache_is_used_and_never_stops_a_run(tmp_path):
    """A cache that cannot be written: kernels in it are loaded, a kernel not
    in it is compiled and not saved, with one warning (numba raised
    PermissionError from the first new kernel)."""
    first = _draw(tmp_path)
    assert first.returncode == 0, first.stderr
    r = _read_only(tmp_path, "read-only")
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split("\n")[0] == first.stdout.strip()
    assert r.stderr.count("VGXWarning: numba cache: cannot write") == 1


def test_no_writable_place_for_a_cache_never_stops_a_run(tmp_path):
    """No cache directory can be written anywhere (a read-only install and
    home): the kernels are compiled without a cache, with one warning (numba
    raised RuntimeError 'no locator available' at import)."""
    r = _read_only(tmp_path, "nowhere")
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split("\n")[0] == _draw(tmp_path).stdout.strip()
    assert r.stderr.count("VGXWarning: numba cache:") == 1


def test_a_damaged_cache_warns_once(tmp_path):
    """Every cache file garbled: one warning for the whole run."""
    assert _draw(tmp_path).returncode == 0
    for p in tmp_path.rglob("*.nb[ic]"):
        p.write_bytes(b"\x80garbage")
    env_run = subprocess.run([sys.executable, "-W", "always", "-c", DRAW], capture_output=True,
                             text=True, timeout=900,
                             env=dict(__import__("os").environ, NUMBA_CACHE_DIR=str(tmp_path)))
    assert env_run.returncode == 0, env_run.stderr[-2000:]
    assert env_run.stderr.count("VGXWarning: numba cache: damaged") == 1


def test_two_processes_saving_at_once_never_share_a_data_file(tmp_path):
    """Two processes read the same index, then save two variants of one
    kernel, the first one's data written last (numba wrote the index, then
    the data).  numba gave both the first free data file, so the index named
    the second variant and the file held the first: the next process ran
    one variant's code for the other (found by the fuzz, --jobs 2).  Each
    entry must load its own data."""
    import vgx_emulator.jit  # noqa: F401  (installs the cache's guards)
    from numba.core import caching
    p = caching.IndexDataCacheFile(str(tmp_path), "walk", "stamp")
    q = caching.IndexDataCacheFile(str(tmp_path), "walk", "stamp")
    stale = {}
    p._load_index = q._load_index = lambda: dict(stale)      # both read it empty
    deferred = []
    write_data = p._save_data
    p._save_data = lambda name, data: deferred.append((name, data))
    p.save(("variant", 1), "code of variant 1")
    q.save(("variant", 2), "code of variant 2")
    for name, data in deferred:                              # p's data lands last
        write_data(name, data)
    r = caching.IndexDataCacheFile(str(tmp_path), "walk", "stamp")
    for key, name in r._load_index().items():
        assert r._load_data(name) == f"code of variant {key[1]}"
