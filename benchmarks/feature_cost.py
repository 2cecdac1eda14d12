"""Feature cost: what each pipeline feature costs a realistic scene when it is
used, when it is configured but disabled, and when it is absent (shadow
study, section 3: "leave out what a scene does not need"); prints markdown.

The scene is benchmarks/vs_mesa.py's ``spheres``: four_spheres' four lit,
Gouraud-shaded spheres (32 x 16 quad strips) on a 24 x 24 quad ground, 5248
triangles, in an IRIS GL object, z-buffered, double-buffered, 1280x1024.
Each frame clears, draws the object and ends with swapbuffers() (which draws
everything queued).  Per feature, three windows of one machine:

  uses it       the feature on and doing work;
  configured,   the bank or definition exists, the state turns it off;
  disabled
  absent        the window never configured it.

==========  ========================  ==============================  ==============
feature     uses it                   configured, disabled            absent
==========  ========================  ==============================  ==============
z           zbuffer(TRUE), czclear    bank made, zbuffer(FALSE),      no z bank,
                                      clear()                         clear()
stencil     stensize(8), ST_REPLACE   stensize(8), stencil(FALSE..)   no stensize
            on z-pass, sclear(0)
blend       blendfunction(BF_SA,      set, then (BF_ONE, BF_ZERO)     never called
            BF_MSA)
pattern     16x16 halftone            defpattern, setpattern(0)       none bound
lighting    lmbind MATERIAL, LMODEL,  same binds, lmbind(MATERIAL,0)  no lmbind
            LIGHT0 (object: cpack,
            n3f, v3f)
texture     texdef2d 64x64 RGBA,      defined, tevbind'd, texbind(0)  none bound
            tevdef MODULATE, binds
            (object with t2f)
accum       acsize(16), acbuf(        acsize(16), no acbuf            no acsize
            AC_ACCUMULATE) per frame
shading     GOURAUD                   (FLAT is the off state)         FLAT
==========  ========================  ==============================  ==============

The same object (and so the same normals and texture coordinates) is drawn
in the three windows of a row; definitions (lmdef, texdef2d, defpattern)
are global to the machine as in IRIS GL, so "absent" means the window never
binds or configures the feature.  A control row draws the base scene in
three identical windows: its "overheads" are the noise floor of the run.

Timing: two untimed frames per window (the first compiles or loads the
kernels), then rounds in which each window draws one timed frame (winset
untimed, gc.collect() between frames, the order rotated each round).
Reported: the median (and minimum) frame time, and the overhead of a column
over "absent" as the median (and interquartile range) of the per-round
ratios of frames taken side by side, and as the ratio of the minima: on a
shared machine that pairing, not the difference of two medians, is what
keeps the number honest.  One numba thread by default (--threads 0 keeps
numba's default): with two threads on a shared two-core machine the banded
walker waits for whichever core is taken, and paired ratios swung by +-20 %.
The last column says whether the disabled window runs the same kernel
variant (machine._raster_setup's RasterKey) and the same geometry stages
(texturing, lighting_active) as the absent one: a structural check beside
the timing.

Also: (b) work the scene does not need (vertex data sent but unused, Gouraud
over constant colours); (c) a light's view of the scene at 1024x1024: the
full lit pass against depth-only passes (wmpack(0)); (d) memory of a
1280x1024 window with and without each bank: the banks' bytes read from the
machine (``machine().current.fb``) and the RSS delta of a fresh process
after the window is opened and configured, and after a first frame that
uses the bank.

Usage: python benchmarks/feature_cost.py [--quick] [--rounds N] [--threads N]
           [--sections abcd]
"""
import os
import sys


sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # benchmarks/: threads.py
from threads import early_threads  # noqa: E402


if __name__ == "__main__":
    _threads = early_threads(sys.argv[1:])
    if _threads is None and "NUMBA_NUM_THREADS" not in os.environ:
        _threads = "1"
    if _threads not in (None, "0"):
        os.environ["NUMBA_NUM_THREADS"] = _threads

