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
C16X1, C16X2, C32X1, C32X2, CCROSS = 0, 1, 2, 3, 4          # curstype(3G)
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


#: Control+key switches what a window shows (the key is not queued for the
#: program): the screen, or one bank in false colour (vgx_emulator/planes.py)
VIEW_KEYS = {"1": "screen", "2": "z", "3": "stencil", "4": "accum", "5": "overlay",
             "6": "back"}
#: Control+P pauses after the next frame, which is traced pass by pass
#: (vgx_emulator/trace.py); Control+N / Control+B step through its passes,
#: Control+P again resumes the program
PAUSE, NEXT, BACK = "p", "n", "b"


class NoDisplay(RuntimeError):
    """No display to open a real window on."""


class TkDisplay:
    """The real windows of one machine.  It is the machine's frame hook
    (``frame``), its queue's wait hook (``wait``) and its menus' chooser
    (``popup``); it opens and closes real windows as the program's windows
    come and go (``sync``)."""

    def __init__(self, machine, fps=30.0, screen=None):
        try:
            import tkinter
        except ImportError as e:            # a Python built without Tk
            raise NoDisplay(f"tkinter is not available ({e})") from None
        try:
            self.root = tkinter.Tk(screenName=screen)
        except tkinter.TclError as e:
            raise NoDisplay(str(e)) from None
        self.tk = tkinter
        self.root.withdraw()
        self.machine = machine
        self.period = 1.0 / fps if fps and fps > 0 else 0.0
        self.views = {}                     # gid -> _View
        self.last_shown = 0.0
        self.quit = False
        self.cursors = {}                   # defcursor glyph -> Tk cursor spec
        self.view = "screen"                # what the windows show (VIEW_KEYS)
        self.trace = None                   # the Trace of the frame being paused on
        self.pause_asked = self.paused = self.redraw_step = False
        self.steps, self.step_i = None, 0
        self.showing = False
        self.last_pump = 0.0

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
                    self.views.pop(gid)
                    v.top.destroy()
                self.views[gid] = _View(self, win)

    def frame(self, m, win):
        """A frame point (the machine's frame hook): show the window, then
        keep to the frame rate.  With a pause asked for, the next frame is
        traced and the program then waits while its passes are looked at."""
        if self.trace is not None and not self.trace.recording:
            self.trace.uninstall()
            steps, self.trace = self.trace.steps, None
            if steps:
                self.inspect(steps)
        if self.pause_asked:
            from ..trace import Trace
            self.pause_asked = False
            self.trace = Trace(frame=1, keep=True).install(m)
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

    def inspect(self, steps):
        """The paused frame: show pass ``i`` (the last one first) in every
        window of the trace until Control+P resumes the program."""
        self.steps, self.step_i, self.paused = steps, len(steps) - 1, True
        try:
            while self.paused:
                for v in self.views.values():
                    v.show()
                while self.paused and not self.redraw_step:
                    self.pump()
                    time.sleep(0.01)
                self.redraw_step = False
        finally:
            self.steps = None

    def command(self, key):
        """A Control key the display keeps for itself (VIEW_KEYS, PAUSE ...)."""
        if key in VIEW_KEYS:
            self.view = VIEW_KEYS[key]
        elif key == PAUSE:
            if self.paused:
                self.paused = False
            else:
                self.pause_asked = True
        elif key in (NEXT, BACK) and self.steps:
            d = 1 if key == NEXT else -1
            self.step_i = min(max(self.step_i + d, 0), len(self.steps) - 1)
        else:
            return False
        self.redraw_step = True
        if not self.paused:
            for v in self.views.values():
                v.show()
        return True

    def drawn(self, win):
        """A batch was drawn (the machine's display hook): a single-buffered
        window shows its drawing as it happens, at most ``fps`` times a
        second (30 when unpaced), without waiting for a frame point."""
        if win.st.double or self.showing:
            return
        now = time.perf_counter()
        if now - self.last_shown >= (self.period or 1.0 / 30.0):
            self.last_shown = now
            self.showing = True             # show() flushes: no second look from there
            try:
                self.sync()
                v = self.views.get(win.gid)
                if v is not None:
                    v.show()
            finally:
                self.showing = False
            self.pump()

    def poll(self):
        """qtest found the queue empty (the queue's poll hook): a program
        that polls instead of waiting still sees its input and its windows."""
        now = time.perf_counter()
        if now - self.last_pump >= 0.005:
            self.last_pump = now
            if now - self.last_shown >= (self.period or 1.0 / 30.0):
                self.last_shown = now
                self.sync()
                for v in self.views.values():
                    v.show()
            self.pump()

    def wait(self):
        """qread on an empty queue: show every window, then wait for input."""
        self.sync()
        for v in self.views.values():
            v.show()
        ev = self.machine.events
        while not ev.entries:
            ev.tick()                  # TIMERn entries in real time
            self.pump()
            if not self.views:
                raise SystemExit(0)
            time.sleep(0.005)

    def bitmap_cursor(self, index, typ, words, origin):
        """A Tk cursor for a defcursor(3G) glyph: 16x16 (16 shorts) or 32x32
        (32 longs), rows bottom to top, the leftmost pixel in the high bit;
        written once as an X bitmap (XBM: rows top to bottom, leftmost pixel
        in the low bit)."""
        import tempfile
        key = (index, typ, tuple(int(w) for w in words), origin)
        if key in self.cursors:
            return self.cursors[key]
        n = 32 if typ in (C32X1, C32X2) else 16
        rows = [int(w) & ((1 << n) - 1) for w in list(words)[:n]] + [0] * n
        rows = rows[:n][::-1]
        data = []
        for r in rows:
            bits = int(format(r, f"0{n}b")[::-1], 2)          # leftmost pixel -> bit 0
            data += [(bits >> (8 * k)) & 0xFF for k in range(n // 8)]
        hx, hy = origin[0], n - 1 - origin[1]
        text = (f"#define c_width {n}\n#define c_height {n}\n#define c_x_hot {hx}\n"
                f"#define c_y_hot {hy}\nstatic unsigned char c_bits[] = {{"
                + ",".join(f"0x{b:02x}" for b in data) + "};\n")
        f = tempfile.NamedTemporaryFile("w", suffix=".xbm", delete=False)
        f.write(text)
        f.close()
        self.cursors[key] = f"@{f.name} black"
        return self.cursors[key]

    def pump(self):
        """Let Tk deliver what the window system has for the program."""
        try:
            self.root.update()
        except self.tk.TclError:
            raise SystemExit(0) from None
        if self.quit:
            raise SystemExit(0)

    def close_all(self):
        views, self.views = list(self.views.values()), {}
        for v in views:
            v.top.destroy()
        try:
            self.root.destroy()
        except self.tk.TclError:
            pass

    # -- pop-up menus (dopup(3G)) ---------------------------------------------
    def popup(self, pup):
        """Pop menu ``pup`` up at the pointer; the path of item numbers the
        user chose through submenus, or None when nothing was chosen."""
        chosen = {"path": None, "done": False}
        menu = self._build(pup, (), chosen, self.root)
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

    def _build(self, pup, prefix, chosen, master):
        """A Tk menu for IRIS GL menu ``pup``: its title, items, separator
        lines (%l), submenus (%m) and greyed entries (setpup PUP_GREY)."""
        from ..menus import PUP_GREY
        m = self.machine.menus.menus.get(pup)
        if m is None:
            return None
        menu = self.tk.Menu(master, tearoff=0)
        if m.title:
            menu.add_command(label=m.title, state="disabled")
            menu.add_separator()
        for i, item in enumerate(m.items, start=1):
            path = prefix + (i,)
            state = "disabled" if item.mode & PUP_GREY else "normal"
            sub = (self._build(item.submenu, path, chosen, menu)
                   if item.submenu is not None else None)
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
        self.machine.events.device_input(dev, val)


class _View:
    """One IRIS GL window on screen: a toplevel holding its picture."""

    def __init__(self, display, win):
        tk = display.tk
        self.d, self.win = display, win
        self.top = tk.Toplevel(display.root)
        self.top.title(getattr(win, "wm", {}).get("title") or win.name or "IRIS GL")
        self.placed = None
        self.follow()
        self.label = tk.Label(self.top, bd=0, highlightthickness=0, cursor="crosshair")
        self.label.pack(fill="both", expand=True)
        self.photo = None
        self.shown_cursor = None
        self.shown_title = None
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
        t.bind("<Destroy>", self.on_destroy)
        t.bind("<FocusIn>", lambda e: self.d.machine.events.post(INPUTCHANGE, self.win.gid))
        t.bind("<FocusOut>", lambda e: self.d.machine.events.post(INPUTCHANGE, 0))

    def show(self):
        """Put what the screen shows of the window into the toplevel."""
        m, win = self.d.machine, self.win
        if win.gid not in m.windows:
            return
        self.follow()
        self.cursor()
        img = self.picture()
        h, w = img.shape[:2]
        header = f"P6 {w} {h} 255 ".encode()
        data = header + img.tobytes()
        if self.photo is None or (self.photo.width(), self.photo.height()) != (w, h):
            self.photo = self.d.tk.PhotoImage(width=w, height=h, data=data, format="PPM")
            self.label.configure(image=self.photo)
        else:
            self.photo.configure(data=data, format="PPM")

    def picture(self):
        """What the window shows: the screen, or the bank chosen with the
        view keys as its false-colour picture (the legend in the title)."""
        from ..planes import banks, picture, stencil_key
        m, win = self.d.machine, self.win
        name = self.d.view
        title = getattr(win, "wm", {}).get("title") or win.name or "IRIS GL"
        if self.d.steps:
            return self.step_picture(title, name)
        if name != "screen":
            m._flush(win)
            banks = banks(win)
            if name in banks:
                pic = picture(name, banks[name], win, stencil_key(win), m)
                legend = "; ".join(t for _, t in pic.legend[:4])
                self.set_title(f"{title} [{pic.title}: {legend}]")
                return pic.image
            self.set_title(f"{title} [no {name} bank]")
        else:
            self.set_title(title)
        return m.image(win)

    def step_picture(self, title, name):
        """Pass ``step_i`` of the paused frame: the chosen bank as it was
        after that pass (the screen view shows the bank drawn into)."""
        from ..planes import banks, picture, stencil_key
        d, win = self.d, self.win
        step = d.steps[d.step_i]
        head = f"{title} [pass {d.step_i + 1}/{len(d.steps)}: {step.label}"
        if step.gid != win.gid or not step.arrays:
            self.set_title(head + "]")
            return d.machine.image(win)
        if name == "screen":
            name = "back" if win.st.double and "back" in step.arrays else "front"
        if name not in step.arrays:
            self.set_title(head + f"; no {name} bank]")
            return d.machine.image(win)
        pic = picture(name, step.arrays[name], win, step.key, d.machine)
        self.set_title(head + f"; {pic.title}: " +
                       "; ".join(t for _, t in pic.legend[:3]) + "]")
        return pic.image

    def set_title(self, text):
        if text != self.shown_title:
            self.shown_title = text
            self.top.title(text)

    def cursor(self):
        """The cursor calls (curson, cursoff, curstype, defcursor, setcursor):
        hidden, the cross-hair, or the defined glyph as an X bitmap cursor."""
        c = self.d.machine.system.get("cursor")
        name = "left_ptr"
        if c is not None:
            if not c.get("visible", True):
                name = "none"
            else:
                typ, words = c["glyphs"].get(c["index"], (0, None))
                if typ == CCROSS:
                    name = "crosshair"
                elif words is not None:
                    name = self.d.bitmap_cursor(c["index"], typ, words,
                                                c["origins"].get(c["index"], (0, 0)))
        if name != self.shown_cursor:
            self.shown_cursor = name
            self.label.configure(cursor=name)

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
        if e.state & 0x4 and (e.keysym in VIEW_KEYS or e.keysym.lower() in (PAUSE, NEXT, BACK)):
            if down:
                self.d.command(e.keysym.lower())    # the display's own keys, not queued
            return
        dev = _KEYS.get(e.keysym, _KEYS.get(e.keysym.lower()))
        if dev is not None:
            self.d.input(dev, down)
        ev = self.d.machine.events
        if down and e.char and len(e.char) == 1 and ord(e.char) < 128 and KEYBD in ev.queued:
            ev.enter(KEYBD, ord(e.char))

    def on_configure(self, e):
        """Moved or resized by the user: the window's origin (getorigin) and,
        for a new size, its banks follow, and REDRAW is queued."""
        if e.widget is not self.top or e.width <= 1 or e.height <= 1:
            return
        win = self.win
        x, y = e.x, config.SCREEN_HEIGHT - e.y - e.height
        if (x, y, e.width, e.height) == self.placed:
            return
        self.placed = (x, y, e.width, e.height)
        resized = (e.width, e.height) != (win.width, win.height)
        self.d.machine.state_change(win)
        win.resize(x, y, e.width, e.height)
        if resized:
            self.d.machine.events.post(REDRAW, win.gid, coalesce=True)

    def follow(self):
        """The program moved or reshaped its window (winposition, winmove,
        fullscrn): the real window follows."""
        win = self.win
        x, y = win.origin
        want = (x, y, win.width, win.height)
        if want != self.placed:
            self.placed = want
            self.top.geometry(f"{win.width}x{win.height}+{x}+"
                              f"{config.SCREEN_HEIGHT - y - win.height}")

    def on_expose(self, e):
        self.d.machine.events.post(REDRAW, self.win.gid, coalesce=True)

    def on_destroy(self, e):
        """The window was destroyed from outside (not by winclose): as a close."""
        if e.widget is self.top and self.win.gid in self.d.views:
            self.d.views.pop(self.win.gid, None)
            self.d.quit = True

    def on_close(self):
        ev = self.d.machine.events
        asked = [d for d in (WINQUIT, WINSHUT) if d in ev.queued]
        if asked:
            for d in asked:
                ev.enter(d, self.win.gid)
        else:
            self.d.quit = True
