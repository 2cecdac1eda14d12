"""Scan Conversion: window-space work -> fragments -> raster operations.

``scan_batch`` chooses the kernel variant for the raster state
(:mod:`raster.variants`), runs triangle setup once for the batch, then the
walker; lines and points have their own walkers.  All pixel work happens in
the numba kernels; this module only prepares arrays.
"""
import numpy as np

from ..geometry.batch import FILLED, LINES
from . import lines as _lines
from . import triangles as _tris
from .triangles import setup_triangles


def scan_batch(work, key, planes, ip, cull, closed_lines):
    """Rasterize one WindowWork with the raster ``key`` and parameters ``ip``."""
    if work.klass == FILLED:
        if work.tris is None or len(work.tris) == 0:
            return 0
        setup = setup_triangles(work.X, work.Y, work.tris, cull,
                                ip[0], ip[1], ip[2], ip[3])
        _tris.triangle_kernel(key)(setup, work.X, work.Y, work.Z, work.C, work.CB,
                                   work.prov, planes, ip)
        return int(setup[5].sum())
    if work.klass == LINES:
        if len(work.seg0) == 0:
            return 0
        _lines.line_kernel(key)(work.seg0, work.seg1, work.segflat, closed_lines,
                                planes, ip)
        return len(work.seg0)
    if len(work.points) == 0:
        return 0
    _lines.point_kernel(key)(np.ascontiguousarray(work.points), planes, ip)
    return len(work.points)
