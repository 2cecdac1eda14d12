"""Heidmann (1991), "Real shadows, real time" (IRIS Universe): stencil shadow
volumes on the VGX, several coloured lights, soft shadows by accumulation.

The algorithm, as the article states it:
1. draw the whole scene with the emitted and ambient material components
   only (all lights bound, for their ambient terms), setting the z-buffer;
2. for each light: sclear(MYZERO); with z and colour writes off, draw the
   faces of the shadow volumes (silhouette edges of every caster extruded
   away from the light), ST_INCR on faces going into shadow (front-facing
   seen from the eye), ST_DECR on faces going out (back-facing);
3. redraw the scene with the diffuse and specular components of that light
   only, added with blendfunction(BF_ONE, BF_ONE), where the stencil still
   holds MYZERO (in as many times as out: not in shadow).

Figures (``--figure``):
  1e     a triangle lit by one point light casts its shadow on a surface
  4a-4d  five objects; red, green, blue, yellow lights added one at a time
  5b     the full scene (eight objects) under all four coloured lights
  6      soft shadows: 32 images with the light jittered over a disc,
         accumulated (acsize(16), AC_CLEAR_ACCUMULATE / AC_ACCUMULATE, then
         AC_RETURN 1/32); ``--jitter N`` for fewer images
  eyein  the eye inside the crate's shadow volume: the z-pass count of the
         article is off by one (``--zfail`` fixes it, below)
  spheres  not a figure of the article: four spheres on the ground under one
         light, the scene a side-by-side harness of 1991-style ports draws
         (benchmarks/vs_mesa.py, workload heidmann-spheres)

Options: ``--zfail`` (depth-fail counting), ``--jitter N``, ``--size WxH``,
``--volumes-only I`` (stop after the volume pass of light I: the stencil
then holds MYZERO + the number of volumes each visible point lies in),
``--objects`` (what DrawObjects and DrawShadowVolumes send is recorded once
in IRIS GL objects, makeobj/closeobj, and replayed with callobj: the same
calls, as a port tuned for the VGX would keep its static geometry; the
volumes are recorded per light position.  The images are the same),
``--two-pass`` (the volume faces drawn twice, as many ports of the time
did: ``backface(TRUE)`` with ST_INCR counts the faces turned towards the
eye, then ``frontface(TRUE)`` with ST_DECR those turned away; the same
counts as choosing the operation per face), ``--infinite`` (the volumes
extruded to infinity: each far corner sent as ``v4f(d, 0)``, its direction
from the light, under a perspective whose far plane is at infinity, loaded
with ``loadmatrix``; z-pass only).

From the listing, in its order and with its names: the stencil check and
``stensize(getgdesc(GD_BITS_STENCIL))``, gconfig, ``zbuffer(TRUE)``; the
ambient pass (``lmbind(LIGHT0+i, light[i].index)`` for i < nLights,
``zwritemask(0xffffffff)``, ``czclear(0x00000000, getgdesc(GD_ZMAX))``,
``blendfunction(BF_ONE, BF_ZERO)``, ``DrawObjects(matl_emitambient)``,
``lmbind(LIGHT0+i, 0)``); per light ``lmbind(LIGHT0, light[i].index)``,
``sclear(MYZERO)``, ``zwritemask(0x0)``, ``wmpack(0x0)``, the loop
``for iEdge ...: v3 = ...; v4 = ...; ingoing = ...;
stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ingoing ? ST_INCR : ST_DECR);
bgnpolygon() ...``; then ``zclear(getgdesc(GD_ZMAX))``, ``zwritemask``,
``wmpack``, ``blendfunction(BF_ONE, BF_ONE)``,
``stencil(TRUE, MYZERO, SF_EQUAL, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)``,
``DrawObjects(matl_diffspec)``, ``lmbind(LIGHT0, 0)``.  MYZERO = 128.

Errata of the scan: ``LIGHTO`` is LIGHT0, ``Oxff`` is 0xff; the masks
``0xfffffffff`` (nine digits) are 0xffffffff; the missing ``;`` after the
stencil call and the closing braces are restored.

Reconstructed (the listing elides or the scan lost it):
- ``v3``, ``v4``: the edge's end points pushed away from the light to a fixed
  distance EXTRUDE from it ("a length which will extend through every object
  potentially in shadow"): 60 units, past the ground everywhere and still
  inside the far clipping plane (needed by the z-fail variant).
- The edges: an adjacency structure (each edge with the one or two polygons
  it bounds) built once per object with numpy; per light, a polygon faces
  the light when its plane has the light on its outer side; an edge is a
  silhouette when it bounds one polygon only or its two polygons face the
  light differently.  The edge is taken in the direction it has in its
  light-facing polygon and the face is drawn the other way round
  (b, a, v3, v4), so its normal points out of the volume (the article's
  fig. 2 rule, which reverses for an edge of a polygon facing away);
  ``ingoing`` = the face is front-facing from the eye (normal towards the
  eye), as the article says.  The ground only receives shadows (it can cast
  none on anything above it).
- ``DrawObjects(matl)``: ``matl_emitambient`` (0) and ``matl_diffspec`` (1)
  select one of the two material definitions each object has: emission +
  ambient (diffuse, specular 0) for the ambient pass, diffuse + specular
  (ambient 0) for the light passes, so the model ambient is added once.
- The lit pass keeps the listing as scanned: ``zclear(getgdesc(GD_ZMAX))``
  (zclear takes no argument; the extra one is ignored, docs/semantics.md §1), then
  ``zwritemask(0xffffffff)`` and the default ZF_LEQUAL.  Read alone the
  comment "Reset the z-buffer contents" suggests the z of the ambient pass is
  lost, which would let every surface hidden behind a lit visible point add
  its colour under the MYZERO mask (the mask holds the count of the visible
  surface only).  It is not lost: zclear honours zwritemask, and the volume
  pass has just set ``zwritemask(0x0)``, so the zclear clears nothing.  The
  lit pass then redraws the same surfaces against the ambient pass's z:
  the visible surface passes ZF_LEQUAL as equal (the same vertices through
  the same matrices give the same z), everything behind it fails.  ZF_EQUAL
  would select the same pixels; ZF_LEQUAL is what the listing leaves set,
  so no zfunction call is added.
- After the loop: ``stencil(FALSE, ...)``, ``wmpack(0xffffffff)``,
  ``zwritemask(0xffffffff)``, ``blendfunction(BF_ONE, BF_ZERO)``, so the next
  frame's ambient pass is drawn unmasked.
- ``subpixel(TRUE)`` after gconfig: shadow faces are long slivers on the
  screen; with the default vertex snapping to pixel centres a sliver can
  fold over its neighbour and be counted twice (a dashed line of wrong
  counts; seen in the eyein view).  Sub-pixel vertices keep the mesh of
  volume faces watertight.
- The stencil call is made only when ``ingoing`` changes, the faces being
  drawn going-into-shadow first (the article's other way of keeping the
  count off the lower clamp): each stencil call ends the current batch of
  primitives, which costs far more than the call itself.
- Scene, lights, materials, viewpoint: the article gives none.  Objects are
  closed polyhedra with counter-clockwise outward polygons and flat normals
  (a box, a pillar, a faceted sphere, a torus that shadows itself, a
  pyramid; for 5b also a floating slab, a second box and a hexagonal
  prism), resting 0.005 above a 24 x 24 grid ground so no surface is
  coplanar with another (the lit pass would add both).  Local point lights,
  no attenuation.  Soft shadows: the light's 32 positions on a disc of
  radius 0.7 perpendicular to the light direction (golden-angle spiral).

The z-fail variant (``--zfail``): the z-pass count starts at the eye, so an
eye inside a volume starts one short and every pixel of that volume's
neighbourhood is inverted (fig. ``eyein``).  Counting the faces *behind* the
visible point instead (Carmack's reverse / Bilodeau-Songy) does not depend
on where the eye is, but needs closed volumes: the caps (the light-facing
polygons of each caster as the near cap, its polygons facing away pushed to
EXTRUDE as the far cap; for the open triangle of 1e the triangle and its
pushed copy) are drawn with the sides, and the stencil call becomes
``stencil(TRUE, 0, SF_ALWAYS, 0xff, ST_KEEP, ingoing ? ST_DECR : ST_INCR,
ST_KEEP)`` (the *pass* operation, applied when the z test fails).  The near
cap coincides with the visible surface of the caster, so this pass runs
with ``zfunction(ZF_LESS)``: a lit caster point then counts its own cap
(z fails as equal) against the exit behind it.  The far cap must not be
clipped: EXTRUDE keeps every volume inside the far plane.

Written as an IRIS GL program of 1991 would be: configuration, an event
loop on REDRAW, swapbuffers.
"""
import argparse
import math
import sys

