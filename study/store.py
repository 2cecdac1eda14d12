"""The sweep's output folder: a file per configuration, written as each
one finishes, so that nothing done is lost and ``--resume`` can skip it.

Layout (``<s>``: a scene name, ``<key>``: sweep.Config.key)::

    sweep.json                what the sweep is (size, scenes, settings)
    <s>/reference.npz         the exact reference's arrays (+ reference.json)
    <s>/<key>.npz             error phase: the image and the decision
    <s>/<key>.json            its record: the measures, or the error it raised
    <s>/<key>.time.json       timing phase: the times, where and under what load
    results.json, report.md, scene<s>_*.png    assembled at the end

Every file is written to a temporary name and renamed into place, so a
file that exists is complete.  A configuration is done when its ``.json``
says ``"status": "ok"``; a failed one (``"status": "error"``) is tried
again by ``--resume``.
"""
import json
import os
import shutil
import uuid
from pathlib import Path

import numpy as np


def _json_default(o):
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)


def write_json(path, data):
    tmp = path.with_name(f".{path.name}.{uuid.uuid4().hex[:8]}.tmp")
    tmp.write_text(json.dumps(data, indent=1, default=_json_default))
    os.replace(tmp, path)


def read_json(path):
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None


class Store:
    """The output folder of one sweep; ``settings`` must match the folder's
    sweep.json to resume into it (a fresh run empties the folder's records)."""

    def __init__(self, root, settings, resume=False):
        self.root = Path(root)
        self.root.mkdir(parents=True, exist_ok=True)
        self.run_id = uuid.uuid4().hex[:12]
        old = read_json(self.root / "sweep.json")
        if resume and old is not None:
            diff = sorted(k for k in set(old) | set(settings) if old.get(k) != settings.get(k))
            if diff:
                raise ValueError(f"--resume: {self.root} holds a sweep with other settings "
                                 f"({', '.join(diff)}); give another --out or run without "
                                 f"--resume")
        else:
            self.clear(old, settings)
        write_json(self.root / "sweep.json", settings)

    def clear(self, old, new):
        """Remove a previous sweep's records: only the scene folders it or
        this sweep write, and the assembled results."""
        for name in {*(old or {}).get("scene_names", []), *new.get("scene_names", [])}:
            d = self.root / name
            if d.is_dir():
                shutil.rmtree(d)
        for f in ("results.json", "sweep.json"):
            (self.root / f).unlink(missing_ok=True)

    def dir(self, scene):
        d = self.root / scene
        d.mkdir(exist_ok=True)
        return d

    # -- the reference -------------------------------------------------------
    def reference(self, scene):
        """(arrays, summary) of a saved reference, or None."""
        meta = read_json(self.root / scene / "reference.json")
        path = self.root / scene / "reference.npz"
        if meta is None or not path.exists():
            return None
        with np.load(path) as z:
            return {k: z[k] for k in z.files}, meta

    def save_reference(self, scene, arrays, meta):
        d = self.dir(scene)
        tmp = d / f".reference.{uuid.uuid4().hex[:8]}.npz"
        np.savez_compressed(tmp, **arrays)
        os.replace(tmp, d / "reference.npz")
        write_json(d / "reference.json", meta)

    # -- the error phase -----------------------------------------------------
    def record(self, scene, key):
        return read_json(self.root / scene / f"{key}.json")

    def done(self, scene, key):
        r = self.record(scene, key)
        return r is not None and r.get("status") == "ok"

    def shot(self, scene, key):
        """(image uint8, decision, meta dict) of a configuration, or None."""
        path = self.root / scene / f"{key}.npz"
        if not path.exists():
            return None
        with np.load(path) as z:
            meta = json.loads(str(z["meta"])) if "meta" in z.files else {}
            return z["image"], z["lit"], meta

    def save_shot(self, scene, key, image, lit, meta=None):
        """The image and decision, with ``meta`` (JSON: where it was drawn...)."""
        d = self.dir(scene)
        tmp = d / f".{key}.{uuid.uuid4().hex[:8]}.npz"
        np.savez_compressed(tmp, image=image, lit=lit,
                            meta=np.array(json.dumps(meta or {}, default=_json_default)))
        os.replace(tmp, d / f"{key}.npz")

    def forget(self, scene, key):
        """Remove a configuration's record (a failure that is now mended)."""
        (self.root / scene / f"{key}.json").unlink(missing_ok=True)

    def save_record(self, scene, key, record):
        write_json(self.dir(scene) / f"{key}.json", dict(record, run=self.run_id))

    # -- the timing phase ----------------------------------------------------
    def timing(self, scene, key):
        t = read_json(self.root / scene / f"{key}.time.json")
        return t if t is not None and t.get("ok") else None

    def save_timing(self, scene, key, timing):
        write_json(self.dir(scene) / f"{key}.time.json", dict(timing, run=self.run_id))
