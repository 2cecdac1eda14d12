"""programs/tessman_flat_shadows.py (Tessman 1989): the planar shadow matrices
and the halftone shadows they draw.

The expected pictures are computed here with numpy from the program's own
constants: the chair's polygons go through position_object, the shadow
matrix, lookat and perspective (docs/semantics.md §1, §2) to window
coordinates, and the union of the projected faces is the shadow's outline.
Pixels well inside it (and not behind the chair) must show the halftone:
black exactly where the 16x16 checker has a 1 bit, at the screen phase of
the window (origin (0, 0), docs/semantics.md §8), ground colour elsewhere; pixels
well outside must be ground colour.  The stability cases are checked
against an exact float64 ray cast from each ground pixel to the light.
"""
import math

import numpy as np
import pytest

import programs.tessman_flat_shadows as T
from vgx_emulator import run_program

from reference.camera import lookat_matrix, perspective_matrix

PROGRAM = T.__file__
W, H = T.WIDTH, T.HEIGHT
GROUND = np.array(T.GROUND_RGB)
MARGIN = 2                      # pixels: vertex snapping moves edges by <= 0.5 px


# -- the camera, from lookat(3G) and perspective(3G) ---------------------------
def rot_y(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[c, 0, -s, 0], [0, 1, 0, 0], [s, 0, c, 0], [0, 0, 0, 1]])


def model_matrix():
    """position_object(): translate(OBJECT_AT) then rotate(OBJECT_TURN, 'y');
    the last call acts first on the vertex: p . R . T."""
    Tm = np.identity(4)
    Tm[3, :3] = T.OBJECT_AT
    return rot_y(T.OBJECT_TURN / 10.0) @ Tm


assert T.TWIST == 0
VIEW = lookat_matrix(T.EYE, T.REF)
PROJ = perspective_matrix(T.FOVY, W / H, T.NEAR, T.FAR)


def to_window(pts4, m):
    """Homogeneous object points (N, 4) through m, view and projection ->
    window x, y (pixel centres at integers) and clip w."""
    c = pts4 @ m @ VIEW @ PROJ
    xn, yn = c[:, 0] / c[:, 3], c[:, 1] / c[:, 3]
    return (xn + 1) / 2 * W - 0.5, (yn + 1) / 2 * H - 0.5, c[:, 3]


def polygon_mask(xs, ys):
    """Pixel centres inside a convex polygon (either winding), (H, W) with row
    0 at the top of the image."""
    X, Y = np.meshgrid(np.arange(W), np.arange(H - 1, -1, -1))
    n = len(xs)
    area = sum(xs[i] * ys[(i + 1) % n] - xs[(i + 1) % n] * ys[i] for i in range(n))
    if abs(area) < 1e-9:
        return np.zeros((H, W), bool)
    sgn = 1.0 if area > 0 else -1.0
    inside = np.ones((H, W), bool)
    for i in range(n):
        x0, y0, x1, y1 = xs[i], ys[i], xs[(i + 1) % n], ys[(i + 1) % n]
        inside &= sgn * ((x1 - x0) * (Y - y0) - (y1 - y0) * (X - x0)) >= 0
    return inside


def faces_mask(m):
    mask = np.zeros((H, W), bool)
    for _, quad in T.CHAIR:
        p = np.array([list(v) + [1.0] for v in quad])
        x, y, w = to_window(p, m)
        assert (w > 0).all()
        mask |= polygon_mask(x, y)
    return mask


def grow(mask, r):
    out = mask.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= np.roll(np.roll(mask, dy, 0), dx, 1)
    return out


def shrink(mask, r):
    return ~grow(~mask, r)


def halftone_bits():
    """(H, W) image-order array: 1 where the halftone lets a pixel be drawn;
    window (x, y) uses bit 15 - (x mod 16) of word y mod 16 (origin 0, 0)."""
    xs = np.arange(W)
    ys = np.arange(H - 1, -1, -1)
    words = np.array(T.halftone)[ys % 16]
    return (words[:, None] >> (15 - (xs[None, :] % 16))) & 1