import numpy as np

from irisgl import *

FIGURES = [
    {"name": "1e", "args": ["--figure", "1e"],
     "caption": "Heidmann 1991, fig. 1e: a triangle lit by one point light; where the "
                "viewing ray went into its shadow volume more often than out, the "
                "surface behind is in shadow (stencil shadow volume, z-pass)."},
    {"name": "4a", "args": ["--figure", "4a"],
     "caption": "Heidmann 1991, fig. 4a: the scene with one (red) light: ambient pass, "
                "then the red light's diffuse and specular where the stencil is MYZERO."},
    {"name": "4b", "args": ["--figure", "4b"],
     "caption": "Heidmann 1991, fig. 4b: a green light added (its own shadow volumes, "
                "added with blendfunction(BF_ONE, BF_ONE))."},
    {"name": "4c", "args": ["--figure", "4c"],
     "caption": "Heidmann 1991, fig. 4c: a blue light added from behind the scene."},
    {"name": "4d", "args": ["--figure", "4d"],
     "caption": "Heidmann 1991, fig. 4d: four coloured lights; each shadow lacks only "
                "the colour of the light it hides."},
    {"name": "5b", "args": ["--figure", "5b"],
     "caption": "Heidmann 1991, fig. 5b: the full scene (eight objects, shadows on the "
                "ground and on each other) under four coloured lights."},
    {"name": "6", "args": ["--figure", "6"],
     "caption": "Heidmann 1991, fig. 6: soft shadows, 32 images with the light jittered "
                "over a disc accumulated (acbuf AC_ACCUMULATE, then AC_RETURN 1/32)."},
    {"name": "eyein-zpass", "args": ["--figure", "eyein"],
     "caption": "The eye inside the crate's shadow volume, the article's z-pass count: "
                "it starts one short, so the shadow is inverted (lit ground drawn dark)."},
    {"name": "eyein-zfail", "args": ["--figure", "eyein", "--zfail"],
     "caption": "The same view counting the capped volume faces behind each point "
                "(z-fail): correct with the eye inside the volume."},
]

