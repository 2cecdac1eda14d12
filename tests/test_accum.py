"""acbuf(3G) and acsize(3G) (docs/semantics.md §10).

The accumulation buffer has 16 signed bits per component on the VGX.  Its
contents are observed through AC_RETURN and, where the signed values matter
(wrap, clamping of AC_CLEAR), through the bank itself ((h, w, 4) int16, RGBA,
row 0 at the bottom).  Rounding follows framebuffer/accum.py's documented
rule: round to nearest (floor(v + 0.5)).
"""
import math
import threading
import time

from functools import partial

import numpy as np
import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import new_window, colour


open_win = partial(new_window, accum=16, pixels=True)   # pixel (i, j)'s centre at (i, j)



def acc_bank():
    from irisgl._current import machine
    machine.flush()
    return machine.current.fb.accum.astype(np.int64).copy()


def comps(word):
    return [(int(word) >> (8 * k)) & 0xFF for k in range(4)]


def pack(c):
    return c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24)


def rnd(v):
    return math.floor(v + 0.5)


def wrap16(v):
    v &= 0xFFFF
    return v - 0x10000 if v >= 0x8000 else v


def ret_word(acc4, value):
    """AC_RETURN of one pixel: value clamped 0..1, result clamped 0..255."""
    value = min(max(value, 0.0), 1.0)
    return pack([min(max(rnd(a * value), 0), 255) for a in acc4])


# -- configuration -----------------------------------------------------------------
def test_acbuf_without_acsize_raises():
    open_win(2, 2, accum=0)
    with pytest.raises(GLError) as e:
        acbuf(AC_CLEAR, 0)
    assert str(e.value).startswith("acbuf")


def test_acsize_only_0_or_16():
    prefsize(2, 2)
    winopen("a")
    with pytest.raises(GLError):
        acsize(8)
    acsize(16)
    RGBmode()
    gconfig()
    assert getgconfig(GC_BITS_ACBUF) == -16        # signed: reported negative
    assert getgdesc(GD_BITS_ACBUF) == 16


def test_acbuf_in_cmode_raises():
    open_win(2, 2, rgb=False)
    with pytest.raises(GLError):
        acbuf(AC_CLEAR, 0)


def test_acbuf_bad_op_raises_and_changes_nothing():
    open_win(2, 2)
    acbuf(AC_CLEAR, 5)
    with pytest.raises(GLError):
        acbuf(6, 1.0)
    assert (acc_bank() == 5).all()


# -- clear / accumulate / return -------------------------------------------------------
def test_clear_then_return():
    open_win(2, 2)
    acbuf(AC_CLEAR, 77.4)
    assert (acc_bank() == 77).all()
    acbuf(AC_RETURN, 1.0)
    assert (colour() == pack([77] * 4)).all()


@pytest.mark.parametrize("value,want", [(40000, 32767), (-40000, -32768), (-3.6, -4)])
def test_clear_value_rounded_and_clamped_to_range(value, want):
    open_win(1, 1)
    acbuf(AC_CLEAR, value)
    assert (acc_bank() == want).all()


def test_accumulate_adds_scaled_pixels():
    src = 0x40C08010
    open_win(2, 2)
    czclear(src, 0)
    acbuf(AC_CLEAR, 3)
    acbuf(AC_ACCUMULATE, 0.75)
    acbuf(AC_ACCUMULATE, 2.0)
    want = [3 + rnd(c * 0.75) + rnd(c * 2.0) for c in comps(src)]
    assert (acc_bank() == np.array(want)).all()


def test_clear_accumulate_discards_old_contents():
    src = 0x10203040
    open_win(2, 2)
    czclear(src, 0)
    acbuf(AC_CLEAR, 1000)
    acbuf(AC_CLEAR_ACCUMULATE, 1.5)
    assert (acc_bank() == np.array([rnd(c * 1.5) for c in comps(src)])).all()


