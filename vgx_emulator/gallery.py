"""vgx-gallery: render every figure of every seed program into a folder with
an index.html (the project's main job).

One section per paper (``PAPERS``: its full reference, what it contributed,
the programs that reproduce it), then the demo programs of our own
(``programs/demos/``).  Contract with the programs: a program module in
either folder that defines ``FIGURES`` (a list of dicts with ``name``,
``caption``, ``args``) takes part; each figure is drawn by running the
program headless as ``vgx-run`` would, with ``args`` as its command line,
for one frame (``frames`` in the dict to change that).  The order of
programs is that of ``PAPERS``, then any other program with FIGURES,
alphabetically.  Every figure also gets a page of its own with the command
that reproduces it.  A figure that fails or cannot be written is reported
on its place in the page and the gallery goes on.
"""
import argparse
import ast
import html
import sys
import time
from collections import namedtuple
from pathlib import Path

from .display.anim import AccumulationFrames, write_gif
from .display.png import write_png
from .progress import Progress
from .runner import run_program

#: figures that also get an animation (a GIF next to the PNG), by
#: (program, figure name); a figure dict may carry the same as "animate".
#: {"frames": N, "every": K}: every K-th of N frames, at the pace of
#: vgx-run's --fps default; {"at": "acbuf"}: the accumulation buffer after
#: each AC_ACCUMULATE of the figure's frame (display/anim.py).
ANIMATIONS = {("tessman_flat_shadows", "moving"): {"frames": 18, "every": 1},
              ("heidmann_shadow_volumes", "6"): {"at": "acbuf"}}

#: the papers the seed programs reproduce, in gallery order: a section each
PAPERS = [
    {"key": "williams", "title": "Williams 1978: the shadow z-buffer",
     "reference": "Lance Williams, \"Casting curved shadows on curved surfaces\", "
                  "Computer Graphics (Proceedings of SIGGRAPH '78) 12(3), 270-274, "
                  "August 1978.",
     "contribution": "The shadow z-buffer: draw the scene from the light keeping only depth, "
                     "then carry every visible point of the observer's view into the light's "
                     "view and call it shadowed when it lies behind the stored depth.  Curved "
                     "shadows on curved surfaces for the cost of a second visible-surface "
                     "pass; the paper also names the method's discrete troubles (depth "
                     "quantization moire, the bias against self-shadowing) and its remedies "
                     "(bilinear interpolation of depths, dither, low-pass filtering).",
     "programs": ["williams_shadow_zbuffer", "four_spheres"]},
    {"key": "tessman", "title": "Tessman 1989: shadows on flat surfaces",
     "reference": "Thant Tessman, \"Casting shadows on flat surfaces\", IRIS Universe "
                  "(Silicon Graphics), winter 1989.",
     "contribution": "The IRIS Geometry Pipeline flattens an object onto the ground: "
                     "scale(1.0, 0.0, 1.0) for a light straight above, a hand-built matrix for "
                     "a light at infinity and one whose fourth column does the perspective "
                     "divide for a local light; the flattened object drawn black through a "
                     "halftone pattern is its shadow.",
     "programs": ["tessman_flat_shadows"]},
    {"key": "bentley", "title": "Bentley 1995: two shadow rendering algorithms",
     "reference": "Chris Bentley, \"Two shadow rendering algorithms\", course presentation, "
                  "Worcester Polytechnic Institute (CS 563), 1995.",
     "contribution": "A side-by-side account of the ground transformation (every polygon "
                     "projected onto the ground away from each light, at infinity or local) "
                     "and the shadow z-buffer with one depth map per light and "
                     "percentage-closer filtering; several lights, texture-mapped objects and "
                     "surfaces that shadow themselves.",
     "programs": ["bentley_ground_shadows", "bentley_shadow_zbuffer"]},
    {"key": "hart", "title": "Hart: the shadow buffer in lecture slides",
     "reference": "John C. Hart, \"Shadows\", lecture slides of CS 418 Computer Graphics, "
                  "University of Illinois at Urbana-Champaign.",
     "contribution": "Williams' shadow buffer as three renders (lit and ambient-only from the "
                     "eye, depth only from the light), the eye pixel carried into the light's "
                     "window through the inverse matrices, the perspective depth mapping with "
                     "its alpha and beta, and percentage-closer filtering over 3 x 3 light "
                     "samples.",
     "programs": ["hart_shadow_buffer"]},
    {"key": "heidmann", "title": "Heidmann 1991: stencil shadow volumes on the VGX",
     "reference": "Tim Heidmann, \"Real shadows, real time\", IRIS Universe (Silicon "
                  "Graphics) 18, 28-31, 1991.",
     "contribution": "Crow's shadow volumes counted in the VGX stencil planes: an ambient "
                     "pass, then per light the volume faces drawn with ST_INCR and ST_DECR "
                     "around a stencil value MYZERO, the light's pass where the count is "
                     "MYZERO, added with blendfunction(BF_ONE, BF_ONE); several coloured "
                     "lights in real time, and soft shadows from 32 jittered lights summed in "
                     "the accumulation buffer.",
     "programs": ["heidmann_shadow_volumes"]},
    {"key": "newell", "title": "Newell 1975: the Utah teapot",
     "reference": "Martin Newell's teapot (University of Utah, 1975): 32 bicubic Bezier "
                  "patches; its story in Frank Crow, \"The origins of the teapot\", IEEE "
                  "Computer Graphics and Applications 7(1), 8-19, January 1987.",
     "contribution": "The test shape of curved-surface rendering, here drawn both as IRIS GL "
                     "drew patches (patch(), a web of curves) and as a lit, shaded surface.",
     "programs": ["teapot"]},
]

