"""Primitives and the current colour and normal (docs/semantics.md §3).

bgn/end pairs collect vertices; ``v2*``/``v3*``/``v4*`` take C arrays in the
s/i/f/d flavours (z = 0 and w = 1 where not given).  Old-style calls
(rect, rectf, poly, polf, pnt, move, draw) go through the same stream.
Colours: ``c3f``/``c4f`` take 0.0-1.0, the integer forms 0-255; values above
the maximum are clamped, below 0 clamped to 0 (docs/semantics.md §3); c3* sets
alpha to the maximum.
"""
import math

from vgx_emulator.errors import fail
from vgx_emulator.geometry.assemble import CLOSEDLINE, LINE, POINT, POLYGON, QSTRIP, TMESH

from . import constants as K
from ._current import boolean, glcall, integer, machine, num, token, ulong, vec, win

__all__ = []


def _export(f):
    __all__.append(f.__name__)
    return f


# -- bgn / end ---------------------------------------------------------------
def _pair(kind, bgn_name, end_name):
    def bgn():
        machine.begin(win(bgn_name), kind, bgn_name)

    def end():
        machine.end(win(end_name), kind, end_name)
    bgn.__name__, end.__name__ = bgn_name, end_name
    bgn.__doc__ = f"{bgn_name}(3G): start a {end_name[3:]} primitive."
    end.__doc__ = f"{end_name}(3G): finish the {end_name[3:]} primitive."
    # bgn is not allowed inside another pair; end must be callable there
    return _export(glcall(bgn)), _export(glcall(end, inside=True))


bgnpolygon, endpolygon = _pair(POLYGON, "bgnpolygon", "endpolygon")
bgntmesh, endtmesh = _pair(TMESH, "bgntmesh", "endtmesh")
bgnqstrip, endqstrip = _pair(QSTRIP, "bgnqstrip", "endqstrip")
bgnline, endline = _pair(LINE, "bgnline", "endline")
bgnclosedline, endclosedline = _pair(CLOSEDLINE, "bgnclosedline", "endclosedline")
bgnpoint, endpoint = _pair(POINT, "bgnpoint", "endpoint")


@_export
@glcall(inside=True)
def swaptmesh():
    """swaptmesh(3G): toggle the tmesh replace pointer (no triangle)."""
    machine.swaptmesh(win("swaptmesh"))


# -- vertices ----------------------------------------------------------------
def _vertex_calls():
    made = {}
    for n in (2, 3, 4):
        for t in "sifd":
            name = f"v{n}{t}"

            def make(name=name, n=n):
                def v(a):
                    w = machine.current
                    if w is None:
                        fail(name, "no window is open", "call winopen first")
                    p = vec(name, a, n, "vertex")
                    if n == 2:
                        machine.vertex(w, p[0], p[1], 0.0, 1.0, name)
                    elif n == 3:
                        machine.vertex(w, p[0], p[1], p[2], 1.0, name)
                    else:
                        machine.vertex(w, p[0], p[1], p[2], p[3], name)
                v.__name__ = name
                v.__doc__ = f"{name}(3G): a vertex of {n} coordinates."
                return glcall(v, inside=True)
            made[name] = _export(make())
    return made


globals().update(_vertex_calls())


@_export
@glcall(inside=True)
def n3f(n):
    """n3f(3G): the current normal for the following vertices."""
    machine.set_normal(win("n3f"), vec("n3f", n, 3, "normal"))


# -- colours -----------------------------------------------------------------
def _clamp01(v):
    # NaN and +-inf pass unclamped: the flush drops the primitive with a warning
    return min(max(v, 0.0), 1.0) if -1e300 < v < 1e300 else v


def _rgb_only(call):
    w = win(call)
    if not w.st.rgb:
        fail(call, "RGB colour in colour-map mode", "use color() in cmode, or RGBmode()")
    return w


