"""programs/bentley_ground_shadows.py (Bentley 1995, ground transformation):
the listing's matrix and its corrections, two lights at infinity with
stencil-once shadows, a local light, the listing beside the corrected matrix,
and the stability rule (w <= 0 clipped).

Expected pictures are computed with numpy from the program's constants: each
object polygon through the IRIS GL ground matrix, the z-up view (lookat then
rotate(-900, 'x')) and the perspective, to window coordinates; the union of
the projected polygons per light is that light's shadow.  Ground colours come
from the lighting equation (docs/semantics.md §9): ambient Am*Alm, plus Dm*Ci*N.L for
each light that sees the pixel.
"""

import numpy as np
import pytest

import programs.bentley_ground_shadows as B
from vgx_emulator import run_program

from reference.camera import lookat_matrix, perspective_matrix

PROGRAM = B.__file__
W, H = B.WIDTH, B.HEIGHT
MARGIN = 2
GROUND_AMB = np.array([0.55, 0.6, 0.5])
GROUND_DIF = np.array([0.55, 0.62, 0.5])
TOL = 2


# -- camera ---------------------------------------------------------------------


def view_matrix():
    """lookat on the y-up coordinates, then rotate(-900, 'x'): p . Rx . L."""
    ex, ey, ez = B.EYE
    rx, ry, rz = B.REF
    Rx = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1.0]])
    return Rx @ lookat_matrix((ex, ez, -ey), (rx, rz, -ry))


