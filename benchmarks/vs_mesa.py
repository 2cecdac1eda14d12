"""The emulated VGX side by side with Mesa's llvmpipe (OSMesa through PyOpenGL).

Every workload is built twice from the same numpy data and the same numbers:
once through IRIS GL (``irisgl``) on the emulator, once through legacy OpenGL
on Mesa.  Same triangles, matrices (taken from the emulator with
``getmatrix``: IRIS GL's row-vector Matrix has the same 16 floats as GL's
column-major one), lights, materials (read back from the emulator's lmdef
tables and mapped to glLight/glMaterial/glLightModel) and resolution.

Workloads:
  spheres         four lit, Gouraud-shaded spheres (programs/four_spheres.py:
                  its centres, 32 x 16 quad strips, material and light model)
                  on a 24 x 24 quad ground plane, z-buffered, 5248 triangles.
                  Its infinite light is four_spheres' light raised 40 degrees
                  above the horizon, so the ground is lit.  Each side runs its
                  own lighting (IRIS lmdef -> GL fixed function).
  spheres-depth   the same, depth only (zclear; wmpack(0) / glColorMask 0).
  spheres-lmcolor the same, every vertex with its own colour through c4f under
                  lmcolor(LMC_AD), as 1991 programs coloured lit surfaces (GL:
                  GL_COLOR_MATERIAL with GL_AMBIENT_AND_DIFFUSE, a colour array).
  heidmann        programs/heidmann_shadow_volumes.py figure 5b (eight objects,
                  four coloured local lights): ambient pass, then per light
                  sclear(MYZERO), the shadow-volume faces with ST_INCR/ST_DECR
                  (colour and z writes off), the additive lit pass where the
                  stencil is MYZERO.  The emulator runs the program's own
                  draw_scene(); Mesa replays the same algorithm with the faces
                  the program's shadow_faces() returns.
  heidmann-immediate  the same program without --objects: every polygon and
                  shadow face sent vertex by vertex in every frame (v3f, n3f);
                  Mesa in immediate mode through PyOpenGL (glBegin, glNormal3f,
                  glVertex3f/3fv, glEnd), the same faces.
  heidmann-1991   the program with --two-pass --infinite, as ports of the time
                  drew the volumes: every face twice, backface(TRUE) with
                  ST_INCR then frontface(TRUE) with ST_DECR (GL: glCullFace
                  GL_BACK / GL_FRONT, GL_INCR / GL_DECR), far corners at
                  infinity (v4f / glVertex4f with w = 0) under an infinite far
                  plane; objects / display lists.
  heidmann-1991-immediate  the same, sent call by call in every frame.
  heidmann-spheres  the program's "spheres" scene (four spheres on the ground,
                  one light) drawn the 1991 way (--two-pass --infinite,
                  objects): the scene of a side-by-side harness written from
                  outside, where stencil volumes of one light over a few
                  curved casters make many small per-pass batches.
  heidmann-soft   the program's figure 6 (five objects, one light): 32 jittered
                  light positions accumulated (acbuf / glAccum).
  shadowmap       the 5b scene's depth from each of its 4 lights into a
                  1024 x 1024 z-buffer (window/viewport 1024 x 1024, colour
                  writes off); only the depth passes.  Run once, at 1024x1024.
  fill-z          32 full-screen Gouraud quads, z-tested, back to front (each
                  passes: the worst case).
  fill-stencil    32 full-screen quads, ST_INCR on z-pass, colour and z writes
                  off.
  cold            (emulator only) a fresh process to the first PNG of
                  four_spheres with an empty and a filled numba cache, and
                  with Python's bytecode cached too:
                  benchmarks/first_light.py's cold_start().

Equal work: the Mesa side keeps its geometry in display lists built once,
outside the timing; the emulator side keeps it in IRIS GL objects
(makeobj/callobj, compiled to arrays at closeobj); heidmann* run the
program with --objects, which records its DrawObjects and each light's
DrawShadowVolumes in objects on the first (untimed) frame and replays them
with callobj (the program's immediate mode costs about 100 ms more a frame
at 5b, all of it Python calls: 21,100 v3f and 5,325 bgnpolygon).  The Mesa timing ends with glFinish(); the emulator timing
ends with swapbuffers(), which draws everything queued (machine._flush) before
the swap.  Each workload: one untimed run per side, then N alternating timed
runs (emulator, Mesa, emulator, ...).  One PNG per workload per side goes to
--out; depth and stencil workloads are saved as grey images (the same scaling
on both sides).  The last column is the fraction of pixels whose RGB differs
by more than 8 between the two images: a sanity check that both sides did the
same work, not a test.  Known differences: the emulator snaps vertices to
pixel centres unless subpixel(TRUE) (IRIS GL's default; heidmann* and the
fill quads are unaffected), and edge pixels follow each side's fill rule.

Usage: python benchmarks/vs_mesa.py [--quick] [--reps N] [--sizes 640x480,1280x1024]
           [--only NAME ...] [--threads N] [--out DIR] [--no-cold]
"""
import os
import sys


# -- 0. environment, before numba or Mesa start ----------------------------------------
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # benchmarks/: threads.py
from threads import early_threads  # noqa: E402


if __name__ == "__main__":
    _threads = early_threads(sys.argv[1:])
    if _threads:
        os.environ["NUMBA_NUM_THREADS"] = _threads     # numba's prange walker
        os.environ["LP_NUM_THREADS"] = _threads        # llvmpipe's rasterizer threads
    if "OpenGL" not in sys.modules:
        import OpenGL
        OpenGL.ERROR_CHECKING = False     # no glGetError after every timed call
if "OpenGL.GL" not in sys.modules:
    os.environ["PYOPENGL_PLATFORM"] = "osmesa"

import argparse  # noqa: E402
import math  # noqa: E402
import resource  # noqa: E402
import statistics  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
for _p in (str(ROOT), str(ROOT / "benchmarks")):
    if _p not in sys.path:
        sys.path.insert(0, _p)

