"""Immediate mode: what one per-vertex call costs, and triangles per second.

Part 1 (ns per call): each per-vertex call runs in the loop
``for p in data: call(p)`` over 1,000 prepared arguments, beside a no-op
Python function called in the same loop over the same data (the floor: a
Python call cannot cost less).  The ratio is call / floor, both measured in
this run (best of ``--repeat`` rounds, rounds interleaved so that a busy
moment hits both).  v*/n3f/c*/t* run inside an open bgnpoint (their normal
place); bgn/end is one bgnpolygon() + endpolygon() pair of an empty polygon,
reported per call.

Part 2 (triangles per second, end to end: from the first call to the pixels
read back): a lit, z-buffered height field of small triangles in a 640x480
window (``--size``), drawn three ways: immediate polygons (bgnpolygon, three
n3f + v3f, endpolygon per triangle), an immediate tmesh (one bgntmesh per
row, n3f + v3f per vertex) and the same tmesh from a display list
(makeobj once, callobj timed).  Where PyOpenGL and Mesa's OSMesa are
installed, the same calls run on llvmpipe beside it (glBegin(GL_POLYGON) /
glNormal3fv / glVertex3fv; GL_TRIANGLE_STRIP; a display list).  Every
timing is the median of ``--repeat`` runs after one warm-up run (the first
run compiles the kernels).

    python benchmarks/immediate.py [--size 640x480] [--repeat 5] [--no-mesa]
"""
import argparse
import os
import statistics
import sys
import time
import timeit

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
if "OpenGL.GL" not in sys.modules:
    os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")

import numpy as np  # noqa: E402

import vgx_emulator  # noqa: E402
from vgx_emulator import config, specialise  # noqa: E402

from irisgl import (DEFLIGHT, DEFLMODEL, DEFMATERIAL, DIFFUSE, LCOLOR, LIGHT0,  # noqa: E402
                    LMNULL, LMODEL, MATERIAL, POSITION, RGBcolor, RGBmode, bgnpoint,
                    bgnpolygon, bgntmesh, c3f, c4f, callobj, closeobj, cpack, czclear,
                    endpoint, endpolygon, endtmesh, finish, gconfig, genobj, gexit,
                    lmbind, lmdef, lrectread, makeobj, mmode, n3f, ortho, prefsize, t2f, v2f,
                    v3f, v4f, winopen, zbuffer, MVIEWING)

N = 1000


def _noop(a):
    pass


def _noop3(a, b, c):
    pass


def _noop0():
    pass


def per_call(repeat):
    """{call: (ns, floor ns, ratio)} for the per-vertex calls."""
    rng = np.random.default_rng(1)
    p2 = [tuple(r) for r in rng.random((N, 2)).tolist()]
    p3 = [tuple(r) for r in rng.random((N, 3)).tolist()]
    p4 = [tuple(r) for r in rng.random((N, 4)).tolist()]
    words = [int(w) for w in rng.integers(0, 2**32, N)]
    ints = [tuple(r) for r in rng.integers(0, 256, (N, 3)).tolist()]
    rounds = 20

    def loop1(f, data):
        def run():
            for p in data:
                f(p)
        return run

    def loop3(f, data):
        def run():
            for r, g, b in data:
                f(r, g, b)
        return run

    def loop0(f, g):
        def run():
            for _ in p2:
                f()
                g()
        return run

    cases = {
        "v2f": (loop1(v2f, p2), loop1(_noop, p2), 1),
        "v3f": (loop1(v3f, p3), loop1(_noop, p3), 1),
        "v4f": (loop1(v4f, p4), loop1(_noop, p4), 1),
        "n3f": (loop1(n3f, p3), loop1(_noop, p3), 1),
        "c3f": (loop1(c3f, p3), loop1(_noop, p3), 1),
        "c4f": (loop1(c4f, p4), loop1(_noop, p4), 1),
        "cpack": (loop1(cpack, words), loop1(_noop, words), 1),
        "RGBcolor": (loop3(RGBcolor, ints), loop3(_noop3, ints), 1),
        "t2f": (loop1(t2f, p2), loop1(_noop, p2), 1),
        "bgnpolygon/endpolygon": (loop0(bgnpolygon, endpolygon), loop0(_noop0, _noop0), 2),
    }
    best = {k: [1e9, 1e9] for k in cases}
    for _ in range(repeat):
        for name, (call, floor, per) in cases.items():
            inside = not name.startswith("bgn")
            if inside:
                bgnpoint()
            t = timeit.timeit(call, number=rounds) / (rounds * N * per) * 1e9
            if inside:
                endpoint()
            finish()                          # draw and drop what the round sent
            f = timeit.timeit(floor, number=rounds) / (rounds * N * per) * 1e9
            best[name][0] = min(best[name][0], t)
            best[name][1] = min(best[name][1], f)
    return {k: (t, f, t / f) for k, (t, f) in best.items()}


