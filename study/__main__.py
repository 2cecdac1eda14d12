"""Run the shadow study into an output folder (docs/ only with --docs).

``python -m study`` or ``vgx-study``: a file per configuration as it
finishes, then results.json, the pictures, the plots and report.md, into
``--out`` (out/study; out/study-quick with --quick, out/study-full with
--full); ``--docs`` also writes docs/shadow-study.md and docs/shadow-study/.
``--workers N`` / ``--scheduler ADDRESS``: the tasks on Dask (the
``[cluster]`` extra); ``--resume``: skip what a previous run of the same
folder finished.  docs/shadow-study-at-scale.md tells the whole story."""
import argparse
import sys
from pathlib import Path

from .render import MAX_TILE
from .report import ROOT, main_run


def parse(argv=None):
    ap = argparse.ArgumentParser(prog="vgx-study", description=__doc__.splitlines()[0])
    kind = ap.add_mutually_exclusive_group()
    kind.add_argument("--quick", action="store_true",
                      help="a reduced sweep at 160x120 (unless --size is given)")
    kind.add_argument("--full", action="store_true",
                      help="the big sweep: light maps to 8192, grids of bias, filters and PCF, "
                           "5 seeds of each jittered configuration (unless --seeds)")
    ap.add_argument("--size", default=None, help="image WxH (default 320x240)")
    ap.add_argument("--scenes", nargs="+", default=["A", "B"], metavar="SCENE",
                    help="built-in scenes (A, B) and scene files (JSON, see "
                         "docs/shadow-study-at-scale.md)")
    ap.add_argument("--methods", nargs="+", default=None,
                    choices=["planar", "shadow map", "volumes", "soft"],
                    help="only these method families")
    ap.add_argument("--seeds", type=int, default=None, metavar="K",
                    help="run each jittered configuration (soft shadows, dithered maps) with "
                         "seeds 0..K-1 and report the spread (default: the fixed patterns)")
    ap.add_argument("--repeats", type=int, default=5, help="timed runs per configuration")
    ap.add_argument("--budget", type=float, default=20.0,
                    help="stop repeating a configuration after this many seconds")
    ap.add_argument("--threads", type=int, default=1,
                    help="numba threads of the emulator's kernels in the timing phase (default "
                         "1: on a shared machine 2 threads made times vary with the other "
                         "users' load)")
    ap.add_argument("--no-timing", action="store_true",
                    help="skip the timing phase (errors and pictures only)")
    ap.add_argument("--tile", type=int, default=MAX_TILE,
                    help=f"largest light window: maps beyond it are drawn in tiles "
                         f"(default {MAX_TILE}, the screen's height)")
    ap.add_argument("--workers", type=int, default=None, metavar="N",
                    help="run the tasks on a Dask LocalCluster of N worker processes")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the tasks on an existing Dask cluster (tcp://host:8786)")
    ap.add_argument("--resume", action="store_true",
                    help="keep what a previous run into --out finished; run only the rest")
    ap.add_argument("--out", "--out-dir", dest="out", default=None,
                    help="output folder (default out/study, out/study-quick, out/study-full)")
    ap.add_argument("--md", default=None, help="write the report here too")
    ap.add_argument("--docs", action="store_true",
                    help="also regenerate docs/shadow-study.md and docs/shadow-study/")
    a = ap.parse_args(argv)
    size = a.size or ("160x120" if a.quick else "320x240")
    try:
        a.size = tuple(int(s) for s in size.lower().split("x"))
        assert len(a.size) == 2 and min(a.size) > 0
    except (ValueError, AssertionError):
        ap.error(f"--size {size}: WxH expected, e.g. 320x240")
    if a.workers is not None and a.workers < 1:
        ap.error("--workers: at least 1")
    if a.workers and a.scheduler:
        ap.error("--workers and --scheduler: one or the other")
    if a.seeds is not None and a.seeds < 1:
        ap.error("--seeds: at least 1")
    if a.out is None:
        a.out = ROOT / "out" / ("study-quick" if a.quick else "study-full" if a.full
                                else "study")
    a.out = Path(a.out)
    return a


def main(argv=None):
    a = parse(argv)
    try:
        res = main_run(a)
    except ValueError as e:
        sys.exit(f"vgx-study: {e}")
    print(f"report: {res['markdown']}", file=sys.stderr)


if __name__ == "__main__":
    main()
