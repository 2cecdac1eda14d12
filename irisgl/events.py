"""Event queue and input devices (docs/semantics.md §13,
docs/windows-and-devices.md).

Device numbers are checked against the partition of qenter(3G): qdevice,
getbutton, getvaluator and tie take the devices SGI defines (buttons,
valuators, pseudo devices); qenter also takes the program's own devices
0x1000-0x7FFF.
"""
import errno


from vgx_emulator import events as E
from vgx_emulator.errors import fail

from ._current import fill, glcall, integer, machine, out_array

__all__ = ["qdevice", "unqdevice", "qread", "qtest", "qenter", "qreset", "getvaluator",
           "getbutton", "isqueued", "tie", "setvaluator", "getdev", "noise", "blkqread",
           "qgetfd", "qcontrol"]

_SGI = ("a device defined in device.h: buttons 1-255 and 3840-4095, "
        "valuators 256-511, pseudo devices 512-767")


def _device(call, dev):
    """An SGI-defined device (qdevice(3G), qenter(3G) partition)."""
    d = integer(call, dev, "device")
    if not E.is_sgi_device(d):
        fail(call, f"device {d} is not an SGI device", _SGI)
    return d


def _button(call, dev):
    d = integer(call, dev, "button")
    if not E.is_button(d):
        fail(call, f"device {d} is not a button", "buttons 1-255 and 3840-4095 (device.h)")
    return d


def _valuator(call, dev, null=False):
    d = integer(call, dev, "valuator")
    if null and d == 0:
        return 0
    if not E.is_valuator(d):
        fail(call, f"device {d} is not a valuator",
             "valuators 256-511 (device.h)" + (" or NULLDEV" if null else ""))
    return d


def _short(call, v, what):
    v = integer(call, v, what)
    if not -32768 <= v <= 32767:
        fail(call, f"{what} {v} does not fit a short", "-32768..32767")
    return v


@glcall(immediate=True)
def qdevice(dev):
    """qdevice(3G): queue events of this device."""
    machine.events.qdevice(_device("qdevice", dev))


@glcall(immediate=True)
def unqdevice(dev):
    """unqdevice(3G): stop queueing the device (entries already queued stay)."""
    machine.events.unqdevice(_device("unqdevice", dev))


@glcall(immediate=True)
def isqueued(dev):
    """isqueued(3G): TRUE if the device is queued."""
    return int(_device("isqueued", dev) in machine.events.queued)


@glcall(immediate=True)
def qread():
    """qread(3G): ``dev, val = qread()``; removes the first entry.  With the
    queue empty and no real window it ends the program (QueueExhausted, a
    SystemExit with status 0) instead of blocking forever."""
    machine.flush()
    return machine.events.read()


@glcall(immediate=True)
def blkqread(data, n=None):
    """blkqread(3G): read up to n/2 entries at once.  ``blkqread(n)`` returns
    the list of (dev, val) pairs; ``blkqread(data, n)`` with a writable
    numpy array (or a list) fills it with dev, val, dev, val ... and returns the count
    of 16-bit words read (twice the entries).  Blocks like qread."""
    if n is None:
        data, n = None, data
    n = integer("blkqread", n, "n")
    if n < 0:
        fail("blkqread", f"n = {n}", "n >= 0 elements")
    out_array("blkqread", data, n, "data", "pass at least n shorts, or blkqread(n)")
    machine.flush()
    pairs = machine.events.read_block(n)
    if data is None:
        return pairs
    fill(data, [x for pair in pairs for x in pair])
    return 2 * len(pairs)


@glcall(immediate=True)
def qtest():
    """qtest(3G): the device of the first entry, or 0; the queue is unchanged."""
    return machine.events.test()


@glcall(immediate=True)
def qenter(dev, val):
    """qenter(3G): append exactly this entry; the device's state follows it.
    A tied button brings no valuators and noise does not filter (tie(3G)
    and noise(3G) act when a device changes state, not on qenter): a
    program that enters a tied button enters its valuators itself.
    Devices 1-0x7FFF.  A C character constant ported as a one-character
    string (``qenter(KEYBD, 't')``) is its character code, as in C; qread
    gives that code back."""
    if isinstance(val, str) and len(val) == 1:
        val = ord(val)
    v = integer("qenter", val, "value")
    if not -32768 <= v <= 65535:
        fail("qenter", f"value {v}", "a short")
    d = integer("qenter", dev, "device")
    if not (E.is_sgi_device(d) or d in E.USER_RANGE):
        fail("qenter", f"device {d} is outside the device space",
             "SGI devices 1-767 and 3840-4095, your own 4096-32767 (qenter(3G))")
    machine.events.enter(d, v)


@glcall(immediate=True)
def qreset():
    """qreset(3G): empty the queue."""
    machine.events.reset()


