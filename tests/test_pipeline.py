"""The raster subsystem on its own thread (vgx_emulator/pipeline.py).

Passes, clears and acbuf are queued and run in order on one thread while
the program goes on; whatever reads a bank waits for them.  These tests
check that the pixels are those of running everything at once (every
gallery figure, every bank), that a bank read right after a call that
queued work sees that work even when the raster thread is slow, that a
failure inside queued work reaches the program, that the waiting thread
helps with the walker's shares (each share run exactly once), and that a
frame of the multipass programs waits only at its frame point.
"""
import importlib
import threading
import time
import warnings
from pathlib import Path

import numba
import numpy as np
import pytest

from irisgl import (RGBcolor, backface, bgnpolygon, clear, cpack, endpolygon, gflush,
                    lrectread, swapbuffers, v2f, zclear)
from irisgl._current import machine
from vgx_emulator import config, gallery, pipeline
from vgx_emulator.runner import run_program

machine_module = importlib.import_module("vgx_emulator.machine")   # (the package's
# ``machine`` is its function returning the VGX)

ROOT = Path(__file__).resolve().parent.parent
pytestmark = pytest.mark.skipif(numba.config.NUMBA_NUM_THREADS < 2,
                                reason="one numba thread: nothing is pipelined")


def _banks():
    """Every bank of the current window, after the queued work."""
    fb = machine.current.fb
    names = ("front", "back", "z", "stencil", "accum")
    return {n: (None if getattr(fb, n) is None else getattr(fb, n).copy()) for n in names}


def _figure(prog, fig, on, monkeypatch):
    monkeypatch.setattr(config, "PIPELINE", on)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        img = run_program(prog, frames=fig.get("frames", 1), argv=fig.get("args", []))
    return img, (_banks() if machine.current is not None else {})


FIGURES = gallery.collect(ROOT / "programs")


@pytest.mark.parametrize("prog,fig", [(p, f) for p, f, _ in FIGURES],
                         ids=[gallery._stem(p, f) for p, f, _ in FIGURES])
def test_every_figure_draws_the_same_pipelined(prog, fig, monkeypatch):
    """Each gallery figure: the picture and every bank (colour, z, stencil,
    accumulation) the same with the raster thread as drawn at once."""
    a_img, a = _figure(prog, fig, False, monkeypatch)
    b_img, b = _figure(prog, fig, True, monkeypatch)
    assert (a_img is None) == (b_img is None)
    if a_img is not None:
        assert np.array_equal(a_img, b_img)
    assert a.keys() == b.keys()
    for name in a:
        assert (a[name] is None) == (b[name] is None), name
        if a[name] is not None:
            assert np.array_equal(a[name], b[name]), name


def _slow_raster(monkeypatch, seconds=0.05):
    """Every queued pass first sleeps: work is surely still queued when the
    program's next call runs.  Small passes are queued too (not drawn at
    once: config.INLINE_TRIANGLES)."""
    monkeypatch.setattr(config, "INLINE_TRIANGLES", -1)
    real = machine_module._raster_pass

    def slow(*args):
        time.sleep(seconds)
        real(*args)
    monkeypatch.setattr(machine_module, "_raster_pass", slow)


def _square(x0, y0, x1, y1):
    bgnpolygon()
    for v in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
        v2f(v)
    endpolygon()


def test_a_bank_read_waits_for_the_queued_passes(open_window, monkeypatch):
    """A slow raster thread: right after the call that queued a pass the
    work is still pending, and reading fb.front (a test's direct read) or
    lrectread (the IRIS GL read) returns the pixels the pass drew."""
    monkeypatch.setattr(config, "PIPELINE", True)
    _slow_raster(monkeypatch)
    open_window(32, 32, pixels=True, cleared=True)
    cpack(0xFF0000FF)
    _square(4, 4, 12, 12)
    machine.flush()                       # the batch's pass queued, not waited for
    queued = pipeline.pending()
    front = machine.current.fb.front
    assert queued
    assert front[8, 8] == 0xFF0000FF and front[20, 20] == 0
    RGBcolor(0, 255, 0)
    _square(16, 16, 28, 28)
    machine.flush()
    assert pipeline.pending()
    px = lrectread(20, 20, 20, 20)
    assert int(px[0, 0]) & 0xFFFFFF == 0x00FF00


