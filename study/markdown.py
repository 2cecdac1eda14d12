"""docs/shadow-study.md from the results of a run (every number in it is
computed from them)."""
import math

from .measure import pareto

MB = 1024.0 * 1024.0


def document(results, rel, plots):
    w, h = results["size"]
    kind = (" (this run: `--quick`, a reduced sweep)" if results.get("quick") else
            " (this run: `--full`)" if results.get("full") else "")
    res = sorted({r["params"]["res"] for sc in results["scenes"].values() for r in sc["rows"]
                  if r["family"] == "shadow map"}) or [0]
    out = [HEADER.format(cmd="python -m study", w=w, h=h, quick=kind, repeats=results["repeats"],
                         budget=results["budget_s"], lo=res[0], hi=res[-1],
                         tile=results.get("max_tile", 1024), rel=rel,
                         scenes=_count(len(results["scenes"]), "scene"))]
    out.append("| | |\n|---|---|")
    out += [f"| {k} | {v} |" for k, v in results["meta"].items()]
    out.append(timing_section(results))
    out.append(MEASURES)
    for name, sc in results["scenes"].items():
        out.append(scene_section(name, sc, rel, plots))
    out.append(LIMITS)
    return "\n".join(out) + "\n"


def _count(n, noun):
    words = {1: "one", 2: "two", 3: "three", 4: "four"}
    return f"{words.get(n, n)} {noun}" + ("" if n == 1 else "s")


def timing_section(results):
    """How the times were taken, on which machines, and how they are compared."""
    t = results.get("timing") or {}
    machines, compared = t.get("machines") or {}, t.get("compared on")
    lines = [TIMING.format(threads=results["meta"].get("numba threads (timing)", 1),
                           repeats=results["repeats"])]
    if not machines:
        lines.append("No configuration was timed in this run (`--no-timing`, or every "
                     "timing failed): the time columns are empty.")
        return "\n".join(lines)
    lines.append("| machine | cores | numba threads | timing slots | rows timed "
                 "| load (1 min) during timing |\n|---|---:|---:|---:|---:|---|")
    for key, m in machines.items():
        mark = " (compared)" if key == compared else ""
        slots = ", ".join(str(v) for v in m["slots"]) or "?"
        lo, hi = m["load (1 min)"]
        lines.append(f"| {key}{mark} | {m['cores']} | {', '.join(map(str, m['threads']))} "
                     f"| {slots} | {m['rows']} | {lo:.2f} to {hi:.2f} |")
    busy = [(k, m) for k, m in machines.items() if m["load (1 min)"][1] > m["cores"]]
    for key, m in busy:
        lines.append(f"\nOn {key} the 1-minute load average reached "
                     f"{m['load (1 min)'][1]:.2f} on {m['cores']} cores during the timing: "
                     f"other work shared the machine, and its times carry it (compare them "
                     f"with each other, not with another run's).")
    if len(machines) > 1:
        lines.append(f"\nTimes were taken on {len(machines)} machines.  Only those of "
                     f"{compared} are compared (findings, Pareto fronts, plots); a row timed "
                     f"elsewhere shows its time in parentheses with its host and takes no "
                     f"part in any comparison.")
    return "\n".join(lines)


def scene_section(name, sc, rel, plots):
    ref = sc["reference"]
    lines = [f"\n## Scene {name}: {sc['title']}\n", f"{sc['notes']}; {sc['triangles']} triangles.",
             "", "Reference: " + ", ".join(f"{k} {_fmt(v)}" for k, v in ref.items()) + ".", ""]
    if plots and name in plots:
        lines.append(f"![scene {name}: error against time]({rel}/{plots[name]})\n")
    if sc.get("pictures"):
        lines.append(f"![scene {name}: images (top) and decision errors (bottom: red false lit, "
                     f"blue false shadow)]({rel}/{sc['pictures']})\n")
        lines.append("Pictures: each method's image above its decision errors "
                     "(grey right, red false lit, blue false shadow).\n")
    rows = sc["rows"]
    hard = [r for r in rows if r["family"] != "soft"]
    soft = [r for r in rows if r["family"] == "soft"]
    lines += ["### Findings (computed from the table)\n"] + findings(hard, soft) + [""]
    lines += ["### Hard shadows, against the point-light reference\n", table(hard)]
    if soft:
        lines += ["\n### Soft shadows, against the converged area-light reference\n",
                  table(soft)]
    seeded = [r for r in rows if r.get("spread")]
    if seeded:
        lines += ["\n### Seeds of the jittered configurations\n", SEEDS, seed_table(seeded)]
    if sc.get("failed"):
        lines += ["\n### Failed configurations\n",
                  "| configuration | seed | error |\n|---|---|---|"]
        lines += [f"| {f['label']} | {'–' if f['seed'] is None else f['seed']} "
                  f"| {_cell(f['error'])} |" for f in sc["failed"]]
    return "\n".join(lines)