def ground_pixels():
    """Window pixels whose ray meets the ground square in front of the eye,
    with the ground points (H, W, 3)."""
    X, Y = np.meshgrid(np.arange(W), np.arange(H - 1, -1, -1))
    xn, yn = (X + 0.5) * 2 / W - 1, (Y + 0.5) * 2 / H - 1
    inv = np.linalg.inv(VIEW @ PROJ)
    a = np.stack([xn, yn, -np.ones_like(xn), np.ones_like(xn)], -1) @ inv
    b = np.stack([xn, yn, np.ones_like(xn), np.ones_like(xn)], -1) @ inv
    a, b = a[..., :3] / a[..., 3:], b[..., :3] / b[..., 3:]
    d = b - a
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -a[..., 1] / d[..., 1]
    g = a + t[..., None] * d
    lim = T.GROUND_SIZE - 1.0        # keep off the ground's edge
    depth = -(np.concatenate([g, np.ones_like(g[..., :1])], -1) @ VIEW)[..., 2]
    ok = ((t > 0) & (np.abs(g[..., 0]) < lim) & (np.abs(g[..., 2]) < lim)
          & (depth < 0.97 * T.FAR))      # ... and off the far plane
    return ok, g


def chair_planes():
    """World-space (n, d) of every box of the chair: inside iff n.x <= d."""
    M = model_matrix()
    out = []
    for b in T.chair_boxes():
        ns, ds = [], []
        for n, quad in T.box_faces(b):
            n4 = np.array(list(n) + [0.0]) @ M
            p4 = np.array(list(quad[0]) + [1.0]) @ M
            ns.append(n4[:3])
            ds.append(n4[:3] @ p4[:3])
        out.append((np.array(ns), np.array(ds)))
    return out


def exact_shadow(g, light):
    """Ground points (..., 3) from which the light is blocked by the chair
    (segment to a local light, ray towards an infinite one)."""
    lx, ly, lz, lw = light
    L = np.array([lx, ly, lz])
    d = (L - g) if lw else np.broadcast_to(L, g.shape)
    tmax = 1.0 if lw else np.inf
    hit = np.zeros(g.shape[:-1], bool)
    for ns, ds in chair_planes():
        t0 = np.full(g.shape[:-1], 1e-9)
        t1 = np.full(g.shape[:-1], tmax)
        for n, dd in zip(ns, ds):
            a = g @ n - dd           # <= 0 inside
            b = d @ n
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -a / b
            t0 = np.where(b < 0, np.maximum(t0, t), t0)
            t1 = np.where(b > 0, np.minimum(t1, t), t1)
            t0 = np.where((b == 0) & (a > 0), np.inf, t0)
        hit |= t0 < t1
    return hit


def run(argv, frames=1):
    return run_program(PROGRAM, frames=frames, argv=argv).astype(int)


# -- the matrices ---------------------------------------------------------------
def test_figures_contract():
    names = [f["name"] for f in T.FIGURES]
    assert names == ["fig1", "fig2", "fig3", "moving"]
    for f in T.FIGURES:
        assert f["caption"] and isinstance(f["args"], list)


@pytest.mark.parametrize("light", [(0.55, 1.0, 0.35), (-2.0, 0.5, 1.5), (0.1, 3.0, -0.4)])
def test_infinite_matrix_gives_the_documented_formulas(light):
    lx, ly, lz = light
    M = np.array(T.infinite_shadow_matrix(lx, ly, lz))
    for p in [(0.3, 1.7, -0.4), (2.0, 0.5, 1.0), (-1.0, 2.2, 0.0)]:
        x, y, z = p
        q = np.array([x, y, z, 1.0]) @ M
        assert q[3] == pytest.approx(1.0)
        assert q[0] == pytest.approx(x - y * lx / ly)       # X_new = X_old - Y_old lx/ly
        assert q[1] == 0.0                                  # Y_new = 0
        assert q[2] == pytest.approx(z - y * lz / ly)       # Z_new = Z_old - Y_old lz/ly
        # the point moved along the light vector onto the ground
        assert np.cross(np.array(p) - q[:3], light) == pytest.approx(np.zeros(3), abs=1e-12)


