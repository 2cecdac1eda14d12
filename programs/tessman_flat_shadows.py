"""Tessman (1989), "Casting shadows on flat surfaces": the object flattened
onto the ground plane y = 0 by the Geometry Pipeline and drawn black through
a halftone pattern.

The program is the listing of the paper's Figure 1 put into a complete IRIS
GL program (configuration, gconfig, a REDRAW loop, swapbuffers):

    zbuffer(FALSE);  lookat(vx, vy, vz, px, py, pz, twist);  draw_ground();
    setpattern(halftone);  RGBcolor(0, 0, 0);
    pushmatrix();  scale(1.0, 0.0, 1.0);   /* or multmatrix(shadow matrix) */
        position_object();  draw_object_shadow();
    popmatrix();
    setpattern(0);  zbuffer(TRUE);
    position_object();  draw_object();      /* shading lit from above */

The object is a small faceted chair (boxes: four legs, a seat, two back posts
and a back rest), every face a polygon with its normal, lit by lmdef/lmbind
in MVIEWING.  The ground and the shadow are neither z-tested nor z-written
("don't bother z-buffering ground or shadow"): the shadow is drawn after the
ground, so it needs no depth test, and the coplanar shadow cannot z-fight.

Light vector convention (the paper's figure with the sign is lost).  The
light is one homogeneous 4-vector L = (lx, ly, lz, lw), the same one given to
``lmdef(DEFLIGHT, ..., POSITION, lx, ly, lz, lw)``: lw = 0 is a light at
infinity and (lx, ly, lz) points FROM the scene TOWARDS the light (ly > 0 is
a light above the ground); lw = 1 is a local light at the absolute position
(lx, ly, lz).  A point P goes to the ground along the ray through P parallel
to L: P - t L with t = Y_old / ly, so

    X_new = X_old - Y_old * lx/ly,   Y_new = 0,   Z_new = Z_old - Y_old * lz/ly.

(The scan prints "X_old + Y_old |x|/|y|": with the absolute-value bars read as
l's, the + sign belongs to the opposite convention, a vector along which the
light travels, whose ly < 0; the ratio lx/ly is the same for both
directions of a line only up to that sign.  Written with the vector towards
the light, as here and as lmdef wants it, the sign is minus.)

Reconstructed matrices (the scanned ones are damaged: the infinite-light one
came out with five rows, a spurious "ly 0 ly 0" row and the minus signs
lost).  IRIS GL layout: points are row vectors, p' = p . M, so row 1 holds
what Y_old contributes and column 3 is w:

    infinite light                    local light at (lx, ly, lz)
    [    1    0     0    0 ]          [  ly   0    0    0 ]
    [ -lx/ly  0  -lz/ly  0 ]          [ -lx   0  -lz   -1 ]
    [    0    0     1    0 ]          [   0   0   ly    0 ]
    [    0    0     0    1 ]          [   0   0    0   ly ]

The local matrix gives X = ly X_old - lx Y_old, Z = ly Z_old - lz Y_old and
W = ly - Y_old, which the divide turns into the paper's similar-triangle
result X_new = (ly X_old - lx Y_old) / (ly - Y_old).  With lx = lz = 0 the
infinite matrix is diag(1, 0, 1, 1), i.e. scale(1.0, 0.0, 1.0).

Stability rule (docs/stability.md, "local light below the top of an object"):
only the part of the object with W > 0, i.e. below the light, casts a shadow;
parts at or above a local light would land on the wrong side of it (an
inverted shadow). The emulator's homogeneous clipper discards W <= 0, as the
VGX clipper does, so the matrix is simply used as it is. The shadow of a part
just below a local light reaches towards the horizon, and with the ground
drawn without z-buffer nothing stops it at the ground's edge: the ground is
made larger than the far clipping distance, so the far plane ends ground and
shadow together (a smaller ground would let the shadow run on over the sky). A
light at or below the horizon (ly <= 0, or an infinite light within 0.5
degrees of it) lights nothing on the top of the ground: no shadow is drawn,
and no division by ly is attempted.

Options (after ``--`` under vgx-run):
  --figure fig1|fig2|fig3|moving   the paper's three cases and a moving light
  --light down|infinite|local      --dir LX LY LZ   --pos LX LY LZ
  --scale          use scale(1,0,1) itself (light straight down, fig. 1)
  --moving         rebuild the local-light matrix every frame, the light
                   circling the chair ("no reason not to rebuild a matrix for
                   each frame"); run with vgx-run --frames N
  --frame N        start the moving light at frame N
"""
import argparse
import math
import sys

from irisgl import *

