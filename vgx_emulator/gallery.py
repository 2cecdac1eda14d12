"""vgx-gallery: render every figure of every seed program into a folder with
an index.html (the project's main job).

Two sections: the seed programs' figures (``programs/``), then the demo
programs of our own (``programs/demos/``).  Contract with the programs: a
program module in either folder that defines
``FIGURES`` (a list of dicts with ``name``, ``caption``, ``args``) takes part;
each figure is drawn by running the program headless as ``vgx-run`` would,
with ``args`` as its command line, for one frame (``frames`` in the dict to
change that).  The order of programs is ``PROGRAMS`` below, then any other
program with FIGURES, alphabetically.
"""
import argparse
import ast
import html
import sys
import time
from pathlib import Path

from .display.anim import AccumulationFrames, write_gif
from .display.png import write_png
from .runner import run_program

#: figures that also get an animation (a GIF next to the PNG), by
#: (program, figure name); a figure dict may carry the same as "animate".
#: {"frames": N, "every": K}: every K-th of N frames, at the pace of
#: vgx-run's --fps default; {"at": "acbuf"}: the accumulation buffer after
#: each AC_ACCUMULATE of the figure's frame (display/anim.py).
ANIMATIONS = {("tessman_flat_shadows", "moving"): {"frames": 18, "every": 1},
              ("heidmann_shadow_volumes", "6"): {"at": "acbuf"}}

PROGRAMS = ["williams_shadow_zbuffer", "tessman_flat_shadows", "bentley_ground_shadows",
            "bentley_shadow_zbuffer", "hart_shadow_buffer", "heidmann_shadow_volumes",
            "four_spheres", "teapot"]


def _figures_of(path):
    """The FIGURES literal of a program, read without importing it."""
    tree = ast.parse(path.read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "FIGURES" for t in node.targets):
            return ast.literal_eval(node.value)
    return None


#: the gallery's sections: (title, sub-folder of the programs folder)
SECTIONS = (("The seed figures", "."), ("Demo programs", "demos"))


def collect(folder):
    """[(program path, figure dict, section title)] in gallery order."""
    out = []
    for title, sub in SECTIONS:
        d = Path(folder) / sub
        progs = {p.stem: p for p in sorted(d.glob("*.py")) if not p.stem.startswith("_")}
        order = [n for n in PROGRAMS if n in progs] + sorted(n for n in progs
                                                             if n not in PROGRAMS)
        for name in order:
            figs = _figures_of(progs[name])
            if figs:
                out.extend((progs[name], f, title) for f in figs)
    return out


def _bar(i, n, label, t0):
    width = 30
    done = int(width * i / n) if n else width
    sys.stderr.write(f"\r[{'#' * done}{'.' * (width - done)}] {i}/{n} "
                     f"{time.perf_counter() - t0:6.1f}s {label[:40]:<40}")
    sys.stderr.flush()


def render(outdir, folder, only=None):
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    items = collect(folder)
    if only:
        items = [(p, f, s) for p, f, s in items
                 if any(o in f"{p.stem}/{f['name']}" for o in only)]
    rows = []
    t0 = time.perf_counter()
    for i, (prog, fig, section) in enumerate(items):
        _bar(i, len(items), f"{prog.stem}: {fig['name']}", t0)
        t = time.perf_counter()
        err = None
        anim = fig.get("animate") or ANIMATIONS.get((prog.stem, fig["name"]))
        try:
            img, frames = _run(prog, fig, anim)
            if frames:
                gif = ("demos__" if prog.parent.name == "demos" else "") + \
                    f"{prog.stem}__{fig['name']}.gif"
                write_gif(outdir / gif, frames, 30.0 if anim.get("at") != "acbuf" else 8.0,
                          anim.get("every", 1))
                fig = dict(fig, _gif=gif)
        except Exception as e:          # a broken figure must not stop the gallery
            img, err = None, f"{type(e).__name__}: {e}"
        dt = time.perf_counter() - t
        fname = ("demos__" if prog.parent.name == "demos" else "") + \
            f"{prog.stem}__{fig['name']}.png"
        if img is not None:
            write_png(outdir / fname, img)
        elif err is None:
            err = "the program opened no window"
        rows.append((prog, fig, fname if img is not None else None, dt, err, section))
    _bar(len(items), len(items), "done", t0)
    sys.stderr.write("\n")
    _index(outdir, rows, time.perf_counter() - t0)
    return rows


def _run(prog, fig, anim):
    """The figure's image, and the frames of its animation (or None)."""
    args, n = fig.get("args", []), fig.get("frames", 1)
    if not anim:
        return run_program(prog, frames=n, argv=args), None
    if anim.get("at") == "acbuf":
        acc = AccumulationFrames()
        img = run_program(prog, frames=n, argv=args, trace=acc)
        return img, acc.frames
    frames = []
    run_program(prog, frames=anim["frames"], argv=args, collect=frames,
                every=anim.get("every", 1))
    return run_program(prog, frames=n, argv=args), frames


def _index(outdir, rows, total):
    parts = ["<!doctype html><html><head><meta charset='utf-8'><title>IRIS VGX gallery</title>",
             "<style>body{font-family:sans-serif;background:#222;color:#ddd}"
             "figure{display:inline-block;margin:12px;vertical-align:top;max-width:660px}"
             "img{max-width:640px;border:1px solid #555}figcaption{font-size:14px}"
             ".err{color:#f88}</style></head><body>",
             "<h1>IRIS VGX gallery</h1>",
             f"<p>{len(rows)} figures in {total:.1f} s.</p>"]
    section = None
    for prog, fig, fname, dt, err, sec in rows:
        if sec != section:
            section = sec
            parts.append(f"<h2>{html.escape(sec)}</h2>")
        rel = ("demos/" if prog.parent.name == "demos" else "") + prog.name
        parts.append("<figure>")
        if fname:
            parts.append(f"<img src='{html.escape(fname)}' alt='{html.escape(fig['name'])}'>")
        if fig.get("_gif"):
            parts.append(f"<img src='{html.escape(fig['_gif'])}' "
                         f"alt='{html.escape(fig['name'])} (animation)'>")
        parts.append(f"<figcaption><b>{html.escape(fig['caption'])}</b><br>"
                     f"program <code>programs/{html.escape(rel)}</code> "
                     f"{html.escape(' '.join(fig.get('args', [])))}; {dt:.2f} s")
        if err:
            parts.append(f"<br><span class='err'>failed: {html.escape(err)}</span>")
        parts.append("</figcaption></figure>")
    parts.append("</body></html>")
    (outdir / "index.html").write_text("\n".join(parts))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="vgx-gallery", description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="gallery", help="output folder (default: gallery)")
    ap.add_argument("--programs", default=None,
                    help="folder of programs (default: the programs/ of this checkout)")
    ap.add_argument("--only", nargs="*", help="render only figures whose program/name "
                                              "contains one of these strings")
    a = ap.parse_args(argv)
    folder = Path(a.programs) if a.programs else Path(__file__).resolve().parent.parent / "programs"
    rows = render(a.out, folder, a.only)
    failed = [r for r in rows if r[4]]
    print(f"vgx-gallery: {len(rows) - len(failed)} of {len(rows)} figures -> "
          f"{Path(a.out) / 'index.html'}")
    for prog, fig, _, _, err, _ in failed:
        print(f"  failed: {prog.stem}/{fig['name']}: {err}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
