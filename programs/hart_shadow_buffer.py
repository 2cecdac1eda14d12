"""Hart, CS418 slides "Shadows": the shadow buffer as two renders from the
eye and one z-buffer from the light, the perspective depth mapping with its
alpha and beta, and percentage-closer filtering over 3 x 3.

The slides' algorithm (Williams 78), step by step as this program does it:

1. "Render scene from light position; save only z-buffer":
   (x, y, z)_light = W_l P_l V_l (x, y, z)_world.  The light is a local
   spot light, so P_l is a *perspective* (``perspective`` + ``lookat`` from
   the light, in a LSIZE x LSIZE window).  No shading is needed:
   ``wmpack(0)`` with the z-buffer on, read back with
   ``readsource(SRC_ZBUFFER)`` + ``lrectread``.
2. "Render scene twice from viewpoint, once with light source on, once only
   with ambient; save a z-buffer": (x, y, z)_screen = W P V (x, y, z)_world.
   The ambient-only render is the same scene with the light unbound
   (``lmbind(LIGHT0, 0)``): Em + Am * (model AMBIENT).
3. "For each viewpoint image pixel compute
   (x, y, z)_vis = W_l P_l V_l V^-1 P^-1 W^-1 (x, y, z)_screen": the eye's
   z-buffer is carried back to world points through the inverse of the eye
   matrices (shadowbuf.window_to_world) and on into the light's window
   (shadowbuf.world_to_window).
4. Compare: the pixel takes the lit image where z_vis <= z_light + bias at
   (x, y)_vis and the ambient image where it is farther (in shadow).  The
   result is written into the eye window with ``lrectwrite``.
5. Percentage-closer filtering (Reeves, Salesin, Cook 87): the binary answer
   over the 3 x 3 light pixels around (x, y)_vis is averaged
   (shadowbuf.pcf); the fraction f in shadow blends the two renders,
   f * ambient + (1 - f) * lit.

The perspective depth mapping.  The slides write the projection with alpha
and beta in the z row (column vectors):

    [1 0 0 0; 0 1 0 0; 0 0 alpha beta; 0 0 -1 0] (x y z 1)^T
        = (x, y, alpha z + beta, -z)  ==  (x/-z, y/-z, -alpha - beta/z, 1)

IRIS GL's ``perspective(fovy, aspect, n, f)`` is that matrix, transposed for
row vectors: alpha = Projection[2][2] = -(f+n)/(f-n) and
beta = Projection[3][2] = -2fn/(f-n).  The viewport then maps NDC z to the
``lsetdepth(zn, zf)`` range (docs/semantics.md §5):
z_window = (zf+zn)/2 + (zf-zn)/2 * z_ndc.  So window z is again of the form

    z_window = ALPHA + BETA / z_eye,
    ALPHA = (zf+zn)/2 - (zf-zn)/2 * alpha = (zf+zn)/2 + (zf-zn)/2 * (f+n)/(f-n)
    BETA  = -(zf-zn)/2 * beta             = (zf-zn) * f * n / (f-n)

(z_eye < 0 in front of the light).  With the light's n = 4, f = 24 and the
VGX's default range zn = GD_ZMIN = -8388608, zf = GD_ZMAX = 8388607:
alpha = -1.4, beta = -9.6, ALPHA = 11744050.0, BETA = 80530632.0
(``--figure depth`` prints them as computed from the float32 matrix that
getmatrix returns, and the z read back from squares drawn at known light
distances beside ALPHA + BETA/z_eye: they agree within half a unit, the
rounding of the depth mapping).  The hyperbola is why a constant bias in
window z is worth more world distance far from the light than near it:
dz_window / d(-z_eye) = BETA / z_eye^2, so the bias of 2^18 units is
0.16 world units at the sphere (7 from the light) and 0.25 at the ground
under the objects (9 from the light).

Figures (``--figure``):
  light    the light's z-buffer (near = bright), in the light's window
  lit      the eye view, light on (no shadows)
  ambient  the eye view, ambient only (light unbound)
  hard     the shadow buffer: nearest light sample, binary lit/ambient
  pcf      3 x 3 percentage-closer filtering: fractional blend
  depth    the depth mapping: window z against light distance -z_eye, the
           curve ALPHA + BETA/z_eye and the read-back z of probe squares,
           with the light's depth image as an inset

Reconstructions (the slides give no scene and no numbers): a ground square
12 x 12 at y = 0, a sphere resting on it, a box and a torus standing on its
rim; a spot light at LIGHT_POS aimed at LIGHT_AT, its cone (SPREAD degrees)
inside the light view's 90-degree frustum, so everything the spot lights has
a light depth (outside the light's view a point counts as lit: Williams'
rule, shadowbuf.light_depth_at); the light view 512 x 512, near 4, far 24.
The bias, 2^18 light window units, was chosen by looking: 2^15 leaves acne
over the whole lit ground; 2^17 clears the ground but leaves a dotted line
along the sphere's terminator (grazing light, where the depth slope over one
light pixel is largest); 2^18 leaves only a faint stipple there in the hard
figure, which the 3 x 3 PCF hides; 2^19 removes it but doubles the world
distance of the bias. With 2^18 the shadows stay attached to the box and the
sphere. The slides' test "if z_vis < z_light then pixel is in shadow" has
lost its sides in the extraction: with IRIS GL's window z growing away from
the light, a point is in shadow when z_vis - bias > z_light. The combination
is done on the host in numpy over whole images, as a 1991 program would have
looped over the pixels of lrectread buffers. IRIS GL text (cmov2/charstr) is
not in the emulator, so the depth plot has tick marks but no labels; the
numbers are in the caption and on stdout.
"""
import argparse
import math
import sys

