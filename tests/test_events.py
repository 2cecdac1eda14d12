"""The event queue and the headless runner (docs/semantics.md §13,
docs/porting.md §5)."""
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import GLError
from vgx_emulator import run_program
from vgx_emulator.events import QueueExhausted

ROOT = Path(__file__).resolve().parent.parent


def drain():
    """Every entry left in the queue, in order (qread until it is empty)."""
    out = []
    while qtest():
        out.append(qread())
    with pytest.raises(QueueExhausted):
        qread()
    return out


# -- the queue -----------------------------------------------------------------------
def test_device_constants():
    assert (REDRAW, INPUTCHANGE, QFULL, KEYBD, LEFTMOUSE, MOUSEX, MOUSEY, ESCKEY) == \
        (528, 534, 535, 513, 103, 266, 267, 7)


def test_winopen_queues_inputchange_and_redraw(open_window):
    gid = open_window(8, 8)
    assert qtest() == INPUTCHANGE                 # docs/decisions.md: INPUTCHANGE then REDRAW
    assert qread() == (INPUTCHANGE, gid)
    assert qtest() == REDRAW
    assert qread() == (REDRAW, gid)
    assert qtest() == 0


def test_second_window_queues_its_own_id(open_window):
    a = open_window(8, 8)
    b = open_window(8, 8)
    entries = drain()
    assert (REDRAW, a) in entries and (REDRAW, b) in entries
    assert (INPUTCHANGE, b) in entries


def test_qenter_qtest_qread_fifo(open_window):
    open_window(8, 8)
    qreset()
    assert qtest() == 0
    qdevice(LEFTMOUSE)
    qdevice(MOUSEX)
    qdevice(KEYBD)
    qenter(MOUSEX, 100)
    qenter(LEFTMOUSE, 1)
    qenter(KEYBD, ord("a"))
    qenter(LEFTMOUSE, 0)
    assert qtest() == MOUSEX
    assert qtest() == MOUSEX                      # qtest does not remove
    assert qread() == (MOUSEX, 100)
    assert qtest() == LEFTMOUSE
    assert qread() == (LEFTMOUSE, 1)
    assert qread() == (KEYBD, 97)
    assert qread() == (LEFTMOUSE, 0)
    assert qtest() == 0


def test_qdevice_unqdevice_isqueued(open_window):
    open_window(8, 8)
    assert not isqueued(LEFTMOUSE)
    qdevice(LEFTMOUSE)
    assert isqueued(LEFTMOUSE)
    unqdevice(LEFTMOUSE)
    assert not isqueued(LEFTMOUSE)


def test_qread_empty_raises_queue_exhausted(open_window):
    open_window(8, 8)
    qreset()
    with pytest.raises(SystemExit) as e:
        qread()
    assert isinstance(e.value, QueueExhausted)
    assert e.value.code == 0


def test_qreset_empties_queue(open_window):
    open_window(8, 8)
    qenter(LEFTMOUSE, 1)
    assert qtest() != 0
    qreset()
    assert qtest() == 0
    assert drain() == []


def test_queue_limit_101_and_qfull(open_window):
    open_window(8, 8)
    qreset()
    sent = [(MOUSEX, i) for i in range(150)]
    for dev, val in sent:
        qenter(dev, val)
    got = drain()
    assert len(got) <= 101
    assert got[-1][0] == QFULL
    kept = got[:-1]
    assert len(kept) >= 100
    assert kept == sent[:len(kept)]               # the oldest events survive, in order
    assert QFULL not in [d for d, _ in kept]


def test_queue_exactly_101_fits(open_window):
    open_window(8, 8)
    qreset()
    for i in range(101):
        qenter(KEYBD, 65 + i % 26)
    got = drain()
    assert len(got) == 101
    assert QFULL not in [d for d, _ in got]


def test_getvaluator_and_getbutton_follow_qenter(open_window):
    open_window(8, 8)
    assert getbutton(LEFTMOUSE) == 0
    qenter(MOUSEX, 321)
    qenter(MOUSEY, 123)
    assert getvaluator(MOUSEX) == 321
    assert getvaluator(MOUSEY) == 123
    qenter(LEFTMOUSE, 1)
    assert getbutton(LEFTMOUSE) == 1
    qenter(LEFTMOUSE, 0)
    assert getbutton(LEFTMOUSE) == 0


def test_bad_device_is_an_error(open_window):
    open_window(8, 8)
    with pytest.raises(GLError) as e:
        qdevice(-1)
    assert str(e.value).startswith("qdevice")
    with pytest.raises(GLError) as e:
        qenter(70000, 1)
    assert str(e.value).startswith("qenter")


# -- the runner ----------------------------------------------------------------------
LOOP_PROGRAM = '''
import sys
from irisgl import *

log = open(sys.argv[1], "a")
COLOURS = [0xFF0000FF, 0xFF00FF00, 0xFFFF0000, 0xFFFFFFFF]
prefsize(32, 24)
winopen("loop")
RGBmode()
doublebuffer()
gconfig()
qdevice(REDRAW)
qdevice(ESCKEY)
n = 0
while True:
    dev, val = qread()
    if dev == REDRAW:
        reshapeviewport()
        cpack(COLOURS[n % 4])
        clear()
        n += 1
        log.write("frame\\n")
        log.flush()
        swapbuffers()
    elif dev == ESCKEY and val == 0:
        break
gexit()
'''

NO_REDRAW_PROGRAM = '''
from irisgl import *
prefsize(16, 16)
winopen("once")
RGBmode()
gconfig()
cpack(0xFF00FF00)
clear()
gflush()
while True:
    dev, val = qread()
'''

