"""The Utah teapot (Newell, 1975) from its 32 bicubic Bezier patches, two ways.

``--wire``   the classic IRIS GL picture: every patch drawn with ``patch()``
             as a web of curves, after ``defbasis`` (the Bezier matrix of the
             Programming Guide), ``patchbasis``, ``patchcurves`` and
             ``patchprecision``; no z-buffer, as patches were drawn in 1990.
(default)    the same patches as a lit, Gouraud-shaded, z-buffered surface:
             ``vgx_emulator.surfaces.draw_patch_surface`` (an emulator
             extension; IRIS GL itself draws patches only as curves)
             tessellates each patch into triangle meshes with a normal per
             vertex, lit by one infinite light bound in MVIEWING.

The data (programs/teapot_data.py) has +y up; the spout points to +x, the
handle to -x.  The viewer is in front (+z), a little above and to the right;
the light comes from the upper left and in front, fixed in the world.  All
patches of the data are oriented with cross(dP/du, dP/dv) pointing out of
the teapot (the lid knob and the bottom included), so no patch needs
``flip`` (checked in tests/test_curves.py).
"""
import argparse
import sys

from irisgl import *
from programs.teapot_data import patch_geometry
from vgx_emulator.surfaces import draw_patch_surface

FIGURES = [
    {"name": "surface", "args": [],
     "caption": "The Utah teapot's 32 Bezier patches as a lit, Gouraud-shaded, "
                "z-buffered surface (8 x 8 quads per patch)."},
    {"name": "wire", "args": ["--wire"],
     "caption": "The same 32 patches as IRIS GL draws them: patch() with a Bezier "
                "basis, patchcurves(4, 4), patchprecision(12, 12)."},
]

WIDTH, HEIGHT = 640, 480
EYE = (3.0, 5.0, 9.0)
CENTRE = (0.25, 1.4, 0.0)

BEZIER = 1
BEZIER_MATRIX = [[-1.0, 3.0, -3.0, 1.0],
                 [3.0, -6.0, 3.0, 0.0],
                 [-3.0, 3.0, 0.0, 0.0],
                 [1.0, 0.0, 0.0, 0.0]]
UCURVES, VCURVES = 4, 4
UPREC, VPREC = 12, 12
SURFACE_SEGS = 8

GLAZE = 1
LAMP = 1
MODEL = 1
LIGHT_DIR = [-1.0, 1.0, 0.8, 0.0]      # towards the light: upper left, in front


def define_lighting():
    lmdef(DEFMATERIAL, GLAZE, 0, [AMBIENT, 0.2, 0.2, 0.2,
                                  DIFFUSE, 0.8, 0.55, 0.3,
                                  SPECULAR, 0.6, 0.6, 0.6,
                                  SHININESS, 40.0, LMNULL])
    lmdef(DEFLIGHT, LAMP, 0, [LCOLOR, 1.0, 1.0, 1.0, POSITION] + LIGHT_DIR + [LMNULL])
    lmdef(DEFLMODEL, MODEL, 0, [AMBIENT, 0.15, 0.15, 0.15, LMNULL])


def draw_wire(patches):
    cpack(0x00402010)
    clear()
    pushmatrix()
    lookat(EYE[0], EYE[1], EYE[2], CENTRE[0], CENTRE[1], CENTRE[2], 0)
    cpack(0x0040ffff)                  # yellow curves
    for gx, gy, gz in patches:
        patch(gx, gy, gz)
    popmatrix()
    swapbuffers()


def draw_surface(patches):
    czclear(0x00402010, getgdesc(GD_ZMAX))
    pushmatrix()
    lookat(EYE[0], EYE[1], EYE[2], CENTRE[0], CENTRE[1], CENTRE[2], 0)
    lmbind(LIGHT0, LAMP)               # bound under the viewing transform: fixed in the world
    for gx, gy, gz in patches:
        draw_patch_surface(gx, gy, gz, SURFACE_SEGS, SURFACE_SEGS)
    popmatrix()
    swapbuffers()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wire", action="store_true", help="draw the patches as curves (patch())")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)

    prefsize(WIDTH, HEIGHT)
    winopen("teapot")
    RGBmode()
    doublebuffer()
    gconfig()
    mmode(MVIEWING)
    perspective(400, WIDTH / HEIGHT, 1.0, 50.0)

    defbasis(BEZIER, BEZIER_MATRIX)
    patchbasis(BEZIER, BEZIER)
    patchcurves(UCURVES, VCURVES)
    patchprecision(UPREC, VPREC)
    patches = patch_geometry()

    if not args.wire:
        zbuffer(TRUE)
        define_lighting()
        lmbind(MATERIAL, GLAZE)
        lmbind(LMODEL, MODEL)

    qdevice(ESCKEY)
    while True:
        dev, val = qread()
        if dev == REDRAW:
            reshapeviewport()
            if args.wire:
                draw_wire(patches)
            else:
                draw_surface(patches)
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
