"""programs/bentley_shadow_zbuffer.py (Bentley 1995, part II: the shadow
z-buffer per light with percentage-closer filtering).

Every expectation is computed here from the program's constants, without the
emulator: eye rays through the pixel centres (lookat on the y-up coordinates,
rotate(-900, 'x'), perspective), hits on the ground, the cube's top face or
the corrugated sheet, and exact shadow tests (rays to each light against the
convex objects; for the sheet, the piecewise-linear profile against the light
ray).  Pixels near any exact shadow boundary are left out, since percentage
closer filtering and the depth map's resolution blur the boundary by design.
"""
import math

import numpy as np
import pytest

import programs.bentley_shadow_zbuffer as P
from programs import bentley_ground_shadows as B
from vgx_emulator import run_program

from reference.camera import lookat_matrix, perspective_matrix

W, H = P.WIDTH, P.HEIGHT
AMB_MODEL = np.array(P.AMBIENT_MODEL)


def run(figure, *extra):
    img = run_program(P.__file__, frames=1, argv=["--figure", figure, *extra])
    assert img is not None and img.shape == (H, W, 3)
    return img[::-1].astype(int)          # row 0 at the bottom, as in IRIS GL


# -- the eye, rebuilt from the matrix conventions of docs/semantics.md §1 ------------------


def camera(eye, ref):
    Rx = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1.0]])
    view = Rx @ lookat_matrix((eye[0], eye[2], -eye[1]), (ref[0], ref[2], -ref[1]))
    return view @ perspective_matrix(B.FOVY, W / H, B.NEAR, B.FAR)


def eye_rays(eye, ref):
    """Origin (the eye) and unit directions of every pixel centre, (H, W, 3)."""
    X, Y = np.meshgrid(np.arange(W), np.arange(H))
    xn, yn = (X + 0.5) * 2 / W - 1, (Y + 0.5) * 2 / H - 1
    inv = np.linalg.inv(camera(eye, ref))
    ends = []
    for zn in (-1.0, 1.0):
        q = np.stack([xn, yn, np.full_like(xn, zn, dtype=float), np.ones_like(xn, float)], -1)
        q = q @ inv
        ends.append(q[..., :3] / q[..., 3:])
    d = ends[1] - ends[0]
    return np.asarray(eye, float), d / np.linalg.norm(d, axis=-1, keepdims=True)


def hit_plane_z(eye, d, z):
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (z - eye[2]) / d[..., 2]
    return t, eye + t[..., None] * d


def convex_hit(o, d, tmax, polys):
    """Does the ray o + t d, 0 < t < tmax, enter the convex polyhedron?"""
    shape = np.broadcast_shapes(np.shape(o), np.shape(d))[:-1]
    t0 = np.full(shape, 1e-7)
    t1 = np.broadcast_to(np.asarray(tmax, float), shape).copy()
    for poly in polys:
        n = B.normal(poly)
        a = o @ n - n @ np.array(poly[0])
        b = d @ n
        with np.errstate(divide="ignore", invalid="ignore"):
            t = -a / b
        t0 = np.where(b < 0, np.maximum(t0, t), t0)
        t1 = np.where(b > 0, np.minimum(t1, t), t1)
        t0 = np.where((b == 0) & (a > 0), np.inf, t0)
    return t0 < t1


def blocked(points, light, objects):
    """Exact shadow of ``points`` from ``light`` by convex ``objects``."""
    if light[3]:
        d = np.asarray(light[:3], float) - points
        tmax = 1.0
    else:
        d = np.broadcast_to(np.asarray(light[:3], float), points.shape)
        tmax = np.inf
    hit = np.zeros(points.shape[:-1], bool)
    for obj in objects:
        hit |= convex_hit(points, d, tmax, obj)
    return hit


def hidden_from_eye(eye, d, t, objects):
    hit = np.zeros(t.shape, bool)
    for obj in objects:
        hit |= convex_hit(np.broadcast_to(eye, d.shape), d, t, obj)
    return hit


def steady(label, valid, r):
    """Pixels whose (2r+1)^2 neighbourhood is valid and carries one label."""
    ok = valid.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            sl = np.roll(np.roll(label, dy, 0), dx, 1)
            sv = np.roll(np.roll(valid, dy, 0), dx, 1)
            ok &= sv & (sl == label)
    ok[:r + 1] = ok[-r - 1:] = False
    ok[:, :r + 1] = ok[:, -r - 1:] = False
    return ok


def ground_classes(eye, ref, lights, objects, r):
    """Visible ground pixels and their shadow class (bit k: hidden from light k)."""
    o, d = eye_rays(eye, ref)
    t, g = hit_plane_z(o, d, 0.0)
    valid = (t > 0) & (np.abs(g[..., 0]) < 10) & (np.abs(g[..., 1]) < 10)
    g = np.where(valid[..., None], g, 0.0)
    valid &= ~hidden_from_eye(o, d, np.where(valid, t, 0.0), objects)
    label = np.zeros((H, W), int)
    for k, light in enumerate(lights):
        label |= blocked(g, light, objects).astype(int) << k
    return steady(label, valid, r), label