from irisgl import (AMBIENT, DEFLIGHT, DEFLMODEL, DEFMATERIAL, DIFFUSE,  # noqa: E402
                    GD_BITS_STENCIL, GD_ZMAX, LIGHT0, LMC_AD, LMNULL, LMODEL, MATERIAL, MPROJECTION,
                    MVIEWING, POSITION, SF_ALWAYS, SPECULAR, SRC_AUTO, SRC_ZBUFFER,
                    ST_INCR, ST_KEEP, TRUE, RGBmode, acsize, bgnpolygon, bgnqstrip,
                    c4f, callobj, closeobj, cpack, czclear, doublebuffer, endpolygon, endqstrip,
                    gconfig, genobj, getgdesc, getmatrix, lmbind, lmcolor, lmdef, lookat, lrectread,
                    makeobj, mmode, n3f, ortho, perspective, popmatrix, prefsize,
                    pushmatrix, readsource, sclear, stencil, stensize, subpixel,
                    swapbuffers, v3f, winopen, wmpack, zbuffer, zclear, zwritemask)
from vgx_emulator.geometry import lighting as L  # noqa: E402
import programs.four_spheres as fs  # noqa: E402
import programs.heidmann_shadow_volumes as hv  # noqa: E402
import vgx_emulator  # noqa: E402
from vgx_emulator.display.png import write_png  # noqa: E402
from vgx_emulator import config, specialise  # noqa: E402

WORKLOADS = ["spheres", "spheres-depth", "spheres-lmcolor", "heidmann", "heidmann-immediate", "heidmann-1991",
             "heidmann-1991-immediate", "heidmann-spheres", "heidmann-soft", "shadowmap", "fill-z", "fill-stencil",
             "cold"]
SHADOWMAP_SIZE = 1024
NQUADS = 32
DIFF_THRESHOLD = 8


def _machine():
    from irisgl._current import machine
    return machine


# ======================================================================================
# 1. scenes as numpy arrays (shared by both sides)
# ======================================================================================
GROUND_N = 24
GROUND_Y = -1.0                     # the spheres (radius 1, centres at y = 0) rest on it
GROUND_X, GROUND_Z = (-7.0, 7.0), (-6.0, 7.0)
GROUND_MAT = 2
LIGHT_ELEVATION = 40.0              # degrees above the horizon


def sphere_strips(centre, r=1.0):
    """four_spheres.sphere() as arrays: (STACKS, 2*(SLICES+1), 3) positions and
    unit normals, one quad strip per band, vertices in the program's order."""
    i = np.arange(fs.STACKS)[:, None, None]
    j = np.arange(fs.SLICES + 1)[None, :, None]
    k = np.arange(2)[None, None, :]             # (phi1, phi0) per column
    phi = math.pi * (i + 1 - k) / fs.STACKS - math.pi / 2
    th = 2 * math.pi * j / fs.SLICES
    n = np.stack(np.broadcast_arrays(np.cos(phi) * np.cos(th), np.sin(phi),
                                     -np.cos(phi) * np.sin(th)), -1)
    n = n.reshape(fs.STACKS, -1, 3)
    return np.asarray(centre, float) + r * n, n


def ground_strips():
    """A GROUND_N x GROUND_N quad grid at y = GROUND_Y, one strip per row,
    normal +y: ((rows, 2*(cols+1), 3) positions, normals)."""
    xs = np.linspace(*GROUND_X, GROUND_N + 1)
    zs = np.linspace(*GROUND_Z, GROUND_N + 1)
    p = np.empty((GROUND_N, GROUND_N + 1, 2, 3))
    p[..., 0] = xs[None, :, None]
    p[..., 1] = GROUND_Y
    p[:, :, 0, 2] = zs[1:, None]
    p[:, :, 1, 2] = zs[:-1, None]
    p = p.reshape(GROUND_N, -1, 3)
    n = np.zeros_like(p)
    n[..., 1] = 1.0
    return p, n


def spheres_scene():
    """[(material index, positions (S, V, 3), normals (S, V, 3))]: quad strips."""
    parts = [(GROUND_MAT, *ground_strips())]
    for c in fs.CENTRES:
        parts.append((fs.SPHERE_MAT, *sphere_strips(c)))
    return parts


def spheres_light():
    """four_spheres' light direction raised LIGHT_ELEVATION degrees (w = 0)."""
    d = np.array(fs.LIGHT_DIR[:3], float)
    e = math.radians(LIGHT_ELEVATION)
    d = np.array([d[0] * math.cos(e), math.sin(e), d[2] * math.cos(e)])
    return [float(v) for v in d] + [0.0]


def fill_quads(w, h):
    """NQUADS full-screen quads (corners one pixel outside the window, so
    every pixel centre is strictly inside), back to front (z from -0.9 to
    0.9 with ortho(.., -1, 1): each nearer than the last), and a packed
    0xAABBGGRR colour per corner.  The colours are affine over each quad
    (c2 = c1 + c3 - c0), so Gouraud shading gives the same picture whichever
    diagonal an implementation splits the quad along.  Fixed seed."""
    z = np.linspace(-0.9, 0.9, NQUADS)
    xy = np.array([(-1.0, -1.0), (w, -1.0), (w, h), (-1.0, h)])
    pos = np.empty((NQUADS, 4, 3))
    pos[:, :, :2] = xy
    pos[:, :, 2] = z[:, None]
    rng = np.random.default_rng(1991)
    base = rng.integers(0, 86, (NQUADS, 1, 3))
    dx, dy = rng.integers(0, 85, (2, NQUADS, 1, 3))        # every corner <= 255
    rgb = base + np.array([0, 1, 1, 0])[None, :, None] * dx \
        + np.array([0, 0, 1, 1])[None, :, None] * dy
    words = 0xFF000000 | rgb[..., 0] | (rgb[..., 1] << 8) | (rgb[..., 2] << 16)
    return pos, words.astype(np.int64)


SHADOWMAP_FOVY = 900                # tenths of a degree
SHADOWMAP_NEAR = 1.0                # no vertex of the scene is nearer to a light


def light_frustum(lpos, pts):
    """A light's view: (fovy tenths, near, far, target): 90 degrees towards
    the centre of the ground (the origin), far just past the farthest point."""
    far = 1.05 * float(np.linalg.norm(pts - lpos, axis=1).max())
    return SHADOWMAP_FOVY, SHADOWMAP_NEAR, far, np.zeros(3)


def shadowmap_views():
    """The 5b scene's objects and, per light of figure 5b, (lpos, frustum)."""
    objs = hv.make_scene(hv.FIGURE_SETUP["5b"][0])
    pts = np.concatenate([o.verts for o in objs])
    views = []
    for name in hv.FIGURE_SETUP["5b"][1]:
        lpos = np.array(hv.LIGHT_DEFS[name][1], float)
        views.append((lpos, light_frustum(lpos, pts)))
    return objs, views


