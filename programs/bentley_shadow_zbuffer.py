"""Bentley (1995), "Two shadow rendering algorithms", part II: the shadow
z-buffer (after Williams 1978) with one depth map per light and
percentage-closer filtering; several objects lit by two lights,
texture-mapped objects with shadows, surfaces shadowing themselves.

The paper's outline, as ported:

    1.0  for each light source                      light_view()
    1.1      make light point be center of projection
             (a local light: perspective from its position; a light at
             infinity: ortho along its direction)
    1.2      calculate transformation matrices       getmatrix() of the window
    1.3/1.4  render object using zbuffer - lighting is skipped
             (its own window, wmpack(0): depth only, no shading)
    1.5      save computed zbuffer                   readsource(SRC_ZBUFFER), lrectread
    2.0-5.0  render the object from the eye, z-buffered
    5.1      for every pixel visible from eye:       window_to_world on the eye's z
    5.1.1      transform to shadow coordinates        world_to_window in each light
    5.1.2      for every light: sample its z-buffer,
               in shadow if farther (percentage closer filtered)

Scene conventions of part I (programs/bentley_ground_shadows): z is up, the
ground is z = 0, the view is ``lookat`` on the y-up coordinates followed by
``rotate(-900, 'x')``; its objects (box, pyramid, prism, faceted ball), ground
grid, materials and light definitions are reused by import.

How the lights are combined (the paper says only "if it was not [visible to
the light], then that point is in shadow", per light).  Chosen route: an
ambient pass plus each light's contribution masked by its own shadow test
and added (Williams' "correct" form, Hart's lit/ambient pair generalised to N
lights):

    A    = eye view, lighting model ambient only, no light bound
    D_i  = eye view, model ambient 0, only light i bound (diffuse+specular of i)
    s_i  = percentage-closer fraction of light i's samples that hide the point
    C    = A + sum_i (1 - s_i) D_i

so a point hidden from one light keeps the other light's full contribution,
and only where both shadows overlap is it left with the ambient light.  With
TV_MODULATE the texture multiplies every pass alike, so A and D_i are each
textured and their sum is the textured, shadowed colour.  The passes are
drawn by the emulator, read back with lrectread and summed on the host (what
a 1995 program did with its saved z-buffers; shadowbuf.write_image puts the
sum into the window).

Reconstructions (the paper's pictures only are described, no numbers):
- fudge factor: "add a small fudge factor so that points project in front of
  themselves" -> the eye's world point is moved ``--bias`` world units
  towards the light before it is projected into the light's view (a pure
  depth offset along the light ray, for ortho and perspective lights alike);
- "area sampling ... Percent Closer Filtering" -> shadowbuf.pcf over a 3x3
  (default) or 5x5 neighbourhood of the nearest light pixel; ``--pcf 1`` is
  the single comparison of step 5.1.2.2;
- each light's view is fitted to what can cast or receive its shadows: the
  objects and their shadows on z = 0 (part I's ground matrix), or the whole
  self-shadowing surface; ground outside a light's view is lit (Williams:
  "points outside the viewing volume of the light source are illuminated");
  points beyond the light's far plane or behind a local light are lit too;
- the light's depth map is 512 x 512 (the VGX z is 24 bits deep);
- light positions: the paper's pictures show two lights and no numbers; "two"
  puts the local light behind the objects (-1, 5, 6.5) and the infinite one
  behind-left (-0.9, 1, 1.4) so both shadows and their overlap fall towards
  the viewer; "textured" moves the local light to (3.2, 3.6, 6) to light
  the cube's visible faces;
- fudge factors: 0.1 for the 512 maps of the object scenes (3x3 PCF on the
  ground at the local light's grazing periphery needs ~1.5 texels x tan of
  the incidence), 0.2 for the 128 map with 5x5 PCF, 0.04 for the sheet
  (ortho map fitted to it), 0.001 for the acne figure;
- the self-shadowing surface is a corrugated sheet z = AMP sin(2 pi x / WAVE)
  lit at WAVE_ELEVATION degrees from +x, so each crest throws a shadow into
  the next trough while the slopes facing the light stay lit.

Figures (``--figure``):
  two         several objects, a local light (perspective light view) and a
              light at infinity (ortho light view), 3x3 PCF
  compare     a close-up of the box's shadow, light map 128 x 128, one light at
              infinity: the middle half of the view twice, side by side, with
              the single comparison (left) and 5x5 PCF (right)
  textured    a checker-textured cube (texdef2d, t2f, TV_MODULATE) and a
              brick-textured ground, casting and receiving shadows, two lights
  selfshadow  the corrugated sheet at a grazing light, bias BIAS_GOOD
  acne        the same with bias BIAS_ACNE: "points ... shadow themselves"

Options (after ``--`` under vgx-run):
  --pcf 1|3|5       kernel (compare: the right half's kernel; left is 1)
  --bias B          fudge factor in world units along the light ray
  --lsize N         light depth map size       --size W H  eye window size
"""
import argparse
import math
import sys

