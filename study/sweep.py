"""What the study runs: the configurations of every method, and running
one configuration on a stage: its image and decision (error phase), its
times and memory (timing phase), its measures against the reference."""
import re
from dataclasses import dataclass, field

import numpy as np

from . import measure, methods

RESOLUTIONS = [64, 128, 256, 512, 1024, 2048, 4096]
BIASES = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]      # world units along the light
DEFAULT_MAP = dict(res=1024, bias=0.05, bilinear=False, dither=False, pcf=1, bits=24)
SOFT_N = [1, 2, 4, 8, 16, 32, 64, 128, 256]
# --full: every resolution to 8192 against every bias, filters and PCF on a grid
FULL_RESOLUTIONS = RESOLUTIONS + [8192]
FULL_BIASES = [0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0]
FULL_PCF = [3, 5, 7, 9]
FULL_SEEDS = 5


@dataclass
class Config:
    family: str                      # a key of methods.METHODS
    params: dict = field(default_factory=dict)
    seed: int = None                 # jittered methods: None = the fixed pattern

    @property
    def soft(self):
        return self.family == "soft"

    @property
    def jittered(self):
        """Soft shadows (jittered lights) and dithered shadow maps."""
        return self.soft or bool(self.params.get("dither"))

    @property
    def key(self):
        """A file name for the configuration (its label and seed)."""
        text = re.sub(r"[^A-Za-z0-9.=-]+", "_", self.label).replace("=", "").strip("_")
        return text + ("" if self.seed is None else f"_seed{self.seed}")

    def kwargs(self):
        """The method's keyword arguments."""
        return dict(self.params, **({} if self.seed is None else {"seed": self.seed}))

    @property
    def label(self):
        p = self.params
        if self.family == "planar":
            return "planar (ground matrix)"
        if self.family == "volumes":
            return "volumes " + ("z-fail" if p.get("zfail") else "z-pass")
        if self.family == "soft":
            return f"soft N={p['n']}"
        text = f"map R={p['res']} b={p['bias']:g} " + ("bilin" if p["bilinear"] else "near")
        text += " dith" if p["dither"] else ""
        text += f" pcf{p['pcf']}" if p["pcf"] > 1 else ""
        return text + (" 16-bit" if p["bits"] == 16 else "")


def shadow_map_configs(quick, full=False):
    """One factor at a time around DEFAULT_MAP: resolution, bias at three
    resolutions, nearest/bilinear x dither x bits, PCF sizes, 16 bits
    (``full``: grids of them instead, light maps to 8192)."""
    out = []

    def add(**kw):
        c = Config("shadow map", dict(DEFAULT_MAP, **kw))
        if c.params not in [o.params for o in out]:
            out.append(c)
    if full:
        for r in FULL_RESOLUTIONS:
            for b in FULL_BIASES:
                for bilinear in (False, True):
                    add(res=r, bias=b, bilinear=bilinear)
            add(res=r, bits=16)
        for r in (256, 1024, 4096, 8192):
            for b in (0.02, 0.05, 0.2):
                for k in FULL_PCF:
                    add(res=r, bias=b, pcf=k)
        for r in (1024, 4096):
            for bilinear in (False, True):
                for bits in (24, 16):
                    add(res=r, bilinear=bilinear, dither=True, bits=bits)
        return out
    for r in ([64, 256, 1024] if quick else RESOLUTIONS):
        add(res=r)
    if quick:
        add(res=256, pcf=3)
        return out
    for r in (256, 1024, 4096):
        for b in BIASES:
            add(res=r, bias=b)
    for bilinear in (False, True):
        for dither in (False, True):
            for bits in (24, 16):
                add(bilinear=bilinear, dither=dither, bits=bits)
    for r, b in ((256, 0.05), (1024, 0.05), (1024, 0.2)):
        for k in (3, 5, 7):
            add(res=r, bias=b, pcf=k)
    for r in (256, 4096):
        add(res=r, bits=16)
    return out


