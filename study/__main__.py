"""Run the shadow study; write docs/shadow-study.md and docs/shadow-study/.

``python -m study`` or ``vgx-study``: results.json, the pictures and the
plots go to docs/shadow-study/, the report to docs/shadow-study.md."""
import argparse
import sys
import tempfile
from pathlib import Path

from .report import main_run


def parse(argv=None):
    ap = argparse.ArgumentParser(prog="vgx-study", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="a reduced sweep at 160x120 (unless --size is given), written to a "
                         "temporary directory unless --out-dir / --md are given")
    ap.add_argument("--size", default=None, help="image WxH (default 320x240)")
    ap.add_argument("--scenes", nargs="+", default=["A", "B"], choices=["A", "B"])
    ap.add_argument("--methods", nargs="+", default=None,
                    choices=["planar", "shadow map", "volumes", "soft"],
                    help="only these method families")
    ap.add_argument("--repeats", type=int, default=5, help="timed runs per configuration")
    ap.add_argument("--budget", type=float, default=20.0,
                    help="stop repeating a configuration after this many seconds")
    ap.add_argument("--threads", type=int, default=1,
                    help="numba threads of the emulator's kernels (default 1: on a shared "
                         "machine 2 threads made times vary with the other users' load)")
    ap.add_argument("--out-dir", default=None, help="results and pictures (docs/shadow-study)")
    ap.add_argument("--md", default=None, help="the report (docs/shadow-study.md)")
    a = ap.parse_args(argv)
    size = a.size or ("160x120" if a.quick else "320x240")
    a.size = tuple(int(s) for s in size.lower().split("x"))
    if a.quick and a.out_dir is None:
        a.out_dir = Path(tempfile.gettempdir()) / "vgx-study-quick"
        a.md = a.md or a.out_dir / "shadow-study.md"
    return a


def main(argv=None):
    a = parse(argv)
    res = main_run(a)
    print(f"report: {res['markdown']}", file=sys.stderr)


if __name__ == "__main__":
    main()
