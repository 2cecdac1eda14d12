"""Reading pixels (docs/semantics.md §11): readsource, lrectread."""
import numpy as np

from vgx_emulator.errors import fail

from . import constants as K
from ._current import fill, glcall, integer, machine, num, out_array, token, win
from ._current import words as _words

__all__ = ["readsource", "lrectread", "rectread", "lrectwrite", "rectwrite", "rectcopy",
           "rectzoom"]

_SRC = {K.SRC_AUTO: "SRC_AUTO", K.SRC_FRONT: "SRC_FRONT", K.SRC_BACK: "SRC_BACK",
        K.SRC_ZBUFFER: "SRC_ZBUFFER",
        # the pop-up, overlay and underlay banks (drawmode(3G)): colour indices
        K.SRC_PUP: "SRC_PUP", K.SRC_OVER: "SRC_OVER", K.SRC_UNDER: "SRC_UNDER"}


def _order(w, block):
    """pixmode(3G) PM_TTOB / PM_RTOL: the array's rows run top to bottom,
    its columns right to left (irisgl.system.pixmode keeps them)."""
    pm = w.wm.get("pixmode")
    if pm:
        if pm.get(K.PM_TTOB):
            block = block[::-1]
        if pm.get(K.PM_RTOL):
            block = block[:, ::-1]
    return block


@glcall
def readsource(src):
    """readsource(3G): the bank lrectread reads (SRC_AUTO: front in single-,
    back in double-buffer mode).  SRC_BACK needs double-buffer mode."""
    w = win("readsource")
    s = token("readsource", src, _SRC, "source")
    if s == K.SRC_BACK and not w.st.double:
        fail("readsource", "SRC_BACK in single-buffer mode", "doublebuffer() then gconfig()")
    w.readsource = s


#: the most pixels one read or copy moves: 16 screens of the VGX (a larger
#: block is a mistake, not a picture; it would only exhaust memory)
MAX_PIXELS = 16 * 1280 * 1024


def _screencoord(call, v):
    """A Screencoord argument: a C short."""
    v = integer(call, v, "coordinate")
    if not -32768 <= v <= 32767:
        fail(call, f"coordinate {v}", "a Screencoord is a short: -32768..32767")
    return v


def _rect(call, x1, y1, x2, y2):
    """The inclusive rectangle of a pixel read or copy, checked first."""
    x1, y1, x2, y2 = (_screencoord(call, v) for v in (x1, y1, x2, y2))
    if x2 < x1 or y2 < y1:
        fail(call, f"({x1}, {y1})-({x2}, {y2}) is empty", "x1 <= x2, y1 <= y2")
    if (x2 - x1 + 1) * (y2 - y1 + 1) > MAX_PIXELS:
        fail(call, f"({x1}, {y1})-({x2}, {y2}) is {(x2 - x1 + 1) * (y2 - y1 + 1)} pixels",
             f"at most {MAX_PIXELS} (16 screens) in one call")
    return x1, y1, x2, y2


@glcall
def lrectread(x1, y1, x2, y2, parray=None):
    """lrectread(3G): pixels x1..x2, y1..y2 (window coordinates, inclusive),
    left to right then bottom to top.  Returns (x2-x1+1)*(y2-y1+1).

    Python: without ``parray`` returns an (h, w) uint32 array, row 0 at y1
    (from SRC_ZBUFFER: int32 signed z values, docs/semantics.md §5); with a writable
    numpy array or a list of at least h*w elements, fills its first h*w
    (as C fills a larger buffer) and returns the count.
    """
    w = win("lrectread")
    x1, y1, x2, y2 = _rect("lrectread", x1, y1, x2, y2)
    n = (x2 - x1 + 1) * (y2 - y1 + 1)
    out_array("lrectread", parray, n, "parray", f"pass (x2-x1+1)*(y2-y1+1) = {n}, or nothing")
    block = _order(w, machine.lrectread(w, x1, y1, x2, y2, w.readsource))
    if parray is None:
        return block if w.readsource == K.SRC_ZBUFFER else block.astype(np.uint32)
    flat = block.reshape(-1)
    if isinstance(parray, np.ndarray) or w.readsource != K.SRC_ZBUFFER:
        flat = flat.view(np.uint32)          # a list gets signed z words, as returned
    fill(parray, flat)
    return n


