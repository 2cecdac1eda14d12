"""vgx_emulator/precompile.py: on a cold numba cache a second process
compiles the commonest walker while the first compiles the rest; the walker
it saves is the one a real pass loads (the same argument types)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest
from test_kernel_cache import LISTEN

ROOT = Path(__file__).resolve().parent.parent

DRAW = LISTEN + r"""
from vgx_emulator.runner import run_program
img = run_program(%r, frames=1)
print(int(img.sum()))
print("compiled:", " ".join(compiled.names))
"""

WALKER = "_make_triangle_kernel.<locals>.walk"
SETUP = "_make_setup.<locals>.setup_kernel"


def _python(code, cache, **env):
    e = dict(os.environ, NUMBA_CACHE_DIR=str(cache), **env)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=900, env=e, cwd=ROOT)
    assert r.returncode == 0, r.stderr[-3000:]
    return r.stdout.strip().splitlines()


def _draw(cache):
    """four_spheres' first picture in a fresh process without a second one:
    (picture checksum, the kernels it compiled)."""
    out = _python(DRAW % str(ROOT / "programs" / "four_spheres.py"), cache, VGX_PRECOMPILE="0")
    return int(out[-2]), out[-1].split()[1:]


def test_the_warmed_walker_is_the_one_a_pass_loads(tmp_path):
    """warm() of the common key alone (without exercise(), which draws and
    so compiles setup too) into an empty cache, then four spheres: the
    walker comes from the cache (warm gave it the argument types of a real
    pass), everything else is compiled (the cache was otherwise cold), and
    the picture is the one drawn with a cold cache."""
    cold_sum, cold_compiled = _draw(tmp_path / "cold")
    assert WALKER in cold_compiled and SETUP in cold_compiled
    _python("from vgx_emulator.precompile import warm, common_key; warm([common_key()])",
            tmp_path / "warm",
            VGX_PRECOMPILE="0")
    warm_sum, warm_compiled = _draw(tmp_path / "warm")
    assert WALKER not in warm_compiled
    assert SETUP in warm_compiled
    assert warm_sum == cold_sum


def test_a_cold_cache_starts_the_second_process_once(tmp_path):
    """import vgx_emulator with an empty cache starts the second process
    (which ends cleanly and leaves the walker and, from exercise(), setup
    in the cache); with
    VGX_PRECOMPILE=0, or once the cache is warm, nothing is started."""
    probe = ("import vgx_emulator, vgx_emulator.precompile as p\n"
             "q = p._started[0] if p._started else None\n"
             "print(None if q is None else q.wait(600))\n"
             "print(p.cache_is_cold())\n")
    assert _python(probe, tmp_path / "c", VGX_PRECOMPILE="0") == ["None", "True"]
    # started; its exercise() drew, so setup is in the cache too
    assert _python(probe, tmp_path / "c") == ["0", "False"]
    _, compiled = _draw(tmp_path / "c")
    assert WALKER not in compiled                                # the second process's walker
    assert _python(probe, tmp_path / "c") == ["None", "False"]  # warm now: nothing started


@pytest.mark.parametrize("env", [{"NUMBA_DISABLE_JIT": "1"}])
def test_nothing_is_started_without_compiling(tmp_path, env):
    """No JIT (coverage runs): nothing to compile, nothing started."""
    probe = ("import vgx_emulator.precompile as p, vgx_emulator\n"
             "print(bool(p._started and p._started[0]))\n")
    assert _python(probe, tmp_path / "n", **env) == ["False"]


def _ended(pid):
    """Whether process ``pid`` has ended (gone, or a zombie nobody reaped)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except OSError:
        return True


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc")
def test_the_second_process_ends_when_its_cache_is_removed(tmp_path):
    """A program on a temporary cache starts the second process and ends;
    the cache directory is removed while the second process compiles: the
    second process ends within seconds (instead of compiling on for
    nobody) and does not make the directory again."""
    import shutil
    import time
    cache = tmp_path / "c"
    cache.mkdir()
    probe = ("import vgx_emulator.precompile as p, vgx_emulator\n"
             "print(p._started[0].pid)\n")
    pid = int(_python(probe, cache)[-1])
    assert not _ended(pid)              # (the compile takes seconds: still running)
    shutil.rmtree(cache, ignore_errors=True)
    deadline = time.monotonic() + 20
    while not _ended(pid) and time.monotonic() < deadline:
        shutil.rmtree(cache, ignore_errors=True)    # (one save may race the removal)
        time.sleep(0.1)
    assert _ended(pid)
    shutil.rmtree(cache, ignore_errors=True)
    time.sleep(0.5)
    assert not cache.exists()
