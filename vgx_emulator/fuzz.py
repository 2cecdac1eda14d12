"""A fuzzer of the emulated VGX, driven from outside through the IRIS GL calls.

``python -m vgx_emulator.fuzz --seed S --primitives N`` draws N random
primitives in batches, each batch in a fresh subprocess (so a crash or a hang
is caught and reported with the seed and batch that reproduce it), and with
``--misuse`` also gives every public irisgl call wrong types, arities, tokens
and sizes.  docs/reliability.md reports its runs and says what each check
promises.

Drawing (``draw`` worker, one batch): random windows (1..96 pixels a side, RGB
or colour map, single or double buffered, 1-8 stencil planes), random
viewport and scrmask (partly outside the window), random matrices, and a
raster state from a bounded pool of recipes (``--states``: which stages are
on, so that the number of compiled kernel variants stays small) with random
values (z function and writemask, stencil function, ops, ref and masks, blend
factors, logicop, alpha function, pattern bits, colour writemask, shade model,
lighting, line width, point size).  Vertices are mostly ordinary, some NaN,
infinite, 1e38, w <= 0, tiny, or slivers.  After every frame:

- no exception other than GLError, and no warning other than a VGXWarning
  whose message starts with the name of a call (numpy's floating-point
  warnings must not reach the user);
- nothing written outside viewport ∩ scrmask ∩ window (every bank compared
  before and after outside that box);
- values in range: z within the 24-bit VGX range, stencil within its planes,
  colour-map indices within 12 bits;
- a hash of every bank, which the parent compares between a run on 1 and on 2
  threads, between two runs, and with a run on the general kernel variants
  (``VGX_GENERAL=always``, vgx_emulator/specialise.py) (``--recheck-every``).

Misuse (``misuse`` worker): for each call of ``irisgl._current.API``, wrong
arities and, argument by argument, None, an object, a complex, a dict, a
string, NaN, infinities, 2**70, -2**70, 1e38, 10**6, -1, 9999 and short or
wrong-typed arrays.  Each trial must raise GLError with a message starting
with the call's name and leave the machine's state (matrices, modes, banks,
queue, definitions: a hash of everything) unchanged, or be accepted; an
accepted trial is followed by a flush and a small drawing in the state it
left, which must not fail.  A garbage value (an object, a complex) accepted
where the call takes no such argument is a finding (``TAKES_OBJECTS``,
``ANSWER_MINUS_ONE``).
"""
import argparse
import hashlib
import inspect
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import traceback
import warnings
from collections import Counter
from concurrent.futures import ThreadPoolExecutor

import numpy as np

#: the specials vertices draw from
SPECIALS = (float("nan"), float("inf"), -float("inf"), 1e38, -1e38, 3e38, 1e30, -1e-30,
            1e-30, 0.0)

#: how many vertices / primitives a frame draws at most
MAX_PRIMS_PER_FRAME = 120


# ----------------------------------------------------------------------------
# raster-state recipes: which stages a frame enables (its kernel variant)
def recipes(k):
    """The pool of ``k`` raster-state recipes, the same for every seed (so
    that the kernels they compile are served from numba's disk cache in every
    later run): recipe 0 is the default state, the others switch stages on."""
    rng = np.random.default_rng(20250119)
    out = [dict(cmode=False, double=False, ztest=False, zwrite=False, stencil=0,
                blend=None, logic=False, atest=False, pattern=False, cmask=False,
                gouraud=True, light=0, dual=False, planes=8)]
    pairs = [(1, 1), (4, 5), (1, 5), (2, 0), (0, 2), "generic"]
    while len(out) < k:
        cm = bool(rng.random() < 0.2)
        ztest = bool(rng.random() < 0.6)
        r = dict(cmode=cm, double=bool(rng.random() < 0.4),
                 ztest=ztest, zwrite=ztest and bool(rng.random() < 0.8),
                 stencil=int(rng.choice([0, 0, 1, 2, 2])),
                 blend=None if cm or rng.random() < 0.6 else pairs[int(rng.integers(len(pairs)))],
                 logic=bool(rng.random() < 0.25), atest=not cm and bool(rng.random() < 0.2),
                 pattern=bool(rng.random() < 0.3), cmask=bool(rng.random() < 0.3),
                 gouraud=bool(rng.random() < 0.6),
                 light=0 if cm else int(rng.choice([0, 0, 1, 2])),
                 dual=False, planes=int(rng.choice([1, 3, 8])))
        r["dual"] = r["double"] and bool(rng.random() < 0.3)
        out.append(r)
    return out[:k]


# ----------------------------------------------------------------------------
# drawing worker
class Finding(Exception):
    pass


def _num(rng, scale=1.5, special=0.03):
    if rng.random() < special:
        return SPECIALS[int(rng.integers(len(SPECIALS)))]
    return float(rng.normal() * scale)