import numpy as np

from irisgl import *
from programs import bentley_ground_shadows as B
from programs import shadowbuf as sb

FIGURES = [
    {"name": "two_lights_pcf", "args": ["--figure", "two"],
     "caption": "Bentley 1995, shadow z-buffer: multiple objects illuminated by two light "
                "sources (a local light with a perspective depth map, a light at infinity "
                "with an ortho one), 3x3 percentage-closer filtering; one light's shadow "
                "keeps the other light, the overlap is ambient only."},
    {"name": "single_vs_pcf", "args": ["--figure", "compare"],
     "caption": "A shadow edge from a 128 x 128 depth map: the single comparison (left) "
                "gives stair steps with two values; 5x5 percentage-closer filtering "
                "(right) gives intermediate values, a slightly softer edge."},
    {"name": "textured", "args": ["--figure", "textured"],
     "caption": "Shadowing of texture-mapped objects: a checker cube (texdef2d, t2f, "
                "TV_MODULATE) shadowed by a pole and casting onto a brick ground, two "
                "lights; the texture shows in light and in shadow."},
    {"name": "self_shadow", "args": ["--figure", "selfshadow"],
     "caption": "Visible surfaces shadowing themselves: a corrugated sheet lit at a grazing "
                "angle; each crest shadows the next trough (fudge factor 0.04, 3x3 PCF)."},
    {"name": "self_shadow_acne", "args": ["--figure", "acne"],
     "caption": "The same surface with too small a fudge factor (0.001): points shadow "
                "themselves or are compared with nearer neighbours - shadow acne on the "
                "lit slopes."},
]

WIDTH, HEIGHT = 640, 480
LSIZE = 512
SKY = 0x00E0C8A8
AMBIENT_MODEL = B.AMBIENT_MODEL

# the two lights of "two" and "textured": local (w = 1) and at infinity (w = 0)
LIGHTS = [(-1.0, 5.0, 6.5, 1.0), (-0.9, 1.0, 1.4, 0.0)]
LIGHT_RGB = [(0.6, 0.6, 0.6), (0.55, 0.55, 0.55)]

# -- "two": part I's objects ---------------------------------------------------
TWO_EYE, TWO_REF = B.EYE, B.REF
BIAS_TWO = 0.1

# -- "compare": one light at infinity, a close-up of the box's shadow ------------
COMPARE_LIGHT = [(-0.9, 1.0, 1.4, 0.0)]
COMPARE_RGB = [(0.7, 0.7, 0.7)]
COMPARE_EYE, COMPARE_REF = (-0.6, -4.6, 2.4), (-1.0, -1.6, 0.0)
COMPARE_LSIZE = 128
BIAS_COMPARE = 0.2

# -- "textured": checker cube, pole, brick ground ------------------------------
CUBE = (-0.8, 0.8, -0.8, 0.8, 0.0, 1.6)
CUBE_REPEAT = 2.0                   # texture repeats per face edge (2x2 squares each)
POLE = (-0.6, 1.5, 0.3, 3.6)        # centre x, y, radius, height
BRICK_SCALE = 0.5                   # texture repeats per world unit on the ground
TEX_LIGHTS = [(3.2, 3.6, 6.0, 1.0), (-0.9, 1.0, 1.4, 0.0)]
TEX_EYE, TEX_REF = (4.0, -5.0, 6.5), (-0.2, 0.4, 0.8)
BIAS_TEX = 0.1
CHECKER_TEX, BRICK_TEX, MODULATE_ENV = 1, 2, 1
CHECK_TEXELS = 64                   # 2 x 2 squares of 32 texels
CHECK_DARK = (150, 30, 25)
CHECK_LIGHT = (245, 235, 210)
BRICK_TEXELS = 64
BRICK_RGB = (190, 80, 55)
MORTAR_RGB = (200, 195, 185)