@glcall(immediate=True)
def qgetfd():
    """qgetfd(3G): the read file descriptor of the queue, for select(2): a
    pipe that is readable while entries are queued."""
    return machine.events.fd()


@glcall(immediate=True)
def qcontrol(cmd, icnt, idata, ocnt, odata=None):
    """qcontrol(3G): queue administration for window managers and input
    daemons.  There is neither headless, so every command is refused the
    man page's way: ``-EINVAL`` (C's negative errno), nothing changed."""
    integer("qcontrol", cmd, "cmd")
    for c, a, what in ((icnt, idata, "idata"), (ocnt, odata, "odata")):
        c = integer("qcontrol", c, f"count of {what}")
        if c and not hasattr(a, "__len__"):
            fail("qcontrol", f"{what} is not an array", "pass an array of shorts or NULL (0)")
        if c < 0 or (c and len(a) < c):
            fail("qcontrol", f"{what} holds fewer than {c} elements",
                 "counts must not exceed the arrays")
    return -errno.EINVAL


@glcall(immediate=True)
def getvaluator(dev):
    """getvaluator(3G): the valuator's current value (0 for a valuator that
    never reported); only valuators 256-511."""
    d = _valuator("getvaluator", dev)
    machine.events.polled()
    return machine.events.valuator(d)


@glcall(immediate=True)
def getbutton(dev):
    """getbutton(3G): the button's state, 0 or 1; only buttons."""
    b = _button("getbutton", dev)
    machine.events.polled()
    return machine.events.button(b)


@glcall(immediate=True)
def getdev(n, devs, vals=None):
    """getdev(3G): the values of n devices (buttons and valuators) at once.
    ``vals = getdev(n, devs)`` returns a list; given a writable ``vals``
    array (or list) it is filled in place."""
    n = integer("getdev", n, "n")
    if n < 0 or n > 128:
        fail("getdev", f"n = {n}", "0..128 devices")
    try:
        if len(devs) < n:
            fail("getdev", f"devs has {len(devs)} elements", f"it takes n = {n}")
    except TypeError:
        fail("getdev", "devs is not an array", "pass n devices")
    ds = [integer("getdev", devs[i], "device") for i in range(n)]
    for d in ds:
        if not (E.is_button(d) or E.is_valuator(d)):
            fail("getdev", f"device {d} is neither a button nor a valuator",
                 "buttons 1-255, 3840-4095 and valuators 256-511")
    out_array("getdev", vals, n, "vals", "pass n shorts, or nothing")
    ev = machine.events
    ev.polled()
    out = [ev.button(d) if E.is_button(d) else ev.valuator(d) for d in ds]
    if vals is None:
        return out
    fill(vals, out)
    return None


@glcall(immediate=True)
def setvaluator(dev, init, vmin, vmax):
    """setvaluator(3G): a valuator's value and range; what it reports stays in the range.
    The range is "the minimum and maximum values the device can assume";
    for MOUSEX/MOUSEY the value is the cursor position.  Nothing is queued.
    From then on the values the device reports are held in [vmin, vmax] (a
    mouse dragged out of the range reads its edge); [S] an init outside the
    range is held there too, and vmin > vmax is an error (the man page
    lists no error)."""
    d = _valuator("setvaluator", dev)
    i, lo, hi = (_short("setvaluator", v, w)
                 for v, w in ((init, "init"), (vmin, "vmin"), (vmax, "vmax")))
    if lo > hi:
        fail("setvaluator", f"vmin {lo} > vmax {hi}", "vmin <= vmax")
    machine.events.set_valuator(d, min(max(i, lo), hi), lo, hi)


@glcall(immediate=True)
def noise(dev, delta):
    """noise(3G): a valuator's report is queued only when it changed by at
    least delta since its last queued entry (delta 1: every change); what
    a program qenters is not filtered.  For a timer (TIMER0..TIMER3) delta
    is its period in ticks of getgdesc(GD_TIMERHZ) (default 10000)."""
    d = integer("noise", dev, "valuator")
    if not E.is_timer(d):
        d = _valuator("noise", dev)
    n = _short("noise", delta, "delta")
    if n < 1:
        fail("noise", f"delta {n}", "delta >= 1")
    machine.events.set_noise(d, n)


@glcall(immediate=True)
def tie(button, val1, val2):
    """tie(3G): while the button is queued, its entry is followed by the
    current values of val1 then val2 (NULLDEV = none); both NULLDEV unties.
    When the button changes state (the window system), not on a qenter."""
    b = _button("tie", button)
    v1 = _valuator("tie", val1, null=True)
    v2 = _valuator("tie", val2, null=True)
    if v1 == 0 and v2 == 0:
        machine.events.ties.pop(b, None)
    else:
        machine.events.ties[b] = (v1, v2)
