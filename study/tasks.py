"""The study's tasks: what a worker process (or the serial run's own
process) does for one piece of the sweep.  Every task takes plain data (a
scene spec, an image size, a configuration as family, params and seed) and
returns plain data, so it can run in any process that has the project
installed: the process's own emulator draws it.

A process keeps the scenes it has built and the last few stages (the eye's
and the light's windows, the display lists), so consecutive configurations
of a scene reuse them; a lock keeps one task at a time on the emulator
when a worker runs tasks in several threads.
"""
import json
import os
import platform
import socket
import threading
import time
import traceback
from collections import OrderedDict

import numpy as np

STAGES_KEPT = 2
_LOCK = threading.RLock()
_SCENES = {}
_STAGES = OrderedDict()


def _spec_key(spec):
    return json.dumps(spec, sort_keys=True)


def scene_of(spec):
    """The Scene of a spec (built once per process)."""
    from . import scenes
    key = _spec_key(spec)
    if key not in _SCENES:
        _SCENES[key] = scenes.build(spec)
    return _SCENES[key]


def stage_of(spec, size, max_tile):
    """The process's Stage of a scene at an image size (the least recently
    used of more than STAGES_KEPT is closed)."""
    from .render import Stage
    key = (_spec_key(spec), tuple(size), int(max_tile))
    if key in _STAGES:
        _STAGES.move_to_end(key)
        return _STAGES[key]
    while len(_STAGES) >= STAGES_KEPT:
        _, old = _STAGES.popitem(last=False)
        old.close()
    _STAGES[key] = Stage(scene_of(spec), *size, max_tile=max_tile)
    return _STAGES[key]


def reset():
    """Close every stage of this process (its windows, display lists);
    forget those whose windows are already gone (a machine reset)."""
    from vgx_emulator.errors import GLError
    while _STAGES:
        try:
            _STAGES.popitem()[1].close()
        except GLError:
            pass


def _threads(n):
    import numba
    numba.set_num_threads(max(1, min(int(n), numba.config.NUMBA_NUM_THREADS)))
    return numba.get_num_threads()


def _config(family, params, seed):
    from .sweep import Config
    return Config(family, dict(params), seed)


def cpu_model():
    """The CPU's model name (/proc/cpuinfo), else platform.processor()."""
    try:
        with open("/proc/cpuinfo") as f:
            for ln in f:
                if ln.startswith("model name"):
                    return ln.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "?"


def where():
    """The process a task ran in: host, CPU, cores, pid, Dask worker name."""
    name = "serial"
    try:
        from distributed import get_worker
        name = str(get_worker().name)
    except (ImportError, ValueError):
        pass
    return {"host": socket.gethostname(), "cpu": cpu_model(), "cores": os.cpu_count(),
            "pid": os.getpid(), "worker": name}


def _failure(exc):
    return {"ok": False, "error": f"{type(exc).__name__}: {exc}",
            "traceback": traceback.format_exc(), "where": where()}


def reference_task(spec, size, soft, threads=1):
    """The exact reference of a scene: its arrays and its time (s)."""
    from . import reference
    with _LOCK:
        _threads(threads)
        t0 = time.perf_counter()
        ref = reference.compute(scene_of(spec), *size, soft=soft)
        return {"arrays": reference_arrays(ref), "seconds": time.perf_counter() - t0}


def reference_arrays(ref):
    """A Reference as a dict of arrays (what reference_from takes back)."""
    out = {k: getattr(ref, k) for k in ("tri", "point", "facing", "lit", "image",
                                         "soft_fraction", "soft_image", "soft_levels")
           if getattr(ref, k) is not None}
    out["size"] = np.array([ref.width, ref.height])
    return out


def reference_from(arrays):
    from .reference import Reference
    a = dict(arrays)
    w, h = (int(v) for v in a.pop("size"))
    return Reference(w, h, **{k: np.asarray(v) for k, v in a.items()})


def _shot(out, t0):
    return {"ok": True, "image": np.asarray(np.rint(out.image), np.uint8),
            "lit": np.asarray(out.lit, np.float64), "fb_bytes": int(out.fb_bytes),
            "info": {k: v for k, v in out.info.items()},
            "seconds": time.perf_counter() - t0, "where": where()}


def render_task(spec, size, family, params, seed=None, threads=1, max_tile=1024):
    """Error phase, one configuration: its image (uint8) and decision, or
    the error it raised (``ok`` False, with the traceback)."""
    from . import sweep
    with _LOCK:
        t0 = time.perf_counter()
        try:
            _threads(threads)
            out = sweep.error_run(stage_of(spec, size, max_tile), _config(family, params, seed))
            return _shot(out, t0)
        except Exception as e:          # recorded; the sweep goes on
            return _failure(e)


def floor_task(spec, size, lit, threads=1, max_tile=1024):
    """The floor: the rasterized image blended with the reference's
    decision ``lit``."""
    from . import methods
    with _LOCK:
        t0 = time.perf_counter()
        try:
            _threads(threads)
            out = methods.composite(stage_of(spec, size, max_tile), lit)
            return _shot(out, t0)
        except Exception as e:
            return _failure(e)


def time_task(spec, size, family, params, seed=None, repeats=5, budget=20.0, threads=1,
              max_tile=1024):
    """Timing phase, one configuration: warm run times, the peak host
    memory, and where and under what load they were taken (host, CPU,
    numba threads, 1/5/15-minute load averages before and after)."""
    from . import sweep
    with _LOCK:
        try:
            used = _threads(threads)
            stage = stage_of(spec, size, max_tile)
            load0 = os.getloadavg()
            times, peak = sweep.time_run(stage, _config(family, params, seed), repeats, budget)
            load1 = os.getloadavg()
        except Exception as e:
            return _failure(e)
        return {"ok": True, "times_s": times, "host_peak_bytes": peak, "threads": used,
                "load_before": [round(v, 2) for v in load0],
                "load_after": [round(v, 2) for v in load1], "where": where(),
                "date": time.strftime("%Y-%m-%dT%H:%M:%S")}
