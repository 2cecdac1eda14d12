"""Running the whole study and writing docs/shadow-study.md, the results
(JSON), the pictures and, when matplotlib is importable, the plots."""
import datetime
import hashlib
import json
import math
import os
import platform
import shutil
import socket
import subprocess
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import measure, scenes, sweep, tasks
from .cluster import SerialPool, make_pool
from .progress import Progress
from .render import MAX_TILE
from .store import Store

FLOOR = "floor"
REFERENCE = "reference_task"
#: the record of an image drawn and saved whose scene's reference failed
UNMEASURED = {"error": "not measured: the scene's reference failed (the image is saved; "
                       "--resume measures it)", "traceback": "", "unmeasured": True}

ROOT = Path(__file__).resolve().parent.parent
COMMAND = "python -m study"


def machine_info(threads=1):
    """Where the sweep was driven from (each time carries its own machine:
    tasks.where) and which emulator: its commit and the files of the
    working tree that differ from it."""
    import numba
    return {"host": socket.gethostname(), "cpu": tasks.cpu_model(), "cores": os.cpu_count(),
            "numba threads (timing)": threads,
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
        repeats=5, budget=20.0, families=None, stream=None, *, full=False, seeds=None,
        workers=None, scheduler=None, client=None, resume=False, threads=1, timing=True,
        max_tile=MAX_TILE, cfgs=None, docs=False, on_record=None):
    """Run the sweep on every scene (built-in names or scene files) and
    write everything into ``out_dir``: a file per configuration as it
    finishes (study/store.py), then results.json, the pictures, the plots
    and report.md (also ``md_path`` if given, and docs/shadow-study.md with
    its folder if ``docs``).  Tasks run in this process, or on Dask with
    ``workers`` / ``scheduler`` / ``client`` (study/cluster.py); the
    timing phase follows the error phase.  ``on_record(scene, key,
    record)`` is called after each record is written.  Returns the results
    dict."""
    specs = {}
    for arg in scene_names:
        spec = scenes.spec_of(arg)
        name = spec.get("builtin") or str(spec["name"])
        if name in specs:
            raise ValueError(f"two scenes are named {name!r}")
        specs[name] = spec
    size = tuple(int(v) for v in size)
    cfgs = list(cfgs) if cfgs is not None else sweep.configs(quick, families, full, seeds)
    out_dir = Path(out_dir or ROOT / "out" / "study")
    settings = {"size": list(size), "scene_names": list(specs),
                "scenes": {n: _digest(s) for n, s in specs.items()}, "max_tile": int(max_tile),
                "repeats": int(repeats), "budget_s": float(budget), "threads": int(threads)}
    pool = make_pool(workers, scheduler, client)
    t0 = time.perf_counter()
    meta = machine_info(threads)
    try:
        store = Store(out_dir, settings, resume)
        log = stream if stream is not None else sys.stderr
        print(f"study: {len(cfgs)} configurations x {len(specs)} scenes on {pool.description}, "
              f"into {out_dir}", file=log)
        refs = error_phase(pool, store, specs, size, cfgs, threads, max_tile, stream, on_record)
        if timing:
            timing_phase(pool, store, specs, size, cfgs, repeats, budget, threads, max_tile,
                         stream)
    finally:
        pool.close()
    meta["wall time (s)"] = round(time.perf_counter() - t0, 1)
    meta["load average (1 min) at end"] = round(os.getloadavg()[0], 2)
    meta["engine"] = pool.description
    results = assemble(store, specs, refs, cfgs, meta, size, quick, full, repeats, budget)
    results["max_tile"] = int(max_tile)
    return write_outputs(results, store, specs, refs, cfgs, out_dir, md_path, docs)


def _digest(spec):
    return hashlib.sha1(json.dumps(spec, sort_keys=True).encode()).hexdigest()[:16]