import argparse  # noqa: E402
import gc  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import statistics  # noqa: E402
import subprocess  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
for _p in (str(ROOT), str(ROOT / "benchmarks")):
    if _p not in sys.path:
        sys.path.insert(0, _p)

from irisgl import (AC_ACCUMULATE, AC_CLEAR, BF_MSA, BF_ONE, BF_SA, BF_ZERO,  # noqa: E402
                    DEFLIGHT, DEFMATERIAL, FALSE, FLAT, GD_ZMAX, LIGHT0, LMNULL, LMODEL,
                    MATERIAL, MVIEWING, POSITION, SF_ALWAYS, ST_KEEP, ST_REPLACE, TRUE,
                    TV_ENV0, TV_MODULATE, TV_NULL, TX_NULL, TX_TEXTURE_0, AMBIENT, DIFFUSE,
                    SPECULAR, RGBmode, acbuf, acsize, bgnqstrip, blendfunction, callobj,
                    clear, closeobj, cpack, czclear, defpattern, doublebuffer, endqstrip,
                    gconfig, genobj, getgdesc, lmbind, lmdef, lookat, makeobj, mmode, n3f,
                    perspective, popmatrix, prefsize, pushmatrix, sclear, setpattern,
                    shademodel, stencil, stensize, swapbuffers, t2f, tevbind, tevdef,
                    texbind, texdef2d, v3f, winopen, winset, wmpack, zbuffer, zclear)

import programs.four_spheres as fs  # noqa: E402
import vgx_emulator  # noqa: E402
from vs_mesa import (GROUND_MAT, light_frustum, spheres_light, spheres_scene,  # noqa: E402
                     spheres_view)

W, H = 1280, 1024
LIGHT_SIZE = 1024
LIGHT_DISTANCE = 15.0          # the light's eye, along the sun's direction from the origin
PATTERN = 1
TEXTURE = ENV = 1
TEXTURE_SIZE = 64
PART_COLOURS = [0xFF4C8C5A, 0xFF3040C0, 0xFF30A0D0, 0xFFC06030, 0xFF9050A0]   # 0xAABBGGRR


# ======================================================================================
# 1. the machine, the definitions, the objects
# ======================================================================================
def _machine():
    return vgx_emulator.machine()


def fresh_machine():
    """Power-on state, then the scene's definitions (global, as in IRIS GL):
    four_spheres' material, light and model, the sun raised 40 degrees, the
    ground material, a halftone pattern, a checker texture and a MODULATE
    environment."""
    _machine().reset()
    gc.collect()
    fs.define_lighting()
    lmdef(DEFLIGHT, fs.SUN, 0, [POSITION] + spheres_light() + [LMNULL])
    lmdef(DEFMATERIAL, GROUND_MAT, 0, [AMBIENT, 0.15, 0.15, 0.15, DIFFUSE, 0.55, 0.6, 0.5,
                                       SPECULAR, 0.0, 0.0, 0.0, LMNULL])


def define_pattern():
    """A 50 % halftone (alternate pixels): defpattern(3G), 16x16."""
    defpattern(PATTERN, 16, [0xAAAA, 0x5555] * 8)


