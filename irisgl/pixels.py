"""Reading pixels (reference section 11): readsource, lrectread."""
import numpy as np

from vgx_emulator.errors import fail

from . import constants as K
from ._current import glcall, integer, machine, token, win

__all__ = ["readsource", "lrectread"]

_SRC = {K.SRC_AUTO: "SRC_AUTO", K.SRC_FRONT: "SRC_FRONT", K.SRC_BACK: "SRC_BACK",
        K.SRC_ZBUFFER: "SRC_ZBUFFER"}


@glcall
def readsource(src):
    """readsource(3G): the bank lrectread reads (SRC_AUTO: front in single-,
    back in double-buffer mode).  SRC_BACK needs double-buffer mode."""
    w = win("readsource")
    s = token("readsource", src, _SRC, "source")
    if s == K.SRC_BACK and not w.st.double:
        fail("readsource", "SRC_BACK in single-buffer mode", "doublebuffer() then gconfig()")
    w.readsource = s


@glcall
def lrectread(x1, y1, x2, y2, parray=None):
    """lrectread(3G): pixels x1..x2, y1..y2 (window coordinates, inclusive),
    left to right then bottom to top.  Returns (x2-x1+1)*(y2-y1+1).

    Python: without ``parray`` returns an (h, w) uint32 array, row 0 at y1
    (from SRC_ZBUFFER: int32 signed z values, Decision 3); with a writable
    numpy array of h*w elements, fills it and returns the count.
    """
    w = win("lrectread")
    x1, y1, x2, y2 = (integer("lrectread", v) for v in (x1, y1, x2, y2))
    if x2 < x1 or y2 < y1:
        fail("lrectread", f"({x1}, {y1})-({x2}, {y2}) is empty", "x1 <= x2, y1 <= y2")
    n = (x2 - x1 + 1) * (y2 - y1 + 1)
    if parray is not None and (not isinstance(parray, np.ndarray) or parray.size != n):
        fail("lrectread", "parray is not a numpy array of (x2-x1+1)*(y2-y1+1) elements",
             f"pass {n} elements or nothing")
    block = machine.lrectread(w, x1, y1, x2, y2, w.readsource)
    if parray is None:
        return block if w.readsource == K.SRC_ZBUFFER else block.astype(np.uint32)
    parray.reshape(-1)[...] = block.reshape(-1).view(np.uint32).astype(parray.dtype, copy=False)
    return n