# -- "selfshadow"/"acne": the corrugated sheet -------------------------------------
SHEET_X = (-4.0, 4.0)
SHEET_Y = (-3.0, 3.0)
SHEET_Z0 = 0.5
AMP, WAVE = 0.35, 2.0
NSEG = 128
WAVE_ELEVATION = 25.0               # degrees above the horizon, light from +x
WAVE_LIGHT = [(math.cos(math.radians(WAVE_ELEVATION)), 0.0,
               math.sin(math.radians(WAVE_ELEVATION)), 0.0)]
WAVE_RGB = [(0.8, 0.8, 0.8)]
WAVE_EYE, WAVE_REF = (2.5, -8.0, 6.0), (0.0, 0.0, 0.3)
BIAS_GOOD = 0.04
BIAS_ACNE = 0.001

# materials beyond part I's (GROUND_MAT 1, OBJECT_MATS 2..5)
CUBE_MAT, POLE_MAT, TEXGROUND_MAT, SHEET_MAT = 6, 7, 8, 9
CUBE_RGB = (1.0, 1.0, 1.0)
POLE_RGB = (0.85, 0.7, 0.2)
SHEET_AMB, SHEET_DIF = (0.35, 0.4, 0.5), (0.55, 0.65, 0.8)


# -- geometry -------------------------------------------------------------------
def sheet_x():
    return np.linspace(SHEET_X[0], SHEET_X[1], NSEG + 1)


def sheet_z(x):
    return SHEET_Z0 + AMP * np.sin(2.0 * math.pi * np.asarray(x) / WAVE)


def sheet_normal(x):
    dz = AMP * 2.0 * math.pi / WAVE * math.cos(2.0 * math.pi * x / WAVE)
    n = np.array([-dz, 0.0, 1.0])
    return n / np.linalg.norm(n)


def pole():
    cx, cy, r, h = POLE
    return B.prism(cx, cy, r, 0.0, h, 12)


CUBE_POLYS = B.box(*CUBE)
POLE_POLYS = pole()


def view_lookat(eye, ref):
    """lookat on the y-up coordinates of z-up points, then z becomes y."""
    lookat(eye[0], eye[2], -eye[1], ref[0], ref[2], -ref[1], 0)
    rotate(-900, 'x')


current_mvp = sb.current_mvp



# -- drawing --------------------------------------------------------------------
def draw_polys(polys, texcoords=None):
    for poly in polys:
        bgnpolygon()
        n3f(B.normal(poly))
        for k, v in enumerate(poly):
            if texcoords is not None:
                t2f(texcoords[k])
            v3f(v)
        endpolygon()


def draw_ground(textured=False):
    """Part I's z = 0 grid (quad strips), with texture coordinates if asked."""
    if B.GROUND_LINES is None:
        B.GROUND_LINES = B._ground_lines()
    c = B.GROUND_LINES
    n3f((0.0, 0.0, 1.0))
    for x0, x1 in zip(c, c[1:]):
        bgnqstrip()
        for y in c:
            for x in (x1, x0):
                if textured:
                    t2f((x * BRICK_SCALE, y * BRICK_SCALE))
                v3f((x, y, 0.0))
        endqstrip()


def draw_sheet():
    xs = sheet_x()
    zs = sheet_z(xs)
    bgnqstrip()
    for x, z in zip(xs, zs):
        n3f(sheet_normal(x))
        v3f((x, SHEET_Y[0], z))
        v3f((x, SHEET_Y[1], z))
    endqstrip()


def draw_two(shade):
    if shade:
        lmbind(MATERIAL, B.GROUND_MAT)
    draw_ground()
    for k, obj in enumerate(B.OBJECTS):
        if shade:
            lmbind(MATERIAL, B.OBJECT_MATS[k])
        draw_polys(obj)


