"""The device queue behind qdevice/qread/qtest/qenter (reference section 13).

The queue holds 101 entries; a full queue drops the event and queues QFULL.
With no real window to wait on, a ``qread`` on an empty queue cannot block
forever: it raises :class:`QueueExhausted`, a ``SystemExit`` with code 0, so
a ported program ends cleanly (porting conventions 4) and the runner, which
catches it, saves what the program drew.
"""
from collections import deque

from . import config

QFULL = 535
REDRAW = 528
INPUTCHANGE = 534
MOUSEX, MOUSEY = 266, 267
BUTTON_RANGE = range(1, 256)
VALUATOR_RANGE = range(256, 512)


class QueueExhausted(SystemExit):
    """qread() found the queue empty while no real window can produce events."""

    def __init__(self):
        super().__init__(0)


class EventQueue:
    def __init__(self):
        self.reset_all()

    def reset_all(self):
        self.queued = set()
        self.entries = deque()
        self.buttons = {}
        self.valuators = {MOUSEX: 0, MOUSEY: 0}
        self.wait_hook = None          # called when qread would block

    def qdevice(self, dev):
        self.queued.add(dev)

    def unqdevice(self, dev):
        self.queued.discard(dev)

    def enter(self, dev, val):
        """Append an entry; the device state follows what is queued."""
        if dev in BUTTON_RANGE:
            self.buttons[dev] = 1 if val else 0
        elif dev in VALUATOR_RANGE:
            self.valuators[dev] = val
        if len(self.entries) >= config.QUEUE_LENGTH:
            if not self.entries or self.entries[-1][0] != QFULL:
                self.entries[-1] = (QFULL, 0)
            return
        self.entries.append((dev, val))

    def post(self, dev, val, coalesce=False):
        """A system event (REDRAW, INPUTCHANGE): queued only if the device is
        queued; a pending identical REDRAW is not repeated (coalescing)."""
        if dev not in self.queued:
            return
        if coalesce and (dev, val) in self.entries:
            return
        self.enter(dev, val)

    def read(self):
        if not self.entries and self.wait_hook is not None:
            self.wait_hook()
        if not self.entries:
            raise QueueExhausted()
        return self.entries.popleft()

    def test(self):
        return self.entries[0][0] if self.entries else 0

    def reset(self):
        self.entries.clear()

    def valuator(self, dev):
        return int(self.valuators.get(dev, 0))

    def button(self, dev):
        return int(self.buttons.get(dev, 0))
