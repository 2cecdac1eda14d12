"""Williams (1978), "Casting curved shadows on curved surfaces": the shadow
z-buffer on the four spheres, figures 1-6, both forms of the algorithm.

The algorithm, as the paper states it:
1. a view of the scene from the light source; "only the Z values and not the
   shading values need be computed" -> a light window drawn with wmpack(0)
   and the z-buffer on, read back with readsource(SRC_ZBUFFER);
2. the observer's view; every visible point is transformed into the light's
   view and tested against the light depth.  The paper's pictures use the
   *post-process* form (the whole image is shaded, then points found in shadow
   are darkened, so highlights are darkened rather than removed); the
   "correct" form shades points in shadow without the light (no highlights in
   shadow).  Both are here (``--figure 6`` and ``--figure correct``).

Figures (``--figure``):
  1  the observer's view (lit, no shadow)
  2  the spheres seen from the light (its depth image, near = white)
  3  shadow alone with reduced bias: the quantization moire (16-bit z)
  4  increased bias, bilinear interpolation of light depths, dither of one
     quantum (uniform in -0.5..+0.5 quanta)
  5  fig. 4 low-pass filtered (a 5x5 box; the paper's edge-dequantizing filter
     is not specified further)
  6  the filtered shadow applied to fig. 1 as a translucent shadow (post-process)
  correct  the correct form: shadowed points shaded by ambient light only
  24bit    fig. 3's bias with 24-bit depth: the moire stays (x, y quantization
           dominates: "the problem is much greater than in Z")
  robot    curved shadows on curved surfaces: the Utah teapot's patches
           (Williams' robot is not available) over a curved floor

Reconstructed (the paper gives no numbers): the scene of programs/four_spheres
(light at infinity turned 100 degrees to the left of the viewer's bearing);
a 512 x 512 light view ("nine bits of resolution in X and Y"), orthographic
since the light is at infinity; 16-bit depth as in the paper's pictures
(the VGX has 24: the ``24bit`` figure); the reduced bias of fig. 3 is a
quarter of a 16-bit quantum (64 units of the 24-bit range); the increased
bias of figs. 4-6 is 0.04 world units along the light (about two texels of
the light view at the spheres' slope), because here, as Williams observes,
the lateral quantization (10 units over 512 pixels) dominates the depth
quantization.
"""
import argparse
import sys

import numpy as np

from irisgl import *
from programs import four_spheres as fs
from programs import shadowbuf as sb

FIGURES = [
    {"name": "fig1", "args": ["--figure", "1"],
     "caption": "Williams fig. 1: the observer's view of four spheres."},
    {"name": "fig2", "args": ["--figure", "2"],
     "caption": "Williams fig. 2: the four spheres viewed from the position of the light "
                "source (its z-buffer, near = bright)."},
    {"name": "fig3", "args": ["--figure", "3"],
     "caption": "Williams fig. 3: shadow with reduced surface bias reveals quantization "
                "moire (16-bit z)."},
    {"name": "fig4", "args": ["--figure", "4"],
     "caption": "Williams fig. 4: increased bias, bilinear interpolation of light depths "
                "and dither applied to the shadow computation."},
    {"name": "fig5", "args": ["--figure", "5"],
     "caption": "Williams fig. 5: low-pass filtering applied to the shadow."},
    {"name": "fig6", "args": ["--figure", "6"],
     "caption": "Williams fig. 6: shadow applied to the image of fig. 1 (post-process form: "
                "highlights darkened)."},
    {"name": "correct", "args": ["--figure", "correct"],
     "caption": "Williams' \"correct\" form: points in shadow shaded without the light, "
                "so no highlight survives in shadow."},
    {"name": "24bit", "args": ["--figure", "24bit"],
     "caption": "Fig. 3's bias with the VGX's 24-bit z: the moire stays, because the lateral "
                "quantization (9 bits in x and y) dominates, as Williams observes."},
    {"name": "curved", "args": ["--figure", "correct", "--scene", "teapot", "--bits", "24"],
     "caption": "In the spirit of fig. 8: curved shadows on curved surfaces. The Utah "
                "teapot's 32 bicubic patches shadow themselves and a bicubic floor "
                "(correct form, 24-bit z, filtered)."},
]

WIDTH, HEIGHT = 640, 480
LSIZE = 512                                  # the light view, 9 bits in x and y
LIGHT_DIST = 20.0
BIAS_REDUCED = 64                            # a quarter of a 16-bit quantum
BIAS_INCREASED = 3 * 256                     # three 16-bit quanta (--bias overrides)
DITHER_SEED = 1978


