"""Running the whole study and writing docs/shadow-study.md, the results
(JSON), the pictures and, when matplotlib is importable, the plots."""
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from . import reference, scenes, sweep
from .progress import Progress
from .render import Stage

ROOT = Path(__file__).resolve().parent.parent
COMMAND = "python -m study"


def machine_info():
    """What the numbers were measured on (and which emulator: its commit and
    the files of the working tree that differ from it)."""
    import numba
    cpu = platform.processor() or "?"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")),
                       cpu)
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "numba threads": numba.get_num_threads(),
            "load average (1 min) at start": round(os.getloadavg()[0], 2),
            "python": platform.python_version(), "numpy": np.__version__,
            "numba": numba.__version__, "platform": platform.platform(),
            "date": datetime.datetime.now().isoformat(timespec="seconds"), **git_info()}


def git_info():
    """The commit of the working tree and its uncommitted library files."""
    def git(*args):
        try:
            return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True,
                                  text=True, timeout=10).stdout.strip()
        except (OSError, subprocess.SubprocessError):
            return ""
    changed = [ln[3:] for ln in git("status", "--porcelain").splitlines()
               if ln[3:].startswith(("vgx_emulator/", "irisgl/"))]
    return {"emulator commit": git("rev-parse", "--short", "HEAD") or "?",
            "uncommitted emulator files": ", ".join(changed) or "none"}


def run(scene_names=("A", "B"), size=(320, 240), quick=False, out_dir=None, md_path=None,
        repeats=5, budget=20.0, families=None, stream=None):
    """Run the sweep on every scene; write results, pictures, plots and the
    markdown report; return the results dict."""
    out_dir = Path(out_dir or ROOT / "docs" / "shadow-study")
    md_path = Path(md_path or out_dir.parent / "shadow-study.md")
    out_dir.mkdir(parents=True, exist_ok=True)
    cfgs = sweep.configs(quick, families)
    results = {"meta": machine_info(), "size": list(size), "quick": quick, "repeats": repeats,
               "budget_s": budget, "scenes": {}}
    bar = Progress(len(scene_names) * (len(cfgs) + 2), stream=stream)
    t0 = time.perf_counter()
    for name in scene_names:
        results["scenes"][name] = run_scene(scenes.get(name), size, cfgs, repeats, budget,
                                            bar, out_dir)
    bar.close()
    results["meta"]["wall time (s)"] = round(time.perf_counter() - t0, 1)
    results["meta"]["load average (1 min) at end"] = round(os.getloadavg()[0], 2)
    (out_dir / "results.json").write_text(json.dumps(results, indent=1, default=_json))
    plots = write_plots(results, out_dir)
    md_path.write_text(markdown(results, out_dir, md_path, plots))
    results["markdown"] = str(md_path)
    return results


def run_scene(scene, size, cfgs, repeats, budget, bar, out_dir):
    """The reference, then every configuration, of one scene."""
    from irisgl import gexit
    w, h = size
    bar.show(f"{scene.name}: reference")
    t = time.perf_counter()
    ref = reference.compute(scene, w, h, soft=any(c.soft for c in cfgs))
    ref_time = time.perf_counter() - t
    bar.step(f"{scene.name}: reference done")
    stage = Stage(scene, w, h)
    floor, floor_out = sweep.floor_row(stage, ref)
    rows, shots = [floor], {floor["label"]: floor_out}
    bar.step(f"{scene.name}: floor")
    for cfg in cfgs:
        bar.show(f"{scene.name}: {cfg.label}")
        row, out = sweep.run_config(stage, ref, cfg, repeats, budget)
        rows.append(row)
        shots[row["label"]] = out
        bar.step(f"{scene.name}: {cfg.label}")
    gexit()
    pictures = write_pictures(scene, ref, shots, out_dir)
    return {"title": scene.title, "notes": scene.notes, "triangles": len(scene.flat()["mesh"]),
            "reference": reference_summary(ref, ref_time), "rows": rows, "pictures": pictures}


def reference_summary(ref, seconds):
    vis = ref.visible
    out = {"visible pixels": int(vis.sum()), "lit %": 100.0 * ref.lit[vis].mean(),
           "facing the light %": 100.0 * ref.facing[vis].mean(), "time (s)": round(seconds, 1)}
    if ref.soft_levels is not None:
        lv = ref.soft_levels[vis]
        out["soft: pixels per converged level k"] = {int(k): int((lv == k).sum())
                                                     for k in np.unique(lv)}
        out["soft: penumbra %"] = 100.0 * np.mean((ref.soft_fraction[vis] > 0)
                                                  & (ref.soft_fraction[vis] < 1))
    return out


def _json(o):
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.floating,)):
        return float(o)
    return str(o)


# ---------------------------------------------------------------------------
# pictures (Pillow, a dependency of the project)
SHOW = ["reference (point light)", "planar (ground matrix)", "map R=64 b=0.05 near",
        "map R=256 b=0.05 near", "map R=1024 b=0.05 near", "map R=4096 b=0.05 near",
        "volumes z-pass", "reference (area light)", "soft N=4", "soft N=16", "soft N=64",
        "soft N=256"]


def write_pictures(scene, ref, shots, out_dir):
    """A montage of images (top) and decision errors (bottom: red false lit,
    blue false shadow) for a few configurations; returns the file name."""
    from PIL import Image, ImageDraw
    tiles = []
    for label in SHOW:
        if label == "reference (point light)":
            img, err = ref.image, sweep.decision_map(ref.lit, ref.lit, ref.visible)
        elif label == "reference (area light)":
            if ref.soft_image is None:
                continue
            img = ref.soft_image
            err = sweep.decision_map(ref.soft_fraction, ref.soft_fraction, ref.visible)
        elif label in shots:
            o = shots[label]
            soft = label.startswith("soft")
            img = o.image
            err = sweep.decision_map(o.lit, ref.soft_fraction if soft else ref.lit, ref.visible,
                                     None if soft else ref.facing)
        else:
            continue
        tiles.append((label, np.concatenate([img[::-1], err[::-1]], axis=0)))
    if not tiles:
        return None
    h, w = tiles[0][1].shape[:2]
    cols = 6
    rows = math.ceil(len(tiles) / cols)
    sheet = Image.new("RGB", (cols * w, rows * (h + 14)), (255, 255, 255))
    draw = ImageDraw.Draw(sheet)
    for k, (label, arr) in enumerate(tiles):
        x, y = (k % cols) * w, (k // cols) * (h + 14)
        sheet.paste(Image.fromarray(np.clip(arr + 0.5, 0, 255).astype(np.uint8)), (x, y + 14))
        draw.text((x + 3, y + 1), label, fill=(0, 0, 0))
    name = f"scene{scene.name}_pictures.png"
    sheet.save(out_dir / name)
    return name


# ---------------------------------------------------------------------------
def write_plots(results, out_dir):
    """The plots, or None when matplotlib cannot be imported."""
    try:
        from . import plots
    except ImportError:
        return None
    return plots.write(results, out_dir)


def markdown(results, out_dir, md_path, plots):
    from .markdown import document
    return document(results, os.path.relpath(out_dir, md_path.parent), plots)


def main_run(args):
    import numba
    numba.set_num_threads(min(args.threads, numba.config.NUMBA_NUM_THREADS))
    return run(args.scenes, args.size, args.quick, args.out_dir, args.md, args.repeats,
               args.budget, args.methods, sys.stderr)