def seed_table(rows):
    """Mean and spread (min, max, standard deviation) over the seeds."""
    head = ("| method | seeds | misclassified % mean (min to max, std) "
            "| RMSE mean (min to max, std) |\n|---|---:|---|---|")
    body = []
    for r in rows:
        cells = []
        for k, f in (("misclassified", ".3f"), ("rmse", ".2f")):
            sp = r["spread"][k]
            cells.append(f"{r[k]:{f}} ({sp['min']:{f}} to {sp['max']:{f}}, {sp['std']:{f}})")
        body.append(f"| {r['label']} | {len(r['seeds'])} | {cells[0]} | {cells[1]} |")
    return "\n".join([head] + body)


def _cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")[:200]


def _time_cell(r):
    if not math.isnan(r["time_ms"]):
        return f"{r['time_ms']:.0f}"
    if r.get("time_ms_elsewhere") is not None:
        return f"({r['time_ms_elsewhere']:.0f} on {r['machine'].split(' ')[0]})"
    return "–"


def _ms(r):
    return "–" if math.isnan(r["time_ms"]) else f"{r['time_ms']:.0f} ms"


def table(rows):
    head = ("| method | parameters | false lit % | false shadow % | RMSE | max abs | time ms "
            "| runs | memory MB (host + framebuffer) |\n"
            "|---|---|---:|---:|---:|---:|---:|---:|---|")
    body = []
    for r in rows:
        params = ", ".join(f"{k}={v}" for k, v in r["params"].items()) or "–"
        t = _time_cell(r)
        mem = "–" if not r["memory_bytes"] else (
            f"{r['memory_bytes'] / MB:.1f} ({r['host_peak_bytes'] / MB:.1f} + "
            f"{r['fb_bytes'] / MB:.1f})")
        body.append(f"| {r['label']} | {params} | {r['false_lit']:.3f} | {r['false_shadow']:.3f} "
                    f"| {r['rmse']:.2f} | {r['max_abs']:.0f} | {t} | {len(r['times_ms'])} "
                    f"| {mem} |")
    return "\n".join([head] + body)