# ======================================================================================
# 2. the emulator side (IRIS GL calls)
# ======================================================================================
class Side:
    """One side of a workload: frame() draws one finished frame; capture()
    returns (kind, image) of what the last frame left: kind "rgb" (h, w, 3)
    uint8, "depth" (h, w) in [0, 1], or "stencil" (h, w); top row first."""

    def __init__(self, frame, capture, close=lambda: None, **info):
        self.frame, self.capture, self.close = frame, capture, close
        self.info = info


def emu_window(w, h, stencil_planes=0, accum=False):
    """A fresh machine and an RGB, double-buffered, z-buffered window."""
    _machine().reset()
    prefsize(w, h)
    winopen("vs_mesa")
    RGBmode()
    doublebuffer()
    if stencil_planes:
        stensize(stencil_planes)
    if accum:
        acsize(16)
    gconfig()
    zbuffer(TRUE)


def emu_depth(w, h):
    """The z bank as lrectread(SRC_ZBUFFER) gives it, mapped to [0, 1]."""
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, w - 1, h - 1).astype(np.float64)
    readsource(SRC_AUTO)
    return ((z + 0x800000) / 0xFFFFFF)[::-1]


def emu_stencil():
    """The stencil bank (inspection; IRIS GL has no stencil read-back)."""
    return _machine().current.fb.stencil[::-1].astype(np.int64)


def emu_rgb_capture():
    return "rgb", vgx_emulator.window_image()


def emu_matrices(view):
    """Projection and the ModelView after view() (called inside push/pop)."""
    mmode(MPROJECTION)
    proj = getmatrix()
    mmode(MVIEWING)
    pushmatrix()
    view()
    mv = getmatrix()
    popmatrix()
    return {"proj": proj, "view": mv}


def vertex_colours(nrm):
    """spheres-lmcolor's per-vertex RGBA: the normal mapped to 0..1, alpha 1."""
    c = np.ones(nrm.shape[:-1] + (4,))
    c[..., :3] = 0.5 + 0.5 * nrm
    return c


def emu_strips_object(parts, lmc=False):
    """An object with lmbind(MATERIAL) + quad strips (n3f, v3f per vertex);
    ``lmc``: lmcolor(LMC_AD) after each bind and c4f before each vertex."""
    obj = genobj()
    makeobj(obj)
    for mat, pos, nrm in parts:
        lmbind(MATERIAL, mat)
        if lmc:
            lmcolor(LMC_AD)
            for ps, ns, cs in zip(pos.tolist(), nrm.tolist(), vertex_colours(nrm).tolist()):
                bgnqstrip()
                for p, n, c in zip(ps, ns, cs):
                    c4f(c)
                    n3f(n)
                    v3f(p)
                endqstrip()
            continue
        for ps, ns in zip(pos.tolist(), nrm.tolist()):
            bgnqstrip()
            for p, n in zip(ps, ns):
                n3f(n)
                v3f(p)
            endqstrip()
    closeobj()
    return obj


def spheres_view():
    lookat(0.0, 3.0, 12.0, 0.0, 0.0, 0.0, 0)      # four_spheres.draw_scene's


def emu_spheres(w, h, depth_only=False, lmc=False):
    """spheres / spheres-depth / spheres-lmcolor: four_spheres' lighting,
    view and projection."""
    emu_window(w, h)
    mmode(MVIEWING)
    perspective(400, w / h, 1.0, 50.0)
    fs.define_lighting()
    lmdef(DEFLIGHT, fs.SUN, 0, [POSITION] + spheres_light() + [LMNULL])
    lmdef(DEFMATERIAL, GROUND_MAT, 0, [AMBIENT, 0.15, 0.15, 0.15, DIFFUSE, 0.55, 0.6, 0.5,
                                       SPECULAR, 0.0, 0.0, 0.0, LMNULL])
    lmbind(LMODEL, fs.MODEL)
    obj = emu_strips_object(spheres_scene(), lmc)
    if depth_only:
        wmpack(0)
    zmax = getgdesc(GD_ZMAX)

    def frame():
        if depth_only:
            zclear()
        else:
            czclear(0x00000000, zmax)
        pushmatrix()
        spheres_view()
        lmbind(LIGHT0, fs.SUN)
        callobj(obj)
        popmatrix()
        swapbuffers()

    capture = (lambda: ("depth", emu_depth(w, h))) if depth_only else emu_rgb_capture
    return Side(frame, capture, **emu_matrices(spheres_view))


def heidmann_opts(figure, w, h, objects=True, style=()):
    """The program's options, with --objects: its scene and shadow volumes
    recorded in IRIS GL objects on the untimed first frame, as the Mesa side
    keeps them in display lists (without: every vertex a v3f call in every
    frame, as the Mesa side then sends glVertex3f)."""
    return hv.parse(["--figure", figure, "--size", f"{w}x{h}"] + (["--objects"] if objects else [])
                    + list(style))


def emu_heidmann(w, h, figure, objects=True, style=()):
    """The program's main() up to its event loop; frame = its draw_scene()."""
    opts = heidmann_opts(figure, w, h, objects, style)
    hv.setup(opts)
    emu_window(w, h, stencil_planes=getgdesc(GD_BITS_STENCIL), accum=opts.jitter > 1)
    subpixel(TRUE)
    mmode(MVIEWING)
    hv.projection(w / h)
    hv.define_materials()
    for lt in hv.light:
        hv.define_light(lt)
    e, r = hv.eye, opts.ref
    return Side(lambda: hv.draw_scene(opts), emu_rgb_capture, opts=opts,
                **emu_matrices(lambda: lookat(e[0], e[1], e[2], r[0], r[1], r[2], 0)))


def emu_polygons_object(objs):
    """An object with every polygon of objs, positions only."""
    obj = genobj()
    makeobj(obj)
    for o in objs:
        for _, vs in o.draw_polys:
            bgnpolygon()
            for v in vs:
                v3f(v)
            endpolygon()
    closeobj()
    return obj