WIDTH, HEIGHT = 640, 480
MYZERO = 128
EXTRUDE = 60.0                      # shadow faces reach this far from the light
LIFT = 0.005                        # objects rest just above the ground
NEAR, FAR = 0.5, 150.0
FOVY = 450                          # tenths of a degree

matl_emitambient, matl_diffspec = 0, 1
LMODEL_INDEX = 1
MODEL_AMBIENT = 0.25

# viewpoints: eye, reference point
VIEWS = {
    "default": ((0.0, 9.0, 16.0), (0.0, 1.0, -0.5)),
    "high": ((2.0, 13.0, 15.0), (0.0, 0.5, -0.5)),
    "eyein": ((-1.2, 1.4, 0.2), (6.0, 0.0, -1.0)),
}

# light definitions: colour, position (w = 1: local lights)
LIGHT_DEFS = {
    "red":    ((0.70, 0.15, 0.12), (-6.0, 10.0, 6.0)),
    "green":  ((0.15, 0.65, 0.18), (7.0, 9.0, 5.0)),
    "blue":   ((0.18, 0.25, 0.75), (1.0, 11.0, -9.0)),
    "yellow": ((0.55, 0.50, 0.15), (9.0, 6.0, -1.0)),
    "white":  ((0.85, 0.85, 0.80), (-5.0, 11.0, 5.0)),
    "low":    ((0.85, 0.85, 0.80), (-9.0, 4.5, 0.0)),
}

FIGURE_SETUP = {     # scene, lights, view
    "1e": ("triangle", ["white"], "default"),
    "4a": ("five", ["red"], "default"),
    "4b": ("five", ["red", "green"], "default"),
    "4c": ("five", ["red", "green", "blue"], "default"),
    "4d": ("five", ["red", "green", "blue", "yellow"], "default"),
    "5b": ("full", ["red", "green", "blue", "yellow"], "high"),
    "6": ("five", ["white"], "default"),
    "eyein": ("five", ["low"], "eyein"),
    "spheres": ("spheres", ["white"], "default"),
}
SOFT_RADIUS = 0.7


