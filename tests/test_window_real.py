"""vgx-run --window: a program in a real X window, driven by real X events.

The events come from outside (xdotool, as a user's mouse and keyboard would
send them) and the screenshots from the X server (Pillow's ImageGrab), never
from the emulator, so the tests check the whole path: the window's place and
size, the picture shown at each frame point, mouse and key input into the
queue, the real pop-up menu, and the end of the program.  They run on a
private Xvfb server and are skipped where Xvfb or xdotool is missing
(.ci/run installs both).
"""
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from vgx_emulator.runner import run_program

ROOT = Path(__file__).resolve().parent.parent
CUBE = ROOT / "programs" / "demos" / "lit_valuators.py"
SCREEN_H = 1024
#: vgx-run, as its console script runs it
VGX_RUN = [sys.executable, "-c", "import sys; from vgx_emulator.runner import main; "
           "sys.exit(main())"]

pytestmark = pytest.mark.skipif(not (shutil.which("Xvfb") and shutil.which("xdotool")),
                                reason="needs Xvfb and xdotool (Debian xvfb, xdotool)")


@pytest.fixture(scope="module")
def xserver():
    """A private X server of the VGX's screen size."""
    for n in range(90, 120):
        if not Path(f"/tmp/.X11-unix/X{n}").exists() and not Path(f"/tmp/.X{n}-lock").exists():
            break
    disp = f":{n}"
    proc = subprocess.Popen(["Xvfb", disp, "-screen", "0", "1280x1024x24", "-nolisten", "tcp"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(100):
        if Path(f"/tmp/.X11-unix/X{n}").exists():
            break
        time.sleep(0.05)
    time.sleep(0.3)
    yield disp
    proc.terminate()
    proc.wait(10)


class Program:
    """A program run by ``vgx-run --window`` in its own process."""

    def __init__(self, disp, path, *args, name):
        self.disp = disp
        self.env = dict(os.environ, DISPLAY=disp)
        self.proc = subprocess.Popen(
            [*VGX_RUN, "--window", "--fps", "0", str(path),
             "--", *args], env=self.env, cwd=ROOT,
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        out = self.xdo("search", "--sync", "--onlyvisible", "--name", name, timeout=60)
        self.wid = out.split()[0]

    def xdo(self, *args, timeout=10):
        return subprocess.run(["xdotool", *args], env=self.env, capture_output=True, text=True,
                              timeout=timeout, check=True).stdout

    def geometry(self):
        out = self.xdo("getwindowgeometry", "--shell", self.wid)
        g = dict(line.split("=") for line in out.split())
        return int(g["X"]), int(g["Y"]), int(g["WIDTH"]), int(g["HEIGHT"])

    def shot(self):
        """The window's pixels as the X server has them, (h, w, 3) top row first."""
        from PIL import ImageGrab
        x, y, w, h = self.geometry()
        img = ImageGrab.grab(bbox=(x, y, x + w, y + h), xdisplay=self.disp)
        return np.asarray(img.convert("RGB"))

    def settle(self, previous=None, timeout=10.0):
        """Wait until the picture stops changing (and differs from ``previous``)."""
        t0, last = time.time(), None
        while time.time() - t0 < timeout:
            img = self.shot()
            if last is not None and np.array_equal(img, last) and (
                    previous is None or not np.array_equal(img, previous)):
                return img
            last = img
            time.sleep(0.25)
        return last

    def wait(self, timeout=30):
        return self.proc.wait(timeout)

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


@pytest.fixture
def cube(xserver):
    p = Program(xserver, CUBE, name="lit_valuators")
    yield p
    p.kill()


def test_window_is_placed_and_shows_the_headless_frame(cube):
    """prefsize 300x300, no prefposition: the window's lower-left corner is at
    the screen origin, and its picture is the headless image pixel for pixel."""
    x, y, w, h = cube.geometry()
    assert (w, h) == (300, 300)
    assert (x, SCREEN_H - (y + h)) == (0, 0)
    shown = cube.settle()
    assert np.array_equal(shown, run_program(CUBE, frames=1))


def test_a_drag_turns_the_cube_as_the_same_drag_headless(cube):
    """LEFTMOUSE tied to MOUSEX/MOUSEY: a real drag from window pixel (100, 150)
    to (160, 150), i.e. screen (100, 149) to (160, 149), gives exactly the
    picture of the same drag entered headless."""
    before = cube.settle()
    cube.xdo("mousemove", "--window", cube.wid, "100", "150", "mousedown", "1")
    time.sleep(0.3)
    cube.xdo("mousemove", "--window", cube.wid, "160", "150")
    time.sleep(0.3)
    cube.xdo("mouseup", "1")
    after = cube.settle(previous=before)
    assert not np.array_equal(after, before)
    assert np.array_equal(after, run_program(CUBE, frames=2,
                                             argv=["-drag", "100", "149", "160", "149"]))


def test_right_button_menu_selection_changes_the_picture(cube):
    """dopup pops up a real menu (title, separator, a cascade): choosing
    Material > blue plastic gives the picture of the scripted answer 2.3."""
    before = cube.settle()
    cube.xdo("mousemove", "--window", cube.wid, "150", "150", "mousedown", "3")
    time.sleep(0.8)
    for key in ("Down", "Down", "Right", "Down", "Down", "Return"):
        cube.xdo("key", key)
        time.sleep(0.3)
    cube.xdo("mouseup", "3")
    after = cube.settle(previous=before)
    blue = run_program(CUBE, frames=2, argv=["--menu", "2.3"])
    assert np.array_equal(after, blue)


def test_resizing_the_window_gives_redraw_with_the_new_size(cube):
    """A resize from outside reaches the program as REDRAW; reshapeviewport
    sees the new size and the cube is drawn again in the middle."""
    before = cube.settle()
    cube.xdo("windowsize", cube.wid, "420", "360")
    cube.xdo("windowmove", cube.wid, "0", str(SCREEN_H - 360))   # keep it on the screen
    after = cube.settle(previous=before)
    assert after.shape[:2] == (360, 420)
    bg = after[2, 2]
    assert (after[180, 210] != bg).any()            # the cube, centred again
    assert (after[357, 417] == bg).all()


def test_defined_cursor_becomes_an_x_bitmap(xserver):
    """defcursor(3G) glyph rows run bottom to top, leftmost pixel in the high
    bit; the X bitmap holds the same pixels top to bottom."""
    from vgx_emulator.display.tkwindow import C16X1, TkDisplay
    from irisgl._current import machine
    d = TkDisplay(machine, screen=xserver)
    try:
        words = [0] * 16
        words[0] = 0x8000                  # bottom row: the leftmost pixel
        words[15] = 0x0001                 # top row: the rightmost pixel
        spec = d.bitmap_cursor(1, C16X1, words, (0, 0))
        text = Path(spec.split()[0][1:]).read_text()
        bits = [int(b, 16) for b in text.split("{")[1].split("}")[0].split(",")]
        grid = np.array([[(bits[2 * r + (c // 8)] >> (c % 8)) & 1 for c in range(16)]
                         for r in range(16)])          # row 0 = top
        assert grid.sum() == 2 and grid[0, 15] == 1 and grid[15, 0] == 1
        assert "c_y_hot 15" in text                     # curorigin (0, 0): bottom left
    finally:
        d.close_all()


def test_escape_key_ends_the_program(cube):
    cube.settle()
    cube.xdo("windowfocus", "--sync", cube.wid)
    cube.xdo("key", "Escape")
    assert cube.wait() == 0


def _wm_delete(disp, wid):
    """What a window manager sends when the user closes a window: the
    WM_DELETE_WINDOW client message (ICCCM), through libX11 with ctypes."""
    import ctypes
    import ctypes.util
    x = ctypes.CDLL(ctypes.util.find_library("X11"))
    x.XOpenDisplay.restype = ctypes.c_void_p
    x.XInternAtom.restype = ctypes.c_ulong
    x.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]

    class ClientMessage(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong),
                    ("send_event", ctypes.c_int), ("display", ctypes.c_void_p),
                    ("window", ctypes.c_ulong), ("message_type", ctypes.c_ulong),
                    ("format", ctypes.c_int), ("data", ctypes.c_long * 5),
                    ("pad", ctypes.c_long * 24)]
    d = x.XOpenDisplay(disp.encode())
    ev = ClientMessage(type=33, display=d, window=int(wid), format=32,
                       message_type=x.XInternAtom(d, b"WM_PROTOCOLS", 0))
    ev.data[0] = x.XInternAtom(d, b"WM_DELETE_WINDOW", 0)
    x.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long,
                             ctypes.c_void_p]
    x.XSendEvent(d, int(wid), 0, 0, ctypes.byref(ev))
    x.XCloseDisplay.argtypes = [ctypes.c_void_p]
    x.XFlush.argtypes = [ctypes.c_void_p]
    x.XFlush(d)
    x.XCloseDisplay(d)


def test_closing_the_window_ends_the_program_cleanly(cube):
    """A program that queues neither WINQUIT nor WINSHUT ends when its window
    is closed, with exit status 0."""
    cube.settle()
    _wm_delete(cube.disp, cube.wid)
    assert cube.wait() == 0


def test_no_display_is_a_one_line_error():
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    r = subprocess.run([*VGX_RUN, "--window", str(CUBE)],
                       env=env, cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "run without --window" in lines[0]


def test_a_program_that_queues_winquit_gets_it_on_close(xserver, tmp_path):
    prog = tmp_path / "quitter.py"
    prog.write_text(
        "from irisgl import *\n"
        "prefsize(64, 48); gid = winopen('quitter'); RGBmode(); gconfig()\n"
        "qdevice(WINQUIT)\n"
        "cpack(0xff0000ff); clear(); gflush()\n"
        "while True:\n"
        "    dev, val = qread()\n"
        "    if dev == WINQUIT:\n"
        "        print('WINQUIT', val, val == gid, flush=True)\n"
        "        break\n")
    p = Program(xserver, prog, name="quitter")
    try:
        shown = p.settle()
        assert (shown == (255, 0, 0)).all()           # gflush put the clear on screen
        _wm_delete(p.disp, p.wid)
        assert p.wait() == 0
        assert "WINQUIT 1 True" in p.proc.stdout.read()
    finally:
        p.kill()


def test_single_buffered_drawing_shows_as_it_happens(xserver, tmp_path):
    """No frame point at all: a single-buffered program's drawing reaches the
    screen while the program is still busy (bounded by the frame rate)."""
    prog = tmp_path / "busy.py"
    prog.write_text(
        "import time\n"
        "from irisgl import *\n"
        "prefsize(64, 48); winopen('busy'); RGBmode(); gconfig()\n"
        "ortho2(-0.5, 63.5, -0.5, 47.5)\n"
        "cpack(0xff00ff00)\n"
        "t0 = time.time()\n"
        "while time.time() - t0 < 12:\n"
        "    rectf(-1, -1, 64, 48)\n"
        "    time.sleep(0.01)\n")
    p = Program(xserver, prog, name="busy")
    try:
        t0 = time.time()
        while time.time() - t0 < 8:
            if (p.shot() == (0, 255, 0)).all():
                break
            time.sleep(0.2)
        shot = p.shot()
        assert (shot == (0, 255, 0)).all(), (np.unique(shot.reshape(-1, 3), axis=0),
                                             p.proc.poll())
        assert p.proc.poll() is None                   # still drawing, never swapped
    finally:
        p.kill()


def test_pause_and_step_through_the_passes_of_a_frame(xserver, tmp_path):
    """Control+P traces the next frame and pauses on it; Control+B/N step
    through its passes; Control+3 shows the stencil bank, which after the
    sclear(5) pass holds 5 everywhere (the legend counts every pixel)."""
    prog = tmp_path / "passes.py"
    prog.write_text(
        "from irisgl import *\n"
        "prefsize(64, 48); winopen('passes'); RGBmode(); doublebuffer(); stensize(8)\n"
        "gconfig(); zbuffer(TRUE); ortho2(-0.5, 63.5, -0.5, 47.5)\n"
        "while True:\n"
        "    czclear(0xff000000, getgdesc(GD_ZMAX))\n"
        "    sclear(5)\n"
        "    cpack(0xff0000ff); rectf(10, 10, 40, 30)\n"
        "    swapbuffers()\n")
    p = Program(xserver, prog, name="passes")
    try:
        p.settle()
        p.xdo("windowfocus", "--sync", p.wid)
        p.xdo("key", "ctrl+2")                        # the z bank of the running program
        t0 = time.time()
        while "z bank" not in p.xdo("getwindowname", p.wid) and time.time() - t0 < 10:
            time.sleep(0.2)
        assert "z bank" in p.xdo("getwindowname", p.wid)
        p.xdo("key", "ctrl+1")
        p.xdo("key", "ctrl+p")

        def title(want, timeout=15):
            t0 = time.time()
            while time.time() - t0 < timeout:
                name = p.xdo("getwindowname", p.wid)
                if want in name:
                    return name
                time.sleep(0.2)
            return name
        last = title("pass 4/4")
        assert "pass 4/4" in last                     # czclear, sclear, rectf, swap
        p.xdo("key", "ctrl+b")
        p.xdo("key", "ctrl+b")
        p.xdo("key", "ctrl+3")
        name = title("stencil bank")
        assert "pass 2/4" in name and "5 (= key): 3072 px" in name, name
        p.xdo("key", "ctrl+n")
        assert "pass 3/4" in title("pass 3/4")
        p.xdo("key", "ctrl+1")
        p.xdo("key", "ctrl+p")                        # resume
        t0 = time.time()
        while p.xdo("getwindowname", p.wid).strip() != "passes" and time.time() - t0 < 10:
            time.sleep(0.2)
        assert p.xdo("getwindowname", p.wid).strip() == "passes"    # running again
        time.sleep(1)
        assert p.proc.poll() is None
    finally:
        p.kill()


def test_two_windows_keys_and_focus(xserver, tmp_path):
    """Each IRIS GL window is a real window at its prefposition; KEYBD gives
    ASCII, INPUTCHANGE names the window that gets the input focus."""
    prog = tmp_path / "two.py"
    prog.write_text(
        "from irisgl import *\n"
        "prefposition(100, 199, 200, 279); a = winopen('first'); RGBmode(); gconfig()\n"
        "cpack(0xff0000ff); clear()\n"
        "prefposition(400, 463, 500, 547); b = winopen('second'); RGBmode(); gconfig()\n"
        "cpack(0xffff0000); clear()\n"
        "qdevice(KEYBD); qdevice(INPUTCHANGE)\n"
        "qreset()\n"
        "while True:\n"
        "    dev, val = qread()\n"
        "    print(dev, val, flush=True)\n"
        "    if dev == KEYBD and val == ord('q'):\n"
        "        break\n")
    p = Program(xserver, prog, name="second")
    try:
        first = p.xdo("search", "--sync", "--onlyvisible", "--name", "first").split()[0]
        x, y, w, h = p.geometry()
        assert (x, SCREEN_H - (y + h), w, h) == (400, 500, 64, 48)
        assert (p.settle() == (0, 0, 255)).all()
        p.wid = first
        x, y, w, h = p.geometry()
        assert (x, SCREEN_H - (y + h), w, h) == (100, 200, 100, 80)
        assert (p.settle() == (255, 0, 0)).all()
        p.xdo("windowfocus", "--sync", first)
        time.sleep(0.5)
        p.xdo("type", "aq")
        assert p.wait() == 0
        lines = p.proc.stdout.read().split("\n")
        assert "534 1" in lines                          # INPUTCHANGE: window 1
        keys = [ln for ln in lines if ln.startswith("513 ")]
        assert keys == ["513 97", "513 113"]
    finally:
        p.kill()


def test_a_polling_program_sees_its_input(xserver, tmp_path):
    """A program that never waits nor swaps, only polls qtest(3G): its window
    still shows and its keys still arrive."""
    prog = tmp_path / "poller.py"
    prog.write_text(
        "from irisgl import *\n"
        "prefsize(64, 48); winopen('poller'); RGBmode(); gconfig()\n"
        "qdevice(ESCKEY)\n"
        "cpack(0xff0000ff); clear()\n"
        "while True:\n"
        "    if qtest():\n"
        "        dev, val = qread()\n"
        "        if dev == ESCKEY and val == 0:\n"
        "            break\n")
    p = Program(xserver, prog, name="poller")
    try:
        assert (p.settle() == (255, 0, 0)).all()
        p.xdo("windowfocus", "--sync", p.wid)
        p.xdo("key", "Escape")
        assert p.wait() == 0
    finally:
        p.kill()


def test_frames_are_paced_to_30_a_second_by_default(xserver, tmp_path):
    """--fps defaults to 30: a program swapping as fast as it can shows at
    most 30 frames a second (a bound, so the test allows for a slow start)."""
    prog = tmp_path / "fast.py"
    prog.write_text(
        "import time\n"
        "from irisgl import *\n"
        "prefsize(32, 32); winopen('fast'); RGBmode(); doublebuffer(); gconfig()\n"
        "n, t0 = 0, None\n"
        "while True:\n"
        "    clear(); swapbuffers(); n += 1\n"
        "    if n == 5:\n"
        "        t0 = time.perf_counter()\n"
        "    if n == 65:\n"
        "        print('rate', 60 / (time.perf_counter() - t0), flush=True)\n"
        "        break\n")
    env = dict(os.environ, DISPLAY=xserver)
    r = subprocess.run([*VGX_RUN, "--window", str(prog)], env=env, cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    rate = float(r.stdout.split("rate")[1])
    assert 20 < rate <= 30.5