def test_calls_that_only_queue_do_not_wait(open_window, monkeypatch):
    """Drawing, the state changes that flush it and clears queue their work
    and return without waiting: with a slow raster thread the work is still
    pending after them, and no thread has waited; the frame point waits."""
    monkeypatch.setattr(config, "PIPELINE", True)
    _slow_raster(monkeypatch, 0.2)
    open_window(32, 32, pixels=True)
    waits = pipeline.waits()
    clear()
    for k in range(3):
        cpack(0xFF000000 | (k * 40))
        _square(2 + k, 2, 20 + k, 20)
        backface(k % 2)                    # a state change: the batch is flushed
    zclear()
    assert pipeline.pending()
    assert pipeline.waits() == waits
    swapbuffers()                          # a frame point waits
    assert not pipeline.pending() and pipeline.waits() == waits + 1
    assert machine.current.fb.front[10, 10] == 0xFF000050


def test_a_failure_in_queued_work_reaches_the_program(open_window, monkeypatch):
    """An exception inside a queued pass is raised by the next call that
    waits, with its own message; the pipeline is usable afterwards."""
    monkeypatch.setattr(config, "PIPELINE", True)
    open_window(16, 16, pixels=True)

    def broken(*args):
        raise RuntimeError("walker broke")
    monkeypatch.setattr(machine_module, "_raster_pass", broken)
    _square(2, 2, 8, 8)
    machine.flush()                        # queues the pass, does not wait
    with pytest.raises(RuntimeError, match="walker broke"):
        gflush()
    monkeypatch.undo()
    monkeypatch.setattr(config, "PIPELINE", True)
    cpack(0xFF00FF00)
    _square(2, 2, 8, 8)
    gflush()
    assert machine.current.fb.front[4, 4] == 0xFF00FF00


def test_waiting_thread_takes_shares_each_once(monkeypatch):
    """pipeline.shared: the shares of a pass are run once each, by the
    raster thread and by the thread waiting in sync."""
    monkeypatch.setattr(config, "PIPELINE", True)
    ran, who = [], set()
    started = threading.Event()

    def run(k):
        time.sleep(0.002)
        ran.append(k)
        who.add(threading.get_ident())

    def task():
        started.set()
        deadline = time.perf_counter() + 5
        while not pipeline.helper_waiting() and time.perf_counter() < deadline:
            time.sleep(0.001)
        pipeline.shared(run, 60)

    pipeline.submit(task)
    assert started.wait(5)                 # the raster thread runs it (not this one)
    pipeline.sync()
    assert sorted(ran) == list(range(60))
    assert threading.get_ident() in who and len(who) == 2


def test_a_waiting_thread_runs_the_items_not_started(monkeypatch):
    """Items the raster thread has not started when the program waits are
    run by the waiting thread itself, in the order they were queued.  (A
    pipeline whose raster thread never wakes: fresh queue, lock and state.)"""
    import collections
    monkeypatch.setattr(config, "PIPELINE", True)
    monkeypatch.setattr(pipeline, "_lock", threading.Condition())
    monkeypatch.setattr(pipeline, "_items", collections.deque())
    monkeypatch.setattr(pipeline, "_state", dict(pipeline._state, sent=0, done=0, running=False,
                                                 error=None, thread=object(), offer=None,
                                                 waiting=0))
    order = []
    for k in range(5):
        pipeline.submit(lambda k=k: order.append((k, threading.get_ident())))
    assert pipeline.pending() and not order
    pipeline.sync()
    assert order == [(k, threading.get_ident()) for k in range(5)]
    assert not pipeline.pending()