@glcall
def rectread(x1, y1, x2, y2, parray=None):
    """rectread(3G): as lrectread with 16-bit Colorindex words (uint16)."""
    w = win("rectread")
    x1, y1, x2, y2 = _rect("rectread", x1, y1, x2, y2)
    n = (x2 - x1 + 1) * (y2 - y1 + 1)
    out_array("rectread", parray, n, "parray", f"pass (x2-x1+1)*(y2-y1+1) = {n}, or nothing")
    block = (_order(w, machine.lrectread(w, x1, y1, x2, y2, w.readsource)).astype(np.int64)
             & 0xFFFF).astype(np.uint16)
    if parray is None:
        return block
    fill(parray, block.reshape(-1))
    return n


def _write(call, x1, y1, x2, y2, parray, dtype):
    w = win(call)
    x1, y1, x2, y2 = _rect(call, x1, y1, x2, y2)
    h, wd = y2 - y1 + 1, x2 - x1 + 1
    try:
        a = np.asarray(parray)
    except (TypeError, ValueError):
        a = None
    if a is None or a.ndim == 0 or not (a.dtype.kind in "iub" or (a.dtype == object and all(
            isinstance(v, (int, np.integer)) for v in a.reshape(-1)))):
        fail(call, "parray is not an array of integer pixel words",
             f"{h * wd} {'32' if dtype == np.uint32 else '16'}-bit words (C: "
             f"{'unsigned long' if dtype == np.uint32 else 'unsigned short'}), no floats")
    words = _words(a, 0xFFFFFFFF if dtype == np.uint32 else 0xFFFF)
    if words.size < h * wd:
        fail(call, f"parray has {words.size} elements", f"(x2-x1+1)*(y2-y1+1) = {h * wd}")
    # a longer C array is read from its first elements
    words = words.reshape(-1)[:h * wd]
    machine.write_pixels(w, x1, y1, _order(w, words.reshape(h, wd)).astype(np.uint32),
                         w.st.zoom)


@glcall
def lrectwrite(x1, y1, x2, y2, parray):
    """lrectwrite(3G): write (x2-x1+1)*(y2-y1+1) packed pixels, left to right
    then bottom to top, lower-left at (x1, y1), zoomed by rectzoom.
    Writemasks, blend/logicop, afunction and scrmask apply; no z, stencil or
    pattern (docs/semantics.md §11)."""
    _write("lrectwrite", x1, y1, x2, y2, parray, np.uint32)


@glcall
def rectwrite(x1, y1, x2, y2, parray):
    """rectwrite(3G): as lrectwrite with 16-bit Colorindex words."""
    _write("rectwrite", x1, y1, x2, y2, parray, np.uint16)


@glcall
def rectcopy(x1, y1, x2, y2, newx, newy):
    """rectcopy(3G): copy from readsource to the enabled buffers with its
    lower-left at (newx, newy), zoomed by rectzoom."""
    w = win("rectcopy")
    x1, y1, x2, y2 = _rect("rectcopy", x1, y1, x2, y2)
    nx, ny = (_screencoord("rectcopy", v) for v in (newx, newy))
    block = machine.lrectread(w, x1, y1, x2, y2, w.readsource).view(np.uint32)
    machine.write_pixels(w, nx, ny, block.copy(), w.st.zoom)


@glcall
def rectzoom(xfactor, yfactor):
    """rectzoom(3G): pixel replication (> 1) or decimation (< 1) factors for
    lrectwrite, rectwrite and rectcopy; default 1.0."""
    w = win("rectzoom")
    xf = num("rectzoom", xfactor, "xfactor")
    yf = num("rectzoom", yfactor, "yfactor")
    if not (xf > 0 and yf > 0 and xf < 1e4 and yf < 1e4):
        fail("rectzoom", f"factors ({xfactor}, {yfactor})", "positive and finite")
    w.st.zoom = (xf, yf)