def findings(hard, soft):
    """Sentences computed from the rows."""
    out = []
    by = {r["label"]: r for r in hard + soft}
    floor = next((r for r in hard if r["family"] == "floor"), None)
    if floor:
        out.append(f"- Floor: the rasterized image blended with the reference's own decision "
                   f"has RMSE {floor['rmse']:.2f} (pixel coverage and 8-bit rounding).")
    for r in hard:
        if r["family"] in ("volumes", "planar"):
            out.append(f"- {r['label']}: {r['false_lit']:.3f} % false lit, "
                       f"{r['false_shadow']:.3f} % false shadow, RMSE {r['rmse']:.2f}, "
                       f"{_ms(r)}.")
    maps = [r for r in hard if r["family"] == "shadow map"]
    res = sorted((r for r in maps if _is_default(r, "res")), key=lambda r: r["params"]["res"])
    if res:
        seq = ", ".join(f"R={r['params']['res']}: {r['misclassified']:.2f} % / {_ms(r)}"
                        for r in res)
        out.append(f"- Shadow map over resolution (bias 0.05, nearest, 24-bit): misclassified "
                   f"/ time: {seq}.")
    for R in sorted({r["params"]["res"] for r in maps}):
        bias = [r for r in maps if r["params"]["res"] == R and _is_default(r, "res", "bias")]
        if len(bias) > 2:
            best = min(bias, key=lambda r: r["misclassified"])
            seq = ", ".join(f"{r['params']['bias']:g}: {r['misclassified']:.2f}"
                            for r in sorted(bias, key=lambda r: r["params"]["bias"]))
            out.append(f"- Bias at R={R} (misclassified %): {seq}; best "
                       f"{best['params']['bias']:g}.")
    filt = [r for r in maps if r["params"]["res"] == 1024 and r["params"]["pcf"] == 1
            and r["params"]["bias"] == 0.05]
    if len(filt) > 2:
        seq = "; ".join(f"{r['label'][len('map R=1024 b=0.05 '):]}: {r['false_lit']:.2f} + "
                        f"{r['false_shadow']:.2f} %, RMSE {r['rmse']:.2f}" for r in filt)
        out.append(f"- R=1024, bias 0.05 (false lit + false shadow): {seq}.")
    pcf = [r for r in maps if _is_default(r, "res", "bias", "pcf") and r["params"]["pcf"] > 1]
    for r in pcf:
        base = by.get(r["label"].replace(f" pcf{r['params']['pcf']}", ""))
        if base:
            out.append(f"- PCF {r['params']['pcf']}x{r['params']['pcf']} at R="
                       f"{r['params']['res']}, bias {r['params']['bias']:g}: RMSE {base['rmse']:.2f} -> {r['rmse']:.2f}, "
                       f"misclassified {base['misclassified']:.2f} -> {r['misclassified']:.2f} %, "
                       f"{_ms(base)} -> {_ms(r)}.")
    if soft:
        seq = ", ".join(f"N={r['params']['n']}: {r['rmse']:.2f} / {_ms(r)}" for r in soft)
        out.append(f"- Soft shadows, RMSE / time against the area-light reference: {seq}.")
    timed = [r for r in hard if r["family"] != "floor" and not math.isnan(r["time_ms"])]
    for key in ("misclassified", "rmse"):
        if not timed:
            break
        front = pareto([(r["time_ms"], r[key]) for r in timed])
        names = ", ".join(timed[i]["label"] for i in sorted(front,
                                                             key=lambda i: timed[i]["time_ms"]))
        out.append(f"- Pareto front, {key} against time (hard): {names}.")
    return out


def _is_default(r, *free):
    """A shadow-map row that differs from the default only in ``free``."""
    from .sweep import DEFAULT_MAP
    return all(r["params"][k] == v for k, v in DEFAULT_MAP.items() if k not in free)


def _fmt(v):
    if isinstance(v, float):
        return f"{v:.2f}"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k}: {_fmt(x)}" for k, x in v.items()) + "}"
    return str(v)


HEADER = """# Shadow study, part 1: error against run time

Every shadow method of the seed papers run through the emulator with IRIS GL
calls, measured against an exact float64 ray-cast reference on {scenes}.

Regenerate this page, its results and pictures with one command (a progress bar
is written on standard error; the study at scale, on Dask, resumable, with
scene files and the big sweep: [shadow-study-at-scale.md](shadow-study-at-scale.md)):

```sh
{cmd} --docs     # or: vgx-study --docs (after pip install -e '.[plots]')
{cmd} --quick    # a reduced sweep at 160 x 120, into out/study-quick/ only
```

Results: `{rel}/results.json`{quick}.  Images are {w} x {h} pixels; light
maps {lo} to {hi} square (beyond {tile} x {tile}, the largest light window, drawn
and tested tile by tile, each an `ortho` sub-box of the light's box, because
the virtual screen is 1280 x 1024).  Times: median of up to {repeats} warm runs
after an untimed one, fewer when the runs of a configuration pass {budget:g} s
("runs" column), taken in a timing phase of their own (below).
"""

TIMING = """
## How the times were taken

Errors and pictures are deterministic: they come out the same in any process
on any machine, and are computed first (the error phase).  Times are not: they
come from a separate timing phase after it, one configuration per task, each
task alone on its worker and at most cores / threads timing tasks per host at a
time, so a timed run shares its core with nothing else of the sweep; the
emulator's numba kernels ran with {threads} thread(s) (`--threads`).  Each
task makes an untimed warm-up run, a run under `tracemalloc` (the memory
column), then up to {repeats} timed runs.  Every time is recorded with its
host, CPU, numba threads and the 1, 5 and 15-minute load averages before and
after (`results.json`, `<scene>/<key>.time.json`): the machine may be shared,
and a load above its cores means the times carry other users' work.  Times
from different machines are never compared with each other: the findings,
Pareto fronts and plots use the times of one machine only.
"""

