"""Bentley (1995), "Two shadow rendering algorithms", part I: the "ground
transformation" (after Blinn 1988, "Me and my (fake) shadow"): every polygon
of every object projected onto the ground plane z = 0 away from each light,
for lights at infinity and for local lights.

Scene convention of the paper: z is up, the ground is z = 0.  IRIS GL's
lookat keeps y up, so the view is ``lookat(...)`` on the y-up coordinates of
the eye followed by ``rotate(-900, 'x')`` (Tessman's recipe: z becomes y).

The matrix of the paper's listing (a column-vector matrix: P' = W P, then
``homo`` divides by the fourth coordinate):

    ident_mat(W);
    W[0][0] = -light_point[2];  W[0][2] = light_point[0];
    W[1][1] = -light_point[2];  W[1][2] = light_point[1];
    W[2][2] = 0;
    W[3][3] = -light_point[2];

Side by side with the matrix the equations of the text give, for a light at
l = (lx, ly, lz) (local) or in the direction L = (lx, ly, lz) from the point
towards the light (at infinity), lw = 1 for local, 0 for infinite:

    listing (as printed)             corrected (Blinn's general form)
    [ -lz   0   lx   0 ]             [ -lz   0   lx    0 ]
    [   0 -lz   ly   0 ]             [   0 -lz   ly    0 ]
    [   0   0    0   0 ]             [   0   0    0    0 ]
    [   0   0    0 -lz ]             [   0   0   lw  -lz ]   <- W[3][2] = lw

Local light: P' = P + t (l - P) with z' = 0 gives t = -Pz / (lz - Pz) and
x' = (lz Px - lx Pz) / (lz - Pz), so the homogeneous w is lz - Pz (times -1
in the listing's sign): the listing omits ``W[3][2] = 1`` (the z entry of the
w row).  Without it w is the constant -lz and the "local" matrix is the
light-at-infinity matrix for the direction l: a parallel projection along
the line from the ORIGIN to the light, so the shadow is neither enlarged nor
aimed away from the light as seen from the object (figure ``listing``).  For
lights at infinity the listing is right (x' = Px - Pz lx/lz after the
divide); ``light_point`` must then hold the direction L.

Two more corrections are needed to use W in IRIS GL with ``multmatrix``:
1. layout: IRIS GL multiplies row vectors (p' = p . M), so the matrix is
   transposed (the w "column" of the paper becomes IRIS GL's column 3);
2. sign: the listing's w is -lz (infinite) or Pz - lz (local), negative for
   every point below the light.  Bentley's ``homo`` divides whatever the
   sign, but the IRIS GL clipper keeps only w > 0, so the listing's matrix
   given to multmatrix draws no shadow at all (option --keep-sign).  -W is the same projective
   map with w = lz - Pz > 0 below the light:

    IRIS GL matrix = transpose(-W_corrected) =
    [  lz   0   0    0 ]
    [   0  lz   0    0 ]
    [ -lx -ly   0  -lw ]
    [   0   0   0   lz ]

   That is Tessman's local-light matrix with y and z exchanged.

Stability (docs/stability.md, "local light below the top of an object"):
points at or above a local light (w <= 0) would be thrown to the far side of
the light, an inverted shadow; the clipper drops w <= 0, so only the part
below the light casts (its shadow reaching to the horizon). A light at or
below the horizon (lz <= 0, or an infinite light within 0.5 degrees of it)
lights nothing on the top of the ground and casts no shadow there: it is
skipped, and lz is never divided by.

Two lights, overlapping shadows.  The paper projects every polygon once per
light ("for N lights there will be N projections of each polygon") and
defines shadow per light: a point is in shadow for a light if that light
cannot see it.  So a ground point blocked from one light is still lit by the
other, and only where both shadows overlap does it get the ambient light
alone: the overlap is darker, each light's shadow is not.  Overlapping
shadow polygons of the SAME light (the faces of one object, or two objects)
must not darken twice (tests/test_program_bentley_ground.py checks it).
Route used: stencil once per light.

    ground, ambient only                       (zbuffer off)
    for each light i:
        sclear(0); wmpack(0)
        stencil(TRUE, 1, SF_ALWAYS, ..., ST_REPLACE)   shadow polygons of light i
        wmpack(all); stencil(TRUE, 0, SF_EQUAL, ...)
        blendfunction(BF_ONE, BF_ONE)            ground lit by light i alone
    zbuffer(TRUE); objects lit by all lights

Every ground pixel thus receives ambient + the sum of the lights that see it,
whatever the number of shadow polygons covering it.  The objects shade
themselves by the lighting equation only (the ground transformation puts
shadows on the ground, nowhere else, as the paper says).

The ``--route software`` variant is the paper's own code path: each vertex
is multiplied by W in the program (``pt_matrix_mult``) and the divide is
left to the pipeline (``v4f`` of the homogeneous point, after the sign is
made positive below the light), so the clipper still refuses w <= 0.

Options (after ``--`` under vgx-run):
  --figure two|local|listing    --matrix listing|corrected
  --route multmatrix|software   --listing   (the listing's W, software route)
  --keep-sign      give W to the pipeline with the paper's sign (w < 0 below
                   the light): the clipper rejects every shadow vertex
  --light X Y Z W  (repeatable: W = 0 direction towards the light, 1 position)
"""
import argparse
import math
import sys