def draw_textured(shade):
    if shade:
        lmbind(MATERIAL, TEXGROUND_MAT)
        texbind(TX_TEXTURE_0, BRICK_TEX)
        tevbind(TV_ENV0, MODULATE_ENV)
    draw_ground(textured=shade)
    if shade:
        lmbind(MATERIAL, CUBE_MAT)
        texbind(TX_TEXTURE_0, CHECKER_TEX)
    r = CUBE_REPEAT
    draw_polys(CUBE_POLYS, [(0.0, 0.0), (r, 0.0), (r, r), (0.0, r)] if shade else None)
    if shade:
        texbind(TX_TEXTURE_0, 0)
        tevbind(TV_ENV0, 0)
        lmbind(MATERIAL, POLE_MAT)
    draw_polys(POLE_POLYS)


def draw_selfshadow(shade):
    if shade:
        lmbind(MATERIAL, SHEET_MAT)
    draw_sheet()


# -- the light's field of view: what can cast or receive its shadows -------------
def shadow_points(polys, light):
    """Object vertices and their shadows on z = 0 (part I's ground matrix)."""
    pts = np.array([v for p in polys for v in p], np.float64)
    out = [pts]
    if B.casts_shadow(light):
        h = np.concatenate((pts, np.ones((len(pts), 1))), axis=1) @ B.ground_matrix(light)
        out.append(h[:, :3] / h[:, 3:4])
    return np.concatenate(out)


def two_bounds(light):
    return shadow_points([p for obj in B.OBJECTS for p in obj], light)


def textured_bounds(light):
    return shadow_points(CUBE_POLYS + POLE_POLYS, light)


def sheet_bounds(light):
    xs = sheet_x()
    zs = sheet_z(xs)
    return np.array([(x, y, z) for x, z in zip(xs, zs) for y in SHEET_Y])


# -- scenes ---------------------------------------------------------------------
SCENES = {
    "two": dict(draw=draw_two, bounds=two_bounds, lights=LIGHTS, rgbs=LIGHT_RGB,
                eye=TWO_EYE, ref=TWO_REF, bias=BIAS_TWO, pcf=3, lsize=LSIZE, sky=SKY),
    "compare": dict(draw=draw_two, bounds=two_bounds, lights=COMPARE_LIGHT, rgbs=COMPARE_RGB,
                    eye=COMPARE_EYE, ref=COMPARE_REF, bias=BIAS_COMPARE, pcf=5,
                    lsize=COMPARE_LSIZE, sky=SKY),
    "textured": dict(draw=draw_textured, bounds=textured_bounds, lights=TEX_LIGHTS,
                     rgbs=LIGHT_RGB, eye=TEX_EYE, ref=TEX_REF, bias=BIAS_TEX, pcf=3,
                     lsize=LSIZE, sky=SKY),
    "selfshadow": dict(draw=draw_selfshadow, bounds=sheet_bounds, lights=WAVE_LIGHT,
                       rgbs=WAVE_RGB, eye=WAVE_EYE, ref=WAVE_REF, bias=BIAS_GOOD, pcf=3,
                       lsize=LSIZE, sky=SKY),
}
SCENES["acne"] = dict(SCENES["selfshadow"], bias=BIAS_ACNE)


def define_lighting(lights, rgbs):
    B.define_lighting(lights, rgbs)          # ground, objects, lmodels, LIGHT_DEFS
    lmdef(DEFMATERIAL, CUBE_MAT, 0, [AMBIENT] + list(CUBE_RGB) + [DIFFUSE] + list(CUBE_RGB)
          + [LMNULL])
    lmdef(DEFMATERIAL, POLE_MAT, 0, [AMBIENT] + list(POLE_RGB) + [DIFFUSE] + list(POLE_RGB)
          + [SPECULAR, 0.3, 0.3, 0.3, SHININESS, 25.0, LMNULL])
    lmdef(DEFMATERIAL, TEXGROUND_MAT, 0, [AMBIENT, 1.0, 1.0, 1.0, DIFFUSE, 1.0, 1.0, 1.0,
                                          LMNULL])
    lmdef(DEFMATERIAL, SHEET_MAT, 0, [AMBIENT] + list(SHEET_AMB) + [DIFFUSE] + list(SHEET_DIF)
          + [LMNULL])