ENDLESS_PROGRAM = '''
import sys
from irisgl import *
log = open(sys.argv[1], "a")
prefsize(16, 16)
winopen("endless")
RGBmode()
doublebuffer()
gconfig()
while True:
    cpack(0xFFFF0000)
    clear()
    log.write("frame\\n")
    log.flush()
    swapbuffers()
'''

COLOURS = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255)]


def _write(tmp_path, text, name="prog.py"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


@pytest.mark.parametrize("frames", [1, 2, 3, 5])
def test_runner_event_loop_stops_after_n_frames(tmp_path, frames):
    prog = _write(tmp_path, LOOP_PROGRAM)
    log = tmp_path / "log.txt"
    img = run_program(prog, frames=frames, argv=[str(log)])
    assert log.read_text().count("frame") == frames
    assert isinstance(img, np.ndarray) and img.shape == (24, 32, 3) and img.dtype == np.uint8
    assert np.all(img == COLOURS[(frames - 1) % 4])      # the last frame swapped in


def test_runner_ends_program_that_never_queues_redraw(tmp_path):
    prog = _write(tmp_path, NO_REDRAW_PROGRAM)
    img = run_program(prog, frames=4)
    assert img.shape == (16, 16, 3)
    assert np.all(img == (0, 255, 0))


def test_runner_stops_endless_drawing_loop(tmp_path):
    prog = _write(tmp_path, ENDLESS_PROGRAM)
    log = tmp_path / "log.txt"
    img = run_program(prog, frames=3, argv=[str(log)])
    assert log.read_text().count("frame") == 3
    assert np.all(img == (0, 0, 255))


def test_runner_program_that_closes_its_window(tmp_path):
    """ESC ends the loop and gexit closes the window: the last image is kept."""
    text = LOOP_PROGRAM.replace("qdevice(ESCKEY)\n", "qdevice(ESCKEY)\nqenter(ESCKEY, 0)\n")
    prog = _write(tmp_path, text)
    log = tmp_path / "log.txt"
    img = run_program(prog, frames=10, argv=[str(log)])
    # INPUTCHANGE, REDRAW (drawn: red) then the ESC release ends the loop
    assert log.read_text().count("frame") == 1
    assert img is not None and np.all(img == (255, 0, 0))


def test_runner_program_without_window_returns_none(tmp_path):
    prog = _write(tmp_path, "x = 1\n")
    assert run_program(prog, frames=1) is None


def _vgx_run_cmd():
    exe = shutil.which("vgx-run")
    return [exe] if exe else [sys.executable, "-m", "vgx_emulator.runner"]


def test_vgx_run_cli_writes_png(tmp_path):
    from PIL import Image
    out = tmp_path / "spheres.png"
    r = subprocess.run(_vgx_run_cmd() + [str(ROOT / "programs" / "four_spheres.py"),
                                         "--out", str(out), "--frames", "1"],
                       capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert out.is_file()
    with Image.open(out) as im:
        im.load()
        assert im.size == (640, 480)
        a = np.asarray(im.convert("RGB"))
    assert a.max() > 0                     # not all black
    assert (a.sum(axis=2) > 0).mean() > 0.01


def test_vgx_run_cli_rejects_missing_program(tmp_path):
    r = subprocess.run(_vgx_run_cmd() + [str(tmp_path / "nope.py")], capture_output=True,
                       text=True, timeout=120, cwd=tmp_path)
    assert r.returncode != 0


# -- TIMER0..TIMER3 (noise(3G), getgdesc(GD_TIMERHZ)) ------------------------------
def test_a_queued_timer_makes_an_entry_every_noise_ticks(open_window):
    """noise(3G): a timer device makes an entry every ``delta`` ticks of
    GD_TIMERHZ (default 10000).  Headless, a qread with nothing else queued
    gets the next tick at once, the queue's clock moving on by one period
    each time; entries are (TIMERn, 0)."""
    from irisgl._current import machine
    open_window(8, 8)
    qreset()
    ev = machine.events
    qdevice(TIMER0)
    assert ev.period(TIMER0) == 10000 / getgdesc(GD_TIMERHZ)
    noise(TIMER0, getgdesc(GD_TIMERHZ) // 10)          # 4Dgifts zoom: ten a second
    period = 6 / getgdesc(GD_TIMERHZ)
    start = ev.now()
    assert [qread() for _ in range(3)] == [(TIMER0, 0)] * 3
    assert ev.now() - start >= 3 * period - 1e-9
    unqdevice(TIMER0)
    with pytest.raises(SystemExit):
        qread()                                          # no tick any more


def test_timer_periods_that_passed_are_all_queued(open_window):
    """Periods that ended while the program was busy each queue an entry
    (qtest and qread look at the clock), in order with the other entries."""
    from irisgl._current import machine
    open_window(8, 8)
    qreset()
    ev = machine.events
    qdevice(TIMER1)
    noise(TIMER1, 60)                                    # one a second
    qenter(KEYBD, 65)
    ev.timers[TIMER1] = ev.now() - 2.5                   # due 2.5 s ago: 3 periods ended
    assert qtest() == KEYBD
    assert list(ev.entries) == [(KEYBD, 65)] + [(TIMER1, 0)] * 3
    assert ev.timers[TIMER1] > ev.now()


def test_noise_takes_timers_but_not_other_pseudo_devices(open_window):
    open_window(8, 8)
    noise(TIMER3, 1)
    with pytest.raises(GLError, match="^noise: device 528 is not a valuator"):
        noise(REDRAW, 1)
