"""Short spans padded to whole vectors (config.PAD_SPAN, scan/triangles.py).

The padding is an optimisation that must never change a pixel: the walker
starts a short span's loop early (or ends it late) inside the row, and the
extra pixels must fail like a 0 pattern bit.  Each scene is drawn with no
padding (PAD_SPAN 0), with the default, and with every span of
config.PAD_MIN pixels or more padded (a huge PAD_SPAN), on banks that hold different values everywhere (so a
padding pixel that stored anything but its own old value shows), and the
colour, z and stencil banks must be identical.  The scenes have many
small triangles (spans of 1-12 pixels), spans at both ends of the row
(the loop must stay inside it), a scrmask that cuts spans, a pattern,
blending, stencil counting and a window narrower than one vector.
"""
import numpy as np
import pytest

from irisgl import (BF_ONE, BF_ZERO, PATTERN_16, SF_ALWAYS, SF_GEQUAL, ST_INCR, ST_KEEP,
                    ST_REPLACE, TRUE, ZF_ALWAYS, ZF_LESS, bgnpolygon, blendfunction, c4i,
                    defpattern, endpolygon, lrectwrite, scrmask, setpattern, stencil, v3f,
                    zfunction)
from vgx_emulator import config

from banks import colour, depth_stencil_window, stencil_bank, z_bank


def _tris(rnd, n, w, h, size):
    """n random triangles of about ``size`` pixels, many of them at the
    left and right ends of the rows."""
    for _ in range(n):
        where = rnd.integers(0, 3)
        cx = {0: rnd.uniform(-2, 4), 1: rnd.uniform(w - 4, w + 2)}.get(where, rnd.uniform(0, w))
        cy = rnd.uniform(-2, h + 2)
        bgnpolygon()
        for _ in range(3):
            c4i((int(rnd.integers(0, 256)), int(rnd.integers(0, 256)),
                 int(rnd.integers(0, 256)), int(rnd.integers(0, 256))))
            v3f((float(cx + rnd.uniform(-size, size)), float(cy + rnd.uniform(-size, size)),
                 float(rnd.uniform(-0.9, 0.9))))
        endpolygon()


def _scene(open_window, seed, w, h):
    depth_stencil_window(open_window, w, h)
    rnd = np.random.default_rng(seed)
    lrectwrite(0, 0, w - 1, h - 1,
               rnd.integers(0, 1 << 32, w * h, dtype=np.uint64).astype(np.uint32))
    # z different everywhere (large triangles at any z) and the stencil
    # varied (small ones, each set replacing it with its own value)
    zfunction(ZF_ALWAYS)
    _tris(rnd, 8, w, h, 2 * w)
    for ref in range(1, 9):
        stencil(TRUE, ref * 29, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_REPLACE)
        _tris(rnd, 12, w, h, 4)
    lrectwrite(0, 0, w - 1, h - 1,
               rnd.integers(0, 1 << 32, w * h, dtype=np.uint64).astype(np.uint32))
    zfunction(ZF_LESS)
    stencil(TRUE, 100, SF_GEQUAL, 0xFF, ST_KEEP, ST_INCR, ST_INCR)
    _tris(rnd, 60, w, h, 3)                  # z and stencil written
    blendfunction(BF_ONE, BF_ONE)
    stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_INCR)
    _tris(rnd, 40, w, h, 6)                  # additive, stencil counting
    blendfunction(BF_ONE, BF_ZERO)
    scrmask(1, w - 2, 1, h - 2)
    _tris(rnd, 40, w, h, 4)                  # spans cut by the scrmask
    scrmask(0, w - 1, 0, h - 1)
    defpattern(1, PATTERN_16, [0x5A5A, 0x3C3C] * 8)
    setpattern(1)
    _tris(rnd, 40, w, h, 5)                  # pattern
    setpattern(0)
    return colour(), z_bank(), stencil_bank()


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("w, h", [(45, 20), (5, 7)])
def test_padding_changes_no_bank(open_window, vgx, monkeypatch, seed, w, h):
    got = {}
    for pad in (0, config.PAD_SPAN, 1 << 30):
        monkeypatch.setattr(config, "PAD_SPAN", pad)
        vgx.reset()
        got[pad] = _scene(open_window, seed, w, h)
    banks = list(got.values())
    for other in banks[1:]:
        for a, b in zip(banks[0], other):
            np.testing.assert_array_equal(a, b)
    colours, z, s = banks[0]
    # the scene does reach every bank in varied ways
    assert len(np.unique(z)) > w * h // 4 and len(np.unique(s)) > 4
