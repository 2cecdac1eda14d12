"""The fuzzer (vgx_emulator/fuzz.py, docs/reliability.md): a quick run in CI,
and its checks shown to catch what they look for."""
import json
import subprocess
import sys

import numpy as np
import pytest

from vgx_emulator import fuzz


def test_quick_fuzz_finds_nothing(tmp_path):
    """3000 random primitives over 3 raster-state recipes (rechecked on 1
    and 2 threads and run to run), then every public call given wrong
    arguments: no crash, no write outside viewport ∩ scrmask, no value out
    of range, no numpy warning, every misuse a GLError naming the call with
    the state unchanged (or accepted and still drawing)."""
    from irisgl._current import API
    out = tmp_path / "summary.json"
    r = subprocess.run([sys.executable, "-m", "vgx_emulator.fuzz", "--seed", "7",
                        "--primitives", "3000", "--batch", "3000", "--states", "3",
                        "--recheck-every", "1", "--misuse", "quick", "--json", str(out)],
                       capture_output=True, text=True, timeout=1800)
    s = json.loads(out.read_text())
    assert s["findings"] == [], json.dumps(s["findings"][:5], indent=1)
    assert r.returncode == 0
    assert s["primitives"] == 3000 and s["rechecked"] == 1
    assert s["stats"]["vgxwarnings"] > 0           # non-finite input was drawn and dropped
    m = s["misuse"]
    assert m["calls"] == len(API) and m["trials"] > 20 * len(API) // 2
    assert m["outcomes"]["refused"] > m["trials"] // 2


@pytest.fixture
def drawer(open_window):
    import numba
    threads = numba.get_num_threads()
    d = fuzz.Drawer(seed=1, index=0, count=0, nstates=1, threads=1)
    open_window(8, 6)
    yield d
    numba.set_num_threads(threads)


def _banks(d):
    return d._banks()


def test_a_write_outside_the_box_is_a_finding(drawer):
    recipe = fuzz.recipes(1)[0]
    before = _banks(drawer)
    after = {k: (None if a is None else a.copy()) for k, a in before.items()}
    after["front"][1, 1] = 7                    # inside (1..3, 0..2): fine
    drawer._check(before, after, (1, 3, 0, 2), recipe, 0)
    after["front"][5, 7] = 7                    # outside
    with pytest.raises(fuzz.Finding, match=r"front bank written outside .* at \(7, 5\)"):
        drawer._check(before, after, (1, 3, 0, 2), recipe, 0)
    with pytest.raises(fuzz.Finding, match="front bank written outside"):
        drawer._check(before, after, None, recipe, 0)      # empty box: nothing may change


def test_values_out_of_range_are_findings(drawer):
    recipe = dict(fuzz.recipes(1)[0], planes=3)
    before = _banks(drawer)
    after = dict(before, z=np.full((6, 8), 1 << 23, np.int32))
    with pytest.raises(fuzz.Finding, match="z value outside the 24-bit range"):
        drawer._check(dict(before, z=after["z"]), after, (0, 7, 0, 5), recipe, 0)
    st = np.zeros((6, 8), np.uint8)
    st[2, 2] = 8
    with pytest.raises(fuzz.Finding, match="stencil value 8 outside 3 planes"):
        drawer._check(dict(before, stencil=st), dict(before, stencil=st), (0, 7, 0, 5),
                      recipe, 0)


def test_the_fingerprint_sees_every_state_change(open_window):
    from irisgl import GLError, translate, zfunction
    from irisgl._current import machine
    open_window(8, 8)
    a = fuzz.fingerprint(machine)
    assert fuzz.fingerprint(machine) == a
    with pytest.raises(GLError):
        zfunction(99)
    assert fuzz.fingerprint(machine) == a
    translate(1, 0, 0)
    assert fuzz.fingerprint(machine) != a


def test_a_crashing_batch_is_reported_with_its_seed_and_batch(monkeypatch):
    """A worker that dies (here: exits 3) is a finding naming the batch and
    the command that reproduces it; the other batches go on."""
    real = fuzz._worker_cmd

    def cmd(kind, seed, index, count, states, threads, quick=False):
        if index == 1:
            return [sys.executable, "-c", "import sys; sys.exit(3)"]
        return [sys.executable, "-c", "print('{\"primitives\": %d, \"frames\": 1, "
                "\"hashes\": [], \"findings\": [], \"stats\": {}}')" % count]
    monkeypatch.setattr(fuzz, "_worker_cmd", cmd)
    s = fuzz.run(seed=5, primitives=30, batch=10, states=1, jobs=1, recheck_every=0,
                 timeout=60, misuse=None)
    monkeypatch.setattr(fuzz, "_worker_cmd", real)
    assert s["primitives"] == 20
    (f,) = s["findings"]
    assert f["batch"] == 1 and "crashed (exit 3)" in f["finding"]
    assert "--seed 5 --index 1 --count 10" in f["repro"]


def test_banks_differing_between_thread_counts_are_a_finding(monkeypatch):
    def worker(cmd, timeout, threads, general=None):
        return dict(primitives=10, frames=2, stats={}, findings=[],
                    hashes=["a", "b" if threads == 1 else "c"])
    monkeypatch.setattr(fuzz, "_run_worker", worker)
    s = fuzz.run(seed=1, primitives=10, batch=10, states=1, jobs=1, recheck_every=1,
                 timeout=60, misuse=None)
    assert [f["finding"] for f in s["findings"]] == [
        "banks differ between a run on 2 threads and a run on 1 thread(s) at frame 1"]


def test_banks_differing_on_the_general_variants_are_a_finding(monkeypatch):
    """The recheck's third run draws on the general kernel variants
    (VGX_GENERAL=always); other banks there are a finding."""
    calls = []

    def worker(cmd, timeout, threads, general=None):
        calls.append((threads, general))
        return dict(primitives=10, frames=2, stats={}, findings=[],
                    hashes=["a", "x" if general == "always" else "b"])
    monkeypatch.setattr(fuzz, "_run_worker", worker)
    s = fuzz.run(seed=1, primitives=10, batch=10, states=1, jobs=1, recheck_every=1,
                 timeout=60, misuse=None)
    assert calls == [(2, None), (1, None), (2, None), (2, "always")]
    assert [f["finding"] for f in s["findings"]] == [
        "banks differ between a run on 2 threads and a run on the general kernel variants "
        "(VGX_GENERAL=always) at frame 1"]