def configs(quick=False, families=None, full=False, seeds=None):
    """Every configuration of the sweep (``quick``: a reduced one, ``full``:
    the big one).  ``seeds``: each jittered configuration once per seed
    0..seeds-1 instead of once with the fixed pattern (``full`` default:
    FULL_SEEDS)."""
    out = [Config("planar"), Config("volumes", {"zfail": False}),
           Config("volumes", {"zfail": True})]
    out += shadow_map_configs(quick, full)
    out += [Config("soft", {"n": n}) for n in ([1, 4, 16] if quick else SOFT_N)]
    if families:
        out = [c for c in out if c.family in families]
    if seeds is None and full:
        seeds = FULL_SEEDS
    if seeds:
        out = [Config(c.family, c.params, k) for c in out
               for k in (range(seeds) if c.jittered else [None])]
    return out


def error_run(stage, cfg):
    """The configuration's untimed run that also reads its decision."""
    return methods.METHODS[cfg.family](stage, True, **cfg.kwargs())


def time_run(stage, cfg, repeats=3, budget=20.0):
    """A warm-up run, a run under tracemalloc, then timed runs: (times in
    s, peak host bytes)."""
    fn = methods.METHODS[cfg.family]
    fn(stage, False, **cfg.kwargs())
    _, peak = measure.host_peak(lambda: fn(stage, False, **cfg.kwargs()))
    times = measure.warm_times(lambda: fn(stage, False, **cfg.kwargs()), repeats, budget)
    return times, int(peak)


def measures(cfg_soft, lit, image, ref):
    """Misclassified (false lit, false shadow) and image error of a
    decision and image against the reference: deterministic, computed
    wherever the reference is."""
    if cfg_soft:
        mis = measure.misclassified(lit, ref.soft_fraction, ref.visible)
        err = measure.image_error(image, ref.soft_image)
    else:
        mis = measure.misclassified(lit, ref.lit, ref.visible, ref.facing)
        err = measure.image_error(image, ref.image)
    return dict(false_lit=mis["false_lit"], false_shadow=mis["false_shadow"],
                misclassified=mis["false_lit"] + mis["false_shadow"], **err)


def run_config(stage, ref, cfg, repeats=3, budget=20.0):
    """Measure one configuration: an untimed run that also reads the
    method's decision, a run under tracemalloc, then timed runs.
    Returns (row, image)."""
    first = error_run(stage, cfg)
    times, peak = time_run(stage, cfg, repeats, budget)
    row = dict(family=cfg.family, label=cfg.label, params=dict(cfg.params),
               reference="area light" if cfg.soft else "point light",
               **measures(cfg.soft, first.lit, first.image, ref),
               time_ms=1000.0 * measure.median(times), times_ms=[1000.0 * t for t in times],
               host_peak_bytes=int(peak), fb_bytes=int(first.fb_bytes),
               memory_bytes=int(peak) + int(first.fb_bytes))
    return row, first


def floor_row(stage, ref):
    """The rasterized image blended with the reference's own decision: the
    image error no shadow method can go below (coverage and rounding)."""
    out = methods.composite(stage, ref.lit)
    err = measure.image_error(out.image, ref.image)
    return dict(family="floor", label="reference decision (floor)", params={},
                reference="point light", false_lit=0.0, false_shadow=0.0, misclassified=0.0,
                **err, time_ms=float("nan"), times_ms=[], host_peak_bytes=0, fb_bytes=0,
                memory_bytes=0), out


def decision_map(lit, truth, visible, facing=None):
    """RGB picture of a decision's errors: grey = right, red = false lit,
    blue = false shadow, black = background (rows bottom first)."""
    m = np.asarray(lit, float) * (facing if facing is not None else 1.0)
    d = (m - np.asarray(truth, float)) * visible
    over, under = np.clip(d, 0, None), np.clip(-d, 0, None)
    grey = 110.0 * visible * (1.0 - over - under)
    return np.clip(np.stack([grey + 230.0 * over, grey + 40.0 * (over + under),
                             grey + 255.0 * under], axis=-1), 0, 255)
