"""The shadow study at scale, without Dask: scene files, light maps in
tiles, the output folder (a record per configuration, failures recorded,
--resume), seeds and their spread, the timing records, the CLI."""
import copy
import json
import math
import socket

import numpy as np
import pytest

from programs import shadowbuf as sb
from study import __main__ as cli
from study import measure, methods, report, scenes, sweep, tasks
from study.render import Stage
from study.store import read_json

#: a tiny scene file: a turned box and a coarse ball on the ground
TINY = {
    "format": "vgx-study-scene 1", "name": "T", "title": "a box and a ball on the ground",
    "materials": {"ground": {"ambient": [0.5, 0.6, 0.5], "diffuse": [0.5, 0.6, 0.5]},
                  "thing": {"ambient": [0.8, 0.7, 0.6], "diffuse": [0.8, 0.7, 0.6]}},
    "model_ambient": 0.3, "light": {"azimuth_left": 60, "elevation": 40},
    "light_radius_degrees": 4, "ground_y": 0,
    "view": {"eye": [0, 4, 8], "ref": [0, 0.5, 0], "fovy": 450, "near": 1, "far": 30},
    "meshes": [{"kind": "ground", "y": 0, "half": 6, "material": "ground"},
               {"kind": "box", "name": "box", "half": [0.5, 0.5, 0.5], "centre": [-1, 0.5, 0],
                "rotate": [["y", 30]], "material": "thing"},
               {"kind": "sphere", "name": "ball", "centre": [1.2, 0.7, 0.3], "radius": 0.7,
                "slices": 12, "stacks": 6, "material": "thing"}]}
SIZE = (40, 30)
FAILING = sweep.Config("shadow map", dict(sweep.DEFAULT_MAP, res=0))


def tiny_file(folder, data=TINY, name="tiny.json"):
    path = folder / name
    path.write_text(json.dumps(data))
    return str(path)


def tiny_configs():
    """Every family, two seeds of the soft ones, and one that fails."""
    cfgs = sweep.configs(True, ["planar", "volumes", "shadow map"])
    return cfgs + sweep.configs(True, ["soft"], seeds=2)[:4] + [FAILING]


def records(folder, scene="T"):
    return {p.stem: json.loads(p.read_text()) for p in (folder / scene).glob("*.json")
            if not p.stem.endswith(".time") and p.stem != "reference"}


MEASURES = ("status", "false_lit", "false_shadow", "misclassified", "rmse", "max_abs", "error")


def same_results(a, b, scene="T"):
    """Two output folders hold the same records (measures, errors), images
    and decisions, and the same pictures."""
    ra, rb = records(a, scene), records(b, scene)
    assert ra.keys() == rb.keys()
    for k in ra:
        assert {m: ra[k].get(m) for m in MEASURES} == {m: rb[k].get(m) for m in MEASURES}, k
        if ra[k]["status"] == "ok":
            with np.load(a / scene / f"{k}.npz") as za, np.load(b / scene / f"{k}.npz") as zb:
                assert np.array_equal(za["image"], zb["image"]), k
                assert np.array_equal(za["lit"], zb["lit"]), k
    pic = f"scene{scene}_pictures.png"
    assert (a / pic).read_bytes() == (b / pic).read_bytes()


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    """The serial sweep of the tiny scene, uninterrupted."""
    root = tmp_path_factory.mktemp("serial")
    out = root / "out"
    res = report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
                     cfgs=tiny_configs(), stream=None)
    return res, out, root


# -- scene files --------------------------------------------------------------
def test_a_scene_file_round_trips_every_triangle():
    """to_dict / from_dict (through JSON) give back scene B exactly."""
    b = scenes.get("B")
    c = scenes.from_dict(json.loads(json.dumps(scenes.to_dict(b))))
    assert [m.name for m in c.meshes] == [m.name for m in b.meshes]
    for m, n in zip(b.meshes, c.meshes):
        assert np.array_equal(m.verts, n.verts) and np.array_equal(m.tris, n.tris)
        assert (m.material, m.casts) == (n.material, n.casts)
    assert np.array_equal(b.light, c.light) and b.light_radius == c.light_radius
    assert b.view == c.view and b.materials == c.materials and b.ground_y == c.ground_y