# ---------------------------------------------------------------------------
# objects: vertices, counter-clockwise outward polygons, edge adjacency
class Object:
    def __init__(self, name, verts, polys, diffuse, specular=(0.3, 0.3, 0.3),
                 shininess=20.0, casts=True):
        self.name = name
        self.verts = np.asarray(verts, float)
        self.polys = [list(p) for p in polys]
        self.diffuse, self.specular, self.shininess = diffuse, specular, shininess
        self.casts = casts
        self.matl = [0, 0]
        v = self.verts
        # flat normals (Newell) and a point of each polygon's plane
        n = np.zeros((len(self.polys), 3))
        for k, p in enumerate(self.polys):
            a = v[p]
            b = np.roll(a, -1, axis=0)
            n[k] = np.cross(a, b).sum(axis=0)
        self.normals = n / np.linalg.norm(n, axis=1)[:, None]
        self.p0 = v[[p[0] for p in self.polys]]
        # directed edges of every polygon, then each undirected edge once with
        # the polygon(s) it bounds: (a, b) as in polygon e_p0; e_p1 = -1 when it
        # bounds only one polygon
        ea = np.concatenate([p for p in self.polys])
        eb = np.concatenate([np.roll(p, -1) for p in self.polys])
        ep = np.concatenate([[k] * len(p) for k, p in enumerate(self.polys)])
        nv = len(v)
        fwd = ea * nv + eb
        rev = eb * nv + ea
        order = np.argsort(fwd)
        pos = np.clip(np.searchsorted(fwd[order], rev), 0, len(fwd) - 1)
        twin = np.where(fwd[order][pos] == rev, order[pos], -1)
        keep = (twin < 0) | (ea < eb)
        self.e_a, self.e_b, self.e_p0 = ea[keep], eb[keep], ep[keep]
        self.e_p1 = np.where(twin[keep] >= 0, ep[twin[keep]], -1)
        self.closed = bool((twin >= 0).all())
        # lists for drawing
        self.draw_polys = [(tuple(self.normals[k]), [tuple(v[i]) for i in p])
                           for k, p in enumerate(self.polys)]

    def facing(self, lpos):
        """Polygons whose outer side has the light."""
        return ((lpos - self.p0) * self.normals).sum(axis=1) > 0


def box(name, x0, x1, y0, y1, z0, z1, diffuse, **kw):
    v = [(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (z0, z1)]
    # index = 4*ix + 2*iy + iz
    polys = [(0, 1, 3, 2), (4, 6, 7, 5),          # -x, +x
             (0, 4, 5, 1), (2, 3, 7, 6),          # -y, +y
             (0, 2, 6, 4), (1, 5, 7, 3)]          # -z, +z
    return Object(name, v, polys, diffuse, **kw)


def sphere(name, c, r, slices, stacks, diffuse, **kw):
    v = [(c[0], c[1] - r, c[2])]
    for i in range(1, stacks):
        phi = math.pi * i / stacks - math.pi / 2
        for j in range(slices):
            th = 2 * math.pi * j / slices
            v.append((c[0] + r * math.cos(phi) * math.cos(th), c[1] + r * math.sin(phi),
                      c[2] - r * math.cos(phi) * math.sin(th)))
    v.append((c[0], c[1] + r, c[2]))
    top = len(v) - 1

    def ring(i, j):
        return 1 + (i - 1) * slices + j % slices
    polys = [(0, ring(1, j + 1), ring(1, j)) for j in range(slices)]
    for i in range(1, stacks - 1):
        polys += [(ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j))
                  for j in range(slices)]
    polys += [(ring(stacks - 1, j), ring(stacks - 1, j + 1), top) for j in range(slices)]
    return Object(name, v, polys, diffuse, **kw)


def torus(name, c, big, small, n1, n2, diffuse, **kw):
    v = []
    for i in range(n1):
        th = 2 * math.pi * i / n1
        for j in range(n2):
            ph = 2 * math.pi * j / n2
            rr = big + small * math.cos(ph)
            v.append((c[0] + rr * math.cos(th), c[1] + small * math.sin(ph),
                      c[2] - rr * math.sin(th)))

    def k(i, j):
        return (i % n1) * n2 + j % n2
    polys = [(k(i, j), k(i + 1, j), k(i + 1, j + 1), k(i, j + 1))
             for i in range(n1) for j in range(n2)]
    return Object(name, v, polys, diffuse, **kw)


def prism(name, c, r, h, n, diffuse, **kw):
    """An n-sided upright prism, base at c[1]."""
    v = []
    for y in (c[1], c[1] + h):
        for j in range(n):
            th = 2 * math.pi * j / n
            v.append((c[0] + r * math.cos(th), y, c[2] - r * math.sin(th)))
    polys = [tuple(range(n - 1, -1, -1)), tuple(range(n, 2 * n))]
    polys += [(j, (j + 1) % n, n + (j + 1) % n, n + j) for j in range(n)]
    return Object(name, v, polys, diffuse, **kw)