#: the section of the demo programs (programs/demos/), after the papers
DEMOS = {"key": "demos", "title": "Demo programs of our own",
         "reference": "",
         "contribution": "Short programs in the style of 1990 IRIS GL (event loop, gconfig, "
                         "swapbuffers) that together use every group of calls: text and "
                         "menus, 2-D drawing, colour maps, depth cueing, picking, lighting "
                         "with valuators, GL2-style ginit, fog and clip planes, NURBS.",
         "programs": []}

#: any other program with FIGURES
OTHERS = {"key": "others", "title": "Other programs", "reference": "", "contribution": "",
          "programs": []}

PROGRAMS = [n for paper in PAPERS for n in paper["programs"]]

#: one rendered figure: program path, figure dict, PNG file name (None if it
#: failed), render seconds without kernel compilation, error (None), section
#: key, seconds spent compiling (or loading) kernels during it
Row = namedtuple("Row", "prog fig png seconds error section compile")


def _figures_of(path):
    """The FIGURES literal of a program, read without importing it."""
    tree = ast.parse(path.read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "FIGURES" for t in node.targets):
            return ast.literal_eval(node.value)
    return None


def section_of(key):
    """The section dict (PAPERS, DEMOS or OTHERS) of a section key."""
    return next((p for p in PAPERS + [DEMOS, OTHERS] if p["key"] == key), OTHERS)


def collect(folder):
    """[(program path, figure dict, section key)] in gallery order."""
    out = []
    top = Path(folder)
    progs = {p.stem: p for p in sorted(top.glob("*.py")) if not p.stem.startswith("_")}
    for paper in PAPERS:
        for name in paper["programs"]:
            if name in progs:
                out.extend((progs[name], f, paper["key"]) for f in _figures_of(progs[name]) or [])
    demos = sorted((top / "demos").glob("*.py"))
    out.extend((p, f, "demos") for p in demos if not p.stem.startswith("_")
               for f in _figures_of(p) or [])
    out.extend((progs[n], f, "others") for n in sorted(progs) if n not in PROGRAMS
               for f in _figures_of(progs[n]) or [])
    return out


def _stem(prog, fig):
    """The file name stem of a figure's PNG, GIF and page."""
    return ("demos__" if prog.parent.name == "demos" else "") + f"{prog.stem}__{fig['name']}"


def _timed_run(prog, fig, anim):
    """_run, and the seconds numba spent compiling kernels (or loading them
    from its disk cache) during it, the time it held its compiler lock: the
    one-off cost of a process that the page shows apart."""
    from numba.core import event
    spent = []
    with event.install_timer("numba:compiler_lock", spent.append):
        img, frames = _run(prog, fig, anim)
    return img, frames, sum(spent)


