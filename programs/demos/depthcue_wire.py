"""depthcue_wire: a depth-cued wire cube, turning, in colour-map mode.

Written in the style of a 1990 IRIS GL C program: a green ramp in the
colour map, lshaderange over the cube's own depth, and depthcue(TRUE) so
that near edges are bright and far ones fade (depthcue(3G)).

    vgx-run programs/demos/depthcue_wire.py --out /tmp/x.png --frames 3
"""
import math
import sys

from irisgl import *

FIGURES = [{"name": "depthcue_wire", "args": [],
            "caption": "A depth-cued wire cube in colour-map mode: lshaderange maps the "
                       "cube's depth onto a green ramp, near edges bright, far edges dim."}]

RAMP_LO, RAMP_HI = 64, 191          # colour-map entries of the ramp
NEAR, FAR, DIST = 1.0, 10.0, 6.0    # perspective near/far, cube centre distance
HALF = math.sqrt(3.0)               # the cube's circumradius (vertices at +-1)
ZMIN, ZMAX = -0x800000, 0x7FFFFF    # getgdesc(GD_ZMIN), getgdesc(GD_ZMAX)

CUBE = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
        (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]


def ramp_green(i):
    """The green of ramp entry i (entries outside the ramp are black)."""
    if not RAMP_LO <= i <= RAMP_HI:
        return 0
    return 40 + (215 * (i - RAMP_LO)) // (RAMP_HI - RAMP_LO)


def screen_z(d):
    """The screen z of a point at eye distance d under perspective(NEAR, FAR)
    and the default lsetdepth range."""
    zn = ((FAR + NEAR) / (FAR - NEAR) * d - 2.0 * FAR * NEAR / (FAR - NEAR)) / d
    return (ZMAX + ZMIN) / 2.0 + zn * (ZMAX - ZMIN) / 2.0


def makeramp():
    for i in range(RAMP_LO, RAMP_HI + 1):
        mapcolor(i, 0, ramp_green(i), 0)


def drawcube(angle):
    color(BLACK)
    clear()
    pushmatrix()
    translate(0.0, 0.0, -DIST)
    rotate(angle + 250, 'x')
    rotate(2 * angle + 300, 'y')
    for a, b in EDGES:
        bgnline()
        v3i(CUBE[a])
        v3i(CUBE[b])
        endline()
    popmatrix()


def main():
    prefsize(400, 400)
    winopen("depthcue")
    cmode()
    doublebuffer()
    gconfig()
    makeramp()
    perspective(400, 1.0, NEAR, FAR)
    # the ramp spans the cube's depth: its bounding sphere's near and far ends
    lshaderange(RAMP_LO, RAMP_HI, int(screen_z(DIST - HALF)), int(screen_z(DIST + HALF)))
    depthcue(TRUE)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    angle = 0
    while True:
        dev, val = qread()
        if dev == ESCKEY:
            gexit()
            sys.exit(0)
        if dev == REDRAW:
            drawcube(angle)
            swapbuffers()
            angle = (angle + 30) % 3600


if __name__ == "__main__":
    main()
