"""study/ (the shadow study): the exact reference against closed forms, the
measures on synthetic masks, and a quick sweep through the emulator."""
import io
import json
import math

import numpy as np
import pytest

from study import measure, methods, reference, report, scenes, volumes
from study.render import Stage


def _scene(meshes, light, radius=0.0, view=None):
    view = view or scenes.View((0.0, 8.0, 6.0), (0.0, 0.0, 0.0), 450, 1.0, 30.0)
    return scenes.Scene("T", "test", meshes, {"m": ((0.2, 0.2, 0.2), (0.8, 0.8, 0.8))}, 0.3,
                        np.asarray(light, float), radius, view, 0.0)


def _inside(p, a, b, c):
    """Signed edge distances of points p (n, 2) to the triangle (a, b, c):
    (inside, smallest |distance|)."""
    d = []
    for u, v in ((a, b), (b, c), (c, a)):
        e = v - u
        d.append(((p[:, 0] - u[0]) * e[1] - (p[:, 1] - u[1]) * e[0]) / np.hypot(*e))
    d = np.stack(d)
    inside = (d >= 0).all(axis=0) | (d <= 0).all(axis=0)
    return inside, np.abs(d).min(axis=0)


def test_point_light_shadow_is_the_projected_triangle():
    """A triangle above the ground, a point light: the reference's shadow on
    the ground is exactly the triangle projected from the light onto y = 0
    (every ground pixel, except any within 1e-9 of the projected edges)."""
    v = np.array([(-1.0, 1.0, -0.5), (0.1, 0.8, 1.1), (1.2, 1.3, -0.2)])
    tri = scenes.Mesh("triangle", v, np.array([[0, 1, 2]]), "m")
    light = np.array([0.4, 4.0, 0.3, 1.0])
    s = _scene([scenes.ground("ground", 0.0, 6.0, "m"), tri], light)
    ref = reference.compute(s, 96, 72, soft=False)
    ground = ref.visible & (ref.tri < 2)
    lp = light[:3]
    proj = lp + (v - lp) * (lp[1] / (lp[1] - v[:, 1]))[:, None]
    inside, margin = _inside(ref.point[ground][:, [0, 2]], *proj[:, [0, 2]])
    sure = margin > 1e-9
    assert inside.sum() > 100 and (~inside).sum() > 100 and sure.mean() > 0.999
    assert np.array_equal(ref.lit[ground][sure], ~inside[sure])
    # the triangle itself faces the light (normal up) and is lit
    assert ref.lit[ref.tri == 2].all() and (ref.tri == 2).sum() > 50


def test_point_light_facing_away_is_not_lit():
    """The same triangle wound the other way faces down: its pixels get no
    light (N.L <= 0) though nothing blocks them."""
    v = np.array([(-1.0, 1.0, -0.5), (1.2, 1.3, -0.2), (0.1, 0.8, 1.1)])
    tri = scenes.Mesh("triangle", v, np.array([[0, 1, 2]]), "m")
    s = _scene([scenes.ground("ground", 0.0, 6.0, "m"), tri], (0.4, 4.0, 0.3, 1.0))
    ref = reference.compute(s, 64, 48, soft=False)
    mine = ref.tri == 2
    assert mine.sum() > 20 and not ref.facing[mine].any() and not ref.lit[mine].any()


def _segment(delta):
    """Fraction of the unit disc where x >= delta."""
    d = np.clip(delta, -1.0, 1.0)
    return (np.arccos(d) - d * np.sqrt(1.0 - d * d)) / math.pi