def pack(rgb):
    r, g, b = rgb
    return 0xFF000000 | (b << 16) | (g << 8) | r


def define_textures():
    """A 2 x 2 checker (4 components, 0xAABBGGRR words, rows bottom to top) and
    a running-bond brick (one brick course per half texture)."""
    n = CHECK_TEXELS
    ii, jj = np.mgrid[0:n, 0:n]
    dark = ((ii // (n // 2)) + (jj // (n // 2))) % 2 == 0
    checker = np.where(dark, pack(CHECK_DARK), pack(CHECK_LIGHT)).astype(np.uint32)
    texdef2d(CHECKER_TEX, 4, n, n, checker.reshape(-1), 0,
             [TX_MAGFILTER, TX_POINT, TX_WRAP, TX_REPEAT, TX_NULL])
    n = BRICK_TEXELS
    row, col = np.mgrid[0:n, 0:n]
    course = row // (n // 2)
    shift = (course % 2) * (n // 2)
    mortar = (row % (n // 2) < 3) | ((col + shift) % n < 3)
    brick = np.where(mortar, pack(MORTAR_RGB), pack(BRICK_RGB)).astype(np.uint32)
    texdef2d(BRICK_TEX, 4, n, n, brick.reshape(-1), 0, [TX_WRAP, TX_REPEAT, TX_NULL])
    tevdef(MODULATE_ENV, 0, [TV_MODULATE, TV_NULL])


# -- pass 1: the light's depth map --------------------------------------------
def light_matrices(light, pts):
    """Set the light window's projection and viewing: centre of projection at
    a local light (perspective), or a parallel view along the direction of a
    light at infinity (ortho), fitted to ``pts``."""
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2.0
    radius = float(np.linalg.norm(hi - lo)) / 2.0
    if light[3] != 0.0:
        src = np.asarray(light[:3], np.float64)
    else:
        d = np.asarray(light[:3], np.float64)
        src = centre + d / np.linalg.norm(d) * (radius * 3.0 + 1.0)
    loadmatrix(np.identity(4))
    view_lookat(src, centre)
    V = np.asarray(getmatrix(), np.float64)
    p = np.concatenate((pts, np.ones((len(pts), 1))), axis=1) @ V
    depth = -p[:, 2]
    near, far = depth.min() * 0.9 - 0.05, depth.max() * 1.02 + 0.05
    if light[3] != 0.0:
        near = max(near, 0.05)
        half = np.degrees(np.arctan(np.maximum(np.abs(p[:, 0]), np.abs(p[:, 1])) / depth)).max()
        perspective(int(math.ceil(2 * half * 10 * 1.03)) + 2, 1.0, near, far)
    else:
        m = 0.02 * radius
        ortho(p[:, 0].min() - m, p[:, 0].max() + m, p[:, 1].min() - m, p[:, 1].max() + m,
              near, far)


def light_view(win, light, scene, lsize):
    """Steps 1.1-1.5: depth only (wmpack(0), no lighting), read back."""
    winset(win)
    mmode(MVIEWING)
    light_matrices(light, scene["bounds"](light))
    wmpack(0)
    zclear()
    scene["draw"](False)
    wmpack(0xFFFFFFFF)
    return sb.read_depth(lsize, lsize), current_mvp()


# -- pass 2: the eye's passes -------------------------------------------------
def eye_pass(scene, nlights, only, width, height):
    """Ambient only (only=None) or light ``only`` alone; returns colour and z."""
    czclear(scene["sky"] if only is None else 0, getgdesc(GD_ZMAX))
    loadmatrix(np.identity(4))
    view_lookat(scene["eye"], scene["ref"])
    for k in range(nlights):
        lmbind(LIGHT0 + k, 0)
    if only is None:
        lmbind(LMODEL, B.AMBIENT_LM)
    else:
        lmbind(LMODEL, B.DIRECT_LM)
        B.bind_lights(only, nlights)
    scene["draw"](True)
    lmbind(MATERIAL, 0)
    return sb.read_colour(width, height), sb.read_depth(width, height), current_mvp()


def shadow_fraction(ze, mvp_e, zl, mvp_l, light, bias, kernel, width, height):
    """Steps 5.1-5.1.2.2 for one light: the fraction of the kernel x kernel
    light samples nearer to the light than the eye's point (moved ``bias``
    towards the light first)."""
    world = sb.window_to_world(ze, mvp_e, width, height)
    if light[3] != 0.0:
        to_light = np.asarray(light[:3], np.float64) - world
        to_light /= np.linalg.norm(to_light, axis=-1, keepdims=True)
    else:
        to_light = np.asarray(light[:3], np.float64) / np.linalg.norm(light[:3])
    world = world + bias * to_light
    ls = zl.shape[0]
    x, y, zp = sb.world_to_window(world, mvp_l, ls, ls)
    wl = np.concatenate((world, np.ones(world.shape[:-1] + (1,))), axis=-1) @ mvp_l[:, 3]
    zp = np.minimum(zp, sb.ZMAX)                 # beyond the light's far plane: lit
    s = sb.pcf(zl, x, y, zp, 0.0, kernel)
    s[(wl <= 0.0) | (ze >= sb.ZMAX)] = 0.0      # behind a local light, background
    return s


def compose(a, scene, lwins, width, height):
    """Both passes; for ``compare`` the middle half of the picture twice, the
    single comparison on the left and the --pcf kernel on the right."""
    lights = scene["lights"]
    maps = [light_view(lwins[k], light, scene, a.lsize) for k, light in enumerate(lights)]
    winset(EYE)
    amb, ze, mvp_e = eye_pass(scene, len(lights), None, width, height)
    kernels = [1, a.pcf] if a.figure == "compare" else [a.pcf]
    outs = [amb.copy() for _ in kernels]
    for k, light in enumerate(lights):
        direct, _, _ = eye_pass(scene, len(lights), k, width, height)
        zl, mvp_l = maps[k]
        for out, kernel in zip(outs, kernels):
            s = shadow_fraction(ze, mvp_e, zl, mvp_l, light, a.bias, kernel, width, height)
            out += (1.0 - s)[..., None] * direct
    if a.figure != "compare":
        return outs[0]
    q, half = width // 4, width // 2
    out = np.concatenate((outs[0][:, q:q + half], outs[1][:, q:q + width - half]), axis=1)
    out[:, half] = 0.0                                  # the dividing line
    return out


def parse(argv):
    ap = argparse.ArgumentParser(prog="bentley_shadow_zbuffer",
                                 description=__doc__.splitlines()[0])
    ap.add_argument("--figure", choices=sorted(SCENES), default="two")
    ap.add_argument("--pcf", type=int, choices=[1, 3, 5], default=None,
                    help="percentage-closer kernel (1 = single comparison)")
    ap.add_argument("--bias", type=float, default=None,
                    help="fudge factor: world units towards the light")
    ap.add_argument("--lsize", type=int, default=None, help="light depth map size")
    ap.add_argument("--size", type=int, nargs=2, default=(WIDTH, HEIGHT), metavar=("W", "H"))
    a = ap.parse_args(argv)
    scene = SCENES[a.figure]
    a.pcf = scene["pcf"] if a.pcf is None else a.pcf
    a.bias = scene["bias"] if a.bias is None else a.bias
    a.lsize = scene["lsize"] if a.lsize is None else a.lsize
    return a


def main(argv=None):
    global EYE
    a = parse(sys.argv[1:] if argv is None else argv)
    scene = SCENES[a.figure]
    width, height = a.size
    lwins = []
    for k in range(len(scene["lights"])):
        prefsize(a.lsize, a.lsize)
        lwins.append(winopen(f"light {k}"))
        RGBmode()
        gconfig()
        zbuffer(TRUE)
        mmode(MVIEWING)
    prefsize(width, height)
    EYE = winopen("bentley shadow z-buffer")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(B.FOVY, width / height, B.NEAR, B.FAR)
    define_lighting(scene["lights"], scene["rgbs"])
    define_textures()
    qdevice(ESCKEY)
    qdevice(REDRAW)
    while True:
        dev, val = qread()
        if dev == REDRAW and val == EYE:
            img = compose(a, scene, lwins, width, height)
            winset(EYE)
            sb.write_image(img, width, height)
            gflush()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
