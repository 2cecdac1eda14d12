"""Patterns (docs/semantics.md §8): defpattern, setpattern, getpattern.

Bit 15 of each short is the leftmost pixel; shorts run left to right, then
bottom to top.  The pattern is tiled over the whole screen, so its phase
follows the window's origin (docs/semantics.md §8).  A 0 bit protects the pixel in
every bank.  Patterns apply to filled primitives and clear only.
"""
import numpy as np

from vgx_emulator.errors import fail

from ._current import glcall, integer, machine, win

__all__ = ["defpattern", "setpattern", "getpattern"]


def pattern_bits(size, shorts):
    """(size, size) uint8 array, row 0 at the bottom, column 0 at the left."""
    words = np.asarray(shorts, np.int64).reshape(size, size // 16) & 0xFFFF
    bits = (words[:, :, None] >> np.arange(15, -1, -1)) & 1
    return np.ascontiguousarray(bits.reshape(size, size).astype(np.uint8))


@glcall
def defpattern(n, size, mask):
    """defpattern(3G): define pattern n (1..65535) of size 16, 32 or 64 from
    size*size/16 shorts.  Pattern 0 is the solid pattern and is built in."""
    n = integer("defpattern", n, "index")
    size = integer("defpattern", size, "size")
    if n <= 0 or n > 0xFFFF:
        fail("defpattern", f"index {n}", "1..65535 (0 is the built-in solid pattern)")
    if size not in (16, 32, 64):
        fail("defpattern", f"size {size}", "PATTERN_16, PATTERN_32 or PATTERN_64")
    try:
        vals = [integer("defpattern", v, "pattern word") for v in mask]
    except TypeError:
        fail("defpattern", "mask is not a sequence", "a list of 16-bit words")
    need = size * size // 16
    if len(vals) != need:
        fail("defpattern", f"{len(vals)} words for size {size}", f"{need} words")
    machine.flush_all()
    machine.patterns[n] = (size, pattern_bits(size, vals))


@glcall
def setpattern(index):
    """setpattern(3G): select a pattern; 0 (default) is solid; an undefined
    index draws solid."""
    w = win("setpattern")
    i = integer("setpattern", index, "index")
    machine.state_change(w)
    w.st.pattern = i if i in machine.patterns else 0


@glcall
def getpattern():
    """getpattern(3G): the index of the current pattern (0: solid)."""
    return win("getpattern").st.pattern
