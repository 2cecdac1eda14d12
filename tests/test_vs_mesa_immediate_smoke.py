"""Smoke test of benchmarks/immediate.py: a tiny run prints every per-vertex
call beside the no-op floor and the three workloads' rates, and, where
OSMesa and PyOpenGL are installed, pictures that agree with Mesa's (the
benchmark's own check that both sides drew the same, lit, scene)."""
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CALLS = ("v2f", "v3f", "v4f", "n3f", "c3f", "c4f", "cpack", "RGBcolor", "t2f",
         "bgnpolygon/endpolygon")
WORKLOADS = ("immediate polygons", "immediate tmesh", "display-list tmesh")


def test_immediate_benchmark_runs_and_both_sides_agree():
    env = dict(os.environ, VGX_GENERAL="0")     # each state its own variant: no waiting
    run = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "immediate.py"),
                          "--size", "96x64", "--repeat", "1", "--tmesh-triangles", "400",
                          "--polygons", "100"],
                         capture_output=True, text=True, cwd=ROOT, env=env, timeout=600)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    for call in CALLS:
        row = [ln for ln in lines if ln.split()[:1] == [call]]
        assert len(row) == 1, call
        ns, floor, ratio = row[0].split()[1:4]
        assert float(ns) > 0 and float(floor) > 0 and ratio.endswith("x")
    mesa = "Mesa side skipped" not in run.stdout
    for name in WORKLOADS:
        row = [ln for ln in lines if ln.startswith(name)]
        assert len(row) == 1, name
        cols = row[0][len(name):].split()
        assert float(cols[1]) > 0                    # emulator M tri/s
        if mesa:
            assert float(cols[-1]) <= 0.05, row[0]   # pixels differing from Mesa's
