"""Cursors, valuators, tie, blkqread, qgetfd, device ranges (defcursor(3G),
setvaluator(3G), tie(3G), blkqread(3G), qgetfd(3G), qenter(3G) partition)."""
import os
import select

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403
from irisgl import GLError
from irisgl._current import machine


def queue():
    return list(machine.events.entries)


# -- cursors -----------------------------------------------------------------------
def test_getcursor_defaults():
    # getcursor(3G): glyph 0, colour 1, first plane, shown
    assert getcursor() == (0, 1, 1, 1)


def test_defcursor_setcursor_getcursor():
    defcursor(3, [0xFFFF] * 16)
    setcursor(3, 5, 0xF)
    assert getcursor() == (3, 5, 0xF, 1)
    cursoff()
    assert getcursor()[3] == 0
    curson()
    assert getcursor()[3] == 1


def test_cursor_zero_cannot_be_redefined():
    with pytest.raises(GLError) as e:
        defcursor(0, [0] * 16)
    assert str(e.value).startswith("defcursor")


def test_glyph_size_follows_curstype():
    curstype(C32X1)
    with pytest.raises(GLError):
        defcursor(2, [0] * 16)              # a 32x32 glyph is 64 words
    defcursor(2, [0] * 64)
    curstype(C16X2)
    with pytest.raises(GLError):
        defcursor(4, [0] * 16)              # two layers: 32 words
    defcursor(4, [1] * 40)                  # longer: the first 32 are read
    with pytest.raises(GLError):
        curstype(9)


def test_setcursor_undefined_fails_and_keeps_cursor():
    defcursor(1, [0] * 16)
    setcursor(1, 2, 3)
    with pytest.raises(GLError) as e:
        setcursor(7, 0, 0)
    assert str(e.value).startswith("setcursor")
    assert getcursor() == (1, 2, 3, 1)


def test_curorigin_inside_glyph():
    defcursor(1, [0] * 16)
    curorigin(1, 8, 8)
    with pytest.raises(GLError):
        curorigin(1, 16, 0)                 # a 16x16 glyph
    with pytest.raises(GLError):
        curorigin(5, 0, 0)                  # undefined


def test_rgbcursor_and_grgbcursor():
    defcursor(2, [0] * 16)
    RGBcursor(2, 10, 20, 300, 1, 2, 3)      # 300 clamps to 255
    assert gRGBcursor() == (2, 10, 20, 255, 1, 2, 3, 1)


def test_attachcursor_takes_valuators():
    attachcursor(DIAL0, DIAL1)
    with pytest.raises(GLError):
        attachcursor(LEFTMOUSE, MOUSEY)


# -- valuators and buttons ----------------------------------------------------------
def test_setvaluator_sets_value_without_queueing(open_window):
    open_window()
    qreset()
    qdevice(MOUSEX)
    setvaluator(MOUSEX, 640, 0, 1279)
    assert getvaluator(MOUSEX) == 640
    assert qtest() == 0
    setvaluator(MOUSEX, 2000, 0, 1279)      # init outside the range: held at its edge
    assert getvaluator(MOUSEX) == 1279
    setvaluator(MOUSEX, -20, 0, 1279)
    assert getvaluator(MOUSEX) == 0
    with pytest.raises(GLError, match="vmin 10 > vmax 5"):
        setvaluator(MOUSEX, 7, 10, 5)
    assert getvaluator(MOUSEX) == 0
    with pytest.raises(GLError):
        setvaluator(LEFTMOUSE, 0, 0, 1)     # not a valuator


def test_a_device_reports_values_within_its_range(open_window):
    """setvaluator(3G): vmin and vmax are "the minimum and maximum values the
    device can assume": what the window system reports (a real window's
    motion, machine.events.device_input) is held in the range, queued and
    read alike; the mouse's power-on range is the screen."""
    open_window()
    qreset()
    qdevice(MOUSEY)
    ev = machine.events
    ev.device_input(MOUSEY, 5000)
    assert getvaluator(MOUSEY) == 1023 and qread() == (MOUSEY, 1023)
    setvaluator(MOUSEY, 100, 0, 479)                # e.g. held to a window while dragging
    ev.device_input(MOUSEY, 700)
    ev.device_input(MOUSEY, -3)
    assert qread() == (MOUSEY, 479) and qread() == (MOUSEY, 0)
    assert getvaluator(MOUSEY) == 0
    setvaluator(DIAL3, 0, -50, 50)                  # any valuator
    ev.device_input(DIAL3, 80)
    assert getvaluator(DIAL3) == 50


