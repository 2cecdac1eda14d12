"""A study scene drawn through the emulator with IRIS GL calls.

The ``Stage`` opens the eye's window (RGB, single-buffered, 8 stencil
planes, a 16-bit accumulation buffer, z-buffer, ``subpixel(TRUE)`` so the
vertices are not snapped to pixel centres and the coverage is that of the
reference's rays through the pixel centres), defines the materials and
the light with ``lmdef``, and compiles the scene into display lists
(``makeobj``/``closeobj``; an IRIS GL program of 1991 would have done so
for a static scene).  One polygon per triangle with its flat normal.

Display lists: per subset (``all`` meshes, the ``ground``, the ``casters``)
and material set: ``full`` (AMBIENT and DIFFUSE: the lit image, or the
ambient-only image with the light unbound), ``diffuse`` (AMBIENT 0, for
Heidmann's additive lit pass and Bentley's lit ground pass) and ``plain``
(no materials, no normals: depth-only and stencil-only passes).

Rows of every array read back are bottom first (lrectread's order).
"""
import weakref

import numpy as np

from irisgl import (AMBIENT, DEFLIGHT, DEFLMODEL, DEFMATERIAL, DIFFUSE, FALSE, GD_ZMAX, LCOLOR,
                    LIGHT0, LMNULL, LMODEL, MATERIAL, MVIEWING, POSITION, RGBmode, SF_EQUAL,
                    SPECULAR, ST_KEEP, TRUE, acsize, bgnpolygon, clear, closeobj, cpack,
                    czclear, delobj, endpolygon, gconfig, genobj, getgdesc, lmbind, lmdef,
                    loadmatrix, lookat, makeobj, mmode, n3f, ortho2, perspective, popmatrix,
                    prefsize, pushmatrix, rectf, stencil, stensize, subpixel, v3f, winclose,
                    winopen, winset, zbuffer)
from programs import shadowbuf as sb

MYZERO = 128                 # Heidmann's stencil "zero"
SUN = 1                      # the light's lmdef index
MODEL = 1                    # the lighting model's index
MAX_TILE = 1024              # light windows are at most this size (the screen is 1280x1024)
_LIGHTING = lambda: None     # noqa: E731 (a weak reference to the Stage whose lmdefs hold)
IDENTITY = np.identity(4)