def test_one_thread_or_pipeline_off_runs_at_once(open_window, monkeypatch):
    """config.PIPELINE off, or numba.set_num_threads(1): nothing is queued."""
    open_window(16, 16, pixels=True)
    for on, threads in ((False, 2), (True, 1)):
        monkeypatch.setattr(config, "PIPELINE", on)
        before = numba.get_num_threads()
        numba.set_num_threads(threads)
        try:
            _square(1, 1, 9, 9)
            machine.flush()
            assert not pipeline.pending()
        finally:
            numba.set_num_threads(before)


@pytest.mark.parametrize("args", [["--figure", "5b", "--objects"],
                                  ["--figure", "5b", "--objects", "--two-pass", "--infinite"],
                                  ["--figure", "5b"],
                                  ["--figure", "6", "--objects"]])
def test_a_multipass_frame_waits_once(args, monkeypatch):
    """Heidmann's figure 5b (clears, volumes, lit passes for four lights;
    from objects and call by call) and figure 6 (32 passes accumulated with
    acbuf): a frame waits for the raster thread only at its frame point."""
    monkeypatch.setattr(config, "PIPELINE", True)
    marks = []
    real = machine_module.VGX.frame_end

    def frame_end(self, win):
        marks.append(pipeline.waits())
        real(self, win)
    monkeypatch.setattr(machine_module.VGX, "frame_end", frame_end)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        img = run_program(ROOT / "programs" / "heidmann_shadow_volumes.py", frames=3,
                          argv=args + ["--size", "160x120"])
    assert len(marks) >= 3 and img.any()
    # between two frame points: the first one's wait, none while drawing
    assert [b - a for a, b in zip(marks[1:], marks[2:])] == [1] * (len(marks) - 2)


def test_setup_and_lighting_in_shares_draw_the_same(open_window, monkeypatch):
    """A large batch's triangle setup and lighting run in shares on the
    walker's threads while the raster thread is idle (pipeline.split): the
    picture and z are those of one share each, and the shares did run."""
    from irisgl import (DEFLIGHT, DEFLMODEL, DEFMATERIAL, DIFFUSE, LIGHT0, LMNULL, LMODEL,
                        MATERIAL, MVIEWING, POSITION, bgntmesh, endtmesh, lmbind, lmdef,
                        mmode, n3f, ortho, v3f, zbuffer)
    from vgx_emulator.geometry import lighting

    def draw(share):
        monkeypatch.setattr(config, "SETUP_SHARE", share)
        monkeypatch.setattr(lighting, "LIGHT_SHARE", share)
        open_window(64, 48, cleared=True)
        zbuffer(1)
        zclear()
        mmode(MVIEWING)
        ortho(0, 64, 0, 48, -10, 10)
        lmdef(DEFMATERIAL, 1, 0, [DIFFUSE, 0.8, 0.6, 0.3, LMNULL])
        lmdef(DEFLIGHT, 1, 0, [POSITION, 0.3, 0.4, 1.0, 0.0, LMNULL])
        lmdef(DEFLMODEL, 1, 0, [LMNULL])
        lmbind(MATERIAL, 1)
        lmbind(LIGHT0, 1)
        lmbind(LMODEL, 1)
        for r in range(24):                    # 24 strips of 2 x 64 triangles
            bgntmesh()
            for c in range(65):
                for y in (2 * r, 2 * r + 2):
                    z = np.sin(c / 5.0) * np.cos(y / 7.0)
                    n3f((0.3 * np.cos(c / 5.0), -0.2 * np.sin(y / 7.0), 1.0))
                    v3f((c, y, z))
            endtmesh()
        pipeline.sync()                        # the clears done: the raster thread idle
        machine.flush()
        fb = machine.current.fb
        return fb.front.copy(), fb.z.copy()

    calls = []
    real = pipeline.on_threads
    monkeypatch.setattr(pipeline, "on_threads", lambda *a: (calls.append(a[1]), real(*a)))
    whole = draw(1 << 30)
    assert not calls
    shared = draw(256)
    assert len(calls) == 2 and min(calls) > 1       # setup and lighting, in shares
    assert (whole[0] != 0).sum() > 2000
    assert np.array_equal(whole[0], shared[0])
    assert np.array_equal(whole[1], shared[1])


