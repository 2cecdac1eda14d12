"""Cross-check against Mesa: the same random scenes through this emulator and
through Mesa's software OpenGL (OSMesa), compared pixel by pixel.

OpenGL 1.x descends from IRIS GL, and for the per-fragment operations both
define, the two must agree:

==========================  ============================================
IRIS GL                     OpenGL (legacy context)
==========================  ============================================
zfunction(ZF_*)             glDepthFunc(GL_NEVER .. GL_ALWAYS), same order
stencil(on, ref, func,      glStencilFunc(func, ref, mask) -- ``ref`` on
  mask, fail, pass, zpass)  the left in both; glStencilOp(fail, pass,
                            zpass) while the z-buffer is on (ST_* and
                            GL_KEEP..GL_INVERT in the same order; INCR and
                            DECR saturate in both)
swritemask / sclear         glStencilMask / glClearStencil + glClear
blendfunction(BF_*, BF_*)   glBlendFunc(GL_ZERO, GL_ONE, GL_DST_COLOR, ...)
defpattern(32) + setpattern glPolygonStipple + GL_POLYGON_STIPPLE
acbuf(AC_*)                 glAccum(GL_LOAD/ACCUM/MULT/ADD/RETURN)
logicop(LO_*)               glLogicOp(GL_CLEAR .. GL_SET), same order
afunction(ref, AF_*)        glAlphaFunc(GL_*, ref / 255)
wmpack (0x00/0xFF bytes)    glColorMask
==========================  ============================================

How the two set-ups are made to agree:

* Matrices: IRIS GL's row-vector Matrix has the same 16 floats in memory as
  the OpenGL column-major matrix (docs/semantics.md §1), so the projection that
  ``ortho`` builds here is handed to Mesa as it is stored:
  ``glLoadMatrixf(getmatrix())``, with an identity ModelView.
* Pixel centres: this emulator puts pixel (i, j)'s centre at window
  (i, j) and its viewport mapping carries a -0.5 (geometry/viewport.py);
  OpenGL samples at (i + 0.5, j + 0.5) with no offset in its viewport
  mapping.  The two half-pixel shifts cancel: with the *same* matrix an
  object point lands on the centre of the same pixel in both.  So no extra
  half-pixel offset is added to the GL projection.
* Depth: the VGX z range is signed 24-bit (docs/semantics.md §5); Mesa's is unsigned
  24-bit.  ``zs = -0x800000 + (zn + 1) / 2 * 0xFFFFFF`` is the same affine map
  in both, so stored z values differ by exactly 0x800000 (up to rounding).
  Scenes use a few well separated z levels so that rounding never reorders
  them; ties (equal levels) are exact ties in both.
* Coverage: most scenes are made of axis-aligned rectangles with edges on
  pixel boundaries (subpixel(TRUE), corners at half-integers), where no pixel
  centre lies on an edge and coverage is independent of the fill rule.
  Random-triangle scenes use snapped integer vertices (the VGX default): a
  pixel centre exactly on an edge is then decided by each implementation's
  fill rule (this emulator: left-bottom, scan/fixed.py).  Those tests
  compute the set of pixels whose centre lies on an edge and require every
  difference to be inside it (and count the differences).
* Flat shading: IRIS GL takes the colour of the last vertex of a polygon
  (docs/semantics.md §3), OpenGL the first vertex of a GL_POLYGON; the GL polygon is
  issued starting from IRIS GL's last vertex (same polygon, same colour).
  Triangle strips use the last vertex in both.
* The window is at the screen origin, so IRIS GL's screen-aligned patterns
  and GL's window-relative stipple have the same phase.

Only the colour, z and stencil banks are compared (and the colour bank after
acbuf(AC_RETURN)); rounding differences are bounded per test.  Fixed seeds.

Needs Mesa's OSMesa (Debian: ``libosmesa6``) and PyOpenGL (PyPI:
``PyOpenGL``); without them the module is skipped (``pytest -rs`` shows why).
"""
import os
import sys

import numpy as np
import pytest


# -- OSMesa context (module level: skip cleanly when unavailable) -------------------
def _osmesa_context(w, h):
    """(GL module, buffer) with a legacy OSMesa context current, or raise."""
    if "OpenGL" in sys.modules and os.environ.get("PYOPENGL_PLATFORM") != "osmesa":
        raise RuntimeError("PyOpenGL was already imported for another platform "
                           f"({os.environ.get('PYOPENGL_PLATFORM')!r}); "
                           "run with PYOPENGL_PLATFORM=osmesa")
    os.environ["PYOPENGL_PLATFORM"] = "osmesa"
    from OpenGL import GL, arrays, osmesa
    ctx = osmesa.OSMesaCreateContextExt(osmesa.OSMESA_RGBA, 24, 8, 16, None)
    if not ctx:
        raise RuntimeError("OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16) failed")
    buf = arrays.GLubyteArray.zeros((h, w, 4))
    if not osmesa.OSMesaMakeCurrent(ctx, buf, GL.GL_UNSIGNED_BYTE, w, h):
        raise RuntimeError("OSMesaMakeCurrent failed")
    bits = {n: int(GL.glGetIntegerv(q)) for n, q in
            (("depth", GL.GL_DEPTH_BITS), ("stencil", GL.GL_STENCIL_BITS),
             ("accum", GL.GL_ACCUM_RED_BITS), ("alpha", GL.GL_ALPHA_BITS))}
    if bits != {"depth": 24, "stencil": 8, "accum": 16, "alpha": 8}:
        raise RuntimeError(f"OSMesa context has {bits}; need 24/8/16/8")
    return GL, osmesa, ctx, buf


W = H = 64
try:
    GL, _osmesa, _CTX, _BUF = _osmesa_context(W, H)
except Exception as e:  # ImportError, missing libOSMesa, context failure
    _reason = (f"Mesa cross-check skipped: OSMesa/PyOpenGL unavailable "
               f"({type(e).__name__}: {e}). Install libosmesa6 (apt) and PyOpenGL (pip).")
    print(_reason, file=sys.stderr)
    pytest.skip(_reason, allow_module_level=True)

