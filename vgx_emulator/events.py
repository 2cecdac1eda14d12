"""The device queue behind qdevice/qread/qtest/qenter, and the input devices
it reports (docs/semantics.md §13, docs/windows-and-devices.md).

The queue holds 101 entries; a full queue drops the event and queues QFULL.
With no real window to wait on, a ``qread`` on an empty queue cannot block
forever: it raises :class:`QueueExhausted`, a ``SystemExit`` with code 0, so
a ported program ends cleanly (docs/porting.md §5) and the runner, which
catches it, saves what the program drew.

Device numbers follow the partition of qenter(3G): SGI buttons 0x0001-0x00FF
and 0x0F00-0x0FFF, valuators 0x0100-0x01FF, pseudo devices 0x0200-0x02FF;
0x1000-0x7FFF are the program's own devices (qenter only); 0x8000 and up
cannot be used.  ``qenter`` enters exactly its entry; a device that changes
state (device_input, the window system) is held in its setvaluator range,
filtered by noise, and a button tied to valuators (tie(3G)) queues its
entry and then the valuators' current values as one group.
"""
import os
import time
from collections import deque

from . import config

QFULL = 535
REDRAW = 528
INPUTCHANGE = 534
MOUSEX, MOUSEY = 266, 267
BUTTON_RANGE = range(1, 256)
EXTRA_BUTTON_RANGE = range(0xF00, 0x1000)
VALUATOR_RANGE = range(256, 512)
PSEUDO_RANGE = range(512, 768)
USER_RANGE = range(0x1000, 0x8000)
USER_BUTTON_RANGE = range(0x1000, 0x3000)
USER_VALUATOR_RANGE = range(0x3000, 0x4000)
TIMER_RANGE = range(515, 519)      # device.h TIMER0..TIMER3
TIMER_NOISE = 10000                # noise(3G): a timer's default noise

#: the valuators' power-on ranges: the mouse spans the screen (setvaluator(3G))
_SCREEN = (config.SCREEN_WIDTH - 1, config.SCREEN_HEIGHT - 1)


def is_button(dev):
    return dev in BUTTON_RANGE or dev in EXTRA_BUTTON_RANGE


def is_valuator(dev):
    return dev in VALUATOR_RANGE


def is_timer(dev):
    return dev in TIMER_RANGE


def is_sgi_device(dev):
    return is_button(dev) or is_valuator(dev) or dev in PSEUDO_RANGE


class QueueExhausted(SystemExit):
    """qread() found the queue empty while no real window can produce events."""

    def __init__(self):
        super().__init__(0)