def height_field(w, h, ntri):
    """A wavy z = f(x, y) grid with about ``ntri`` triangles over the window:
    (rows, cols + 1, 2, 3) strip vertices, their unit normals, triangle area."""
    aspect = w / h
    rows = int(round(np.sqrt(ntri / 2 / aspect)))
    cols = int(round(ntri / 2 / rows))
    xs = np.linspace(0, w, cols + 1)
    ys = np.linspace(0, h, rows + 1)
    X, Y = np.meshgrid(xs, ys)
    Z = -50 + 20 * np.sin(X / 37.0) * np.cos(Y / 23.0)
    dzx = 20 / 37.0 * np.cos(X / 37.0) * np.cos(Y / 23.0)
    dzy = -20 / 23.0 * np.sin(X / 37.0) * np.sin(Y / 23.0)
    nrm = np.stack((-dzx, -dzy, np.ones_like(X)), -1)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    pos = np.stack((X, Y, Z), -1)
    # strip r: vertices (r, c), (r + 1, c) alternating
    sp = np.stack((pos[:-1], pos[1:]), 2)          # (rows, cols+1, 2, 3)
    sn = np.stack((nrm[:-1], nrm[1:]), 2)
    area = (w / cols) * (h / rows) / 2
    return sp, sn, 2 * rows * cols, area


def emu_window(w, h):
    prefsize(w, h)
    winopen("immediate")
    RGBmode()
    gconfig()
    zbuffer(1)
    mmode(MVIEWING)                 # lighting needs MVIEWING (lmbind(3G))
    ortho(0, w, 0, h, 0, 100)
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.8, 0.6, 0.3, LMNULL])
    lmdef(DEFLIGHT, 1, 0, [POSITION, 0.3, 0.4, 1.0, 0.0, LCOLOR, 1, 1, 1, LMNULL])
    lmdef(DEFLMODEL, 1, 0, [LMNULL])
    lmbind(MATERIAL, 1)
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)


def emu_polygons(tris):
    for (a, b, c), (na, nb, nc) in tris:
        bgnpolygon()
        n3f(na)
        v3f(a)
        n3f(nb)
        v3f(b)
        n3f(nc)
        v3f(c)
        endpolygon()


def emu_tmesh(strips):
    for verts, norms in strips:
        bgntmesh()
        for v, n in zip(verts, norms):
            n3f(n)
            v3f(v)
        endtmesh()


def timed(run, repeat, read, capture, warm=lambda: None):
    """(median seconds of ``run`` + ``read``, the picture it left as RGB),
    after ``warm`` (the emulator: frames until its state's own kernel
    variant is in use, as vs_mesa.py does)."""
    run()
    read()                                 # warm-up: compiles
    warm()
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        run()
        read()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts), capture()


def workloads(w, h, ntri):
    """The three drawings as Python lists, as a program would hold them."""
    sp, sn, ntm, area = height_field(w, h, ntri)
    strips = []
    for r in range(sp.shape[0]):
        strips.append((sp[r].reshape(-1, 3).tolist(), sn[r].reshape(-1, 3).tolist()))
    tris = []
    for verts, norms in strips:
        for i in range(len(verts) - 2):
            tris.append(((verts[i], verts[i + 1], verts[i + 2]),
                         (norms[i], norms[i + 1], norms[i + 2])))
    return tris, strips, ntm, area


def emulator(w, h, repeat, tris_poly, strips, ntm):
    emu_window(w, h)

    def read():
        lrectread(0, 0, 0, 0)

    def capture():
        return vgx_emulator.window_image()[..., :3]

    def warm_up(run):
        def warm():
            # the frames after the first until the pass's own kernel variant
            # is used (vgx_emulator/specialise.py: compiled by a second
            # process after config.SPECIALISE_AFTER uses), as a program's
            # animation loop reaches it
            for _ in range(config.SPECIALISE_AFTER):
                run()
                read()
            specialise.wait(900)
        return warm

    out = {}
    clear = lambda: czclear(0, 0x7FFFFF)   # noqa: E731
    polys = lambda: (clear(), emu_polygons(tris_poly))     # noqa: E731
    tmesh = lambda: (clear(), emu_tmesh(strips))           # noqa: E731
    out["immediate polygons"] = (len(tris_poly), *timed(polys, repeat, read, capture,
                                                        warm_up(polys)))
    out["immediate tmesh"] = (ntm, *timed(tmesh, repeat, read, capture, warm_up(tmesh)))
    ob = genobj()
    makeobj(ob)
    emu_tmesh(strips)
    closeobj()
    replay = lambda: (clear(), callobj(ob))                # noqa: E731
    out["display-list tmesh"] = (ntm, *timed(replay, repeat, read, capture, warm_up(replay)))
    gexit()
    return out


