"""Line and point modes: width, style, repeat, reset, backup, smoothing,
point size (linewidth(3G), deflinestyle(3G), setlinestyle(3G), lsrepeat(3G),
resetls(3G), lsbackup(3G), linesmooth(3G), pntsize(3G), pntsmooth(3G)).

The state lives in the window (linestyles in the machine: deflinestyle(3G)
says they are shared by all windows); the geometry stage applies width,
style and point size to every line and point drawn (vgx_emulator/geometry/
lines2d.py, docs/drawing-2d-and-lines.md).
"""
import math

from vgx_emulator.errors import fail

from . import constants as K
from ._current import boolean, glcall, integer, machine, num, win

__all__ = ["linewidth", "linewidthf", "getlwidth", "deflinestyle", "setlinestyle",
           "getlstyle", "lsrepeat", "getlsrepeat", "resetls", "getresetls", "lsbackup",
           "getlsbackup", "linesmooth", "smoothline", "pntsize", "pntsizef",
           "pntsmooth"]


def _set(call, **fields):
    """Flush what was drawn with the old mode, then set the fields."""
    w = win(call)
    machine.state_change(w)
    for k, v in fields.items():
        setattr(w.st, k, v)


def _width(call, n, conv):
    v = conv(call, n, "width")
    if not math.isfinite(v) or v < 0:
        fail(call, f"width {n!r}", "a width of 0 or more pixels (0 draws as 1)")
    return float(v)


@glcall
def linewidth(n):
    """linewidth(3G): lines n pixels across their minor axis (aliased widths
    1..255 on the VGX; 0 draws as 1).  The value given is retained."""
    _set("linewidth", linewidth=_width("linewidth", n, integer))


@glcall
def linewidthf(n):
    """linewidthf(3G): as linewidth, a float width rounded to the nearest
    integer when lines are drawn (the retained value is not rounded)."""
    _set("linewidthf", linewidth=_width("linewidthf", n, num))


@glcall
def getlwidth():
    """getlwidth(3G): the current line width, rounded to an integer."""
    return int(math.floor(win("getlwidth").st.linewidth + 0.5))


def _ls_index(call, n):
    i = integer(call, n, "linestyle index")
    if not 0 <= i <= 0x7FFF:
        fail(call, f"linestyle index {i}", "0..32767")
    return i


@glcall(immediate=True)
def deflinestyle(n, ls):
    """deflinestyle(3G): define linestyle n as the 16-bit pattern ls (bit 0
    applied first).  Index 0 is the solid style 0xFFFF and cannot be
    redefined; the table is shared by all windows; immediate mode only."""
    i = _ls_index("deflinestyle", n)
    pat = integer("deflinestyle", ls, "pattern") & 0xFFFF
    if i == 0:
        fail("deflinestyle", "linestyle 0 cannot be redefined", "use an index 1..32767")
    machine.flush_all()             # lines already drawn keep the old definition
    machine.linestyles[i] = pat


@glcall
def setlinestyle(n):
    """setlinestyle(3G): draw the following lines with linestyle n (0 = solid)."""
    i = _ls_index("setlinestyle", n)
    if i not in machine.linestyles:
        fail("setlinestyle", f"linestyle {i} is not defined", "deflinestyle it first, or 0")
    _set("setlinestyle", linestyle=i)


@glcall
def getlstyle():
    """getlstyle(3G): the current linestyle index."""
    return win("getlstyle").st.linestyle


@glcall
def lsrepeat(factor):
    """lsrepeat(3G): each bit of the linestyle covers ``factor`` consecutive
    pixels (1..255)."""
    f = integer("lsrepeat", factor, "factor")
    if not 1 <= f <= 255:
        fail("lsrepeat", f"factor {f}", "1..255")
    _set("lsrepeat", lsrepeat=f)


@glcall
def getlsrepeat():
    """getlsrepeat(3G): the linestyle repeat factor."""
    return win("getlsrepeat").st.lsrepeat


@glcall
def resetls(b):
    """resetls(3G): TRUE (default) starts the linestyle afresh at every line;
    FALSE carries it on from the end of the previous line.  Either way the
    call restarts the pattern and leaves the graphics position undefined."""
    v = boolean("resetls", b)
    _set("resetls", resetls=v, ls_phase=0, gpos=None)


@glcall
def getresetls():
    """getresetls(3G): TRUE when the linestyle restarts at every line."""
    return int(win("getresetls").st.resetls)


@glcall
def lsbackup(b):
    """lsbackup(3G): TRUE colours the last two pixels of every line whatever
    the linestyle says."""
    _set("lsbackup", lsbackup=boolean("lsbackup", b))


@glcall
def getlsbackup():
    """getlsbackup(3G): the linestyle backup flag."""
    return int(win("getlsbackup").st.lsbackup)


_SML = K.SML_ON | K.SML_SMOOTHER | K.SML_END_CORRECT


@glcall
def linesmooth(mode):
    """linesmooth(3G): SML_OFF or SML_ON (+ the SML_SMOOTHER and
    SML_END_CORRECT hints, which the emulated VGX ignores).  Antialiased
    lines share each step's coverage between the two pixels nearest the
    exact line: RGB alpha times coverage (blend with BF_SA, BF_MSA),
    colour-map index low 4 bits = coverage (docs/drawing-2d-and-lines.md)."""
    m = integer("linesmooth", mode, "mode")
    if m & ~_SML or (m and not m & K.SML_ON):
        fail("linesmooth", f"mode {mode!r}",
             "SML_OFF, or SML_ON optionally + SML_SMOOTHER + SML_END_CORRECT")
    _set("linesmooth", linesmooth=m)


@glcall
def smoothline(onoff):
    """smoothline(3G): the old Boolean form of linesmooth (TRUE = SML_ON)."""
    _set("smoothline", linesmooth=K.SML_ON if boolean("smoothline", onoff) else K.SML_OFF)


def _size(call, n, conv):
    v = conv(call, n, "size")
    if not math.isfinite(v) or v < 0:
        fail(call, f"point size {n!r}", "a size of 0 or more pixels (0 draws as 1)")
    return float(v)


@glcall
def pntsize(n):
    """pntsize(3G): points are n x n pixel squares (1..255; 0 draws as 1)."""
    _set("pntsize", pntsize=_size("pntsize", n, integer))


@glcall
def pntsizef(n):
    """pntsizef(3G): as pntsize, rounded to the nearest integer when drawn."""
    _set("pntsizef", pntsize=_size("pntsizef", n, num))


@glcall
def pntsmooth(mode):
    """pntsmooth(3G): SMP_OFF or SMP_ON (+ the SMP_SMOOTHER hint, ignored).
    An antialiased one-pixel point covers the 2 x 2 pixels around it with
    bilinear coverage, applied as for linesmooth; wider points stay aliased
    (docs/drawing-2d-and-lines.md)."""
    m = integer("pntsmooth", mode, "mode")
    if m & ~(K.SMP_ON | K.SMP_SMOOTHER) or (m and not m & K.SMP_ON):
        fail("pntsmooth", f"mode {mode!r}", "SMP_OFF, or SMP_ON optionally + SMP_SMOOTHER")
    _set("pntsmooth", pntsmooth=m)