def test_disc_light_behind_a_half_plane_edge():
    """A light straight up, a disc of directions of radius r; an opaque
    half-plane y = h, x < 0 above the ground.  From the ground point
    (x, 0, z) the blocked directions are those of the disc with
    a < -x / (h r) (a straight chord), so the visible fraction is the
    circular segment (acos(d) - d sqrt(1 - d^2)) / pi, d = -x / (h r).
    The converged estimate is within 0.008 of it everywhere (mean 0.0015;
    a disc 5 % too wide is off by 0.017)."""
    h, r = 1.0, math.tan(math.radians(5.0))
    sheet = np.array([(-50.0, h, -50.0), (-50.0, h, 50.0), (0.0, h, 50.0), (0.0, h, -50.0)])
    occluder = scenes.Mesh("half-plane", sheet, np.array([(0, 1, 2), (0, 2, 3)]), "m")
    s = _scene([scenes.ground("ground", 0.0, 60.0, "m"), occluder], (0.0, 1.0, 0.0, 0.0), r)
    xs = np.linspace(-1.5 * h * r, 1.5 * h * r, 61)
    pts = np.stack([xs, np.zeros_like(xs), np.full_like(xs, 0.3)], axis=1)
    on = np.zeros(len(xs), np.int64)                  # ground triangle 0 (its normal: +y)
    bvh = reference.shadow_bvh(s, math.atan(r))
    frac, _, level = reference.soft_visibility(s, on[None], pts[None], bvh)
    err = np.abs(frac[0] - _segment(-xs / (h * r)))
    assert err.max() < 0.008 and err.mean() < 0.0015
    assert (level[0][np.abs(xs) < 0.9 * h * r] >= 16).all()   # penumbra: at least 16 x 16


def test_misclassified_counts_false_lit_and_false_shadow():
    truth = np.array([[1, 1, 0, 0], [1, 0, 0, 1]], float)
    decision = np.array([[1, 0, 1, 0], [1, 0, 1, 1]], float)
    visible = np.array([[1, 1, 1, 1], [1, 1, 0, 1]], bool)        # (1, 2) is background
    m = measure.misclassified(decision, truth, visible)
    assert m["false_lit"] == pytest.approx(100 / 7) and m["false_shadow"] == pytest.approx(100 / 7)
    facing = np.ones_like(truth)
    facing[0, 2] = 0                                  # N.L <= 0 there: no light either way
    m = measure.misclassified(decision, truth, visible, facing)
    assert m["false_lit"] == 0.0 and m["false_shadow"] == pytest.approx(100 / 7)
    frac = truth.copy()
    frac[0, 0] = 0.25                                 # a filtered decision: 0.75 short
    m = measure.misclassified(frac, truth, visible)
    assert m["false_shadow"] == pytest.approx(75 / 7) and m["false_lit"] == 0.0


def test_image_error_and_pareto():
    ref = np.zeros((2, 2, 3))
    img = ref.copy()
    img[0, 0, 0] = 12.0
    e = measure.image_error(img, ref)
    assert e["rmse"] == pytest.approx(math.sqrt(144 / 12)) and e["max_abs"] == 12.0
    pts = [(1, 5), (2, 4), (3, 4), (2, 6), (4, 1)]
    assert sorted(measure.pareto(pts)) == [0, 1, 4]


def test_warm_times_stop_at_the_budget():
    calls = []
    times = measure.warm_times(lambda: calls.append(1), repeats=3, budget=1e9)
    assert len(times) == 3 == len(calls)
    assert len(measure.warm_times(lambda: sum(range(10000)), repeats=5, budget=0.0)) == 1


def test_volume_geometry():
    """A box lit obliquely from above: three faces face the light, so the
    silhouette is a closed loop of six edges; the caps are the six lit
    triangles and the six others pushed away; an open mesh is refused."""
    b = scenes.box("b", (1.0, 0.5, 1.0), "m")
    L = np.array([0.3, 1.0, 0.2])
    L /= np.linalg.norm(L)
    e = volumes.adjacency(_scene([b], (*L, 0.0)))
    sides = volumes.side_faces(e, L, 10.0)
    # a convex box seen from a light not along an axis: a silhouette of 6 edges
    assert sides.shape == (6, 4, 3)
    # every silhouette vertex appears as the start of one edge and the end of one
    starts = {tuple(q[1]) for q in sides}
    ends = {tuple(q[0]) for q in sides}
    assert starts == ends and len(starts) == 6
    caps = volumes.caps(e, L, 10.0)
    assert caps.shape == (12, 3, 3)
    with pytest.raises(ValueError):
        volumes.Edges(scenes.ground("g", 0.0, 1.0, "m"))