def emu_shadowmap(views, objs):
    """Per light: zclear, its perspective and lookat, the scene, depth only.
    frame(reads) appends each light's depth map to reads when given."""
    n = SHADOWMAP_SIZE
    emu_window(n, n)
    mmode(MVIEWING)
    wmpack(0)
    obj = emu_polygons_object(objs)
    mats = []
    for lpos, (fovy, near, far, tgt) in views:
        perspective(fovy, 1.0, near, far)
        mats.append(emu_matrices(lambda: lookat(*lpos, *tgt, 0)))

    def frame(reads=None):
        for lpos, (fovy, near, far, tgt) in views:
            zclear()
            perspective(fovy, 1.0, near, far)
            pushmatrix()
            lookat(lpos[0], lpos[1], lpos[2], tgt[0], tgt[1], tgt[2], 0)
            callobj(obj)
            popmatrix()
            if reads is not None:
                reads.append(emu_depth(n, n))
        swapbuffers()

    def capture():
        reads = []
        frame(reads)
        return "depth", mosaic(reads)

    return Side(frame, capture, mats=mats)


def emu_quads_object(pos, words):
    obj = genobj()
    makeobj(obj)
    for ps, ws in zip(pos.tolist(), words.tolist()):
        bgnpolygon()
        for p, c in zip(ps, ws):
            cpack(c)
            v3f(p)
        endpolygon()
    closeobj()
    return obj


def emu_fill(w, h, use_stencil):
    """fill-z: czclear, 32 z-tested Gouraud quads.  fill-stencil: czclear,
    sclear(0), the quads with ST_INCR on z-pass, zwritemask(0), wmpack(0)
    (czclear ignores the writemasks, so they are set once)."""
    emu_window(w, h, stencil_planes=8 if use_stencil else 0)
    ortho(-0.5, w - 0.5, -0.5, h - 0.5, -1.0, 1.0)      # MSINGLE
    obj = emu_quads_object(*fill_quads(w, h))
    zmax = getgdesc(GD_ZMAX)
    if use_stencil:
        zwritemask(0)
        wmpack(0)
        stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)

    def frame():
        czclear(0x00000000, zmax)
        if use_stencil:
            sclear(0)
        callobj(obj)
        swapbuffers()

    capture = (lambda: ("stencil", emu_stencil())) if use_stencil else emu_rgb_capture
    return Side(frame, capture, proj=getmatrix())


# ======================================================================================
# 3. the Mesa side (legacy OpenGL through OSMesa)
# ======================================================================================
class Mesa:
    """One OSMesa context (RGBA, 24-bit depth, 8 stencil, 16 accum) made
    current on a buffer of the size a workload needs.  close() destroys it
    and makes current again whatever OSMesa context was current before (a
    test module's, say)."""

    def __init__(self):
        if "OpenGL.GL" in sys.modules and os.environ.get("PYOPENGL_PLATFORM") != "osmesa":
            raise RuntimeError("PyOpenGL was already imported for another platform "
                               f"({os.environ.get('PYOPENGL_PLATFORM')!r})")
        from OpenGL import GL, arrays, osmesa
        self.GL, self.arrays, self.osmesa = GL, arrays, osmesa
        prev = osmesa.OSMesaGetCurrentContext()
        self.prev = (prev, osmesa.OSMesaGetColorBuffer(prev)) if prev else None
        self.ctx = osmesa.OSMesaCreateContextExt(osmesa.OSMESA_RGBA, 24, 8, 16, None)
        if not self.ctx:
            raise RuntimeError("OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16) failed")
        self.size = None
        self.use(64, 64)
        self.renderer = GL.glGetString(GL.GL_RENDERER).decode()
        self.version = GL.glGetString(GL.GL_VERSION).decode()

    def use(self, w, h):
        """Make the context current on a w x h RGBA buffer; default state."""
        if self.size != (w, h):
            self.buf = self.arrays.GLubyteArray.zeros((h, w, 4))
            if not self.osmesa.OSMesaMakeCurrent(self.ctx, self.buf,
                                                 self.GL.GL_UNSIGNED_BYTE, w, h):
                raise RuntimeError("OSMesaMakeCurrent failed")
            self.size = (w, h)
        gl_default_state(self.GL, w, h)

    def close(self):
        self.osmesa.OSMesaDestroyContext(self.ctx)
        if self.prev is not None:
            ctx, (w, h, _, ptr) = self.prev
            self.osmesa.OSMesaMakeCurrent(ctx, ptr, self.GL.GL_UNSIGNED_BYTE, w, h)

    def rgb(self):
        w, h = self.size
        return np.asarray(self.buf).reshape(h, w, 4)[::-1, :, :3].copy()

    def read(self, fmt, typ, dtype):
        w, h = self.size
        out = np.zeros((h, w), dtype)
        self.GL.glPixelStorei(self.GL.GL_PACK_ALIGNMENT, 1)
        self.GL.glReadPixels(0, 0, w, h, fmt, typ, out)
        return out[::-1]

    def depth(self):
        z = self.read(self.GL.GL_DEPTH_COMPONENT, self.GL.GL_UNSIGNED_INT, np.uint32)
        return (z >> 8).astype(np.float64) / 0xFFFFFF

    def stencil(self):
        g = self.GL
        return self.read(g.GL_STENCIL_INDEX, g.GL_UNSIGNED_BYTE, np.uint8).astype(np.int64)

    def check(self, where):
        err = self.GL.glGetError()
        if err:
            raise RuntimeError(f"OpenGL error {err:#x} in {where}")


def gl_default_state(g, w, h):
    """IRIS GL's state after winopen/gconfig where the two differ: z test
    LEQUAL, Gouraud; everything else off."""
    g.glViewport(0, 0, w, h)
    for cap in (g.GL_DEPTH_TEST, g.GL_STENCIL_TEST, g.GL_BLEND, g.GL_LIGHTING,
                g.GL_DITHER, g.GL_CULL_FACE, g.GL_NORMALIZE, g.GL_COLOR_MATERIAL):
        g.glDisable(cap)
    for i in range(8):
        g.glDisable(g.GL_LIGHT0 + i)
    g.glDepthFunc(g.GL_LEQUAL)
    g.glShadeModel(g.GL_SMOOTH)
    g.glColorMask(1, 1, 1, 1)
    g.glDepthMask(1)
    g.glStencilMask(0xFF)
    g.glStencilFunc(g.GL_ALWAYS, 0, 0xFF)
    g.glStencilOp(g.GL_KEEP, g.GL_KEEP, g.GL_KEEP)
    g.glBlendFunc(g.GL_ONE, g.GL_ZERO)
    g.glClearColor(0, 0, 0, 0)
    g.glClearDepth(1.0)
    g.glClearStencil(0)
    g.glMatrixMode(g.GL_PROJECTION)
    g.glLoadIdentity()
    g.glMatrixMode(g.GL_MODELVIEW)
    g.glLoadIdentity()