import numpy as np

from irisgl import *
from programs import shadowbuf as sb

FIGURES = [
    {"name": "light_depth", "args": ["--figure", "light"],
     "caption": "Hart: \"render scene from light position, save only z-buffer\". The spot "
                "light's perspective z-buffer (wmpack(0), read back with "
                "readsource(SRC_ZBUFFER)); near = bright."},
    {"name": "lit", "args": ["--figure", "lit"],
     "caption": "Hart: the eye view rendered \"once with light source on\" (local spot "
                "light, no shadows)."},
    {"name": "ambient", "args": ["--figure", "ambient"],
     "caption": "Hart: the eye view rendered \"once only with ambient\" (lmbind(LIGHT0, 0))."},
    {"name": "hard", "args": ["--figure", "hard"],
     "caption": "Hart: the shadow buffer. Each eye pixel carried into the light's window "
                "(W_l P_l V_l V^-1 P^-1 W^-1); lit image where it is not farther than the "
                "light's depth + bias, ambient image where it is (nearest light sample)."},
    {"name": "pcf", "args": ["--figure", "pcf"],
     "caption": "Hart: percentage-closer filtering over 3x3 light samples; the fraction in "
                "shadow blends the ambient and lit renders (soft, anti-aliased edges)."},
    {"name": "depth_mapping", "args": ["--figure", "depth"],
     "caption": "Hart: the perspective depth mapping of the light view (near 4, far 24, "
                "lsetdepth GD_ZMIN..GD_ZMAX). Window z (up, GD_ZMIN..GD_ZMAX) against "
                "light distance -z_eye (right, 4..24, ticks every 1): the curve "
                "z_window = ALPHA + BETA/z_eye with ALPHA = 11744050.0, "
                "BETA = 80530632.0 (slide alpha = -1.4, beta = -9.6), the dim line a linear "
                "mapping for comparison, the squares the z read back from probe squares "
                "drawn at distances 4.5..22; inset: the light's z-buffer."},
]

WIDTH, HEIGHT = 640, 480
LSIZE = 512

# eye
EYE = (5.0, 5.5, 9.5)
EYE_AT = (0.0, 0.6, -0.3)
FOVY = 420                      # tenths of degrees
NEAR, FAR = 2.0, 40.0