def test_accumulation_weight_never_overflows():
    """N images of 255 accumulated at the weight fit the signed 16-bit
    accumulation buffer, and the return weight is a valid acbuf value."""
    for n in (1, 2, 64, 128, 129, 256, 1024):
        v = methods.accumulation_weight(n)
        assert n * round(255 * v) <= 32767 and 0.0 < 1.0 / (n * v) <= 1.0


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("study")
    log = io.StringIO()
    res = report.run(("A",), (80, 60), quick=True, out_dir=out, md_path=out / "study.md",
                     repeats=1, families=["planar", "volumes", "shadow map"], stream=log)
    rows = {r["label"]: r for r in res["scenes"]["A"]["rows"]}
    return res, rows, out, log.getvalue()


def test_quick_sweep_writes_the_report(quick):
    res, rows, out, log = quick
    text = (out / "study.md").read_text()
    assert "## Scene A" in text and "map R=1024 b=0.05 near" in text
    assert json.loads((out / "results.json").read_text())["size"] == [80, 60]
    assert (out / "sceneA_pictures.png").exists()
    n = len(res["scenes"]["A"]["rows"]) + 1         # the rows, and the reference step
    assert f"{n}/{n}" in log
    for r in rows.values():
        if r["family"] != "floor":
            assert r["time_ms"] > 0 and r["memory_bytes"] > r["fb_bytes"] > 0


def test_quick_shadow_map_numbers_are_plausible(quick):
    """Scene A at 80 x 60, bias 0.05: with a 1024 light map (texels of about
    0.02 world units, below the bias) the decision is wrong only along the
    shadow edges and the spheres' terminators: under 2 % of the visible
    pixels (0.7 % at 160 x 120).  A 64 map (texels of 0.3 units) covers the
    lit ground with acne: several times more, and over 5 %."""
    _, rows, _, _ = quick
    hi, lo = rows["map R=1024 b=0.05 near"], rows["map R=64 b=0.05 near"]
    assert hi["misclassified"] < 2.0
    assert lo["misclassified"] > 5.0 and lo["misclassified"] > 3 * hi["misclassified"]
    assert lo["rmse"] > hi["rmse"] > rows["reference decision (floor)"]["rmse"]


def test_quick_volumes_and_planar_are_plausible(quick):
    """Shadow volumes are exact up to pixel coverage (under 0.2 %, a few
    pixels); planar projection misses the spheres' shadows on each other
    (false lit) and darkens nothing the reference lights."""
    _, rows, _, _ = quick
    for label in ("volumes z-pass", "volumes z-fail"):
        assert rows[label]["misclassified"] < 0.2
    planar = rows["planar (ground matrix)"]
    assert planar["false_lit"] > 0.1 and planar["false_shadow"] < 0.2


def test_soft_shadows_approach_the_area_light():
    """Accumulating 8 jittered lights is much closer to the converged area
    light than one (RMSE 2.75 -> 0.5 at 160 x 120 for 1 -> 16), and the
    accumulated decision is a fraction between the extremes."""
    s = scenes.get("A")
    ref = reference.compute(s, 64, 48)
    stage = Stage(s, 64, 48)
    one = methods.soft_shadows(stage, False, n=1)
    many = methods.soft_shadows(stage, True, n=8)
    e1 = measure.image_error(one.image, ref.soft_image)["rmse"]
    e8 = measure.image_error(many.image, ref.soft_image)["rmse"]
    assert e8 < 0.6 * e1
    frac = many.lit[ref.visible]
    assert ((frac > 0) & (frac < 1)).any() and frac.min() >= 0 and frac.max() <= 1