def test_scene_file_primitives_are_the_builders(tmp_path):
    """A file's box, sphere and ground are the builders' meshes; a file
    without a name is named after itself."""
    data = {k: v for k, v in TINY.items() if k != "name"}
    spec = scenes.spec_of(tiny_file(tmp_path, data, "garden.json"))
    s = scenes.build(spec)
    assert s.name == "garden" and s.light_dir @ scenes.light_from(60, 40)[:3] == \
        pytest.approx(1.0)
    box = scenes.box("box", (0.5, 0.5, 0.5), "thing", (-1, 0.5, 0), scenes.rotation("y", 30))
    ball = scenes.sphere("ball", (1.2, 0.7, 0.3), 0.7, 12, 6, "thing")
    for want, got in zip((box, ball), s.meshes[1:]):
        assert np.array_equal(want.verts, got.verts) and np.array_equal(want.tris, got.tris)
    assert not s.meshes[0].casts and s.light_radius == pytest.approx(math.tan(math.radians(4)))
    assert scenes.spec_of("A") == {"builtin": "A"}


@pytest.mark.parametrize("change, message", [
    (lambda d: d["meshes"].append({"kind": "triangles", "name": "sheet", "material": "thing",
                                   "verts": [[0, 1, 0], [1, 1, 0], [0, 1, 1]],
                                   "tris": [[0, 1, 2]]}),
     "'sheet' casts shadows but is not closed"),
    (lambda d: d["meshes"].append({"kind": "cone", "material": "thing"}), "unknown kind 'cone'"),
    (lambda d: d["meshes"][1].update(material="gold"), "material 'gold'"),
    (lambda d: d.pop("view"), "'view' missing"),
    (lambda d: d["meshes"][1].update(half=[1, 2]), "half: 3 numbers"),
])
def test_a_bad_scene_file_says_what_is_wrong(tmp_path, change, message):
    data = copy.deepcopy(TINY)
    change(data)
    with pytest.raises(ValueError, match=message):
        scenes.spec_of(tiny_file(tmp_path, data))


def test_an_unknown_scene_is_refused(tmp_path):
    with pytest.raises(ValueError, match="not a built-in scene"):
        scenes.spec_of(str(tmp_path / "nothing.json"))
    (tmp_path / "bad.json").write_text("{")
    with pytest.raises(ValueError, match="not JSON"):
        scenes.spec_of(str(tmp_path / "bad.json"))


# -- light maps in tiles -------------------------------------------------------
@pytest.fixture
def tiny_stage():
    return Stage(scenes.from_dict(TINY), *SIZE)


def test_a_tiled_light_map_equals_the_untiled_one(tiny_stage):
    """A 256 map in tiles of 40 (with their borders) holds the same depths as
    one 256 window, and the shadow test tile by tile takes the same
    decisions as shadowbuf's on the whole map, nearest, bilinear, PCF 3 and
    5, 16 bits; tiles no eye point falls in are not drawn."""
    st, res = tiny_stage, 256
    whole = methods.light_depth(st, res)
    st.max_tile = 40
    assert np.array_equal(methods.light_depth(st, res), whole)
    st.eye_view(light=True)
    st.clear()
    from irisgl import callobj
    callobj(st.obj("all", "full"))
    ze, mvp_e = st.read_depth(), sb.current_mvp()
    box = st.light_box()[2]
    mvp_l = methods.light_mvp(st, st.light_box(), res, 40)
    h, w = ze.shape
    x, y, zp = sb.world_to_window(sb.window_to_world(ze, mvp_e, w, h), mvp_l, res, res)
    bias = methods.bias_units(box, 0.05)
    for bilinear, pcf, bits in ((False, 1, 24), (True, 1, 24), (False, 3, 24), (False, 5, 24),
                                (False, 1, 16)):
        st.max_tile = 40
        tiled, drawn, tiles, _ = methods.shadow_test(st, ze, mvp_e, res, 0.05, bilinear,
                                                     False, pcf, bits)
        st.max_tile = 1024
        one, drawn1, tiles1, _ = methods.shadow_test(st, ze, mvp_e, res, 0.05, bilinear,
                                                     False, pcf, bits)
        zl, zq = whole, np.floor(zp + 0.5)
        if bits < 24:
            zl, zq = sb.quantize(whole, bits), sb.quantize(zq, bits).astype(np.float64)
        else:
            zq = zp
        if pcf > 1:
            want = 1.0 - sb.pcf(zl, x, y, zq, bias, pcf)
        else:
            want = (zq - bias <= sb.light_depth_at(zl, x, y, bilinear)).astype(float)
        want[ze >= sb.ZMAX] = 1.0
        assert np.array_equal(tiled, one) and np.array_equal(one, want), (bilinear, pcf, bits)
        assert (tiles1, drawn1) == (1, 1) and tiles > 36 and 0 < drawn < tiles