def render(outdir, folder, only=None, workers=None):
    """Render the figures (``only``: those whose program/name contains one
    of these strings) into ``outdir`` with index.html and a page per figure;
    return the [Row].  ``workers``: render in that many worker processes
    (each its own machine), the rows still in gallery order."""
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    items = collect(folder)
    if only:
        items = [(p, f, s) for p, f, s in items
                 if any(o in f"{p.stem}/{f['name']}" for o in only)]
    t0 = time.perf_counter()
    bar = Progress(len(items))
    if workers and workers > 1 and len(items) > 1:
        rows = _render_parallel(outdir, items, workers, bar)
    else:
        rows = []
        for prog, fig, section in items:
            bar.show(f"{prog.stem}: {fig['name']}")
            rows.append(render_one(outdir, prog, fig, section))
            bar.step(f"{prog.stem}: {fig['name']}")
    bar.close()
    write_pages(outdir, rows, time.perf_counter() - t0)
    return rows


def _render_parallel(outdir, items, workers, bar):
    """render_one of every item in a pool of worker processes; a process
    that dies fails its figure, the others go on."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed
    rows = [None] * len(items)
    ctx = multiprocessing.get_context("spawn")        # a fresh machine in each worker
    with ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
        jobs = {pool.submit(render_one, outdir, *item): k for k, item in enumerate(items)}
        for job in as_completed(jobs):
            k = jobs[job]
            prog, fig, section = items[k]
            try:
                rows[k] = job.result()
            except Exception as e:
                rows[k] = Row(prog, fig, None, 0.0, f"worker process failed: "
                              f"{type(e).__name__}: {e}", section, 0.0)
            bar.step(f"{prog.stem}: {fig['name']}")
    return rows


def render_one(outdir, prog, fig, section):
    """Render one figure and write its PNG (and GIF); a figure that fails or
    cannot be written gets its error in the Row."""
    t = time.perf_counter()
    err, compiled = None, 0.0
    anim = fig.get("animate") or ANIMATIONS.get((prog.stem, fig["name"]))
    stem = _stem(prog, fig)
    try:
        img, frames, compiled = _timed_run(prog, fig, anim)
    except Exception as e:          # a broken figure must not stop the gallery
        img, frames, err = None, None, f"{type(e).__name__}: {e}"
    dt = time.perf_counter() - t - compiled
    fname = stem + ".png"
    if img is not None:
        try:
            write_png(outdir / fname, img)
            fig = dict(fig, _size=(img.shape[1], img.shape[0]))
        except Exception as e:      # a figure it cannot write is reported, not fatal
            img, err = None, f"cannot write {outdir / fname}: {type(e).__name__}: {e}"
    elif err is None:
        err = "the program opened no window"
    if frames and img is not None:
        try:
            write_gif(outdir / (stem + ".gif"), frames,
                      30.0 if anim.get("at") != "acbuf" else 8.0, anim.get("every", 1))
            fig = dict(fig, _gif=stem + ".gif")
        except Exception as e:
            err = f"cannot write {outdir / (stem + '.gif')}: {type(e).__name__}: {e}"
    return Row(prog, fig, fname if img is not None else None, dt, err, section, compiled)


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


STYLE = """
body{font-family:system-ui,sans-serif;background:#1c1d1f;color:#ddd;margin:0 28px 60px;
 line-height:1.45}