def test_unreported_valuator_reads_zero():
    assert getvaluator(DIAL3) == 0
    assert getbutton(MIDDLEMOUSE) == 0


@pytest.mark.parametrize("call, args", [
    (qdevice, (9999,)), (qdevice, (0,)), (qdevice, (0x300,)), (unqdevice, (9999,)),
    (getbutton, (9999,)), (getbutton, (MOUSEX,)), (getvaluator, (LEFTMOUSE,)),
    (getvaluator, (9999,)), (tie, (MOUSEX, MOUSEX, MOUSEY)), (tie, (LEFTMOUSE, LEFTMOUSE, 0)),
    (noise, (LEFTMOUSE, 2)), (qenter, (0x8000, 1)),
])
def test_device_ranges(open_window, call, args):
    open_window()
    before = queue()
    with pytest.raises(GLError) as e:
        call(*args)
    assert str(e.value).startswith(call.__name__)
    assert queue() == before


def test_user_devices_may_be_entered(open_window):
    open_window()
    qreset()
    qenter(0x1234, 7)                       # qenter(3G): user devices 0x1000-0x7FFF
    assert qread() == (0x1234, 7)


def test_tie_queues_button_then_valuators_in_order(open_window):
    """tie(3G): when the queued button changes state (the window system,
    machine.events.device_input), its entry is followed by the valuators'
    current values."""
    open_window()
    qreset()
    qdevice(LEFTMOUSE)
    tie(LEFTMOUSE, MOUSEX, MOUSEY)
    setvaluator(MOUSEX, 300, 0, 1279)
    setvaluator(MOUSEY, 200, 0, 1023)
    machine.events.device_input(LEFTMOUSE, 1)
    assert [qread() for _ in range(3)] == [(LEFTMOUSE, 1), (MOUSEX, 300), (MOUSEY, 200)]
    assert qtest() == 0


def test_qenter_of_a_tied_button_enters_that_entry_alone(open_window):
    """qenter(3G) "takes a device number and a value and enters them": a
    tied button brings no valuators, so a program that enters the button
    and then its own MOUSEX, MOUSEY (buttonfly's menu choice) reads back
    exactly those three; the button's state follows the entry."""
    open_window()
    qreset()
    qdevice(LEFTMOUSE)
    tie(LEFTMOUSE, MOUSEX, MOUSEY)
    setvaluator(MOUSEX, 5, 0, 1279)
    setvaluator(MOUSEY, 6, 0, 1023)
    qenter(LEFTMOUSE, 1)
    qenter(MOUSEX, 320)
    qenter(MOUSEY, 256)
    assert queue() == [(LEFTMOUSE, 1), (MOUSEX, 320), (MOUSEY, 256)]
    assert getbutton(LEFTMOUSE) == 1


def test_tie_one_valuator_and_untie(open_window):
    open_window()
    qreset()
    qdevice(RIGHTMOUSE)
    tie(RIGHTMOUSE, MOUSEY, NULLDEV)
    setvaluator(MOUSEY, 9, 0, 1023)
    machine.events.device_input(RIGHTMOUSE, 1)
    assert queue() == [(RIGHTMOUSE, 1), (MOUSEY, 9)]
    qreset()
    tie(RIGHTMOUSE, NULLDEV, NULLDEV)
    machine.events.device_input(RIGHTMOUSE, 0)
    assert queue() == [(RIGHTMOUSE, 0)]


def test_tied_button_not_queued_brings_nothing(open_window):
    open_window()
    qreset()
    tie(LEFTMOUSE, MOUSEX, MOUSEY)          # LEFTMOUSE not qdevice'd
    machine.events.device_input(LEFTMOUSE, 1)
    assert queue() == [] and getbutton(LEFTMOUSE) == 1


def test_tied_group_is_not_split_by_a_full_queue(open_window):
    open_window()
    qreset()
    qdevice(LEFTMOUSE)
    tie(LEFTMOUSE, MOUSEX, MOUSEY)
    for i in range(99):
        qenter(KEYBD, 65)
    machine.events.device_input(LEFTMOUSE, 1)   # 3 entries do not fit in 101 - 99
    q = queue()
    assert len(q) == 99
    assert q[-1] == (QFULL, 0)
    assert (LEFTMOUSE, 1) not in q


