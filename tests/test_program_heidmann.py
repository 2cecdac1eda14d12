"""programs/heidmann_shadow_volumes.py (Heidmann 1991, stencil shadow volumes)
runs headless, and its shadows are where the scene geometry puts them: the
stencil after one light's volume pass holds MYZERO + the number of shadow
volumes each visible point lies in (counted here independently, by casting
the segment point -> light against the convex casters), shadowed ground is
darker than lit ground, the soft-shadow figure has a penumbra, and the z-fail
variant is right where the article's z-pass count fails (eye inside a
volume)."""
import warnings
from pathlib import Path

import numpy as np
import pytest

from irisgl import *
from irisgl._current import machine
from programs import heidmann_shadow_volumes as H
from vgx_emulator import run_program

ROOT = Path(__file__).resolve().parent.parent
PROGRAM = ROOT / "programs" / "heidmann_shadow_volumes.py"
W, HGT = 320, 240
SIZE = ["--size", f"{W}x{HGT}"]


def run(*args):
    """Run the program headless; return (image, stencil bank, z bank, V, P)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        img = run_program(PROGRAM, frames=1, argv=list(args) + SIZE)
    machine.flush()
    sten = machine.current.fb.stencil.astype(int).copy()
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, W - 1, HGT - 1).astype(np.int64)
    readsource(SRC_AUTO)
    return img, sten, z


def scene(figure):
    opts = H.parse(["--figure", figure])
    H.setup(opts)
    return opts


def matrices(opts):
    """ModelView (the figure's lookat) and Projection, from the library,
    in the window the program left open."""
    mmode(MVIEWING)
    pushmatrix()
    loadmatrix(np.eye(4))
    lookat(*H.eye, *opts.ref, 0)
    V = np.array(getmatrix(), float)
    popmatrix()
    mmode(MPROJECTION)
    P = np.array(getmatrix(), float)
    mmode(MVIEWING)
    return V @ P                          # row vectors: p_clip = [x y z 1] V P


def to_pixel(M, p):
    c = np.append(p, 1.0) @ M
    n = c[:3] / c[3]
    return int(round((n[0] + 1) / 2 * W - 0.5)), int(round((n[1] + 1) / 2 * HGT - 0.5))


def unproject(M, z):
    """World points seen at every pixel centre, from the z bank."""
    inv = np.linalg.inv(M)
    lo, hi = getgdesc(GD_ZMIN), getgdesc(GD_ZMAX)
    ys, xs = np.mgrid[0:HGT, 0:W]
    nx = (xs + 0.5) / W * 2 - 1
    ny = (ys + 0.5) / HGT * 2 - 1
    nz = (z - (hi + lo) / 2) / ((hi - lo) / 2)
    c = np.stack((nx, ny, nz, np.ones_like(nx)), axis=-1) @ inv
    return c[..., :3] / c[..., 3:4]


def segment_hits(obj, p, q):
    """Does segment p -> q pass through the (convex) object? Cyrus-Beck
    against the planes of its polygons; None if the object is not convex."""
    d = q - p
    t0, t1 = 0.0, 1.0
    for n, p0 in zip(obj.normals, obj.p0):
        num = np.dot(n, p0 - p)
        den = np.dot(n, d)
        if abs(den) < 1e-12:
            if num < 0:
                return False
            continue
        t = num / den
        if den < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return False
    return t1 - t0 > 1e-6


def volumes_containing(p, lpos, margin=0.0):
    """Shadow volumes of the current scene that contain p (casters between p
    and the light); None if the segment comes near the non-convex torus."""
    n = 0
    for obj in H.objects:
        if not obj.casts:
            continue
        if obj.name == "torus":
            lo, hi = obj.verts.min(axis=0) - 0.3, obj.verts.max(axis=0) + 0.3
            ts = np.linspace(0, 1, 400)[:, None]
            pts = p + ts * (lpos - p)
            if ((pts > lo) & (pts < hi)).all(axis=1).any():
                return None
            continue
        n += segment_hits(obj, p, lpos)
    return n


def shadow_point(obj_name, lpos):
    """An object's centre projected from the light onto the ground."""
    obj = next(o for o in H.objects if o.name == obj_name)
    c = obj.verts.mean(axis=0)
    t = lpos[1] / (lpos[1] - c[1])
    return lpos + t * (c - lpos)


def lum(img, xy):
    """Luminance of window pixel (x, y) (image rows are top first)."""
    x, y = xy
    return float(img[HGT - 1 - y, x].astype(int).sum())


# ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def fig4a():
    opts = scene("4a")
    img, sten, z = run("--figure", "4a")
    return opts, img, matrices(opts)


@pytest.fixture(scope="module")
def volumes4a():
    opts = scene("4a")
    img, sten, z = run("--figure", "4a", "--volumes-only", "0")
    return opts, sten, z, matrices(opts)


def test_figures_literal_lists_every_figure():
    names = [f["name"] for f in H.FIGURES]
    for n in ("1e", "4a", "4b", "4c", "4d", "5b", "6", "eyein-zpass", "eyein-zfail"):
        assert n in names
    for f in H.FIGURES:
        H.parse(f["args"])                     # every figure's args parse


def test_silhouette_of_a_box_is_a_closed_loop():
    """The adjacency finds each box edge once; from a light above a corner
    the silhouette is 6 edges, each vertex used twice (a closed loop)."""
    scene("4a")
    crate = next(o for o in H.objects if o.name == "crate")
    assert crate.closed and len(crate.e_a) == 12
    H.objects = [H.objects[0], crate]
    faces, ingoing = H.shadow_faces(np.array([-10.0, 10.0, 10.0]))
    assert faces.shape == (6, 4, 3)
    ends = np.concatenate([faces[:, 0], faces[:, 1]])
    _, counts = np.unique(ends.round(6), axis=0, return_counts=True)
    assert (counts == 2).all()


def test_shadow_on_ground_darker_than_lit_ground(fig4a):
    opts, img, M = fig4a
    lpos = H.light[0].position
    ps = shadow_point("pillar", lpos)
    assert volumes_containing(ps, lpos) == 1
    # a ground point 1.5 to the side of the shadow's axis is lit
    axis = ps - np.array([lpos[0], 0.0, lpos[2]])
    side = np.cross(axis, (0.0, 1.0, 0.0))
    pl = ps + 1.5 * side / np.linalg.norm(side)
    assert volumes_containing(pl, lpos) == 0
    s, l = lum(img, to_pixel(M, ps)), lum(img, to_pixel(M, pl))
    assert s < 0.6 * l, (s, l)


def test_stencil_counts_volumes_after_volume_pass(volumes4a):
    """After light 0's volume pass: MYZERO + number of volumes containing
    the visible point, at a shadowed and a lit pixel and at 99% of all
    ground pixels (silhouette edges excepted)."""
    opts, sten, z, M = volumes4a
    lpos = H.light[0].position
    ps = shadow_point("pillar", lpos)
    x, y = to_pixel(M, ps)
    assert sten[y, x] == H.MYZERO + 1
    pl = np.array([-6.0, 0.0, 6.0])                  # under the light: lit
    x, y = to_pixel(M, pl)
    assert volumes_containing(pl, lpos) == 0 and sten[y, x] == H.MYZERO

    world = unproject(M, z)
    agree = total = inside = 0
    for yy in range(2, HGT - 2, 3):
        for xx in range(2, W - 2, 3):
            if z[yy, xx] >= getgdesc(GD_ZMAX):
                continue
            p = world[yy, xx]
            if abs(p[1]) > 1e-3:                    # ground points only
                continue
            n = volumes_containing(p, lpos)
            if n is None:
                continue
            total += 1
            inside += n > 0
            agree += sten[yy, xx] == H.MYZERO + n
    assert total > 1000 and inside > 100
    assert agree >= 0.99 * total, (agree, total)


def test_lights_add_up(fig4a):
    """4b adds the green light: a ground point in the red light's shadow but
    not the green one's gains green; in no light's shadow it gains green."""
    opts4a, img4a, M = fig4a
    scene("4b")
    img4b, _, _ = run("--figure", "4b")
    red, green = H.light[0].position, H.light[1].position
    ps = shadow_point("pillar", red)
    assert volumes_containing(ps, red) == 1 and volumes_containing(ps, green) == 0
    x, y = to_pixel(M, ps)
    a, b = img4a[HGT - 1 - y, x].astype(int), img4b[HGT - 1 - y, x].astype(int)
    assert b[1] > a[1] + 30 and b[1] - a[1] > 2 * (b[0] - a[0]), (a, b)


def test_soft_shadow_has_penumbra():
    opts = scene("6")
    img, _, _ = run("--figure", "6", "--jitter", "8")
    M = matrices(opts)
    lpos = H.light[0].position
    ps = shadow_point("pillar", lpos)
    axis = ps - np.array([lpos[0], 0.0, lpos[2]])
    side = np.cross(axis, (0.0, 1.0, 0.0))
    side /= np.linalg.norm(side)
    assert volumes_containing(ps + 2.0 * side, lpos) == 0
    prof = [lum(img, to_pixel(M, ps + t * side)) for t in np.linspace(0.0, 2.0, 81)]
    umbra, lit = prof[0], prof[-1]
    assert umbra < 0.6 * lit
    between = [v for v in prof if umbra + 0.1 * (lit - umbra) < v < lit - 0.1 * (lit - umbra)]
    assert len(between) >= 3 and len(set(between)) >= 3, prof
    # the hard shadow of one light position has (almost) no such values
    img1, _, _ = run("--figure", "6", "--jitter", "1")
    prof1 = [lum(img1, to_pixel(M, ps + t * side)) for t in np.linspace(0.0, 2.0, 81)]
    between1 = [v for v in prof1 if umbra + 0.1 * (lit - umbra) < v < lit - 0.1 * (lit - umbra)]
    assert len(between1) < len(between)


def test_zfail_correct_with_eye_inside_volume():
    opts = scene("eyein")
    lpos = H.light[0].position
    assert volumes_containing(H.eye, lpos) == 1          # the eye is in the crate's shadow
    shadowed = np.array([1.5, 0.0, -0.2])
    lit = np.array([5.0, 0.0, 0.8])
    assert volumes_containing(shadowed, lpos) == 1 and volumes_containing(lit, lpos) == 0

    _, st_pass, _ = run("--figure", "eyein", "--volumes-only", "0")
    M = matrices(opts)
    ps, pl = to_pixel(M, shadowed), to_pixel(M, lit)
    _, st_fail, _ = run("--figure", "eyein", "--zfail", "--volumes-only", "0")
    # z-pass starts the count one short; z-fail counts right
    assert st_pass[ps[1], ps[0]] == H.MYZERO and st_pass[pl[1], pl[0]] == H.MYZERO - 1
    assert st_fail[ps[1], ps[0]] == H.MYZERO + 1 and st_fail[pl[1], pl[0]] == H.MYZERO

    img_pass, _, _ = run("--figure", "eyein")
    img_fail, _, _ = run("--figure", "eyein", "--zfail")
    assert lum(img_pass, ps) > 1.5 * lum(img_pass, pl)       # the artefact: inverted
    assert lum(img_fail, pl) > 1.5 * lum(img_fail, ps)       # the fix


def test_zfail_agrees_with_zpass_when_eye_is_outside(volumes4a):
    opts, st_pass, z, M = volumes4a
    scene("4a")
    _, st_fail, _ = run("--figure", "4a", "--zfail", "--volumes-only", "0")
    seen = z < getgdesc(GD_ZMAX)
    same = (st_pass == st_fail) & seen
    assert same.sum() >= 0.995 * seen.sum(), (same.sum(), seen.sum())


def test_lit_pass_zclear_is_masked(volumes4a):
    """The listing's zclear before the lit pass runs under zwritemask(0x0)
    and clears nothing: the z-buffer after the whole frame is the ambient
    pass's, and a lit crate top shows only the crate (ambient + red), not
    the ground hidden under it added as well."""
    opts, _, z_vol, M = volumes4a
    scene("4a")
    img, _, z = run("--figure", "4a")
    assert np.array_equal(z, z_vol)
    crate = next(o for o in H.objects if o.name == "crate")
    top = crate.verts.mean(axis=0) + np.array([0.0, 0.9, 0.0])
    x, y = to_pixel(M, top)
    d, g = np.array(crate.diffuse), np.array(H.objects[0].diffuse)
    lc = np.array(H.light[0].color)
    px = img[HGT - 1 - y, x].astype(float) / 255
    # ambient 0.25 * diffuse + diffuse * light colour * cos (<= 1): never the
    # ground's red added on top
    assert (px <= H.MODEL_AMBIENT * d + d * lc + 2 / 255).all(), px
    assert px[0] > H.MODEL_AMBIENT * d[0] + 0.2 * d[0] * lc[0]


def test_1e_triangle_shadow():
    """The open triangle: its three edges bound one polygon each, so all are
    silhouette edges; its shadow centre is darker than the ground beside it."""
    opts = scene("1e")
    img, sten, z = run("--figure", "1e", "--volumes-only", "0")
    M = matrices(opts)
    lpos = H.light[0].position
    tri = H.objects[1]
    assert not tri.closed and len(tri.e_a) == 3
    c = tri.verts.mean(axis=0)
    t = lpos[1] / (lpos[1] - c[1])
    ps = lpos + t * (c - lpos)
    x, y = to_pixel(M, ps)
    assert sten[y, x] == H.MYZERO + 1
    img, _, _ = run("--figure", "1e")
    far = to_pixel(M, np.array([-6.0, 0.0, 6.0]))
    assert lum(img, (x, y)) < 0.6 * lum(img, far)


def test_same_banks_with_one_and_two_threads():
    """Figure 5b (z, stencil counting, additive blending, four lights) drawn
    with one and with two threads leaves identical colour, z and stencil
    banks: each band of the walker is drawn by one thread in submission
    order, and a pixel's z and colour depend only on its triangle and row."""
    import numba
    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("numba has a single thread here")
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = run("--figure", "5b")
        numba.set_num_threads(2)
        two = run("--figure", "5b")
    finally:
        numba.set_num_threads(before)
    for a, b in zip(one, two):
        assert np.array_equal(a, b)
    assert len(np.unique(one[1])) > 1          # the stencil did count something


@pytest.mark.parametrize("extra", [[], ["--zfail"]])
def test_objects_replay_draws_the_same_banks(extra):
    """--objects records what DrawObjects and DrawShadowVolumes send in IRIS
    GL objects and replays them with callobj: colour, z and stencil banks
    are those of the immediate-mode listing, bit for bit (the material
    binds, stencil changes and polygons replay in order)."""
    immediate = run("--figure", "5b", *extra)
    objects = run("--figure", "5b", "--objects", *extra)
    for a, b in zip(immediate, objects):
        assert np.array_equal(a, b)
    assert len(machine.objects) == 2 + 4       # two material passes, one volume set per light


@pytest.mark.parametrize("extra", [[], ["--objects"]])
def test_two_pass_volumes_count_the_same(extra):
    """--two-pass: backface(TRUE) with ST_INCR then frontface(TRUE) with
    ST_DECR over every face gives each pixel the same count as choosing the
    operation per face (backface(3G) removes clockwise polygons, frontface
    counter-clockwise ones; the faces wind counter-clockwise about their
    outward normal): colour, stencil and z banks bit for bit."""
    one = run("--figure", "5b", *extra)
    two = run("--figure", "5b", "--two-pass", *extra)
    for a, b in zip(one, two):
        assert np.array_equal(a, b)


def test_infinite_volumes_shadow_the_same_points():
    """--infinite: far corners v4f(d, 0) under an infinite far plane.  The
    projection differs in z only (far = infinity), so the z bank differs;
    the shadows (the stencil after the volume passes) and the picture are
    the same except where two surfaces' quantized z meet differently: at
    most 0.05 % of the pixels."""
    fin = run("--figure", "5b")
    inf = run("--figure", "5b", "--infinite", "--two-pass")
    img_f, img_i = (np.asarray(i).astype(int) for i in (fin[0], inf[0]))
    differ = (np.abs(img_f - img_i).max(-1) > 0).mean()
    assert differ <= 0.0005
    assert (np.asarray(fin[0]) != 0).mean() > 0.5     # a full picture
    shaded = run("--figure", "5b", "--volumes-only", "0", "--infinite")[1]
    assert np.array_equal(shaded, run("--figure", "5b", "--volumes-only", "0")[1])