# -- the contract -----------------------------------------------------------------
def test_figures_contract():
    names = [f["name"] for f in P.FIGURES]
    assert names == ["two_lights_pcf", "single_vs_pcf", "textured", "self_shadow",
                     "self_shadow_acne"]
    for f in P.FIGURES:
        assert f["args"][0] == "--figure" and f["caption"]
    assert P.SCENES["two"]["lights"][0][3] == 1.0 and P.SCENES["two"]["lights"][1][3] == 0.0


def test_light_views_are_perspective_and_ortho(vgx):
    """A local light gets a perspective depth map (w varies), a light at
    infinity an ortho one (w = 1); both read back from wmpack(0) windows."""
    from irisgl import (RGBmode, TRUE, gconfig, getgdesc, GD_ZMAX, MVIEWING, mmode,
                        prefsize, winopen, zbuffer)
    scene = P.SCENES["two"]
    for light in scene["lights"]:
        prefsize(64, 64)
        win = winopen("light")
        RGBmode()
        gconfig()
        zbuffer(TRUE)
        mmode(MVIEWING)
        zl, mvp = P.light_view(win, light, scene, 64)
        assert zl.shape == (64, 64)
        assert (zl < getgdesc(GD_ZMAX)).mean() > 0.5        # the scene fills the map
        col_w = mvp[:, 3]
        if light[3]:
            assert abs(col_w[2]) > 1e-3
        else:
            assert np.allclose(col_w, [0, 0, 0, 1])
        assert (vgx.image(vgx.current) == 0).all()          # wmpack(0): no colour


# -- two lights: one light's shadow keeps the other light ----------------------------
def test_two_lights_one_shadow_between_lit_and_both():
    img = run("two")
    scene = P.SCENES["two"]
    ok, label = ground_classes(scene["eye"], scene["ref"], scene["lights"], B.OBJECTS, 4)
    v = img.sum(axis=-1)
    med = {}
    for cls in range(4):
        px = v[ok & (label == cls)]
        assert px.size >= 30, f"class {cls}: only {px.size} pixels"
        med[cls] = np.median(px)
    assert med[0] > med[1] + 30 and med[0] > med[2] + 30
    assert med[1] > med[3] + 30 and med[2] > med[3] + 30
    # both shadows: the ambient light alone, Am * Alm
    amb = GROUND_AMB * AMB_MODEL * 255
    both = img[ok & (label == 3)]
    assert np.abs(np.median(both, axis=0) - amb).max() <= 2


GROUND_AMB = np.array([0.55, 0.6, 0.5])
GROUND_DIF = np.array([0.55, 0.62, 0.5])


# -- single comparison versus percentage-closer filtering ---------------------------
def test_pcf_gives_intermediate_values_single_comparison_two():
    img = run("compare")
    scene = P.SCENES["compare"]
    light = scene["lights"][0]
    ok, label = ground_classes(scene["eye"], scene["ref"], scene["lights"], B.OBJECTS, 0)
    L = np.array(light[:3]) / np.linalg.norm(light[:3])
    amb = GROUND_AMB * AMB_MODEL * 255
    lit = amb + GROUND_DIF * np.array(scene["rgbs"][0]) * L[2] * 255
    q, half = W // 4, W // 2
    left = img[:, :half]
    right = img[:, half + 1:]
    okl = ok[:, q:q + half]
    okr = ok[:, q + 1:q + half]
    labr = label[:, q + 1:q + half]

    def near(px, c):
        return np.abs(px - c).max(axis=-1) <= 3

    pl = left[okl]
    two = near(pl, amb) | near(pl, lit)
    assert near(pl, amb).sum() > 2000 and near(pl, lit).sum() > 2000
    assert (~two).sum() <= 0.002 * len(pl)              # single comparison: two values
    pr = right[okr]
    between = (~(near(pr, amb) | near(pr, lit))
               & (pr[:, 1] > amb[1] + 4) & (pr[:, 1] < lit[1] - 4))
    assert between.sum() > 1000                          # PCF: a band of intermediates
    levels = np.unique(pr[between][:, 1])
    assert len(levels) >= 10
    # the intermediates sit along the exact shadow edge: within the kernel's
    # reach (2.5 texels of the 128 map) plus the fudge factor's shift
    o, d = eye_rays(scene["eye"], scene["ref"])
    _, g = hit_plane_z(o, d[:, q + 1:q + half], 0.0)
    gp = g[okr][between]
    base = blocked(gp, light, B.OBJECTS)
    mixed = np.zeros(len(gp), bool)
    for a in np.linspace(0, 2 * math.pi, 16, endpoint=False):
        off = np.array([math.cos(a), math.sin(a), 0.0]) * 0.4
        mixed |= blocked(gp + off, light, B.OBJECTS) != base
    assert mixed.mean() > 0.98