def test_local_matrix_w_column_does_the_divide():
    lx, ly, lz = 1.6, 3.4, 1.3
    M = np.array(T.local_shadow_matrix(lx, ly, lz))
    p = np.array([0.4, 1.5, -0.7, 1.0])
    q = p @ M
    assert q[3] == pytest.approx(ly - p[1])                 # W_new = ly - Y_old
    g = q[:3] / q[3]
    assert g[0] == pytest.approx((ly * p[0] - lx * p[1]) / (ly - p[1]))
    assert g[2] == pytest.approx((ly * p[2] - lz * p[1]) / (ly - p[1]))
    assert g[1] == 0.0
    # light, point and shadow on one line, the point between the two
    L = np.array([lx, ly, lz])
    t = (p[1] - 0.0) / (ly - 0.0)
    assert g + t * (L - g) == pytest.approx(p[:3])
    # a point above the light gets w < 0: the clipper drops it
    assert (np.array([0.0, ly + 0.5, 0.0, 1.0]) @ M)[3] < 0


def test_infinite_matrix_is_the_local_one_far_away():
    lx, ly, lz = 0.55, 1.0, 0.35
    k = 1e7
    Ml = np.array(T.local_shadow_matrix(k * lx, k * ly, k * lz)) / (k * ly)
    assert Ml == pytest.approx(np.array(T.infinite_shadow_matrix(lx, ly, lz)), abs=1e-6)


def test_light_straight_down_is_scale_1_0_1():
    assert np.array(T.infinite_shadow_matrix(0.0, 1.0, 0.0)) == pytest.approx(
        np.diag([1.0, 0.0, 1.0, 1.0]))
    assert np.array(T.infinite_shadow_matrix(0.0, 2.5, 0.0)) == pytest.approx(
        np.diag([1.0, 0.0, 1.0, 1.0]))
    # and in the emulator: the hand-built matrix draws the same picture
    assert np.array_equal(run(["--figure", "fig1"]), run(["--light", "down"]))


# -- the pictures ----------------------------------------------------------------
def check_halftone_shadow(img, light):
    sm = np.array(T.shadow_matrix(light))
    M = model_matrix()
    shadow = faces_mask(M @ sm)
    chair = faces_mask(M)
    on_ground, _ = ground_pixels()
    free = on_ground & ~grow(chair, MARGIN + 1)
    inside = shrink(shadow, MARGIN) & free
    outside = ~grow(shadow, MARGIN) & free
    if light[3]:                       # the light marker
        h = 0.09
        lx, ly, lz = light[:3]
        marker = np.zeros((H, W), bool)
        for _, quad in T.box_faces((lx - h, lx + h, ly - h, ly + h, lz - h, lz + h)):
            x, y, _ = to_window(np.array([list(v) + [1.0] for v in quad]), np.identity(4))
            marker |= polygon_mask(x, y)
        outside &= ~grow(marker, MARGIN)
    assert inside.sum() > 400 and outside.sum() > 50000
    bits = halftone_bits().astype(bool)
    dark = inside & bits
    light_px = inside & ~bits
    assert (img[dark] == 0).all(), "pattern-1 pixels inside the shadow must be black"
    assert (img[light_px] == GROUND).all(), "pattern-0 pixels must keep the ground colour"
    assert (img[outside] == GROUND).all(), "no darkening outside the projected silhouette"
    # the checker's phase: (0, 0) of the window is protected (word 0x5555)
    assert T.halftone[0] == 0x5555 and halftone_bits()[H - 1, 0] == 0
    return shadow