def _vertex(rng, special):
    x, y, z = _num(rng, special=special), _num(rng, special=special), _num(rng, 0.8, special)
    if rng.random() < special:                     # w <= 0, tiny or huge
        w = float(rng.choice([0.0, -1.0, -1e-30, 1e-30, 1e30, -0.3]))
    else:
        w = 1.0
    return [x, y, z, w]


def _points(rng, n, special):
    pts = [_vertex(rng, special) for _ in range(n)]
    if n >= 3 and rng.random() < 0.15:             # a sliver: nearly collinear points
        a, b = np.array(pts[0]), np.array(pts[1])
        t = rng.random()
        with np.errstate(all="ignore"):            # the fuzzer's own arithmetic on specials
            pts[2] = list(a + t * (b - a) + rng.normal(size=4) * 1e-7 * np.array([1, 1, 1, 0]))
    if n >= 2 and rng.random() < 0.05:             # coincident vertices
        pts[1] = list(pts[0])
    return pts


#: what each primitive kind of Drawer._primitive draws
KIND_NAMES = ("bgnpoint", "bgnline", "bgnclosedline", "bgnpolygon", "bgntmesh", "bgnqstrip",
              "rectf", "circf", "move/draw", "polf", "pnt", "lrectwrite", "bgnpolygon",
              "bgntmesh", "rectcopy")


