"""Primitives and the current colour and normal (docs/semantics.md §3).

bgn/end pairs collect vertices; ``v2*``/``v3*``/``v4*`` take C arrays in the
s/i/f/d flavours (z = 0 and w = 1 where not given).  Old-style calls
(rect, rectf, poly, polf, pnt, move, draw) go through the same stream.
Colours: ``c3f``/``c4f`` take 0.0-1.0, the integer forms 0-255; values above
the maximum are clamped, below 0 clamped to 0 (docs/semantics.md §3); c3* sets
alpha to the maximum.
"""
import math

from vgx_emulator.errors import GLError, fail
from vgx_emulator.geometry.assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH
from vgx_emulator.geometry.batch import EV_BYTE, EV_CPACK, EV_NORMAL, EV_UNIT

from . import constants as K
from ._current import (NOT_GIVEN, boolean, glcall, integer, machine, num, raise_or_report,
                       token, ulong, vec, win)

__all__ = []


def _export(f):
    __all__.append(f.__name__)
    return f


# -- the per-vertex calls ------------------------------------------------------
# A ported program calls v*/n3f/c*/t* once per vertex, so their cost is the
# program's cost.  Each call below is a plain function that does the common
# case in a few bytecodes: unpack and convert its numbers (float() refuses
# anything that is not one), then append them with one C call to the lists
# the machine's handles point at (VGX.rebind: ``V`` extends the positions
# inside bgn/end, ``E``/``EC`` the attribute events; geometry/batch.py says
# what the flush makes of them).  Anything else (no window, outside bgn/end,
# an object being recorded, a longer or odd array, a wrong type or number of
# arguments, colour-map mode) raises before anything was appended, and the
# call takes its checked path: the glcall-wrapped validator below, which
# records it, or raises the GLError (reported in lenient mode).

_NO = NOT_GIVEN         # "argument not given": the checked path reports the arity


def _checked_call(name, args, more):
    """Run the checked version of ``name`` with the arguments as given."""
    _CHECKED[name](*([] if args[0] is _NO else list(args)), *more)


def _vertex_checker(name, n):
    def checked(v):
        w = win(name)
        p = vec(name, v, n, "vertex")
        if n == 2:
            machine.vertex(w, p[0], p[1], 0.0, 1.0, name)
        elif n == 3:
            machine.vertex(w, p[0], p[1], p[2], 1.0, name)
        else:
            machine.vertex(w, p[0], p[1], p[2], p[3], name)
    checked.__name__ = checked.__qualname__ = name
    return glcall(checked, inside=True)


_CHECKED = {f"v{n}{t}": _vertex_checker(f"v{n}{t}", n) for n in (2, 3, 4) for t in "sifd"}