@pytest.mark.parametrize("fig, light", [("fig1", T.LIGHT_DOWN), ("fig2", T.LIGHT_INFINITE),
                                        ("fig3", T.LIGHT_LOCAL)])
def test_shadow_outline_matches_projected_silhouette(fig, light):
    img = run(["--figure", fig])
    check_halftone_shadow(img, light)


def test_moving_light_rebuilds_the_matrix_each_frame():
    a = run(["--figure", "moving"], frames=1)
    b = run(["--figure", "moving"], frames=3)
    assert not np.array_equal(a, b)
    check_halftone_shadow(a, T.moving_light(0))
    check_halftone_shadow(b, T.moving_light(2))


def test_local_shadow_is_larger_than_the_parallel_one():
    """The local light enlarges the shadow (the divide by ly - Y_old)."""
    M = model_matrix()
    L = T.LIGHT_LOCAL
    local = faces_mask(M @ np.array(T.local_shadow_matrix(*L[:3])))
    far = faces_mask(M @ np.array(T.infinite_shadow_matrix(*L[:3])))
    assert local.sum() > 1.2 * far.sum()


# -- stability: a local light below the top of the object (docs/stability.md) ------
def check_no_inverted_shadow(img, light):
    black = (img == 0).all(axis=2)
    on_ground, g = ground_pixels()
    exact = exact_shadow(g, light) & on_ground
    chair = faces_mask(model_matrix())
    # every black pixel is on the ground within the exact shadow (or at the
    # chair's silhouette edge, where snapping moves a pixel)
    stray = black & ~grow(exact, MARGIN) & ~grow(chair, MARGIN)
    assert stray.sum() == 0, f"{stray.sum()} darkened pixels outside the exact shadow"
    return black, exact, chair


def test_local_light_below_the_top_of_the_chair():
    """Light at 1.6, between the seat (1.05) and the top of the back (2.3):
    the back above the light casts nothing (w <= 0 clipped); the part below
    casts a shadow reaching towards the horizon, not an inverted one."""
    light = (2.2, 1.6, 1.2, 1.0)
    img = run(["--light", "local", "--pos", "2.2", "1.6", "1.2"])
    black, exact, chair = check_no_inverted_shadow(img, light)
    inside = shrink(exact, MARGIN) & ~grow(chair, MARGIN + 1)
    bits = halftone_bits().astype(bool)
    assert (inside & bits).sum() > 300
    assert (img[inside & bits] == 0).all()
    # the unclipped matrix would throw the back's top past the light, to the
    # far side: nothing is drawn there
    M = model_matrix() @ np.array(T.local_shadow_matrix(*light[:3]))
    top = np.array([[-0.5, 2.3, -0.55, 1.0]]) @ M
    assert top[0, 3] < 0


@pytest.mark.parametrize("d", [(1.0, 0.02, 0.3), (-1.0, 0.05, -0.2)])
def test_infinite_light_nearly_parallel_to_the_ground(d):
    light = tuple(d) + (0.0,)
    img = run(["--light", "infinite", "--dir"] + [str(v) for v in d])
    black, exact, _ = check_no_inverted_shadow(img, light)
    assert black.sum() > 1000            # a long shadow, drawn


@pytest.mark.parametrize("argv", [["--light", "infinite", "--dir", "1", "0", "0.3"],
                                  ["--light", "infinite", "--dir", "1", "-0.5", "0"],
                                  ["--light", "infinite", "--dir", "1", "0.001", "0"],
                                  ["--light", "local", "--pos", "1", "-1", "1"],
                                  ["--light", "local", "--pos", "1", "0", "1"]])
def test_light_at_or_below_the_horizon_casts_nothing(argv):
    img = run(argv)
    assert not (img == 0).all(axis=2).any()