import numpy as np

from irisgl import *

FIGURES = [
    {"name": "two_infinite", "args": ["--figure", "two"],
     "caption": "Bentley 1995: shadows by the ground transformation with two light sources at "
                "infinity; each light's shadow darkens once, the overlap (ambient only) is darker."},
    {"name": "local", "args": ["--figure", "local"],
     "caption": "Bentley 1995: perspective shadows from a local light source (yellow marker), "
                "corrected matrix with W[3][2] = 1, transposed and negated for multmatrix."},
    {"name": "listing_vs_corrected", "args": ["--figure", "listing"],
     "caption": "Bentley's matrix listing (left: W[3][2] missing, a parallel projection along "
                "the origin-to-light line) beside the corrected matrix (right), same local light."},
]

WIDTH, HEIGHT = 640, 480
EYE = (8.0, -9.5, 4.6)            # z up
REF = (-0.3, 0.4, 0.7)
FOVY, NEAR, FAR = 380, 1.0, 100.0
GROUND_SIZE = 40.0
GROUND_GRID, GROUND_STEP = 12.0, 0.75
GROUND_RINGS = (15.0, 19.0, 24.0, 31.0)
SKY = 0x00E0C8A8
MIN_ELEVATION = math.radians(0.5)

TWO_LIGHTS = [(0.9, 1.1, 1.5, 0.0), (-0.9, 1.0, 1.4, 0.0)]   # towards the lights
LOCAL_LIGHT = [(0.3, 0.1, 3.4, 1.0)]
LIGHT_RGB = [(0.6, 0.6, 0.6), (0.6, 0.6, 0.6)]
LOCAL_RGB = [(0.9, 0.9, 0.9)]
AMBIENT_MODEL = (0.28, 0.28, 0.28)

GROUND_MAT = 1
OBJECT_MATS = [2, 3, 4, 5]
AMBIENT_LM, DIRECT_LM, FULL_LM = 1, 2, 3
LIGHT_DEFS = [1, 2]


