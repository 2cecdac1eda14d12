"""Picking, selecting and the screen-to-world mappings: pick, gselect,
endpick, endselect, picksize, the name stack (initnames, loadname,
pushname, popname), gethitcode/clearhitcode, mapw/mapw2; feedback is not
emulated (docs/picking.md).

The C hit buffer ``short buffer[]`` follows docs/picking.md:
``pick(buffer, numnames)`` with a writable numpy array is filled in place
at ``n = endpick(buffer)``; with the buffer left out, ``pick(numnames)``
and ``n, buffer = endpick()`` (a new int16 array of numnames elements).
"""
import math

import numpy as np

from vgx_emulator import picking as P
from vgx_emulator.errors import fail
from vgx_emulator.geometry import stack as S

from ._current import fill, glcall, integer, machine, not_emulated, out_array, win

__all__ = ["pick", "endpick", "gselect", "endselect", "initnames", "loadname", "pushname",
           "popname", "picksize", "clearhitcode", "gethitcode", "mapw", "mapw2",
           "feedback", "endfeedback"]

MOUSEX, MOUSEY = 266, 267


# -- the hit buffer ------------------------------------------------------------
def _is_buffer(b):
    return isinstance(b, (np.ndarray, list))


def _buffer(call, b, need):
    """A C ``short buffer[]`` the call fills, at least ``need`` elements."""
    out_array(call, b, need, "the buffer", f"it must hold numnames = {need}")


def _numnames(call, n):
    n = integer(call, n, "numnames")
    if n < 0:
        fail(call, f"numnames {n}", "the number of shorts the buffer holds, >= 0")
    return n


def _begin(call, mode, buffer, numnames):
    w = win(call)
    if numnames is None:
        if _is_buffer(buffer):
            n = _numnames(call, len(buffer) if isinstance(buffer, list) else buffer.size)
        else:
            n, buffer = _numnames(call, buffer), None
    else:
        n = _numnames(call, numnames)
    if buffer is not None:
        _buffer(call, buffer, n)
    if machine.picking is not None:
        fail(call, f"already in {machine.picking.mode}ing mode",
             f"end{machine.picking.mode} first")
    machine.state_change(w)            # what came before is drawn, not picked
    region = None
    if mode == P.PICK:
        dx, dy = machine.picksize
        cx = machine.events.valuator(MOUSEX) - w.origin[0]
        cy = machine.events.valuator(MOUSEY) - w.origin[1]
        region = (cx - dx / 2.0, cx + dx / 2.0, cy - dy / 2.0, cy + dy / 2.0)
    s = P.Session(mode, w, n, buffer, region)
    if mode == P.PICK:
        s.pick_matrix = P.pick_matrix(w.st.viewport, cx, cy, dx, dy)
    machine.picking = s


def _end(call, mode, buffer):
    s = machine.picking
    if s is None or s.mode != mode:
        now = f"in {s.mode}ing mode" if s is not None else "not picking or selecting"
        fail(call, now, f"call {'pick' if mode == P.PICK else 'gselect'} first")
    if buffer is not None:
        _buffer(call, buffer, s.numnames)
    w = s.win
    machine.state_change(w)            # the primitives still batched are tested
    machine.picking = None
    words = s.words()
    n = s.count()
    if buffer is not None:
        fill(buffer, words)
        return n
    out = s.buffer if s.buffer is not None else np.zeros(s.numnames, np.int16)
    fill(out, words)
    return n, out


@glcall(immediate=True)
def pick(buffer, numnames=None):
    """pick(3G): picking mode; nothing is drawn, and every primitive that
    meets the picksize region around the cursor (MOUSEX/MOUSEY) is a hit.
    The projection restated after pick is loaded times the picking matrix
    (Programming Guide 12.1.1).  ``pick(buffer, numnames)`` or ``pick(numnames)``."""
    _begin("pick", P.PICK, buffer, numnames)


@glcall(immediate=True)
def endpick(buffer=None):
    """endpick(3G): leave picking mode and return the number of hit records
    (negative if the buffer was too small); the matrices are left as they
    are, so the program restates its projection (Programming Guide 12.1.1).
    ``n = endpick(buffer)`` fills buffer; ``n, buffer = endpick()``."""
    return _end("endpick", P.PICK, buffer)