VIEW = view_matrix()
FULL = (0, W - 1)
LEFT, RIGHT = (0, W // 2 - 1), (W // 2, W - 1)


def camera(vp):
    width = vp[1] - vp[0] + 1
    return VIEW @ perspective_matrix(B.FOVY, width / H, B.NEAR, B.FAR)


def to_window(pts4, m, vp=FULL):
    c = pts4 @ m @ camera(vp)
    width = vp[1] - vp[0] + 1
    return (vp[0] - 0.5 + (c[:, 0] / c[:, 3] + 1) / 2 * width,
            (c[:, 1] / c[:, 3] + 1) / 2 * H - 0.5, c[:, 3])


def polygon_mask(xs, ys, vp=FULL):
    X, Y = np.meshgrid(np.arange(W), np.arange(H - 1, -1, -1))
    n = len(xs)
    area = sum(xs[i] * ys[(i + 1) % n] - xs[(i + 1) % n] * ys[i] for i in range(n))
    if abs(area) < 1e-9:
        return np.zeros((H, W), bool)
    sgn = 1.0 if area > 0 else -1.0
    inside = (X >= vp[0]) & (X <= vp[1])
    for i in range(n):
        x0, y0, x1, y1 = xs[i], ys[i], xs[(i + 1) % n], ys[(i + 1) % n]
        inside &= sgn * ((x1 - x0) * (Y - y0) - (y1 - y0) * (X - x0)) >= 0
    return inside


def project_polygons(m, vp=FULL, count=False):
    total = np.zeros((H, W), int)
    for obj in B.OBJECTS:
        for poly in obj:
            p = np.array([list(v) + [1.0] for v in poly])
            x, y, w = to_window(p, m, vp)
            assert (w > 0).all()
            total += polygon_mask(x, y, vp)
    return total if count else total > 0


def grow(mask, r):
    out = mask.copy()
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out |= np.roll(np.roll(mask, dy, 0), dx, 1)
    return out


def shrink(mask, r):
    return ~grow(~mask, r)


def ground_pixels(vp=FULL, radius=None):
    X, Y = np.meshgrid(np.arange(W), np.arange(H - 1, -1, -1))
    width = vp[1] - vp[0] + 1
    xn, yn = (X - vp[0] + 0.5) * 2 / width - 1, (Y + 0.5) * 2 / H - 1
    inv = np.linalg.inv(camera(vp))
    a = np.stack([xn, yn, -np.ones_like(xn), np.ones_like(xn)], -1) @ inv
    b = np.stack([xn, yn, np.ones_like(xn), np.ones_like(xn)], -1) @ inv
    a, b = a[..., :3] / a[..., 3:], b[..., :3] / b[..., 3:]
    d = b - a
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -a[..., 2] / d[..., 2]
    g = a + t[..., None] * d
    lim = radius if radius else B.GROUND_SIZE - 1.0
    depth = -(np.concatenate([g, np.ones_like(g[..., :1])], -1) @ VIEW)[..., 2]
    ok = ((t > 0) & (np.abs(g[..., 0]) < lim) & (np.abs(g[..., 1]) < lim)
          & (depth < 0.97 * B.FAR) & (X >= vp[0]) & (X <= vp[1]))
    return ok, g


def exact_shadow(g, light):
    """Ground points from which the light is blocked: the segment to a local
    light (or the ray towards an infinite one) enters a convex object."""
    lx, ly, lz, lw = light
    L = np.array([lx, ly, lz])
    d = (L - g) if lw else np.broadcast_to(L, g.shape)
    tmax = 1.0 if lw else np.inf
    hit = np.zeros(g.shape[:-1], bool)
    for obj, normals in zip(B.OBJECTS, B.NORMALS):
        t0 = np.full(g.shape[:-1], 1e-9)
        t1 = np.full(g.shape[:-1], tmax)
        for poly, n in zip(obj, normals):
            a = g @ n - n @ np.array(poly[0])
            b = d @ n
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -a / b
            t0 = np.where(b < 0, np.maximum(t0, t), t0)
            t1 = np.where(b > 0, np.minimum(t1, t), t1)
            t0 = np.where((b == 0) & (a > 0), np.inf, t0)
        hit |= t0 < t1
    return hit


def diffuse(light, rgb):
    """The ground's diffuse term for an infinite light (constant on z = 0)."""
    L = np.array(light[:3]) / np.linalg.norm(light[:3])
    return GROUND_DIF * np.array(rgb) * max(L[2], 0.0) * 255


AMBIENT = GROUND_AMB * np.array(B.AMBIENT_MODEL) * 255


def run(argv):
    return run_program(PROGRAM, frames=1, argv=argv).astype(int)


def objects_mask(vp=FULL):
    m = project_polygons(np.identity(4), vp)
    for light in B.LOCAL_LIGHT:          # the marker, for the local figures
        x, y, z = light[:3]
        for poly in B.box(x - 0.12, x + 0.12, y - 0.12, y + 0.12, z - 0.12, z + 0.12):
            px, py, _ = to_window(np.array([list(v) + [1.0] for v in poly]), np.identity(4), vp)
            m |= polygon_mask(px, py, vp)
    return m


# -- matrices ---------------------------------------------------------------------
def test_figures_contract():
    assert [f["name"] for f in B.FIGURES] == ["two_infinite", "local", "listing_vs_corrected"]


def test_listing_matrix_as_printed():
    lx, ly, lz = 1.5, -0.5, 4.0
    Wm = B.listing_matrix((lx, ly, lz, 1.0))
    assert Wm.tolist() == [[-lz, 0, lx, 0], [0, -lz, ly, 0], [0, 0, 0, 0], [0, 0, 0, -lz]]
    C = B.corrected_matrix((lx, ly, lz, 1.0))
    assert (C - Wm).tolist() == [[0] * 4, [0] * 4, [0] * 4, [0, 0, 1, 0]]
    assert B.corrected_matrix((lx, ly, lz, 0.0)).tolist() == Wm.tolist()


def homo(q):
    return q[:3] / q[3]


def test_corrected_local_matrix_projects_through_the_light():
    l = np.array([1.5, -0.5, 4.0])
    P = np.array([0.7, 1.2, 1.6])
    g = homo(B.pt_matrix_mult(B.corrected_matrix(tuple(l) + (1.0,)), P))
    assert g[2] == 0.0
    assert g[0] == pytest.approx((l[2] * P[0] - l[0] * P[2]) / (l[2] - P[2]))
    assert np.cross(P - l, g - l) == pytest.approx(np.zeros(3), abs=1e-12)   # collinear
    # the listing as printed: a parallel projection along the origin-to-light line
    q = homo(B.pt_matrix_mult(B.listing_matrix(tuple(l) + (1.0,)), P))
    assert q[:2] == pytest.approx(P[:2] - P[2] * l[:2] / l[2])
    assert np.linalg.norm(q - g) > 0.3


def test_infinite_light_listing_and_corrected_agree():
    L = (0.9, 1.1, 1.5, 0.0)
    P = np.array([0.3, -0.8, 2.0])
    a = homo(B.pt_matrix_mult(B.listing_matrix(L), P))
    b = homo(B.pt_matrix_mult(B.corrected_matrix(L), P))
    assert a == pytest.approx(b)
    assert a[:2] == pytest.approx(P[:2] - P[2] * np.array(L[:2]) / L[2])
    assert np.cross(P - a, L[:3]) == pytest.approx(np.zeros(3), abs=1e-12)


def test_irisgl_layout_and_sign():
    """Row vectors and w > 0 below the light: p . M = -(W p)."""
    light = (1.5, -0.5, 4.0, 1.0)
    M = B.ground_matrix(light)
    assert M.tolist() == [[4.0, 0, 0, 0], [0, 4.0, 0, 0], [-1.5, 0.5, 0, -1.0], [0, 0, 0, 4.0]]
    p = np.array([0.7, 1.2, 1.6, 1.0])
    q = p @ M
    assert q[3] == pytest.approx(4.0 - 1.6) and q[3] > 0
    assert q == pytest.approx(-B.pt_matrix_mult(B.corrected_matrix(light), p[:3]))
    # the listing's own sign gives w < 0 for every point below the light
    assert B.pt_matrix_mult(B.corrected_matrix(light), p[:3])[3] < 0
    assert B.pt_matrix_mult(B.listing_matrix(light), p[:3])[3] < 0
    # above the light w <= 0: clipped
    assert (np.array([0, 0, 4.5, 1.0]) @ M)[3] < 0


# -- pictures -----------------------------------------------------------------------
def test_two_infinite_lights_darken_once_per_light():
    img = run(["--figure", "two"])
    lights = B.TWO_LIGHTS
    cover = [project_polygons(B.ground_matrix(l), count=True) for l in lights]
    on, _ = ground_pixels()
    free = on & ~grow(objects_mask(), MARGIN + 1)
    ins = [shrink(c > 0, MARGIN) for c in cover]
    outs = [~grow(c > 0, MARGIN) for c in cover]
    d = [diffuse(l, rgb) for l, rgb in zip(lights, B.LIGHT_RGB)]
    cases = {"lit": (outs[0] & outs[1], AMBIENT + d[0] + d[1]),
             "shadow of light 1": (ins[0] & outs[1], AMBIENT + d[1]),
             "shadow of light 2": (outs[0] & ins[1], AMBIENT + d[0]),
             "both": (ins[0] & ins[1], AMBIENT)}
    for name, (mask, colour) in cases.items():
        m = mask & free
        assert m.sum() > 100, name
        err = np.abs(img[m] - colour).max()
        assert err <= TOL, (name, err, colour, np.unique(img[m], axis=0)[:5])
    # overlapping shadow polygons of one light (a convex object casts each shadow
    # point twice, from a front and a back face) are
    # darkened once: they have the one-light colour, not darker
    multi = (cover[0] >= 2) & shrink(cover[0] > 0, MARGIN) & outs[1] & free
    assert multi.sum() > 100
    assert np.abs(img[multi] - (AMBIENT + d[1])).max() <= TOL


def check_local(img, W_kind, vp, light, min_inside=200):
    Wm = B.listing_matrix(light) if W_kind == "listing" else B.corrected_matrix(light)
    shadow = project_polygons(B.irisgl_matrix(Wm), vp)
    on, g = ground_pixels(vp, radius=9.0)
    free = on & ~grow(objects_mask(vp), MARGIN + 1)
    inside = shrink(shadow, MARGIN) & free
    outside = ~grow(shadow, MARGIN) & free
    assert inside.sum() > min_inside and outside.sum() > 5000
    assert np.abs(img[inside] - AMBIENT).max() <= TOL        # ambient only
    assert (img[outside].sum(axis=1) > AMBIENT.sum() + 20).all()   # the light adds
    return shadow


def test_local_light_shadows():
    img = run(["--figure", "local"])
    light = B.LOCAL_LIGHT[0]
    shadow = check_local(img, "corrected", FULL, light)
    # the outline is the exact shadow (ray cast from each ground pixel)
    on, g = ground_pixels(FULL, radius=9.0)
    exact = exact_shadow(g, light) & on
    free = ~grow(objects_mask(), MARGIN + 1)
    assert not (shrink(exact, MARGIN) & ~shadow & free).any()
    assert not (shrink(shadow, MARGIN) & on & ~exact & free).any()


def test_local_light_software_route_matches():
    img = run(["--figure", "local", "--route", "software"])
    check_local(img, "corrected", FULL, B.LOCAL_LIGHT[0])


def test_listing_beside_corrected():
    img = run(["--figure", "listing"])
    light = B.LOCAL_LIGHT[0]
    left = check_local(img, "listing", LEFT, light, min_inside=40)
    right = check_local(img, "corrected", RIGHT, light)
    # the listing's parallel shadows are much smaller than the perspective ones
    assert left.sum() < 0.7 * right.sum()


def test_listing_through_multmatrix_is_the_parallel_shadow():
    img = run(["--figure", "local", "--matrix", "listing", "--route", "multmatrix"])
    check_local(img, "listing", FULL, B.LOCAL_LIGHT[0], min_inside=40)


@pytest.mark.parametrize("kind, route", [("listing", "multmatrix"), ("corrected", "multmatrix"),
                                         ("corrected", "software")])
def test_paper_sign_draws_no_shadow(kind, route):
    """With the paper's sign w = -lz (listing) or Pz - lz (corrected) is < 0
    for every vertex below the light: the clipper rejects all of it."""
    img = run(["--figure", "local", "--matrix", kind, "--route", route, "--keep-sign"])
    free, _ = free_ground(B.LOCAL_LIGHT[0], radius=9.0)
    assert free.sum() > 5000
    assert not (np.abs(img[free] - AMBIENT).max(axis=1) <= TOL).any()


# -- stability -------------------------------------------------------------------------
def marker_mask(light, vp=FULL):
    m = np.zeros((H, W), bool)
    if light[3]:
        x, y, z = light[:3]
        for poly in B.box(x - 0.12, x + 0.12, y - 0.12, y + 0.12, z - 0.12, z + 0.12):
            px, py, _ = to_window(np.array([list(v) + [1.0] for v in poly]), np.identity(4), vp)
            m |= polygon_mask(px, py, vp)
    return m


def free_ground(light, radius=12.0):
    on, g = ground_pixels(FULL, radius=radius)
    hide = project_polygons(np.identity(4)) | marker_mask(light)
    return on & ~grow(hide, MARGIN + 1), g


def test_local_light_below_the_top_of_the_column():
    """Light at z = 1.8, below the column's top (2.4): only the part below the
    light casts, the shadow runs to the horizon, nothing lands beyond the light."""
    light = (0.2, 0.9, 1.8, 1.0)
    img = run(["--light"] + [str(v) for v in light])
    free, g = free_ground(light)
    exact = exact_shadow(g, light)
    dark = (np.abs(img - AMBIENT).max(axis=2) <= TOL) & free
    assert dark.sum() > 1000
    assert not (dark & ~grow(exact, MARGIN)).any(), "shadow outside the exact one"
    inside = shrink(exact, MARGIN) & free
    assert inside.sum() > 1000 and dark[inside].all()
    # without the clipper the column's top would land on the far side of the light
    top = np.array([0.9 + 0.45, 1.7, 2.4, 1.0]) @ B.ground_matrix(light)
    assert top[3] < 0


@pytest.mark.parametrize("light", [(1.0, 0.2, 0.05, 0.0), (1.0, 0.2, 0.002, 0.0),
                                   (1.0, 0.0, 0.0, 0.0), (1.0, 0.3, -0.5, 0.0),
                                   (0.5, 0.5, -2.0, 1.0), (0.5, 0.5, 0.0, 1.0)])
def test_grazing_or_low_lights_do_not_crash_or_invert(light):
    img = run(["--light"] + [str(v) for v in light])
    assert img.shape == (H, W, 3)
    free, g = free_ground(light)
    if light[2] <= 0:                   # lights nothing on top of the ground: all ambient
        assert np.abs(img[free] - AMBIENT).max() <= TOL
        return
    d = diffuse(light, B.LOCAL_RGB[0])
    if d.max() < 3 * TOL:               # 0.1 degrees: too faint to tell from ambient
        return
    exact = exact_shadow(g, light)
    dark = (np.abs(img - AMBIENT).max(axis=2) <= TOL) & free
    assert dark.sum() > 1000             # a long shadow, drawn
    assert not (dark & ~grow(exact, MARGIN)).any()