# light: a spot light with a perspective light view
LIGHT_POS = (-6.0, 6.0, 2.5)
LIGHT_AT = (0.2, 0.4, -0.6)
LFOVY = 900
LNEAR, LFAR = 4.0, 24.0
SPREAD = 44.0                   # spot half-angle (degrees), inside LFOVY/2
SPOT_EXP = 10.0

# objects
SPHERE_C, SPHERE_R = (-1.5, 1.0, 0.8), 1.0
BOX_C, BOX_HALF, BOX_TURN = (1.0, 0.7, -0.5), 0.7, -30.0     # turn about y, degrees
TORUS_C, TORUS_R, TORUS_r = (-2.4, 1.15, -1.8), 0.85, 0.3   # standing on its rim
TORUS_TURN = -40.0             # its axis turned from z towards -x, degrees
GROUND_HALF = 6.0

BIAS = 1 << 18                  # light window z units
PROBE_DISTANCES = (4.5, 5.0, 6.0, 7.5, 9.0, 11.0, 13.0, 15.5, 18.0, 22.0)

GROUND_MAT, SPHERE_MAT, BOX_MAT, TORUS_MAT = 1, 2, 3, 4
LAMP = 1
MODEL = 1
BACKGROUND = 0xFF301810         # 0xAABBGGRR


# -- the depth mapping ---------------------------------------------------------
def slide_alpha_beta(n, f):
    """The slides' alpha and beta: the z row of the perspective matrix."""
    return -(f + n) / (f - n), -2.0 * f * n / (f - n)


def window_alpha_beta(n, f, zn, zf):
    """ALPHA, BETA of z_window = ALPHA + BETA / z_eye, for near/far n, f and
    the lsetdepth range zn..zf."""
    a, b = slide_alpha_beta(n, f)
    return (zf + zn) / 2.0 - (zf - zn) / 2.0 * a, -(zf - zn) / 2.0 * b


def depth_constants():
    """ALPHA, BETA of the current window, derived from its projection matrix
    (getmatrix in MPROJECTION: alpha = P[2][2], beta = P[3][2]) and its
    lsetdepth range (lgetdepth)."""
    mmode(MPROJECTION)
    p = np.asarray(getmatrix(), np.float64)
    mmode(MVIEWING)
    a, b = p[2][2], p[3][2]
    zn, zf = lgetdepth()
    return (zf + zn) / 2.0 - (zf - zn) / 2.0 * a, -(zf - zn) / 2.0 * b, a, b