@_export
def v2s(v=_NO, *more):
    """v2s(3G): a vertex of 2 shorts (z = 0, w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y = v
        machine.V((float(x), float(y), 0.0, 1.0))
    except Exception:
        _checked_call("v2s", (v,), more)


@_export
def v2i(v=_NO, *more):
    """v2i(3G): a vertex of 2 longs (z = 0, w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y = v
        machine.V((float(x), float(y), 0.0, 1.0))
    except Exception:
        _checked_call("v2i", (v,), more)


@_export
def v2f(v=_NO, *more):
    """v2f(3G): a vertex of 2 floats (z = 0, w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y = v
        machine.V((float(x), float(y), 0.0, 1.0))
    except Exception:
        _checked_call("v2f", (v,), more)


@_export
def v2d(v=_NO, *more):
    """v2d(3G): a vertex of 2 doubles (z = 0, w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y = v
        machine.V((float(x), float(y), 0.0, 1.0))
    except Exception:
        _checked_call("v2d", (v,), more)


@_export
def v3s(v=_NO, *more):
    """v3s(3G): a vertex of 3 shorts (w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z = v
        machine.V((float(x), float(y), float(z), 1.0))
    except Exception:
        _checked_call("v3s", (v,), more)


@_export
def v3i(v=_NO, *more):
    """v3i(3G): a vertex of 3 longs (w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z = v
        machine.V((float(x), float(y), float(z), 1.0))
    except Exception:
        _checked_call("v3i", (v,), more)


@_export
def v3f(v=_NO, *more):
    """v3f(3G): a vertex of 3 floats (w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z = v
        machine.V((float(x), float(y), float(z), 1.0))
    except Exception:
        _checked_call("v3f", (v,), more)


@_export
def v3d(v=_NO, *more):
    """v3d(3G): a vertex of 3 doubles (w = 1), inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z = v
        machine.V((float(x), float(y), float(z), 1.0))
    except Exception:
        _checked_call("v3d", (v,), more)


@_export
def v4s(v=_NO, *more):
    """v4s(3G): a vertex of 4 shorts, inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z, w = v
        machine.V((float(x), float(y), float(z), float(w)))
    except Exception:
        _checked_call("v4s", (v,), more)


@_export
def v4i(v=_NO, *more):
    """v4i(3G): a vertex of 4 longs, inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z, w = v
        machine.V((float(x), float(y), float(z), float(w)))
    except Exception:
        _checked_call("v4i", (v,), more)


@_export
def v4f(v=_NO, *more):
    """v4f(3G): a vertex of 4 floats, inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z, w = v
        machine.V((float(x), float(y), float(z), float(w)))
    except Exception:
        _checked_call("v4f", (v,), more)


@_export
def v4d(v=_NO, *more):
    """v4d(3G): a vertex of 4 doubles, inside bgn*/end*."""
    try:
        if more:
            raise TypeError
        x, y, z, w = v
        machine.V((float(x), float(y), float(z), float(w)))
    except Exception:
        _checked_call("v4d", (v,), more)



def _n3f_checked(n):
    machine.set_normal(win("n3f"), vec("n3f", n, 3, "normal"))


_n3f_checked.__name__ = _n3f_checked.__qualname__ = "n3f"
_CHECKED["n3f"] = glcall(_n3f_checked, inside=True)


@_export
def n3f(n=_NO, *more):
    """n3f(3G): the current normal, for the following vertices."""
    try:
        if more:
            raise TypeError
        x, y, z = n
        m = machine
        m.E.extend((len(m.P), EV_NORMAL, float(x), float(y), float(z), 0.0))
    except Exception:
        _checked_call("n3f", (n,), more)


# -- colours -----------------------------------------------------------------
# The calls append their components as given (EV_UNIT 0.0-1.0, EV_BYTE
# 0-255, EV_CPACK a word); clamping and scaling happen at the flush,
# in its compiled event pass (geometry/batch.py per_vertex).  ``EC`` is None in
# colour-map mode, where these calls are errors.
def _limit(v, top):
    """v clamped to 0..top; NaN and +-inf pass unclamped (the flush drops
    the primitive with a warning)."""
    return min(max(v, 0.0), top) if -1e300 < v < 1e300 else v


def _rgb_only(call):
    w = win(call)
    if not w.st.rgb:
        fail(call, "RGB colour in colour-map mode", "use color() in cmode, or RGBmode()")
    return w


def _colour_checker(name, n, top):
    def checked(v):
        w = _rgb_only(name)
        p = vec(name, v, n, "colour")
        k = 255.0 / top
        q = [_limit(c, top) * k for c in p]
        machine.set_colour(w, (q[0], q[1], q[2], q[3] if n == 4 else 255.0))
    checked.__name__ = checked.__qualname__ = name
    return glcall(checked, inside=True)


for _n in (3, 4):
    _CHECKED[f"c{_n}f"] = _colour_checker(f"c{_n}f", _n, 1.0)
    _CHECKED[f"c{_n}i"] = _colour_checker(f"c{_n}i", _n, 255.0)
    _CHECKED[f"c{_n}s"] = _colour_checker(f"c{_n}s", _n, 255.0)


@_export
def c3f(c=_NO, *more):
    """c3f(3G): RGB colour, components 0.0-1.0 (clamped); alpha := 255."""
    try:
        if more:
            raise TypeError
        r, g, b = c
        m = machine
        m.EC.extend((len(m.P), EV_UNIT, float(r), float(g), float(b), 1.0))
    except Exception:
        _checked_call("c3f", (c,), more)


@_export
def c3i(c=_NO, *more):
    """c3i(3G): RGB colour, components 0-255 (clamped); alpha := 255."""
    try:
        if more:
            raise TypeError
        r, g, b = c
        m = machine
        m.EC.extend((len(m.P), EV_BYTE, float(r), float(g), float(b), 255.0))
    except Exception:
        _checked_call("c3i", (c,), more)


@_export
def c3s(c=_NO, *more):
    """c3s(3G): RGB colour, components 0-255 (clamped); alpha := 255."""
    try:
        if more:
            raise TypeError
        r, g, b = c
        m = machine
        m.EC.extend((len(m.P), EV_BYTE, float(r), float(g), float(b), 255.0))
    except Exception:
        _checked_call("c3s", (c,), more)


@_export
def c4f(c=_NO, *more):
    """c4f(3G): RGBA colour, components 0.0-1.0 (clamped)."""
    try:
        if more:
            raise TypeError
        r, g, b, a = c
        m = machine
        m.EC.extend((len(m.P), EV_UNIT, float(r), float(g), float(b), float(a)))
    except Exception:
        _checked_call("c4f", (c,), more)


@_export
def c4i(c=_NO, *more):
    """c4i(3G): RGBA colour, components 0-255 (clamped)."""
    try:
        if more:
            raise TypeError
        r, g, b, a = c
        m = machine
        m.EC.extend((len(m.P), EV_BYTE, float(r), float(g), float(b), float(a)))
    except Exception:
        _checked_call("c4i", (c,), more)


@_export
def c4s(c=_NO, *more):
    """c4s(3G): RGBA colour, components 0-255 (clamped)."""
    try:
        if more:
            raise TypeError
        r, g, b, a = c
        m = machine
        m.EC.extend((len(m.P), EV_BYTE, float(r), float(g), float(b), float(a)))
    except Exception:
        _checked_call("c4s", (c,), more)


def _rgbcolor_checked(r, g, b):
    w = _rgb_only("RGBcolor")
    p = [min(max(integer("RGBcolor", v, "component"), 0), 255) for v in (r, g, b)]
    machine.set_colour(w, (float(p[0]), float(p[1]), float(p[2]), 255.0))


def _cpack_checked(word):
    w = _rgb_only("cpack")
    c = ulong(integer("cpack", word, "colour"))
    machine.set_colour(w, (float(c & 0xFF), float((c >> 8) & 0xFF),
                           float((c >> 16) & 0xFF), float((c >> 24) & 0xFF)))


_rgbcolor_checked.__name__ = _rgbcolor_checked.__qualname__ = "RGBcolor"
_cpack_checked.__name__ = _cpack_checked.__qualname__ = "cpack"
_CHECKED["RGBcolor"] = glcall(_rgbcolor_checked, inside=True)
_CHECKED["cpack"] = glcall(_cpack_checked, inside=True)


@_export
def RGBcolor(r=_NO, g=_NO, b=_NO, *more):
    """RGBcolor(3G): 0-255 integer components, clamped; alpha := 255.  An
    error in colour-map mode."""
    try:
        if more:
            raise TypeError
        m = machine                    # | 0: integers only (a float is truncated, checked path)
        m.EC.extend((len(m.P), EV_BYTE, r | 0, g | 0, b | 0, 255))
    except Exception:
        _checked_call("RGBcolor", (r, g, b) if b is not _NO else
                      tuple(a for a in (r, g) if a is not _NO) or (_NO,), more)


@_export
def cpack(word=_NO, *more):
    """cpack(3G): packed 0xAABBGGRR colour (red in the low byte)."""
    try:
        if more:
            raise TypeError
        m = machine                    # & : an integer (a float is truncated, checked path)
        m.EC.extend((len(m.P), EV_CPACK, word & 0xFFFFFFFF, 0, 0, 0))
    except Exception:
        _checked_call("cpack", (word,), more)


@_export
@glcall(inside=True)
def color(index):
    """color(3G): colour index of the current drawmode's framebuffer, clamped
    to 0..2**getplanes()-1 (below 0 is undefined: 0 here, docs/decisions.md);
    an error in RGB mode."""
    w = win("color")
    i = integer("color", index, "colour index")
    if w.st.rgb:
        fail("color", "colour index in RGB mode", "use RGBcolor/cpack/c3f in RGBmode")
    machine.set_colour(w, (float(min(max(i, 0), color_limit(w))), 0.0, 0.0, 0.0))


def color_limit(w):
    """The largest colour index of the current drawmode (color(3G))."""
    from vgx_emulator.framebuffer.layers import planes
    return (1 << planes(w)) - 1


# -- bgn / end ---------------------------------------------------------------
# Each pair is two plain functions around VGX.begin/VGX.end (the one
# implementation, shared with rect, poly, circ ...); ``machine.W`` is the
# current window when the fast handles apply (VGX.rebind).  A GLError from
# the machine is final (it checks before it changes anything); anything else
# (no window, an object being recorded, a trace) takes the checked path.

def _pair_checkers(kind, bgn_name, end_name):
    def bgn():
        machine.begin(win(bgn_name), kind, bgn_name)

    def end():
        machine.end(win(end_name), kind, end_name)
    bgn.__name__ = bgn.__qualname__ = bgn_name
    end.__name__ = end.__qualname__ = end_name
    # bgn is not allowed inside another pair; end must be callable there
    _CHECKED[bgn_name] = glcall(bgn)
    _CHECKED[end_name] = glcall(end, inside=True)


for _k, _nm in ((POLYGON, "polygon"), (TMESH, "tmesh"), (QSTRIP, "qstrip"), (LINE, "line"),
                (CLOSEDLINE, "closedline"), (POINT, "point")):
    _pair_checkers(_k, "bgn" + _nm, "end" + _nm)


@_export
def bgnpolygon(*more):
    """bgnpolygon(3G): start a polygon primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, POLYGON, "bgnpolygon")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgnpolygon"](*more)


@_export
def endpolygon(*more):
    """endpolygon(3G): finish the polygon primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, POLYGON, "endpolygon")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endpolygon"](*more)


@_export
def bgntmesh(*more):
    """bgntmesh(3G): start a tmesh primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, TMESH, "bgntmesh")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgntmesh"](*more)


@_export
def endtmesh(*more):
    """endtmesh(3G): finish the tmesh primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, TMESH, "endtmesh")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endtmesh"](*more)


@_export
def bgnqstrip(*more):
    """bgnqstrip(3G): start a qstrip primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, QSTRIP, "bgnqstrip")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgnqstrip"](*more)