def test_a_small_pass_is_drawn_at_once_when_the_raster_thread_is_idle(open_window,
                                                                      monkeypatch):
    """A pass of few triangles over a small box (config.INLINE_TRIANGLES,
    INLINE_PIXELS) is drawn on the program's thread when nothing is queued:
    nothing is pending after its flush.  Queued behind a slow clear it
    waits its turn instead, and the pixels are those of the order the calls
    were made in."""
    monkeypatch.setattr(config, "PIPELINE", True)
    open_window(32, 32, pixels=True, cleared=True)
    pipeline.sync()                        # (the window's clear)
    cpack(0xFF0000FF)
    _square(4, 4, 12, 12)
    machine.flush()
    assert not pipeline.pending()
    assert machine.current.fb.front[8, 8] == 0xFF0000FF
    real = machine_module._kernel_calls

    def slow(*args):
        time.sleep(0.2)
        real(*args)
    monkeypatch.setattr(machine_module, "_kernel_calls", slow)
    clear()                                # (in the current red) queued, slow
    cpack(0xFF00FF00)
    _square(4, 4, 12, 12)
    machine.flush()
    assert pipeline.pending()              # the square waits behind the clear
    front = machine.current.fb.front
    assert front[8, 8] == 0xFF00FF00 and front[20, 20] == 0xFF0000FF


def test_num_threads_is_numbas_count_of_the_calling_thread():
    """pipeline.num_threads reads what numba.get_num_threads gives, after
    set_num_threads on this thread and on another."""
    n = numba.get_num_threads()
    assert pipeline.num_threads() == n
    seen = []
    try:
        numba.set_num_threads(1)
        assert pipeline.num_threads() == 1 == numba.get_num_threads()
        t = threading.Thread(target=lambda: seen.append(pipeline.num_threads()))
        t.start()
        t.join()
    finally:
        numba.set_num_threads(n)
    assert pipeline.num_threads() == n
    assert seen == [numba.get_num_threads()]


def test_the_walkers_threads_follow_the_batch_area(open_window, monkeypatch):
    """run_bands walks a batch on several threads only when its triangles'
    boxes cover config.PARALLEL_MIN_PIXELS or more, estimated from every
    step-th triangle (scan.triangles.AREA_SAMPLE) in a large batch: 4,608
    triangles whose setup boxes are 4 x 4 pixels (73,728 pixels; each square
    of two draws 3 x 3 pixels) stay on one thread under a threshold of
    80,000 and go to the threads under 60,000, which the estimate tells
    apart; the pixels are the same either way."""
    from vgx_emulator.scan import triangles
    if pipeline.num_threads() < 2 or not config.PARALLEL:
        pytest.skip("one thread: nothing to share")
    monkeypatch.setattr(config, "PIPELINE", False)
    monkeypatch.setattr(config, "SETUP_SHARE", 1 << 30)     # only the walker in shares
    calls = []
    real = pipeline.on_threads
    monkeypatch.setattr(pipeline, "on_threads", lambda *a: (calls.append(a[1]), real(*a)))

    def draw(threshold):
        monkeypatch.setattr(config, "PARALLEL_MIN_PIXELS", threshold)
        open_window(256, 256, cleared=True)
        for j in range(48):                    # 48 x 48 squares of two triangles
            for i in range(48):
                cpack(0xFF000000 | (i * 5 << 8) | j * 5)
                _square(5 * i + 2, 5 * j + 2, 5 * i + 5, 5 * j + 5)
        calls.clear()
        machine.flush()
        return list(calls), machine.current.fb.front.copy()

    assert 48 * 48 * 2 > 2 * triangles.AREA_SAMPLE        # the estimate samples
    one, a = draw(80_000)
    many, b = draw(60_000)
    assert one == [] and len(many) == 1 and many[0] > 1
    assert np.array_equal(a, b) and (a != 0).sum() == 48 * 48 * 9