def mesa(w, h, repeat, tris_poly, strips, ntm):
    from vs_mesa import Mesa
    m = Mesa()
    m.use(w, h)
    g = m.GL
    g.glMatrixMode(g.GL_PROJECTION)
    g.glLoadIdentity()
    g.glOrtho(0, w, 0, h, 0, 100)
    g.glMatrixMode(g.GL_MODELVIEW)
    g.glLoadIdentity()
    g.glEnable(g.GL_DEPTH_TEST)
    g.glEnable(g.GL_LIGHTING)
    g.glEnable(g.GL_LIGHT0)
    g.glLightfv(g.GL_LIGHT0, g.GL_POSITION, (0.3, 0.4, 1.0, 0.0))
    g.glMaterialfv(g.GL_FRONT_AND_BACK, g.GL_DIFFUSE, (0.8, 0.6, 0.3, 1.0))
    g.glShadeModel(g.GL_SMOOTH)
    n3, v3 = g.glNormal3fv, g.glVertex3fv

    def polys():
        for (a, b, c), (na, nb, nc) in tris_poly:
            g.glBegin(g.GL_POLYGON)
            n3(na)
            v3(a)
            n3(nb)
            v3(b)
            n3(nc)
            v3(c)
            g.glEnd()

    def tmesh():
        for verts, norms in strips:
            g.glBegin(g.GL_TRIANGLE_STRIP)
            for v, n in zip(verts, norms):
                n3(n)
                v3(v)
            g.glEnd()

    def clear():
        g.glClear(g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT)

    out = {"immediate polygons": (len(tris_poly), *timed(lambda: (clear(), polys()), repeat,
                                                         g.glFinish, m.rgb)),
           "immediate tmesh": (ntm, *timed(lambda: (clear(), tmesh()), repeat, g.glFinish,
                                           m.rgb))}
    lst = g.glGenLists(1)
    g.glNewList(lst, g.GL_COMPILE)
    tmesh()
    g.glEndList()
    out["display-list tmesh"] = (ntm, *timed(lambda: (clear(), g.glCallList(lst)), repeat,
                                             g.glFinish, m.rgb))
    m.close()
    return m.renderer, out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--tmesh-triangles", type=int, default=40000)
    ap.add_argument("--polygons", type=int, default=20000)
    ap.add_argument("--no-mesa", action="store_true")
    a = ap.parse_args(argv)
    w, h = (int(v) for v in a.size.split("x"))

    prefsize(64, 64)
    winopen("per-call")
    RGBmode()
    gconfig()
    pc = per_call(a.repeat)
    gexit()
    print("per-vertex call            ns/call   no-op floor   ratio")
    for k, (t, f, r) in pc.items():
        print(f"{k:<24} {t:9.1f} {f:11.1f} {r:9.2f}x")

    tris, strips, ntm, area = workloads(w, h, a.tmesh_triangles)
    tris_poly = tris[:a.polygons]
    emu = emulator(w, h, a.repeat, tris_poly, strips, ntm)
    gl = None
    if not a.no_mesa:
        try:
            gl = mesa(w, h, a.repeat, tris_poly, strips, ntm)
        except Exception as e:                # no PyOpenGL/OSMesa here
            print(f"(Mesa side skipped: {type(e).__name__}: {e})")
    if gl:
        from vs_mesa import DIFF_THRESHOLD, diff_fraction
    print(f"\n{w}x{h}, lit z-buffered height field, triangles of {area:.1f} px")
    head = "workload                 triangles   emulator M tri/s"
    if gl:
        head += f"   {gl[0][:24]} M tri/s   ratio   differs"
    print(head)
    for k, (n, t, img) in emu.items():
        line = f"{k:<24} {n:9d} {n / t / 1e6:14.3f}"
        if gl:
            ng, tg, gimg = gl[1][k]
            line += f" {ng / tg / 1e6:24.3f} {(n / t) / (ng / tg):8.2f}x" \
                    f" {diff_fraction(img, gimg):9.4f}"
        print(line)
    if gl:
        print(f"(differs: the fraction of pixels whose R, G or B differs by more than "
              f"{DIFF_THRESHOLD} between the two pictures, a check that both drew the same)")


if __name__ == "__main__":
    main()
