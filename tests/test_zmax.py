"""Span skipping against the z bank's per-segment maxima (framebuffer/zmax.py).

The skip is an optimisation that must never change a pixel: every scene
here is drawn twice, with the maxima and with them switched off
(machine._z_maxima_bound returning None), and the colour, z and stencil banks
must be identical.  The passes mix the cases that decide whether maxima
may be used and whether they must be rebuilt: z writes that raise z
(ZF_GREATER, ZF_ALWAYS), partial zwritemasks, partial and whole clears,
stencil ops on z-fail, ZF_EQUAL redraws.  A last test feeds maxima that
are too low on purpose, to show that the walker does read them.
"""
import numpy as np
import pytest

from irisgl import (FALSE, GD_ZMAX, ST_INCR, ST_KEEP, SF_ALWAYS, SF_EQUAL, TRUE, ZF_ALWAYS,
                    ZF_EQUAL, ZF_GREATER, ZF_LEQUAL, ZF_LESS, bgnpolygon, c4i, czclear,
                    endpolygon, getgdesc, ortho, scrmask, stencil, v3f, viewport, wmpack,
                    zbuffer, zclear, zfunction, zwritemask)

from banks import colour, depth_stencil_window, stencil_bank, z_bank

W, H = 96, 64


def _tris(rnd, n):
    """n random triangles: vertices (x, y, zn) with colours."""
    for _ in range(n):
        bgnpolygon()
        for _ in range(3):
            c4i((int(rnd.integers(0, 256)), int(rnd.integers(0, 256)),
                 int(rnd.integers(0, 256)), 255))
            v3f((float(rnd.uniform(-10, W + 10)), float(rnd.uniform(-10, H + 10)),
                 float(rnd.uniform(-0.9, 0.9))))
        endpolygon()