from irisgl import *  # noqa: E402,F401,F403
from irisgl import (AC_ACCUMULATE, AC_ADD, AC_CLEAR_ACCUMULATE, AC_MULT,  # noqa: E402
                    AC_RETURN, AF_ALWAYS, BF_DA, BF_DC, BF_MDA, BF_MDC,
                    BF_MIN_SA_MDA, BF_MSA, BF_MSC, BF_ONE, BF_SA, BF_SC, BF_ZERO, FALSE,
                    FLAT, GOURAUD, LO_SRC, SRC_AUTO, SRC_ZBUFFER, TRUE,
                    RGBmode, acbuf, acsize, afunction, bgnpolygon, bgntmesh,
                    blendfunction, cpack, czclear, defpattern, endpolygon, endtmesh,
                    gconfig, getmatrix, logicop, lrectread, ortho,
                    prefposition, readsource, sclear, setpattern, shademodel, stencil,
                    stensize, subpixel, swritemask, v3f, winopen, wmpack, zbuffer,
                    zfunction, zwritemask)

ZMIN, ZMAX = -0x800000, 0x7FFFFF

# IRIS value -> GL enum
GL_FUNC = [GL.GL_NEVER, GL.GL_LESS, GL.GL_EQUAL, GL.GL_LEQUAL, GL.GL_GREATER,
           GL.GL_NOTEQUAL, GL.GL_GEQUAL, GL.GL_ALWAYS]            # ZF_*, SF_*, AF_*
GL_STOP = [GL.GL_KEEP, GL.GL_ZERO, GL.GL_REPLACE, GL.GL_INCR, GL.GL_DECR, GL.GL_INVERT]
GL_BSRC = {BF_ZERO: GL.GL_ZERO, BF_ONE: GL.GL_ONE, BF_DC: GL.GL_DST_COLOR,
           BF_MDC: GL.GL_ONE_MINUS_DST_COLOR, BF_SA: GL.GL_SRC_ALPHA,
           BF_MSA: GL.GL_ONE_MINUS_SRC_ALPHA, BF_DA: GL.GL_DST_ALPHA,
           BF_MDA: GL.GL_ONE_MINUS_DST_ALPHA, BF_MIN_SA_MDA: GL.GL_SRC_ALPHA_SATURATE}
GL_BDST = {BF_ZERO: GL.GL_ZERO, BF_ONE: GL.GL_ONE, BF_SC: GL.GL_SRC_COLOR,
           BF_MSC: GL.GL_ONE_MINUS_SRC_COLOR, BF_SA: GL.GL_SRC_ALPHA,
           BF_MSA: GL.GL_ONE_MINUS_SRC_ALPHA, BF_DA: GL.GL_DST_ALPHA,
           BF_MDA: GL.GL_ONE_MINUS_DST_ALPHA}
GL_LOGIC = [GL.GL_CLEAR, GL.GL_AND, GL.GL_AND_REVERSE, GL.GL_COPY, GL.GL_AND_INVERTED,
            GL.GL_NOOP, GL.GL_XOR, GL.GL_OR, GL.GL_NOR, GL.GL_EQUIV, GL.GL_INVERT,
            GL.GL_OR_REVERSE, GL.GL_COPY_INVERTED, GL.GL_OR_INVERTED, GL.GL_NAND, GL.GL_SET]
GL_ACCUM = {AC_CLEAR_ACCUMULATE: GL.GL_LOAD, AC_ACCUMULATE: GL.GL_ACCUM,
            AC_MULT: GL.GL_MULT, AC_ADD: GL.GL_ADD, AC_RETURN: GL.GL_RETURN}


def test_enum_orders_match():
    """The IRIS GL constants index the GL tables above by value."""
    assert [ZF_NEVER, ZF_LESS, ZF_EQUAL, ZF_LEQUAL, ZF_GREATER, ZF_NOTEQUAL, ZF_GEQUAL,
            ZF_ALWAYS] == list(range(8))
    assert [SF_NEVER, SF_LESS, SF_EQUAL, SF_LEQUAL, SF_GREATER, SF_NOTEQUAL, SF_GEQUAL,
            SF_ALWAYS] == list(range(8))
    assert [ST_KEEP, ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT] == list(range(6))
    assert [GL_FUNC[i] - GL.GL_NEVER for i in range(8)] == list(range(8))
    assert [GL_LOGIC[i] - GL.GL_CLEAR for i in range(16)] == list(range(16))


# -- scenes: a list of ops, run by two interpreters ---------------------------------
# ("clear", word, zval)                 czclear / glClear (colour+depth)
# ("sclear", s)                         sclear / glClearStencil + glClear
# ("zbuffer", on) ("zfunc", f) ("zwrite", on)
# ("stencil", on, ref, func, mask, fail, pass, zpass)   ("swritemask", m)
# ("blend", s, d) ("logicop", op) ("afunc", ref, func) ("wmpack", mask)
# ("pattern", shorts64 or None) ("shade", FLAT|GOURAUD) ("subpixel", on)
# ("poly", kind, [(x, y, z)...], [word...])   kind "polygon" | "tmesh"
# ("acbuf", iris_op, iris_value, gl_value)


def _zval_to_gl(zval):
    return (zval - ZMIN) / float(0xFFFFFF)