def error_phase(pool, store, specs, size, cfgs, threads, max_tile, stream, on_record):
    """Every configuration's image and decision, and the references; the
    records written as results arrive.  Returns {scene: Reference or None}."""
    err_threads = threads if isinstance(pool, SerialPool) else 1
    soft = any(c.soft for c in cfgs)
    refs, waiting = {}, {name: [] for name in specs}
    bar = Progress(len(specs) * (len(cfgs) + 2), stream=stream)

    def submit_floor(name):
        if not store.done(name, FLOOR):
            pool.submit((name, FLOOR, None), tasks.floor_task, specs[name], size,
                        refs[name].lit, err_threads, max_tile, priority=5)
        else:
            bar.step(f"{name}: floor (done before)")

    def finish(name, key, cfg, image, lit, meta):
        rec = {"status": "ok", "scene": name, "key": key, "label": _label(cfg),
               "family": "floor" if cfg is None else cfg.family,
               "params": {} if cfg is None else dict(cfg.params),
               "seed": None if cfg is None else cfg.seed, **meta,
               **sweep.measures(cfg is not None and cfg.soft, lit, image, refs[name])}
        store.save_record(name, key, rec)
        if on_record:
            on_record(name, key, rec)

    for name, spec in specs.items():
        saved = store.reference(name)
        if saved is not None and (not soft or "soft_fraction" in saved[0]):
            refs[name] = tasks.reference_from(saved[0])
            bar.step(f"{name}: reference (saved)")
            submit_floor(name)
        else:
            pool.submit((name, REFERENCE, None), tasks.reference_task, spec, size, soft,
                        err_threads, priority=10)
        for cfg in cfgs:
            if store.done(name, cfg.key):
                bar.step(f"{name}: {cfg.label} (done before)")
                continue
            shot, rec = store.shot(name, cfg.key), store.record(name, cfg.key)
            if shot is not None and (rec is None or rec.get("unmeasured")):
                waiting[name].append((cfg, shot))      # rendered, not measured: no rerun
                continue
            pool.submit((name, cfg.key, cfg), tasks.render_task, spec, size, cfg.family,
                        dict(cfg.params), cfg.seed, err_threads, max_tile)
        if name in refs:
            for c, (image, lit, meta) in waiting.pop(name, []):
                finish(name, c.key, c, image, lit, meta)
                bar.step(f"{name}: {_label(c)}")
    for (name, key, cfg), ok, value in pool:
        if ok and key == REFERENCE:
            refs[name] = tasks.reference_from(value["arrays"])
            store.save_reference(name, value["arrays"],
                                 reference_summary(refs[name], value["seconds"]))
            store.forget(name, REFERENCE)
            bar.step(f"{name}: reference")
            submit_floor(name)
            for c, (image, lit, meta) in waiting.pop(name, []):
                finish(name, c.key, c, image, lit, meta)
                bar.step(f"{name}: {_label(c)}")
            continue
        if ok and value.get("ok"):
            meta = {"fb_bytes": value["fb_bytes"], "info": value["info"],
                    "where": value["where"], "render_s": value["seconds"]}
            store.save_shot(name, key, value["image"], value["lit"], meta)
            if name not in refs:
                waiting[name].append((cfg, (value["image"], value["lit"], meta)))
                continue
            if refs[name] is not None:
                finish(name, key, cfg, value["image"], value["lit"], meta)
                bar.step(f"{name}: {_label(cfg)}")
                continue
            value = dict(UNMEASURED, **meta)
        fail = value if ok else {"error": f"{type(value).__name__}: {value}",
                                 "traceback": "".join(traceback.format_exception(value))}
        rec = {"status": "error", "scene": name, "key": key,
               "label": "reference" if key == REFERENCE else _label(cfg),
               "family": "floor" if cfg is None else cfg.family,
               "params": {} if cfg is None else dict(cfg.params),
               "seed": None if cfg is None else cfg.seed, **fail}
        store.save_record(name, key, rec)
        if key == REFERENCE:
            refs[name] = None
            for c, _ in waiting.pop(name, []):
                store.save_record(name, c.key, dict(rec, key=c.key, label=_label(c),
                                                    family=c.family, params=dict(c.params),
                                                    seed=c.seed, **UNMEASURED))
                bar.step(f"{name}: {_label(c)} not measured")
        print(f"\nstudy: {name}: {rec['label']} failed: {rec['error']}", file=sys.stderr)
        if on_record:
            on_record(name, key, rec)
        bar.step(f"{name}: {rec['label']} failed")
    bar.close()
    return refs


def _label(cfg):
    return "reference decision (floor)" if cfg is None else cfg.label


