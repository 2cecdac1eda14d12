"""A lit, trimmed NURBS surface: a bicubic saddle with a round hole.

The surface is a 6 x 6 net of control points on z = (x^2 - y^2) / 3, order
4 in s and t with clamped uniform knots.  Two trimming loops cut it: a
counter-clockwise piecewise linear square around the whole domain, and a
clockwise circle of radius 0.16 at the centre of the domain, one rational
quadratic NURBS curve of four arcs.  The surface is lit by one light; its
normals come from the surface itself (nurbssurface(3G)).

``-- outline`` draws the tessellation's polygons instead
(setnurbsproperty(N_DISPLAY, N_OUTLINE_POLY)); ``-- patch`` the patch
boundaries and trimming curves (N_OUTLINE_PATCH).
"""
import math
import sys

from irisgl import *

FIGURES = [
    {"name": "surface", "args": [],
     "caption": "A bicubic NURBS saddle, lit, trimmed by a square and a round "
                "NURBS hole (bgntrim(3G), pwlcurve(3G), nurbscurve(3G) of type N_P2DR)."},
    {"name": "outline", "args": ["outline"],
     "caption": "The same surface with N_DISPLAY = N_OUTLINE_POLY: the "
                "triangles it is tessellated into."},
    {"name": "patch", "args": ["patch"],
     "caption": "N_DISPLAY = N_OUTLINE_PATCH: the boundaries of the nine "
                "patches and the trimming curves, mapped onto the surface."},
]

WIDTH, HEIGHT = 400, 400
N = 6                                   # control points per direction
ORDER = 4
SIZE = 3.0                              # the net spans -1.5 .. 1.5
HOLE = 0.16                             # radius of the hole in (s, t)
DOUBLE = 8                              # sizeof(double): offsets are in bytes

knots = [0.0] * ORDER + [1.0 / 3, 2.0 / 3] + [1.0] * ORDER
ctlpoints = [[[0.0] * 3 for t in range(N)] for s in range(N)]
square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]]
circle_knots = [0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4]
circle = []                             # (ws, wt, w) control points


def init_surface():
    for s in range(N):
        for t in range(N):
            x = SIZE * (s / (N - 1) - 0.5)
            y = SIZE * (t / (N - 1) - 0.5)
            ctlpoints[s][t] = [x, y, (x * x - y * y) / 3.0]
    # clockwise from the top: top, top-right, right, ..., back to the top
    w = math.sqrt(0.5)
    dirs = [(0, 1), (1, 1), (1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1), (0, 1)]
    for i, (dx, dy) in enumerate(dirs):
        wt = 1.0 if i % 2 == 0 else w
        circle.append([wt * (0.5 + HOLE * dx), wt * (0.5 + HOLE * dy), wt])


def init_lights():
    lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.8, 0.55, 0.2, SPECULAR, 0.6, 0.6, 0.6,
                              SHININESS, 30.0, LMNULL])
    lmdef(DEFLIGHT, 1, 0, [POSITION, 1.0, 1.0, 2.0, 0.0, LMNULL])
    lmdef(DEFLMODEL, 1, 0, [AMBIENT, 0.3, 0.3, 0.3, TWOSIDE, 1.0, LMNULL])
    lmbind(LIGHT0, 1)
    lmbind(LMODEL, 1)


def draw():
    czclear(0x302010, getgdesc(GD_ZMAX))
    pushmatrix()
    translate(0.0, 0.0, -7.0)
    rotate(-550, 'x')
    rotate(300, 'z')
    lmbind(MATERIAL, 1)
    bgnsurface()
    nurbssurface(len(knots), knots, len(knots), knots, N * 3 * DOUBLE, 3 * DOUBLE,
                 ctlpoints, ORDER, ORDER, N_V3D)
    bgntrim()
    pwlcurve(len(square), square, 2 * DOUBLE, N_ST)
    endtrim()
    bgntrim()
    nurbscurve(len(circle_knots), circle_knots, 3 * DOUBLE, circle, 3, N_P2DR)
    endtrim()
    endsurface()
    lmbind(MATERIAL, 0)
    popmatrix()
    swapbuffers()


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    prefsize(WIDTH, HEIGHT)
    winopen("nurbs")
    RGBmode()
    doublebuffer()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, WIDTH / HEIGHT, 1.0, 20.0)
    loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    init_lights()
    init_surface()
    setnurbsproperty(N_PIXEL_TOLERANCE, 10.0)
    if mode == "outline":
        setnurbsproperty(N_PIXEL_TOLERANCE, 20.0)
        setnurbsproperty(N_DISPLAY, N_OUTLINE_POLY)
    elif mode == "patch":
        setnurbsproperty(N_DISPLAY, N_OUTLINE_PATCH)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    draw()
    while True:
        dev, val = qread()
        if dev == ESCKEY:
            break
        if dev == REDRAW:
            reshapeviewport()
            draw()
    gexit()


if __name__ == "__main__":
    main()