a{color:#8cc8ff}
h1{margin:24px 0 4px}
nav.toc{columns:2 26em;background:#26282b;padding:8px 20px;border-radius:6px}
nav.toc ul{margin:4px 0 10px;padding-left:18px}
nav.toc>ul>li{break-inside:avoid}
section.paper{margin-top:44px;padding-top:8px;border-top:1px solid #444}
p.ref{font-style:italic;color:#bbb;margin:2px 0}
p.what{max-width:58em}
.figs{display:grid;grid-template-columns:repeat(auto-fill,minmax(min(100%,1000px),1fr));
 gap:36px 40px;margin-top:18px}
figure{margin:0;display:grid;grid-template-columns:max-content minmax(14em,24em);
 gap:8px 18px;align-items:start;overflow-x:auto}
figure.wide{grid-column:1/-1}
figure .pics{display:grid;gap:8px}
figure img{display:block;border:1px solid #555}
figcaption{font-size:15px}
figcaption .meta{color:#999;font-size:13px}
code,pre{background:#2b2d31;border-radius:4px;padding:1px 4px}
pre{padding:10px;overflow-x:auto}
.err{color:#f88}
"""


def _e(text):
    return html.escape(str(text), quote=True)


def command(prog, fig, gif=False):
    """The vgx-run command that reproduces a figure (``gif``: its animation)."""
    rel = ("demos/" if prog.parent.name == "demos" else "") + prog.name
    args = list(fig.get("args", []))
    opts = []
    if len(args) >= 2 and args[0] == "--menu":
        opts += ["--menu", args[1]]
        args = args[2:]
    anim = fig.get("animate") or ANIMATIONS.get((prog.stem, fig["name"])) or {}
    if gif and anim.get("frames"):
        opts = ["--frames", str(anim["frames"])] + (
            ["--every", str(anim["every"])] if anim.get("every", 1) != 1 else []) + opts
        out = _stem(prog, fig) + ".gif"
    else:
        n = fig.get("frames", 1)
        opts = (["--frames", str(n)] if n != 1 else []) + opts
        out = _stem(prog, fig) + ".png"
    cmd = ["vgx-run", f"programs/{rel}", "--out", out] + opts
    return " ".join(cmd + (["--"] + args if args else []))


def _label(fig):
    """A figure's short name: its caption up to the first colon when that
    names a figure ("Williams fig. 1"), else the caption's first words."""
    cap = fig["caption"]
    head = cap.split(":")[0]
    if head != cap and len(head) < 40 and "fig" in head:
        return head
    if len(cap) <= 64:
        return cap.rstrip(".")
    return cap[:64].rsplit(" ", 1)[0].rstrip(",;:") + " ..."


def _seconds(row):
    return (f"rendered in {row.seconds:.2f} s"
            + (f" (+ {row.compile:.2f} s compiling or loading kernels, once a process)"
               if row.compile >= 0.005 else ""))


def _pictures(row, href=None):
    """The <img> elements of a figure at their own size (PNG, then GIF)."""
    out = []
    size = row.fig.get("_size")
    wh = f" width='{size[0]}' height='{size[1]}'" if size else ""
    for src, alt in ((row.png, row.fig["name"]), (row.fig.get("_gif"),
                                                    f"{row.fig['name']} (animation)")):
        if src:
            img = f"<img src='{_e(src)}' alt='{_e(alt)}'{wh}>"
            out.append(f"<a href='{_e(href)}'>{img}</a>" if href else img)
    return "".join(out)


def _figure(row):
    """A figure of the index: its pictures, the caption beside them."""
    stem = _stem(row.prog, row.fig)
    size = row.fig.get("_size")
    wide = " class='wide'" if size and size[0] > 700 else ""
    rel = ("demos/" if row.prog.parent.name == "demos" else "") + row.prog.name
    parts = [f"<figure id='{_e(stem)}'{wide}><div class='pics'>",
             _pictures(row, stem + ".html"), "</div>",
             f"<figcaption><b>{_e(row.fig['caption'])}</b><br>"
             f"<span class='meta'>program <code>programs/{_e(rel)}</code>"
             f"{' ' + _e(' '.join(row.fig.get('args', []))) if row.fig.get('args') else ''}; "
             f"{_e(_seconds(row))}; <a href='{_e(stem)}.html'>how to reproduce it</a></span>"]
    if row.error:
        parts.append(f"<br><span class='err'>failed: {_e(row.error)}</span>")
    parts.append("</figcaption></figure>")
    return "".join(parts)


def _head(title):
    return (f"<!doctype html><html lang='en'><head><meta charset='utf-8'>"
            f"<meta name='viewport' content='width=device-width'><title>{_e(title)}</title>"
            f"<style>{STYLE}</style></head><body>")


def write_pages(outdir, rows, total):
    """index.html (a section per paper, a table of contents, the figures in
    a grid at their own size with their captions) and a page per figure."""
    outdir = Path(outdir)
    keys = list(dict.fromkeys(r.section for r in rows))
    compiled = sum(r.compile for r in rows)
    done = sum(1 for r in rows if not r.error)
    parts = [_head("IRIS VGX gallery"), "<h1>IRIS VGX gallery</h1>",
             f"<p>{done} of {len(rows)} figures, drawn by the emulated IRIS VGX from the "
             f"ported programs in {sum(r.seconds for r in rows):.1f} s of rendering; "
             f"compiling the kernels (or loading them from numba's disk cache) took "
             f"{compiled:.1f} s more, once for the process. "
             f"{total:.1f} s in all.</p>", "<nav class='toc'><b>Contents</b><ul>"]
    for key in keys:
        sec = section_of(key)
        parts.append(f"<li><a href='#{_e(key)}'>{_e(sec['title'])}</a><ul>")
        for r in rows:
            if r.section == key:
                parts.append(f"<li><a href='#{_e(_stem(r.prog, r.fig))}'>"
                             f"{_e(_label(r.fig))}"
                             f"</a>{' <span class=err>(failed)</span>' if r.error else ''}</li>")
        parts.append("</ul></li>")
    parts.append("</ul></nav>")
    for key in keys:
        sec = section_of(key)
        parts.append(f"<section class='paper' id='{_e(key)}'><h2>{_e(sec['title'])}</h2>")
        if sec["reference"]:
            parts.append(f"<p class='ref'>{_e(sec['reference'])}</p>")
        if sec["contribution"]:
            parts.append(f"<p class='what'>{_e(sec['contribution'])}</p>")
        parts.append("<div class='figs'>")
        parts.extend(_figure(r) for r in rows if r.section == key)
        parts.append("</div></section>")
    parts.append("</body></html>")
    (outdir / "index.html").write_text("\n".join(parts))
    for r in rows:
        _figure_page(outdir, r)


def _figure_page(outdir, row):
    """<stem>.html: one figure, its caption, paper and the command that
    reproduces it."""
    sec = section_of(row.section)
    stem = _stem(row.prog, row.fig)
    parts = [_head(row.fig["caption"][:80]),
             f"<p><a href='index.html#{_e(stem)}'>&larr; the gallery</a></p>",
             f"<h1>{_e(_label(row.fig))}</h1>",
             f"<div class='pics'>{_pictures(row)}</div>",
             f"<p>{_e(row.fig['caption'])}</p>",
             f"<p class='ref'>{_e(sec['title'])}{'. ' + _e(sec['reference']) if sec['reference'] else ''}</p>",
             "<h2>Reproduce it</h2>",
             "<p>From a checkout, after <code>pip install -e .</code>:</p>",
             f"<pre>{_e(command(row.prog, row.fig))}</pre>"]
    if row.fig.get("_gif"):
        anim = row.fig.get("animate") or ANIMATIONS.get((row.prog.stem, row.fig["name"])) or {}
        if anim.get("frames"):
            parts += ["<p>The animation:</p>", f"<pre>{_e(command(row.prog, row.fig, gif=True))}</pre>"]
        else:
            parts.append("<p>The animation shows the accumulation buffer after each "
                         "<code>acbuf(AC_ACCUMULATE, ...)</code> of the frame "
                         "(<code>vgx_emulator.display.anim.AccumulationFrames</code>).</p>")
    parts.append(f"<p class='meta'>{_e(_seconds(row))}.</p>")
    if row.error:
        parts.append(f"<p class='err'>failed: {_e(row.error)}</p>")
    parts.append("</body></html>")
    (outdir / f"{stem}.html").write_text("\n".join(parts))


def main(argv=None):
    ap = argparse.ArgumentParser(prog="vgx-gallery", description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="gallery", help="output folder (default: gallery)")
    ap.add_argument("--programs", default=None,
                    help="folder of programs (default: the programs/ of this checkout)")
    ap.add_argument("--only", nargs="*", help="render only figures whose program/name "
                                              "contains one of these strings")
    ap.add_argument("--workers", type=int, default=None, metavar="N",
                    help="render in N worker processes (default: one after another here)")
    a = ap.parse_args(argv)
    if a.workers is not None and a.workers < 1:
        ap.error("--workers: at least 1")
    folder = Path(a.programs) if a.programs else Path(__file__).resolve().parent.parent / "programs"
    rows = render(a.out, folder, a.only, a.workers)
    failed = [r for r in rows if r.error]
    print(f"vgx-gallery: {len(rows) - len(failed)} of {len(rows)} figures -> "
          f"{Path(a.out) / 'index.html'}")
    for r in failed:
        print(f"  failed: {r.prog.stem}/{r.fig['name']}: {r.error}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