FIGURES = [
    {"name": "fig1", "args": ["--figure", "fig1"],
     "caption": "Tessman 1989, fig. 1: scale(1.0, 0.0, 1.0) flattens the chair onto y = 0, "
                "a shadow from a light straight down, drawn black through the halftone pattern."},
    {"name": "fig2", "args": ["--figure", "fig2"],
     "caption": "Tessman 1989, fig. 2: shadow from an infinite light source, the hand-built "
                "matrix X_new = X_old - Y_old lx/ly, Z_new = Z_old - Y_old lz/ly via multmatrix."},
    {"name": "fig3", "args": ["--figure", "fig3"],
     "caption": "Tessman 1989, fig. 3: shadow from a local light source (the yellow marker), "
                "the perspective-like matrix with W = ly - Y_old doing the divide."},
    {"name": "moving", "args": ["--figure", "moving"], "frames": 6,
     "caption": "Tessman 1989: a moving local light, the shadow matrix rebuilt every frame "
                "(the sixth frame of the animation)."},
]

WIDTH, HEIGHT = 640, 480
EYE = (3.6, 3.6, 5.6)
REF = (-0.5, 1.2, -0.6)
TWIST = 0
FOVY, NEAR, FAR = 420, 1.0, 80.0
GROUND_SIZE = 200.0              # beyond the far plane: ground and shadow end together
GROUND_RGB = (96, 150, 84)
SKY = 0x00D8B890                 # cpack 0xAABBGGRR: a pale blue sky
OBJECT_TURN = 300                # position_object: rotate 30 degrees about y
OBJECT_AT = (0.0, 0.0, 0.0)

# a 16x16 checker: bit 15 of each short is the leftmost pixel, rows bottom up
HALFTONE = 1
halftone = [0x5555, 0xAAAA] * 8

LIGHT_DOWN = (0.0, 1.0, 0.0, 0.0)
LIGHT_INFINITE = (0.55, 1.0, 0.35, 0.0)
LIGHT_LOCAL = (1.6, 3.4, 1.3, 1.0)
MOVING_RADIUS, MOVING_HEIGHT, MOVING_STEP = 2.0, 3.4, 20.0   # degrees per frame
MIN_ELEVATION = math.radians(0.5)

CHAIR_MAT, MARKER_MAT = 1, 2
LAMP = 1
MODEL = 1


def chair_boxes():
    """The chair as axis-aligned boxes (x0, x1, y0, y1, z0, z1), object space."""
    boxes = []
    for x in (-0.55, 0.45):
        for z in (-0.55, 0.45):
            boxes.append((x, x + 0.1, 0.0, 0.9, z, z + 0.1))         # legs
    boxes.append((-0.6, 0.6, 0.9, 1.05, -0.6, 0.6))                  # seat
    for x in (-0.55, 0.45):
        boxes.append((x, x + 0.1, 1.05, 2.3, -0.6, -0.5))           # back posts
    boxes.append((-0.45, 0.45, 1.55, 2.15, -0.58, -0.52))           # back rest
    return boxes


def box_faces(b):
    """The six faces of a box: (normal, four corners counter-clockwise seen
    from outside)."""
    x0, x1, y0, y1, z0, z1 = b
    return [
        ((1, 0, 0), [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)]),
        ((-1, 0, 0), [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)]),
        ((0, 1, 0), [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)]),
        ((0, -1, 0), [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)]),
        ((0, 0, 1), [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]),
        ((0, 0, -1), [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)]),
    ]


CHAIR = [f for b in chair_boxes() for f in box_faces(b)]


# -- the shadow matrices (IRIS GL row-vector layout) --------------------------
def infinite_shadow_matrix(lx, ly, lz):
    """Ground y = 0, light at infinity in direction (lx, ly, lz) (towards the
    light): X_new = X_old - Y_old lx/ly, Z_new = Z_old - Y_old lz/ly."""
    return [[1.0, 0.0, 0.0, 0.0],
            [-lx / ly, 0.0, -lz / ly, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0]]


def local_shadow_matrix(lx, ly, lz):
    """Ground y = 0, local light at (lx, ly, lz); W = ly - Y_old."""
    return [[ly, 0.0, 0.0, 0.0],
            [-lx, 0.0, -lz, -1.0],
            [0.0, 0.0, ly, 0.0],
            [0.0, 0.0, 0.0, ly]]


def casts_shadow(light):
    """False for a light at or below the horizon (no shadow on the ground's
    top, and no division by ly)."""
    lx, ly, lz, lw = light
    if lw == 0.0:
        return ly > math.hypot(lx, lz) * math.tan(MIN_ELEVATION) and ly > 0.0
    return ly > 0.0


def shadow_matrix(light):
    lx, ly, lz, lw = light
    if lw == 0.0:
        return infinite_shadow_matrix(lx, ly, lz)
    return local_shadow_matrix(lx, ly, lz)


def moving_light(frame):
    a = math.radians(MOVING_STEP * frame + 30.0)
    return (MOVING_RADIUS * math.cos(a), MOVING_HEIGHT, MOVING_RADIUS * math.sin(a), 1.0)


# -- the pieces of the listing --------------------------------------------------
def draw_ground():
    RGBcolor(*GROUND_RGB)
    s = GROUND_SIZE
    bgnpolygon()
    for v in ((-s, 0.0, -s), (-s, 0.0, s), (s, 0.0, s), (s, 0.0, -s)):
        v3f(v)
    endpolygon()