def gl_load(g, proj, view=None):
    """IRIS GL matrices as they are stored: same 16 floats."""
    g.glMatrixMode(g.GL_PROJECTION)
    g.glLoadMatrixf(np.ascontiguousarray(proj, np.float32))
    g.glMatrixMode(g.GL_MODELVIEW)
    if view is None:
        g.glLoadIdentity()
    else:
        g.glLoadMatrixf(np.ascontiguousarray(view, np.float32))


# -- IRIS GL lighting definitions -> GL fixed function ---------------------------------
def _v4(rgb, a=1.0):
    return (float(rgb[0]), float(rgb[1]), float(rgb[2]), float(a))


def gl_material(g, m):
    """An lmdef material: ALPHA is the diffuse alpha; SHININESS 0 turns the
    specular term off in IRIS GL (docs/semantics.md §9) but not in GL, so it is
    dropped then."""
    f = g.GL_FRONT_AND_BACK
    spec = m[L.SPECULAR] if m[L.SHININESS][0] != 0.0 else (0.0, 0.0, 0.0)
    g.glMaterialfv(f, g.GL_EMISSION, _v4(m[L.EMISSION]))
    g.glMaterialfv(f, g.GL_AMBIENT, _v4(m[L.AMBIENT]))
    g.glMaterialfv(f, g.GL_DIFFUSE, _v4(m[L.DIFFUSE], m[L.ALPHA][0]))
    g.glMaterialfv(f, g.GL_SPECULAR, _v4(spec))
    g.glMaterialf(f, g.GL_SHININESS, min(float(m[L.SHININESS][0]), 128.0))


def gl_light(g, slot, lt, model, position=None):
    """An lmdef light in GL_LIGHT0 + slot: LCOLOR is both the diffuse and the
    specular colour; the attenuation of IRIS GL's light model goes to each
    light.  The position is transformed by the current ModelView, as lmbind
    does."""
    li = g.GL_LIGHT0 + slot
    pos = lt[L.POSITION] if position is None else position
    g.glLightfv(li, g.GL_AMBIENT, _v4(lt[L.AMBIENT]))
    g.glLightfv(li, g.GL_DIFFUSE, _v4(lt[L.LCOLOR]))
    g.glLightfv(li, g.GL_SPECULAR, _v4(lt[L.LCOLOR]))
    g.glLightfv(li, g.GL_POSITION, tuple(float(v) for v in pos))
    g.glLightfv(li, g.GL_SPOT_DIRECTION, tuple(float(v) for v in lt[L.SPOTDIRECTION]))
    g.glLightf(li, g.GL_SPOT_EXPONENT, float(lt[L.SPOTLIGHT][0]))
    g.glLightf(li, g.GL_SPOT_CUTOFF, float(lt[L.SPOTLIGHT][1]))
    k0, k1 = model[L.ATTENUATION]
    g.glLightf(li, g.GL_CONSTANT_ATTENUATION, float(k0))
    g.glLightf(li, g.GL_LINEAR_ATTENUATION, float(k1))
    g.glLightf(li, g.GL_QUADRATIC_ATTENUATION, float(model[L.ATTENUATION2][0]))
    g.glEnable(li)


def gl_light_model(g, model):
    g.glLightModelfv(g.GL_LIGHT_MODEL_AMBIENT, _v4(model[L.AMBIENT]))
    g.glLightModeli(g.GL_LIGHT_MODEL_LOCAL_VIEWER, int(model[L.LOCALVIEWER][0] != 0.0))
    g.glLightModeli(g.GL_LIGHT_MODEL_TWO_SIDE, int(model[L.TWOSIDE][0] != 0.0))
    g.glEnable(g.GL_LIGHTING)


def defs():
    return _machine().defs


# -- display lists ------------------------------------------------------------------
def gl_list(g, build):
    """A display list compiled from build() (client arrays are copied in)."""
    lst = g.glGenLists(1)
    g.glNewList(lst, g.GL_COMPILE)
    build()
    g.glEndList()
    return lst


def gl_draw_arrays(g, mode, pos, nrm=None, words=None, rgba=None):
    """Vertex arrays: all of pos ((P, V, 3)) in one call for GL_QUADS, else
    one primitive (strip) per row; colours as packed words or float RGBA."""
    p = np.ascontiguousarray(pos.reshape(-1, 3), np.float32)
    g.glEnableClientState(g.GL_VERTEX_ARRAY)
    g.glVertexPointer(3, g.GL_FLOAT, 0, p)
    if nrm is not None:
        nr = np.ascontiguousarray(nrm.reshape(-1, 3), np.float32)
        g.glEnableClientState(g.GL_NORMAL_ARRAY)
        g.glNormalPointer(g.GL_FLOAT, 0, nr)
    if words is not None:
        c = np.ascontiguousarray(words.reshape(-1), np.uint32).view(np.uint8)
        g.glEnableClientState(g.GL_COLOR_ARRAY)
        g.glColorPointer(4, g.GL_UNSIGNED_BYTE, 0, c)      # 0xAABBGGRR = R, G, B, A bytes
    if rgba is not None:
        cf = np.ascontiguousarray(rgba.reshape(-1, 4), np.float32)
        g.glEnableClientState(g.GL_COLOR_ARRAY)
        g.glColorPointer(4, g.GL_FLOAT, 0, cf)
    nv = pos.shape[1]
    if mode == g.GL_QUADS:
        g.glDrawArrays(mode, 0, len(p))
    else:
        for s in range(pos.shape[0]):
            g.glDrawArrays(mode, s * nv, nv)
    for arr in (g.GL_VERTEX_ARRAY, g.GL_NORMAL_ARRAY, g.GL_COLOR_ARRAY):
        g.glDisableClientState(arr)


def gl_polygons(g, objs, materials=None):
    """Each object's polygons (GL_POLYGON, its flat normal), with its material."""
    for k, o in enumerate(objs):
        if materials is not None:
            gl_material(g, materials[k])
        for n, vs in o.draw_polys:
            g.glBegin(g.GL_POLYGON)
            g.glNormal3f(*n)
            for v in vs:
                g.glVertex3f(*v)
            g.glEnd()