# -- objects: polygons, counter-clockwise seen from outside, z up ------------
def box(x0, x1, y0, y1, z0, z1):
    return [[(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
            [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
            [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
            [(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)],
            [(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)],
            [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]]


def pyramid(cx, cy, half, h):
    b = [(cx - half, cy - half, 0.0), (cx + half, cy - half, 0.0),
         (cx + half, cy + half, 0.0), (cx - half, cy + half, 0.0)]
    apex = (cx, cy, h)
    sides = [[b[i], b[(i + 1) % 4], apex] for i in range(4)]
    return [list(reversed(b))] + sides


def prism(cx, cy, r, z0, z1, n=8):
    ring = [(cx + r * math.cos(2 * math.pi * k / n), cy + r * math.sin(2 * math.pi * k / n))
            for k in range(n)]
    polys = [[(x, y, z0) for x, y in reversed(ring)], [(x, y, z1) for x, y in ring]]
    for k in range(n):
        (xa, ya), (xb, yb) = ring[k], ring[(k + 1) % n]
        polys.append([(xa, ya, z0), (xb, yb, z0), (xb, yb, z1), (xa, ya, z1)])
    return polys


def ball(cx, cy, cz, r, slices=10, stacks=6):
    """A faceted sphere (flat-shaded quads and triangles)."""
    def p(i, j):
        ph = math.pi * i / stacks - math.pi / 2
        th = 2 * math.pi * j / slices
        return (cx + r * math.cos(ph) * math.cos(th), cy + r * math.cos(ph) * math.sin(th),
                cz + r * math.sin(ph))
    polys = []
    for i in range(stacks):
        for j in range(slices):
            q = [p(i, j), p(i, j + 1), p(i + 1, j + 1), p(i + 1, j)]
            if i == 0:
                q = [q[0], q[2], q[3]]
            elif i == stacks - 1:
                q = q[:3]
            polys.append(q)
    return polys


OBJECTS = [box(-2.6, -1.2, -1.0, 0.4, 0.0, 1.4),
           pyramid(1.3, -1.3, 0.8, 1.8),
           prism(0.9, 1.7, 0.45, 0.0, 2.4),
           ball(-1.0, 2.2, 1.3, 0.55)]
OBJECT_RGB = [(0.75, 0.2, 0.15), (0.2, 0.35, 0.8), (0.85, 0.7, 0.2), (0.85, 0.85, 0.85)]


def normal(poly):
    """Newell's normal of a planar polygon, normalized."""
    n = np.zeros(3)
    for a, b in zip(poly, poly[1:] + poly[:1]):
        n += np.cross(a, b)
    return n / np.linalg.norm(n)


NORMALS = [[normal(p) for p in obj] for obj in OBJECTS]


# -- the ground transformation ---------------------------------------------
def listing_matrix(light_point):
    """W exactly as the paper's listing loads it (column vectors)."""
    W = np.identity(4)
    W[0][0] = -light_point[2]
    W[0][2] = light_point[0]
    W[1][1] = -light_point[2]
    W[1][2] = light_point[1]
    W[2][2] = 0
    W[3][3] = -light_point[2]
    return W


def corrected_matrix(light):
    """The listing plus the omitted W[3][2] = lw (1: local, 0: infinite)."""
    W = listing_matrix(light)
    W[3][2] = light[3]
    return W


def irisgl_matrix(W, keep_sign=False):
    """Column-vector W -> IRIS GL row-vector layout, sign chosen so that w > 0
    below the light (the clipper keeps only w > 0).  keep_sign: the paper's
    sign, w < 0 below the light (only transposed)."""
    return W.T.copy() if keep_sign else (-W).T


def ground_matrix(light):
    """The IRIS GL matrix for multmatrix: transpose(-W_corrected)."""
    return irisgl_matrix(corrected_matrix(light))


def casts_shadow(light):
    lx, ly, lz, lw = light
    if lw == 0.0:
        return lz > 0.0 and lz > math.hypot(lx, ly) * math.tan(MIN_ELEVATION)
    return lz > 0.0


def pt_matrix_mult(W, p):
    """The paper's software transform, P' = W P (P homogeneous)."""
    return W @ np.array([p[0], p[1], p[2], 1.0])


# -- drawing ------------------------------------------------------------------
def _ground_lines():
    """Grid lines of the ground: fine near the objects, coarser outwards, one
    grid with no T-junctions (so the additive passes meet edge to edge)."""
    k = int(round(2 * GROUND_GRID / GROUND_STEP))
    fine = [-GROUND_GRID + i * GROUND_STEP for i in range(k + 1)]
    outer = [c for c in GROUND_RINGS if c < GROUND_SIZE] + [GROUND_SIZE]
    return [-c for c in reversed(outer)] + fine + outer


GROUND_LINES = None


def draw_ground():
    """z = 0, one grid of quad strips.  A local light is evaluated per vertex,
    so one huge polygon would be lit only at its far corners."""
    global GROUND_LINES
    if GROUND_LINES is None:
        GROUND_LINES = _ground_lines()
    c = GROUND_LINES
    n3f((0.0, 0.0, 1.0))
    for x0, x1 in zip(c, c[1:]):
        bgnqstrip()
        for y in c:
            v3f((x1, y, 0.0))
            v3f((x0, y, 0.0))
        endqstrip()


def draw_objects():
    for k, obj in enumerate(OBJECTS):
        lmbind(MATERIAL, OBJECT_MATS[k])
        for poly, n in zip(obj, NORMALS[k]):
            bgnpolygon()
            n3f(n)
            for v in poly:
                v3f(v)
            endpolygon()


def draw_shadow_polygons(light, matrix, route, keep_sign=False):
    """Every polygon of every object projected to z = 0 for one light."""
    if route == "multmatrix":
        pushmatrix()
        multmatrix(irisgl_matrix(matrix, keep_sign))
        for obj in OBJECTS:
            for poly in obj:
                bgnpolygon()
                for v in poly:
                    v3f(v)
                endpolygon()
        popmatrix()
        return
    sign = -1.0 if light[2] > 0 and not keep_sign else 1.0   # w > 0 below the light
    for obj in OBJECTS:
        for poly in obj:
            bgnpolygon()
            for v in poly:
                v4f(sign * pt_matrix_mult(matrix, v))   # homo(): the pipeline divides
            endpolygon()


def draw_light_marker(light):
    if light[3] == 0.0:
        return
    lmbind(MATERIAL, 0)
    RGBcolor(255, 225, 40)
    x, y, z = light[:3]
    for poly in box(x - 0.12, x + 0.12, y - 0.12, y + 0.12, z - 0.12, z + 0.12):
        bgnpolygon()
        for v in poly:
            v3f(v)
        endpolygon()


def define_lighting(lights, rgbs):
    lmdef(DEFMATERIAL, GROUND_MAT, 0, [AMBIENT, 0.55, 0.6, 0.5, DIFFUSE, 0.55, 0.62, 0.5,
                                       LMNULL])
    for k, rgb in enumerate(OBJECT_RGB):
        lmdef(DEFMATERIAL, OBJECT_MATS[k], 0, [AMBIENT] + list(rgb) + [DIFFUSE] + list(rgb)
              + [SPECULAR, 0.3, 0.3, 0.3, SHININESS, 25.0, LMNULL])
    lmdef(DEFLMODEL, AMBIENT_LM, 0, [AMBIENT] + list(AMBIENT_MODEL) + [LMNULL])
    lmdef(DEFLMODEL, DIRECT_LM, 0, [AMBIENT, 0.0, 0.0, 0.0, LMNULL])
    lmdef(DEFLMODEL, FULL_LM, 0, [AMBIENT] + list(AMBIENT_MODEL) + [LMNULL])
    for k, (light, rgb) in enumerate(zip(lights, rgbs)):
        lmdef(DEFLIGHT, LIGHT_DEFS[k], 0, [LCOLOR] + list(rgb) + [POSITION] + list(light)
              + [LMNULL])


def bind_lights(only=None, n=2):
    for k in range(n):
        lmbind(LIGHT0 + k, 0)
    if only is not None:
        lmbind(LIGHT0, LIGHT_DEFS[only])
    else:
        for k in range(n):
            lmbind(LIGHT0 + k, LIGHT_DEFS[k])


def view():
    ex, ey, ez = EYE
    rx, ry, rz = REF
    lookat(ex, ez, -ey, rx, rz, -ry, 0)     # y-up coordinates of the z-up points
    rotate(-900, 'x')                        # z becomes y, y becomes -z


def draw_scene(lights, matrix_kind, route, vp, keep_sign=False):
    viewport(*vp)
    pushmatrix()
    view()
    # the ground: ambient, then each light where its shadow is not
    zbuffer(FALSE)
    bind_lights(None, len(lights))
    for k in range(len(lights)):
        lmbind(LIGHT0 + k, 0)
    lmbind(LMODEL, AMBIENT_LM)
    lmbind(MATERIAL, GROUND_MAT)
    draw_ground()
    for i, light in enumerate(lights):
        lmbind(MATERIAL, 0)
        if casts_shadow(light):
            sclear(0)
            wmpack(0)
            stencil(TRUE, 1, SF_ALWAYS, 0xff, ST_KEEP, ST_REPLACE, ST_REPLACE)
            W = listing_matrix(light) if matrix_kind == "listing" else corrected_matrix(light)
            draw_shadow_polygons(light, W, route, keep_sign)
            wmpack(0xffffffff)
            stencil(TRUE, 0, SF_EQUAL, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
        if light[2] > 0.0:                   # a light below the horizon lights no ground
            blendfunction(BF_ONE, BF_ONE)
            lmbind(LMODEL, DIRECT_LM)
            bind_lights(i, len(lights))
            lmbind(MATERIAL, GROUND_MAT)
            draw_ground()
            blendfunction(BF_ONE, BF_ZERO)
        stencil(FALSE, 0, SF_ALWAYS, 0xff, ST_KEEP, ST_KEEP, ST_KEEP)
    # the objects, z-buffered, lit by every light
    zbuffer(TRUE)
    for light in lights:
        draw_light_marker(light)
    lmbind(LMODEL, FULL_LM)
    bind_lights(None, len(lights))
    draw_objects()
    lmbind(MATERIAL, 0)
    popmatrix()


def parse(argv):
    ap = argparse.ArgumentParser(prog="bentley_ground_shadows", description=__doc__.splitlines()[0])
    ap.add_argument("--figure", choices=["two", "local", "listing"], default="two")
    ap.add_argument("--matrix", choices=["listing", "corrected"], default="corrected")
    ap.add_argument("--route", choices=["multmatrix", "software"], default="multmatrix")
    ap.add_argument("--keep-sign", action="store_true",
                    help="use W with the paper's sign (w < 0 below the light): clipped, no shadow")
    ap.add_argument("--listing", action="store_true",
                    help="the listing's W through the paper's software route")
    ap.add_argument("--light", nargs=4, type=float, action="append", metavar=("X", "Y", "Z", "W"))
    a = ap.parse_args(argv)
    if a.listing:
        a.matrix, a.route = "listing", "software"
    if a.light:
        a.lights = [tuple(l) for l in a.light][:2]
        a.rgbs = (LOCAL_RGB if len(a.lights) == 1 else LIGHT_RGB)[:len(a.lights)]
    elif a.figure == "two":
        a.lights, a.rgbs = TWO_LIGHTS, LIGHT_RGB
    else:
        a.lights, a.rgbs = LOCAL_LIGHT, LOCAL_RGB
    return a


def draw(a):
    czclear(SKY, getgdesc(GD_ZMAX))
    if a.figure == "listing" and not a.light:
        half = WIDTH // 2
        perspective(FOVY, half / HEIGHT, NEAR, FAR)
        draw_scene(a.lights, "listing", "software", (0, half - 1, 0, HEIGHT - 1))
        draw_scene(a.lights, "corrected", "software", (half, WIDTH - 1, 0, HEIGHT - 1))
        perspective(FOVY, WIDTH / HEIGHT, NEAR, FAR)
    else:
        draw_scene(a.lights, a.matrix, a.route, (0, WIDTH - 1, 0, HEIGHT - 1), a.keep_sign)
    swapbuffers()


def main(argv=None):
    a = parse(sys.argv[1:] if argv is None else argv)
    prefsize(WIDTH, HEIGHT)
    winopen("bentley ground shadows")
    RGBmode()
    doublebuffer()
    stensize(1)
    gconfig()
    mmode(MVIEWING)
    perspective(FOVY, WIDTH / HEIGHT, NEAR, FAR)
    define_lighting(a.lights, a.rgbs)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            draw(a)
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