def test_a_big_map_in_tiles_keeps_memory_to_a_tile(tiny_stage):
    """A 4096 map drawn in tiles of 128: the host's peak allocations stay
    far below the 128 MB one int64 map of that size would take."""
    tiny_stage.max_tile = 128
    out, peak = measure.host_peak(lambda: methods.shadow_map(tiny_stage, True, res=4096))
    assert peak < 8 * 2 ** 20
    assert out.info["light tiles"] > 1000 and 0 < out.info["light tiles drawn"]
    assert out.fb_bytes == methods.fb_bytes(*SIZE) + methods.fb_bytes(128, 128)


# -- the sweep's configurations -------------------------------------------------
def test_the_full_sweep_is_big_and_seeded():
    full = sweep.configs(full=True)
    keys = [c.key for c in full]
    assert len(keys) == len(set(keys)) > 250
    res = {c.params["res"] for c in full if c.family == "shadow map"}
    assert max(res) == 8192 and min(res) == 64
    soft = [c for c in full if c.family == "soft"]
    assert {c.seed for c in soft} == set(range(sweep.FULL_SEEDS))
    assert all(c.seed is None for c in full if not c.jittered)


def test_jittered_discs_differ_by_seed_and_stay_in_the_disc():
    a, b = scenes.jittered_disc(64, 0), scenes.jittered_disc(64, 1)
    assert np.array_equal(a, scenes.jittered_disc(64, 0)) and not np.allclose(a, b)
    r2 = (a * a).sum(axis=1)
    k = np.arange(64)
    assert (r2 >= k / 64 - 1e-12).all() and (r2 < (k + 1) / 64 + 1e-12).all()


# -- the output folder ------------------------------------------------------------
def test_every_configuration_has_its_record_and_the_failure_is_one(serial):
    """One record and one image file per configuration; the failing one is
    recorded with its error, the others are measured and timed."""
    res, out, _ = serial
    recs = records(out)
    assert set(recs) == {c.key for c in tiny_configs()} | {"floor"}
    bad = recs[FAILING.key]
    assert bad["status"] == "error" and "ValueError: shadow map: res 0" in bad["error"]
    assert "Traceback" in bad["traceback"] and not (out / "T" / f"{FAILING.key}.npz").exists()
    good = [k for k, r in recs.items() if r["status"] == "ok"]
    assert len(good) == len(recs) - 1
    assert all((out / "T" / f"{k}.npz").exists() for k in good)
    sc = res["scenes"]["T"]
    assert [f["label"] for f in sc["failed"]] == [FAILING.label]
    text = (out / "report.md").read_text()
    assert "### Failed configurations" in text and FAILING.label in text
    for r in sc["rows"]:
        if r["family"] != "floor":
            assert r["time_ms"] > 0 and r["memory_bytes"] > r["fb_bytes"] > 0


def test_times_carry_their_machine_threads_and_load(serial):
    res, out, _ = serial
    t = read_json(out / "T" / "planar_ground_matrix.time.json")
    assert t["where"]["host"] == socket.gethostname() and t["where"]["cpu"]
    assert t["threads"] == 1 and len(t["load_before"]) == 3 and len(t["load_after"]) == 3
    assert len(t["times_s"]) == 1 and t["slots"] == 1
    machines = res["timing"]["machines"]
    assert list(machines) == [res["timing"]["compared on"]]
    assert "## How the times were taken" in (out / "report.md").read_text()
    # one timing per label: the seeds of a jittered configuration share it
    timed = {p.name for p in (out / "T").glob("*.time.json")}
    assert "soft_N1_seed0.time.json" in timed and "soft_N1_seed1.time.json" not in timed


