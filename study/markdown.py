"""docs/shadow-study.md from the results of a run (every number in it is
computed from them)."""
import math

from .measure import pareto

MB = 1024.0 * 1024.0


def document(results, rel, plots):
    w, h = results["size"]
    out = [HEADER.format(cmd="python -m study", w=w, h=h,
                         quick=" (this run: `--quick`, a reduced sweep)" if results["quick"]
                         else "", repeats=results["repeats"], budget=results["budget_s"])]
    out.append("| | |\n|---|---|")
    out += [f"| {k} | {v} |" for k, v in results["meta"].items()]
    out.append(MEASURES)
    for name, sc in results["scenes"].items():
        out.append(scene_section(name, sc, rel, plots))
    out.append(LIMITS)
    return "\n".join(out) + "\n"


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
    return "\n".join(lines)


def table(rows):
    head = ("| method | parameters | false lit % | false shadow % | RMSE | max abs | time ms "
            "| runs | memory MB (host + framebuffer) |\n"
            "|---|---|---:|---:|---:|---:|---:|---:|---|")
    body = []
    for r in rows:
        params = ", ".join(f"{k}={v}" for k, v in r["params"].items()) or "–"
        t = "–" if math.isnan(r["time_ms"]) else f"{r['time_ms']:.0f}"
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
                       f"{r['time_ms']:.0f} ms.")
    maps = [r for r in hard if r["family"] == "shadow map"]
    res = sorted((r for r in maps if _is_default(r, "res")), key=lambda r: r["params"]["res"])
    if res:
        seq = ", ".join(f"R={r['params']['res']}: {r['misclassified']:.2f} % / "
                        f"{r['time_ms']:.0f} ms" for r in res)
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
                       f"{base['time_ms']:.0f} -> {r['time_ms']:.0f} ms.")
    if soft:
        seq = ", ".join(f"N={r['params']['n']}: {r['rmse']:.2f} / {r['time_ms']:.0f} ms"
                        for r in soft)
        out.append(f"- Soft shadows, RMSE / time against the area-light reference: {seq}.")
    timed = [r for r in hard if r["family"] != "floor"]
    for key in ("misclassified", "rmse"):
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
    return str(v)


HEADER = """# Shadow study, part 1: error against run time

Every shadow method of the seed papers run through the emulator with IRIS GL
calls, measured against an exact float64 ray-cast reference on two scenes.

Regenerate this page, its results and pictures with one command (a progress bar
is written on standard error):

```sh
{cmd}            # or: vgx-study (after pip install -e '.[plots]')
{cmd} --quick    # a reduced sweep at 160 x 120, into a temporary directory
```

Results: `shadow-study/results.json`{quick}.  Images are {w} x {h} pixels; light
maps 64 to 4096 square (drawn in tiles of at most 1024 x 1024, each an `ortho`
sub-box of the light's box, because the virtual screen is 1280 x 1024).  Times:
median of up to {repeats} warm runs after an untimed one, fewer when the runs
of a configuration pass {budget:g} s ("runs" column).  The machine is shared, so
times carry its load (see the load averages below); the emulator's numba kernels
ran with the number of threads in the table (`--threads`, default 1: with 2
threads on this 2-core machine the same run took from 1x to 3x as long
depending on the other users' load).
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
- Times include the emulator's Python front end (one `v3f` per vertex of the
  shadow-volume faces, display lists for the scene) and the numba kernels; they
  rank the methods on this emulator, not on a 1990 VGX.
"""