class GLSide(Side):
    def __init__(self, mesa, frame, capture, lists):
        def close():
            for lst in lists:
                mesa.GL.glDeleteLists(lst, 1)
        super().__init__(frame, capture, close)


def gl_spheres(mesa, w, h, emu, depth_only=False, lmc=False):
    """The spheres scene: four_spheres' lighting read from the emulator's
    lmdef tables, the same strips in one list, the same matrices."""
    g = mesa.GL
    mesa.use(w, h)
    d = defs()
    model = d[DEFLMODEL][fs.MODEL]
    mats = {m: d[DEFMATERIAL][m] for m in (fs.SPHERE_MAT, GROUND_MAT)}

    def build():
        for mat, pos, nrm in spheres_scene():
            gl_material(g, mats[mat])
            gl_draw_arrays(g, g.GL_QUAD_STRIP, pos, nrm,
                           rgba=vertex_colours(nrm) if lmc else None)

    lst = gl_list(g, build)
    gl_load(g, emu.info["proj"])
    gl_light_model(g, model)
    if lmc:
        g.glColorMaterial(g.GL_FRONT_AND_BACK, g.GL_AMBIENT_AND_DIFFUSE)
        g.glEnable(g.GL_COLOR_MATERIAL)     # (gl_default_state turns it off)
    g.glEnable(g.GL_DEPTH_TEST)
    sun = d[DEFLIGHT][fs.SUN]
    view = np.ascontiguousarray(emu.info["view"], np.float32)

    def frame():
        if depth_only:
            g.glColorMask(0, 0, 0, 0)
            g.glClear(g.GL_DEPTH_BUFFER_BIT)
        else:
            g.glClear(g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT)
        g.glLoadMatrixf(view)
        gl_light(g, 0, sun, model)
        g.glCallList(lst)
        g.glFinish()

    capture = (lambda: ("depth", mesa.depth())) if depth_only else (lambda: ("rgb", mesa.rgb()))
    mesa.check("gl_spheres")
    return GLSide(mesa, frame, capture, [lst])


def volume_list(g, lpos, immediate=False, two_pass=False, infinite=False):
    """The program's shadow faces for a light, z-pass counting: ingoing ones
    with INCR, then the others with DECR (DrawShadowVolumes' order), or
    (``two_pass``) all of them culling back faces with INCR, then all
    culling front faces with DECR; (``infinite``) far corners at infinity,
    (x, y, z, 0).  A display list, or (``immediate``) the function sending
    them with glBegin/glVertex*fv/glEnd."""
    lpos = np.asarray(lpos, float)
    faces, ingo = hv.shadow_faces(lpos)
    hom = np.concatenate((faces, np.ones(faces.shape[:2] + (1,))), axis=2)
    if infinite:
        hom[:, 2:, :3] -= lpos
        hom[:, 2:, 3] = 0.0
    if two_pass:
        passes = [(g.GL_BACK, g.GL_INCR, hom), (g.GL_FRONT, g.GL_DECR, hom)]
    else:
        passes = [(None, g.GL_INCR, hom[ingo]), (None, g.GL_DECR, hom[~ingo])]

    def build(send_faces):
        for cull, op, fs in passes:
            if cull is not None:
                g.glEnable(g.GL_CULL_FACE)
                g.glCullFace(cull)
            g.glStencilOp(g.GL_KEEP, g.GL_KEEP, op)
            if len(fs):
                send_faces(fs)
        g.glDisable(g.GL_CULL_FACE)

    def arrays(fs):
        p = np.ascontiguousarray(fs.reshape(-1, 4), np.float32)
        g.glEnableClientState(g.GL_VERTEX_ARRAY)
        g.glVertexPointer(4, g.GL_FLOAT, 0, p)
        g.glDrawArrays(g.GL_QUADS, 0, len(p))
        g.glDisableClientState(g.GL_VERTEX_ARRAY)
    lists = {id(fs): fs.tolist() for _, _, fs in passes}

    def calls(fs):
        v4 = g.glVertex4fv
        for f in lists[id(fs)]:
            g.glBegin(g.GL_POLYGON)
            for v in f:
                v4(v)
            g.glEnd()
    if immediate:
        return lambda: build(calls)
    return gl_list(g, lambda: build(arrays))


def heidmann_light_positions(opts):
    """[frame][light] world positions: the base ones, or draw_scene's jitter."""
    base = [lt.position.copy() for lt in hv.light]
    if opts.jitter <= 1:
        return [base]
    offs = [hv.jitter_offsets(opts.jitter, hv.SOFT_RADIUS, b, np.zeros(3)) for b in base]
    return [[b + o[j] for b, o in zip(base, offs)] for j in range(opts.jitter)]


