"""Real windows for the emulated VGX (``vgx-run --window``), drawn with Tk.

Why Tk: it ships with CPython (``tkinter``), so a real window needs no
extra package; it runs on X11, macOS and Windows; and its event loop can be
pumped from the program's own thread (``update()``), which is exactly how
an IRIS GL program lives: it draws, swaps and reads the queue in one
thread, and the window system's events only have to reach the queue
between its calls.  No second thread touches the machine.

What the window system does for a program (qdevice(3G), qread(3G)):
- each IRIS GL window is a Tk toplevel of its size and place (the virtual
  1280x1024 screen's origin is the lower left; X's is the upper left);
- its picture is what the screen shows of the window (``machine.image``),
  shown at every frame point (swapbuffers, gflush, finish) and before the
  program waits for input, paced to at most ``fps`` frames a second;
- mouse buttons, motion (MOUSEX/MOUSEY in screen coordinates, tied
  valuators through the queue's own tie rule), keys (KEYBD as ASCII, each
  raw key device when queued), REDRAW on expose and resize (the banks take
  the new size), INPUTCHANGE on focus, WINQUIT/WINSHUT on close go into the
  real queue; a device's state changes whether or not it is queued;
- a blocking qread waits for real input; closing a window of a program that
  queues neither WINQUIT nor WINSHUT ends the program cleanly.
"""
import time

from .. import config
from ..events import INPUTCHANGE, MOUSEX, MOUSEY, REDRAW

LEFTMOUSE, MIDDLEMOUSE, RIGHTMOUSE = 103, 102, 101
KEYBD, WINQUIT, WINSHUT = 513, 542, 546

#: Tk keysym -> IRIS GL raw key device (device.h)
_KEYS = {
    **{c: d for c, d in zip("abcdefghijklmnopqrstuvwxyz",
                            (11, 36, 28, 18, 17, 19, 26, 27, 40, 34, 35, 42, 44, 37, 41, 48,
                             10, 24, 12, 25, 33, 29, 16, 21, 32, 20))},
    **{str(i): d for i, d in enumerate((46, 8, 14, 15, 22, 23, 30, 31, 38, 39))},
    "Escape": 7, "space": 83, "Return": 51, "Tab": 9, "Delete": 62, "BackSpace": 61,
    "Left": 73, "Down": 74, "Right": 80, "Up": 81, "Shift_L": 6, "Shift_R": 5,
    "Control_L": 3, "Control_R": 3,
    **{f"F{i}": 145 + i for i in range(1, 13)},
}


class NoDisplay(RuntimeError):
    """No display to open a real window on."""


class TkDisplay:
    """The real windows of one machine.  It is the machine's frame hook
    (``frame``), its queue's wait hook (``wait``) and its menus' chooser
    (``popup``); it opens and closes real windows as the program's windows
    come and go (``sync``)."""

    def __init__(self, machine, fps=30.0):
        try:
            import tkinter
        except ImportError as e:            # a Python built without Tk
            raise NoDisplay(f"tkinter is not available ({e})") from None
        try:
            self.root = tkinter.Tk()
        except tkinter.TclError as e:
            raise NoDisplay(str(e)) from None
        self.tk = tkinter
        self.root.withdraw()
        self.machine = machine
        self.period = 1.0 / fps if fps and fps > 0 else 0.0
        self.views = {}                     # gid -> _View
        self.last_shown = 0.0
        self.quit = False

    # -- the machine's side ---------------------------------------------
    def sync(self):
        """Open a real window for every IRIS GL window that has none, and
        close those whose IRIS GL window was closed."""
        wins = self.machine.windows
        for gid in [g for g in self.views if g not in wins]:
            self.views.pop(gid).top.destroy()
        for gid, win in wins.items():
            v = self.views.get(gid)
            if v is None or v.win is not win:
                if v is not None:
                    v.top.destroy()
                self.views[gid] = _View(self, win)

    def frame(self, m, win):
        """A frame point (the machine's frame hook): show the window, then
        keep to the frame rate."""
        self.sync()
        v = self.views.get(win.gid)
        if v is not None:
            v.show()
        self.pump()
        if self.period:
            rest = self.last_shown + self.period - time.perf_counter()
            while rest > 0:
                time.sleep(min(rest, 0.005))
                self.pump()
                rest = self.last_shown + self.period - time.perf_counter()
        self.last_shown = time.perf_counter()

    def wait(self):
        """qread on an empty queue: show every window, then wait for input."""
        self.sync()
        for v in self.views.values():
            v.show()
        ev = self.machine.events
        while not ev.entries:
            self.pump()
            if not self.views:
                raise SystemExit(0)
            time.sleep(0.005)

    def pump(self):
        """Let Tk deliver what the window system has for the program."""
        try:
            self.root.update()
        except self.tk.TclError:
            raise SystemExit(0) from None
        if self.quit:
            raise SystemExit(0)

    def close_all(self):
        for v in list(self.views.values()):
            v.top.destroy()
        self.views.clear()
        try:
            self.root.destroy()
        except self.tk.TclError:
            pass

    # -- pop-up menus (dopup(3G)) ---------------------------------------------
    def popup(self, pup):
        """Pop menu ``pup`` up at the pointer; the path of item numbers the
        user chose through submenus, or None when nothing was chosen."""
        chosen = {"path": None, "done": False}
        menu = self._build(pup, (), chosen)
        if menu is None:
            return None
        x, y = self.root.winfo_pointerxy()

        def unmapped(_e):
            self.root.after(50, lambda: chosen.__setitem__("done", True))
        menu.bind("<Unmap>", unmapped)
        menu.tk_popup(x, y)
        while not chosen["done"] and chosen["path"] is None:
            self.pump()
            time.sleep(0.005)
        menu.destroy()
        self.machine.events.buttons[RIGHTMOUSE] = 0
        return chosen["path"]

    def _build(self, pup, prefix, chosen):
        """A Tk menu for IRIS GL menu ``pup``: its title, items, separator
        lines (%l), submenus (%m) and greyed entries (setpup PUP_GREY)."""
        from ..menus import PUP_GREY
        m = self.machine.menus.menus.get(pup)
        if m is None:
            return None
        menu = self.tk.Menu(self.root, tearoff=0)
        if m.title:
            menu.add_command(label=m.title, state="disabled")
            menu.add_separator()
        for i, item in enumerate(m.items, start=1):
            path = prefix + (i,)
            state = "disabled" if item.mode & PUP_GREY else "normal"
            sub = self._build(item.submenu, path, chosen) if item.submenu is not None else None
            if sub is not None:
                menu.add_cascade(label=item.label, menu=sub, state=state)
            else:
                menu.add_command(label=item.label, state=state,
                                 command=lambda p=path: chosen.__setitem__("path", p))
            if item.line:
                menu.add_separator()
        return menu

    # -- input ----------------------------------------------------------
    def input(self, dev, val):
        """A device changed: its state always, the queue when it is queued."""
        ev = self.machine.events
        if dev in ev.queued:
            ev.enter(dev, val)
        elif dev in (MOUSEX, MOUSEY) or 256 <= dev < 512:
            ev.valuators[dev] = val
        else:
            ev.buttons[dev] = 1 if val else 0


