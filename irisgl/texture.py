"""Texture mapping calls (docs/semantics.md §16): texdef2d, tevdef, tevbind,
texbind, t2*/t3*/t4*, texgen, scrsubdivide.

Texturing happens only while a texture != 0 is bound to TX_TEXTURE_0 and an
environment != 0 to TV_ENV0, in RGB mode.  Texture coordinates are
interpolated with perspective correction (the issue's rule for this
emulator; the VGX itself interpolated them linearly in screen space and
offered scrsubdivide to hide it, which is accepted here as a no-op:
perspective-correct interpolation is the limit of subdivision).  Mipmap
levels are chosen per triangle (docs/decisions.md).
"""
import numpy as np

from vgx_emulator import texture as T
from vgx_emulator.errors import fail
from vgx_emulator.geometry.batch import EV_TEX

from . import constants as K
from ._current import NOT_GIVEN, glcall, integer, machine, num, token, vec, win

__all__ = ["texdef2d", "tevdef", "tevbind", "texbind", "texgen", "scrsubdivide"] + \
    [f"t{n}{t}" for n in (2, 3, 4) for t in "sifd"]

_NO = NOT_GIVEN         # "argument not given": the checked path reports the arity


def _props(call, props, table):
    """Token list -> {token: values}; ends at TX_NULL / TV_NULL (0).  The
    call's ``np`` is not used to cut the list: texdef(3G) and tevdef(3G) say
    it only makes the call more efficient over a network connection (and is
    ignored when 0), and programs passed np = 1 with a longer list."""
    if props is None:
        return {}
    try:
        vals = [float(v) for v in props]
    except (TypeError, ValueError):
        fail(call, "props is not a list of numbers", "tokens and values ending with 0")
    out = {}
    i = 0
    while i < len(vals) and vals[i] != 0.0:
        tok = int(vals[i])
        if tok not in table:
            fail(call, f"unknown property {vals[i]:g}", "a TX_*/TV_* token")
        n = table[tok]
        if i + 1 + n > len(vals):
            fail(call, f"property {tok:#x} needs {n} values", "give them before the 0")
        out[tok] = vals[i + 1:i + 1 + n]
        i += 1 + n
    return out


@glcall
def texdef2d(index, nc, width, height, image, np, props):
    """texdef2d(3G): define texture ``index`` (> 0) of nc components
    (1 I, 2 IA, 3 RGB, 4 RGBA), width x height texels; the image is copied."""
    win("texdef2d")             # a window first, as every drawing-state call
    i = integer("texdef2d", index, "index")
    nc = integer("texdef2d", nc, "components")
    w = integer("texdef2d", width, "width")
    h = integer("texdef2d", height, "height")
    if i <= 0:
        fail("texdef2d", f"index {i}", "index 0 is the null texture; use 1 and up")
    if nc not in (1, 2, 3, 4):
        fail("texdef2d", f"{nc} components", "1, 2, 3 or 4")
    if not (1 <= w <= 4096 and 1 <= h <= 4096):
        fail("texdef2d", f"size {w}x{h}", "1..4096 texels each way")
    integer("texdef2d", np, "np")
    p = _props("texdef2d", props, T.TEX_PROPS)
    p = {k: int(v[0]) if len(v) == 1 else v for k, v in p.items()}
    for key, allowed in ((T.TX_MINFILTER, T.MIN_FILTERS), (T.TX_MAGFILTER, T.MAG_FILTERS)):
        if key in p and p[key] not in allowed:
            fail("texdef2d", f"filter {p[key]:#x} not valid for {key:#x}", "a TX_* filter")
    for key in (T.TX_WRAP, T.TX_WRAP_S, T.TX_WRAP_T, T.TX_WRAP_R):
        if key in p and p[key] not in T.WRAPS:
            fail("texdef2d", f"wrap {p[key]:#x}", "TX_REPEAT, TX_CLAMP or TX_SELECT")
    try:
        rgba = T.unpack_image(nc, w, h, image)
    except (ValueError, TypeError) as e:
        fail("texdef2d", f"image: {e}", "uint32 words per texdef(3G), bytes, or (h, w, nc)")
    machine.flush_all()
    machine.textures[i] = T.Texture(nc, rgba, p)


@glcall
def tevdef(index, np, props):
    """tevdef(3G): define texture environment ``index`` (TV_MODULATE default,
    TV_DECAL, TV_BLEND with TV_COLOR r g b a)."""
    win("tevdef")             # a window first, as every drawing-state call
    i = integer("tevdef", index, "index")
    if i <= 0:
        fail("tevdef", f"index {i}", "index 0 is the null environment; use 1 and up")
    table = {T.TV_MODULATE: 0, T.TV_BLEND: 0, T.TV_DECAL: 0, T.TV_ALPHA: 0, T.TV_COLOR: 4,
             0x300: 1}
    integer("tevdef", np, "np")
    p = _props("tevdef", props, table)
    mode = T.TV_MODULATE
    for m in (T.TV_DECAL, T.TV_BLEND, T.TV_ALPHA, T.TV_MODULATE):
        if m in p:
            mode = m
    colour = tuple(p.get(T.TV_COLOR, (1.0, 1.0, 1.0, 1.0)))
    machine.flush_all()
    machine.environments[i] = T.Environment(mode, colour)


@glcall
def tevbind(target, index):
    """tevbind(3G): bind environment ``index`` (0 = none) to TV_ENV0."""
    w = win("tevbind")
    token("tevbind", target, {K.TV_ENV0: "TV_ENV0"}, "target")
    i = integer("tevbind", index, "index")
    machine.state_change(w)
    w.st.tev = i if i in machine.environments else 0