# -- textured objects ---------------------------------------------------------------
def test_checker_visible_in_lit_and_shadowed_parts():
    img = run("textured")
    scene = P.SCENES["textured"]
    x0, x1, y0, y1, _, ztop = P.CUBE
    o, d = eye_rays(scene["eye"], scene["ref"])
    t, p = hit_plane_z(o, d, ztop)
    on = (t > 0) & (p[..., 0] > x0) & (p[..., 0] < x1) & (p[..., 1] > y0) & (p[..., 1] < y1)
    p = np.where(on[..., None], p, 0.0)
    on &= ~hidden_from_eye(o, d, np.where(on, t, 0.0), [P.POLE_POLYS])
    s = (p[..., 0] - x0) / (x1 - x0) * P.CUBE_REPEAT
    tt = (p[..., 1] - y0) / (y1 - y0) * P.CUBE_REPEAT
    fs, ft = (2 * s) % 1.0, (2 * tt) % 1.0
    inner = (fs > 0.12) & (fs < 0.88) & (ft > 0.12) & (ft < 0.88)
    dark = (np.floor(2 * s) + np.floor(2 * tt)) % 2 == 0     # texel rows/cols // 32
    objects = [P.CUBE_POLYS, P.POLE_POLYS]
    label = np.zeros((H, W), int)
    for k, light in enumerate(scene["lights"]):
        label |= blocked(p + np.array([0, 0, 1e-6]), light, objects).astype(int) << k
    ok = steady(label, on, 3) & inner
    g = img[..., 1]
    lit = ok & (label == 0)
    shadow = ok & (label != 0)
    assert shadow.sum() > 200 and lit.sum() > 200
    for region in (lit, shadow):
        assert (region & dark).sum() > 50 and (region & ~dark).sum() > 50
        assert np.median(g[region & ~dark]) - np.median(g[region & dark]) > 40
    assert np.median(g[lit & ~dark]) > np.median(g[shadow & ~dark]) + 20
    assert np.median(g[lit & dark]) >= np.median(g[shadow & dark])


# -- self-shadowing: good bias versus acne -----------------------------------------
def sheet_pixels():
    """Eye-ray hits on the corrugated sheet (the drawn piecewise-linear profile):
    mask, hit x and z, exact shadow clearance, N.L."""
    scene = P.SCENES["selfshadow"]
    o, d = eye_rays(scene["eye"], scene["ref"])
    xs = P.sheet_x()
    zs = P.sheet_z(xs)
    best = np.full((H, W), np.inf)
    hx = np.zeros((H, W))
    for xa, xb, za, zb in zip(xs, xs[1:], zs, zs[1:]):
        m = (zb - za) / (xb - xa)
        # z - za - m (x - xa) = 0 along the ray
        den = d[..., 2] - m * d[..., 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (za + m * (o[0] - xa) - o[2]) / den
        x = o[0] + t * d[..., 0]
        y = o[1] + t * d[..., 1]
        good = (t > 0) & (x >= xa) & (x <= xb) & (y > P.SHEET_Y[0]) & (y < P.SHEET_Y[1])
        take = good & (t < best)
        best = np.where(take, t, best)
        hx = np.where(take, x, hx)
    on = np.isfinite(best)
    hz = np.interp(hx, xs, zs)
    light = scene["lights"][0]
    slope = light[2] / light[0]                  # the light ray rises this much per +x
    clear = np.full((H, W), -np.inf)
    for xj, zj in zip(xs, zs):
        c = zj - (hz + (xj - hx) * slope)
        clear = np.where(xj > hx + 1e-9, np.maximum(clear, c), clear)
    dz = P.AMP * 2 * math.pi / P.WAVE * np.cos(2 * math.pi * hx / P.WAVE)
    n = np.stack([-dz, np.zeros_like(dz), np.ones_like(dz)], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    L = np.array(light[:3]) / np.linalg.norm(light[:3])
    return on, clear, n @ L


def false_shadows(img, on, clear, nl):
    """Pixels lit by exact geometry (clear of every crest by 0.05, N.L > 0.4)
    that lost more than a quarter of the light."""
    amb = np.array(P.SHEET_AMB) * AMB_MODEL * 255
    dif = np.array(P.SHEET_DIF) * np.array(P.WAVE_RGB[0]) * 255
    lit = on & (clear < -0.05) & (nl > 0.4)
    g = img[..., 1]
    expected_missing = g < amb[1] + 0.75 * dif[1] * nl
    return lit, lit & expected_missing


def test_self_shadowing_is_real_and_acne_only_with_small_bias():
    on, clear, nl = sheet_pixels()
    good = run("selfshadow")
    acne = run("acne")
    lit, false_good = false_shadows(good, on, clear, nl)
    _, false_acne = false_shadows(acne, on, clear, nl)
    assert lit.sum() > 5000
    assert false_good.sum() <= 0.01 * lit.sum()
    assert false_acne.sum() >= 0.15 * lit.sum()
    assert false_acne.sum() >= 10 * max(false_good.sum(), 1)
    # the crests' cast shadows are there: sheet pixels facing the light but
    # hidden by a crest get the ambient light only
    amb = np.array(P.SHEET_AMB) * AMB_MODEL * 255
    cast = on & (clear > 0.05) & (nl > 0.2)
    assert cast.sum() > 2000
    assert np.median(np.abs(good[cast] - amb).max(axis=-1)) <= 2