@glcall(immediate=True)
def gselect(buffer, numnames=None):
    """gselect(3G): selecting mode; every primitive inside the current
    viewing volume is a hit.  ``gselect(buffer, numnames)`` or
    ``gselect(numnames)``."""
    _begin("gselect", P.SELECT, buffer, numnames)


@glcall(immediate=True)
def endselect(buffer=None):
    """endselect(3G): leave selecting mode; returns the number of hit records,
    negative if some did not fit (``n = endselect(buffer)`` or
    ``n, buffer = endselect()``)."""
    return _end("endselect", P.SELECT, buffer)


@glcall(immediate=True)
def picksize(deltax, deltay):
    """picksize(3G): width and height in pixels of the picking region
    (default 10 x 10), used by the next pick."""
    dx = integer("picksize", deltax, "deltax")
    dy = integer("picksize", deltay, "deltay")
    if not (0 < dx <= 32767 and 0 < dy <= 32767):
        fail("picksize", f"({dx}, {dy})", "positive sizes in pixels (a short)")
    machine.picksize = (dx, dy)


# -- the name stack ------------------------------------------------------------
def _name(call, name):
    """A 16-bit name: the C argument is a short, so wider values wrap."""
    v = integer(call, name, "name")
    return ((v + 0x8000) & 0xFFFF) - 0x8000


def _session(call):
    """The current window's pick/select session, after drawing what was
    issued under the old names; None outside those modes (ignored there)."""
    w = win(call)
    s = machine.picking
    if s is None or s.win is not w:
        return None
    machine.state_change(w)
    return s


@glcall
def initnames():
    """initnames(3G): empty the name stack (ignored outside picking and
    selecting mode)."""
    s = _session("initnames")
    if s is not None:
        s.initnames()


@glcall
def loadname(name):
    """loadname(3G): replace the top name (on an empty stack, the name
    becomes its only entry); ignored outside picking and selecting mode."""
    n = _name("loadname", name)
    s = _session("loadname")
    if s is not None:
        s.loadname(n)


@glcall
def pushname(name):
    """pushname(3G): push a 16-bit name; ignored outside picking and
    selecting mode.  The stack holds NAMESTACKDEPTH names."""
    n = _name("pushname", name)
    s = machine.picking
    if s is not None and s.win is win("pushname") and len(s.names) >= P.NAMESTACKDEPTH:
        fail("pushname", f"the name stack is full ({P.NAMESTACKDEPTH} names)",
             "pop names before pushing more")
    s = _session("pushname")
    if s is not None:
        s.pushname(n)


@glcall
def popname():
    """popname(3G): pop the top name; ignored outside picking and selecting
    mode."""
    s = machine.picking
    if s is not None and s.win is win("popname") and not s.names:
        fail("popname", "the name stack is empty", "pop only what was pushed or loaded")
    s = _session("popname")
    if s is not None:
        s.popname()


# -- hitcode ---------------------------------------------------------------------
@glcall
def gethitcode():
    """gethitcode(3G): the cumulative clipping-plane hitcode.  The man page:
    it functions only on IRIS-4D B and G models; on the emulated VGX it
    stays 0 (LEFTPLANE ... FARPLANE bits never set)."""
    return 0


@glcall(immediate=True)
def clearhitcode():
    """clearhitcode(3G): clear the hitcode (always 0 on the VGX, see
    gethitcode)."""
    win("clearhitcode")


# -- mapw / mapw2 ------------------------------------------------------------------
_VIEWING_CALLS = {"viewport", "reshapeviewport", "pushviewport", "popviewport", "ortho",
                  "ortho2", "perspective", "window", "lookat", "polarview", "translate",
                  "rotate", "rot", "scale", "multmatrix", "loadmatrix", "pushmatrix",
                  "popmatrix", "mmode"}