def _float_colour(name, n):
    def c(v):
        w = _rgb_only(name)
        p = vec(name, v, n, "colour")
        a = _clamp01(p[3]) * 255.0 if n == 4 else 255.0
        machine.set_colour(w, (_clamp01(p[0]) * 255.0, _clamp01(p[1]) * 255.0,
                               _clamp01(p[2]) * 255.0, a))
    c.__name__ = name
    c.__doc__ = f"{name}(3G): RGB{'A' if n == 4 else ''} colour, components 0.0-1.0."
    return _export(glcall(c, inside=True))


def _int_colour(name, n):
    def c(v):
        w = _rgb_only(name)
        p = vec(name, v, n, "colour")
        q = [min(max(v, 0.0), 255.0) if -1e300 < v < 1e300 else v for v in p]
        machine.set_colour(w, (q[0], q[1], q[2], q[3] if n == 4 else 255.0))
    c.__name__ = name
    c.__doc__ = f"{name}(3G): RGB{'A' if n == 4 else ''} colour, components 0-255."
    return _export(glcall(c, inside=True))


c3f = _float_colour("c3f", 3)
c4f = _float_colour("c4f", 4)
c3i = _int_colour("c3i", 3)
c4i = _int_colour("c4i", 4)
c3s = _int_colour("c3s", 3)
c4s = _int_colour("c4s", 4)


@_export
@glcall(inside=True)
def RGBcolor(r, g, b):
    """RGBcolor(3G): 0-255 components, clamped; alpha := 255.  An error in
    colour-map mode."""
    w = _rgb_only("RGBcolor")
    p = [min(max(integer("RGBcolor", v, "component"), 0), 255) for v in (r, g, b)]
    machine.set_colour(w, (float(p[0]), float(p[1]), float(p[2]), 255.0))


@_export
@glcall(inside=True)
def cpack(word):
    """cpack(3G): packed 0xAABBGGRR colour (red in the low byte)."""
    w = _rgb_only("cpack")
    c = ulong(integer("cpack", word, "colour"))
    machine.set_colour(w, (float(c & 0xFF), float((c >> 8) & 0xFF),
                           float((c >> 16) & 0xFF), float((c >> 24) & 0xFF)))


@_export
@glcall(inside=True)
def color(index):
    """color(3G): colour index of the current drawmode's framebuffer, clamped
    to 0..2**getplanes()-1 (below 0 is undefined: 0 here, [S]); an error in
    RGB mode."""
    w = win("color")
    i = integer("color", index, "colour index")
    if w.st.rgb:
        fail("color", "colour index in RGB mode", "use RGBcolor/cpack/c3f in RGBmode")
    machine.set_colour(w, (float(min(max(i, 0), color_limit(w))), 0.0, 0.0, 0.0))


def color_limit(w):
    """The largest colour index of the current drawmode (color(3G))."""
    from vgx_emulator.framebuffer.layers import planes
    return (1 << planes(w)) - 1


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


def _point_calls(prefix, dim, suffix):
    name = f"{prefix}{'2' if dim == 2 else ''}{suffix}"
    conv = num if suffix == "" else integer

    def call(*args):
        w = win(name)
        if len(args) != dim:
            fail(name, f"{len(args)} coordinates", f"it takes {dim}")
        c = tuple(conv(name, a) for a in args)
        p = (float(c[0]), float(c[1]), float(c[2]) if dim == 3 else 0.0, 1.0)
        if prefix == "pnt":
            machine.polyline_vertices(w, POINT, (p,), name)
        elif prefix == "move":
            machine.move(w, p)
        else:
            machine.draw(w, p, name)
    call.__name__ = name
    call.__doc__ = {"pnt": f"{name}(3G): one point.",
                    "move": f"{name}(3G): set the graphics position.",
                    "draw": f"{name}(3G): line from the graphics position; it moves there."
                    }[prefix]
    return _export(glcall(call))


for _p in ("pnt", "move", "draw"):
    for _d in (2, 3):
        for _s in ("", "i", "s"):
            _c = _point_calls(_p, _d, _s)
            globals()[_c.__name__] = _c


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