def timing_groups(cfgs):
    """{label: the configurations of a label (its seeds)}, in sweep order."""
    groups = {}
    for c in cfgs:
        groups.setdefault(c.label, []).append(c)
    return groups


def timing_phase(pool, store, specs, size, cfgs, repeats, budget, threads, max_tile, stream):
    """Time every configuration done (one seed of each), one task per
    timing slot at a time, after the error phase."""
    jobs = []
    for name, spec in specs.items():
        for label, group in timing_groups(cfgs).items():
            c = group[0]
            if store.done(name, c.key) and store.timing(name, c.key) is None:
                jobs.append(((name, c.key, c), tasks.time_task,
                             (spec, size, c.family, dict(c.params), c.seed, repeats, budget,
                              threads, max_tile)))
    if not jobs:
        return
    slots = pool.timing_slots(threads)
    free, running, pending = list(slots), {}, list(reversed(jobs))
    bar = Progress(len(jobs), stream=stream)

    def fill():
        while pending and (free or not running):
            slot = free.pop(0) if free else None
            tag, fn, args = pending.pop()
            pool.submit(tag, fn, *args, slot=slot)
            running[tag[:2]] = slot
    fill()
    for (name, key, cfg), ok, value in pool:
        slot = running.pop((name, key))
        if not pool.alive(slot):
            slot = pool.spare_slot(set(running.values()) | set(free))
        if slot is not None or not free:
            free.append(slot)
        if not ok:
            value = {"ok": False, "error": f"{type(value).__name__}: {value}"}
        if value.get("ok"):
            value["slots"] = len(slots)
        else:
            print(f"\nstudy: {name}: timing {cfg.label} failed: {value['error']}",
                  file=sys.stderr)
        store.save_timing(name, key, value)
        bar.step(f"{name}: timed {cfg.label}")
        fill()
    bar.close()


def assemble(store, specs, refs, cfgs, meta, size, quick, full, repeats, budget):
    """results.json's dict, from the records in the store: per scene the
    floor and a row per configuration label (the mean over its seeds with
    their spread), its time and where it was taken; failures listed."""
    results = {"meta": meta, "size": list(size), "quick": quick, "full": full,
               "repeats": repeats, "budget_s": budget, "scenes": {}}
    machines = {}
    for name in specs:
        sc = scenes.build(specs[name])
        rows, failed = [], []
        broken = store.record(name, REFERENCE)
        if broken is not None:
            failed.append(_failed(broken))
        floor = store.record(name, FLOOR)
        if floor is not None and floor["status"] == "ok":
            rows.append(dict(_row(floor, [floor]), time_ms=float("nan"), times_ms=[],
                             host_peak_bytes=0, memory_bytes=0, fb_bytes=0))
        elif floor is not None:
            failed.append(_failed(floor))
        for label, group in timing_groups(cfgs).items():
            recs = [store.record(name, c.key) for c in group]
            failed += [_failed(r) if r else {"label": label, "seed": c.seed,
                                             "error": "no record (the run was interrupted, or the "
                                                      "scene's reference failed)"}
                       for c, r in zip(group, recs) if r is None or r["status"] != "ok"]
            good = [r for r in recs if r is not None and r["status"] == "ok"]
            if not good:
                continue
            row = _row(good[0], good)
            t = store.timing(name, group[0].key)
            if t is not None:
                w = t["where"]
                mkey = f"{w['host']} ({w['cpu']})"
                m = machines.setdefault(mkey, {"host": w["host"], "cpu": w["cpu"],
                                               "cores": w["cores"], "threads": set(),
                                               "load (1 min)": [], "rows": 0, "slots": set()})
                m["threads"].add(t["threads"])
                m["load (1 min)"] += [t["load_before"][0], t["load_after"][0]]
                m["rows"] += 1
                m["slots"].add(t.get("slots"))
                row.update(time_ms=1000.0 * measure.median(t["times_s"]),
                           times_ms=[1000.0 * v for v in t["times_s"]],
                           host_peak_bytes=t["host_peak_bytes"],
                           memory_bytes=t["host_peak_bytes"] + row["fb_bytes"],
                           machine=mkey, threads=t["threads"], load=[t["load_before"],
                                                                      t["load_after"]])
            else:
                row.update(time_ms=float("nan"), times_ms=[], host_peak_bytes=0,
                           memory_bytes=0)
            rows.append(row)
        summary = (store.reference(name) or (None, None))[1]
        results["scenes"][name] = {"title": sc.title, "notes": sc.notes,
                                   "triangles": len(sc.flat()["mesh"]),
                                   "reference": summary or {}, "rows": rows,
                                   "failed": failed}
    # times are compared on one machine only: the one that timed the most rows
    compared = max(machines, key=lambda k: machines[k]["rows"]) if machines else None
    for sc in results["scenes"].values():
        for r in sc["rows"]:
            if r.get("machine") and r["machine"] != compared:
                r["time_ms_elsewhere"], r["time_ms"] = r["time_ms"], float("nan")
    for m in machines.values():
        loads = m.pop("load (1 min)")
        m["load (1 min)"] = [min(loads), max(loads)]
        m["threads"] = sorted(m["threads"])
        m["slots"] = sorted(s for s in m["slots"] if s is not None)
    results["timing"] = {"machines": machines, "compared on": compared}
    return results