def run_iris(ops, accum=False):
    """Render on the emulator; returns dict(colour uint32, z int64, stencil int64)."""
    from irisgl._current import machine
    prefposition(0, W - 1, 0, H - 1)           # at the screen origin (docs/semantics.md §8)
    winopen("mesa-crosscheck")
    RGBmode()
    stensize(8)
    if accum:
        acsize(16)
    gconfig()
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    shademodel(FLAT)
    pat_index = 0
    for op in ops:
        k = op[0]
        if k == "clear":
            czclear(op[1], op[2])
        elif k == "sclear":
            sclear(op[1])
        elif k == "zbuffer":
            zbuffer(TRUE if op[1] else FALSE)
        elif k == "zfunc":
            zfunction(op[1])
        elif k == "zwrite":
            zwritemask(0xFFFFFF if op[1] else 0)
        elif k == "stencil":
            stencil(*op[1:])
        elif k == "swritemask":
            swritemask(op[1])
        elif k == "blend":
            blendfunction(op[1], op[2])
        elif k == "logicop":
            logicop(op[1])
        elif k == "afunc":
            afunction(op[1], op[2])
        elif k == "wmpack":
            wmpack(op[1])
        elif k == "pattern":
            if op[1] is None:
                setpattern(0)
            else:
                pat_index += 1
                defpattern(pat_index, 32, op[1])
                setpattern(pat_index)
        elif k == "shade":
            shademodel(op[1])
        elif k == "subpixel":
            subpixel(TRUE if op[1] else FALSE)
        elif k == "poly":
            _, kind, verts, cols = op
            (bgnpolygon if kind == "polygon" else bgntmesh)()
            for i, v in enumerate(verts):
                cpack(cols[min(i, len(cols) - 1)])
                v3f(v)
            (endpolygon if kind == "polygon" else endtmesh)()
        elif k == "acbuf":
            acbuf(op[1], op[2])
        else:
            raise ValueError(op)
    colour = lrectread(0, 0, W - 1, H - 1).astype(np.int64)
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, W - 1, H - 1).astype(np.int64)
    readsource(SRC_AUTO)
    machine.flush()
    sten = machine.current.fb.stencil.astype(np.int64).copy()   # inspection only
    return {"colour": colour, "z": z, "stencil": sten, "matrix": getmatrix()}


def run_gl(ops, matrix):
    """Render the same ops through Mesa; same dict, z shifted to the VGX range."""
    g = GL
    g.glViewport(0, 0, W, H)
    g.glMatrixMode(g.GL_PROJECTION)
    g.glLoadMatrixf(np.ascontiguousarray(matrix, np.float32))   # same 16 floats
    g.glMatrixMode(g.GL_MODELVIEW)
    g.glLoadIdentity()
    for cap in (g.GL_DEPTH_TEST, g.GL_STENCIL_TEST, g.GL_BLEND, g.GL_COLOR_LOGIC_OP,
                g.GL_ALPHA_TEST, g.GL_POLYGON_STIPPLE, g.GL_DITHER, g.GL_CULL_FACE,
                g.GL_SCISSOR_TEST, g.GL_LIGHTING, g.GL_TEXTURE_2D):
        g.glDisable(cap)
    g.glShadeModel(g.GL_FLAT)
    g.glDepthFunc(g.GL_LEQUAL)                  # IRIS GL's default zfunction
    g.glDepthMask(g.GL_TRUE)
    g.glColorMask(True, True, True, True)
    g.glStencilMask(0xFF)
    g.glStencilFunc(g.GL_ALWAYS, 0, 0xFF)
    g.glStencilOp(g.GL_KEEP, g.GL_KEEP, g.GL_KEEP)
    g.glBlendFunc(g.GL_ONE, g.GL_ZERO)
    g.glLogicOp(g.GL_COPY)
    # everything is cleared first, as winopen + gconfig leave zeros
    g.glClearColor(0, 0, 0, 0)
    g.glClearDepth(1.0)
    g.glClearStencil(0)
    g.glClearAccum(0, 0, 0, 0)
    g.glClear(g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT | g.GL_STENCIL_BUFFER_BIT
              | g.GL_ACCUM_BUFFER_BIT)
    zon = False
    zmask = True
    cmask = (True,) * 4
    sops = (0, 0, 0)
    for op in ops:
        k = op[0]
        if k == "clear":
            word = op[1]
            g.glColorMask(True, True, True, True)
            g.glDepthMask(True)
            g.glClearColor(*[((word >> (8 * i)) & 0xFF) / 255.0 for i in range(4)])
            g.glClearDepth(_zval_to_gl(op[2]))
            g.glClear(g.GL_COLOR_BUFFER_BIT | g.GL_DEPTH_BUFFER_BIT)
            g.glColorMask(*cmask)
            g.glDepthMask(zmask)
        elif k == "sclear":
            g.glClearStencil(op[1])
            g.glClear(g.GL_STENCIL_BUFFER_BIT)
        elif k == "zbuffer":
            zon = op[1]
            (g.glEnable if zon else g.glDisable)(g.GL_DEPTH_TEST)
        elif k == "zfunc":
            g.glDepthFunc(GL_FUNC[op[1]])
        elif k == "zwrite":
            zmask = bool(op[1])
            g.glDepthMask(zmask)
        elif k == "stencil":
            on, ref, func, mask, sfail, spass, szpass = op[1:]
            (g.glEnable if on else g.glDisable)(g.GL_STENCIL_TEST)
            if on:
                g.glStencilFunc(GL_FUNC[func], ref, mask)
                sops = (sfail, spass, szpass)
        elif k == "swritemask":
            g.glStencilMask(op[1])
        elif k == "blend":
            if (op[1], op[2]) == (BF_ONE, BF_ZERO):
                g.glDisable(g.GL_BLEND)
            else:
                g.glEnable(g.GL_BLEND)
                g.glBlendFunc(GL_BSRC[op[1]], GL_BDST[op[2]])
        elif k == "logicop":
            (g.glDisable if op[1] == LO_SRC else g.glEnable)(g.GL_COLOR_LOGIC_OP)
            g.glLogicOp(GL_LOGIC[op[1]])
        elif k == "afunc":
            (g.glDisable if op[2] == AF_ALWAYS else g.glEnable)(g.GL_ALPHA_TEST)
            g.glAlphaFunc(GL_FUNC[op[2]], op[1] / 255.0)
        elif k == "wmpack":
            m = op[1]
            assert all(((m >> (8 * i)) & 0xFF) in (0, 0xFF) for i in range(4))
            cmask = tuple(bool((m >> (8 * i)) & 0xFF) for i in range(4))
            g.glColorMask(*cmask)
        elif k == "pattern":
            if op[1] is None:
                g.glDisable(g.GL_POLYGON_STIPPLE)
            else:
                g.glEnable(g.GL_POLYGON_STIPPLE)
                g.glPolygonStipple(pattern_to_stipple(op[1]))
        elif k == "shade":
            g.glShadeModel(g.GL_FLAT if op[1] == FLAT else g.GL_SMOOTH)
        elif k == "subpixel":
            pass                                 # GL never snaps; scenes agree on it
        elif k == "poly":
            _, kind, verts, cols = op
            # docs/semantics.md §6: with the z-buffer off IRIS GL applies `pass` where
            # OpenGL applies its dppass (zpass): map it.
            if zon:
                g.glStencilOp(GL_STOP[sops[0]], GL_STOP[sops[1]], GL_STOP[sops[2]])
            else:
                g.glStencilOp(GL_STOP[sops[0]], g.GL_KEEP, GL_STOP[sops[1]])
            cols = [cols[min(i, len(cols) - 1)] for i in range(len(verts))]
            if kind == "polygon":
                # provoking vertex: IRIS GL the last, GL_POLYGON the first
                verts = verts[-1:] + verts[:-1]
                cols = cols[-1:] + cols[:-1]
                g.glBegin(g.GL_POLYGON)
            else:
                g.glBegin(g.GL_TRIANGLE_STRIP)
            for v, c in zip(verts, cols):
                g.glColor4ub(c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF, (c >> 24) & 0xFF)
                g.glVertex3f(*v)
            g.glEnd()
        elif k == "acbuf":
            g.glAccum(GL_ACCUM[op[1]], op[3])
        else:
            raise ValueError(op)
    g.glFinish()
    colour = np.asarray(_BUF).reshape(H, W, 4).copy().view("<u4").reshape(H, W).astype(np.int64)
    z = _read(g.GL_DEPTH_COMPONENT, g.GL_UNSIGNED_INT).astype(np.uint32)
    z = (z >> 8).astype(np.int64) + ZMIN
    sten = _read(g.GL_STENCIL_INDEX, g.GL_UNSIGNED_BYTE).astype(np.int64)
    return {"colour": colour, "z": z, "stencil": sten}


