"""Specialised raster kernels draw exactly what the general ones draw:

* the folded blend kernels (raster/blend.py ``FOLDED``: additive,
  transparency, premultiplied transparency, the two modulations), whose
  factor arithmetic is a constant of the kernel, against the generic blend
  kernel that reads the factors at run time;
* a Gouraud batch whose vertices all have one colour, which the machine
  draws with the flat kernel (no colour interpolation), against the same
  batch drawn by the Gouraud kernel.

Each scene is drawn twice, the second time with the specialisation turned
off, and every bank (colour, z, stencil) must be the same; a spy on the scan
records which kernel key each pass used, so that the test knows both
kernels really ran."""
import numpy as np
import pytest

import vgx_emulator.scan as scan_module
from irisgl import (BF_DC, BF_MSA, BF_ONE, BF_SA, BF_SC, BF_ZERO, FALSE, GD_ZMAX, GOURAUD,
                    ST_INCR, ST_KEEP, SF_ALWAYS, TRUE, bgnpolygon, bgntmesh, blendfunction,
                    c4f, czclear, endpolygon, endtmesh, getgdesc, ortho, sclear,
                    shademodel, stencil, subpixel, v3f, wmpack, zbuffer)
from banks import colour, stencil_bank, z_bank
from vgx_emulator.geometry import WindowWork
from vgx_emulator.geometry.batch import FILLED
from vgx_emulator.raster import blend

W, H = 40, 30


@pytest.fixture
def keys(monkeypatch):
    """The RasterKey of every triangle pass, in order."""
    seen = []
    real = scan_module.scan_batch

    def spy(work, key, *args, **kw):
        if work.klass == FILLED:
            seen.append(key)
        return real(work, key, *args, **kw)
    monkeypatch.setattr(scan_module, "scan_batch", spy)
    return seen


def _scene(open_window, draw):
    """A window with z and 8 stencil planes, cleared to a colour with alpha;
    ``draw`` draws; returns the colour, z and stencil banks."""
    open_window(W, H, planes=8)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    subpixel(TRUE)
    shademodel(GOURAUD)
    zbuffer(TRUE)
    czclear(0x80406080, getgdesc(GD_ZMAX))
    sclear(0)
    draw()
    return colour(), z_bank(), stencil_bank()


def _triangles(colours):
    """Three overlapping triangles at different depths; ``colours`` gives
    each vertex's RGBA (floats 0..1)."""
    tris = [[(2, 2, 0.5), (30, 4, -0.2), (10, 26, 0.1)],
            [(8, 1, -0.5), (38, 20, 0.6), (20, 28, 0.0)],
            [(1, 14, 0.3), (36, 9, 0.3), (24, 29, -0.8)]]
    i = 0
    for t in tris:
        bgnpolygon()
        for v in t:
            c4f(colours[i % len(colours)])
            v3f(v)
            i += 1
        endpolygon()


SHADED = [(1.0, 0.2, 0.1, 0.9), (0.1, 0.8, 0.3, 0.3), (0.2, 0.3, 1.0, 0.6),
          (0.9, 0.9, 0.1, 0.0), (0.5, 0.1, 0.7, 1.0)]


@pytest.mark.parametrize("pair", sorted(blend.FOLDED))
def test_folded_blend_kernel_equals_the_generic_one(open_window, keys, monkeypatch, pair):
    def draw():
        blendfunction(*pair)
        _triangles(SHADED)
        blendfunction(BF_ONE, BF_ZERO)
    folded = _scene(open_window, draw)
    assert keys and all(k.blend == blend.key_code(*pair) > 0 for k in keys)
    keys.clear()
    monkeypatch.setattr(blend, "key_code", lambda s, d: blend.GENERIC)
    generic = _scene(open_window, draw)
    assert keys and all(k.blend == blend.GENERIC for k in keys)
    for a, b, name in zip(folded, generic, ("colour", "z", "stencil")):
        assert np.array_equal(a, b), name
    assert (folded[0] != 0x80406080).any()          # something was blended


def test_the_folded_pairs_are_the_named_ones():
    assert blend.FOLDED == {(BF_ONE, BF_ONE), (BF_SA, BF_MSA), (BF_ONE, BF_MSA),
                            (BF_DC, BF_ZERO), (BF_ZERO, BF_SC)}


ONE_COLOUR = [(0.3, 0.6, 0.9, 0.5)]


@pytest.mark.parametrize("case", ["plain", "blended", "stencil", "tmesh"])
def test_one_colour_gouraud_drawn_flat_equals_gouraud(open_window, keys, monkeypatch, case):
    def draw():
        if case == "blended":
            blendfunction(BF_SA, BF_MSA)
        if case == "stencil":
            stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_INCR)
        if case == "tmesh":
            bgntmesh()
            for v in [(1, 1, 0.2), (39, 3, -0.4), (3, 28, 0.5), (37, 29, 0.0)]:
                c4f(ONE_COLOUR[0])
                v3f(v)
            endtmesh()
        _triangles(ONE_COLOUR)
        stencil(FALSE, 0, SF_ALWAYS, 0, ST_KEEP, ST_KEEP, ST_KEEP)
        blendfunction(BF_ONE, BF_ZERO)
    flat = _scene(open_window, draw)
    assert keys and not any(k.gouraud for k in keys)      # demoted: one colour
    keys.clear()
    monkeypatch.setattr(WindowWork, "constant_colour", lambda self: False)
    gouraud = _scene(open_window, draw)
    assert keys and all(k.gouraud for k in keys)
    for a, b, name in zip(flat, gouraud, ("colour", "z", "stencil")):
        assert np.array_equal(a, b), name
    assert (flat[0] != 0x80406080).any()


def test_colour_writes_off_draw_without_interpolation(open_window, keys):
    """wmpack(0): no colour is written, so no pass interpolates colour even
    when the vertices differ; z is still written."""
    def draw():
        wmpack(0)
        _triangles(SHADED)
        wmpack(0xFFFFFFFF)
    col, z, _ = _scene(open_window, draw)
    assert keys and not any(k.gouraud for k in keys)
    assert (col == 0x80406080).all() and (z != 0x7FFFFF).any()


def test_shaded_vertices_keep_gouraud(open_window, keys):
    _scene(open_window, lambda: _triangles(SHADED))
    assert keys and all(k.gouraud for k in keys)