# -- fast paths for the per-vertex calls ------------------------------------
# A ported program calls v*/n3f/c* once per vertex, so their cost is the
# program's cost.  Each public call below tries the common case inline (a
# window is open, inside bgn/end, attributes unchanged, numbers given) and
# hands anything else to the validating version above, which raises the
# proper GLError (or reports it in lenient mode).  Nothing is changed before
# every value has been converted, so a failed fast path leaves no trace.

class _Slow(Exception):
    pass


def _fast_vertex(slow, n):
    if n == 2:
        def v(a):
            try:
                x, y = a
                win = machine.current
                b = win.batch
                if len(b.akey) >= b.cap or b.open is None:
                    raise _Slow
                p = (float(x), float(y), 0.0, 1.0)
                if b.dirty:
                    b.record_attributes(win.st)
                b.pos += p
                b.akey.append(b.cur)
            except Exception:
                slow(a)
    elif n == 3:
        def v(a):
            try:
                x, y, z = a
                win = machine.current
                b = win.batch
                if len(b.akey) >= b.cap or b.open is None:
                    raise _Slow
                p = (float(x), float(y), float(z), 1.0)
                if b.dirty:
                    b.record_attributes(win.st)
                b.pos += p
                b.akey.append(b.cur)
            except Exception:
                slow(a)
    else:
        def v(a):
            try:
                x, y, z, w = a
                win = machine.current
                b = win.batch
                if len(b.akey) >= b.cap or b.open is None:
                    raise _Slow
                p = (float(x), float(y), float(z), float(w))
                if b.dirty:
                    b.record_attributes(win.st)
                b.pos += p
                b.akey.append(b.cur)
            except Exception:
                slow(a)
    v.__name__ = slow.__name__
    v.__doc__ = slow.__doc__
    v.__wrapped__ = slow
    return v


for _n in (2, 3, 4):
    for _t in "sifd":
        _name = f"v{_n}{_t}"
        globals()[_name] = _fast_vertex(globals()[_name], _n)

_n3f_checked = n3f


def n3f(a):
    """n3f(3G): the current normal for the following vertices."""
    try:
        x, y, z = a
        if machine.recording is not None:
            raise _Slow
        w = machine.current
        st = w.st
        st.normal = (float(x), float(y), float(z))
        st.last_was_normal = True
        w.batch.dirty = True
    except Exception:
        _n3f_checked(a)


def _unit(v):
    v = float(v)
    if -1e300 < v < 1e300:
        return 0.0 if v < 0.0 else (1.0 if v > 1.0 else v)
    return v                      # NaN and +-inf: dropped with a warning at the flush


def _byte(v):
    v = float(v)
    if -1e300 < v < 1e300:
        return 0.0 if v < 0.0 else (255.0 if v > 255.0 else v)
    return v


def _fast_colour(slow, n, conv, k):
    def c(a):
        try:
            if n == 3:
                r, g, b = a
                al = 255.0
            else:
                r, g, b, al = a
                al = conv(al) * k
            w = machine.current
            st = w.st
            if not st.rgb or machine.recording is not None:
                raise _Slow
            st.colour = (conv(r) * k, conv(g) * k, conv(b) * k, al)
            st.last_was_normal = False
            if st.material:
                st.colour_since_bind = True
            w.batch.dirty = True
        except Exception:
            slow(a)
    c.__name__ = slow.__name__
    c.__doc__ = slow.__doc__
    c.__wrapped__ = slow
    return c


c3f = _fast_colour(c3f, 3, _unit, 255.0)
c4f = _fast_colour(c4f, 4, _unit, 255.0)
c3i = _fast_colour(c3i, 3, _byte, 1.0)
c4i = _fast_colour(c4i, 4, _byte, 1.0)
c3s = _fast_colour(c3s, 3, _byte, 1.0)
c4s = _fast_colour(c4s, 4, _byte, 1.0)
