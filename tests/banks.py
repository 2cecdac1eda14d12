"""Drawing and reading helpers shared by the raster test modules.

Reads go through the IRIS GL calls (lrectread, rectread, readsource); the
stencil bank, which no IRIS GL call reads, is taken from the machine.  All
arrays are (h, w) int64 with row 0 at the bottom, as IRIS GL reads them.
"""
import numpy as np

from irisgl import (SRC_AUTO, SRC_ZBUFFER, TRUE, getsize, lrectread, readsource, rectf,
                    rectread, subpixel)


def box(x1, y1, x2, y2):
    """Fill exactly pixels x1..x2, y1..y2: edges on pixel boundaries with
    sub-pixel vertices, so no pixel centre lies on an edge (independent of
    the fill rule)."""
    subpixel(TRUE)
    rectf(x1 - 0.5, y1 - 0.5, x2 + 0.5, y2 + 0.5)


def colour():
    w, h = getsize()
    return lrectread(0, 0, w - 1, h - 1).astype(np.int64)


def indices():
    w, h = getsize()
    return rectread(0, 0, w - 1, h - 1).astype(np.int64)


def z_bank():
    w, h = getsize()
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, w - 1, h - 1).astype(np.int64)
    readsource(SRC_AUTO)
    return z


def stencil_bank():
    """The stencil bank (inspection only)."""
    from irisgl._current import machine
    machine.flush()
    return machine.current.fb.stencil.astype(np.int64).copy()