SPREAD = ("false_lit", "false_shadow", "misclassified", "rmse", "max_abs")


def _row(first, recs):
    """A table row from the records of one label (several seeds: the mean,
    and min / max / standard deviation in ``spread``)."""
    row = {k: first[k] for k in ("family", "label", "params", "fb_bytes")}
    row["fb_bytes"] = int(row["fb_bytes"] or 0)
    row["reference"] = "area light" if first["family"] == "soft" else "point light"
    for k in SPREAD:
        row[k] = float(np.mean([r[k] for r in recs]))
    if len(recs) > 1:
        row["seeds"] = [r["seed"] for r in recs]
        row["spread"] = {k: {"min": float(np.min([r[k] for r in recs])),
                             "max": float(np.max([r[k] for r in recs])),
                             "std": float(np.std([r[k] for r in recs]))} for k in SPREAD}
    return row


def _failed(rec):
    return {"label": rec.get("label"), "seed": rec.get("seed"), "error": rec.get("error")}


def write_outputs(results, store, specs, refs, cfgs, out_dir, md_path, docs):
    """results.json, pictures, plots and report.md into ``out_dir`` (and
    ``md_path``; and docs/shadow-study.md + docs/shadow-study/ if ``docs``)."""
    for name, sc in results["scenes"].items():
        sc["pictures"] = None
        if refs.get(name) is not None:
            shots = {}
            groups = timing_groups(cfgs)
            for label in SHOW:
                if label in groups:
                    got = store.shot(name, groups[label][0].key)
                    if got is not None:
                        shots[label] = Shot(*got[:2])
            sc["pictures"] = write_pictures(name, refs[name], shots, out_dir)
    (out_dir / "results.json").write_text(json.dumps(results, indent=1, default=_json))
    plots = write_plots(results, out_dir)
    report_md = out_dir / "report.md"
    report_md.write_text(markdown(results, out_dir, report_md, plots))
    results["markdown"] = str(report_md)
    if md_path:
        md_path = Path(md_path)
        md_path.write_text(markdown(results, out_dir, md_path, plots))
        results["markdown"] = str(md_path)
    if docs:
        folder = ROOT / "docs" / "shadow-study"
        folder.mkdir(parents=True, exist_ok=True)
        for f in ["results.json", *[sc["pictures"] for sc in results["scenes"].values()],
                  *(plots or {}).values()]:
            if f:
                shutil.copyfile(out_dir / f, folder / f)
        page = ROOT / "docs" / "shadow-study.md"
        page.write_text(markdown(results, folder, page, plots))
        results["markdown"] = str(page)
    return results


@dataclass
class Shot:
    """A configuration's saved image and decision (for the pictures)."""
    image: np.ndarray
    lit: np.ndarray


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


def write_pictures(scene_name, ref, shots, out_dir):
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
    name = f"scene{scene_name}_pictures.png"
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
    """vgx-study's run from its parsed arguments."""
    return run(args.scenes, args.size, args.quick, args.out, args.md, args.repeats,
               args.budget, args.methods, sys.stderr, full=args.full, seeds=args.seeds,
               workers=args.workers, scheduler=args.scheduler, resume=args.resume,
               threads=args.threads, timing=not args.no_timing, max_tile=args.tile,
               docs=args.docs)