def probe_pixels(distances, width, height):
    """Window pixel (x, y) of the centre of each probe square: spread across
    the window at mid height."""
    k = len(distances)
    return [(int(round((i + 0.5) * width / k)), height // 2) for i in range(k)]


def depth_probe(distances, fovy, aspect, width, height):
    """Draw, in the current window (MVIEWING, a perspective loaded), a small
    square facing the viewer at each eye distance d (z_eye = -d) under an
    identity ModelView, and read back the window z at its centre pixel."""
    t = math.tan(math.radians(fovy / 20.0))
    pix = probe_pixels(distances, width, height)
    pushmatrix()
    loadmatrix(np.eye(4))
    zclear()
    out = []
    for d, (px, py) in zip(distances, pix):
        xn = (px + 0.5) / width * 2.0 - 1.0
        yn = (py + 0.5) / height * 2.0 - 1.0
        x, y = xn * d * t * aspect, yn * d * t
        s = 0.02 * d * t
        bgnpolygon()
        for dx, dy in ((-s, -s), (s, -s), (s, s), (-s, s)):
            v3f((x + dx, y + dy, -d))
        endpolygon()
    z = sb.read_depth(width, height)
    for px, py in pix:
        out.append(int(z[py, px]))
    zclear()
    popmatrix()
    return out


# -- the scene -----------------------------------------------------------------
def ground():
    n = 64
    step = 2 * GROUND_HALF / n
    for i in range(n):
        z0 = GROUND_HALF - i * step
        bgnqstrip()
        for j in range(n + 1):
            x = -GROUND_HALF + j * step
            for z in (z0 - step, z0):
                n3f((0.0, 1.0, 0.0))
                v3f((x, 0.0, z))
        endqstrip()


def sphere(c, r, slices=40, stacks=20):
    for i in range(stacks):
        phi0 = math.pi * i / stacks - math.pi / 2
        phi1 = math.pi * (i + 1) / stacks - math.pi / 2
        bgnqstrip()
        for j in range(slices + 1):
            th = 2 * math.pi * j / slices
            for phi in (phi1, phi0):
                nv = (math.cos(phi) * math.cos(th), math.sin(phi), -math.cos(phi) * math.sin(th))
                n3f(nv)
                v3f((c[0] + r * nv[0], c[1] + r * nv[1], c[2] + r * nv[2]))
        endqstrip()


def box(c, half, turn, sub=8):
    """A cube on the ground, turned about y; each face a sub x sub grid so the
    spot light's falloff is smooth under Gouraud shading."""
    pushmatrix()
    translate(c[0], c[1], c[2])
    rot(turn, 'y')
    for axis in range(3):
        for sgn in (1.0, -1.0):
            nv = [0.0, 0.0, 0.0]
            nv[axis] = sgn
            u, v = (axis + 1) % 3, (axis + 2) % 3
            if sgn < 0:
                u, v = v, u
            for i in range(sub):
                bgnqstrip()
                for j in range(sub + 1):
                    for a in (i + 1, i):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = sgn * half
                        p[u] = -half + 2 * half * a / sub
                        p[v] = -half + 2 * half * j / sub
                        n3f(nv)
                        v3f(p)
                endqstrip()
    popmatrix()


def torus(c, big, small, turn, slices=48, sides=16):
    """A ring standing on its rim, its axis along z turned about y by turn."""
    pushmatrix()
    translate(c[0], c[1], c[2])
    rot(turn, 'y')
    for i in range(slices):
        bgnqstrip()
        for j in range(sides + 1):
            ph = 2 * math.pi * j / sides
            for k in (i, i + 1):
                th = 2 * math.pi * k / slices
                ct, st, cp, sp = math.cos(th), math.sin(th), math.cos(ph), math.sin(ph)
                nv = (cp * ct, cp * st, sp)
                n3f(nv)
                v3f(((big + small * cp) * ct, (big + small * cp) * st, small * sp))
        endqstrip()
    popmatrix()


def draw_scene():
    lmbind(MATERIAL, GROUND_MAT)
    ground()
    lmbind(MATERIAL, SPHERE_MAT)
    sphere(SPHERE_C, SPHERE_R)
    lmbind(MATERIAL, BOX_MAT)
    box(BOX_C, BOX_HALF, BOX_TURN)
    lmbind(MATERIAL, TORUS_MAT)
    torus(TORUS_C, TORUS_R, TORUS_r, TORUS_TURN)


def spot_direction():
    d = np.subtract(LIGHT_AT, LIGHT_POS)
    return list(d / np.linalg.norm(d))


def define_lighting():
    lmdef(DEFMATERIAL, GROUND_MAT, 0, [AMBIENT, 0.55, 0.6, 0.5, DIFFUSE, 0.7, 0.75, 0.62,
                                       LMNULL])
    lmdef(DEFMATERIAL, SPHERE_MAT, 0, [AMBIENT, 0.8, 0.3, 0.25, DIFFUSE, 0.85, 0.3, 0.25,
                                       LMNULL])
    lmdef(DEFMATERIAL, BOX_MAT, 0, [AMBIENT, 0.3, 0.45, 0.8, DIFFUSE, 0.35, 0.5, 0.9,
                                    LMNULL])
    lmdef(DEFMATERIAL, TORUS_MAT, 0, [AMBIENT, 0.85, 0.7, 0.25, DIFFUSE, 0.9, 0.75, 0.3,
                                      LMNULL])
    lmdef(DEFLIGHT, LAMP, 0, [LCOLOR, 1.0, 0.96, 0.88, POSITION, *LIGHT_POS, 1.0,
                              SPOTDIRECTION, *spot_direction(),
                              SPOTLIGHT, SPOT_EXP, SPREAD, LMNULL])
    lmdef(DEFLMODEL, MODEL, 0, [AMBIENT, 0.3, 0.3, 0.32, LMNULL])


current_mvp = sb.current_mvp



# -- the windows ---------------------------------------------------------------
def open_eye_window():
    prefsize(WIDTH, HEIGHT)
    gid = winopen("hart: eye")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(FOVY, WIDTH / HEIGHT, NEAR, FAR)
    loadmatrix(np.eye(4))
    define_lighting()
    lmbind(LMODEL, MODEL)
    return gid


def open_light_window():
    prefsize(LSIZE, LSIZE)
    gid = winopen("hart: light")
    RGBmode()
    gconfig()
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(LFOVY, 1.0, LNEAR, LFAR)
    loadmatrix(np.eye(4))
    return gid


def light_pass():
    """Render from the light, z only (wmpack(0)); return its z-buffer and
    its ModelView . Projection."""
    loadmatrix(np.eye(4))
    lookat(*LIGHT_POS, *LIGHT_AT, 0)
    wmpack(0)
    zclear()
    draw_scene()
    wmpack(0xFFFFFFFF)
    return sb.read_depth(LSIZE, LSIZE), current_mvp()


def eye_pass(light_on):
    """Render from the eye, with the spot light or ambient only; return the
    colour, the z-buffer and ModelView . Projection."""
    czclear(BACKGROUND, getgdesc(GD_ZMAX))
    loadmatrix(np.eye(4))
    lookat(*EYE, *EYE_AT, 0)
    lmbind(LIGHT0, LAMP if light_on else 0)   # the lamp fixed in the world
    draw_scene()
    return sb.read_colour(WIDTH, HEIGHT), sb.read_depth(WIDTH, HEIGHT), current_mvp()


def shadow_fraction(ze, mvp_e, zl, mvp_l, eye_range, light_range, filtered):
    """Fraction of each eye pixel in shadow: 0/1 (nearest light sample) or
    the 3 x 3 PCF fraction.  Background pixels are 0."""
    world = sb.window_to_world(ze, mvp_e, WIDTH, HEIGHT, *eye_range)
    x, y, zp = sb.world_to_window(world, mvp_l, LSIZE, LSIZE, *light_range)
    if filtered:
        frac = sb.pcf(zl, x, y, zp, BIAS, 3)
    else:
        frac = (zp - BIAS > sb.light_depth_at(zl, x, y)).astype(np.float64)
    frac[ze >= eye_range[1]] = 0.0
    return frac


def depth_grey(zl):
    near = zl < sb.ZMAX
    v = np.zeros(zl.shape)
    if near.any():
        lo, hi = zl[near].min(), zl[near].max()
        v[near] = 255.0 - 200.0 * (zl[near] - lo) / max(1, hi - lo)
    return np.repeat(v[..., None], 3, axis=-1)


def depth_figure(lwin, ewin, zl):
    """Window z against light distance: the curve, a linear mapping, the
    probe samples, tick marks; the light's z-buffer as an inset."""
    winset(lwin)
    alpha_w, beta_w, a, b = depth_constants()
    zn, zf = lgetdepth()
    wmpack(0)
    got = depth_probe(PROBE_DISTANCES, LFOVY, 1.0, LSIZE, LSIZE)
    wmpack(0xFFFFFFFF)
    print(f"light view: near {LNEAR}, far {LFAR}, lsetdepth {zn}..{zf}")
    print(f"slide alpha = P[2][2] = {a:.6g}, beta = P[3][2] = {b:.6g}")
    print(f"z_window = ALPHA + BETA / z_eye: ALPHA = {alpha_w:.1f}, BETA = {beta_w:.1f}")
    print("   -z_eye   read back   ALPHA+BETA/z_eye   difference")
    for d, z in zip(PROBE_DISTANCES, got):
        pred = alpha_w + beta_w / (-d)
        print(f"  {d:7.2f}  {z:10d}   {pred:16.1f}   {z - pred:+.1f}")

    winset(ewin)
    mmode(MSINGLE)
    ortho2(-0.5, WIDTH - 0.5, -0.5, HEIGHT - 0.5)
    cpack(0xFF201010)
    clear()
    x0, x1, y0, y1 = 300, 620, 40, 440

    def px(d):
        return x0 + (d - LNEAR) / (LFAR - LNEAR) * (x1 - x0)

    def py(z):
        return y0 + (z - zn) / (zf - zn) * (y1 - y0)

    cpack(0xFF808080)                          # axes and ticks
    bgnline(); v2f((x0, y1)); v2f((x0, y0)); v2f((x1, y0)); endline()
    for d in range(int(LNEAR), int(LFAR) + 1):
        bgnline(); v2f((px(d), y0)); v2f((px(d), y0 - (8 if d % 5 == 0 else 4))); endline()
    for k in range(9):
        z = zn + (zf - zn) * k / 8
        bgnline(); v2f((x0, py(z))); v2f((x0 - (8 if k % 4 == 0 else 4), py(z))); endline()
    cpack(0xFF505050)                          # linear mapping, for contrast
    bgnline(); v2f((px(LNEAR), py(zn))); v2f((px(LFAR), py(zf))); endline()
    cpack(0xFF40E0FF)                          # the hyperbola
    bgnline()
    for i in range(201):
        d = LNEAR + (LFAR - LNEAR) * i / 200
        v2f((px(d), py(alpha_w + beta_w / (-d))))
    endline()
    cpack(0xFF4040FF)                          # read-back samples
    for d, z in zip(PROBE_DISTANCES, got):
        x, y = px(d), py(z)
        rectf(x - 3, y - 3, x + 3, y + 3)
    # inset: the light's z-buffer, halved
    g = depth_grey(zl)[::2, ::2]
    g = np.clip(np.floor(g + 0.5), 0, 255).astype(np.uint32)
    words = (0xFF000000 | (g[..., 2] << 16) | (g[..., 1] << 8) | g[..., 0]).astype(np.uint32)
    n = LSIZE // 2
    lrectwrite(12, 100, 12 + n - 1, 100 + n - 1, words)


def compose(figure, ewin, lwin):
    winset(lwin)
    zl, mvp_l = light_pass()
    light_range = lgetdepth()
    if figure == "light":
        sb.write_image(depth_grey(zl), LSIZE, LSIZE)
        return lwin
    if figure == "depth":
        depth_figure(lwin, ewin, zl)
        return ewin
    winset(ewin)
    eye_range = lgetdepth()
    lit, ze, mvp_e = eye_pass(True)
    if figure == "lit":
        return ewin
    amb, _, _ = eye_pass(False)
    if figure == "ambient":
        return ewin
    if figure not in ("hard", "pcf"):
        raise SystemExit(f"unknown figure {figure!r}")
    f = shadow_fraction(ze, mvp_e, zl, mvp_l, eye_range, light_range, figure == "pcf")
    sb.write_image(amb * f[..., None] + lit * (1.0 - f)[..., None], WIDTH, HEIGHT)
    return ewin


def parse(argv):
    ap = argparse.ArgumentParser(description="Hart's shadow buffer")
    ap.add_argument("--figure", default="pcf",
                    choices=["light", "lit", "ambient", "hard", "pcf", "depth"])
    return ap.parse_args(argv)


def main(argv=None):
    a = parse(sys.argv[1:] if argv is None else argv)
    ewin = open_eye_window()
    lwin = open_light_window()
    winset(ewin)
    qdevice(ESCKEY)
    while True:
        dev, val = qread()
        if dev == REDRAW and val == ewin:
            show = compose(a.figure, ewin, lwin)
            winset(show)
            gflush()
        elif dev == ESCKEY and val == 0:
            break
    gexit()


if __name__ == "__main__":
    main()
