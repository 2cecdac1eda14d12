"""The bitplanes pass by pass (vgx_emulator/trace.py) and planes()
(vgx_emulator/planes.py)."""
import re
from pathlib import Path

import numpy as np
import pytest

import vgx_emulator
from vgx_emulator.errors import GLError
from vgx_emulator.planes import stencil_colours
from vgx_emulator.runner import main as vgx_run
from vgx_emulator.trace import Trace, trace_program

ROOT = Path(__file__).resolve().parent.parent
HEIDMANN = ROOT / "programs" / "heidmann_shadow_volumes.py"
MYZERO = 128
PNG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def heidmann():
    """Heidmann's fig. 4b (two lights), small, traced with every bank kept."""
    return trace_program(HEIDMANN, ["--figure", "4b", "--size", "160x120"])


def _seq(tr):
    out = []
    for s in tr.steps:
        if s.event != "draw":
            out.append(s.event)
        elif "stencil-only" in s.label:
            out.append("volumes")
        elif "gated by stencil SF_EQUAL 128" in s.label:
            out.append("lit")
        else:
            out.append("draw")
    return out


def test_heidmann_passes_in_the_listing_order(heidmann):
    # the ambient pass, then per light: sclear(MYZERO), the shadow-volume
    # faces counted into the stencil (front faces ST_INCR, back ST_DECR),
    # zclear, the lit pass gated on MYZERO; the swap
    seq = _seq(heidmann)
    light = ["sclear", "volumes", "volumes", "zclear", "lit"]
    assert seq == ["czclear", "draw"] + light * 2 + ["frame"]
    steps = heidmann.steps
    assert steps[1].state.startswith("zbuffer on ZF_LEQUAL, zwritemask 0xffffff, wmpack "
                                     "0xffffffff, stencil off")
    assert "zpass ST_INCR" in steps[3].label and "zpass ST_DECR" in steps[4].label
    assert steps[2].label == "sclear(128)"
    assert steps[-1].label == "frame end (swapbuffers)"


def test_each_pass_lists_its_calls(heidmann):
    steps = heidmann.steps
    assert ("czclear", "0, 8388607", 1) in steps[0].calls
    assert steps[2].calls[-1] == ("sclear", "128", 1)
    # the ambient pass was ended by the lmbind that turns a light off
    assert steps[1].ended_by.startswith("lmbind(")
    # the lit pass lists the stencil call that gates it: SF_EQUAL (2) MYZERO
    lit = steps[6]
    assert ("stencil", "1, 128, 2, 255, 0, 0, 0", 1) in lit.calls
    assert ("blendfunction", "1, 1", 1) in lit.calls
    assert steps[-1].calls[-1][0] == "swapbuffers"


@pytest.mark.parametrize("light", [0, 1])
def test_stencil_picture_holds_the_counts_the_test_gates_on(heidmann, light):
    steps = heidmann.steps
    base = 2 + 5 * light
    zclear, lit = steps[base + 3], steps[base + 4]
    assert (zclear.event, lit.event) == ("zclear", "draw")
    # the pictures of the counting passes are keyed on the sclear value
    assert [st.key for st in steps[base:base + 5]] == [MYZERO] * 5
    s = zclear.arrays["stencil"]           # the stencil the lit pass is tested against
    assert np.array_equal(lit.arrays["stencil"], s)   # ST_KEEP: the lit pass keeps it
    # z-pass counts from an eye outside every volume: MYZERO + volumes entered
    assert s.min() == MYZERO and (s > MYZERO).sum() > 50
    # the lit pass added colour only where the stencil holds MYZERO ...
    changed = (lit.arrays["back"] != zclear.arrays["back"])
    assert changed.sum() > 100
    assert not (changed & (s != MYZERO)).any()
    # ... and the stencil picture shows exactly those values: grey = MYZERO,
    # one colour per count, legend with each value's pixel count
    pic = lit.picture("stencil")
    img = pic.image[::-1]                  # picture rows are top first
    for v in np.unique(s):
        col = stencil_colours([v], MYZERO)[0]
        assert np.array_equal((img == col).all(-1), s == v)
        rel = "= key" if v == MYZERO else f"key{int(v) - MYZERO:+d}"
        assert any(t == f"{v} ({rel}): {(s == v).sum()} px" for _, t in pic.legend)


def test_unchanged_banks_share_their_snapshot(heidmann):
    st = heidmann.steps
    # the shadow-volume passes write no colour and no z
    assert st[3].arrays["back"] is st[2].arrays["back"]
    assert st[3].arrays["z"] is st[2].arrays["z"]
    assert st[3].arrays["stencil"] is not st[2].arrays["stencil"]


def test_trace_write_and_cli(tmp_path, heidmann):
    index = heidmann.write(tmp_path / "a")
    text = index.read_text()
    assert text.count("class='step'") == len(heidmann.steps)
    for s in heidmann.steps:
        assert set(s.files) == {"front", "back", "z", "stencil"}
        for f in s.files.values():
            assert f in text and (tmp_path / "a" / f).read_bytes()[:8] == PNG
    out = tmp_path / "b"
    assert vgx_run([str(HEIDMANN), "--trace", str(out), "--out", str(tmp_path / "h.png"),
                    "--", "--figure", "4a", "--size", "96x72"]) == 0
    text = (out / "index.html").read_text()
    files = set(re.findall(r"src='(step\d+_\w+\.png)'", text))
    assert files and all((out / f).is_file() for f in files)
    assert "sclear(128)" in text and "gated by stencil SF_EQUAL 128" in text
    from irisgl._current import machine
    assert machine.trace_hook is None and machine.call_hook is None


