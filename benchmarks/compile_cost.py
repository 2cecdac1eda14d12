"""What each numba kernel costs to compile, and to load from the disk cache.

Runs a workload in fresh processes with a new, empty ``NUMBA_CACHE_DIR``
(the first compiles, the second loads what the first saved, the third is
started again to check that nothing compiles twice) and prints one markdown
table per run: every kernel the process needed, in the order it was first
called, with the seconds it took (compile or load, helpers it compiled
included) and whether it came from the disk cache.

Workloads (``--workload``):

* ``spheres``: the first picture of programs/four_spheres.py (the cold
  start of docs/performance.md);
* ``states``: that picture, then a run of raster states a program meets
  later (lines, points, lrectwrite, rectcopy, stencil, blend, logicop,
  afunction, a pattern, a texture, colour-map mode), each timed apart: the
  cost of a state a process has not used before.

    python benchmarks/compile_cost.py [--workload spheres|states|both]

Timings move with the machine's load (a shared 2-core VM): compare rows of
one run.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: run in the child: time every Dispatcher.compile (a cache load or a
#: compile), innermost first, and the wall time of each workload step
CHILD = r"""
import json, sys, time
T0 = time.perf_counter()
import numba.core.dispatcher as _d
_orig = _d.Dispatcher.compile
RECORDS, STACK = [], []

def compile(self, sig):
    before = sum(self._cache_hits.values())
    STACK.append(0.0)
    t = time.perf_counter()
    try:
        return _orig(self, sig)
    finally:
        dt = time.perf_counter() - t
        inner = STACK.pop()
        if STACK:
            STACK[-1] += dt
        else:
            f = self.py_func
            RECORDS.append(dict(name=f.__qualname__.replace(".<locals>", ""),
                                module=f.__module__.rsplit(".", 1)[-1],
                                seconds=dt, helpers=inner,
                                hit=sum(self._cache_hits.values()) > before,
                                step=STEP[0]))
_d.Dispatcher.compile = compile
STEP = ["import"]
import irisgl
T_IMPORT = time.perf_counter() - T0
steps = {}
sys.path.insert(0, %(root)r)
from benchmarks.compile_cost import STEPS
for name, fn in STEPS[%(workload)r]:
    STEP[0] = name
    t = time.perf_counter()
    fn()
    steps[name] = time.perf_counter() - t
print(json.dumps(dict(records=RECORDS, steps=steps, import_s=T_IMPORT,
                      total=time.perf_counter() - T0)))
"""


# ----------------------------------------------------------------------------
# workload steps (run in the child)

def _spheres():
    """four_spheres' first frame to a PNG, as vgx-run draws it."""
    from vgx_emulator.display.png import write_png
    from vgx_emulator.runner import run_program
    out = Path(tempfile.gettempdir()) / f"compile_cost_{os.getpid()}.png"
    write_png(str(out), run_program(str(ROOT / "programs" / "four_spheres.py"), frames=1))
    out.unlink()


def _window():
    from irisgl import (RGBmode, doublebuffer, gconfig, ortho2, prefsize, stensize,
                        winopen)
    prefsize(64, 64)
    winopen("states")
    RGBmode()
    doublebuffer()
    stensize(8)
    gconfig()
    ortho2(-0.5, 63.5, -0.5, 63.5)


def _quad():
    from irisgl import gflush, rectf
    rectf(4, 4, 40, 40)
    gflush()


def _step_lines():
    from irisgl import cpack, draw2, gflush, move2
    cpack(0xff00ff00)
    move2(1, 1)
    draw2(50, 30)
    gflush()


def _step_points():
    from irisgl import bgnpoint, endpoint, gflush, v2f
    bgnpoint()
    v2f((3, 3))
    endpoint()
    gflush()


def _step_lrectwrite():
    import numpy as np
    from irisgl import lrectwrite
    lrectwrite(0, 0, 7, 7, np.full(64, 0xff0000ff, np.uint32))


def _step_rectcopy():
    from irisgl import rectcopy
    rectcopy(0, 0, 7, 7, 20, 20)


def _step_stencil():
    from irisgl import (SF_ALWAYS, ST_INCR, ST_KEEP, sclear, stencil, zbuffer, czclear,
                        getgdesc, GD_ZMAX)
    zbuffer(1)
    czclear(0, getgdesc(GD_ZMAX))
    sclear(0)
    stencil(1, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_INCR)
    _quad()
    stencil(0, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)


def _step_blend():
    from irisgl import BF_MSA, BF_ONE, BF_SA, BF_ZERO, blendfunction
    blendfunction(BF_SA, BF_MSA)
    _quad()
    blendfunction(BF_ONE, BF_ZERO)


def _step_blend_generic():
    from irisgl import BF_DA, BF_MDA, BF_ONE, BF_ZERO, blendfunction
    blendfunction(BF_DA, BF_MDA)
    _quad()
    blendfunction(BF_ONE, BF_ZERO)