@_export
def endqstrip(*more):
    """endqstrip(3G): finish the qstrip primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, QSTRIP, "endqstrip")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endqstrip"](*more)


@_export
def bgnline(*more):
    """bgnline(3G): start a line primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, LINE, "bgnline")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgnline"](*more)


@_export
def endline(*more):
    """endline(3G): finish the line primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, LINE, "endline")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endline"](*more)


@_export
def bgnclosedline(*more):
    """bgnclosedline(3G): start a closedline primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, CLOSEDLINE, "bgnclosedline")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgnclosedline"](*more)


@_export
def endclosedline(*more):
    """endclosedline(3G): finish the closedline primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, CLOSEDLINE, "endclosedline")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endclosedline"](*more)


@_export
def bgnpoint(*more):
    """bgnpoint(3G): start a point primitive; its vertices follow."""
    try:
        if more:
            raise TypeError
        machine.begin(machine.W, POINT, "bgnpoint")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["bgnpoint"](*more)


@_export
def endpoint(*more):
    """endpoint(3G): finish the point primitive."""
    try:
        if more:
            raise TypeError
        machine.end(machine.W, POINT, "endpoint")
    except GLError as e:
        raise_or_report(e)
    except Exception:
        _CHECKED["endpoint"](*more)



@_export
@glcall(inside=True)
def swaptmesh():
    """swaptmesh(3G): toggle the tmesh replace pointer (no triangle)."""
    machine.swaptmesh(win("swaptmesh"))


# -- old-style primitives ------------------------------------------------------
def _pts(call, arr, dim):
    try:
        pts = [vec(call, p, dim, "point") for p in arr]
    except TypeError:
        fail(call, "point list is not a sequence", "pass n points")
    return [p + (0.0,) * (3 - dim) + (1.0,) for p in pts]


def _rect_calls(fill_, suffix):
    name = ("rectf" if fill_ else "rect") + suffix
    conv = num if suffix == "" else integer

    def r(x1, y1, x2, y2):
        w = win(name)
        a, b, c, d = (conv(name, v) for v in (x1, y1, x2, y2))
        pts = ((a, b, 0.0, 1.0), (c, b, 0.0, 1.0), (c, d, 0.0, 1.0), (a, d, 0.0, 1.0))
        machine.polyline_vertices(w, POLYGON if fill_ else CLOSEDLINE, pts, name)
    r.__name__ = name
    r.__doc__ = (f"{name}(3G): {'filled' if fill_ else 'outlined'} rectangle "
                 "(x1, y1)-(x2, y2) in the z = 0 plane, through the current matrix.")
    return _export(glcall(r))


rect, recti, rects = (_rect_calls(False, s) for s in ("", "i", "s"))
rectf, rectfi, rectfs = (_rect_calls(True, s) for s in ("", "i", "s"))


def _poly_calls(fill_, dim, suffix):
    name = ("polf" if fill_ else "poly") + ("2" if dim == 2 else "") + suffix

    def p(n, parray):
        w = win(name)
        n = integer(name, n, "n")
        try:
            have = len(parray)
        except TypeError:
            fail(name, f"the point array {parray!r} is not a sequence", "pass n points")
        if n < 0 or n > have:
            fail(name, f"n = {n} but the array has {have} points", "0 <= n <= len")
        pts = _pts(name, list(parray)[:n], dim)
        if fill_ and n > 256:
            fail(name, f"{n} vertices", "at most 256 (GD_NVERTEX_POLY)")
        machine.polyline_vertices(w, POLYGON if fill_ else CLOSEDLINE, pts, name)
    p.__name__ = name
    p.__doc__ = (f"{name}(3G): {'filled' if fill_ else 'outlined'} polygon of n "
                 f"{dim}-D points.")
    return _export(glcall(p))


for _f in (False, True):
    for _d in (2, 3):
        for _s in ("", "i", "s"):
            _c = _poly_calls(_f, _d, _s)
            globals()[_c.__name__] = _c


def _point_checker(prefix, dim, suffix):
    name = f"{prefix}{'2' if dim == 2 else ''}{suffix}"
    conv = num if suffix == "" else integer

    def call(*args):
        w = win(name)
        if len(args) != dim:
            fail(name, f"{len(args)} coordinates", f"it takes {dim}")
        c = tuple(conv(name, a) for a in args)
        p = (float(c[0]), float(c[1]), float(c[2]) if dim == 3 else 0.0, 1.0)
        if prefix == "pnt":
            machine.point(w, p, name)
        elif prefix == "move":
            machine.move(w, p)
        else:
            machine.draw(w, p, name)
    call.__name__ = call.__qualname__ = name
    return glcall(call)


for _p in ("pnt", "move", "draw"):
    for _d in (2, 3):
        for _s in ("", "i", "s"):
            _c = _point_checker(_p, _d, _s)
            _CHECKED[_c.__name__] = _c


def _position(name, args, dim, ints):
    """The (x, y, z, 1) of pnt/move/draw arguments, or None when the call
    must take its checked path (wrong count; a float for an integer call,
    which C truncates)."""
    if len(args) != dim:
        return None
    if ints:
        for a in args:
            if a.__class__ is not int:
                return None
    if len(args) == 3:
        return (float(args[0]), float(args[1]), float(args[2]), 1.0)
    return (float(args[0]), float(args[1]), 0.0, 1.0)


def _point_call(name, args, ints, op):
    """The fast path of pnt*/move*/draw*: VGX.point (a run of pnt calls is
    one point primitive), VGX.move, VGX.draw; the checked path otherwise."""
    args = tuple(a for a in args if a is not _NO)
    try:
        p = _position(name, args, 3 if "2" not in name else 2, ints)
        if p is not None:
            w = machine.W
            if w is not None:
                return op(w, p, name)
    except GLError as e:
        return raise_or_report(e)
    except Exception:
        pass
    return _CHECKED[name](*args)


def _move(w, p, name):
    machine.move(w, p)


@_export
def pnt2(x=_NO, y=_NO, *more):
    """pnt2(3G): one point (x, y: Coords)."""
    return _point_call("pnt2", (x, y) + more, False, machine.point)


@_export
def pnt2i(x=_NO, y=_NO, *more):
    """pnt2i(3G): one point (x, y: Icoords)."""
    return _point_call("pnt2i", (x, y) + more, True, machine.point)


@_export
def pnt2s(x=_NO, y=_NO, *more):
    """pnt2s(3G): one point (x, y: Scoords)."""
    return _point_call("pnt2s", (x, y) + more, True, machine.point)


@_export
def pnt(x=_NO, y=_NO, z=_NO, *more):
    """pnt(3G): one point (x, y, z: Coords)."""
    return _point_call("pnt", (x, y, z) + more, False, machine.point)


@_export
def pnti(x=_NO, y=_NO, z=_NO, *more):
    """pnti(3G): one point (x, y, z: Icoords)."""
    return _point_call("pnti", (x, y, z) + more, True, machine.point)


@_export
def pnts(x=_NO, y=_NO, z=_NO, *more):
    """pnts(3G): one point (x, y, z: Scoords)."""
    return _point_call("pnts", (x, y, z) + more, True, machine.point)


@_export
def move2(x=_NO, y=_NO, *more):
    """move2(3G): set the current graphics position (x, y: Coords)."""
    return _point_call("move2", (x, y) + more, False, _move)


@_export
def move2i(x=_NO, y=_NO, *more):
    """move2i(3G): set the current graphics position (x, y: Icoords)."""
    return _point_call("move2i", (x, y) + more, True, _move)


@_export
def move2s(x=_NO, y=_NO, *more):
    """move2s(3G): set the current graphics position (x, y: Scoords)."""
    return _point_call("move2s", (x, y) + more, True, _move)


@_export
def move(x=_NO, y=_NO, z=_NO, *more):
    """move(3G): set the current graphics position (x, y, z: Coords)."""
    return _point_call("move", (x, y, z) + more, False, _move)


@_export
def movei(x=_NO, y=_NO, z=_NO, *more):
    """movei(3G): set the current graphics position (x, y, z: Icoords)."""
    return _point_call("movei", (x, y, z) + more, True, _move)


@_export
def moves(x=_NO, y=_NO, z=_NO, *more):
    """moves(3G): set the current graphics position (x, y, z: Scoords)."""
    return _point_call("moves", (x, y, z) + more, True, _move)


@_export
def draw2(x=_NO, y=_NO, *more):
    """draw2(3G): a line from the graphics position, which moves there (x, y: Coords)."""
    return _point_call("draw2", (x, y) + more, False, machine.draw)


@_export
def draw2i(x=_NO, y=_NO, *more):
    """draw2i(3G): a line from the graphics position, which moves there (x, y: Icoords)."""
    return _point_call("draw2i", (x, y) + more, True, machine.draw)


@_export
def draw2s(x=_NO, y=_NO, *more):
    """draw2s(3G): a line from the graphics position, which moves there (x, y: Scoords)."""
    return _point_call("draw2s", (x, y) + more, True, machine.draw)


@_export
def draw(x=_NO, y=_NO, z=_NO, *more):
    """draw(3G): a line from the graphics position, which moves there (x, y, z: Coords)."""
    return _point_call("draw", (x, y, z) + more, False, machine.draw)


@_export
def drawi(x=_NO, y=_NO, z=_NO, *more):
    """drawi(3G): a line from the graphics position, which moves there (x, y, z: Icoords)."""
    return _point_call("drawi", (x, y, z) + more, True, machine.draw)


@_export
def draws(x=_NO, y=_NO, z=_NO, *more):
    """draws(3G): a line from the graphics position, which moves there (x, y, z: Scoords)."""
    return _point_call("draws", (x, y, z) + more, True, machine.draw)


@_export
@glcall
def clear():
    """clear(3G): fill viewport ∩ scrmask of every enabled colour buffer with
    the current colour (z and stencil untouched)."""
    machine.clear(win("clear"))


# -- modes ---------------------------------------------------------------------
def _mode_setter(name, field, conv, doc):
    def s(v):
        w = win(name)
        val = conv(name, v)
        machine.state_change(w)
        setattr(w.st, field, val)
    s.__name__ = name
    s.__doc__ = doc
    return _export(glcall(s))


backface = _mode_setter("backface", "backface", boolean,
                        "backface(3G): TRUE removes polygons clockwise on the screen.")
frontface = _mode_setter("frontface", "frontface", boolean,
                         "frontface(3G): TRUE removes counter-clockwise polygons.")
subpixel = _mode_setter("subpixel", "subpixel", boolean,
                        "subpixel(3G): FALSE (VGX default) snaps vertices to pixel "
                        "centres; TRUE keeps sub-pixel positions (docs/decisions.md).")
concave = _mode_setter("concave", "concave", boolean,
                       "concave(3G): TRUE makes concave polygons draw correctly.")


@_export
@glcall
def shademodel(mode):
    """shademodel(3G): FLAT (colour of the last vertex, docs/decisions.md) or GOURAUD."""
    w = win("shademodel")
    m = token("shademodel", mode, {K.FLAT: "FLAT", K.GOURAUD: "GOURAUD"}, "shade model")
    machine.state_change(w)
    w.st.gouraud = m == K.GOURAUD


@_export
@glcall
def getbackface():
    """getbackface(3G): TRUE while backface removal is on."""
    return int(win("getbackface").st.backface)


@_export
@glcall
def getsm():
    """getsm(3G): the shading model, FLAT or GOURAUD."""
    return K.GOURAUD if win("getsm").st.gouraud else K.FLAT


@_export
@glcall
def getcolor():
    """getcolor(3G): the current colour index (colour-map mode; 0 in RGB mode)."""
    st = win("getcolor").st
    return int(st.colour[0] + 0.5) if not st.rgb else 0     # colorf: the index written


@_export
@glcall
def gRGBcolor():
    """gRGBcolor(3G): ``r, g, b = gRGBcolor()``."""
    st = win("gRGBcolor").st
    return tuple(int(round(c)) for c in st.colour[:3])