def _viewing(call, vobj):
    """(clip matrix (4, 4) float64, viewport) that the viewing object's
    transformation and viewport calls build, starting from identity
    matrices in the current mmode and the window's viewport; its other
    calls (drawing, attributes) are not executed."""
    o = integer(call, vobj, "object")
    w = win(call)
    if o not in machine.objects:
        fail(call, f"object {o} is not defined", "pass a viewing object made with makeobj")
    if machine.recording == o:
        fail(call, f"object {o} is still open", "closeobj first")
    machine.state_change(w)
    st = w.st
    saved = (st.matrices, st.viewport, st.scrmask, list(st.viewport_stack), st.depth_range,
             machine.picking, machine.recording)
    fresh = S.MatrixState()
    fresh.mode = st.matrices.mode
    st.matrices = fresh
    machine.picking, machine.recording = None, None
    try:
        _replay_viewing(call, o, 0)
        mv, pr = fresh.vertex_matrices()
        vp = st.viewport
    finally:
        (st.matrices, st.viewport, st.scrmask, st.viewport_stack, st.depth_range,
         machine.picking, machine.recording) = saved
        machine.matrices_changed(w)
    return mv @ pr, vp


def _replay_viewing(call, o, depth):
    if depth > 64:
        fail(call, "viewing objects nested deeper than 64", "no recursive objects")
    ob = machine.objects.get(o)
    if ob is None:
        return
    for it in ob.items:
        if it[0] != "call":
            continue
        _, name, fn, args = it
        if name == "callobj":
            _replay_viewing(call, integer(call, args[0], "object"), depth + 1)
        elif name in _VIEWING_CALLS:
            fn(*args)


def _ndc(sx, sy, vp):
    l, r, b, t = vp
    return (2.0 * (sx - l + 0.5) / (r - l + 1) - 1.0,
            2.0 * (sy - b + 0.5) / (t - b + 1) - 1.0)


def _screen(call, sx, sy):
    return integer(call, sx, "sx"), integer(call, sy, "sy")


@glcall(immediate=True)
def mapw(vobj, sx, sy):
    """mapw(3G): ``wx1, wy1, wz1, wx2, wy2, wz2 = mapw(vobj, sx, sy)``, the
    world-space line under window point (sx, sy) for the viewing object
    vobj: its points on the near and on the far clipping plane."""
    sx, sy = _screen("mapw", sx, sy)
    m, vp = _viewing("mapw", vobj)
    xn, yn = _ndc(sx, sy, vp)
    with np.errstate(all="ignore"):
        try:
            inv = np.linalg.inv(m)
        except np.linalg.LinAlgError:
            inv = None
        if inv is None or not np.isfinite(inv).all():
            fail("mapw", f"the transformation of object {vobj} cannot be inverted",
                 "a viewing object with a non-singular projection and viewing matrix")
        p = np.array([[xn, yn, -1.0, 1.0], [xn, yn, 1.0, 1.0]]) @ inv
        out = p[:, :3] / p[:, 3:4]
    if not np.isfinite(out).all():
        fail("mapw", f"the line under ({sx}, {sy}) reaches infinity",
             "a viewing object whose near and far planes are finite")
    return tuple(float(v) for v in out.reshape(-1))


@glcall(immediate=True)
def mapw2(vobj, sx, sy):
    """mapw2(3G): ``wx, wy = mapw2(vobj, sx, sy)``, the 2-D world point
    under window point (sx, sy) (z = 0); undefined, per the man page, for
    a transformation that is not 2-D."""
    sx, sy = _screen("mapw2", sx, sy)
    m, vp = _viewing("mapw2", vobj)
    xn, yn = _ndc(sx, sy, vp)
    m3 = m[np.ix_((0, 1, 3), (0, 1, 3))]
    with np.errstate(all="ignore"):
        try:
            q = np.array([xn, yn, 1.0]) @ np.linalg.inv(m3)
        except np.linalg.LinAlgError:
            q = np.array([math.nan] * 3)
        out = q[:2] / q[2]
    if not np.isfinite(out).all():
        fail("mapw2", f"the 2-D transformation of object {vobj} cannot be inverted",
             "a viewing object with a non-singular 2-D transformation")
    return float(out[0]), float(out[1])


# -- feedback ----------------------------------------------------------------------
_FEEDBACK = ("feedback(3G) returns the raw output of the Geometry Engines; the Programming "
             "Guide (17.3) gives the VGX's record layout (float data type, count, data), "
             "but the numeric values of its data types (FB_POINT, FB_LINE, FB_POLYGON, "
             "FB_CMOV, FB_PASSTHROUGH in the VGX's gl/feed.h) are not in the sources this "
             "emulator follows, so the buffer cannot be reproduced; use pick/gselect or "
             "mapw for what feedback was used for")
feedback = not_emulated("feedback", _FEEDBACK)
endfeedback = not_emulated("endfeedback", _FEEDBACK)