def position_object():
    translate(*OBJECT_AT)
    rotate(OBJECT_TURN, 'y')


def draw_object_shadow():
    """The same polygons as the object, no normals, no colour change."""
    for _, quad in CHAIR:
        bgnpolygon()
        for v in quad:
            v3f(v)
        endpolygon()


def draw_object():
    for n, quad in CHAIR:
        bgnpolygon()
        n3f(n)
        for v in quad:
            v3f(v)
        endpolygon()


def draw_light_marker(light):
    """A small unlit yellow cube where a local light is."""
    lx, ly, lz, lw = light
    if lw == 0.0:
        return
    RGBcolor(255, 230, 60)
    h = 0.09
    for _, quad in box_faces((lx - h, lx + h, ly - h, ly + h, lz - h, lz + h)):
        bgnpolygon()
        for v in quad:
            v3f(v)
        endpolygon()


def define_lighting():
    lmdef(DEFMATERIAL, CHAIR_MAT, 0, [AMBIENT, 0.35, 0.22, 0.12,
                                      DIFFUSE, 0.75, 0.48, 0.26,
                                      SPECULAR, 0.3, 0.3, 0.3,
                                      SHININESS, 20.0, LMNULL])
    lmdef(DEFLMODEL, MODEL, 0, [AMBIENT, 0.35, 0.35, 0.35, LMNULL])


def draw_scene(light, use_scale):
    czclear(SKY, getgdesc(GD_ZMAX))
    lmbind(MATERIAL, 0)                # ground and shadow: no lighting

    zbuffer(FALSE)                     # don't bother z-buffering ground or shadow
    pushmatrix()
    lookat(EYE[0], EYE[1], EYE[2], REF[0], REF[1], REF[2], TWIST)
    lmdef(DEFLIGHT, LAMP, 0, [LCOLOR, 1.0, 1.0, 1.0, POSITION] + list(light) + [LMNULL])
    lmbind(LIGHT0, LAMP)               # fixed in the world: bound under lookat
    draw_ground()

    if casts_shadow(light):
        setpattern(HALFTONE)
        RGBcolor(0, 0, 0)              # only darkens every other pixel
        pushmatrix()
        if use_scale:
            scale(1.0, 0.0, 1.0)       # shadow transformation
        else:
            multmatrix(shadow_matrix(light))
        position_object()
        draw_object_shadow()
        popmatrix()
        setpattern(0)

    zbuffer(TRUE)
    draw_light_marker(light)
    pushmatrix()
    position_object()                  # just like before, without the shadow
    lmbind(MATERIAL, CHAIR_MAT)
    draw_object()                      # shading lit from above
    lmbind(MATERIAL, 0)
    popmatrix()
    popmatrix()
    swapbuffers()


def parse(argv):
    ap = argparse.ArgumentParser(prog="tessman_flat_shadows", description=__doc__.splitlines()[0])
    ap.add_argument("--figure", choices=["fig1", "fig2", "fig3", "moving"], default=None)
    ap.add_argument("--light", choices=["down", "infinite", "local"], default="infinite")
    ap.add_argument("--dir", nargs=3, type=float, metavar=("LX", "LY", "LZ"), default=None)
    ap.add_argument("--pos", nargs=3, type=float, metavar=("LX", "LY", "LZ"), default=None)
    ap.add_argument("--scale", action="store_true", help="use scale(1,0,1) (light straight down)")
    ap.add_argument("--moving", action="store_true")
    ap.add_argument("--frame", type=int, default=0)
    a = ap.parse_args(argv)
    if a.figure == "fig1":
        a.light, a.scale = "down", True
    elif a.figure == "fig2":
        a.light = "infinite"
    elif a.figure == "fig3":
        a.light = "local"
    elif a.figure == "moving":
        a.light, a.moving = "local", True
    if a.light == "down":
        a.L = LIGHT_DOWN
    elif a.light == "infinite":
        a.L = (tuple(a.dir) + (0.0,)) if a.dir else LIGHT_INFINITE
    else:
        a.L = (tuple(a.pos) + (1.0,)) if a.pos else LIGHT_LOCAL
    if a.scale and a.light != "down":
        ap.error("--scale is the shadow of a light straight down (--light down)")
    return a


def main(argv=None):
    a = parse(sys.argv[1:] if argv is None else argv)
    prefsize(WIDTH, HEIGHT)
    winopen("tessman shadows")
    RGBmode()
    doublebuffer()
    gconfig()
    mmode(MVIEWING)
    perspective(FOVY, WIDTH / HEIGHT, NEAR, FAR)
    defpattern(HALFTONE, 16, halftone)
    define_lighting()
    lmbind(LMODEL, MODEL)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    frame = a.frame
    if a.moving:                       # animate: draw whenever the queue is empty
        while True:
            while qtest():
                dev, val = qread()
                if dev == ESCKEY and val == 0:
                    gexit()
                    return
                if dev == REDRAW:
                    reshapeviewport()
            draw_scene(moving_light(frame), False)
            frame += 1
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw_scene(a.L, a.scale)
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