@glcall
def texbind(target, index):
    """texbind(3G): bind texture ``index`` (0 = none) to TX_TEXTURE_0."""
    w = win("texbind")
    token("texbind", target, {K.TX_TEXTURE_0: "TX_TEXTURE_0"}, "target")
    i = integer("texbind", index, "index")
    machine.state_change(w)
    w.st.texture = i if i in machine.textures else 0


_TG_MODES = {K.TG_OFF: "TG_OFF", K.TG_ON: "TG_ON", K.TG_CONTOUR: "TG_CONTOUR",
             K.TG_LINEAR: "TG_LINEAR", K.TG_SPHEREMAP: "TG_SPHEREMAP"}


@glcall
def texgen(coord, mode, params):
    """texgen(3G): define (TG_LINEAR: object-space plane; TG_CONTOUR: eye-space
    plane, taken through the ModelView current now; TG_SPHEREMAP), then enable
    with TG_ON or disable with TG_OFF, per coordinate TX_S..TX_Q."""
    w = win("texgen")
    c = token("texgen", coord, {K.TX_S: "TX_S", K.TX_T: "TX_T", K.TX_R: "TX_R",
                                K.TX_Q: "TX_Q"}, "coordinate")
    m = token("texgen", mode, _TG_MODES, "mode")
    gen = dict(w.st.texgen)
    if m in (K.TG_ON, K.TG_OFF):
        if c not in gen:
            if m == K.TG_ON:
                fail("texgen", "TG_ON before the coordinate was defined",
                     "define it with TG_LINEAR, TG_CONTOUR or TG_SPHEREMAP first")
            return
        mode0, plane, _ = gen[c]
        gen[c] = (mode0, plane, m == K.TG_ON)
    else:
        plane = np.zeros(4)
        if m in (K.TG_LINEAR, K.TG_CONTOUR):
            plane = np.array(vec("texgen", params, 4, "plane"))
            if m == K.TG_CONTOUR:
                mv = w.st.matrices.modelview_matrix()
                plane = np.linalg.pinv(mv) @ plane
        enabled = gen.get(c, (0, 0, False))[2]
        gen[c] = (m, plane, enabled)
    machine.state_change(w)
    w.st.texgen = gen


@glcall
def scrsubdivide(mode, params):
    """scrsubdivide(3G): accepted; texture coordinates are already
    perspective-correct (see the module docstring)."""
    token("scrsubdivide", mode, {K.SS_OFF: "SS_OFF", K.SS_DEPTH: "SS_DEPTH"}, "mode")


# -- t*(): texture coordinates (allowed inside bgn/end) --------------------
# plain functions with the fast path of primitives.py's per-vertex calls:
# convert, append one EV_TEX event, set the state; anything else takes the
# checked path
def _t_checker(name, n):
    def checked(v):
        w = win(name)
        p = vec(name, v, n, "texture coordinate")
        machine.set_texcoord(w, p + (0.0, 1.0)[n - 2:])
    checked.__name__ = checked.__qualname__ = name
    return glcall(checked, inside=True)


_CHECKED = {f"t{n}{t}": _t_checker(f"t{n}{t}", n) for n in (2, 3, 4) for t in "sifd"}


def _t_slow(name, v, more):
    _CHECKED[name](*([] if v is _NO else [v]), *more)


def t2s(v=_NO, *more):
    """t2s(3G): texture coordinate of 2 shorts for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), 0.0, 1.0))
    except Exception:
        _t_slow("t2s", v, more)


def t2i(v=_NO, *more):
    """t2i(3G): texture coordinate of 2 longs for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), 0.0, 1.0))
    except Exception:
        _t_slow("t2i", v, more)


def t2f(v=_NO, *more):
    """t2f(3G): texture coordinate of 2 floats for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), 0.0, 1.0))
    except Exception:
        _t_slow("t2f", v, more)


def t2d(v=_NO, *more):
    """t2d(3G): texture coordinate of 2 doubles for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), 0.0, 1.0))
    except Exception:
        _t_slow("t2d", v, more)


def t3s(v=_NO, *more):
    """t3s(3G): texture coordinate of 3 shorts for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), 1.0))
    except Exception:
        _t_slow("t3s", v, more)


def t3i(v=_NO, *more):
    """t3i(3G): texture coordinate of 3 longs for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), 1.0))
    except Exception:
        _t_slow("t3i", v, more)


def t3f(v=_NO, *more):
    """t3f(3G): texture coordinate of 3 floats for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), 1.0))
    except Exception:
        _t_slow("t3f", v, more)


def t3d(v=_NO, *more):
    """t3d(3G): texture coordinate of 3 doubles for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), 1.0))
    except Exception:
        _t_slow("t3d", v, more)


def t4s(v=_NO, *more):
    """t4s(3G): texture coordinate of 4 shorts for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r, q = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), float(q)))
    except Exception:
        _t_slow("t4s", v, more)


def t4i(v=_NO, *more):
    """t4i(3G): texture coordinate of 4 longs for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r, q = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), float(q)))
    except Exception:
        _t_slow("t4i", v, more)


def t4f(v=_NO, *more):
    """t4f(3G): texture coordinate of 4 floats for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r, q = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), float(q)))
    except Exception:
        _t_slow("t4f", v, more)


def t4d(v=_NO, *more):
    """t4d(3G): texture coordinate of 4 doubles for the following vertices."""
    try:
        if more:
            raise TypeError
        s, t, r, q = v
        m = machine
        m.E.extend((len(m.P), EV_TEX, float(s), float(t), float(r), float(q)))
    except Exception:
        _t_slow("t4d", v, more)