SEEDS = """The jittered configurations (soft shadows: the light's N directions; dithered
maps: the dither noise) were run with several seeds (`--seeds`); the tables
above show the mean over the seeds, this one the spread.
"""

MEASURES = """
## What is measured

- **Reference** (`study/reference.py`): the eye ray through every pixel centre,
  built from the same `perspective`/`lookat` parameters in float64, hits the
  scene's triangles (Moller-Trumbore through a BVH); a shadow ray from the hit
  point (its triangle skipped, blockers beyond 1e-9 |P|) decides whether the light
  reaches it; a point whose triangle faces away (N.L <= 0) is not lit.  Soft:
  the visible fraction of the light's disc of directions by stratified sampling,
  4x4 to 64x64 strata per level until two levels differ by <= 1/512 (at least
  16x16 when anything lies in the pixel's shadow cone); "pixels per converged
  level k" counts where each pixel stopped (k = 64 is the cap).  Checked
  against the closed form of a straight edge's penumbra (a circular segment):
  error below 0.008 of the visible fraction (tests/test_study.py).
- **Misclassified**: percent of the visible pixels where the method's decision
  lets the light through against the reference (false lit) or not (false
  shadow); fractional decisions (PCF, soft) count by how much they differ.  Hard
  decisions are taken together with the facing test (the lighting gives no
  diffuse light where N.L <= 0, whatever the method says).
- **RMSE / max abs**: image against the reference image (same shading:
  AMBIENT x model ambient + DIFFUSE x max(N.L, 0) x visibility), 0..255, every
  channel and pixel.  The max is dominated by silhouette pixels where a
  rasterized edge and a ray disagree by a whole surface.
- **Memory**: peak Python-side allocations in one run (`tracemalloc`; numpy
  arrays included) + the framebuffer banks the method needs (colour and z
  4 bytes each, stencil 1, accumulation 8 per pixel; light windows included).
- Methods (`study/methods.py`): planar = Tessman's ground matrix through
  Bentley's stencil route; map = Williams' shadow z-buffer (light depth by
  `readsource(SRC_ZBUFFER)` + `lrectread`, the eye's z-buffer carried into
  the light's window on the host, Hart's lit/ambient composite written back
  with `lrectwrite`); volumes = Heidmann's stencil volumes (z-pass, or z-fail
  with caps); soft = Heidmann's fig. 6, N jittered lights accumulated with
  `acbuf` over stencil volumes.  Bias is in world units along the light.
"""

LIMITS = """
## Notes and limits

- Planar projection shadows only the ground: its false lit pixels are the
  shadows of objects on objects (and on the curved receiver), its honest result.
- The shadow-map decision on background pixels and the light map's outside
  (lit, Williams' rule) do not count: only the reference's visible pixels do.
- Dither is one quantum of the light depth (Williams); at 24 bits that is
  far below the bias and changes nothing.
- Soft shadows accumulate with `acbuf(AC_ACCUMULATE, v)`, v = min(1, (32767/N - 1/2)/255),
  and return with `1/(N v)`: N images of 255 at weight 1 would overflow the
  VGX's signed 16-bit accumulation buffer from N = 129 on (and v = 128/N still
  overflows by one at N = 256, each scaled value being rounded to nearest).
  Below weight 1 that rounding costs accuracy: a pixel of the same value in
  every image rounds the same way each time, so the error does not average
  out and reaches up to 1/(2v) levels after the return (about 1 level at
  N = 256): compare N = 128 and N = 256 in the soft tables.
- A light map larger than the light window is tested tile by tile: each eye
  point against the tile its nearest texel lies in, drawn with a border as wide
  as the bilinear and PCF neighbourhoods, so the decisions are those of one big
  map (tests/test_study_scale.py) and memory stays one tile whatever the
  resolution.  A tile's depths can differ from one big window's by one z unit
  at a few texels (each tile has its own projection and scissored box, and the
  z plane's error of under 2^-16 unit can round a depth either way), which
  changes a decision only within one z unit of the bias.
- Times include the emulator's Python front end (one `v3f` per vertex of the
  shadow-volume faces, display lists for the scene) and the numba kernels; they
  rank the methods on this emulator, not on a 1990 VGX.
"""
