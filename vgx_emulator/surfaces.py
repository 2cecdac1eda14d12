"""Emulator extension (not IRIS GL): bicubic patches as shaded, lit surfaces.

IRIS GL's ``patch`` draws only a web of curves.  Williams' curved shadows and
the teapot need the same patches as surfaces, so this module tessellates a
patch with the basis matrices set by ``defbasis``/``patchbasis`` and draws it
through ordinary IRIS GL calls (``bgntmesh``, ``n3f``, ``v3f``): lighting,
the z-buffer, stencil, display lists and everything else apply as to any
mesh.
"""
import numpy as np

from .geometry.curves import patch_surface


def patch_mesh(gx, gy, gz, usegs=8, vsegs=8, ubasis=None, vbasis=None):
    """Points (vsegs+1, usegs+1, 3) and unit normals of a patch.  Without
    explicit bases, the current ``patchbasis`` of irisgl is used."""
    if ubasis is None or vbasis is None:
        from irisgl.curves import patch_bases
        ubasis, vbasis = patch_bases("patch_mesh")
    return patch_surface(np.asarray(ubasis, np.float64), np.asarray(vbasis, np.float64),
                         gx, gy, gz, usegs, vsegs)


def draw_patch_surface(gx, gy, gz, usegs=8, vsegs=8, ubasis=None, vbasis=None,
                       flip=False):
    """Draw a patch as lit triangle strips (one bgntmesh per row).
    ``flip`` reverses the winding (and the normals) for patches whose
    control points run the other way."""
    from irisgl import bgntmesh, endtmesh, n3f, v3f
    p, n = patch_mesh(gx, gy, gz, usegs, vsegs, ubasis, vbasis)
    if flip:
        n = -n
    rows = [(i + 1, i) for i in range(vsegs)] if not flip else [(i, i + 1) for i in range(vsegs)]
    for a, b in rows:
        bgntmesh()
        pa, pb, na, nb = p[a].tolist(), p[b].tolist(), n[a].tolist(), n[b].tolist()
        for j in range(usegs + 1):
            n3f(na[j])
            v3f(pa[j])
            n3f(nb[j])
            v3f(pb[j])
        endtmesh()