def test_the_seeds_spread_is_reported(serial):
    res, out, _ = serial
    row = next(r for r in res["scenes"]["T"]["rows"] if r["label"] == "soft N=4")
    sp = row["spread"]["rmse"]
    assert row["seeds"] == [0, 1] and sp["min"] < row["rmse"] < sp["max"] and sp["std"] > 0
    a, b = (np.load(out / "T" / f"soft_N4_seed{k}.npz")["image"] for k in (0, 1))
    assert not np.array_equal(a, b)
    text = (out / "report.md").read_text()
    assert "### Seeds of the jittered configurations" in text and "| soft N=4 | 2 |" in text


def _other_scene():
    """TINY renamed, in other colours and another light."""
    d = copy.deepcopy(TINY)
    d.update(name="U", light={"azimuth_left": -40, "elevation": 25}, model_ambient=0.1)
    d["materials"] = {"ground": {"ambient": [0.1, 0.2, 0.9], "diffuse": [0.2, 0.3, 1.0]},
                      "thing": {"ambient": [0.9, 0.1, 0.1], "diffuse": [1.0, 0.2, 0.1]}}
    return d


def test_a_stage_draws_the_same_after_another_stage_defined_its_lighting():
    """lmdef's materials and lights belong to the process: a second Stage
    redefines the same indices, and the first still draws its own colours."""
    a = Stage(scenes.from_dict(TINY), *SIZE)
    before = methods.shadow_volumes(a).image
    b = Stage(scenes.from_dict(_other_scene()), *SIZE)
    other = methods.shadow_volumes(b).image
    assert np.array_equal(methods.shadow_volumes(a).image, before)
    assert not np.array_equal(other, before)


def test_two_scenes_in_one_sweep_are_each_as_alone(serial, tmp_path):
    """The tiny scene's records in a sweep of two scenes are those of the
    sweep of it alone (the other scene's stage in between)."""
    _, whole, root = serial
    out = tmp_path / "two"
    cfgs = [c for c in tiny_configs() if c.family != "shadow map" or c.params["res"] == 256]
    report.run((tiny_file(root), tiny_file(tmp_path, _other_scene(), "u.json")), SIZE,
               out_dir=out, repeats=1, budget=1.0, cfgs=cfgs, stream=None, timing=False)
    mine, alone = records(out), records(whole)
    assert set(mine) == {c.key for c in cfgs} | {"floor"} and records(out, "U")
    for k in mine:
        assert {m: mine[k].get(m) for m in MEASURES} == {m: alone[k].get(m) for m in MEASURES}, k


def test_resume_finishes_only_what_was_missing(serial, tmp_path):
    """A run stopped after four records, resumed: the resumed run leaves the
    four alone, runs every other configuration once, and the folder ends
    as the uninterrupted run's."""
    _, whole, root = serial
    out = tmp_path / "out"
    seen = []

    def stop(scene, key, rec):
        seen.append(key)
        if len(seen) == 4:
            raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
                   cfgs=tiny_configs(), stream=None, on_record=stop)
    first = records(out)
    assert sorted(first) == sorted(seen) and not list((out / "T").glob("*.time.json"))
    again = []
    report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
               cfgs=tiny_configs(), stream=None, resume=True,
               on_record=lambda s, k, r: again.append(k))
    assert sorted(again) == sorted(set(records(whole)) - set(seen))
    final = records(out)
    assert all(final[k]["run"] == first[k]["run"] for k in first)
    assert len({final[k]["run"] for k in again}) == 1 != first[seen[0]]["run"]
    same_results(out, whole)


def test_resume_measures_a_saved_image_without_drawing_it_again(serial, tmp_path):
    """An image saved without its record (the run stopped before the
    reference was there) is measured on resume, not drawn again."""
    import shutil
    _, whole, root = serial
    out = tmp_path / "copy"
    shutil.copytree(whole, out)
    (out / "T" / "volumes_z-pass.json").unlink()
    ran = []
    report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
               cfgs=tiny_configs(), stream=None, resume=True, timing=False,
               on_record=lambda s, k, r: ran.append(k))
    assert ran == ["volumes_z-pass", FAILING.key]
    old = records(whole)["volumes_z-pass"]
    new = records(out)["volumes_z-pass"]
    assert new["run"] != old["run"]
    assert {k: new[k] for k in ("render_s", "where", "fb_bytes", "rmse", "misclassified")} == \
        {k: old[k] for k in ("render_s", "where", "fb_bytes", "rmse", "misclassified")}