def gl_heidmann(mesa, w, h, emu, immediate=False, two_pass=False, infinite=False):
    """Heidmann's listing replayed in GL with the program's scene, lights and
    shadow faces, from display lists or (``immediate``) sent call by call in
    every frame (glBegin/glNormal3f/glVertex3f).  zclear in the lit pass
    clears nothing (zwritemask is 0 then), so it has no GL counterpart."""
    g = mesa.GL
    opts = emu.info["opts"]
    mesa.use(w, h)
    d = defs()
    model = d[DEFLMODEL][hv.LMODEL_INDEX]
    lights = [d[DEFLIGHT][lt.index] for lt in hv.light]

    def scene(k):
        def send():
            gl_polygons(g, hv.objects, [d[DEFMATERIAL][o.matl[k]] for o in hv.objects])
        return send if immediate else gl_list(g, send)
    amb, lit = scene(0), scene(1)
    positions = heidmann_light_positions(opts)
    vols = [[volume_list(g, p, immediate, two_pass, infinite) for p in frame_pos]
            for frame_pos in positions]

    def call(x):
        x() if immediate else g.glCallList(x)
    gl_load(g, emu.info["proj"], emu.info["view"])
    gl_light_model(g, model)
    g.glEnable(g.GL_DEPTH_TEST)
    n = len(positions)

    def one_frame(j):
        g.glDepthMask(1)
        g.glColorMask(1, 1, 1, 1)
        g.glClear(g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT)
        g.glDisable(g.GL_BLEND)
        for i, lt in enumerate(lights):               # ambient pass, all lights on
            gl_light(g, i, lt, model, (*positions[j][i], 1.0))
        call(amb)
        for i in range(1, len(lights)):
            g.glDisable(g.GL_LIGHT0 + i)
        for i, lt in enumerate(lights):
            gl_light(g, 0, lt, model, (*positions[j][i], 1.0))
            g.glClearStencil(hv.MYZERO)
            g.glClear(g.GL_STENCIL_BUFFER_BIT)
            g.glDepthMask(0)
            g.glColorMask(0, 0, 0, 0)
            g.glEnable(g.GL_STENCIL_TEST)
            g.glStencilFunc(g.GL_ALWAYS, 0, 0xFF)
            call(vols[j][i])
            g.glDepthMask(1)
            g.glColorMask(1, 1, 1, 1)
            g.glEnable(g.GL_BLEND)
            g.glBlendFunc(g.GL_ONE, g.GL_ONE)
            g.glStencilFunc(g.GL_EQUAL, hv.MYZERO, 0xFF)
            g.glStencilOp(g.GL_KEEP, g.GL_KEEP, g.GL_KEEP)
            call(lit)
        g.glDisable(g.GL_STENCIL_TEST)
        g.glDisable(g.GL_BLEND)

    def frame():
        for j in range(n):
            one_frame(j)
            if n > 1:
                g.glAccum(g.GL_LOAD if j == 0 else g.GL_ACCUM, 1.0 / n)
        if n > 1:
            g.glAccum(g.GL_RETURN, 1.0)
        g.glFinish()

    mesa.check("gl_heidmann")
    return GLSide(mesa, frame, lambda: ("rgb", mesa.rgb()),
                  [] if immediate else [amb, lit] + [v for fr in vols for v in fr])


def gl_shadowmap(mesa, views, objs, emu):
    g = mesa.GL
    n = SHADOWMAP_SIZE
    mesa.use(n, n)
    lst = gl_list(g, lambda: gl_polygons(g, objs))
    g.glEnable(g.GL_DEPTH_TEST)
    g.glColorMask(0, 0, 0, 0)

    def frame(reads=None):
        for m in emu.info["mats"]:
            g.glClear(g.GL_DEPTH_BUFFER_BIT)
            gl_load(g, m["proj"], m["view"])
            g.glCallList(lst)
            if reads is not None:
                reads.append(mesa.depth())
        g.glFinish()

    def capture():
        reads = []
        frame(reads)
        return "depth", mosaic(reads)

    mesa.check("gl_shadowmap")
    return GLSide(mesa, frame, capture, [lst])


def gl_fill(mesa, w, h, emu, use_stencil):
    g = mesa.GL
    mesa.use(w, h)
    pos, words = fill_quads(w, h)
    lst = gl_list(g, lambda: gl_draw_arrays(g, g.GL_QUADS, pos, words=words))
    gl_load(g, emu.info["proj"])
    g.glEnable(g.GL_DEPTH_TEST)
    bits = g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT
    if use_stencil:
        bits |= g.GL_STENCIL_BUFFER_BIT
        g.glStencilOp(g.GL_KEEP, g.GL_KEEP, g.GL_INCR)

    def frame():
        if use_stencil:                  # czclear ignores writemasks; glClear does not
            g.glColorMask(1, 1, 1, 1)
            g.glDepthMask(1)
            g.glDisable(g.GL_STENCIL_TEST)
        g.glClear(bits)
        if use_stencil:
            g.glColorMask(0, 0, 0, 0)
            g.glDepthMask(0)
            g.glEnable(g.GL_STENCIL_TEST)
        g.glCallList(lst)
        g.glFinish()

    capture = (lambda: ("stencil", mesa.stencil())) if use_stencil else \
        (lambda: ("rgb", mesa.rgb()))
    mesa.check("gl_fill")
    return GLSide(mesa, frame, capture, [lst])


# ======================================================================================
# 4. the workloads: (emulator side, Mesa side) for a size
# ======================================================================================
def build_pair(name, mesa, w, h):
    """Both sides of a workload, emulator first (the GL side reads its
    matrices and lighting definitions)."""
    if name.startswith("spheres"):
        depth, lmc = name == "spheres-depth", name == "spheres-lmcolor"
        emu = emu_spheres(w, h, depth, lmc)
        return emu, gl_spheres(mesa, w, h, emu, depth, lmc)
    if name.startswith("heidmann"):
        imm = name.endswith("-immediate")
        style = ("--two-pass", "--infinite") if ("1991" in name or name == "heidmann-spheres") \
            else ()
        figure = {"heidmann-soft": "6", "heidmann-spheres": "spheres"}.get(name, "5b")
        emu = emu_heidmann(w, h, figure, objects=not imm, style=style)
        return emu, gl_heidmann(mesa, w, h, emu, immediate=imm, two_pass=bool(style),
                                infinite=bool(style))
    if name == "shadowmap":
        objs, views = shadowmap_views()
        emu = emu_shadowmap(views, objs)
        return emu, gl_shadowmap(mesa, views, objs, emu)
    if name in ("fill-z", "fill-stencil"):
        st = name == "fill-stencil"
        emu = emu_fill(w, h, st)
        return emu, gl_fill(mesa, w, h, emu, st)
    raise ValueError(f"unknown workload {name!r}")


# ======================================================================================
# 5. images
# ======================================================================================
def mosaic(maps):
    """Four square maps as one image of the same size: 2 x 2, each halved."""
    half = [m[::2, ::2] for m in maps]
    return np.block([[half[0], half[1]], [half[2], half[3]]])


def to_rgb_pair(kind, a, b):
    """Both captures as (h, w, 3) uint8 with one scaling: depth grey from the
    nearest drawn depth (white) to the farthest (dark grey), cleared = black;
    stencil grey = count * 255 / the largest count."""
    if kind == "rgb":
        return a, b
    if kind == "depth":
        drawn = np.concatenate([a[a < 1.0], b[b < 1.0]])
        lo, hi = (float(drawn.min()), float(drawn.max())) if drawn.size else (0.0, 1.0)
        t = [np.clip((x - lo) / max(hi - lo, 1e-12), 0.0, 1.0) for x in (a, b)]
        grey = [np.where(x < 1.0, 255.0 - 204.0 * s, 0.0) for x, s in zip((a, b), t)]
    else:
        top = max(int(a.max()), int(b.max()), 1)
        grey = [255.0 * x / top for x in (a, b)]
    return tuple(np.repeat(np.round(x).astype(np.uint8)[..., None], 3, axis=2)
                 for x in grey)


