"""fog_cutaway: a checkered plain fading into fog, with a cut-away ball.

A program of our own in the style of a 1990 C listing ported line by line:
per-vertex fog (fogvertex FG_VTX_LIN, or FG_VTX_EXP2 with the argument
"exp2") over a z-buffered ground of 4 x 4 squares and a row of posts, the
background cleared to the fog colour; a Gouraud-shaded ball in front is cut
in half by a user clipping plane (clipplane CP_DEFINE/CP_ON) defined in the
ball's own coordinates, so its right half is gone.  Redraws on REDRAW,
exits on ESC.
"""
import math
import sys

from irisgl import *

FIGURES = [
    {"name": "fog_cutaway", "args": [],
     "caption": "Linear per-vertex fog (start 5, end 60) over a checkered plain and a row "
                "of posts; a ball cut in half by clipplane(0, CP_DEFINE, [-1, 0, 0, 0])."},
    {"name": "fog_cutaway_exp2", "args": ["exp2"],
     "caption": "The same scene under FG_VTX_EXP2 haze, density 0.03."},
]

WIDTH, HEIGHT = 400, 300
FOG = [0.6, 0.6, 0.8]                       # r, g, b of the fog and the sky
FOGWORD = 0xFFCC9999                        # the same colour for czclear
LIGHT = (-0.5, 0.6, 0.62)                   # direction of the light on the ball
BALL = (0.0, 0.0, -12.0, 2.5)               # centre and radius
SLICES, STACKS = 24, 12


def ground():
    """Squares 4 x 4 at y = -2, x -20..20, z -3..-83, two greens."""
    for i in range(10):
        for j in range(20):
            x0, z0 = -20.0 + 4 * i, -3.0 - 4 * j
            if (i + j) % 2:
                cpack(0xFF208020)
            else:
                cpack(0xFF60C060)
            bgnpolygon()
            v3f([x0, -2.0, z0])
            v3f([x0 + 4, -2.0, z0])
            v3f([x0 + 4, -2.0, z0 - 4])
            v3f([x0, -2.0, z0 - 4])
            endpolygon()


def post(x, z):
    """A yellow post 0.6 wide and 3 high standing on the ground (front face)."""
    cpack(0xFF00FFFF)
    bgnpolygon()
    v3f([x - 0.3, -2.0, z])
    v3f([x + 0.3, -2.0, z])
    v3f([x + 0.3, 1.0, z])
    v3f([x - 0.3, 1.0, z])
    endpolygon()


def ball():
    """A latitude/longitude ball, coloured per vertex by a fixed light."""
    cx, cy, cz, r = BALL
    ln = math.sqrt(sum(c * c for c in LIGHT))
    for i in range(STACKS):
        bgnqstrip()
        for j in range(SLICES + 1):
            th = 2 * math.pi * j / SLICES
            for k in (i + 1, i):
                phi = math.pi * k / STACKS - math.pi / 2
                n = (math.cos(phi) * math.cos(th), math.sin(phi), math.cos(phi) * math.sin(th))
                d = max(0.0, sum(a * b for a, b in zip(n, LIGHT)) / ln)
                c3f([0.25 + 0.75 * d, 0.1 + 0.2 * d, 0.1])
                v3f([cx + r * n[0], cy + r * n[1], cz + r * n[2]])
        endqstrip()


def draw_scene():
    czclear(FOGWORD, getgdesc(GD_ZMAX))
    fogvertex(FG_ON)
    ground()
    for z in (-10.0, -20.0, -30.0, -40.0, -50.0):
        post(-6.0, z)
        post(6.0, z)
    fogvertex(FG_OFF)
    pushmatrix()
    translate(BALL[0], BALL[1], BALL[2])
    clipplane(0, CP_DEFINE, [-1.0, 0.0, 0.0, 0.0])    # keep x <= 0 of the ball
    popmatrix()
    clipplane(0, CP_ON, [0.0, 0.0, 0.0, 0.0])
    ball()
    clipplane(0, CP_OFF, [0.0, 0.0, 0.0, 0.0])
    swapbuffers()


def main():
    haze = len(sys.argv) > 1 and sys.argv[1] == "exp2"
    prefsize(WIDTH, HEIGHT)
    winopen("fog_cutaway")
    RGBmode()
    doublebuffer()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(450, WIDTH / HEIGHT, 1.0, 100.0)
    loadmatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    if haze:
        fogvertex(FG_VTX_EXP2, [0.03] + FOG)
    else:
        fogvertex(FG_VTX_LIN, [5.0, 60.0] + FOG)
    qdevice(ESCKEY)
    qdevice(REDRAW)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            draw_scene()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