class Stage:
    """The eye's window, the light's windows and the compiled scene."""

    def __init__(self, scene, width, height, max_tile=MAX_TILE):
        self.scene, self.width, self.height = scene, width, height
        self.max_tile = int(max_tile)         # the largest light window (a map's tiles)
        prefsize(width, height)
        self.eye_win = winopen("study eye")
        RGBmode()
        stensize(8)
        acsize(16)
        gconfig()
        zbuffer(TRUE)
        subpixel(TRUE)
        mmode(MVIEWING)
        self.materials = {name: k for k, name in enumerate(sorted(scene.materials))}
        self._define_lighting()
        self.lists = {}
        self.light_windows = {}

    def close(self):
        """Close the stage's windows and delete its display lists."""
        for n in self.lists.values():
            delobj(n)
        for gid in [self.eye_win, *self.light_windows.values()]:
            winclose(gid)
        self.lists, self.light_windows = {}, {}

    # -- lighting ---------------------------------------------------------
    def _define_lighting(self):
        """lmdef the scene's materials, lighting model and light.  lmdef's
        tables belong to the process, not to a window: a second Stage
        redefines the same indices, so eye_view defines them again when
        another Stage defined them last."""
        global _LIGHTING
        _LIGHTING = weakref.ref(self)
        for name, k in self.materials.items():
            amb, dif = self.scene.materials[name]
            lmdef(DEFMATERIAL, 10 + k, 0, [AMBIENT, *amb, DIFFUSE, *dif, SPECULAR, 0, 0, 0,
                                           LMNULL])
            lmdef(DEFMATERIAL, 40 + k, 0, [AMBIENT, 0, 0, 0, DIFFUSE, *dif, SPECULAR, 0, 0, 0,
                                           LMNULL])
        a = self.scene.model_ambient
        lmdef(DEFLMODEL, MODEL, 0, [AMBIENT, a, a, a, LMNULL])
        self.set_light(self.scene.light_dir)

    def set_light(self, direction):
        """The light at infinity, towards ``direction`` (bound at the next
        eye_view)."""
        d = [float(c) for c in direction]
        lmdef(DEFLIGHT, SUN, 0, [LCOLOR, 1.0, 1.0, 1.0, POSITION, *d, 0.0, LMNULL])

    # -- display lists ------------------------------------------------------
    def obj(self, subset, mode):
        """The display list of a subset of meshes in a material mode."""
        key = (subset, mode)
        if key not in self.lists:
            self.lists[key] = self._compile(subset, mode)
        return self.lists[key]

    def _compile(self, subset, mode):
        keep = {"all": lambda m: True, "ground": lambda m: not m.casts,
                "casters": lambda m: m.casts}[subset]
        n = genobj()
        makeobj(n)
        for mesh in self.scene.meshes:
            if keep(mesh):
                self._draw_mesh(mesh, mode)
        closeobj()
        return n

    def _draw_mesh(self, mesh, mode):
        corners = mesh.verts[mesh.tris]
        if mode != "plain":
            base = 10 if mode == "full" else 40
            lmbind(MATERIAL, base + self.materials[mesh.material])
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        for tri, nrm in zip(corners.tolist(), normals.tolist()):
            bgnpolygon()
            if mode != "plain":
                n3f(nrm)
            v3f(tri[0])
            v3f(tri[1])
            v3f(tri[2])
            endpolygon()

    # -- the eye ----------------------------------------------------------
    def eye_view(self, light=True):
        """Current window := the eye; its perspective and lookat; the light
        bound (fixed in the world) or not."""
        winset(self.eye_win)
        if _LIGHTING() is not self:
            self._define_lighting()
        v = self.scene.view
        mmode(MVIEWING)
        perspective(v.fovy, self.width / self.height, v.near, v.far)
        loadmatrix(IDENTITY)
        lookat(*v.eye, *v.ref, 0)
        lmbind(LMODEL, MODEL)
        lmbind(LIGHT0, SUN if light else 0)

    def clear(self):
        czclear(0x00000000, getgdesc(GD_ZMAX))

    def read_colour(self):
        return sb.read_colour(self.width, self.height)

    def read_depth(self):
        return sb.read_depth(self.width, self.height)

    def stencil_mask(self, ref):
        """Pixels whose stencil equals ``ref``, read as a flag colour: the
        colour planes cleared to black, then a white rectangle over the
        window drawn where the stencil test passes (z-buffer off)."""
        w, h = self.width, self.height
        lmbind(MATERIAL, 0)
        cpack(0x00000000)
        clear()
        zbuffer(FALSE)
        stencil(TRUE, ref, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
        ortho2(-0.5, w - 0.5, -0.5, h - 0.5)
        pushmatrix()
        loadmatrix(IDENTITY)
        cpack(0xFFFFFFFF)
        rectf(-0.5, -0.5, w - 0.5, h - 0.5)
        popmatrix()
        stencil(FALSE, 0, 0, 0, 0, 0, 0)
        zbuffer(TRUE)
        return self.read_colour()[..., 0] > 127

    # -- the light's view ---------------------------------------------------
    def light_window(self, size):
        """A size x size window for the light's depth (z-buffer on)."""
        if size not in self.light_windows:
            prefsize(size, size)
            gid = winopen(f"study light {size}")
            RGBmode()
            gconfig()
            zbuffer(TRUE)
            mmode(MVIEWING)
            self.light_windows[size] = gid
        winset(self.light_windows[size])
        return self.light_windows[size]

    def light_box(self):
        """The orthographic light view fitted to the scene: (eye point,
        look-at point, (left, right, bottom, top, near, far))."""
        from .reference import lookat_matrix
        lo, hi = self.scene.bounds()
        centre = 0.5 * (lo + hi)
        radius = 0.5 * float(np.linalg.norm(hi - lo))
        L = self.scene.light_dir
        eye = centre + L * (radius + 1.0)
        v = np.concatenate([m.verts for m in self.scene.meshes])
        e = np.c_[v, np.ones(len(v))] @ lookat_matrix(eye, centre)
        pad = 1e-3 * radius
        box = (e[:, 0].min() - pad, e[:, 0].max() + pad, e[:, 1].min() - pad,
               e[:, 1].max() + pad, -e[:, 2].max() - pad, -e[:, 2].min() + pad)
        return eye, centre, box


def fb_bytes(width, height, stencil_planes=False, accum=False):
    """Bytes of the banks a pass needs: colour and z (4 each per pixel),
    stencil (1), accumulation (4 x 16 bits)."""
    per = 8 + (1 if stencil_planes else 0) + (8 if accum else 0)
    return width * height * per


def draw_polygons(polys):
    """bgnpolygon / v3f ... / endpolygon for each polygon of an (n, k, 3) array."""
    for poly in polys.tolist():
        bgnpolygon()
        for v in poly:
            v3f(v)
        endpolygon()