def _scene(open_window, seed):
    """Passes whose z-failing fragments change nothing (maxima used) between
    passes that write z in every way (maxima rebuilt or not used)."""
    depth_stencil_window(open_window, W, H)
    rnd = np.random.default_rng(seed)
    _tris(rnd, 12)                           # LEQUAL, z written: maxima stale
    zfunction(ZF_LESS)
    _tris(rnd, 12)                           # rebuilt, then stale again
    zfunction(ZF_GREATER)
    _tris(rnd, 6)                            # raises z: maxima not used
    zfunction(ZF_LEQUAL)
    _tris(rnd, 8)                            # rebuilt after the raise
    zwritemask(0x00FF00)
    _tris(rnd, 4)                            # partial z write: not used
    zwritemask(0xFFFFFF)
    _tris(rnd, 6)
    scrmask(10, 60, 5, 40)
    zclear()                                 # partial clear: stale
    scrmask(0, W - 1, 0, H - 1)
    _tris(rnd, 8)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)
    zwritemask(0)
    wmpack(0)
    _tris(rnd, 10)                           # z-pass counting: maxima used
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_INCR, ST_KEEP)
    _tris(rnd, 10)                           # z-fail counting: not used
    stencil(TRUE, 1, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    zwritemask(0xFFFFFF)
    wmpack(0xFFFFFFFF)
    zfunction(ZF_EQUAL)
    rnd = np.random.default_rng(seed)        # the first triangles again, ZF_EQUAL
    _tris(rnd, 12)
    stencil(FALSE, 0, SF_ALWAYS, 0, ST_KEEP, ST_KEEP, ST_KEEP)
    zfunction(ZF_ALWAYS)
    _tris(rnd, 3)                            # any z: not used, stale
    zfunction(ZF_LEQUAL)
    viewport(0, W // 2, 0, H - 1)
    _tris(rnd, 8)
    return colour(), z_bank(), stencil_bank()


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_skipping_spans_changes_no_bank(open_window, vgx, monkeypatch, seed):
    with_maxima = _scene(open_window, seed)
    vgx.reset()
    monkeypatch.setattr(type(vgx), "_z_maxima_bound", lambda self, win: None)
    without = _scene(open_window, seed)
    for a, b in zip(with_maxima, without):
        np.testing.assert_array_equal(a, b)


def test_whole_clear_sets_the_maxima(open_window, vgx):
    """czclear of the whole window leaves the maxima fresh at the cleared
    value (no rebuild); a partial one marks them for a rebuild."""
    open_window(W, H)
    zbuffer(TRUE)
    fb = vgx.current.fb
    fb.z_maxima()
    czclear(0, 1000)
    assert fb.zmax_fresh and (fb.zmax == 1000).all()
    scrmask(0, 20, 0, 20)
    czclear(0, 5)
    assert not fb.zmax_fresh
    assert fb.z_maxima()[0, 0] == 5 and fb.z_maxima()[0, 2] == 1000


def test_walker_reads_the_maxima(open_window, vgx, monkeypatch):
    """Maxima below every stored z (wrong on purpose) make an eligible pass
    skip every span, and an ineligible one (ZF_ALWAYS) ignore them."""
    open_window(W, H)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    fb = vgx.current.fb
    low = np.full_like(fb.z_maxima(), -0x800000)
    monkeypatch.setattr(type(fb), "z_maxima", lambda self: low)
    rnd = np.random.default_rng(5)
    _tris(rnd, 5)
    assert (colour() == 0).all()
    zfunction(ZF_ALWAYS)
    _tris(rnd, 5)
    assert (colour() != 0).any()


def test_a_pass_that_changes_no_z_keeps_the_maxima(open_window, vgx):
    """A pass of triangles marks the maxima stale only when it changed a
    stored z (the walker reports it): redrawing the same triangles with
    ZF_EQUAL or ZF_LEQUAL and z writes on keeps them (Heidmann's lit
    passes); a triangle in front lowers z and marks them; the maxima then
    rebuilt equal those built from scratch."""
    from vgx_emulator.framebuffer import zmax
    open_window(W, H)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    fb = vgx.current.fb
    _tris(np.random.default_rng(7), 10)
    fb.z_maxima()
    assert fb.zmax_fresh
    for func in (ZF_EQUAL, ZF_LEQUAL):
        zfunction(func)
        _tris(np.random.default_rng(7), 10)         # the same triangles again
        z_bank()                                    # (flushes)
        assert fb.zmax_fresh, func
    zfunction(ZF_LESS)
    bgnpolygon()
    for x, y in ((0, 0), (W - 1, 0), (W - 1, H - 1)):
        c4i((255, 255, 255, 255))
        v3f((float(x), float(y), -0.99))
    endpolygon()
    z_bank()
    assert not fb.zmax_fresh
    fresh = zmax.empty(H, W)
    zmax.build(fb.z, fresh, 0, W - 1, 0, H - 1)
    np.testing.assert_array_equal(fb.z_maxima(), fresh)


@pytest.mark.parametrize("width", [1, 5, 16, 37, 1280])
def test_build_takes_the_maximum_of_every_segment(width):
    from vgx_emulator.framebuffer import zmax
    rnd = np.random.default_rng(width)
    z = rnd.integers(-0x800000, 0x800000, (7, width)).astype(np.int32)
    out = zmax.empty(7, width)
    zmax.build(z, out, 0, width - 1, 0, 6)
    for y in range(7):
        for s in range(out.shape[1]):
            assert out[y, s] == z[y, s * zmax.SEGMENT:(s + 1) * zmax.SEGMENT].max()


def _small_tri(rnd, x, y, size, z):
    bgnpolygon()
    for dx, dy in ((0, 0), (size, 0), (0, size)):
        c4i((255, int(rnd.integers(0, 256)), 0, 255))
        v3f((x + dx, y + dy, z + float(rnd.uniform(-0.05, 0.05))))
    endpolygon()


def test_a_small_pass_marks_only_its_box(open_window, vgx, monkeypatch):
    """A pass that writes z marks the pixels its vertices span (within the
    scissor), not the window; the next use rebuilds that rectangle only,
    and the maxima equal those built from scratch.  Marks made before a
    use are joined (z_written)."""
    from vgx_emulator.framebuffer import zmax
    open_window(W, H)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    zbuffer(TRUE)
    czclear(0, getgdesc(GD_ZMAX))
    fb = vgx.current.fb
    fb.z_maxima()
    _small_tri(np.random.default_rng(0), 40.25, 20.25, 6.0, 0.0)
    z_bank()                                            # (flushes)
    # (this ortho puts window x at object x + 0.5): the floor of the
    # vertices' extent 40.75..46.75, 20.75..26.75
    assert fb.zmax_dirty == (40, 46, 20, 26)
    scrmask(0, 43, 0, H - 1)
    _small_tri(np.random.default_rng(0), 40.25, 30.25, 6.0, 0.0)
    z_bank()
    # the second pass read the maxima (rebuilt over the first box), then
    # marked its own box, cut at the scissor
    assert fb.zmax_dirty == (40, 43, 30, 36)
    fresh = zmax.empty(H, W)
    zmax.build(fb.z, fresh, 0, W - 1, 0, H - 1)
    built = []
    build = zmax.build
    monkeypatch.setattr(zmax, "build", lambda z, out, *rect: built.append(rect) or
                        build(z, out, *rect))
    np.testing.assert_array_equal(fb.z_maxima(), fresh)
    assert built == [(40, 43, 30, 36)]
    fb.z_written(box=(3, 5, 1, 2))
    fb.z_written(box=(9, 8, 0, 60))                     # empty: nothing
    fb.z_written(box=(7, 20, 4, 4))
    assert fb.zmax_dirty == (3, 20, 1, 4)
    fb.z_written()                                      # anywhere
    assert fb.zmax_dirty == (0, W - 1, 0, H - 1)


@pytest.mark.parametrize("seed", [4, 5])
def test_maxima_rebuilt_where_written_equal_a_whole_rebuild(open_window, vgx, seed):
    """Small triangles anywhere (partly outside the window), every z
    function, scissored passes and partial clears: after each pass the
    maxima a pass would read equal those built from the whole bank."""
    from vgx_emulator.framebuffer import zmax
    open_window(W, H)
    ortho(-0.5, W - 0.5, -0.5, H - 0.5, -1.0, 1.0)
    zbuffer(TRUE)
    czclear(0, -0x700000)           # (far below the triangles: each pass moves maxima)
    fb = vgx.current.fb
    rnd = np.random.default_rng(seed)
    fresh = zmax.empty(H, W)
    fb.z_maxima()
    moved = 0
    for i in range(40):
        zfunction(int(rnd.choice([ZF_LESS, ZF_LEQUAL, ZF_GREATER, ZF_ALWAYS])))
        if i % 7 == 3:
            x0, y0 = int(rnd.integers(0, W - 10)), int(rnd.integers(0, H - 10))
            scrmask(x0, x0 + int(rnd.integers(0, 30)), y0, y0 + int(rnd.integers(0, 20)))
            zclear() if i % 2 else _small_tri(rnd, float(x0), float(y0), 20.0, -0.5)
            scrmask(0, W - 1, 0, H - 1)
        _small_tri(rnd, float(rnd.uniform(-8, W)), float(rnd.uniform(-8, H)),
                   float(rnd.uniform(1, 40)), float(rnd.uniform(-0.9, 0.9)))
        z_bank()
        before = fb.zmax.copy()
        zmax.build(fb.z, fresh, 0, W - 1, 0, H - 1)
        np.testing.assert_array_equal(fb.z_maxima(), fresh)
        moved += not np.array_equal(before, fresh)
    assert moved >= 20                  # (the passes did move the maxima)


@pytest.mark.parametrize("x0, x1", [(0, 36), (5, 5), (16, 31), (17, 36), (33, 36), (30, 34)])
def test_build_of_a_rectangle_touches_its_segments_only(x0, x1):
    """build over pixels x0..x1 of rows 2..4 writes exactly the segments
    holding them (the last, partial one included), each the maximum of its
    whole segment."""
    from vgx_emulator.framebuffer import zmax
    rnd = np.random.default_rng(x0 * 100 + x1)
    z = rnd.integers(-0x800000, 0x800000, (7, 37)).astype(np.int32)
    out = np.full((7, 3), 7, np.int32)
    zmax.build(z, out, x0, x1, 2, 4)
    want = np.full((7, 3), 7, np.int32)
    for y in range(2, 5):
        for s in range(x0 // zmax.SEGMENT, x1 // zmax.SEGMENT + 1):
            want[y, s] = z[y, s * zmax.SEGMENT:(s + 1) * zmax.SEGMENT].max()
    np.testing.assert_array_equal(out, want)
