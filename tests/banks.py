"""Drawing and reading helpers shared by the raster test modules.

Reads go through the IRIS GL calls (lrectread, rectread, readsource); the
stencil bank, which no IRIS GL call reads, is taken from the machine.  All
arrays are (h, w) int64 with row 0 at the bottom, as IRIS GL reads them.
"""
import numpy as np

from irisgl import (GD_ZMAX, GOURAUD, SRC_AUTO, SRC_ZBUFFER, TRUE, RGBmode, acsize, clear,
                    cmode, cpack, czclear, doublebuffer, gconfig, getgdesc, getsize, lrectread,
                    ortho, ortho2, prefposition, prefsize, readsource, rectf, rectread, sclear,
                    shademodel, stensize, subpixel, winopen, zbuffer)


def new_window(w=64, h=48, rgb=True, double=False, planes=0, accum=0, origin=None, pixels=False,
           cleared=False, name="test"):
    """Open a configured w x h window and return its id: prefsize (or
    prefposition with its lower-left corner at ``origin`` on the screen),
    winopen, RGBmode or cmode, doublebuffer, ``planes`` stencil planes,
    ``accum`` accumulation bits, gconfig.  ``pixels``: ortho2 puts pixel
    (i, j)'s centre at (i, j) (otherwise the matrices are as winopen leaves
    them); ``cleared``: cleared to 0, then drawing in white.  The conftest
    fixture ``open_window`` gives this function."""
    if origin is None:
        prefsize(w, h)
    else:
        prefposition(origin[0], origin[0] + w - 1, origin[1], origin[1] + h - 1)
    gid = winopen(name)
    RGBmode() if rgb else cmode()
    if double:
        doublebuffer()
    if planes:
        stensize(planes)
    if accum:
        acsize(accum)
    gconfig()
    if pixels:
        ortho2(-0.5, w - 0.5, -0.5, h - 0.5)
    if cleared:
        cpack(0)
        clear()
        cpack(0xFFFFFFFF)
    return gid


def box(x1, y1, x2, y2):
    """Fill exactly pixels x1..x2, y1..y2: edges on pixel boundaries with
    sub-pixel vertices, so no pixel centre lies on an edge (independent of
    the fill rule)."""
    subpixel(TRUE)
    rectf(x1 - 0.5, y1 - 0.5, x2 + 0.5, y2 + 0.5)


def pixel_window(open_window, w, h):
    """A w x h RGB window where one unit is one pixel, pixel centres on
    integers; cleared to 0, drawing in white."""
    return open_window(w, h, pixels=True, cleared=True)


def lit(w, h):
    """(h, w) bool: the pixels of the window that are not 0."""
    return lrectread(0, 0, w - 1, h - 1) != 0


def depth_stencil_window(open_window, w, h):
    """A w x h RGB window with 8 stencil planes and the z-buffer on, pixel
    centres at integer x and y (z in -1..1), sub-pixel vertices, Gouraud
    shading; colour, z and stencil cleared (0, far, 0)."""
    open_window(w, h, planes=8)
    ortho(-0.5, w - 0.5, -0.5, h - 0.5, -1.0, 1.0)
    subpixel(TRUE)
    shademodel(GOURAUD)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    sclear(0)


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
