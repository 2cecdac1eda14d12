"""A live view of a program in a Jupyter notebook cell (the ``[notebook]``
extra: ipywidgets and ipyevents).

``LiveView("programs/demos/lit_valuators.py")`` shows the program's current
window as an image widget, updated at every frame point and before it waits
for input (at most ``fps`` times a second), and sends the mouse and keys
pressed over the image into the program's queue, as the real window of
``vgx-run --window`` does (display/tkwindow.py).  The program runs in a
thread of its own, so the notebook stays responsive; the widget's events
reach it through a thread-safe inbox that the program's thread empties at
its frame points and while it waits, so the machine is only ever touched by
that one thread.  Pop-up menus take their answers from ``menu`` (as
``vgx-run --menu``), since a notebook has no native pop-up menu.
``stop()`` ends the program.  The live program drives the one machine
that the irisgl calls drive: run one at a time, and leave irisgl alone in
the notebook while it runs.

Plain pictures need no extra: windows, planes and trace steps have
``_repr_png_`` (vgx_emulator/planes.py).
"""
import io
import queue
import threading
import time

from .events import MOUSEX, MOUSEY

LEFTMOUSE, MIDDLEMOUSE, RIGHTMOUSE, KEYBD = 103, 102, 101, 513
_BUTTONS = {0: LEFTMOUSE, 1: MIDDLEMOUSE, 2: RIGHTMOUSE}
#: DOM key names -> IRIS GL raw key devices (device.h)
_KEYS = {
    **{c: d for c, d in zip("abcdefghijklmnopqrstuvwxyz",
                            (11, 36, 28, 18, 17, 19, 26, 27, 40, 34, 35, 42, 44, 37, 41, 48,
                             10, 24, 12, 25, 33, 29, 16, 21, 32, 20))},
    **{str(i): d for i, d in enumerate((46, 8, 14, 15, 22, 23, 30, 31, 38, 39))},
    "Escape": 7, " ": 83, "Enter": 51, "Tab": 9, "Delete": 62, "Backspace": 61,
    "ArrowLeft": 73, "ArrowDown": 74, "ArrowRight": 80, "ArrowUp": 81, "Shift": 6,
    "Control": 3, **{f"F{i}": 145 + i for i in range(1, 13)},
}
_ASCII = {"Enter": 13, "Tab": 9, "Backspace": 8, "Escape": 27, "Delete": 127}


class LiveView:
    """Run ``path`` (with ``argv``) live in a notebook cell; display the
    object (or ``.widget``) to see it."""

    def __init__(self, path, argv=(), fps=30.0, menu=None, start=True):
        try:
            import ipywidgets
            from ipyevents import Event
        except ImportError as e:
            raise ImportError("LiveView needs the [notebook] extra: "
                              "pip install 'iris-vgx[notebook]'") from e
        self.path, self.argv, self.menu = str(path), list(argv), menu
        self.period = 1.0 / fps if fps and fps > 0 else 0.0
        self.widget = ipywidgets.Image(format="png")
        self.events = Event(source=self.widget, prevent_default_action=True,
                            watched_events=["mousedown", "mouseup", "mousemove",
                                            "keydown", "keyup", "contextmenu"])
        self.events.on_dom_event(self.on_event)
        self.inbox = queue.Queue()
        self.frames = 0
        self.size = None                    # (w, h) of the window shown
        self.origin = (0, 0)
        self.error = None
        self._stop = threading.Event()
        self._shown = 0.0
        self.thread = None
        if start:
            self.start()

    def _repr_mimebundle_(self, **kwargs):
        return self.widget._repr_mimebundle_(**kwargs)

    # -- the notebook's side ---------------------------------------------
    def on_event(self, e):
        """A DOM event over the image -> (device, value) entries for the
        program (its thread delivers them)."""
        kind = e.get("type")
        if kind in ("mousedown", "mouseup", "mousemove") and self.size is not None:
            x = int(e.get("dataX", e.get("relativeX", 0)))
            y = int(e.get("dataY", e.get("relativeY", 0)))
            sx = self.origin[0] + x
            sy = self.origin[1] + self.size[1] - 1 - y
            self.inbox.put((MOUSEX, sx))
            self.inbox.put((MOUSEY, sy))
            if kind != "mousemove" and e.get("button") in _BUTTONS:
                self.inbox.put((_BUTTONS[e["button"]], 1 if kind == "mousedown" else 0))
        elif kind in ("keydown", "keyup"):
            key = e.get("key", "")
            dev = _KEYS.get(key, _KEYS.get(key.lower()))
            if dev is not None:
                self.inbox.put((dev, 1 if kind == "keydown" else 0))
            if kind == "keydown":
                code = _ASCII.get(key, ord(key) if len(key) == 1 and ord(key) < 128 else None)
                if code is not None:
                    self.inbox.put(("KEYBD", code))

    def stop(self, timeout=10.0):
        """End the program (it leaves at its next frame point or wait)."""
        self._stop.set()
        if self.thread is not None:
            self.thread.join(timeout)

    def wait(self, timeout=None):
        if self.thread is not None:
            self.thread.join(timeout)
        return self.error

    # -- the program's side ----------------------------------------------
    def start(self):
        self.thread = threading.Thread(target=self._run, name="vgx-live", daemon=True)
        self.thread.start()
        return self

    def _deliver(self, m, first=None):
        """Move what the notebook sent into the queue (program thread only),
        ``first`` (already taken from the inbox) before the rest."""
        ev = m.events
        while True:
            if first is not None:
                (dev, val), first = first, None
            else:
                try:
                    dev, val = self.inbox.get_nowait()
                except queue.Empty:
                    return
            if dev == "KEYBD":
                if KEYBD in ev.queued:
                    ev.enter(KEYBD, val)
            else:
                if dev in (MOUSEX, MOUSEY) and ev.valuators.get(dev) == val:
                    continue
                ev.device_input(dev, val)

    def _show(self, m, win):
        from PIL import Image
        img = m.image(win)
        buf = io.BytesIO()
        Image.fromarray(img).save(buf, "PNG", compress_level=1)
        self.size = (win.width, win.height)
        self.origin = win.origin
        self.widget.value = buf.getvalue()
        self._shown = time.perf_counter()

    def _run(self):
        from irisgl._current import machine as m
        from . import menus
        from .runner import FramesDone, execute
        m.reset()
        if self.menu is not None:
            menus.script(self.menu, m)

        def on_frame(_m, win):
            self.frames += 1
            self._show(m, win)
            while True:                    # keep to the frame rate, taking input
                self._deliver(m)
                if self._stop.is_set():
                    raise FramesDone()
                rest = self._shown + self.period - time.perf_counter()
                if rest <= 0:
                    return
                time.sleep(min(rest, 0.005))

        def on_wait():
            if m.current is not None:
                self._show(m, m.current)
            while not m.events.entries:
                if self._stop.is_set():
                    raise FramesDone()
                m.events.tick()            # TIMERn entries in real time
                if m.events.entries:
                    break
                try:
                    item = self.inbox.get(timeout=0.05)
                except queue.Empty:
                    continue
                self._deliver(m, item)

        try:
            execute(m, self.path, self.argv, {"frame": on_frame, "wait": on_wait})
        except SystemExit as e:
            self.error = e
        except Exception as e:            # shown to the notebook by wait()
            self.error = e
