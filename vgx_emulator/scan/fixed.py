"""Sub-pixel fixed point and the fill rule, shared by every filling primitive.

Window coordinates reach the rasterizer as int64 with ``SUBPIXEL_BITS``
fractional bits.  Pixel (i, j) is sampled at its centre, window (i, j).

Edge function of the directed edge a -> b at point p (all fixed point)::

    E_ab(p) = (bx - ax) * (py - ay) - (by - ay) * (px - ax) = A px + B py + C

For a counter-clockwise triangle (y up, IRIS GL's window orientation) the
inside has E > 0 on all three edges.

**Fill rule (left-bottom).**  A pixel centre exactly on an edge belongs to
the triangle only when that edge is a *left* edge (it runs downwards,
by < ay) or a *bottom* edge (horizontal, running rightwards, bx > ax).  An
edge shared by two triangles is traversed in opposite directions by them, so
exactly one of the two owns it: shared-edge pixels are drawn once, none is
missed.  (This is Direct3D's/OpenGL's top-left rule mirrored for y up.)  The
rule is applied by subtracting 1 from C of the edges not owned and testing
E >= 0 in integers.  Magnitudes: |coord| < 2**24 fixed, so |E| < 2**50.
"""
from .. import config
from ..jit import helper

SHIFT = config.SUBPIXEL_BITS


@helper
def owns_edge(ax, ay, bx, by):
    """True when the directed edge a -> b of a CCW triangle is left or bottom."""
    dy = by - ay
    return dy < 0 or (dy == 0 and bx > ax)


@helper
def edge_coefficients(ax, ay, bx, by):
    """(A, B, C) of E_ab(p) = A px + B py + C, with the fill-rule bias in C."""
    a = ay - by
    b = bx - ax
    c = (by - ay) * ax - (bx - ax) * ay
    if not owns_edge(ax, ay, bx, by):
        c -= 1
    return a, b, c