def test_accumulate_reads_the_readsource_bank():
    front, back = 0x01020304, 0x0A0B0C0D
    open_win(2, 2, double=True)
    frontbuffer(TRUE)
    backbuffer(FALSE)
    czclear(front, 0)
    frontbuffer(FALSE)
    backbuffer(TRUE)
    czclear(back, 0)
    readsource(SRC_FRONT)
    acbuf(AC_CLEAR_ACCUMULATE, 1.0)
    assert (acc_bank() == np.array(comps(front))).all()
    readsource(SRC_BACK)
    acbuf(AC_CLEAR_ACCUMULATE, 1.0)
    assert (acc_bank() == np.array(comps(back))).all()
    readsource(SRC_AUTO)                       # back in double-buffer mode
    acbuf(AC_ACCUMULATE, 2.0)
    assert (acc_bank() == 3 * np.array(comps(back))).all()


@pytest.mark.parametrize("value,factor", [(1000.0, 256), (300, 256), (-1000, -256),
                                          (-2.5, -2.5)])
def test_accumulate_value_clamped_to_256(value, factor):
    c = 100
    open_win(1, 1)
    czclear(pack([c] * 4), 0)
    acbuf(AC_CLEAR_ACCUMULATE, value)
    assert (acc_bank() == rnd(c * factor)).all()


def test_accumulate_overflow_wraps_signed_16_bit():
    """docs/semantics.md §10: 200 * 256 = 51200 does not fit; it wraps to -14336."""
    open_win(1, 1)
    czclear(pack([200, 100, 0, 255]), 0)
    acbuf(AC_CLEAR_ACCUMULATE, 256)
    want = [wrap16(200 * 256), 100 * 256, 0, wrap16(255 * 256)]
    assert want[0] == -14336
    assert list(acc_bank()[0, 0]) == want


def test_add_and_mult():
    open_win(1, 1)
    acbuf(AC_CLEAR, 100)
    acbuf(AC_ADD, 27.2)
    assert (acc_bank() == 127).all()
    acbuf(AC_ADD, -200)
    assert (acc_bank() == -73).all()
    acbuf(AC_MULT, -1.5)
    assert (acc_bank() == rnd(-73 * -1.5)).all()
    acbuf(AC_MULT, 0.1)
    assert (acc_bank() == rnd(rnd(-73 * -1.5) * 0.1)).all()


def test_add_and_mult_wrap():
    open_win(1, 1)
    acbuf(AC_CLEAR, 32767)
    acbuf(AC_ADD, 1)
    assert (acc_bank() == -32768).all()
    acbuf(AC_CLEAR, 20000)
    acbuf(AC_MULT, 2.0)
    assert (acc_bank() == wrap16(40000)).all()


@pytest.mark.parametrize("acc,value", [(300, 1.0), (-50, 1.0), (200, 0.5),
                                       (100, 2.0), (100, -1.0), (255, 0.3)])
def test_return_clamps_value_and_result(acc, value):
    open_win(1, 1)
    czclear(0x55555555, 0)
    acbuf(AC_CLEAR, acc)
    acbuf(AC_RETURN, value)
    assert colour()[0, 0] == ret_word([acc] * 4, value)


def test_return_honours_colour_writemask():
    open_win(2, 2)
    czclear(0x11223344, 0)
    acbuf(AC_CLEAR, 200)
    wmpack(0xFF00FF00)
    acbuf(AC_RETURN, 1.0)
    assert (colour() == ((0x11223344 & 0x00FF00FF) | (0xC8C8C8C8 & 0xFF00FF00))).all()