def test_noise_filters_small_valuator_motion(open_window):
    open_window()
    qreset()
    qdevice(MOUSEX)
    noise(MOUSEX, 5)
    ev = machine.events                     # the mouse moving (the window system)
    ev.device_input(MOUSEX, 100)
    ev.device_input(MOUSEX, 103)            # moved 3 < 5: not queued
    assert getvaluator(MOUSEX) == 103       # (its value follows every change)
    ev.device_input(MOUSEX, 106)            # 6 from the last queued
    assert queue() == [(MOUSEX, 100), (MOUSEX, 106)]
    assert getvaluator(MOUSEX) == 106
    qenter(MOUSEX, 107)                     # what a program enters is not filtered
    assert queue()[-1] == (MOUSEX, 107)
    with pytest.raises(GLError):
        noise(MOUSEX, 0)


def test_getdev_reads_buttons_and_valuators(open_window):
    open_window()
    setvaluator(MOUSEX, 11, 0, 1279)
    qenter(MIDDLEMOUSE, 1)
    assert getdev(3, [MOUSEX, MIDDLEMOUSE, LEFTMOUSE]) == [11, 1, 0]
    vals = np.zeros(3, np.int16)
    getdev(2, [MIDDLEMOUSE, MOUSEX, 0], vals)
    assert list(vals) == [1, 11, 0]
    with pytest.raises(GLError):
        getdev(2, [MOUSEX])                 # fewer devices than n
    with pytest.raises(GLError):
        getdev(1, [REDRAW])                 # a pseudo device has no value


# -- blkqread, qgetfd, qcontrol ------------------------------------------------------
def test_blkqread_pairs_and_array(open_window):
    open_window()
    qreset()
    for v in (1, 2, 3):
        qenter(KEYBD, v)
    assert blkqread(4) == [(KEYBD, 1), (KEYBD, 2)]       # n shorts = n/2 entries
    data = np.zeros(8, np.int16)
    assert blkqread(data, 8) == 2                         # 16-bit words read
    assert list(data[:2]) == [KEYBD, 3]
    assert qtest() == 0


def test_blkqread_empty_queue_ends_like_qread(open_window):
    from vgx_emulator.events import QueueExhausted
    open_window()
    qreset()
    with pytest.raises(QueueExhausted):
        blkqread(10)


def test_qgetfd_readable_iff_events_queued(open_window):
    open_window()
    qreset()
    fd = qgetfd()
    assert fd >= 0 and qgetfd() == fd
    assert select.select([fd], [], [], 0)[0] == []
    qenter(KEYBD, 65)
    assert select.select([fd], [], [], 0)[0] == [fd]
    qread()
    assert select.select([fd], [], [], 0)[0] == []
    qenter(KEYBD, 66)
    qreset()
    assert select.select([fd], [], [], 0)[0] == []
    os.fstat(fd)


def test_qcontrol_refuses_with_negative_errno(open_window):
    import errno
    assert qcontrol(1, 0, None, 2, np.zeros(2, np.int16)) == -errno.EINVAL
    with pytest.raises(GLError):
        qcontrol(1, 3, [1], 0, None)        # count beyond the array


def test_getdev_blkqread_readdisplay_fill_a_list(open_window):
    """porting.md §3: an array C fills may be a list; getdev(3G),
    blkqread(3G) and readdisplay(3G) fill one in place, as they fill a numpy
    array (they refused lists); too short is a GLError naming the call."""
    open_window()
    qreset()
    setvaluator(MOUSEX, 11, 0, 1279)
    vals = [0, 0, 99]
    assert getdev(2, [MOUSEX, LEFTMOUSE], vals) is None and vals == [11, 0, 99]
    qenter(KEYBD, 65)
    qenter(KEYBD, 66)
    data = [0] * 6
    assert blkqread(data, 6) == 4 and data == [KEYBD, 65, KEYBD, 66, 0, 0]
    px = [0] * 4
    assert readdisplay(0, 0, 1, 1, px, 0) == 4 and all(p == 0xFF000000 for p in px)
    with pytest.raises(GLError, match="^getdev: vals has 1 elements"):
        getdev(2, [MOUSEX, LEFTMOUSE], [0])
