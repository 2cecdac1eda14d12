"""Lines and points (bgnline/bgnclosedline/move/draw, bgnpoint/pnt).

IRIS GL rules (bgnline(3G), subpixel(3G); docs/semantics.md §1):

- a line is one pixel wide; it steps one pixel along its major axis and
  takes, on the minor axis, the pixel nearest the exact line;
- snapped lines (subpixel FALSE, the VGX default) are *closed*: both end
  pixels are drawn, so the joint of two segments is drawn by both;
- sub-pixel lines are *half-open*: the last pixel is not drawn, so a (0,0)-(0,2)
  line fills (0,0) and (0,1) only;
- z and colour are interpolated along the line (Gouraud) or taken from the
  segment's last vertex (FLAT, docs/semantics.md §3).

A point fills the pixel whose centre is nearest.  Patterns do not apply to
lines and points (defpattern(3G)), so their kernels never run the pattern
stage.  Fragments then go through
the same per-fragment operations as triangles (:mod:`raster.fragment`).
"""
import math

from ..jit import kernel
from ..raster import fragment
from ..raster.blend import key_terms

_kernels = {}


def line_kernel(key):
    k = _kernels.get(("line",) + tuple(key))
    if k is None:
        k = _kernels[("line",) + tuple(key)] = _make_line_kernel(*key)
    return k


def point_kernel(key):
    k = _kernels.get(("point",) + tuple(key))
    if k is None:
        k = _kernels[("point",) + tuple(key)] = _make_point_kernel(*key)
    return k


def _fragment(ztest, zwrite, color, cmode, stencil, blend, logic, atest, cmask, dual):
    """The per-fragment function of a line or point variant (no pattern
    stage: defpattern(3G) applies to filled primitives only)."""
    return fragment.fragment_function(ztest, zwrite, color, cmode, stencil, blend, logic,
                                      atest, False, cmask, dual)


def _make_line_kernel(ztest, zwrite, color, gouraud, cmode, twoside,
                      stencil, blend, logic, atest, pattern, cmask, texture, dual):
    key = (ztest, zwrite, color, gouraud, cmode, twoside, stencil, blend, logic, atest,
           pattern, cmask, texture, dual)
    bterms = key_terms(blend)
    frag = _fragment(ztest, zwrite, color, cmode, stencil, blend, logic, atest, cmask, dual)

    @kernel(variant=key)
    def draw_lines(P0, P1, FLAT, closed, planes, ip):
        """P0, P1: (S, 7) rows x, y, z, r, g, b, a; FLAT: (S, 4) colours."""
        bt = fragment.blend_terms(blend, bterms, fragment.params(ip))
        sx0 = ip[fragment.P_SX0]
        sx1 = ip[fragment.P_SX1]
        sy0 = ip[fragment.P_SY0]
        sy1 = ip[fragment.P_SY1]
        for s in range(P0.shape[0]):
            x0 = P0[s, 0]
            y0 = P0[s, 1]
            dx = P1[s, 0] - x0
            dy = P1[s, 1] - y0
            xmajor = abs(dx) >= abs(dy)
            if xmajor:
                a0 = math.floor(x0 + 0.5)
                a1 = math.floor(P1[s, 0] + 0.5)
                span = dx
                start = x0
            else:
                a0 = math.floor(y0 + 0.5)
                a1 = math.floor(P1[s, 1] + 0.5)
                span = dy
                start = y0
            step = 1 if a1 >= a0 else -1
            n = int(abs(a1 - a0)) + (1 if closed else 0)
            for k in range(n):
                m = a0 + k * step
                if span != 0.0:
                    t = (m - start) / span
                else:
                    t = 0.0
                t = min(max(t, 0.0), 1.0)
                if xmajor:
                    x = int(m)
                    y = int(math.floor(y0 + t * dy + 0.5))
                else:
                    y = int(m)
                    x = int(math.floor(x0 + t * dx + 0.5))
                if x < sx0 or x > sx1 or y < sy0 or y > sy1:
                    continue
                z = P0[s, 2] + t * (P1[s, 2] - P0[s, 2])
                if gouraud:
                    r = P0[s, 3] + t * (P1[s, 3] - P0[s, 3])
                    g = P0[s, 4] + t * (P1[s, 4] - P0[s, 4])
                    b = P0[s, 5] + t * (P1[s, 5] - P0[s, 5])
                    a = P0[s, 6] + t * (P1[s, 6] - P0[s, 6])
                else:
                    r = FLAT[s, 0]
                    g = FLAT[s, 1]
                    b = FLAT[s, 2]
                    a = FLAT[s, 3]
                frag(bt, x, y, z, r, g, b, a, planes, ip)

    return draw_lines


def _make_point_kernel(ztest, zwrite, color, gouraud, cmode, twoside,
                       stencil, blend, logic, atest, pattern, cmask, texture, dual):
    key = (ztest, zwrite, color, gouraud, cmode, twoside, stencil, blend, logic, atest,
           pattern, cmask, texture, dual)
    bterms = key_terms(blend)
    frag = _fragment(ztest, zwrite, color, cmode, stencil, blend, logic, atest, cmask, dual)

    @kernel(variant=key)
    def draw_points(P, planes, ip):
        """P: (N, 7) rows x, y, z, r, g, b, a."""
        bt = fragment.blend_terms(blend, bterms, fragment.params(ip))
        for i in range(P.shape[0]):
            x = int(math.floor(P[i, 0] + 0.5))
            y = int(math.floor(P[i, 1] + 0.5))
            if x < ip[fragment.P_SX0] or x > ip[fragment.P_SX1]:
                continue
            if y < ip[fragment.P_SY0] or y > ip[fragment.P_SY1]:
                continue
            frag(bt, x, y, P[i, 2], P[i, 3], P[i, 4], P[i, 5], P[i, 6], planes, ip)

    return draw_points