def parse(argv):
    ap = argparse.ArgumentParser(description="Williams' shadow z-buffer")
    ap.add_argument("--figure", default="6")
    ap.add_argument("--bits", type=int, default=None, help="depth bits (16 or 24)")
    ap.add_argument("--scene", choices=sorted(SCENES), default="spheres")
    ap.add_argument("--bias", type=float, default=None,
                    help="increased bias in world units along the light (default: 3 "
                         "16-bit quanta for the spheres, 0.08 for the teapot)")
    return ap.parse_args(argv)


current_mvp = sb.current_mvp



def draw_spheres():
    for c in fs.CENTRES:
        fs.sphere(c[0], c[1], c[2], 1.0)


# -- the curved-surfaces scene: the teapot's patches on a bicubic floor -------
FLOOR_MAT, GLAZE_MAT = 2, 3
_FLOOR_Y = [[0.0, 0.5, -0.3, 0.2], [0.4, -0.6, 0.5, -0.2],
            [-0.3, 0.6, -0.5, 0.3], [0.1, -0.2, 0.4, 0.0]]


def floor_patch():
    """A 10 x 10 wavy Bezier floor; u runs to +x, v to -z, so dP/du x dP/dv is up."""
    xs = [-5.0, -5.0 / 3, 5.0 / 3, 5.0]
    gx = [xs[:] for _ in range(4)]
    gz = [[5.0 - 10.0 * i / 3] * 4 for i in range(4)]
    gy = [[y - 0.2 for y in row] for row in _FLOOR_Y]
    return gx, gy, gz


def draw_teapot_scene():
    from programs.teapot_data import patch_geometry
    from vgx_emulator.surfaces import draw_patch_surface
    defbasis(1, [[-1, 3, -3, 1], [3, -6, 3, 0], [-3, 3, 0, 0], [1, 0, 0, 0]])
    patchbasis(1, 1)
    lmbind(MATERIAL, FLOOR_MAT)
    gx, gy, gz = floor_patch()
    draw_patch_surface(gx, gy, gz, 24, 24)
    lmbind(MATERIAL, GLAZE_MAT)
    for px, py, pz in patch_geometry():
        draw_patch_surface(px, py, pz, 8, 8)
    lmbind(MATERIAL, fs.SPHERE_MAT)


#: scene -> (draw, eye, look-at point, light direction, light box half size)
SCENES = {
    "spheres": (draw_spheres, (0.0, 3.0, 12.0), (0.0, 0.0, 0.0), fs.LIGHT_DIR, 5.0),
    "teapot": (draw_teapot_scene, (6.0, 6.0, 10.0), (0.0, 1.0, 0.0),
               [-0.6, 1.0, 0.5, 0.0], 7.0),
}
SCENE = SCENES["spheres"]


def light_view():
    """Pass 1: the z-buffer seen from the light (no shading: wmpack(0))."""
    prefsize(LSIZE, LSIZE)
    win = winopen("light view")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    draw, _, at, d, half = SCENE
    n = float(np.linalg.norm(d[:3]))
    d = [c / n for c in d[:3]]
    ortho(-half, half, -half, half, LIGHT_DIST - half - 1.0, LIGHT_DIST + half + 1.0)
    loadmatrix(np.eye(4))
    lookat(at[0] + d[0] * LIGHT_DIST, at[1] + d[1] * LIGHT_DIST, at[2] + d[2] * LIGHT_DIST,
           at[0], at[1], at[2], 0)
    wmpack(0)
    zclear()
    draw()
    wmpack(0xFFFFFFFF)
    return win, sb.read_depth(LSIZE, LSIZE), current_mvp()


def observer_view(ambient_only=False):
    """Pass 2: the observer's shaded view (or ambient-only for the correct form)."""
    czclear(0x00000000, getgdesc(GD_ZMAX))
    draw, eye, at, _, _ = SCENE
    loadmatrix(np.eye(4))
    lookat(eye[0], eye[1], eye[2], at[0], at[1], at[2], 0)
    lmbind(LIGHT0, 0 if ambient_only else fs.SUN)
    draw()
    return sb.read_colour(WIDTH, HEIGHT), sb.read_depth(WIDTH, HEIGHT), current_mvp()


