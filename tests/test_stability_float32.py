"""float32 against float64 geometry (docs/stability.md): the four spheres
drawn from float32-rounded input change almost nothing."""
import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from banks import colour, z_bank
from stability_helpers import (fresh)


# 10. float32 geometry versus float64 geometry (the four spheres)
def four_spheres(round32, subpix):
    """programs/four_spheres' configuration and draw_scene, its v3f/n3f
    arguments as given (float64) or rounded to float32 first (what a C
    program's float arrays hold)."""
    import programs.four_spheres as fs
    fresh()
    prefsize(fs.WIDTH, fs.HEIGHT)
    winopen("four spheres")
    RGBmode()
    gconfig()
    subpixel(subpix)
    zbuffer(TRUE)
    mmode(MVIEWING)
    perspective(400, fs.WIDTH / fs.HEIGHT, 1.0, 50.0)
    fs.define_lighting()
    lmbind(MATERIAL, fs.SPHERE_MAT)
    lmbind(LMODEL, fs.MODEL)
    if round32:
        def f32(call):
            return lambda a: call(tuple(float(x) for x in np.float32(a)))
        fs.v3f, fs.n3f = f32(v3f), f32(n3f)
    try:
        fs.draw_scene()
    finally:
        fs.v3f, fs.n3f = v3f, n3f
    return colour(), z_bank()


def float_differences(subpix):
    """(drawn pixels, coverage differences, colour differences, largest
    channel difference, z differences, largest z difference)."""
    c64, z64 = four_spheres(False, subpix)
    c32, z32 = four_spheres(True, subpix)
    drawn = (c64 != 0) | (c32 != 0)
    chan = np.abs(np.stack([((c64 >> s) & 255) - ((c32 >> s) & 255) for s in (0, 8, 16)]))
    return (int(drawn.sum()), int(((c64 != 0) != (c32 != 0)).sum()), int((c64 != c32).sum()),
            int(chan.max()), int((z64 != z32).sum()), int(np.abs(z64 - z32).max()))


@pytest.mark.parametrize("subpix", [FALSE, TRUE], ids=["snapped", "subpixel"])
def test_float32_rounded_geometry_changes_almost_nothing(subpix):
    """Rounding the spheres' vertices and normals to float32 moves a vertex
    by <= 2**-24 of its size (< 3e-7 world units, ~2e-4 of a sub-pixel
    step) and a colour by < 1e-4 of a level.  So: at most 0.1 % of the
    pixels change coverage or colour, by one level at most; z (about 1.2e5
    units per world unit at the spheres) moves by < 0.04 units, so stored z
    changes by one unit at most, at < 2 * 0.04 of the pixels."""
    drawn, cov, col, chan, zd, zmax = float_differences(subpix)
    assert drawn > 30000
    assert cov <= 0.001 * drawn and col <= 0.001 * drawn and chan <= 1
    assert zmax <= 1 and zd <= 0.08 * drawn
