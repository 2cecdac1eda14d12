"""Per-pixel reference model of scan conversion (independent of the library).

Rules modelled (docs/semantics.md §1, §2, §3; the fill
rule documented for the emulator):

* window coordinates, y up; pixel (i, j) is sampled at its centre, the point
  (i, j);
* vertices are kept to 1/256 of a pixel (8 sub-pixel bits, rounded to
  nearest) with ``subpixel(TRUE)``, or snapped to the nearest pixel centre
  (``floor(x + 0.5)``) with ``subpixel(FALSE)``;
* a triangle covers pixel (i, j) iff the centre is strictly inside it, or lies
  on an edge that, with the triangle in counter-clockwise order, is a *left*
  edge (it runs downwards: y decreasing) or a *bottom* edge (horizontal,
  running rightwards: x increasing); a zero-area triangle covers nothing;
* convex polygons are the union of their fan triangles (0, k, k+1).

Everything is computed with :class:`fractions.Fraction`, one pixel at a time,
so it is slow and exact.  Pixel sets are Python ``set`` objects of ``(x, y)``.
"""
from fractions import Fraction
import math

SUBPIXEL_BITS = 8
ONE = 1 << SUBPIXEL_BITS


def fx(v):
    """A coordinate as the rasterizer holds it with subpixel(TRUE): the exact
    rational nearest to ``v`` on the 1/256 grid (ties upwards)."""
    return Fraction(math.floor(Fraction(v) * ONE + Fraction(1, 2)), ONE)


def snap(v):
    """A coordinate as the rasterizer holds it with subpixel(FALSE): the
    nearest pixel centre (ties upwards, floor(v + 1/2))."""
    return Fraction(math.floor(Fraction(v) + Fraction(1, 2)))


def place(vertices, subpixel=True):
    """Window vertices [(x, y), ...] -> exact rational positions."""
    f = fx if subpixel else snap
    return [(f(x), f(y)) for x, y in vertices]


def signed_area2(a, b, c):
    """Twice the signed area of triangle abc (> 0: counter-clockwise, y up)."""
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def winding(a, b, c):
    """'ccw', 'cw' or 'degenerate' (screen orientation, y up)."""
    s = signed_area2(a, b, c)
    return "ccw" if s > 0 else ("cw" if s < 0 else "degenerate")


def _edge_owned(a, b):
    """Does the directed edge a -> b of a CCW triangle own the centres on it?"""
    dy = b[1] - a[1]
    dx = b[0] - a[0]
    return dy < 0 or (dy == 0 and dx > 0)


def _covers(a, b, c, px, py):
    """Triangle abc, counter-clockwise, covers the point (px, py)?"""
    for p, q in ((a, b), (b, c), (c, a)):
        # > 0: p is on the inner (left) side of the directed edge p -> q
        e = (q[0] - p[0]) * (py - p[1]) - (q[1] - p[1]) * (px - p[0])
        if e < 0:
            return False
        if e == 0 and not _edge_owned(p, q):
            return False
    return True


def triangle_pixels(a, b, c, width, height):
    """Pixels of the window (0..width-1, 0..height-1) that triangle abc covers.

    a, b, c: (x, y) exact window positions (use :func:`place` first)."""
    a, b, c = (tuple(Fraction(v) for v in p) for p in (a, b, c))
    s = signed_area2(a, b, c)
    if s == 0:
        return set()
    if s < 0:
        b, c = c, b             # same point set, counter-clockwise order
    xs = [a[0], b[0], c[0]]
    ys = [a[1], b[1], c[1]]
    x0 = max(0, math.ceil(min(xs)))
    x1 = min(width - 1, math.floor(max(xs)))
    y0 = max(0, math.ceil(min(ys)))
    y1 = min(height - 1, math.floor(max(ys)))
    out = set()
    for j in range(y0, y1 + 1):
        for i in range(x0, x1 + 1):
            if _covers(a, b, c, i, j):
                out.add((i, j))
    return out


def fan(vertices):
    """Fan triangles (0, k, k+1) of a polygon."""
    return [(vertices[0], vertices[k], vertices[k + 1])
            for k in range(1, len(vertices) - 1)]


def polygon_pixels(vertices, width, height):
    """Union of the fan triangles of a convex polygon (exact positions)."""
    out = set()
    for t in fan(vertices):
        out |= triangle_pixels(*t, width, height)
    return out


def rect_pixels(x0, x1, y0, y1):
    """Inclusive pixel rectangle as a set."""
    return {(i, j) for i in range(x0, x1 + 1) for j in range(y0, y1 + 1)}


def barycentric(a, b, c, px, py):
    """Exact barycentric weights (wa, wb, wc) of point p in triangle abc."""
    s = signed_area2(a, b, c)
    p = (Fraction(px), Fraction(py))
    return (signed_area2(p, b, c) / s, signed_area2(a, p, c) / s,
            signed_area2(a, b, p) / s)


def tmesh_triangles(n_or_events):
    """Triangles of a tmesh (docs/semantics.md §3): two registers and a replace
    pointer; each vertex after the first two draws (R0, R1, new), then
    replaces the register the pointer selects, and the pointer toggles;
    ``'swap'`` toggles the pointer.  Argument: a list of vertex indices and
    the string 'swap'.  Returns index triples."""
    regs = [None, None]
    ptr = 0
    out = []
    for ev in n_or_events:
        if ev == "swap":
            ptr ^= 1
            continue
        if regs[0] is not None and regs[1] is not None:
            out.append((regs[0], regs[1], ev))
        regs[ptr] = ev
        ptr ^= 1
    return out


def qstrip_quads(n):
    """Quads of a qstrip of n vertices: (2k, 2k+1, 2k+3, 2k+2) (docs/semantics.md §3)."""
    return [(2 * k, 2 * k + 1, 2 * k + 3, 2 * k + 2) for k in range((n - 2) // 2)]


def line_pixels(p0, p1, closed):
    """A one-pixel line between window points whose coordinates are integers
    (pixel centres): it steps one pixel along its major axis, taking the pixel
    nearest the exact line on the minor axis.  ``closed``: both ends drawn
    (snapped lines); otherwise half-open (the last pixel is not drawn).
    Ties on the minor axis are not modelled (callers avoid them)."""
    (x0, y0), (x1, y1) = [(Fraction(x), Fraction(y)) for x, y in (p0, p1)]
    assert all(v.denominator == 1 for v in (x0, y0, x1, y1))
    dx, dy = x1 - x0, y1 - y0
    xmajor = abs(dx) >= abs(dy)
    n = int(abs(dx) if xmajor else abs(dy))
    steps = n + 1 if closed else n
    out = []
    for k in range(steps):
        t = Fraction(k, n) if n else Fraction(0)
        x, y = x0 + t * dx, y0 + t * dy
        if xmajor:
            fy = y - math.floor(y)
            assert fy != Fraction(1, 2), "tie on the minor axis"
            out.append((int(x), math.floor(y + Fraction(1, 2))))
        else:
            fx_ = x - math.floor(x)
            assert fx_ != Fraction(1, 2), "tie on the minor axis"
            out.append((math.floor(x + Fraction(1, 2)), int(y)))
    return out