def shadow_mask(ze, mvp_e, zl, mvp_l, bits, bias, bilinear=False, dither=False):
    """1 where the observer's visible point is farther from the light than the
    light saw (in shadow), 0 where lit; background pixels are 0."""
    ze_q = sb.quantize(ze, bits)
    zl_q = sb.quantize(zl, bits)
    world = sb.window_to_world(ze_q, mvp_e, WIDTH, HEIGHT)
    x, y, zp = sb.world_to_window(world, mvp_l, LSIZE, LSIZE)
    if dither:
        quantum = float(1 << (24 - bits))
        rng = np.random.default_rng(DITHER_SEED)
        zp = zp + rng.uniform(-0.5, 0.5, zp.shape) * quantum
    zref = sb.light_depth_at(zl_q, x, y, bilinear)
    mask = (zp - bias > zref).astype(np.float64)
    mask[ze >= sb.ZMAX] = 0.0
    return mask


def mask_image(mask):
    v = (1.0 - mask) * 255.0
    return np.repeat(v[..., None], 3, axis=-1)


def bias_units(world):
    """A distance along the light direction in light-window z units."""
    half = SCENE[4]
    return world / (2.0 * (half + 1.0)) * float(sb.ZMAX - sb.ZMIN)


def compose(figure, bits, bias=None):
    lwin, zl, mvp_l = light_view()
    winset(EYE)
    lit, ze, mvp_e = observer_view()
    if figure == "1":
        return lit, None
    if figure == "2":
        near = zl < sb.ZMAX
        zn = (zl - zl[near].min()) / max(1, zl[near].max() - zl[near].min()) if near.any() else zl
        v = np.where(near, 255.0 - 200.0 * zn, 0.0)
        return np.repeat(v[..., None], 3, axis=-1), lwin
    b = bits or (24 if figure == "24bit" else 16)
    if figure in ("3", "24bit"):
        return mask_image(shadow_mask(ze, mvp_e, zl, mvp_l, b, BIAS_REDUCED)), None
    big = BIAS_INCREASED if bias is None else bias_units(bias)
    m4 = shadow_mask(ze, mvp_e, zl, mvp_l, b, big, bilinear=True, dither=True)
    if figure == "4":
        return mask_image(m4), None
    m5 = sb.box_blur(m4, 2)
    m5[ze >= sb.ZMAX] = 0.0
    if figure == "5":
        return mask_image(m5), None
    if figure == "6":
        # translucent shadow: darken to the ambient level of the shading
        return lit * (1.0 - 0.8 * m5)[..., None], None
    if figure == "correct":
        amb, _, _ = observer_view(ambient_only=True)
        return amb * m5[..., None] + lit * (1.0 - m5)[..., None], None
    raise SystemExit(f"unknown figure {figure!r}")


def define_lighting(scene):
    fs.define_lighting()
    if scene == "teapot":
        d = SCENES["teapot"][3]
        lmdef(DEFLIGHT, fs.SUN, 0, [LCOLOR, 1.0, 1.0, 1.0, POSITION] + list(d) + [LMNULL])
        lmdef(DEFLMODEL, fs.MODEL, 0, [AMBIENT, 0.25, 0.25, 0.25, LMNULL])
    lmdef(DEFMATERIAL, FLOOR_MAT, 0, [AMBIENT, 0.3, 0.35, 0.3, DIFFUSE, 0.45, 0.6, 0.45,
                                      LMNULL])
    lmdef(DEFMATERIAL, GLAZE_MAT, 0, [AMBIENT, 0.4, 0.3, 0.2, DIFFUSE, 0.85, 0.55, 0.3,
                                      SPECULAR, 0.6, 0.6, 0.6, SHININESS, 40.0, LMNULL])


def main(argv=None):
    global EYE, SCENE
    a = parse(sys.argv[1:] if argv is None else argv)
    SCENE = SCENES[a.scene]
    prefsize(WIDTH, HEIGHT)
    EYE = winopen("williams")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, WIDTH / HEIGHT, 1.0, 50.0)
    define_lighting(a.scene)
    lmbind(MATERIAL, fs.SPHERE_MAT)
    lmbind(LMODEL, fs.MODEL)
    while True:
        dev, val = qread()
        if dev == REDRAW and val == EYE:
            bias = a.bias if a.bias is not None else (0.08 if a.scene == "teapot" else 0.04)
            img, show = compose(a.figure, a.bits, bias)
            winset(show or EYE)
            w, h = getsize()
            sb.write_image(img, w, h)
            gflush()


if __name__ == "__main__":
    main()