def define_texture():
    """A 64x64 RGBA checker (8-texel squares) and a TV_MODULATE environment."""
    i = np.arange(TEXTURE_SIZE)
    on = ((i[:, None] // 8 + i[None, :] // 8) % 2).astype(bool)
    img = np.where(on[..., None], [255, 255, 255, 255], [90, 90, 200, 255]).astype(np.uint8)
    texdef2d(TEXTURE, 4, TEXTURE_SIZE, TEXTURE_SIZE, img, 0, [TX_NULL])
    tevdef(ENV, 0, [TV_MODULATE, TV_NULL])


def texcoords(pos, nrm, ground):
    """(S, V, 2) texture coordinates: the ground repeats the checker every 2
    units; a sphere gets longitude/latitude from its normals."""
    if ground:
        return np.stack((pos[..., 0] / 2.0, pos[..., 2] / 2.0), -1)
    s = np.arctan2(-nrm[..., 2], nrm[..., 0]) / (2 * math.pi) + 0.5
    t = np.arcsin(np.clip(nrm[..., 1], -1.0, 1.0)) / math.pi + 0.5
    return np.stack((4.0 * s, 2.0 * t), -1)


def scene_object(materials=True, normals=True, colours=False, tex=False):
    """The spheres scene as one object: per part lmbind(MATERIAL) and/or a
    cpack, then quad strips with n3f / t2f as asked before each v3f."""
    obj = genobj()
    makeobj(obj)
    for k, (mat, pos, nrm) in enumerate(spheres_scene()):
        if materials:
            lmbind(MATERIAL, mat)
        if colours:
            cpack(PART_COLOURS[k])
        tc = texcoords(pos, nrm, mat == GROUND_MAT)
        for ps, ns, ts in zip(pos.tolist(), nrm.tolist(), tc.tolist()):
            bgnqstrip()
            for p, n, t in zip(ps, ns, ts):
                if normals:
                    n3f(n)
                if tex:
                    t2f(t)
                v3f(p)
            endqstrip()
    closeobj()
    return obj


# ======================================================================================
# 2. windows and frames
# ======================================================================================
def open_window(w=W, h=H, double=True, stencil_planes=0, accum=False):
    """winopen + RGBmode (+ doublebuffer, stensize, acsize) + gconfig, and
    four_spheres' perspective; returns the gid."""
    prefsize(w, h)
    gid = winopen("feature_cost")
    RGBmode()
    if double:
        doublebuffer()
    if stencil_planes:
        stensize(stencil_planes)
    if accum:
        acsize(16)
    gconfig()
    mmode(MVIEWING)
    perspective(400, w / h, 1.0, 50.0)
    return gid


def clear_cz():
    czclear(0x00000000, getgdesc(GD_ZMAX))


def clear_c():
    cpack(0x00000000)
    clear()


def scene_frame(obj, clr=clear_cz, light=True, after=None, view=spheres_view):
    """One frame: clear, the view, the sun (lmbind(LIGHT0), placed in the
    world), the object, after(), swapbuffers()."""
    def frame():
        clr()
        pushmatrix()
        view()
        if light:
            lmbind(LIGHT0, fs.SUN)
        callobj(obj)
        popmatrix()
        if after is not None:
            after()
        swapbuffers()
    return frame


def lit_window(**cfg):
    """The base window: z-buffer on, the light model bound (the object binds
    the materials, the frame the sun)."""
    gid = open_window(**cfg)
    zbuffer(TRUE)
    lmbind(LMODEL, fs.MODEL)
    return gid


# ======================================================================================
# 3. the columns of each feature: (objects) -> (gid, frame)
# ======================================================================================
def z_uses(o):
    return lit_window(), scene_frame(o["lit"])


def z_disabled(o):
    gid = open_window()
    zbuffer(TRUE)              # makes the z bank (framebuffer.ensure_z) ...
    zbuffer(FALSE)             # ... and turns the test off
    lmbind(LMODEL, fs.MODEL)
    return gid, scene_frame(o["lit"], clear_c)


def z_absent(o):
    gid = open_window()
    lmbind(LMODEL, fs.MODEL)
    return gid, scene_frame(o["lit"], clear_c)


def stencil_uses(o):
    gid = lit_window(stencil_planes=8)
    stencil(TRUE, 1, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_REPLACE)

    def clr():
        clear_cz()
        sclear(0)
    return gid, scene_frame(o["lit"], clr)


def stencil_disabled(o):
    gid = lit_window(stencil_planes=8)
    stencil(FALSE, 1, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_REPLACE)
    return gid, scene_frame(o["lit"])


def base(o):
    """The base scene: nothing beyond z and lighting (the "absent" column of
    the rows whose feature the base scene lacks)."""
    return lit_window(), scene_frame(o["lit"])


def blend_uses(o):
    gid = lit_window()
    blendfunction(BF_SA, BF_MSA)
    return gid, scene_frame(o["lit"])


def blend_disabled(o):
    gid = lit_window()
    blendfunction(BF_SA, BF_MSA)
    blendfunction(BF_ONE, BF_ZERO)
    return gid, scene_frame(o["lit"])


def pattern_uses(o):
    gid = lit_window()
    setpattern(PATTERN)
    return gid, scene_frame(o["lit"])


def pattern_disabled(o):
    gid = lit_window()
    setpattern(PATTERN)
    setpattern(0)
    return gid, scene_frame(o["lit"])


def lighting_uses(o):
    gid = lit_window()
    lmbind(MATERIAL, fs.SPHERE_MAT)
    return gid, scene_frame(o["colour"])


def lighting_disabled(o):
    gid = lit_window()
    lmbind(MATERIAL, fs.SPHERE_MAT)
    lmbind(MATERIAL, 0)        # lmbind(3G): no material, no lighting
    return gid, scene_frame(o["colour"])


def lighting_absent(o):
    gid = open_window()
    zbuffer(TRUE)
    return gid, scene_frame(o["colour"], light=False)


def texture_uses(o):
    gid = lit_window()
    tevbind(TV_ENV0, ENV)
    texbind(TX_TEXTURE_0, TEXTURE)
    return gid, scene_frame(o["lit_tex"])


def texture_disabled(o):
    gid = lit_window()
    tevbind(TV_ENV0, ENV)
    texbind(TX_TEXTURE_0, TEXTURE)
    texbind(TX_TEXTURE_0, 0)
    return gid, scene_frame(o["lit_tex"])


def texture_absent(o):
    return lit_window(), scene_frame(o["lit_tex"])


def accum_uses(o):
    return lit_window(accum=True), scene_frame(o["lit"],
                                               after=lambda: acbuf(AC_ACCUMULATE, 1.0))


def accum_disabled(o):
    return lit_window(accum=True), scene_frame(o["lit"])


def flat_lit(o):
    gid = lit_window()
    shademodel(FLAT)
    return gid, scene_frame(o["lit"])


#: (feature, uses it, configured-disabled, absent, objects it needs)
FEATURES = [
    ("control: three identical base windows", base, base, base, ("lit",)),
    ("z-buffer", z_uses, z_disabled, z_absent, ("lit",)),
    ("stencil", stencil_uses, stencil_disabled, base, ("lit",)),
    ("blend (BF_SA, BF_MSA)", blend_uses, blend_disabled, base, ("lit",)),
    ("pattern (16x16 halftone)", pattern_uses, pattern_disabled, base, ("lit",)),
    ("lighting (lmbind)", lighting_uses, lighting_disabled, lighting_absent, ("colour",)),
    ("texture (64x64 MODULATE)", texture_uses, texture_disabled, texture_absent,
     ("lit_tex",)),
    ("accumulation (acbuf per frame)", accum_uses, accum_disabled, base, ("lit",)),
    ("shading GOURAUD (absent: FLAT)", base, None, flat_lit, ("lit",)),
]

OBJECTS = {
    "lit": dict(),                                           # materials + normals
    "lit_tex": dict(tex=True),                               # + t2f
    "colour": dict(materials=False, colours=True),           # cpack + normals
    "colour_only": dict(materials=False, normals=False, colours=True),
    "lit_depth": dict(materials=False, normals=False),       # positions only
}


# ======================================================================================
# 4. work the scene does not need: (label, with, without)
# ======================================================================================
def unlit_with_normals(o):
    gid = open_window()
    zbuffer(TRUE)
    return gid, scene_frame(o["colour"], light=False)


def unlit_without_normals(o):
    gid = open_window()
    zbuffer(TRUE)
    return gid, scene_frame(o["colour_only"], light=False)


def gouraud_constant(o):
    return unlit_without_normals(o)


def flat_constant(o):
    gid, frame = unlit_without_normals(o)
    shademodel(FLAT)
    return gid, frame


UNNEEDED = [
    ("normals sent, lighting off (cpack + n3f + v3f vs cpack + v3f)",
     unlit_with_normals, unlit_without_normals, ("colour", "colour_only")),
    ("texture coordinates sent, texturing off (t2f in the object vs none)",
     texture_absent, base, ("lit", "lit_tex")),
    ("GOURAUD over constant colours (unlit, one cpack per part) vs FLAT",
     gouraud_constant, flat_constant, ("colour_only",)),
]


# ======================================================================================
# 5. the light's view (1024 x 1024)
# ======================================================================================
def light_eye():
    """The light's eye LIGHT_DISTANCE along the sun's direction, and its
    frustum (vs_mesa.light_frustum: 90 degrees towards the origin)."""
    d = np.array(spheres_light()[:3])
    eye = LIGHT_DISTANCE * d / np.linalg.norm(d)
    pts = np.concatenate([p.reshape(-1, 3) for _, p, _ in spheres_scene()])
    return eye, light_frustum(eye, pts)


def light_window():
    eye, (fovy, near, far, tgt) = light_eye()
    gid = open_window(LIGHT_SIZE, LIGHT_SIZE)
    perspective(fovy, 1.0, near, far)
    zbuffer(TRUE)

    def view():
        lookat(*eye, *tgt, 0)
    return gid, view


def lightpass_lit(o):
    gid, view = light_window()
    lmbind(LMODEL, fs.MODEL)
    return gid, scene_frame(o["lit"], view=view)


def lightpass_depth_lighting_bound(o):
    gid, view = light_window()
    lmbind(LMODEL, fs.MODEL)
    wmpack(0)
    return gid, scene_frame(o["lit"], clr=zclear, view=view)


def lightpass_depth_unlit(o):
    gid, view = light_window()
    wmpack(0)
    return gid, scene_frame(o["lit"], clr=zclear, light=False, view=view)


def lightpass_depth_positions(o):
    gid, view = light_window()
    wmpack(0)
    return gid, scene_frame(o["lit_depth"], clr=zclear, light=False, view=view)


LIGHT_PASSES = [
    ("full lit pass (czclear, lighting, colour + z)", lightpass_lit),
    ("depth only, lighting left bound (wmpack(0), zclear, same object)",
     lightpass_depth_lighting_bound),
    ("depth only, no lighting (wmpack(0), zclear, LMODEL unbound, normals sent)",
     lightpass_depth_unlit),
    ("depth only, positions only (wmpack(0), zclear, v3f only)", lightpass_depth_positions),
]


# ======================================================================================
# 6. timing
# ======================================================================================
def build(columns, needs):
    """A fresh machine, the objects, then one window per column:
    {name: (gid, frame)} (None columns are skipped)."""
    fresh_machine()
    define_pattern()
    define_texture()
    objs = {k: scene_object(**OBJECTS[k]) for k in needs}
    return {name: make(objs) for name, make in columns.items() if make is not None}


def timed(frame):
    t0 = time.perf_counter()
    frame()
    return time.perf_counter() - t0


def interleave(windows, rounds, warm=2):
    """Warm each window, then rounds of one timed frame per window, the order
    rotated each round: {name: [seconds, one per round]}."""
    names = list(windows)
    for n in names:
        gid, frame = windows[n]
        winset(gid)
        for _ in range(warm):
            frame()
    times = {n: [] for n in names}
    for r in range(rounds):
        k = r % len(names)
        for n in names[k:] + names[:k]:
            gid, frame = windows[n]
            winset(gid)
            gc.collect()
            times[n].append(timed(frame))
    return times


def overhead(times, a, b):
    """Overhead of a over b: (median, p25, p75) of t_a / t_b - 1 over the
    rounds (frames side by side), and the ratio of the minima - 1 (contention
    only ever adds time, so the fastest frames are the least disturbed)."""
    r = np.array(times[a]) / np.array(times[b]) - 1.0
    return (float(np.median(r)), float(np.percentile(r, 25)), float(np.percentile(r, 75)),
            min(times[a]) / min(times[b]) - 1.0)


def ms(ts):
    """Median (minimum) milliseconds."""
    return f"{1000 * statistics.median(ts):.1f} ({1000 * min(ts):.1f})"


def pct(o):
    med, lo, hi, mins = o
    return f"{100 * med:+.1f}% ({100 * lo:+.1f} .. {100 * hi:+.1f}); min {100 * mins:+.1f}%"


# ======================================================================================
# 7. the tables
# ======================================================================================
def pipeline_of(gid):
    """What a flush of filled primitives runs in window gid, as a dict: the
    RasterKey fields (the compiled kernel variant), texturing, lighting."""
    from vgx_emulator.geometry import lighting_active
    m = _machine()
    win = m.windows[gid]
    key = m._raster_setup(win, None, filled=True)[0]
    out = dict(key._asdict())
    out["texture"] = m._texturing(win) is not None
    out["lighting"] = lighting_active(win.st, m.defs)
    return out


def same_pipeline(windows, a, b):
    """"same" when windows a and b run the same kernel and geometry stages,
    else the fields that differ."""
    pa, pb = (pipeline_of(windows[k][0]) for k in (a, b))
    diff = [k for k in pa if pa[k] != pb[k]]
    return "same" if not diff else "differs: " + ", ".join(diff)


def feature_table(rounds):
    print("| feature | uses it ms | configured, disabled ms | absent ms | uses vs absent "
          "| **configured, disabled vs absent** | disabled: kernel and stages vs absent |")
    print("|---|---|---|---|---|---|---|")
    for name, uses, disabled, absent, needs in FEATURES:
        wins = build({"uses": uses, "disabled": disabled, "absent": absent}, needs)
        t = interleave(wins, rounds)
        has = "disabled" in t
        dis = pct(overhead(t, "disabled", "absent")) if has else "-"
        same = same_pipeline(wins, "disabled", "absent") if has else "-"
        print(f"| {name} | {ms(t['uses'])} | {ms(t['disabled']) if has else '-'} "
              f"| {ms(t['absent'])} | {pct(overhead(t, 'uses', 'absent'))} | {dis} | {same} |",
              flush=True)


def unneeded_table(rounds):
    print("| work the scene does not need | with ms | without ms | overhead |")
    print("|---|---|---|---|")
    for label, with_, without, needs in UNNEEDED:
        t = interleave(build({"with": with_, "without": without}, needs), rounds)
        print(f"| {label} | {ms(t['with'])} | {ms(t['without'])} "
              f"| {pct(overhead(t, 'with', 'without'))} |", flush=True)


def light_table(rounds):
    cols = {label: make for label, make in LIGHT_PASSES}
    t = interleave(build(cols, ("lit", "lit_depth")), rounds)
    ref = LIGHT_PASSES[0][0]
    print(f"| pass from the light, {LIGHT_SIZE}x{LIGHT_SIZE} | ms | vs full lit pass |")
    print("|---|---|---|")
    for label, _ in LIGHT_PASSES:
        vs = "-" if label == ref else pct(overhead(t, label, ref))
        print(f"| {label} | {ms(t[label])} | {vs} |", flush=True)


# ======================================================================================
# 8. memory
# ======================================================================================
def rss():
    """Resident set size of this process now, bytes (/proc/self/statm)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def bank_bytes(fb):
    """{bank: bytes} of the banks a window's Framebuffer holds."""
    return {k: getattr(fb, k).nbytes for k in ("front", "back", "z", "stencil", "accum")
            if getattr(fb, k) is not None}


#: (label, open_window kwargs, setup after gconfig, first-frame use)
MEMORY = [
    ("RGB, single buffer (front only)", dict(double=False), None, clear_c),
    ("+ doublebuffer", dict(), None, clear_c),
    ("+ zbuffer(TRUE)", dict(double=False), lambda: zbuffer(TRUE), clear_cz),
    ("+ stensize(8)", dict(double=False, stencil_planes=8), None, lambda: sclear(0)),
    ("+ acsize(16)", dict(double=False, accum=True), None, lambda: acbuf(AC_CLEAR, 0.0)),
    ("everything (double, z, stencil 8, accum 16)",
     dict(stencil_planes=8, accum=True), lambda: zbuffer(TRUE),
     lambda: (clear_cz(), sclear(0), acbuf(AC_CLEAR, 0.0))),
]


def memory_row(i):
    """In this (fresh) process: (banks, RSS delta after open + gconfig, RSS
    delta after a first frame that uses the banks) of MEMORY[i].  The same
    window is first opened at 16x16, so that loading the kernels is not
    counted."""
    _, kwargs, setup, use = MEMORY[i]
    for w, h in ((16, 16), (W, H)):
        _machine().reset()
        gc.collect()
        r0 = rss()
        open_window(w, h, **kwargs)
        if setup is not None:
            setup()
        r1 = rss()
        use()
        swapbuffers()
        r2 = rss()
    return bank_bytes(_machine().current.fb), r1 - r0, r2 - r0


def memory_in_child(i):
    """memory_row(i) in a fresh interpreter (an allocator that has held and
    freed big arrays keeps their pages, so in-process RSS deltas read 0)."""
    out = subprocess.run([sys.executable, __file__, "--memory-row", str(i)], check=True,
                         capture_output=True, text=True).stdout
    banks, r1, r2 = json.loads(out.strip().splitlines()[-1])
    return banks, r1, r2


def mib(n):
    return f"{n / 2 ** 20:.2f} MiB"


def definition_bytes():
    """Bytes of the global definitions: the halftone pattern, the texture."""
    fresh_machine()
    define_pattern()
    define_texture()
    m = _machine()
    pat = sum(bits.nbytes for _, bits in m.patterns.values())
    tex = sum(t.texels.nbytes for t in m.textures.values())
    m.reset()
    return pat, tex


def memory_table(rounds=None):
    print(f"| window {W}x{H} | banks (bytes, from machine().current.fb) | total | "
          f"RSS delta after gconfig | RSS delta after a first frame |")
    print("|---|---|---|---|---|")
    for i, (label, *_) in enumerate(MEMORY):
        banks, after_cfg, after_use = memory_in_child(i)
        desc = ", ".join(f"{k} {v:,}" for k, v in banks.items())
        print(f"| {label} | {desc} | {mib(sum(banks.values()))} | {mib(after_cfg)} "
              f"| {mib(after_use)} |", flush=True)
    pat, tex = definition_bytes()
    print(f"| definition (global): a 16x16 pattern | {pat:,} | | | |")
    print(f"| definition (global): a {TEXTURE_SIZE}x{TEXTURE_SIZE} RGBA texture and its "
          f"mip levels | {tex:,} | | | |")


SECTIONS = [("a", "each feature: used, configured but disabled, absent", feature_table),
            ("b", "work the scene does not need", unneeded_table),
            ("c", "a light's view of the scene", light_table),
            ("d", "memory", memory_table)]


# ======================================================================================
# 9. main
# ======================================================================================
def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer rounds (20 instead of 60)")
    ap.add_argument("--threads", type=int, default=None,
                    help="NUMBA_NUM_THREADS, set before numba starts (default 1; 0: "
                         "numba's default)")
    ap.add_argument("--memory-row", type=int, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--rounds", type=int, default=None, help="timed frames per window")
    ap.add_argument("--sections", default="abcd",
                    help="which tables: a features, b unneeded work, c light pass, d memory")
    a = ap.parse_args(argv)
    a.rounds = a.rounds or (20 if a.quick else 60)
    return a


def main(argv=None):
    from raster import machine_description
    a = parse(sys.argv[1:] if argv is None else argv)
    if a.memory_row is not None:
        print(json.dumps(memory_row(a.memory_row)))
        return
    t0 = time.perf_counter()
    print(f"Machine: {machine_description()}")
    print(f"Load average at start: {os.getloadavg()[0]:.2f}; {a.rounds} rounds per row; "
          f"scene: spheres (5248 triangles) at {W}x{H}")
    print("Times: median (minimum) ms per frame over the rounds.  Overheads: median of "
          "the paired per-round ratios (interquartile range); min: ratio of the minima.")
    print()
    for key, title, table in SECTIONS:
        if key in a.sections:
            print(f"### ({key}) {title}")
            print()
            table(a.rounds)
            print()
    print(f"Load average at end: {os.getloadavg()[0]:.2f}; total "
          f"{time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