def test_a_failed_reference_is_recorded_and_resume_measures_the_images(serial, tmp_path,
                                                                       monkeypatch):
    """The scene's reference raises: its error is recorded, every image is
    still drawn and saved, each configuration recorded as not measured;
    --resume casts the reference and measures them without drawing again."""
    _, whole, root = serial

    def broken(*args):
        raise RuntimeError("no reference today")
    monkeypatch.setattr(tasks, "reference_task", broken)
    out = tmp_path / "out"
    res = report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
                     cfgs=tiny_configs(), stream=None, timing=False)
    ref = read_json(out / "T" / "reference_task.json")
    assert ref["status"] == "error" and "RuntimeError: no reference today" in ref["error"]
    recs = records(out)
    drawn = [k for k, r in recs.items() if r.get("unmeasured")]
    assert sorted(drawn) == sorted(c.key for c in tiny_configs() if c is not FAILING)
    assert all((out / "T" / f"{k}.npz").exists() for k in drawn)
    assert res["scenes"]["T"]["rows"] == [] and res["scenes"]["T"]["pictures"] is None
    assert res["scenes"]["T"]["failed"][0]["label"] == "reference"
    monkeypatch.undo()
    report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
               cfgs=tiny_configs(), stream=None, resume=True, timing=False)
    again = records(out)
    assert all(again[k]["render_s"] == recs[k]["render_s"] for k in drawn)
    same_results(out, whole)


def test_resume_into_another_sweep_is_refused(serial, tmp_path):
    _, out, root = serial
    with pytest.raises(ValueError, match="other settings .*size"):
        report.run((tiny_file(root),), (32, 24), out_dir=out, repeats=1, budget=1.0,
                   cfgs=tiny_configs()[:1], stream=None, resume=True)


def test_resume_of_a_finished_sweep_runs_only_the_missing_timing(serial, tmp_path):
    import shutil
    _, whole, root = serial
    out = tmp_path / "copy"
    shutil.copytree(whole, out)
    (out / "T" / "volumes_z-fail.time.json").unlink()       # as if stopped while timing
    times = {p.name: read_json(p)["run"] for p in (whole / "T").glob("*.time.json")}
    ran = []
    res = report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
                     cfgs=tiny_configs(), stream=None, resume=True,
                     on_record=lambda s, k, r: ran.append(k))
    assert ran == [FAILING.key]                      # a failure is tried again
    now = {p.name: read_json(p)["run"] for p in (out / "T").glob("*.time.json")}
    assert now.keys() == times.keys()
    assert [k for k in now if now[k] != times[k]] == ["volumes_z-fail.time.json"]
    # the floor, 7 hard configurations, 2 soft ones (of two seeds each); the failure apart
    assert len(res["scenes"]["T"]["rows"]) == 10
    same_results(out, whole)


# -- the command line ------------------------------------------------------------------
def test_the_cli_writes_its_folder_and_leaves_docs_alone(tmp_path):
    a = cli.parse([])
    assert a.out == report.ROOT / "out" / "study" and not a.docs and a.workers is None
    assert cli.parse(["--quick"]).out.name == "study-quick"
    page = report.ROOT / "docs" / "shadow-study.md"
    before = page.stat().st_mtime_ns
    out = tmp_path / "cli"
    cli.main(["--scenes", tiny_file(tmp_path), "--size", "32x24", "--methods", "planar",
              "--quick", "--no-timing", "--out", str(out)])
    assert (out / "report.md").exists() and (out / "results.json").exists()
    assert page.stat().st_mtime_ns == before
    rows = json.loads((out / "results.json").read_text())["scenes"]["T"]["rows"]
    assert [r["label"] for r in rows] == ["reference decision (floor)", "planar (ground matrix)"]
    assert math.isnan(rows[1]["time_ms"])
    with pytest.raises(SystemExit):
        cli.parse(["--workers", "2", "--scheduler", "tcp://x:1"])


def test_no_stage_is_left_open_after_a_serial_run(serial):
    assert not tasks._STAGES