class Drawer:
    """One batch of the drawing fuzz (module docstring)."""

    def __init__(self, seed, index, count, nstates, threads):
        import irisgl as gl
        from irisgl._current import API, machine
        from . import config
        self.gl, self.machine, self.api = gl, machine, set(API)
        self.rng = np.random.default_rng([seed, index])
        self.count, self.recipes = count, recipes(nstates)
        self.findings, self.hashes = [], []
        self.stats = Counter()
        if threads > 1:
            config.PARALLEL_MIN_PIXELS = 0         # every batch of more than one band threaded
        import numba
        numba.set_num_threads(threads)

    # -- checks -------------------------------------------------------------
    def _banks(self):
        self.machine.flush()
        fb = self.machine.current.fb
        return {k: (None if a is None else a.copy()) for k, a in
                (("front", fb.front), ("back", fb.back), ("z", fb.z), ("stencil", fb.stencil))}

    def _check(self, before, after, box, recipe, frame):
        from .framebuffer import ZMAX, ZMIN
        fb = self.machine.current.fb
        h, w = fb.height, fb.width
        inside = np.zeros((h, w), bool)
        if box is not None:
            x0, x1, y0, y1 = box
            inside[y0:y1 + 1, x0:x1 + 1] = True
        for name, a in after.items():
            b = before.get(name)
            if a is None:
                continue
            if b is None:
                # a bank created during the frame (z at first zbuffer): its
                # initial value is GD_ZMAX
                b = np.full_like(a, ZMAX)
            diff = (a != b) & ~inside
            if diff.any():
                ys, xs = np.nonzero(diff)
                raise Finding(f"frame {frame}: {name} bank written outside viewport ∩ scrmask "
                              f"{box} at ({xs[0]}, {ys[0]}) ({int(diff.sum())} pixels)")
        z = after["z"]
        if z is not None and (z.min() < ZMIN or z.max() > ZMAX):
            raise Finding(f"frame {frame}: z value outside the 24-bit range: "
                          f"{int(z.min())}..{int(z.max())}")
        s = after["stencil"]
        if s is not None and int(s.max()) >= (1 << recipe["planes"]):
            raise Finding(f"frame {frame}: stencil value {int(s.max())} outside "
                          f"{recipe['planes']} planes")
        if recipe["cmode"]:
            for name in ("front", "back"):
                a = after[name]
                if a is not None and int(a.max()) >= 1 << 12:
                    raise Finding(f"frame {frame}: colour index {int(a.max())} beyond 12 planes")

    def _hash(self, banks):
        h = hashlib.sha1()
        for name in sorted(banks):
            a = banks[name]
            h.update(name.encode())
            if a is not None:
                h.update(np.ascontiguousarray(a).tobytes())
        return h.hexdigest()[:16]

    # -- one frame ---------------------------------------------------------
    def _window(self, recipe):
        gl, rng = self.gl, self.rng
        if self.machine.windows:
            gl.gexit()
        w, h = int(rng.integers(1, 97)), int(rng.integers(1, 97))
        gl.prefsize(w, h)
        gl.winopen("fuzz")
        gl.cmode() if recipe["cmode"] else gl.RGBmode()
        if recipe["double"]:
            gl.doublebuffer()
        if recipe["stencil"]:
            gl.stensize(recipe["planes"])
        gl.gconfig()
        return w, h

    def _rect(self, w, h):
        rng = self.rng
        x0 = int(rng.integers(-w // 2 - 1, w))
        y0 = int(rng.integers(-h // 2 - 1, h))
        return x0, x0 + int(rng.integers(0, w + 2)), y0, y0 + int(rng.integers(0, h + 2))

    def _state(self, recipe, w, h):
        gl, rng = self.gl, self.rng
        l, r, b, t = self._rect(w, h)
        gl.viewport(l, r, b, t)
        box = (max(l, 0), min(r, w - 1), max(b, 0), min(t, h - 1))
        if rng.random() < 0.6:
            sl, sr, sb, st = self._rect(w, h)
            gl.scrmask(sl, sr, sb, st)
            box = (max(box[0], sl), min(box[1], sr), max(box[2], sb), min(box[3], st))
        if box[0] > box[1] or box[2] > box[3]:
            box = None
        gl.mmode(gl.MVIEWING)
        m = rng.random()
        if m < 0.4:
            gl.perspective(int(rng.integers(100, 1700)), float(rng.uniform(0.3, 3)),
                           float(rng.uniform(0.01, 2)), float(rng.uniform(3, 100)))
            gl.loadmatrix(np.eye(4))
            gl.translate(0, 0, -float(rng.uniform(2, 6)))
            gl.rot(float(rng.uniform(0, 360)), "y")
        elif m < 0.8:
            gl.ortho(-2, 2, -2, 2, -2, 2)
        else:
            gl.mmode(gl.MSINGLE)
            gl.ortho(*(sorted(rng.normal(size=2) * 3) + sorted(rng.normal(size=2) * 3) +
                       [-float(rng.uniform(0.5, 5)), float(rng.uniform(0.5, 5))]))
        if recipe["ztest"]:
            gl.zbuffer(True)
            gl.zfunction(int(rng.integers(0, 8)))
            gl.zwritemask(0xFFFFFF if rng.random() < 0.8 else int(rng.integers(1, 1 << 24))
                          ) if recipe["zwrite"] else gl.zwritemask(0)
            if rng.random() < 0.3:
                zmin, zmax = gl.getgdesc(gl.GD_ZMIN), gl.getgdesc(gl.GD_ZMAX)
                gl.lsetdepth(*sorted(int(v) for v in rng.integers(zmin, zmax, 2)))
            gl.czclear(int(rng.integers(0, 1 << 32)) if not recipe["cmode"] else
                       int(rng.integers(0, 4096)), int(rng.integers(-(1 << 23), 1 << 23)))
        if recipe["stencil"]:
            ops = (lambda: 0) if recipe["stencil"] == 1 else (lambda: int(rng.integers(0, 6)))
            gl.stencil(True, int(rng.integers(0, 300)), int(rng.integers(0, 8)),
                       int(rng.integers(0, 256)), ops(), ops(), ops())
            gl.swritemask(int(rng.integers(0, 256)) if recipe["stencil"] == 2 else 0xFF)
            gl.sclear(int(rng.integers(0, 256)))
        if recipe["blend"] is not None:
            if recipe["blend"] == "generic":
                gl.blendfunction(int(rng.choice([0, 1, 2, 3, 4, 5, 6, 7, 8])),
                                 int(rng.choice([0, 1, 4, 5, 6, 7])))
            else:
                gl.blendfunction(*recipe["blend"])
        if recipe["logic"]:
            gl.logicop(int(rng.choice([o for o in range(16) if o != 3])))
        if recipe["atest"]:
            gl.afunction(int(rng.integers(0, 256)), int(rng.integers(0, 7)))
        if recipe["pattern"]:
            gl.defpattern(1, 16, [int(v) for v in rng.integers(0, 1 << 16, 16)])
            gl.setpattern(1)
        if recipe["cmask"]:
            if recipe["cmode"]:
                gl.writemask(int(rng.integers(0, 4096)))
            else:
                gl.wmpack(int(rng.integers(0, 1 << 32)))
        gl.shademodel(gl.GOURAUD if recipe["gouraud"] else gl.FLAT)
        if recipe["dual"]:
            gl.frontbuffer(True)
            gl.backbuffer(True)
        if recipe["light"]:
            gl.lmdef(gl.DEFMATERIAL, 1, 0, [gl.DIFFUSE] + [float(v) for v in rng.random(3)] +
                     [gl.SPECULAR, 0.5, 0.5, 0.5, gl.SHININESS, 20.0, gl.LMNULL])
            gl.lmdef(gl.DEFLIGHT, 1, 0, [gl.POSITION] + [_num(rng, 2, 0) for _ in range(3)] +
                     [float(rng.choice([0.0, 1.0])), gl.LMNULL])
            gl.lmdef(gl.DEFLMODEL, 1, 0, [gl.TWOSIDE, float(recipe["light"] == 2), gl.LMNULL])
            gl.lmbind(gl.MATERIAL, 1)
            gl.lmbind(gl.LIGHT0, 1)
            gl.lmbind(gl.LMODEL, 1)
        gl.linewidth(int(rng.choice([1, 1, 2, 3])))
        gl.pntsize(int(rng.choice([1, 1, 2, 4])))
        gl.subpixel(bool(rng.random() < 0.5))
        return box

    def _colour(self, recipe, special):
        gl, rng = self.gl, self.rng
        if recipe["cmode"]:
            gl.color(int(rng.integers(0, 4096)))
        elif rng.random() < 0.5:
            gl.c4f([_num(rng, 0.5, special) + 0.5 for _ in range(4)])
        else:
            gl.cpack(int(rng.integers(0, 1 << 32)))

    def _primitive(self, recipe, w, h, special):
        gl, rng = self.gl, self.rng
        k = int(rng.integers(0, 15))
        kinds = ((gl.bgnpoint, gl.endpoint, 1, 6), (gl.bgnline, gl.endline, 2, 6),
                 (gl.bgnclosedline, gl.endclosedline, 2, 6),
                 (gl.bgnpolygon, gl.endpolygon, 3, 8), (gl.bgntmesh, gl.endtmesh, 3, 10),
                 (gl.bgnqstrip, gl.endqstrip, 4, 10))
        self.stats[KIND_NAMES[k]] += 1
        if k < 6 or k in (12, 13):
            bgn, end, lo, hi = kinds[k % 6] if k < 6 else kinds[3 + (k - 12)]
            n = int(rng.integers(lo, hi + 1))
            pts = _points(rng, n, special)
            bgn()
            for i, p in enumerate(pts):
                if rng.random() < 0.5:
                    self._colour(recipe, special)
                if recipe["light"] and rng.random() < 0.7:
                    gl.n3f([_num(rng, 1, special) for _ in range(3)])
                if k == 4 and i > 2 and rng.random() < 0.2:
                    gl.swaptmesh()
                v = rng.random()
                if v < 0.2:
                    gl.v2f(p[:2])
                elif v < 0.6:
                    gl.v3f(p[:3])
                else:
                    gl.v4f(p)
            end()
            self.stats["vertices"] += n
        elif k == 6:
            gl.rectf(*(_num(rng, 2, special) for _ in range(4)))
        elif k == 7:
            gl.circf(_num(rng, 1, special), _num(rng, 1, special), abs(_num(rng, 1, special)))
        elif k == 8:
            gl.move(*(_num(rng, 1.5, special) for _ in range(3)))
            gl.draw(*(_num(rng, 1.5, special) for _ in range(3)))
        elif k == 9:
            pts = [p[:3] for p in _points(rng, int(rng.integers(3, 7)), special)]
            gl.polf(len(pts), pts)
        elif k == 10:
            gl.pnt(*(_num(rng, 1.5, special) for _ in range(3)))
        elif k == 11:
            x0, y0 = int(rng.integers(-5, w + 5)), int(rng.integers(-5, h + 5))
            x1, y1 = x0 + int(rng.integers(0, 12)), y0 + int(rng.integers(0, 12))
            words = rng.integers(0, 1 << 32, (y1 - y0 + 1) * (x1 - x0 + 1), dtype=np.uint64)
            if recipe["cmode"]:
                words %= 4096
            if rng.random() < 0.2:
                gl.rectzoom(float(rng.choice([0.5, 1, 2, 3])), float(rng.choice([0.5, 1, 2])))
            gl.lrectwrite(x0, y0, x1, y1, words.astype(np.uint32))
            gl.rectzoom(1, 1)
        else:
            x0, y0 = int(rng.integers(-5, w + 5)), int(rng.integers(-5, h + 5))
            gl.rectcopy(x0, y0, x0 + int(rng.integers(0, 10)), y0 + int(rng.integers(0, 10)),
                        int(rng.integers(-5, w + 5)), int(rng.integers(-5, h + 5)))

    def _frame(self, frame, n):
        gl, rng = self.gl, self.rng
        recipe = self.recipes[int(rng.integers(len(self.recipes)))]
        w, h = self._window(recipe)
        box = self._state(recipe, w, h)
        before = self._banks()
        special = float(rng.choice([0.0, 0.01, 0.05, 0.3]))
        for _ in range(n):
            try:
                self._primitive(recipe, w, h, special)
            except self.gl.GLError as e:
                self.stats["GLError " + str(e).split(";")[0]] += 1
            if rng.random() < 0.02:
                gl.clear()
            if rng.random() < 0.05:
                gl.gflush()
        gl.gflush()
        after = self._banks()
        self._check(before, after, box, recipe, frame)
        self.hashes.append(self._hash(after))

    def run(self):
        from .errors import VGXWarning
        drawn = frame = 0
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            while drawn < self.count:
                n = min(int(self.rng.integers(1, MAX_PRIMS_PER_FRAME + 1)), self.count - drawn)
                try:
                    self._frame(frame, n)
                except Finding as e:
                    self.findings.append(str(e))
                except Exception:
                    self.findings.append(f"frame {frame}: " + traceback.format_exc(limit=-6))
                drawn += n
                frame += 1
                for wmsg in caught:
                    if issubclass(wmsg.category, VGXWarning):
                        name = str(wmsg.message).split(":")[0]
                        if not all(p in self.api or p in ("v*", "n3f", "c*", "t*")
                                   for p in name.split("/")):
                            self.findings.append(f"frame {frame}: VGXWarning naming no call: "
                                                 f"{wmsg.message}")
                        self.stats["vgxwarnings"] += 1
                    else:
                        self.findings.append(f"frame {frame}: {wmsg.category.__name__} reached "
                                             f"the user: {wmsg.message} ({wmsg.filename}:"
                                             f"{wmsg.lineno})")
                caught.clear()
                if len(self.findings) > 20:
                    break
        return dict(primitives=drawn, frames=frame, seconds=round(time.perf_counter() - t0, 2),
                    hashes=self.hashes, findings=self.findings, stats=dict(self.stats))


# ----------------------------------------------------------------------------
# misuse worker
GARBAGE = (None, object(), 1j, {})
BAD_VALUES = GARBAGE + ("abc", float("nan"), float("inf"), -float("inf"), 2 ** 70, -2 ** 70,
                        1e38, 10 ** 6, -1, 9999, [], [float("nan")] * 3, np.zeros(2),
                        np.zeros(3, np.complex128), ["a", "b", "c", "d"])
QUICK_VALUES = (None, object(), "abc", float("nan"), 2 ** 70, -1, 9999, [])

#: argument names that take any Python object or a string (garbage accepted
#: there is not a finding): callbacks and their arguments, strings, zclear's
#: one tolerated extra argument, and ``params`` that the mode given does not
#: read (clipplane CP_ON/CP_OFF, fogvertex FG_ON/FG_OFF, scrsubdivide: C
#: passes a pointer the call never follows)
TAKES_OBJECTS = {"fctn", "func", "arg", "args", "str", "string", "name", "text", "chars",
                 "ignored", "kwargs", "params"}
#: queries whose man page answers -1 for an invalid argument, whatever it is
ANSWER_MINUS_ONE = {"getgdesc", "getvideo", "scrnselect", "scrnattach"}
_ARRAYS = {"v", "parray", "iarray", "props", "m", "points", "ctlarray", "knot_list",
           "data_array", "narray", "colors", "image", "raster", "chars", "vobj",
           "sknot", "tknot", "buffer", "mask", "idata", "odata", "devs", "vals", "params"}


def _neutral(p):
    """An argument likely to be accepted for parameter ``p``: its default,
    a short array for array names, a string for string names, else 1."""
    from irisgl._current import NOT_GIVEN
    if p.default is not p.empty and p.default is not NOT_GIVEN:
        return p.default
    if p.name in ("name", "str", "string", "text"):
        return "x"
    if p.name in _ARRAYS:
        return [0.0] * 16
    return 1


def fingerprint(obj):
    """A hash of everything reachable from ``obj`` (the machine): numbers,
    strings, arrays, containers and object attributes, functions by name;
    after the queued raster work (pipeline.py: the attributes are read
    directly, not through the banks' waiting accessors)."""
    from . import pipeline
    pipeline.sync()
    h = hashlib.sha1()
    seen, keep = set(), []

    def fp(x, depth):
        t = type(x)
        if x is None or t in (bool, int, float, str, bytes, complex):
            h.update(repr(x).encode())
            return
        if isinstance(x, np.ndarray):
            h.update(repr((x.dtype.str, x.shape)).encode())
            h.update(np.ascontiguousarray(x).tobytes())
            return
        if isinstance(x, np.generic):
            h.update(repr(x).encode())
            return
        if depth > 10 or id(x) in seen:
            h.update(b"@")
            return
        seen.add(id(x))
        keep.append(x)              # no id of a temporary is reused while hashing
        if isinstance(x, dict):
            for k in sorted(x, key=repr):
                fp(k, depth + 1)
                fp(x[k], depth + 1)
        elif isinstance(x, (list, tuple)) or type(x).__name__ == "deque":
            h.update(f"[{len(x)}".encode())
            for v in x:
                fp(v, depth + 1)
        elif isinstance(x, (set, frozenset)):
            for v in sorted(x, key=repr):
                fp(v, depth + 1)
        elif inspect.isroutine(x) or inspect.isclass(x):
            h.update(getattr(x, "__qualname__", repr(type(x))).encode())
        elif hasattr(x, "__dict__") or hasattr(x, "__slots__"):
            h.update(type(x).__name__.encode())
            d = dict(getattr(x, "__dict__", {}))
            for s in getattr(type(x), "__slots__", ()):
                if hasattr(x, s):
                    d[s] = getattr(x, s)
            keep.append(d)
            fp(d, depth + 1)
        else:
            h.update(type(x).__name__.encode())
    fp(obj, 0)
    return h.hexdigest()


#: the calls legal inside bgn*/end*, tried there too (their fast path)
INSIDE_BGN = re.compile(r"^(v[234][sifd]|n3f|c[34][sif]|cpack|RGBcolor|color|t[234][sifd])$")


class Misuser:
    """Every public call given wrong arguments (module docstring)."""

    def __init__(self, quick, only=None):
        import irisgl as gl
        from irisgl._current import API, NOT_EMULATED, machine
        self.gl, self.machine = gl, machine
        self.values = QUICK_VALUES if quick else BAD_VALUES
        self.calls = sorted(n for n in API if (only is None or n in only))
        self.not_emulated = {n for n, (s, _) in API.items() if s == NOT_EMULATED}
        self.findings = []
        self.table = {}

    def _scene(self, inside=False):
        """The neutral state of a trial: a window with a z-buffer, stencil and
        double buffer; ``inside``: with a bgnline open and a vertex sent (the
        per-vertex calls' fast path runs only there)."""
        gl, m = self.gl, self.machine
        m.reset()
        gl.prefsize(16, 12)
        gl.winopen("misuse")
        gl.RGBmode()
        gl.doublebuffer()
        gl.stensize(8)
        gl.gconfig()
        gl.zbuffer(True)
        gl.mmode(gl.MVIEWING)
        gl.ortho(-1, 1, -1, 1, -1, 1)
        gl.cpack(0xFF204060)
        gl.clear()
        gl.frontbuffer(True)
        # state created with its defaults on first use: made now, so that a
        # refused call creating it is not taken for a change
        from irisgl import cursor, curves, nurbs
        cursor._cursor()
        curves._state()
        nurbs._state(m.current)
        if inside:
            gl.bgnline()
            gl.v2f((0.0, 0.0))

    def _probe(self):
        """After an accepted trial: the state it left must still draw."""
        gl = self.gl
        gl.gflush()
        if self.machine.current is None or self.machine.recording is not None or \
                self.machine.current.batch.open is not None:
            return
        gl.rectf(-0.5, -0.5, 0.5, 0.5)
        gl.move(-1, -1, 0)
        gl.draw(1, 1, 0)
        gl.pnt(0, 0, 0)
        gl.gflush()

    def _trials(self, name, f):
        target = getattr(f, "__wrapped__", f)
        try:
            params = [p for p in inspect.signature(target).parameters.values()]
        except (TypeError, ValueError):
            params = []
        fixed = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
        # ``*more`` of the explicit per-vertex calls only catches a wrong
        # arity: such a call takes exactly its fixed parameters, which must
        # all be given (their default is NOT_GIVEN)
        from irisgl._current import NOT_GIVEN
        var = any(p.kind == p.VAR_POSITIONAL and p.name != "more" for p in params)
        base = [_neutral(p) for p in fixed]
        if INSIDE_BGN.match(name) and name[1].isdigit():     # v3f(v): a vector of 3
            base = [[0.5] * int(name[1]) if isinstance(b, list) else b for b in base]
        required = sum(p.default is p.empty or p.default is NOT_GIVEN for p in fixed)
        trials = []
        if not var:
            trials.append(("arity", base + [1]))
            if required:
                trials.append(("arity", base[:required - 1]))
        if var and not fixed:
            vname = next(p.name for p in params if p.kind == p.VAR_POSITIONAL)
            for n in range(0, 5):
                for v in self.values:
                    trials.append((f"{vname}[{n}]", [1] * n + [v]))
            return trials
        for i, p in enumerate(fixed):
            for v in self.values:
                args = list(base)
                args[i] = v
                trials.append((p.name, args))
        return trials

    def run(self):
        from .errors import GLError
        gl = self.gl
        t0 = time.perf_counter()
        totals = Counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")           # VGXWarnings of accepted trials
            for name in self.calls:
                f = getattr(gl, name)
                trials = self._trials(name, f)
                row = Counter()
                for inside in ((False, True) if INSIDE_BGN.match(name) else (False,)):
                    self._scene(inside)
                    for where, args in trials:
                        tag = "inside bgnline: " + where if inside else where
                        before = fingerprint(self.machine)
                        outcome = "accepted"
                        try:
                            signal.alarm(20)
                            f(*args)
                        except GLError as e:
                            outcome = "refused"
                            if not str(e).startswith(name + ":"):
                                self._find(name, tag, args,
                                           f"GLError not naming the call: {e}")
                            elif fingerprint(self.machine) != before:
                                self._find(name, tag, args,
                                           f"GLError, but the state changed: {e}")
                                outcome = "changed"
                        except SystemExit:
                            outcome = "exit"      # qread on an empty queue (QueueExhausted)
                        except BaseException as e:
                            outcome = "crash"
                            self._find(name, tag, args,
                                       f"{type(e).__name__}: {e} "
                                       f"{traceback.format_exc(limit=-2).splitlines()[-3:]}")
                        finally:
                            signal.alarm(0)
                        if outcome == "accepted":
                            if where == "arity":
                                self._find(name, tag, args,
                                           "wrong number of arguments accepted")
                            elif any(a is g for a in args for g in GARBAGE[1:3]) and \
                                    where.split("[")[0] not in TAKES_OBJECTS and \
                                    name not in ANSWER_MINUS_ONE:
                                self._find(name, tag, args, "garbage argument accepted")
                            try:
                                signal.alarm(20)
                                self._probe()
                            except GLError:
                                pass
                            except BaseException as e:
                                outcome = "crash"
                                self._find(name, tag, args, f"drawing after it: "
                                           f"{type(e).__name__}: {e}")
                            finally:
                                signal.alarm(0)
                        if outcome != "refused":
                            self._scene(inside)
                        row[outcome] += 1
                self.table[name] = dict(row)
                totals.update(row)
        return dict(calls=len(self.calls), trials=sum(totals.values()), outcomes=dict(totals),
                    seconds=round(time.perf_counter() - t0, 2), findings=self.findings,
                    table=self.table)

    def _find(self, name, where, args, what):
        if len(self.findings) < 500:
            shown = ", ".join(_show(a) for a in args)
            self.findings.append(f"{name}({shown}) [{where}]: {what}")


def _show(a):
    r = repr(a) if not isinstance(a, np.ndarray) else f"np.{a.dtype}{list(a.shape)}"
    return r if len(r) < 40 else r[:37] + "..."


def _alarm(signum, frame):
    raise TimeoutError("trial hung for 20 s")


# ----------------------------------------------------------------------------
# the parent: batches in subprocesses
def _worker_cmd(kind, seed, index, count, states, threads, quick=False):
    cmd = [sys.executable, "-m", "vgx_emulator.fuzz", "--worker", kind, "--seed", str(seed),
           "--index", str(index), "--count", str(count), "--states", str(states),
           "--threads", str(threads)]
    return cmd + (["--quick"] if quick else [])


def _run_worker(cmd, timeout, threads, general=None):
    env = dict(os.environ, NUMBA_NUM_THREADS=str(max(threads, 2)))
    if general is not None:
        env["VGX_GENERAL"] = general
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return dict(error=f"hung: no answer after {timeout} s", command=" ".join(cmd[1:]))
    wall = time.perf_counter() - t0
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith("{")]
    if r.returncode != 0 or not lines:
        return dict(error=f"crashed (exit {r.returncode}): {r.stderr[-1500:]}",
                    command=" ".join(cmd[1:]))
    out = json.loads(lines[-1])
    out["wall"] = round(wall, 2)
    return out


def run(seed, primitives, batch, states, jobs, recheck_every, timeout, misuse, log=None):
    """Run the fuzz (module docstring); returns the summary dict."""
    nb = max(1, math.ceil(primitives / batch))
    summary = dict(seed=seed, primitives=0, frames=0, batches=nb, batch=batch, states=states,
                   findings=[], rechecked=0, stats=Counter(), started=time.strftime("%F %T"))
    t0 = time.perf_counter()

    def one(k):
        count = min(batch, primitives - k * batch)
        res = _run_worker(_worker_cmd("draw", seed, k, count, states, 2), timeout, 2)
        res["index"] = k
        if "error" not in res and recheck_every and k % recheck_every == 0:
            for threads, general in ((1, None), (2, None), (2, "always")):
                again = _run_worker(_worker_cmd("draw", seed, k, count, states, threads),
                                    timeout, threads, general)
                if "error" in again:
                    res.setdefault("recheck_errors", []).append(again)
                elif again["hashes"] != res["hashes"]:
                    bad = next(i for i, (a, b) in enumerate(zip(again["hashes"], res["hashes"]))
                               if a != b) if len(again["hashes"]) == len(res["hashes"]) else -1
                    other = (f"{threads} thread(s)" if general is None else
                             "the general kernel variants (VGX_GENERAL=always)")
                    res["findings"].append(
                        f"banks differ between a run on 2 threads and a run on {other} "
                        f"at frame {bad}")
            res["rechecked"] = True
        return res

    with ThreadPoolExecutor(max_workers=jobs) as pool:
        for res in pool.map(one, range(nb)):
            k = res["index"]
            repro = (f"python -m vgx_emulator.fuzz --worker draw --seed {seed} --index {k} "
                     f"--count {min(batch, primitives - k * batch)} --states {states} "
                     f"--threads 2")
            if "error" in res:
                summary["findings"].append(dict(batch=k, finding=res["error"], repro=repro))
            else:
                summary["primitives"] += res["primitives"]
                summary["frames"] += res["frames"]
                summary["stats"].update(res["stats"])
                summary["rechecked"] += bool(res.get("rechecked"))
                for f in res["findings"]:
                    summary["findings"].append(dict(batch=k, finding=f, repro=repro))
                    if log:
                        print(f"  batch {k}: {f[:400]}", file=log, flush=True)
                for e in res.get("recheck_errors", ()):
                    summary["findings"].append(dict(batch=k, finding=e["error"], repro=repro))
            if log:
                done = summary["primitives"]
                print(f"batch {k + 1}/{nb}: {done} primitives, "
                      f"{len(summary['findings'])} findings, "
                      f"{time.perf_counter() - t0:.0f} s", file=log, flush=True)
    if misuse:
        res = _run_worker(_worker_cmd("misuse", seed, 0, 0, states, 1, quick=misuse == "quick"),
                          max(timeout, 1800), 1)
        if "error" in res:
            summary["findings"].append(dict(batch="misuse", finding=res["error"]))
        else:
            summary["misuse"] = {k: res[k] for k in ("calls", "trials", "outcomes", "seconds",
                                                     "table")}
            summary["findings"] += [dict(batch="misuse", finding=f) for f in res["findings"]]
    summary["seconds"] = round(time.perf_counter() - t0, 1)
    summary["stats"] = dict(summary["stats"])
    return summary


def markdown(summary):
    """The figures of a summary as Markdown (docs/reliability.md): the
    drawing run, then one row per call of its misuse trials."""
    s = summary
    st = s["stats"]
    kinds = ", ".join(f"{k} {v}" for k, v in sorted(st.items())
                      if k in KIND_NAMES)
    errs = "; ".join(f"{k[8:]}: {v}" for k, v in sorted(st.items()) if k.startswith("GLError"))
    lines = [f"- seed {s['seed']}: {s['primitives']} primitives in {s['frames']} frames, "
             f"{s['batches']} batches of {s['batch']} (a subprocess each), {s['states']} "
             f"raster-state recipes, {s['rechecked']} batches run again on 1 and on 2 threads "
             f"and on the general kernel variants; "
             f"{s['seconds']:.0f} s",
             f"- {st.get('vertices', 0)} vertices in bgn/end primitives; by kind: {kinds}",
             f"- {st.get('vgxwarnings', 0)} VGXWarnings (dropped non-finite primitives, each "
             f"naming its calls); GLErrors while drawing: {errs or 'none'}",
             f"- findings: {len(s['findings'])}"]
    for f in s["findings"][:20]:
        lines.append(f"  - batch {f['batch']}: {f['finding'][:300]}")
    m = s.get("misuse")
    if m:
        o = m["outcomes"]
        lines += ["", f"Misuse: {m['calls']} calls, {m['trials']} trials: " +
                  ", ".join(f"{v} {k}" for k, v in sorted(o.items())) + f"; {m['seconds']:.0f} s.",
                  "", "| call | trials | refused (GLError, state unchanged) | accepted | other |",
                  "|---|---|---|---|---|"]
        for name, row in sorted(m["table"].items()):
            n = sum(row.values())
            other = ", ".join(f"{k} {v}" for k, v in sorted(row.items())
                              if k not in ("refused", "accepted"))
            lines.append(f"| `{name}` | {n} | {row.get('refused', 0)} | "
                         f"{row.get('accepted', 0)} | {other} |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m vgx_emulator.fuzz", description=__doc__.split(
        "\n\n")[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--primitives", type=int, default=20000)
    ap.add_argument("--batch", type=int, default=20000,
                    help="primitives per subprocess (default 20000)")
    ap.add_argument("--states", type=int, default=16,
                    help="raster-state recipes drawn from (default 16)")
    ap.add_argument("--jobs", type=int, default=1, help="batches run at once (default 1)")
    ap.add_argument("--recheck-every", type=int, default=10,
                    help="every K-th batch is run again on 1 and on 2 threads and on the "
                         "general kernel variants (0: never)")
    ap.add_argument("--timeout", type=int, default=1200, help="seconds before a batch hangs")
    ap.add_argument("--misuse", choices=("quick", "full"), default=None,
                    help="also give every call wrong arguments")
    ap.add_argument("--json", help="write the summary there")
    ap.add_argument("--markdown", metavar="SUMMARY_JSON",
                    help="print the figures of a summary written by --json as Markdown")
    ap.add_argument("--worker", choices=("draw", "misuse"), help=argparse.SUPPRESS)
    ap.add_argument("--index", type=int, default=0, help=argparse.SUPPRESS)
    ap.add_argument("--count", type=int, default=0, help=argparse.SUPPRESS)
    ap.add_argument("--threads", type=int, default=2, help=argparse.SUPPRESS)
    ap.add_argument("--quick", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--only", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.markdown:
        with open(a.markdown) as fh:
            print(markdown(json.load(fh)), end="")
        return 0
    if a.worker == "draw":
        print(json.dumps(Drawer(a.seed, a.index, a.count, a.states, a.threads).run()))
        return 0
    if a.worker == "misuse":
        signal.signal(signal.SIGALRM, _alarm)
        only = set(a.only.split(",")) if a.only else None
        print(json.dumps(Misuser(a.quick, only).run()))
        return 0
    s = run(a.seed, a.primitives, a.batch, a.states, a.jobs, a.recheck_every, a.timeout,
            a.misuse, log=sys.stderr)
    text = json.dumps(s, indent=1)
    if a.json:
        with open(a.json, "w") as fh:
            fh.write(text)
    brief = {k: v for k, v in s.items() if k != "misuse"}
    if "misuse" in s:
        brief["misuse"] = {k: v for k, v in s["misuse"].items() if k != "table"}
    print(json.dumps(brief, indent=1))
    return 1 if s["findings"] else 0


if __name__ == "__main__":
    sys.exit(main())
