"""What a raster state a process has not drawn before costs, with and
without the general variants (vgx_emulator/specialise.py).

A machine's cache after its first run: a fresh process draws four spheres
into a new, empty ``NUMBA_CACHE_DIR`` and waits for the second process
that a cold cache starts (vgx_emulator/precompile.py: the commonest walker,
then the general variants of the walker, lines and points).  The cache is
copied, and two fresh processes then draw four spheres and, one after the
other, the raster states of ``compile_cost.py``'s ``states`` workload
(lines, points, lrectwrite, rectcopy, stencil, blend, logicop, afunction,
a pattern, writemask, texture, colour map), each step timed from its first
call until its pixels can be read back (``lrectread`` waits for the raster
thread):

* ``VGX_GENERAL=1`` (the default): a state whose own kernel is not in the
  cache runs on the general variant of its family; the steps are run
  three times (the third use asks a second process for the state's own
  variant: ``config.SPECIALISE_AFTER``), and after ``specialise.wait()``
  once more, their own variants loaded from the cache;
* ``VGX_GENERAL=0``: each state compiles its own kernel in the process.

    python benchmarks/new_state.py

Timings move with the machine's load (a shared 2-core VM): compare the
columns of one run.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

PREPARE = r"""
import sys
sys.path.insert(0, %(root)r)
from benchmarks.compile_cost import _spheres
from vgx_emulator import precompile
_spheres()
if precompile._started and precompile._started[0] is not None:
    precompile._started[0].wait(900)
"""

CHILD = r"""
import json, sys, time
sys.path.insert(0, %(root)r)
from benchmarks.compile_cost import STATE_STEPS, _spheres
from irisgl import lrectread
from vgx_emulator import specialise
_spheres()

def timed():
    out = {}
    for name, fn in STATE_STEPS:
        t = time.perf_counter()
        fn()
        lrectread(0, 0, 0, 0)
        out[name] = time.perf_counter() - t
    return out

first = timed()
timed()
third = timed()              # the use that asks for the own variant (config.SPECIALISE_AFTER)
t = time.perf_counter()
specialise.wait(900)
waited = time.perf_counter() - t
print(json.dumps(dict(first=first, third=third, loaded=timed(), waited=waited)))
"""


def _python(code, cache, **env):
    e = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT), **env)
    r = subprocess.run([sys.executable, "-c", code % dict(root=str(ROOT))],
                       capture_output=True, text=True, env=e, cwd=ROOT)
    if r.returncode:
        sys.exit(r.stderr[-3000:])
    return r.stdout


def main():
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp) / "base"
        t = time.perf_counter()
        _python(PREPARE, base)
        prepared = time.perf_counter() - t
        runs = {}
        for mode in ("1", "0"):
            cache = Path(tmp) / f"mode{mode}"
            shutil.copytree(base, cache)
            out = _python(CHILD, cache, VGX_GENERAL=mode)
            runs[mode] = json.loads(out.strip().splitlines()[-1])
    print(f"cache prepared (four spheres, cold, with the second process) in {prepared:.1f} s\n")
    print("| state, first use in the process | VGX_GENERAL=1 ms | VGX_GENERAL=0 ms | "
          "third use ms | own variant loaded ms |")
    print("|---|---|---|---|---|")
    on, off = runs["1"], runs["0"]
    for name in on["first"]:
        if name == "window":
            continue
        print(f"| {name} | {1e3 * on['first'][name]:.0f} | {1e3 * off['first'][name]:.0f} | "
              f"{1e3 * on['third'][name]:.0f} | {1e3 * on['loaded'][name]:.0f} |")

    def total(run):
        return 1e3 * sum(v for k, v in run.items() if k != "window")
    print(f"| all of them | {total(on['first']):.0f} | {total(off['first']):.0f} | "
          f"{total(on['third']):.0f} | {total(on['loaded']):.0f} |")
    print(f"\nthe second process had finished {on['waited']:.1f} s after the last first use")


if __name__ == "__main__":
    main()
