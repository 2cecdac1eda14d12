"""Raster-subsystem benchmark of the emulated VGX; prints a markdown table.

Fragments per second at 1280x1024 (one window covering the whole virtual
screen), each pass being 32 full-screen quads (2 triangles each, edges on
pixel boundaries: 32 x 1280 x 1024 = 41.9 M fragments per pass):

(a) Heidmann's stencil-only pass: wmpack(0), zwritemask(0), zbuffer(TRUE),
    stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_INCR) (every
    quad passes the z test, so every fragment increments the stencil);
(b) a blended pass, blendfunction(BF_ONE, BF_ONE), z-buffer off;
(c) z-tested coloured quads with nothing else (zbuffer(TRUE), ZF_LEQUAL,
    each quad nearer than the last, so every fragment passes and writes).

Then the cost of enabling each feature alone, against the same 32 quads with
every feature off (z-buffer off, solid pattern, AF_ALWAYS, no blend, LO_SRC,
no stencil, full writemask).  Each feature is set so that every fragment
still passes and is written (the cost measured is the stage itself, not
fewer writes):
  pattern   an all-ones 16x16 pattern (defpattern + setpattern)
  afunction afunction(0, AF_GEQUAL)
  blend     blendfunction(BF_SA, BF_MSA)
  logicop   logicop(LO_XOR)
  stencil   stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_INCR, ST_KEEP)
            (z-buffer off: `pass` applies, docs/semantics.md §6)
  writemask wmpack(0xff00ff00)
  z         zbuffer(TRUE), ZF_LEQUAL, nearer quads

Shading is left at its default (GOURAUD; one colour per quad).

Timing: the quads are issued (untimed), then vgx_emulator.machine().flush()
and the wait for the raster thread's queued passes (pipeline.sync) are
timed: geometry, scan conversion and every fragment.  One untimed
warm-up pass per configuration (numba compile or cache load), then the
median of several repeats.

Usage: python benchmarks/raster.py [--quick]
"""
import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from irisgl import (AF_GEQUAL, BF_MSA, BF_ONE, BF_SA, GD_ZMAX, LO_XOR,  # noqa: E402
                    SF_ALWAYS, ST_INCR, ST_KEEP, TRUE, ZF_LEQUAL, RGBmode, afunction,
                    bgnpolygon, blendfunction, cpack, czclear, defpattern, endpolygon,
                    gconfig, getgdesc, logicop, ortho, prefposition, sclear, setpattern,
                    stencil, stensize, subpixel, v3f, winopen, wmpack, zbuffer, zfunction,
                    zwritemask)

import vgx_emulator  # noqa: E402
from vgx_emulator import pipeline  # noqa: E402

W, H = 1280, 1024
NQUADS = 32
FRAGMENTS = NQUADS * W * H


def _reset():
    from irisgl._current import machine
    machine.reset()


def _window():
    _reset()
    prefposition(0, W - 1, 0, H - 1)
    winopen("raster benchmark")
    RGBmode()
    stensize(8)
    gconfig()
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    subpixel(TRUE)                  # corners on pixel boundaries: exactly W*H each


def _quads():
    """32 full-screen quads, each nearer than the last (window z decreasing)."""
    for k in range(NQUADS):
        z = -0.9 + 1.8 * k / (NQUADS - 1)        # ortho: zn = -z, so nearer each time
        cpack(0x80000000 | ((k * 2654435761) & 0x00FFFFFF))
        for tri in (((-.5, -.5), (W - .5, -.5), (W - .5, H - .5)),
                    ((-.5, -.5), (W - .5, H - .5), (-.5, H - .5))):
            bgnpolygon()
            for x, y in tri:
                v3f((x, y, z))
            endpolygon()


# -- configurations: a function that sets the state after _window() -------------
def cfg_plain():
    pass


def cfg_stencil_only():
    wmpack(0)
    zwritemask(0)
    zbuffer(TRUE)
    zfunction(ZF_LEQUAL)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)


def cfg_additive():
    blendfunction(BF_ONE, BF_ONE)