def diff_fraction(a, b):
    """Fraction of pixels whose R, G or B differs by more than DIFF_THRESHOLD."""
    if a.shape != b.shape:
        return 1.0
    d = np.abs(a.astype(np.int16) - b.astype(np.int16)).max(axis=2)
    return float((d > DIFF_THRESHOLD).mean())


# ======================================================================================
# 6. the harness
# ======================================================================================
def timed(frame):
    t0 = time.perf_counter()
    frame()
    return time.perf_counter() - t0


def run_workload(name, mesa, w, h, reps, out=None):
    """Build, warm (one untimed frame each, then the captures, then the
    emulator's frames until its states' own kernel variants are in use),
    then reps alternating timed frames.  Returns a result dict."""
    emu, glside = build_pair(name, mesa, w, h)
    try:
        emu.frame()
        ka, a = emu.capture()
        # the states drawn on general kernel variants (a cache without their
        # own, vgx_emulator/specialise.py) ask for their own by the third
        # pass; the timed frames run on those
        for _ in range(config.SPECIALISE_AFTER - 1):
            emu.frame()
        specialise.wait(900)
        glside.frame()
        kb, b = glside.capture()
        te, tg = [], []
        for _ in range(reps):
            te.append(timed(emu.frame))
            tg.append(timed(glside.frame))
    finally:
        glside.close()
        _machine().reset()
    assert ka == kb, (ka, kb)
    ia, ib = to_rgb_pair(ka, a, b)
    if out is not None:
        for side, img in (("emulator", ia), ("mesa", ib)):
            write_png(Path(out) / f"{name}_{ia.shape[1]}x{ia.shape[0]}_{side}.png", img)
    return {"name": name, "size": (ia.shape[1], ia.shape[0]), "emu": te, "mesa": tg,
            "differs": diff_fraction(ia, ib), "images": (ia, ib)}


def ms(ts):
    return (f"{1000 * statistics.median(ts):.1f} "
            f"({1000 * min(ts):.1f}-{1000 * max(ts):.1f})")


def table_row(r):
    label = r["name"] + (" (x4 lights)" if r["name"] == "shadowmap" else "")
    ratio = statistics.median(r["emu"]) / statistics.median(r["mesa"])
    return (f"| {label} | {r['size'][0]}x{r['size'][1]} | {ms(r['emu'])} | {ms(r['mesa'])} "
            f"| {ratio:.1f} | {100 * r['differs']:.2f}% |")


def print_table(results):
    print(f"| workload | resolution | emulator ms median (min-max) | Mesa ms median (min-max) "
          f"| emulator/Mesa | pixels with RGB diff > {DIFF_THRESHOLD} |")
    print("|---|---|---|---|---|---|")
    for r in results:
        print(table_row(r))


# ======================================================================================
# 7. cold start and memory
# ======================================================================================
def cold_start():
    """first_light.cold_start(): a fresh process (vgx-run programs/four_spheres.py)
    to its PNG, empty then filled NUMBA_CACHE_DIR, then with Python's
    bytecode cached too; thread settings inherited."""
    import first_light
    with tempfile.TemporaryDirectory() as tmp:
        return first_light.cold_start(tmp)


def peak_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0   # KiB on Linux


# ======================================================================================
# 8. main
# ======================================================================================
def parse_sizes(text):
    out = []
    for s in text.split(","):
        w, h = (int(v) for v in s.lower().split("x"))
        if not (1 <= w <= 1280 and 1 <= h <= 1024):
            raise argparse.ArgumentTypeError(f"{s}: the VGX screen is 1280x1024")
        out.append((w, h))
    return out


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=parse_sizes, default=parse_sizes("640x480,1280x1024"))
    ap.add_argument("--only", action="append", choices=WORKLOADS, metavar="NAME",
                    help="run only this workload (repeatable): " + ", ".join(WORKLOADS))
    ap.add_argument("--reps", type=int, default=None, help="timed runs per side (5)")
    ap.add_argument("--quick", action="store_true", help="3 timed runs per side")
    ap.add_argument("--threads", type=int, default=None,
                    help="NUMBA_NUM_THREADS and LP_NUM_THREADS (set before start-up)")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "out" / "vs_mesa"))
    ap.add_argument("--no-cold", action="store_true", help="skip the cold-start runs")
    a = ap.parse_args(argv)
    a.reps = a.reps or (3 if a.quick else 5)
    a.only = a.only or WORKLOADS
    return a


def describe(mesa):
    import first_light
    import numba
    return (f"Machine: {first_light.machine_description()}\n"
            f"Mesa: {mesa.renderer}, {mesa.version}; LP_NUM_THREADS="
            f"{os.environ.get('LP_NUM_THREADS', 'default')}; numba threads "
            f"{numba.get_num_threads()}")


def run_all(a, mesa):
    results = []
    if "shadowmap" in a.only:
        results.append(run_workload("shadowmap", mesa, SHADOWMAP_SIZE, SHADOWMAP_SIZE,
                                    a.reps, a.out))
    for w, h in a.sizes:
        for name in a.only:
            if name not in ("shadowmap", "cold"):
                results.append(run_workload(name, mesa, w, h, a.reps, a.out))
    order = {n: i for i, n in enumerate(WORKLOADS)}
    return sorted(results, key=lambda r: (order[r["name"]], r["size"][0]))


def main(argv=None):
    a = parse(sys.argv[1:] if argv is None else argv)
    mesa = Mesa()
    print(describe(mesa))
    print(f"Repetitions: {a.reps} per side, alternating, after one untimed run each; "
          f"images in {a.out}")
    print()
    print_table(run_all(a, mesa))
    if "cold" in a.only and not a.no_cold:
        empty, filled, bytecode = cold_start()
        print()
        print(f"Cold start (fresh process to the four_spheres PNG, emulator only): "
              f"empty numba cache {empty:.2f} s, filled cache {filled:.2f} s "
              f"({bytecode:.2f} s with Python's bytecode cached too)")
    print(f"Peak memory of this process (ru_maxrss, emulator + Mesa): {peak_mib():.0f} MiB")
    mesa.close()


if __name__ == "__main__":
    main()