def _step_logicop():
    from irisgl import LO_SRC, LO_XOR, logicop
    logicop(LO_XOR)
    _quad()
    logicop(LO_SRC)


def _step_afunction():
    from irisgl import AF_ALWAYS, AF_GEQUAL, afunction
    afunction(128, AF_GEQUAL)
    _quad()
    afunction(0, AF_ALWAYS)


def _step_pattern():
    from irisgl import defpattern, setpattern
    defpattern(1, 16, [0x5555, 0xAAAA] * 8)
    setpattern(1)
    _quad()
    setpattern(0)


def _step_writemask():
    from irisgl import wmpack
    wmpack(0xff00ff00)
    _quad()
    wmpack(0xffffffff)


def _step_texture():
    import numpy as np
    from irisgl import (TX_TEXTURE_0, TV_ENV0, TV_MODULATE, TV_NULL, TX_NULL, bgnpolygon,
                        endpolygon, gflush, t2f, tevbind, tevdef, texbind, texdef2d, v2f)
    tex = np.full(16, 0xffffffff, np.uint32)
    texdef2d(1, 4, 4, 4, tex, 0, [TX_NULL])
    tevdef(1, 0, [TV_MODULATE, TV_NULL])
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    bgnpolygon()
    for s, t in ((0, 0), (1, 0), (1, 1), (0, 1)):
        t2f((s, t))
        v2f((4 + 30 * s, 4 + 30 * t))
    endpolygon()
    gflush()
    texbind(TX_TEXTURE_0, 0)


def _step_cmode():
    from irisgl import cmode, color, gconfig
    cmode()
    gconfig()
    color(3)
    _quad()


STATE_STEPS = [("window", _window), ("z quad", lambda: (__import__("irisgl").zbuffer(1),
                                                         _quad())),
               ("lines", _step_lines), ("points", _step_points),
               ("lrectwrite", _step_lrectwrite), ("rectcopy", _step_rectcopy),
               ("stencil", _step_stencil), ("blend SA/MSA", _step_blend),
               ("blend DA/MDA", _step_blend_generic), ("logicop", _step_logicop),
               ("afunction", _step_afunction), ("pattern", _step_pattern),
               ("writemask", _step_writemask), ("texture", _step_texture),
               ("colour map", _step_cmode)]
STEPS = {"spheres": [("four spheres", _spheres)],
         "states": [("four spheres", _spheres)] + STATE_STEPS}


# ----------------------------------------------------------------------------
# parent

def run(workload, cache):
    # VGX_PIPELINE=0, VGX_PRECOMPILE=0: every kernel compiled on the calling
    # thread of this one process, so that each compile is timed apart (the
    # raster thread would compile its own kernels while this one compiles
    # others, and their timings would nest; vgx_emulator/precompile.py's
    # second process would compile the walker meanwhile)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT), VGX_PIPELINE="0",
               VGX_PRECOMPILE="0")
    t = time.perf_counter()
    r = subprocess.run([sys.executable, "-c", CHILD % dict(root=str(ROOT), workload=workload)],
                       capture_output=True, text=True, env=env, cwd=ROOT)
    wall = time.perf_counter() - t
    if r.returncode:
        sys.exit(r.stderr)
    out = json.loads(r.stdout.strip().splitlines()[-1])
    out["wall"] = wall
    return out


def table(title, res):
    print(f"\n### {title}\n")
    print(f"process {res['wall']:.2f} s (import irisgl {res['import_s']:.2f} s)\n")
    print("| step | kernel | module | s | of which helpers | from disk |")
    print("|---|---|---|---|---|---|")
    tot = {True: 0.0, False: 0.0}
    for r in res["records"]:
        tot[r["hit"]] += r["seconds"]
        print(f"| {r['step']} | {r['name']} | {r['module']} | {r['seconds']:.3f} | "
              f"{r['helpers']:.3f} | {'yes' if r['hit'] else 'no'} |")
    n_miss = sum(not r["hit"] for r in res["records"])
    print(f"\ncompiled: {n_miss} kernels, {tot[False]:.2f} s; loaded from disk: "
          f"{len(res['records']) - n_miss}, {tot[True]:.2f} s\n")
    print("| step | wall s |")
    print("|---|---|")
    for name, s in res["steps"].items():
        print(f"| {name} | {s:.3f} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--workload", choices=("spheres", "states", "both"), default="both")
    a = ap.parse_args(argv)
    for w in (("spheres", "states") if a.workload == "both" else (a.workload,)):
        with tempfile.TemporaryDirectory() as tmp:
            table(f"{w}: empty numba cache", run(w, tmp))
            table(f"{w}: filled cache (next process)", run(w, tmp))


if __name__ == "__main__":
    main()
