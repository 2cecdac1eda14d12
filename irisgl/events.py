"""Event queue calls (reference section 13)."""
from vgx_emulator.errors import fail

from ._current import glcall, integer, machine

__all__ = ["qdevice", "unqdevice", "qread", "qtest", "qenter", "qreset", "getvaluator",
           "getbutton", "isqueued", "tie"]


def _device(call, dev):
    d = integer(call, dev, "device")
    if not 0 <= d <= 0xFFFF:
        fail(call, f"device {d}", "a Device from device.h (0..65535)")
    return d


@glcall
def qdevice(dev):
    """qdevice(3G): queue events of this device."""
    machine.events.qdevice(_device("qdevice", dev))


@glcall
def unqdevice(dev):
    machine.events.unqdevice(_device("unqdevice", dev))


@glcall
def isqueued(dev):
    return int(_device("isqueued", dev) in machine.events.queued)


@glcall
def qread():
    """qread(3G): ``dev, val = qread()``; removes the first entry.  With the
    queue empty and no real window it ends the program (QueueExhausted, a
    SystemExit with status 0) instead of blocking forever."""
    machine.flush()
    return machine.events.read()


@glcall
def qtest():
    """qtest(3G): the device of the first entry, or 0; the queue is unchanged."""
    return machine.events.test()


@glcall
def qenter(dev, val):
    """qenter(3G): append an entry, as the window system would."""
    v = integer("qenter", val, "value")
    if not -32768 <= v <= 65535:
        fail("qenter", f"value {v}", "a short")
    machine.events.enter(_device("qenter", dev), v)


@glcall
def qreset():
    machine.events.reset()


@glcall
def getvaluator(dev):
    return machine.events.valuator(_device("getvaluator", dev))


@glcall
def getbutton(dev):
    return machine.events.button(_device("getbutton", dev))


@glcall
def tie(button, val1, val2):
    """tie(3G): accepted; headless events come only from qenter."""
    for d in (button, val1, val2):
        _device("tie", d)