def _read(fmt, typ):
    dtype = np.uint32 if typ == GL.GL_UNSIGNED_INT else np.uint8
    out = np.zeros((H, W), dtype)
    GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
    GL.glReadPixels(0, 0, W, H, fmt, typ, out)
    return out


def pattern_to_stipple(shorts):
    """IRIS GL 32x32 pattern -> glPolygonStipple bytes.  Both run bottom row
    first; IRIS GL's bit 15 of a short is the leftmost pixel, and GL's
    stipple (GL_UNPACK_LSB_FIRST false, the default) takes the most
    significant bit of the first byte as the leftmost: big-endian bytes."""
    GL.glPixelStorei(GL.GL_UNPACK_LSB_FIRST, GL.GL_FALSE)
    b = bytearray()
    for s in shorts:
        b += bytes(((s >> 8) & 0xFF, s & 0xFF))
    return bytes(b)


def render_both(ops, accum=False):
    a = run_iris(ops, accum=accum)
    b = run_gl(ops, a["matrix"])
    return a, b


# -- comparisons ---------------------------------------------------------------
def _where(mask, n=8):
    pts = np.argwhere(mask)[:n]
    return ", ".join(f"({x},{y})" for y, x in pts)


def channel_diff(a, b):
    """Per-channel absolute differences of packed words: (h, w, 4)."""
    ca = np.stack([(a >> (8 * i)) & 0xFF for i in range(4)], -1)
    cb = np.stack([(b >> (8 * i)) & 0xFF for i in range(4)], -1)
    return np.abs(ca - cb)


def assert_same(a, b, what="colour", allowed=None, tol=0, channels=slice(None), label=""):
    """Every pixel agrees (within tol per 8-bit channel for colour, tol for z),
    except where ``allowed`` is True."""
    if what == "colour":
        d = channel_diff(a[what], b[what])[..., channels].max(-1)
    else:
        d = np.abs(a[what] - b[what])
    bad = d > tol
    if allowed is not None:
        bad &= ~allowed
    assert not bad.any(), (
        f"{label}: {what} differs at {int(bad.sum())} pixels outside the allowed set "
        f"(max |diff| {int(d[bad].max())}), e.g. {_where(bad)}; "
        f"emulator {a[what][bad][:4].tolist()} vs Mesa {b[what][bad][:4].tolist()}")
    return d


# -- scene pieces ----------------------------------------------------------------
def rect(x0, y0, x1, y1, z, word):
    """Pixels x0..x1, y0..y1 exactly: corners on pixel boundaries (no centre on
    an edge; needs subpixel(TRUE) so they are not snapped)."""
    return ("poly", "polygon", [(x0 - .5, y0 - .5, z), (x1 + .5, y0 - .5, z),
                                (x1 + .5, y1 + .5, z), (x0 - .5, y1 + .5, z)], [word])