def test_a_run_of_one_call_shows_its_first_and_last_arguments(vgx, open_window):
    """A run of one call is one line with its count; the arguments are shown
    once when every call had them, else the first and the last (a run
    listed with only its first arguments read as identical calls)."""
    from irisgl import bgnpolygon, endpolygon, gflush, pclos, pdr, pmv, v2i
    from vgx_emulator.trace import _index
    tr = Trace(frame=1).install(vgx)
    open_window(16, 8)
    pmv(3, 3, -3)
    pdr(3, 3, -3)
    pdr(3, -3, -3)
    pdr(3, -3, 3)
    pclos()
    bgnpolygon()
    for _ in range(3):
        v2i((1, 1))
    endpolygon()
    gflush()
    tr.uninstall()
    calls = tr.steps[0].calls
    assert ("pdr", "3, 3, -3) … (3, -3, 3", 3) in calls
    assert ("v2i", "(1, 1)", 3) in calls
    text = _index(tr, "t")
    assert "pdr(3, 3, -3) … (3, -3, 3)</code> &times;3" in text


def test_a_run_that_ends_the_pass_keeps_its_other_calls(vgx, open_window):
    """The call that ends a pass is taken off its run: callobj(a),
    callobj(b), callobj(c) where c changes the z function lists callobj
    (a) … (b) ×2 in the pass and opens the next with callobj(c)."""
    from irisgl import ZF_ALWAYS, callobj, closeobj, gflush, makeobj, rectfi, zfunction
    open_window(16, 8)
    for obj, x in ((1, 0), (2, 4)):
        makeobj(obj)
        rectfi(x, 0, x + 1, 1)
        closeobj()
    makeobj(3)
    zfunction(ZF_ALWAYS)
    rectfi(8, 0, 9, 1)
    closeobj()
    tr = Trace(frame=1).install(vgx)
    callobj(1)
    callobj(2)
    callobj(3)
    gflush()
    tr.uninstall()
    first, second = tr.steps[0], tr.steps[1]
    assert first.calls == [("callobj", "1) … (2", 2)]
    assert first.ended_by == "callobj(3)"
    assert second.calls[0] == ("callobj", "3", 1)


def test_trace_of_a_later_frame(vgx, open_window):
    from irisgl import clear, cpack, gflush, rectfi
    tr = Trace(frame=2).install(vgx)
    open_window(16, 8)
    cpack(0x0000FF)
    clear()
    gflush()                               # frame 1: not traced
    cpack(0x00FF00)
    rectfi(0, 0, 3, 3)
    gflush()                               # frame 2
    cpack(0x0000FF)
    clear()                                # frame 3: not traced
    tr.uninstall()
    assert [s.event for s in tr.steps] == ["draw", "frame"]
    assert [c[0] for c in tr.steps[0].calls] == ["cpack", "rectfi"]
    assert tr.steps[0].ended_by == "gflush()"         # it flushed the batch ...
    assert tr.steps[1].calls == [("gflush", "", 1)]   # ... and ends the frame
    front = tr.steps[0].arrays["front"]
    green = np.zeros(front.shape, bool)
    green[:3, :3] = True                   # rectfi(0, 0, 3, 3): pixel centres 0..2 inside
    assert (front[green] == 0x0000FF00).all() and (front[~green] == 0x000000FF).all()


def test_planes_gives_every_bank_that_exists(vgx, open_window):
    from irisgl import (RGBmode, acsize, czclear, doublebuffer, gconfig, sclear, stensize,
                        zbuffer)
    with pytest.raises(GLError, match="planes"):
        vgx_emulator.planes()
    open_window(12, 10)
    assert set(vgx_emulator.planes()) == {"front"}
    RGBmode()
    doublebuffer()
    stensize(4)
    acsize(16)
    gconfig()
    zbuffer(1)
    czclear(0x00102030, 1000)
    sclear(9)
    p = vgx_emulator.planes()
    assert set(p) == {"front", "back", "z", "stencil", "accum"}
    assert p["back"].shape == (10, 12) and (p["back"] == 0x00102030).all()
    assert (p["z"] == 1000).all() and (p["stencil"] == 9).all()
    assert p["accum"].shape == (10, 12, 4) and p["accum"].dtype == np.int16
    p["stencil"][:] = 0                                 # a copy
    assert (vgx.current.fb.stencil == 9).all()
    for name in p:
        assert p.picture(name)._repr_png_()[:8] == PNG
    assert p._repr_png_()[:8] == PNG
    assert vgx.current._repr_png_()[:8] == PNG


def test_depth_and_accumulation_pictures(vgx, open_window):
    from irisgl import AC_CLEAR, acbuf, acsize, gconfig, zclear
    open_window(8, 4)
    acsize(16)
    gconfig()
    zclear()
    z = vgx.current.fb.z
    z[:, :2] = -1000                       # nearest
    z[:, 2:4] = 5000
    p = vgx_emulator.planes()
    img = p.picture("z").image[::-1].astype(int)
    assert img[0, 0].sum() > img[0, 2].sum() > 0           # near bright, far darker
    assert (img[:, 4:] == 0).all()                          # GD_ZMAX: cleared, black
    acbuf(AC_CLEAR, 0.0)
    a = vgx.current.fb.accum
    a[:, :4, 0] = 100
    a[:, 4:, 0] = -50
    pic = vgx_emulator.planes().picture("accum")
    im = pic.image[::-1]
    assert (im[:, :4, 0] == 255).all() and (im[:, :4, 1:] == 0).all()
    assert (im[:, 4:, 0] == im[:, 4:, 2]).all() and (im[:, 4:, 0] > 0).all() \
        and (im[:, 4:, 1] == 0).all()                       # negative: magenta
    assert any("from -50 to 100" in t for _, t in pic.legend)