def pyramid(name, c, half, h, diffuse, **kw):
    x, y, z = c
    v = [(x - half, y, z + half), (x + half, y, z + half), (x + half, y, z - half),
         (x - half, y, z - half), (x, y + h, z)]
    polys = [(3, 2, 1, 0), (0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    return Object(name, v, polys, diffuse, **kw)


def ground(n=24, half=12.0):
    xs = np.linspace(-half, half, n + 1)
    v = [(x, 0.0, z) for z in xs for x in xs]
    polys = [(r * (n + 1) + c, (r + 1) * (n + 1) + c, (r + 1) * (n + 1) + c + 1,
              r * (n + 1) + c + 1) for r in range(n) for c in range(n)]
    return Object("ground", v, polys, (0.75, 0.75, 0.72), specular=(0.1, 0.1, 0.1),
                  shininess=10.0, casts=False)


def make_scene(kind):
    L = LIFT
    objs = [ground()]
    if kind == "triangle":
        objs.append(Object("triangle", [(-3.0, 3.2, 1.5), (2.5, 3.6, 2.0), (-0.5, 3.0, -3.0)],
                           [(0, 1, 2)], (0.9, 0.75, 0.2)))
        return objs
    if kind == "spheres":
        return objs + [
            sphere(f"sphere{k}", (x, 1.0 + LIFT, z), 1.0, 20, 10, col,
                   specular=(0.5, 0.5, 0.5), shininess=30.0)
            for k, (x, z, col) in enumerate([(-3.0, 2.0, (0.9, 0.3, 0.3)),
                                             (3.0, 2.0, (0.3, 0.8, 0.3)),
                                             (-3.0, -3.0, (0.3, 0.4, 0.9)),
                                             (3.0, -3.0, (0.9, 0.8, 0.3))])]
    objs += [
        box("crate", -4.0, -2.0, L, 2.0 + L, -1.0, 1.0, (0.85, 0.5, 0.2)),
        box("pillar", 2.0, 3.0, L, 5.0 + L, -3.0, -2.0, (0.55, 0.7, 0.9)),
        sphere("sphere", (0.5, 1.2 + L, 2.5), 1.2, 20, 10, (0.9, 0.9, 0.9),
               specular=(0.6, 0.6, 0.6), shininess=40.0),
        torus("torus", (-1.5, 0.45 + L, -3.5), 1.4, 0.45, 20, 8, (0.4, 0.8, 0.4)),
        pyramid("pyramid", (4.5, L, 2.5), 1.0, 2.5, (0.7, 0.45, 0.8)),
    ]
    if kind == "full":
        objs += [
            box("slab", -6.0, -3.0, 3.0, 3.3, 2.0, 4.5, (0.8, 0.8, 0.5)),
            box("block", 5.0, 7.0, L, 1.2 + L, -5.0, -3.5, (0.9, 0.35, 0.35)),
            prism("hexprism", (-6.0, L, -4.0), 0.9, 3.0, 6, (0.35, 0.6, 0.75)),
        ]
    return objs


# ---------------------------------------------------------------------------
# lights
class Light:
    def __init__(self, index, color, position):
        self.index = index
        self.color = color
        self.position = np.array(position, float)


objects = []
light = []
nLights = 0
eye = np.zeros(3)


def define_materials():
    for k, obj in enumerate(objects):
        d, s = obj.diffuse, obj.specular
        obj.matl = [2 * k + 1, 2 * k + 2]
        lmdef(DEFMATERIAL, obj.matl[matl_emitambient], 0,
              [EMISSION, 0.0, 0.0, 0.0, AMBIENT, d[0], d[1], d[2],
               DIFFUSE, 0.0, 0.0, 0.0, SPECULAR, 0.0, 0.0, 0.0, LMNULL])
        lmdef(DEFMATERIAL, obj.matl[matl_diffspec], 0,
              [EMISSION, 0.0, 0.0, 0.0, AMBIENT, 0.0, 0.0, 0.0, DIFFUSE, d[0], d[1], d[2],
               SPECULAR, s[0], s[1], s[2], SHININESS, obj.shininess, LMNULL])
    lmdef(DEFLMODEL, LMODEL_INDEX, 0, [AMBIENT, MODEL_AMBIENT, MODEL_AMBIENT, MODEL_AMBIENT,
                                       LOCALVIEWER, 1.0, LMNULL])


def define_light(lt):
    p = lt.position
    lmdef(DEFLIGHT, lt.index, 0, [LCOLOR, lt.color[0], lt.color[1], lt.color[2],
                                  POSITION, p[0], p[1], p[2], 1.0, LMNULL])


use_objects = False     # --objects (set by setup)
two_pass = False        # --two-pass
infinite = False        # --infinite
_compiled = {}          # --objects: what a drawing function sent, as an IRIS GL object


def _replayed(key, draw, *args):
    """--objects: callobj of the object holding draw(*args)'s calls, recorded
    with makeobj/closeobj on first use; without --objects, draw(*args)."""
    if not use_objects:
        draw(*args)
        return
    obj = _compiled.get(key)
    if obj is None:
        obj = _compiled[key] = genobj()
        makeobj(obj)
        draw(*args)
        closeobj()
    callobj(obj)


def DrawObjects(matl):
    _replayed(("objects", matl), _draw_objects, matl)


def _draw_objects(matl):
    for obj in objects:
        lmbind(MATERIAL, obj.matl[matl])
        for n, vs in obj.draw_polys:
            bgnpolygon()
            n3f(n)
            for v in vs:
                v3f(v)
            endpolygon()


# ---------------------------------------------------------------------------
# shadow volumes (numpy over each whole mesh)
def push(p, lpos):
    """Points moved along the ray from the light to distance EXTRUDE."""
    d = p - lpos
    return lpos + d * (EXTRUDE / np.linalg.norm(d, axis=-1, keepdims=True))


def shadow_faces(lpos):
    """Faces of every shadow volume for a light at lpos: (n, 4, 3) corners
    (b, a, v3, v4) and ingoing (n,) (front-facing from the eye)."""
    quads = []
    for obj in objects:
        if not obj.casts:
            continue
        f = obj.facing(lpos)
        p1 = obj.e_p1
        f1 = np.where(p1 >= 0, f[np.maximum(p1, 0)], ~f[obj.e_p0])
        sil = f[obj.e_p0] != f1                 # one polygon, or facing differently
        lit0 = f[obj.e_p0][sil]
        a = np.where(lit0, obj.e_a[sil], obj.e_b[sil])   # direction in the lit polygon
        b = np.where(lit0, obj.e_b[sil], obj.e_a[sil])
        va, vb = obj.verts[a], obj.verts[b]
        quads.append(np.stack([vb, va, push(va, lpos), push(vb, lpos)], axis=1))
    q = np.concatenate(quads) if quads else np.zeros((0, 4, 3))
    ns = np.cross(q[:, 1] - q[:, 0], q[:, 2] - q[:, 1])   # (a - b) x (v3 - a), outward
    ingoing = ((eye - q[:, 1]) * ns).sum(axis=1) > 0
    return q, ingoing


def cap_polygons(lpos):
    """The caps closing each volume (z-fail): polygons as vertex arrays with
    outward (out of the volume) orientation, and ingoing per polygon."""
    caps = []
    for obj in objects:
        if not obj.casts:
            continue
        f = obj.facing(lpos)
        for k, p in enumerate(obj.polys):
            v = obj.verts[p]
            if obj.closed:
                caps.append(v if f[k] else push(v, lpos))   # near cap / far cap
            else:                  # an open sheet: it and its pushed copy
                near = v if f[k] else v[::-1]
                caps.append(near)
                caps.append(push(near, lpos)[::-1])
    out = []
    for v in caps:                 # fans, so a non-planar far cap stays consistent
        for t in range(1, len(v) - 1):
            tri = np.array([v[0], v[t], v[t + 1]])
            n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
            out.append((tri, float(np.dot(eye - tri[0], n)) > 0))
    return out


def DrawShadowVolumes(lpos, zfail):
    _replayed(("volumes", tuple(lpos), zfail), _draw_shadow_volumes, lpos, zfail)


def _draw_volume_faces(faces, lpos):
    """Each face as a polygon: b, a and their pushed copies, or (--infinite)
    b, a and the directions from the light as points at infinity."""
    for v1, v2, v3, v4 in faces:
        bgnpolygon()
        v3f(v1)
        v3f(v2)
        if infinite:
            d3, d4 = v3 - lpos, v4 - lpos
            v4f((d3[0], d3[1], d3[2], 0.0))
            v4f((d4[0], d4[1], d4[2], 0.0))
        else:
            v3f(v3)
            v3f(v4)
        endpolygon()


def _draw_shadow_volumes(lpos, zfail):
    if two_pass and not zfail:
        faces, _ = shadow_faces(lpos)
        for cull, op in ((backface, ST_INCR), (frontface, ST_DECR)):
            cull(TRUE)                           # faces towards the eye go in: +1,
            stencil(TRUE, 0, SF_ALWAYS, 0xff,    # those turned away come out: -1
                    ST_KEEP, ST_KEEP, op)
            _draw_volume_faces(faces, lpos)
            cull(FALSE)
        return
    faces, ingo = shadow_faces(lpos)
    order = np.argsort(~ingo, kind="stable")     # going-into-shadow faces first
    faces, ingo = faces[order], ingo[order]
    nEdges = len(faces)
    if zfail:
        zfunction(ZF_LESS)
    last = None
    for iEdge in range(nEdges):                  # For each edge in the scene,
        v1, v2, v3, v4 = faces[iEdge]            # project shadow face from this edge.
        ingoing = bool(ingo[iEdge])
        if ingoing != last:                      # (set only when it changes)
            last = ingoing
            if not zfail:
                stencil(TRUE, 0, SF_ALWAYS, 0xff,    # Write stencil unconditionally,
                        ST_KEEP, ST_KEEP,            # do nothing if zbuffer test fails,
                        ST_INCR if ingoing else ST_DECR)  # otherwise, add or subtract one.
            else:
                stencil(TRUE, 0, SF_ALWAYS, 0xff,    # z-fail: count the faces behind
                        ST_KEEP, ST_DECR if ingoing else ST_INCR,   # the visible point,
                        ST_KEEP)                     # nothing for those in front.
        _draw_volume_faces(faces[iEdge:iEdge + 1], lpos)   # Draw the shadow volume face.
    if zfail:                                    # the caps closing the volumes
        caps = sorted(cap_polygons(lpos), key=lambda c: not c[1])
        for tri, ingoing in caps:
            if ingoing != last:
                last = ingoing
                stencil(TRUE, 0, SF_ALWAYS, 0xff,
                        ST_KEEP, ST_DECR if ingoing else ST_INCR,
                        ST_KEEP)
            bgnpolygon()
            for v in tri:
                v3f(v)
            endpolygon()
        zfunction(ZF_LEQUAL)


# ---------------------------------------------------------------------------
def draw_frame(opts):
    """One shadowed image of the scene (the listing)."""
    pushmatrix()
    lookat(eye[0], eye[1], eye[2], opts.ref[0], opts.ref[1], opts.ref[2], 0)
    lmbind(LMODEL, LMODEL_INDEX)
    # Draw scene w/ ambient light, setting z-buffer.
    for i in range(nLights):                      # Turn on all the lights for
        lmbind(LIGHT0 + i, light[i].index)        # ambient light value calculation.
    zwritemask(0xffffffff)                        # We do want to set z values,
    czclear(0x00000000, getgdesc(GD_ZMAX))        # using the full z range.
    blendfunction(BF_ONE, BF_ZERO)                # No alpha blending.
    DrawObjects(matl_emitambient)                 # Draw all objects using only ambient
    for i in range(nLights):                      # and emitted material components.
        lmbind(LIGHT0 + i, 0)                     # Turn off all the lights when done.
    # Accumulate effects of each light in the scene in turn.
    for i in range(nLights):
        if opts.volumes_only is not None and i != opts.volumes_only:
            continue
        # Draw faces of shadow volumes, setting stencil planes.
        lmbind(LIGHT0, light[i].index)            # Turn on just this light.
        sclear(MYZERO)                            # Reset the stencil values to "zero"
        zwritemask(0x0)                           # We aren't changing any z values
        wmpack(0x0)                               # or any color values.
        DrawShadowVolumes(light[i].position, opts.zfail)
        if opts.volumes_only is not None:
            lmbind(LIGHT0, 0)
            break
        # Add highlights for this light, constrained by stencil mask to unshadowed areas.
        zclear(getgdesc(GD_ZMAX))                 # Reset the z-buffer contents.
        zwritemask(0xffffffff)                    # Enable writing to the z-buffer and
        wmpack(0xffffffff)                        # the color planes.  Set up to add
        blendfunction(BF_ONE, BF_ONE)             # highlight color to existing values.
        stencil(TRUE, MYZERO, SF_EQUAL, 0xff,     # Constrain drawing to "zero" areas
                ST_KEEP, ST_KEEP, ST_KEEP)        # of stencil.  Don't change stencil.
        DrawObjects(matl_diffspec)                # Draw lit part of object material.
        lmbind(LIGHT0, 0)                         # Leave this light off for next pass.
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    wmpack(0xffffffff)
    zwritemask(0xffffffff)
    blendfunction(BF_ONE, BF_ZERO)
    popmatrix()


def jitter_offsets(n, radius, lpos, centre):
    """n points on a disc of the given radius perpendicular to the light's
    direction (golden-angle spiral), as offsets."""
    d = centre - lpos
    d /= np.linalg.norm(d)
    u = np.cross(d, (0.0, 0.0, 1.0))
    if np.linalg.norm(u) < 1e-6:
        u = np.cross(d, (1.0, 0.0, 0.0))
    u /= np.linalg.norm(u)
    w = np.cross(d, u)
    k = np.arange(n) + 0.5
    r = radius * np.sqrt(k / n)
    th = k * math.pi * (3.0 - math.sqrt(5.0))
    return r[:, None] * (np.cos(th)[:, None] * u + np.sin(th)[:, None] * w)


def draw_scene(opts):
    if opts.jitter <= 1:
        draw_frame(opts)
    else:
        base = [lt.position.copy() for lt in light]
        offs = [jitter_offsets(opts.jitter, SOFT_RADIUS, b, np.zeros(3)) for b in base]
        for j in range(opts.jitter):
            for i in range(nLights):
                light[i].position = base[i] + offs[i][j]
                define_light(light[i])
            draw_frame(opts)
            acbuf(AC_CLEAR_ACCUMULATE if j == 0 else AC_ACCUMULATE, 1.0)
        acbuf(AC_RETURN, 1.0 / opts.jitter)
        for i in range(nLights):
            light[i].position = base[i]
            define_light(light[i])
    swapbuffers()


def parse(argv):
    ap = argparse.ArgumentParser(description="Heidmann's stencil shadow volumes")
    ap.add_argument("--figure", default="4d", choices=sorted(FIGURE_SETUP))
    ap.add_argument("--zfail", action="store_true", help="depth-fail counting with caps")
    ap.add_argument("--jitter", type=int, default=None,
                    help="light positions accumulated (figure 6: 32)")
    ap.add_argument("--size", default=f"{WIDTH}x{HEIGHT}", help="window WxH")
    ap.add_argument("--volumes-only", type=int, default=None, metavar="I",
                    help="stop after the shadow-volume pass of light I")
    ap.add_argument("--objects", action="store_true",
                    help="record the scene and the volumes in IRIS GL objects (callobj)")
    ap.add_argument("--two-pass", action="store_true",
                    help="volume faces in two passes: backface/ST_INCR, frontface/ST_DECR")
    ap.add_argument("--infinite", action="store_true",
                    help="volumes to infinity (v4f with w = 0, infinite far plane)")
    a = ap.parse_args(argv)
    if a.infinite and a.zfail:
        ap.error("--infinite draws z-pass volumes (no far caps)")
    a.width, a.height = (int(s) for s in a.size.lower().split("x"))
    if a.jitter is None:
        a.jitter = 32 if a.figure == "6" else 1
    return a


def projection(aspect):
    """perspective(FOVY, aspect, NEAR, FAR), or with --infinite the same
    with the far plane at infinity (the limit of perspective(3G)'s matrix
    as far grows), loaded with loadmatrix in MPROJECTION mode."""
    if not infinite:
        perspective(FOVY, aspect, NEAR, FAR)
        return
    f = 1.0 / math.tan(math.radians(FOVY / 20.0))
    mode = getmmode()
    mmode(MPROJECTION)
    loadmatrix([[f / aspect, 0.0, 0.0, 0.0],
                [0.0, f, 0.0, 0.0],
                [0.0, 0.0, -1.0, -1.0],
                [0.0, 0.0, -2.0 * NEAR, 0.0]])
    mmode(mode)


def setup(opts):
    """Scene, lights and eye of a figure (module globals, as in C)."""
    global objects, light, nLights, eye, use_objects, two_pass, infinite
    use_objects = opts.objects
    two_pass, infinite = opts.two_pass, opts.infinite
    _compiled.clear()
    scene, names, view = FIGURE_SETUP[opts.figure]
    objects = make_scene(scene)
    light = [Light(i + 1, *LIGHT_DEFS[nm]) for i, nm in enumerate(names)]
    nLights = len(light)
    eye = np.array(VIEWS[view][0], float)
    opts.ref = VIEWS[view][1]


def main(argv=None):
    opts = parse(sys.argv[1:] if argv is None else argv)
    setup(opts)
    if getgdesc(GD_BITS_STENCIL) == 0:           # This requires stencil hardware.
        sys.exit(1)
    prefsize(opts.width, opts.height)
    winopen("shadows")
    RGBmode()
    doublebuffer()
    stensize(getgdesc(GD_BITS_STENCIL))          # Use all the stencil bitplanes.
    if opts.jitter > 1:
        acsize(16)
    gconfig()
    zbuffer(TRUE)                                # z comparison always active.
    subpixel(TRUE)                               # (see the docstring: long slivers)
    mmode(MVIEWING)
    projection(opts.width / opts.height)
    define_materials()
    for lt in light:
        define_light(lt)
    qdevice(ESCKEY)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw_scene(opts)
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