def test_return_ignores_z_stencil_blend_and_logicop():
    open_win(2, 2, planes=8)
    czclear(0x11223344, getgdesc(GD_ZMIN))       # every z test would fail
    zbuffer(TRUE)
    sclear(0)
    stencil(TRUE, 1, SF_NEVER, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    blendfunction(BF_ZERO, BF_ONE)               # would keep the destination
    acbuf(AC_CLEAR, 90)
    acbuf(AC_RETURN, 1.0)
    assert (colour() == pack([90] * 4)).all()
    blendfunction(BF_ONE, BF_ZERO)
    logicop(LO_DST)
    acbuf(AC_CLEAR, 60)
    acbuf(AC_RETURN, 1.0)
    assert (colour() == pack([60] * 4)).all()
    # and it wrote neither z nor stencil
    readsource(SRC_ZBUFFER)
    assert (lrectread(0, 0, 1, 1) == getgdesc(GD_ZMIN)).all()
    from irisgl._current import machine
    assert (machine.current.fb.stencil == 0).all()


def test_return_writes_every_enabled_buffer():
    open_win(2, 2, double=True)
    frontbuffer(TRUE)
    backbuffer(TRUE)
    acbuf(AC_CLEAR, 33)
    acbuf(AC_RETURN, 1.0)
    for src in (SRC_FRONT, SRC_BACK):
        readsource(src)
        assert (colour() == pack([33] * 4)).all()


def test_every_operation_bounded_by_viewport_and_scrmask():
    W = H = 8
    open_win(W, H)
    czclear(pack([10] * 4), 0)
    acbuf(AC_CLEAR, 1)
    viewport(1, 6, 2, 7)
    scrmask(3, 7, 0, 4)
    inside = np.zeros((H, W), bool)
    inside[2:5, 3:7] = True                   # rows 2..4, columns 3..6
    acbuf(AC_CLEAR, 5)
    a = acc_bank()[:, :, 0]
    assert (a[inside] == 5).all() and (a[~inside] == 1).all()
    acbuf(AC_ACCUMULATE, 2.0)
    acbuf(AC_ADD, 1)
    acbuf(AC_MULT, 2.0)
    a = acc_bank()[:, :, 0]
    assert (a[inside] == (5 + 20 + 1) * 2).all() and (a[~inside] == 1).all()
    viewport(0, W - 1, 0, H - 1)
    scrmask(0, W - 1, 0, H - 1)
    acbuf(AC_CLEAR, 200)
    viewport(1, 6, 2, 7)
    scrmask(3, 7, 0, 4)
    acbuf(AC_RETURN, 1.0)
    c = colour()
    assert (c[inside] == pack([200] * 4)).all()
    assert (c[~inside] == pack([10] * 4)).all()


def test_heidmann_32_passes_average_exactly():
    """Soft shadows (Heidmann fig. 6): 32 x AC_ACCUMULATE 1.0 of different
    images, then AC_RETURN 1/32, gives the rounded mean of each component."""
    W, H = 6, 5
    open_win(W, H)
    acbuf(AC_CLEAR, 0)
    total = np.zeros((H, W, 4), np.int64)
    rng = np.random.default_rng(7)
    for k in range(32):
        img = rng.integers(0, 256, (H, W, 4))
        if k < 4:
            img[0, 0] = 255                      # some saturated pixels too
        words = (img[..., 0] | (img[..., 1] << 8) | (img[..., 2] << 16)
                 | (img[..., 3] << 24)).astype(np.uint32)
        lrectwrite(0, 0, W - 1, H - 1, words)
        acbuf(AC_ACCUMULATE, 1.0)
        total += img
    assert (acc_bank() == total).all()
    acbuf(AC_RETURN, 1.0 / 32)
    got = colour()
    for y in range(H):
        for x in range(W):
            want = pack([min(max(rnd(t / 32), 0), 255) for t in total[y, x]])
            assert got[y, x] == want, (x, y)


# -- the rows in shares (framebuffer/accum.py, pipeline.in_shares) --------------------
def _accum_case(seed=3, h=96, w=40):
    rng = np.random.default_rng(seed)
    src = rng.integers(0, 2**32, (h, w), dtype=np.uint64).astype(np.uint32)
    acc = rng.integers(-32768, 32768, (h, w, 4)).astype(np.int16)
    value = 1.7
    want = acc.astype(np.int64).copy()
    x0, x1, y0, y1 = 3, w - 5, 2, h - 3
    for k in range(4):
        lut = np.floor(np.arange(256) * value + 0.5).astype(np.int64)
        add = lut[(src[y0:y1 + 1, x0:x1 + 1].astype(np.int64) >> (8 * k)) & 0xFF]
        s = want[y0:y1 + 1, x0:x1 + 1, k] + add
        want[y0:y1 + 1, x0:x1 + 1, k] = ((s + 0x8000) & 0xFFFF) - 0x8000
    ret = np.zeros((h, w), np.uint32)
    ret_want = np.zeros((h, w), np.int64)
    for k in range(4):
        c = np.clip(np.floor(want[y0:y1 + 1, x0:x1 + 1, k] * 0.5 + 0.5), 0, 255).astype(np.int64)
        ret_want[y0:y1 + 1, x0:x1 + 1] |= c << (8 * k)
    return acc, src, value, (x0, x1, y0, y1), want, ret, ret_want


def _run_accum(acc, src, value, r, ret):
    from vgx_emulator.framebuffer import accum
    accum.accumulate(acc, src, accum.AC_ACCUMULATE, value, *r)
    accum.give_back(acc, ret, 0.5, 0xFFFFFFFF, False, *r)


@pytest.mark.skipif(vgx_emulator.config.PARALLEL is False, reason="VGX_PARALLEL=0")
def test_accumulate_and_return_in_shares_on_the_programs_thread(monkeypatch):
    """With the raster thread idle, AC_ACCUMULATE and AC_RETURN cut their rows
    into shares on the walker's threads (pipeline.in_shares, each share a
    band of rows): every pixel equals the man page's sum, wrapped to 16
    bits, and the return's clamp(round(acc * value))."""
    import numba
    from vgx_emulator import pipeline
    from vgx_emulator.framebuffer import accum
    if numba.get_num_threads() < 2:
        pytest.skip("one numba thread")
    pipeline.sync()
    monkeypatch.setattr(accum, "SHARE_ROWS", 8)
    calls = []
    real = pipeline.on_threads
    monkeypatch.setattr(pipeline, "on_threads", lambda *a: (calls.append(a[1]), real(*a)))
    acc, src, value, r, want, ret, ret_want = _accum_case()
    _run_accum(acc, src, value, r, ret)
    assert len(calls) == 2 and min(calls) > 1
    assert np.array_equal(acc.astype(np.int64), want)
    assert np.array_equal(ret.astype(np.int64), ret_want)


def test_accumulate_and_return_in_shares_on_the_raster_thread(monkeypatch):
    """Queued on the raster thread, their rows are shared with the thread
    waiting in sync (pipeline.shared): the same pixels, and both threads
    took shares."""
    import numba
    from vgx_emulator import config, pipeline
    from vgx_emulator.framebuffer import accum
    if numba.get_num_threads() < 2 or not config.PARALLEL:
        pytest.skip("one numba thread or VGX_PARALLEL=0")
    monkeypatch.setattr(config, "PIPELINE", True)
    monkeypatch.setattr(accum, "SHARE_ROWS", 4)
    who = set()
    rows = accum._accumulate_rows

    def slow_rows(*a):
        who.add(threading.get_ident())
        time.sleep(0.002)
        rows(*a)
    monkeypatch.setattr(accum, "_accumulate_rows", slow_rows)
    acc, src, value, r, want, ret, ret_want = _accum_case(seed=4)
    started = threading.Event()

    def task():
        started.set()
        deadline = time.perf_counter() + 5
        while not pipeline.helper_waiting() and time.perf_counter() < deadline:
            time.sleep(0.001)
        _run_accum(acc, src, value, r, ret)

    pipeline.submit(task)
    assert started.wait(5)                 # the raster thread runs it (not this one)
    pipeline.sync()
    assert threading.get_ident() in who and len(who) == 2
    assert np.array_equal(acc.astype(np.int64), want)
    assert np.array_equal(ret.astype(np.int64), ret_want)