def cfg_z():
    zbuffer(TRUE)
    zfunction(ZF_LEQUAL)


def cfg_pattern():
    defpattern(1, 16, [0xFFFF] * 16)
    setpattern(1)


def cfg_afunction():
    afunction(0, AF_GEQUAL)


def cfg_blend():
    blendfunction(BF_SA, BF_MSA)


def cfg_logicop():
    logicop(LO_XOR)


def cfg_stencil():
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)


def cfg_writemask():
    wmpack(0xFF00FF00)


def flush_seconds(cfg, repeats):
    """Median seconds of machine().flush() and pipeline.sync() for the 32
    quads under cfg."""
    _window()
    cfg()
    m = vgx_emulator.machine()
    zmax = getgdesc(GD_ZMAX)
    times = []
    for k in range(repeats + 1):                 # the first pass warms up
        # clears ignore writemasks, pattern, stencil, blend (czclear(3G))
        czclear(0xFF000000, zmax)
        sclear(0)
        m.flush()
        pipeline.sync()                          # the clears done before the clock starts
        _quads()
        t0 = time.perf_counter()
        m.flush()
        pipeline.sync()                          # and the raster thread's passes in the time
        dt = time.perf_counter() - t0
        if k:
            times.append(dt)
    _reset()
    return statistics.median(times)


def machine_description():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    import numba
    import numpy
    return (f"nproc {os.cpu_count()}, numba threads {numba.get_num_threads()}, CPU {cpu}; "
            f"Python {platform.python_version()}, numpy {numpy.__version__}, "
            f"numba {numba.__version__}; VGX_PARALLEL={os.environ.get('VGX_PARALLEL', '1')}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer repetitions (2 instead of 5)")
    a = ap.parse_args(argv)
    reps = 2 if a.quick else 5

    def rate(s):
        return f"{FRAGMENTS / s / 1e6:.1f} M/s"

    print(f"Machine: {machine_description()}")
    print(f"Mode: {'--quick' if a.quick else 'full'}; {NQUADS} full-screen quads at {W}x{H} "
          f"= {FRAGMENTS / 1e6:.1f} M fragments per pass; median of {reps} warm flushes")
    print()
    print("| pass | flush time | fragments/s | ns/fragment |")
    print("|---|---|---|---|")
    for label, cfg in (("(a) stencil-only (wmpack(0), zwritemask(0), z on, ST_INCR)",
                        cfg_stencil_only),
                       ("(b) blended (BF_ONE, BF_ONE)", cfg_additive),
                       ("(c) z-tested coloured quads", cfg_z)):
        s = flush_seconds(cfg, reps)
        print(f"| {label} | {1000 * s:.0f} ms | {rate(s)} | {1e9 * s / FRAGMENTS:.1f} |")
    print()
    base = flush_seconds(cfg_plain, reps)
    print("| feature alone | flush time | fragments/s | ns/fragment | cost vs all off |")
    print("|---|---|---|---|---|")
    print(f"| all off (baseline) | {1000 * base:.0f} ms | {rate(base)} | "
          f"{1e9 * base / FRAGMENTS:.1f} | - |")
    for name, cfg in (("pattern (all-ones 16x16)", cfg_pattern),
                      ("afunction(0, AF_GEQUAL)", cfg_afunction),
                      ("blend (BF_SA, BF_MSA)", cfg_blend),
                      ("logicop(LO_XOR)", cfg_logicop),
                      ("stencil (SF_ALWAYS, pass ST_INCR)", cfg_stencil),
                      ("writemask wmpack(0xff00ff00)", cfg_writemask),
                      ("z (zbuffer, ZF_LEQUAL)", cfg_z)):
        s = flush_seconds(cfg, reps)
        extra = 1e9 * (s - base) / FRAGMENTS
        print(f"| {name} | {1000 * s:.0f} ms | {rate(s)} | {1e9 * s / FRAGMENTS:.1f} | "
              f"x{s / base:.2f} ({extra:+.1f} ns/fragment) |")


if __name__ == "__main__":
    main()