class EventQueue:
    def __init__(self):
        self._fd = None
        self.wait_hook = None          # called when qread would block
        self.poll_hook = None          # called when qtest finds the queue empty
        self.state_hook = None         # called when the program reads a device's state
        self.reset_all()

    def reset_all(self):
        """The queue and the devices of a new graphics session (gexit).  The
        hooks whoever runs the program installed (the runner, a real window)
        stay: a program that calls gexit and then ginit again (GL2-era tools
        did) still has its input handled."""
        self.queued = set()
        self.entries = deque()
        self.buttons = {}
        self.valuators = {MOUSEX: 0, MOUSEY: 0}
        # setvaluator(3G): dev -> (min, max); the mouse spans the screen
        self.ranges = {MOUSEX: (0, _SCREEN[0]), MOUSEY: (0, _SCREEN[1])}
        self.ties = {}                 # tie(3G): button -> (v1, v2), NULLDEV = 0
        self.noise = {}                # noise(3G): valuator -> delta
        self.last_queued = {}          # valuator -> value of its last queued entry
        self.timers = {}               # queued TIMERn -> the queue clock's time of its next tick
        self.skew = 0.0                # seconds a headless qread skipped waiting for a tick
        self._close_fd()

    # -- qdevice ------------------------------------------------------------
    def qdevice(self, dev):
        self.queued.add(dev)
        if is_timer(dev) and dev not in self.timers:
            self.timers[dev] = self.now() + self.period(dev)

    def unqdevice(self, dev):
        self.queued.discard(dev)
        self.timers.pop(dev, None)

    # -- timers -------------------------------------------------------------
    def now(self):
        """The queue's clock: real time, plus what headless waits skipped."""
        return time.monotonic() + self.skew

    def period(self, dev):
        """noise(3G): a timer makes an entry every ``noise`` ticks of
        GD_TIMERHZ (default noise 10000)."""
        from .gdesc import TABLE
        return self.noise.get(dev, TIMER_NOISE) / TABLE["TIMERHZ"][0]

    def set_noise(self, dev, delta):
        """noise(3G) for a valuator or a timer (a timer starts its new
        period now)."""
        self.noise[dev] = delta
        if dev in self.timers:
            self.timers[dev] = self.now() + self.period(dev)

    def tick(self):
        """Queue an entry (TIMERn, 0) for each period of a queued timer that
        has ended by the queue's clock ([S] the value is 0); periods missed
        while the program was busy are queued too, as many as the queue
        holds."""
        if not self.timers:
            return
        now = self.now()
        for dev, due in sorted(self.timers.items(), key=lambda kv: kv[1]):
            if due > now:
                continue
            period = self.period(dev)
            n = int((now - due) // period) + 1
            for _ in range(min(n, config.QUEUE_LENGTH + 1)):
                self._append([(dev, 0)])
            self.timers[dev] = due + n * period

    def _skip_to_tick(self):
        """A headless qread with nothing queued but a timer: the wait until
        its next tick passes at once (the queue's clock jumps), so a program
        paced by a timer runs without sleeping and the same way each run."""
        if self.timers:
            self.skew += max(0.0, min(self.timers.values()) - self.now())
            self.tick()

    # -- entering events ----------------------------------------------------
    def enter(self, dev, val):
        """qenter(3G): append exactly this entry ("takes a device number and
        a value and enters them"); the device's state follows it [S].  No
        tied valuators and no noise filter: those belong to a device that
        changes state (tie(3G), noise(3G)), device_input."""
        self._follow(dev, val)
        self._append([(dev, val)])

    def device_input(self, dev, val):
        """A device changed (the window system: display/tkwindow.py,
        notebook.py, the runner's menu clicks): its state always, an entry
        when it is queued.  A valuator reports a value within its range
        (setvaluator(3G); the mouse: the screen), so a drag past the range
        reads its edge, and is queued only when it moved at least its noise
        threshold since its last queued entry (noise(3G)).  A queued button
        tied to valuators brings their current values right after it, as
        one group (tie(3G))."""
        if dev in self.ranges:
            lo, hi = self.ranges[dev]
            val = min(max(val, lo), hi)
        self._follow(dev, val)
        if dev not in self.queued:
            return
        if is_valuator(dev):
            delta = self.noise.get(dev, 1)
            last = self.last_queued.get(dev)
            if delta > 1 and last is not None and abs(val - last) < delta:
                return
            self.last_queued[dev] = val
        group = [(dev, val)]
        for v in self.ties.get(dev, ()):
            if v:
                group.append((v, self.valuator(v)))
        self._append(group)

    def _follow(self, dev, val):
        if is_button(dev):
            self.buttons[dev] = 1 if val else 0
        elif is_valuator(dev):
            self.valuators[dev] = val

    def _append(self, group):
        """Queue a group of entries whole, or (no room) drop it and queue QFULL."""
        was_empty = not self.entries
        if len(self.entries) + len(group) > config.QUEUE_LENGTH:
            if self.entries and self.entries[-1][0] != QFULL:
                self.entries[-1] = (QFULL, 0)
            return
        self.entries.extend(group)
        if was_empty:
            self._signal()

    def post(self, dev, val, coalesce=False):
        """A system event (REDRAW, INPUTCHANGE): queued only if the device is
        queued; a pending identical REDRAW is not repeated (coalescing)."""
        if dev not in self.queued:
            return
        if coalesce and (dev, val) in self.entries:
            return
        self.enter(dev, val)

    # -- reading ------------------------------------------------------------
    def _wait(self):
        self.tick()
        if not self.entries and self.wait_hook is not None:
            self.wait_hook()           # a real window waits in real time (its loop ticks)
        if not self.entries:
            self._skip_to_tick()
        if not self.entries:
            raise QueueExhausted()

    def read(self):
        self._wait()
        e = self.entries.popleft()
        if not self.entries:
            self._drain()
        return e

    def read_block(self, n):
        """blkqread(3G): up to n // 2 entries (blocks like qread while empty)."""
        self._wait()
        out = []
        while self.entries and len(out) < n // 2:
            out.append(self.entries.popleft())
        if not self.entries:
            self._drain()
        return out

    def test(self):
        self.tick()
        if not self.entries and self.poll_hook is not None:
            self.poll_hook()           # the runner ends a loop that only polls
        return self.entries[0][0] if self.entries else 0

    def reset(self):
        self.entries.clear()
        self._drain()

    def polled(self):
        """The program read a device's state (getbutton, getvaluator,
        getdev): a real window takes its input now, the runner counts the
        reads of a loop that waits on a device (state_hook)."""
        if self.state_hook is not None:
            self.state_hook()

    def valuator(self, dev):
        return int(self.valuators.get(dev, 0))

    def button(self, dev):
        return int(self.buttons.get(dev, 0))

    def set_valuator(self, dev, init, vmin, vmax):
        """setvaluator(3G): the device's value and range (no entry queued)."""
        self.ranges[dev] = (vmin, vmax)
        self.valuators[dev] = init

    # -- qgetfd: a pipe readable while entries are queued -------------------
    def fd(self):
        """The read end of a pipe that holds one byte while the queue is not
        empty, so select(2) on it wakes when events arrive (qgetfd(3G))."""
        if self._fd is None:
            r, w = os.pipe()
            os.set_blocking(r, False)
            self._fd = (r, w)
            if self.entries:
                self._signal()
        return self._fd[0]

    def _signal(self):
        if self._fd is not None:
            os.write(self._fd[1], b"\1")

    def _drain(self):
        if self._fd is not None:
            try:
                while os.read(self._fd[0], 64):
                    pass
            except BlockingIOError:
                pass

    def __del__(self):
        self._close_fd()

    def _close_fd(self):
        if self._fd is not None:
            for f in self._fd:
                try:
                    os.close(f)
                except OSError:
                    pass
            self._fd = None
