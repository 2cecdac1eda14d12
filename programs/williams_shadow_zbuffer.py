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
  24bit    fig. 3's bias with 24-bit depth: the moire is gone
  robot    curved shadows on curved surfaces: the Utah teapot's patches
           (Williams' robot is not available) over a curved floor

Reconstructed (the paper gives no numbers): the scene of programs/four_spheres
(light at infinity turned 100 degrees to the left of the viewer's bearing);
a 512 x 512 light view ("nine bits of resolution in X and Y"), orthographic
since the light is at infinity; 16-bit depth as in the paper's pictures
(the VGX has 24: the ``24bit`` figure); biases in light-window z units of
the 24-bit range (one 16-bit quantum = 256).
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
     "caption": "Fig. 3's bias with the VGX's 24-bit z: the quantization moire disappears."},
]

WIDTH, HEIGHT = 640, 480
LSIZE = 512                                  # the light view, 9 bits in x and y
LIGHT_DIST = 20.0
BIAS_REDUCED = 64                            # a quarter of a 16-bit quantum
BIAS_INCREASED = 3 * 256                     # three 16-bit quanta
DITHER_SEED = 1978


def parse(argv):
    ap = argparse.ArgumentParser(description="Williams' shadow z-buffer")
    ap.add_argument("--figure", default="6")
    ap.add_argument("--bits", type=int, default=None, help="depth bits (16 or 24)")
    return ap.parse_args(argv)


def current_mvp():
    """ModelView . Projection of the current window (row vectors)."""
    mmode(MPROJECTION)
    p = getmatrix()
    mmode(MVIEWING)
    return np.asarray(getmatrix(), np.float64) @ np.asarray(p, np.float64)


def draw_spheres():
    for c in fs.CENTRES:
        fs.sphere(c[0], c[1], c[2], 1.0)


def light_view():
    """Pass 1: the z-buffer seen from the light (no shading: wmpack(0))."""
    prefsize(LSIZE, LSIZE)
    win = winopen("light view")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    ortho(-5.0, 5.0, -5.0, 5.0, LIGHT_DIST - 6.0, LIGHT_DIST + 6.0)
    loadmatrix(np.eye(4))
    d = fs.LIGHT_DIR
    lookat(d[0] * LIGHT_DIST, d[1] * LIGHT_DIST, d[2] * LIGHT_DIST, 0.0, 0.0, 0.0, 0)
    wmpack(0)
    zclear()
    draw_spheres()
    wmpack(0xFFFFFFFF)
    return win, sb.read_depth(LSIZE, LSIZE), current_mvp()


def observer_view(ambient_only=False):
    """Pass 2: the observer's shaded view (or ambient-only for the correct form)."""
    czclear(0x00000000, getgdesc(GD_ZMAX))
    loadmatrix(np.eye(4))
    lookat(0.0, 3.0, 12.0, 0.0, 0.0, 0.0, 0)
    lmbind(LIGHT0, 0 if ambient_only else fs.SUN)
    draw_spheres()
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


def compose(figure, bits):
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
    m4 = shadow_mask(ze, mvp_e, zl, mvp_l, b, BIAS_INCREASED, bilinear=True, dither=True)
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


def main(argv=None):
    global EYE
    a = parse(sys.argv[1:] if argv is None else argv)
    prefsize(WIDTH, HEIGHT)
    EYE = winopen("williams")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, WIDTH / HEIGHT, 1.0, 50.0)
    fs.define_lighting()
    lmbind(MATERIAL, fs.SPHERE_MAT)
    lmbind(LMODEL, fs.MODEL)
    while True:
        dev, val = qread()
        if dev == REDRAW and val == EYE:
            img, show = compose(a.figure, a.bits)
            winset(show or EYE)
            w, h = getsize()
            sb.write_image(img, w, h)
            gflush()


if __name__ == "__main__":
    main()
