"""Williams (1978), figure 1: "The observer's view of four spheres."

Lit, Gouraud-shaded, z-buffered; no shadows yet (the shadow passes come with
the seed programs).  The light source is at infinity, "rotated one hundred
degrees about the vertical axis to the left of the observer's bearing": the
viewer looks along -z, so its bearing (towards the eye) is +z, and the light
direction is +z turned 100 degrees about +y towards -x:
(-sin 100, 0, cos 100) = (-0.985, 0, -0.174), a light from the left and a
little behind the spheres.

Reconstruction (the paper gives no coordinates): four spheres of radius 1 in
a row along x, 2.3 apart, alternately 0.6 nearer and farther, seen from
slightly above; each sphere a 32 x 16 latitude/longitude mesh drawn with
bgnqstrip, a normal per vertex.  Written as an IRIS GL program of 1991
would be: configuration, an event loop on REDRAW, swapbuffers.

The gallery shows this picture once, as Williams fig. 1 of
williams_shadow_zbuffer.py (which draws this scene), so the program lists
no FIGURES of its own.
"""
import math

from irisgl import *

WIDTH, HEIGHT = 640, 480
SLICES, STACKS = 32, 16
CENTRES = [(-3.45, 0.0, 0.6), (-1.15, 0.0, -0.6), (1.15, 0.0, 0.6), (3.45, 0.0, -0.6)]
BEARING_TURN = 100.0          # degrees, about the vertical axis, to the left
LIGHT_DIR = [-math.sin(math.radians(BEARING_TURN)), 0.0,
             math.cos(math.radians(BEARING_TURN)), 0.0]

SPHERE_MAT = 1
SUN = 1
MODEL = 1


def sphere(cx, cy, cz, r):
    """A unit-normal latitude/longitude sphere, one quad strip per band."""
    for i in range(STACKS):
        phi0 = math.pi * i / STACKS - math.pi / 2
        phi1 = math.pi * (i + 1) / STACKS - math.pi / 2
        bgnqstrip()
        for j in range(SLICES + 1):
            th = 2 * math.pi * j / SLICES
            for phi in (phi1, phi0):
                n = (math.cos(phi) * math.cos(th), math.sin(phi), -math.cos(phi) * math.sin(th))
                n3f(n)
                v3f((cx + r * n[0], cy + r * n[1], cz + r * n[2]))
        endqstrip()


def define_lighting():
    lmdef(DEFMATERIAL, SPHERE_MAT, 0, [AMBIENT, 0.15, 0.15, 0.15,
                                       DIFFUSE, 0.75, 0.72, 0.68,
                                       SPECULAR, 0.5, 0.5, 0.5,
                                       SHININESS, 30.0, LMNULL])
    lmdef(DEFLIGHT, SUN, 0, [LCOLOR, 1.0, 1.0, 1.0, POSITION] + LIGHT_DIR + [LMNULL])
    lmdef(DEFLMODEL, MODEL, 0, [AMBIENT, 0.1, 0.1, 0.1, LMNULL])


def draw_scene():
    czclear(0x00000000, getgdesc(GD_ZMAX))
    pushmatrix()
    lookat(0.0, 3.0, 12.0, 0.0, 0.0, 0.0, 0)
    lmbind(LIGHT0, SUN)           # the light stays fixed in the world
    for c in CENTRES:
        sphere(c[0], c[1], c[2], 1.0)
    popmatrix()
    swapbuffers()


def main():
    prefsize(WIDTH, HEIGHT)
    winopen("four spheres")
    RGBmode()
    doublebuffer()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, WIDTH / HEIGHT, 1.0, 50.0)
    define_lighting()
    lmbind(MATERIAL, SPHERE_MAT)
    lmbind(LMODEL, MODEL)
    qdevice(ESCKEY)
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
