"""Shared fixtures: a fresh machine for every test, and a small window opener."""
import pytest

import vgx_emulator


@pytest.fixture(autouse=True)
def vgx():
    """The machine the irisgl calls drive, reset (and strict) around each test."""
    from irisgl._current import machine
    machine.reset()
    vgx_emulator.errors.set_error_mode("strict")
    yield machine
    machine.reset()
    vgx_emulator.errors.set_error_mode("strict")


def _open_window(w=64, h=48, rgb=True, double=False, name="test"):
    """prefsize + winopen + RGBmode/cmode (+ doublebuffer) + gconfig; returns the id.
    The matrices are left as winopen leaves them."""
    from irisgl import RGBmode, cmode, doublebuffer, gconfig, prefsize, winopen
    prefsize(w, h)
    gid = winopen(name)
    if rgb:
        RGBmode()
    else:
        cmode()
    if double:
        doublebuffer()
    gconfig()
    return gid


@pytest.fixture
def open_window():
    """``open_window(w=64, h=48, rgb=True, double=False)`` -> window id."""
    return _open_window
