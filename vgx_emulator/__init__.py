"""vgx_emulator: the emulated IRIS-4D VGX behind :mod:`irisgl`.

Non-IRIS-GL entry points (docs/porting.md §1): the machine, the runner,
PNG output, the error mode.
"""
from .errors import GLError, VGXWarning, error_mode, set_error_mode
from .machine import VGX
from . import menus
from .menus import script as script_menus
from .planes import planes
from .trace import Trace, trace_program
from . import precompile as _precompile

__all__ = ["VGX", "GLError", "VGXWarning", "run_program", "save_png", "machine",
           "set_error_mode", "error_mode", "window_image", "menus", "script_menus",
           "planes", "Trace", "trace_program"]


def __getattr__(name):
    """``run_program`` is imported from the runner at first use, so that
    ``python -m vgx_emulator.runner`` runs the runner module once (runpy
    warns when the package's import has already loaded it)."""
    if name == "run_program":
        from .runner import run_program
        return run_program
    raise AttributeError(f"module 'vgx_emulator' has no attribute {name!r}")


def machine():
    """The VGX that the irisgl calls drive."""
    from irisgl._current import machine as m
    return m


def window_image(gid=None):
    """What the screen shows of a window (default: the current one) as an
    (h, w, 3) uint8 array, top row first."""
    m = machine()
    win = m.windows[gid] if gid is not None else m.current
    if win is None:
        raise GLError("window_image: no window is open; call winopen first")
    return m.image(win)


def save_png(path, gid=None):
    """Save what a window shows (default: the current window) as a PNG."""
    from .display.png import write_png
    return write_png(path, window_image(gid))


_precompile.start_if_cold()     # a cold numba cache: the longest compiles in a second process
