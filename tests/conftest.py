"""Shared fixtures: a fresh machine for every test, and a small window opener
(tests/banks.py has the window and the bank readers)."""
import pytest

import vgx_emulator
from banks import new_window


@pytest.fixture(autouse=True)
def vgx():
    """The machine the irisgl calls drive, reset (and strict) around each test."""
    from irisgl._current import machine
    machine.reset()
    vgx_emulator.errors.set_error_mode("strict")
    yield machine
    machine.reset()
    vgx_emulator.errors.set_error_mode("strict")


@pytest.fixture
def open_window():
    """``open_window(w=64, h=48, rgb=True, double=False, planes=0, accum=0,
    origin=None, pixels=False, cleared=False)`` -> window id (banks.new_window)."""
    return new_window