def rand_rect(rng, z, word, minsize=4):
    x0, y0 = rng.integers(-4, W - minsize, 2)
    x1 = x0 + rng.integers(minsize, W // 2)
    y1 = y0 + rng.integers(minsize, H // 2)
    return rect(int(x0), int(y0), int(x1), int(y1), z, word)


def rand_word(rng, alpha=None):
    r, g, b, a = (int(v) for v in rng.integers(0, 256, 4))
    if alpha is not None:
        a = alpha
    return r | g << 8 | b << 16 | a << 24


# well separated z levels in object space (z_ndc = -z with this ortho)
LEVELS = [k / 8.0 for k in range(-7, 8) if k]


def rand_triangle(rng, z, word):
    """Integer (snapped) vertices; about half are large."""
    big = rng.random() < 0.5
    span = W if big else 16
    cx, cy = rng.integers(0, W, 2)
    pts = [(int(np.clip(cx + rng.integers(-span // 2, span // 2 + 1), -2, W + 1)),
            int(np.clip(cy + rng.integers(-span // 2, span // 2 + 1), -2, H + 1)), z)
           for _ in range(3)]
    return ("poly", "polygon", pts, [word])


def on_edge_pixels(ops):
    """Pixels whose centre lies exactly on an edge of a snapped (integer-vertex)
    polygon of the scene: the only pixels the two fill rules may decide
    differently."""
    ys, xs = np.mgrid[0:H, 0:W]
    hit = np.zeros((H, W), bool)
    for op in ops:
        if op[0] != "poly":
            continue
        v = [(p[0], p[1]) for p in op[2]]
        if not all(float(c).is_integer() for p in v for c in p):
            continue
        for (ax, ay), (bx, by) in zip(v, v[1:] + v[:1]):
            dx, dy = bx - ax, by - ay
            cross = dx * (ys - ay) - dy * (xs - ax)
            dot = dx * (xs - ax) + dy * (ys - ay)
            hit |= (cross == 0) & (dot >= 0) & (dot <= dx * dx + dy * dy)
    return hit


# ======================================================================================
# 0. coverage and the pixel-centre mapping
# ======================================================================================
def test_rectangles_cover_the_same_pixels():
    """Edges on pixel boundaries: identical coverage, exact colour."""
    rng = np.random.default_rng(1)
    ops = [("clear", 0, ZMAX), ("subpixel", True)]
    ops += [rand_rect(rng, 0.0, rand_word(rng), minsize=1) for _ in range(20)]
    a, b = render_both(ops)
    assert_same(a, b, "colour", label="rectangles")


@pytest.mark.parametrize("seed", range(4))
def test_snapped_triangles_differ_only_on_edges(seed):
    """Snapped integer vertices (subpixel(FALSE), the VGX default): pixels
    whose centre is on an edge go by each fill rule; no other pixel may
    differ.  Mesa (llvmpipe) turns out to own the same edges as the
    left-bottom rule; the few on-edge differences seen come from triangles
    with a vertex outside the window: Mesa clips them, and the clipped
    vertices, rounded to its 1/256 grid, move the edge off the pixel centre,
    while the emulator rasterizes the unclipped triangle inside its guard
    band."""
    rng = np.random.default_rng(100 + seed)
    ops = [("clear", 0, ZMAX)]
    ops += [rand_triangle(rng, 0.0, rand_word(rng, 255)) for _ in range(12)]
    a, b = render_both(ops)
    edge = on_edge_pixels(ops)
    d = assert_same(a, b, "colour", allowed=edge, label=f"triangles seed {seed}")
    # the bound: at most every on-edge pixel
    assert (d > 0).sum() <= edge.sum()


# ======================================================================================
# 1. depth functions
# ======================================================================================
ZFUNCS = [ZF_NEVER, ZF_LESS, ZF_EQUAL, ZF_LEQUAL, ZF_GREATER, ZF_NOTEQUAL, ZF_GEQUAL,
          ZF_ALWAYS]


def depth_scene(rng, zf, rects):
    zclear_val = int(rng.choice([ZMAX, 0, -0x400000]))
    ops = [("clear", rand_word(rng, 255), zclear_val), ("zbuffer", True)]
    if rects:
        ops.append(("subpixel", True))
    # a base layer written whatever its depth, then the tested function
    ops.append(("zfunc", ZF_ALWAYS))
    for _ in range(4):
        z = float(rng.choice(LEVELS))
        ops.append(rand_rect(rng, z, rand_word(rng, 255)) if rects
                   else rand_triangle(rng, z, rand_word(rng, 255)))
    ops.append(("zfunc", zf))
    for _ in range(10):
        z = float(rng.choice(LEVELS))
        ops.append(rand_rect(rng, z, rand_word(rng, 255)) if rects
                   else rand_triangle(rng, z, rand_word(rng, 255)))
    return ops


@pytest.mark.parametrize("zf", ZFUNCS)
@pytest.mark.parametrize("seed", range(3))
def test_depth_functions_rectangles(zf, seed):
    """ZF_* vs GL_NEVER..GL_ALWAYS, constant-depth rectangles with ties:
    colour exact, stored z within 1 unit of 2**-24 (Mesa's float depth path)."""
    rng = np.random.default_rng(1000 * zf + seed)
    ops = depth_scene(rng, zf, rects=True)
    a, b = render_both(ops)
    assert_same(a, b, "colour", label=f"zfunction {zf}")
    assert_same(a, b, "z", tol=1, label=f"zfunction {zf}")


@pytest.mark.parametrize("zf", [ZF_LESS, ZF_LEQUAL, ZF_GREATER, ZF_NOTEQUAL])
def test_depth_functions_triangles(zf):
    """Snapped triangles at constant depths: differences only on edges."""
    rng = np.random.default_rng(77 + zf)
    ops = depth_scene(rng, zf, rects=False)
    a, b = render_both(ops)
    edge = on_edge_pixels(ops)
    assert_same(a, b, "colour", allowed=edge, label=f"zfunction {zf}")
    assert_same(a, b, "z", tol=1, allowed=edge, label=f"zfunction {zf}")


@pytest.mark.parametrize("zf", [ZF_LESS, ZF_GREATER])
def test_depth_sloped_planes(zf):
    """Two full-window planes of different slopes cross: z is interpolated
    (emulator in float64, Mesa in float32), so the result may differ only
    where the two depths are within a few units of 2**-24."""
    ops = [("clear", 0xFF000000, ZMAX), ("zbuffer", True), ("subpixel", True),
           ("zfunc", ZF_ALWAYS)]
    p1 = [(-.5, -.5, -0.6), (W - .5, -.5, 0.7), (W - .5, H - .5, 0.5), (-.5, H - .5, -0.8)]
    p2 = [(-.5, -.5, 0.55), (W - .5, -.5, -0.45), (W - .5, H - .5, -0.3), (-.5, H - .5, 0.2)]
    # split each quad into two triangles so the planes are exact
    for p, word in ((p1, 0xFF0000FF), (p2, 0xFF00FF00)):
        ops.append(("poly", "polygon", [p[0], p[1], p[2]], [word]))
        ops.append(("poly", "polygon", [p[0], p[2], p[3]], [word]))
        if word == 0xFF0000FF:
            ops.append(("zfunc", zf))
    a, b = render_both(ops)
    # analytic z of each plane at the pixel centres (object z -> zn = -z)
    ys, xs = np.mgrid[0:H, 0:W].astype(float)

    def plane_z(p):
        za = np.zeros((H, W))
        for tri in ((p[0], p[1], p[2]), (p[0], p[2], p[3])):
            (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = tri
            m = np.array([[x0, y0, 1], [x1, y1, 1], [x2, y2, 1]])
            c = np.linalg.solve(m, [z0, z1, z2])
            za_t = c[0] * xs + c[1] * ys + c[2]
            # barycentric inside test
            den = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
            l0 = ((y1 - y2) * (xs - x2) + (x2 - x1) * (ys - y2)) / den
            l1 = ((y2 - y0) * (xs - x2) + (x0 - x2) * (ys - y2)) / den
            inside = (l0 >= -1e-9) & (l1 >= -1e-9) & (1 - l0 - l1 >= -1e-9)
            za = np.where(inside, za_t, za)
        return za * 0x7FFFFF
    near_tie = np.abs(plane_z(p1) - plane_z(p2)) < 64
    assert near_tie.sum() < 0.1 * W * H
    assert_same(a, b, "colour", allowed=near_tie, label="sloped planes")
    assert_same(a, b, "z", tol=4, label="sloped planes")


# ======================================================================================
# 2. stencil functions and operations (z-buffer on), and docs/semantics.md §6 (z-buffer off)
# ======================================================================================
SFUNCS = [SF_NEVER, SF_LESS, SF_EQUAL, SF_LEQUAL, SF_GREATER, SF_NOTEQUAL, SF_GEQUAL,
          SF_ALWAYS]
SOPS = [ST_KEEP, ST_ZERO, ST_REPLACE, ST_INCR, ST_DECR, ST_INVERT]


def stencil_scene(rng, sf, zbuf=True, npolys=14):
    ops = [("clear", rand_word(rng, 255), ZMAX), ("subpixel", True),
           ("zbuffer", zbuf), ("zfunc", ZF_LEQUAL)]
    # a base of stencil values near both ends (to exercise saturation)
    ops.append(("sclear", int(rng.choice([0, 1, 254, 255, 128]))))
    for _ in range(3):
        ops.append(("stencil", TRUE, int(rng.integers(0, 256)), SF_ALWAYS, 0xFF,
                    ST_KEEP, ST_REPLACE, ST_REPLACE))
        ops.append(rand_rect(rng, float(rng.choice(LEVELS)), rand_word(rng, 255)))
    for i in range(npolys):
        if rng.random() < 0.2:
            ops.append(("swritemask", int(rng.choice([0xFF, 0x0F, 0xF0, 0x01, 0]))))
        ref = int(rng.choice([0, 1, 2, 127, 128, 254, 255, 300, 511, int(rng.integers(0, 256))]))
        mask = int(rng.choice([0xFF, 0xFF, 0x0F, 0xF0, 0x81]))
        func = sf if rng.random() < 0.75 else int(rng.choice(SFUNCS))
        ops.append(("stencil", TRUE, ref, func, mask,
                    *(int(o) for o in rng.choice(SOPS, 3))))
        ops.append(rand_rect(rng, float(rng.choice(LEVELS)), rand_word(rng, 255)))
    return ops


@pytest.mark.parametrize("sf", SFUNCS)
@pytest.mark.parametrize("seed", range(3))
def test_stencil_functions_and_operations(sf, seed):
    """stencil(3G) vs glStencilFunc/glStencilOp with the z-buffer on:
    colour, z and stencil banks exact."""
    rng = np.random.default_rng(2000 + 10 * sf + seed)
    ops = stencil_scene(rng, sf)
    a, b = render_both(ops)
    lab = f"stencil func {sf} seed {seed}"
    assert_same(a, b, "stencil", label=lab)
    assert_same(a, b, "colour", label=lab)
    assert_same(a, b, "z", tol=1, label=lab)


@pytest.mark.parametrize("op", SOPS)
def test_stencil_each_operation_saturates_like_gl(op):
    """Every operation in each of the three slots, drawn 3 times over a
    stencil of 0/1/254/255 bands: INCR/DECR saturate in both."""
    ops = [("clear", 0xFF000000, ZMAX), ("subpixel", True), ("zbuffer", True),
           ("sclear", 0), ("stencil", TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_REPLACE,
                           ST_REPLACE)]
    for i, s in enumerate((0, 1, 254, 255)):
        ops += [("stencil", TRUE, s, SF_ALWAYS, 0xFF, ST_KEEP, ST_REPLACE, ST_REPLACE),
                rect(16 * i, 0, 16 * i + 15, H - 1, 0.5, 0xFF000000)]
    # three horizontal bands: the stencil fails / passes with z failing / both pass
    for _ in range(3):
        ops += [("stencil", TRUE, 0, SF_NEVER, 0xFF, op, ST_KEEP, ST_KEEP),
                rect(0, 0, W - 1, 20, 0.0, 0xFF0000FF),
                ("stencil", TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, op, ST_KEEP),
                rect(0, 21, W - 1, 41, -0.75, 0xFF00FF00),     # behind: z fails
                ("stencil", TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, op),
                rect(0, 42, W - 1, H - 1, 0.75, 0xFFFF0000)]
    a, b = render_both(ops)
    assert_same(a, b, "stencil", label=f"op {op}")
    assert_same(a, b, "colour", label=f"op {op}")


@pytest.mark.parametrize("seed", range(3))
def test_stencil_with_zbuffer_off_maps_pass_to_gl_zpass(seed):
    """docs/semantics.md §6: with the z-buffer off IRIS GL applies `pass` (OpenGL its
    dppass).  Under that mapping the results are identical."""
    rng = np.random.default_rng(3000 + seed)
    ops = stencil_scene(rng, int(rng.choice(SFUNCS)), zbuf=False)
    a, b = render_both(ops)
    assert_same(a, b, "stencil", label=f"z off seed {seed}")
    assert_same(a, b, "colour", label=f"z off seed {seed}")


# ======================================================================================
# 3. blending factors
# ======================================================================================
SRC_FACTORS = [BF_ZERO, BF_ONE, BF_DC, BF_MDC, BF_SA, BF_MSA, BF_DA, BF_MDA, BF_MIN_SA_MDA]
DST_FACTORS = [BF_ZERO, BF_ONE, BF_SC, BF_MSC, BF_SA, BF_MSA, BF_DA, BF_MDA]


def blend_scene(rng, s, d, layers=1):
    ops = [("clear", rand_word(rng), ZMAX), ("subpixel", True)]
    for _ in range(6):                     # an opaque-ish random destination
        ops.append(rand_rect(rng, 0.0, rand_word(rng)))
    ops.append(("blend", s, d))
    # blended rectangles that do not overlap each other: one blend per pixel
    for i in range(layers):
        for j in range(4):
            x0, y0 = 16 * j, 16 * i
            ops.append(rect(x0 + int(rng.integers(0, 3)), y0 + int(rng.integers(0, 3)),
                            x0 + 15 - int(rng.integers(0, 3)),
                            y0 + 15 - int(rng.integers(0, 3)), 0.0, rand_word(rng)))
    return ops


@pytest.mark.parametrize("s", SRC_FACTORS)
@pytest.mark.parametrize("d", DST_FACTORS)
def test_blend_factors(s, d):
    """blendfunction vs glBlendFunc, every legal pair, random colours and
    alphas over a random destination: each channel within 1 (Mesa blends in
    8-bit fixed point, the emulator in floating point, both round).
    BF_MIN_SA_MDA: OpenGL's GL_SRC_ALPHA_SATURATE uses factor 1 for alpha;
    the emulator applies min(SA, 1-DA) to alpha too (blendfunction(3G) gives the
    factor for RGBA and is silent on alpha), so alpha is not compared there."""
    rng = np.random.default_rng(4000 + 16 * s + d)
    ops = blend_scene(rng, s, d, layers=4)
    a, b = render_both(ops)
    ch = slice(0, 3) if s == BF_MIN_SA_MDA else slice(None)
    assert_same(a, b, "colour", tol=1, channels=ch, label=f"blend ({s}, {d})")


@pytest.mark.parametrize("seed", range(3))
def test_blend_additive_layers(seed):
    """Heidmann's (BF_ONE, BF_ONE) over overlapping layers: saturating sums,
    exact."""
    rng = np.random.default_rng(4500 + seed)
    ops = [("clear", 0, ZMAX), ("subpixel", True), ("blend", BF_ONE, BF_ONE)]
    ops += [rand_rect(rng, 0.0, rand_word(rng) & 0x7F7F7F7F) for _ in range(12)]
    a, b = render_both(ops)
    assert_same(a, b, "colour", label=f"additive seed {seed}")


def test_blend_min_sa_mda_alpha_differs_from_gl():
    """Documents the one disagreement: alpha under BF_MIN_SA_MDA."""
    ops = [("clear", 0x40000000, ZMAX), ("subpixel", True),
           ("blend", BF_MIN_SA_MDA, BF_ONE), rect(0, 0, W - 1, H - 1, 0.0, 0x80102030)]
    a, b = render_both(ops)
    ea, ga = a["colour"][0, 0] >> 24, b["colour"][0, 0] >> 24
    # emulator: 0x80 * min(0x80/255, 1 - 0x40/255) + 0x40 = 128*0.502 + 64 = 128
    # GL: 0x80 * 1 + 0x40 = 192
    assert (ea, ga) == (128, 192)
    assert_same(a, b, "colour", tol=1, channels=slice(0, 3), label="min_sa_mda rgb")


# ======================================================================================
# 4. polygon stipple vs setpattern
# ======================================================================================
def rand_pattern(rng, density=0.5):
    return [int(v) for v in (rng.random(64 * 16) < density).reshape(64, 16)
            .dot(1 << np.arange(15, -1, -1))]


def test_pattern_bit_order_single_bit():
    """One set bit per row, at the row's index: a diagonal from the lower
    left, in both (MSB of the first byte/short is the leftmost pixel)."""
    shorts = []
    for r in range(32):
        row = 1 << (31 - r)                  # pixel x = r is set
        shorts += [(row >> 16) & 0xFFFF, row & 0xFFFF]
    ops = [("clear", 0, ZMAX), ("subpixel", True), ("pattern", shorts),
           rect(0, 0, W - 1, H - 1, 0.0, 0xFFFFFFFF)]
    a, b = render_both(ops)
    assert_same(a, b, "colour", label="pattern diagonal")
    lit = np.argwhere(a["colour"] != 0)
    assert all((x % 32) == (y % 32) for y, x in lit) and len(lit) == 2 * H


@pytest.mark.parametrize("seed", range(4))
def test_pattern_vs_polygon_stipple(seed):
    """Random 32x32 patterns on random rectangles and snapped triangles,
    with z and stencil on: a 0 bit protects every bank in both."""
    rng = np.random.default_rng(5000 + seed)
    ops = [("clear", rand_word(rng, 255), ZMAX), ("zbuffer", True), ("sclear", 0),
           ("stencil", TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_INCR)]
    for i in range(10):
        if i % 3 == 0:
            ops.append(("pattern", rand_pattern(rng, float(rng.uniform(0.2, 0.8)))))
        if i == 7:
            ops.append(("pattern", None))
        z = float(rng.choice(LEVELS))
        if rng.random() < 0.6:
            ops += [("subpixel", True), rand_rect(rng, z, rand_word(rng, 255))]
        else:
            ops += [("subpixel", False), rand_triangle(rng, z, rand_word(rng, 255))]
    a, b = render_both(ops)
    edge = on_edge_pixels(ops)
    for what in ("colour", "stencil"):
        assert_same(a, b, what, allowed=edge, label=f"pattern seed {seed}")
    assert_same(a, b, "z", tol=1, allowed=edge, label=f"pattern seed {seed}")


# ======================================================================================
# 5. accumulation
# ======================================================================================
def frame_ops(rng):
    ops = [("clear", rand_word(rng, 255), ZMAX)]
    ops += [rand_rect(rng, 0.0, rand_word(rng, 255)) for _ in range(5)]
    return ops


@pytest.mark.parametrize("n", [2, 4, 8])
def test_accumulation_average_of_frames(n):
    """The soft-shadow idiom.  IRIS GL's buffer holds 16-bit integers in pixel
    units: accumulate each frame at 1.0, return at 1/n.  OpenGL's holds
    values in [-1, 1] (Mesa: 16-bit signed normalized): accumulate at 1/n,
    return at 1.0.  Both give round(mean); GL's per-step quantization of
    1/32767 bounds the difference at 1 per channel."""
    rng = np.random.default_rng(6000 + n)
    ops = [("subpixel", True)]
    for i in range(n):
        ops += frame_ops(rng)
        ops.append(("acbuf", AC_CLEAR_ACCUMULATE if i == 0 else AC_ACCUMULATE, 1.0, 1.0 / n))
    ops.append(("acbuf", AC_RETURN, 1.0 / n, 1.0))
    a, b = render_both(ops, accum=True)
    assert_same(a, b, "colour", tol=1, label=f"average of {n}")


@pytest.mark.parametrize("seed", range(3))
def test_accumulation_same_operations(seed):
    """The same acbuf/glAccum operations and values (ACCUMULATE, MULT, ADD,
    RETURN; AC_ADD takes pixel units, GL_ADD [0, 1] units, so value/255).
    The emulator rounds the buffer to integers after every step (faithful:
    the VGX buffer is integer), GL keeps 15 fractional bits: the difference
    is bounded by half a unit per rounding step, plus one for the final
    conversion."""
    rng = np.random.default_rng(6100 + seed)
    ops = [("subpixel", True)]
    steps = 0
    total = 0.0
    for i in range(4):
        ops += frame_ops(rng)
        w = float(rng.choice([0.125, 0.25, 0.375]))
        if total + w > 1.0:
            w = 1.0 - total
        total += w
        ops.append(("acbuf", AC_CLEAR_ACCUMULATE if i == 0 else AC_ACCUMULATE, w, w))
        steps += 1
        if i == 2:
            m = float(rng.choice([0.5, 0.75]))
            ops.append(("acbuf", AC_MULT, m, m))
            total *= m
            steps += 1
    add = int(rng.integers(-40, 41))
    ops.append(("acbuf", AC_ADD, add, add / 255.0))
    steps += 1
    ops.append(("acbuf", AC_RETURN, 1.0, 1.0))
    a, b = render_both(ops, accum=True)
    bound = int(np.ceil(0.5 * steps)) + 1
    assert_same(a, b, "colour", tol=bound, label=f"acbuf ops seed {seed}")
    # and on average much less than the bound (no systematic drift)
    mean = channel_diff(a["colour"], b["colour"]).mean()
    assert mean < 1.0, mean


# ======================================================================================
# 6. more per-fragment operations both define: logicop, afunction, writemask, flat
# ======================================================================================
@pytest.mark.parametrize("lo", range(16))
def test_logicop(lo):
    rng = np.random.default_rng(7000 + lo)
    ops = [("clear", rand_word(rng), ZMAX), ("subpixel", True)]
    ops += [rand_rect(rng, 0.0, rand_word(rng)) for _ in range(4)]
    ops.append(("logicop", lo))
    ops += [rand_rect(rng, 0.0, rand_word(rng)) for _ in range(8)]
    a, b = render_both(ops)
    assert_same(a, b, "colour", label=f"logicop {lo}")


@pytest.mark.parametrize("af", range(8))
def test_afunction_vs_alpha_func(af):
    """Alphas drawn from a small set including the reference itself (ties)."""
    rng = np.random.default_rng(7100 + af)
    ref = int(rng.choice([0, 1, 100, 128, 254, 255]))
    ops = [("clear", 0, ZMAX), ("subpixel", True), ("afunc", ref, af)]
    for _ in range(14):
        alpha = int(np.clip(ref + rng.choice([-1, 0, 0, 1, 50, -50]), 0, 255))
        ops.append(rand_rect(rng, 0.0, rand_word(rng, alpha)))
    a, b = render_both(ops)
    assert_same(a, b, "colour", label=f"afunction {af} ref {ref}")


@pytest.mark.parametrize("mask", [0x00000000, 0xFF0000FF, 0x00FF00FF, 0xFFFFFF00,
                                  0x0000FF00])
def test_writemask_bytes(mask):
    rng = np.random.default_rng(7200 + mask % 1000)
    ops = [("clear", rand_word(rng), ZMAX), ("subpixel", True), ("zbuffer", True)]
    ops += [rand_rect(rng, float(rng.choice(LEVELS)), rand_word(rng)) for _ in range(3)]
    ops.append(("wmpack", mask))
    ops += [rand_rect(rng, float(rng.choice(LEVELS)), rand_word(rng)) for _ in range(6)]
    a, b = render_both(ops)
    assert_same(a, b, "colour", label=f"wmpack {mask:#x}")
    assert_same(a, b, "z", tol=1, label=f"wmpack {mask:#x}")


@pytest.mark.parametrize("seed", range(3))
def test_flat_shading_provoking_vertex(seed):
    """FLAT: polygons take the last vertex's colour in IRIS GL (docs/semantics.md §3),
    the first in a GL_POLYGON: the GL interpreter rotates the vertex list.
    Triangle meshes take the last vertex of each triangle in both."""
    rng = np.random.default_rng(7300 + seed)
    ops = [("clear", 0, ZMAX), ("subpixel", True), ("shade", FLAT)]
    for _ in range(6):
        x0, y0 = (int(v) for v in rng.integers(0, W - 20, 2))
        quad = [(x0 - .5, y0 - .5, 0), (x0 + 15.5, y0 - .5, 0), (x0 + 15.5, y0 + 15.5, 0),
                (x0 - .5, y0 + 15.5, 0)]
        ops.append(("poly", "polygon", quad, [rand_word(rng, 255) for _ in range(4)]))
    # a tmesh strip over the top: 4 triangles with different last vertices
    strip = [(2.5, 40.5, 0), (2.5, 60.5, 0), (20.5, 40.5, 0), (20.5, 60.5, 0),
             (40.5, 40.5, 0), (40.5, 60.5, 0)]
    ops += [("subpixel", True), ("poly", "tmesh", strip,
                                 [rand_word(rng, 255) for _ in range(6)])]
    a, b = render_both(ops)
    # tmesh triangles share diagonals through no pixel centre (x .5 offsets,
    # slopes 20/18): coverage exact
    assert_same(a, b, "colour", label=f"flat seed {seed}")
