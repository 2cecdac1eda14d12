"""Scan Conversion: window-space work -> fragments -> raster operations.

``scan_batch`` chooses the kernel variant for the raster state
(:mod:`raster.variants`), runs triangle setup once for the batch, then the
walker; lines and points have their own walkers.  All pixel work happens in
the numba kernels; this module only prepares arrays.
"""
import numba
import numpy as np

from .. import specialise
from ..geometry.batch import FILLED, LINES
from ..raster import fragment
from . import lines as _lines
from . import triangles as _tris
from .triangles import setup_triangles


_NO_TC = np.zeros((1, 3))
_NO_ZMAX = np.zeros((1, 1), np.int32)
_BANDS = np.zeros(1, np.int64)      # the type of the walker's bands (run_bands)
_NO_TEX = (np.zeros((1, 4), np.uint8), np.array([1, 0, 1, 1], np.int64),
           np.zeros(1, np.int64), np.zeros(7))


def texture_inputs(work, texture, tparams):
    """The kernel's texture tuple: texels, level table, per-triangle
    (level << 1 | bilinear), parameters.  Level choice is per triangle from
    the ratio of its texel area to its pixel area (log2 / 2, rounded)."""
    tris = work.tris
    s = work.TC[:, 0] / work.TC[:, 2]
    t = work.TC[:, 1] / work.TC[:, 2]
    w, h = texture.levels[0].shape[1], texture.levels[0].shape[0]
    a, b, c = tris[:, 0], tris[:, 1], tris[:, 2]
    tex_area = np.abs((s[b] - s[a]) * (t[c] - t[a]) - (t[b] - t[a]) * (s[c] - s[a])) * w * h
    one = float(1 << 8)
    X, Y = work.X / one, work.Y / one
    pix_area = np.abs((X[b] - X[a]) * (Y[c] - Y[a]) - (Y[b] - Y[a]) * (X[c] - X[a]))
    with np.errstate(divide="ignore", invalid="ignore"):
        lod = 0.5 * np.log2(tex_area / pix_area)
    lod = np.nan_to_num(lod, nan=0.0, posinf=30.0, neginf=0.0)
    minify = lod > 0
    tsel = np.zeros(len(tris), np.int64)
    nlev = len(texture.levels)
    for mn in (False, True):
        sel = minify == mn
        mode, mip = texture.mode(mn)
        level = np.clip(np.floor(lod[sel] + 0.5), 0, nlev - 1).astype(np.int64) if mip else 0
        tsel[sel] = (level << 1) | mode
    return (texture.texels, texture.info, tsel, tparams)


def setup_batch(work, key, ip, cull):
    """Triangle setup of a batch of filled primitives (scan.triangles.
    setup_triangles) for the raster ``key`` and scissor in ``ip``, or None
    (lines, points, no triangle).  Run by the thread that queues the pass
    (pipeline.py), so that the raster thread only walks."""
    if work.klass != FILLED or work.tris is None or len(work.tris) == 0:
        return None
    return setup_triangles(work.X, work.Y, work.Z, work.C, work.CB, work.prov, work.tris,
                           cull, ip[0], ip[1], ip[2], ip[3],
                           interp=key.gouraud and key.color and not key.texture,
                           cmode=key.cmode, twoside=key.twoside)


def scan_batch(work, key, planes, ip, cull, closed_lines, tex=None, zmaxima=None, setup=None):
    """Rasterize one WindowWork with the raster ``key`` and parameters ``ip``;
    ``tex`` = (Texture, tparams) when texturing; ``zmaxima``: the z bank's
    per-segment maxima when ip[P_ZMAX] lets triangles skip spans against
    them (framebuffer/zmax.py); ``setup``: setup_batch's result, when it
    was made already."""
    if work.klass == FILLED:
        if work.tris is None or len(work.tris) == 0:
            return 0
        if setup is None:
            setup = setup_batch(work, key, ip, cull)
        if key.texture:
            tk = texture_inputs(work, tex[0], tex[1])
            tc = work.TC
        else:
            tk, tc = _NO_TEX, _NO_TC
        zm = _NO_ZMAX if zmaxima is None else zmaxima

        def args(planes, ip):
            return (setup, work.X, work.Y, work.Z, work.C, work.CB, work.prov, planes, ip,
                    tc, tk, zm)
        run(_tris.triangle_kernel, "walk", key, planes, ip, args, first=_BANDS)
        return _tris.drawn(setup)
    if work.klass == LINES:
        if len(work.seg0) == 0:
            return 0
        run(_lines.line_kernel, "line", key, planes, ip,
            lambda planes, ip: (work.seg0, work.seg1, work.segflat, closed_lines, planes, ip))
        return len(work.seg0)
    if len(work.points) == 0:
        return 0
    run_points(key, np.ascontiguousarray(work.points), planes, ip)
    return len(work.points)


def run_points(key, points, planes, ip):
    """Points (n, 7: x, y, z, r, g, b, a) through the point kernel of ``key``
    (pnt(3G) batches, charstr(3G) glyph pixels)."""
    run(_lines.point_kernel, "point", key, planes, ip, lambda planes, ip: (points, planes, ip))


def run(kernel_of, kind, key, planes, ip, args, first=None):
    """Call ``kernel_of(k)(*args(planes, ip))`` for the variant ``k`` that
    vgx_emulator/specialise.py chooses for ``key``: its own, or the general
    variant of its family with neutral banks and parameters; the stored-z
    report (P_ZCHANGED) comes back into ``ip``.  ``first``: arguments before
    ``args``' that the kernel itself receives (the walker's bands), for the
    argument types of a compile request."""
    def types():
        lead = () if first is None else (first,)
        return tuple(numba.typeof(a) for a in lead + args(planes, ip))
    k, planes2, ip2 = specialise.choose(kind, key, planes, ip, types)
    kernel_of(k)(*args(planes2, ip2))
    if ip2 is not ip:
        ip[fragment.P_ZCHANGED] = ip2[fragment.P_ZCHANGED]