class _View:
    """One IRIS GL window on screen: a toplevel holding its picture."""

    def __init__(self, display, win):
        tk = display.tk
        self.d, self.win = display, win
        self.top = tk.Toplevel(display.root)
        self.top.title(getattr(win, "title", None) or win.name or "IRIS GL")
        self.size = (win.width, win.height)
        x, y = win.origin
        self.top.geometry(f"{win.width}x{win.height}+{x}+"
                          f"{config.SCREEN_HEIGHT - y - win.height}")
        self.label = tk.Label(self.top, bd=0, highlightthickness=0, cursor="crosshair")
        self.label.pack(fill="both", expand=True)
        self.photo = None
        self.shown_frame = None
        t = self.top
        t.protocol("WM_DELETE_WINDOW", self.on_close)
        for b in (1, 2, 3):
            t.bind(f"<ButtonPress-{b}>", lambda e, b=b: self.on_button(e, b, 1))
            t.bind(f"<ButtonRelease-{b}>", lambda e, b=b: self.on_button(e, b, 0))
        t.bind("<Motion>", self.on_motion)
        t.bind("<KeyPress>", lambda e: self.on_key(e, 1))
        t.bind("<KeyRelease>", lambda e: self.on_key(e, 0))
        t.bind("<Configure>", self.on_configure)
        t.bind("<Expose>", self.on_expose)
        t.bind("<FocusIn>", lambda e: self.d.machine.events.post(INPUTCHANGE, self.win.gid))
        t.bind("<FocusOut>", lambda e: self.d.machine.events.post(INPUTCHANGE, 0))

    def show(self):
        """Put what the screen shows of the window into the toplevel."""
        m, win = self.d.machine, self.win
        if win.gid not in m.windows:
            return
        img = m.image(win)
        h, w = img.shape[:2]
        header = f"P6 {w} {h} 255 ".encode()
        data = header + img.tobytes()
        if self.photo is None or (self.photo.width(), self.photo.height()) != (w, h):
            self.photo = self.d.tk.PhotoImage(width=w, height=h, data=data, format="PPM")
            self.label.configure(image=self.photo)
        else:
            self.photo.configure(data=data, format="PPM")

    # -- events -----------------------------------------------------------
    def _screen(self, e):
        x0, y0 = self.win.origin
        return x0 + e.x, y0 + self.win.height - 1 - e.y

    def on_motion(self, e):
        sx, sy = self._screen(e)
        ev = self.d.machine.events
        if ev.valuators.get(MOUSEX) != sx:
            self.d.input(MOUSEX, sx)
        if ev.valuators.get(MOUSEY) != sy:
            self.d.input(MOUSEY, sy)

    def on_button(self, e, b, down):
        self.on_motion(e)
        self.d.input({1: LEFTMOUSE, 2: MIDDLEMOUSE, 3: RIGHTMOUSE}[b], down)

    def on_key(self, e, down):
        dev = _KEYS.get(e.keysym, _KEYS.get(e.keysym.lower()))
        if dev is not None:
            self.d.input(dev, down)
        ev = self.d.machine.events
        if down and e.char and len(e.char) == 1 and ord(e.char) < 128 and KEYBD in ev.queued:
            ev.enter(KEYBD, ord(e.char))

    def on_configure(self, e):
        if e.widget is not self.top:
            return
        size = (e.width, e.height)
        if size != self.size and e.width > 1 and e.height > 1:
            self.size = size
            resize = getattr(self.d.machine, "resize_window", None)
            if resize is not None:
                resize(self.win, e.width, e.height)
            self.d.machine.events.post(REDRAW, self.win.gid, coalesce=True)

    def on_expose(self, e):
        self.d.machine.events.post(REDRAW, self.win.gid, coalesce=True)

    def on_close(self):
        ev = self.d.machine.events
        asked = [d for d in (WINQUIT, WINSHUT) if d in ev.queued]
        if asked:
            for d in asked:
                ev.enter(d, self.win.gid)
        else:
            self.d.quit = True
