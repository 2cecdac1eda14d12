"""vgx_emulator/specialise.py: a raster state whose own kernels are not
compiled runs on the general variant of its family (raster.variants.general)
with neutral banks and parameters, bit for bit the same pixels, while a
second process compiles its own variant; the next pass loads that one."""
import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from test_kernel_cache import LISTEN

from irisgl._current import machine
from vgx_emulator import gallery, specialise
from vgx_emulator.precompile import common_key
from vgx_emulator.raster import blend, variants
from vgx_emulator.runner import run_program

ROOT = Path(__file__).resolve().parent.parent
FIGURES = gallery.collect(ROOT / "programs")
BANKS = ("front", "back", "z", "stencil", "accum")


def _figure(prog, fig, mode, monkeypatch):
    monkeypatch.setattr(specialise, "MODE", mode)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        img = run_program(prog, frames=fig.get("frames", 1), argv=fig.get("args", []))
    fb = machine.current.fb if machine.current is not None else None
    return img, {n: (None if fb is None or getattr(fb, n) is None else getattr(fb, n).copy())
                 for n in BANKS}


@pytest.mark.parametrize("prog,fig", [(p, f) for p, f, _ in FIGURES],
                         ids=[gallery._stem(p, f) for p, f, _ in FIGURES])
def test_every_figure_draws_the_same_on_the_general_variants(prog, fig, monkeypatch):
    """Each gallery figure (every raster state the seed programs and demos
    use: z, stencil counting, blending, logicop, patterns, writemasks,
    colour-map mode, texture, lines, points, text): the picture and every
    bank the same when every pass runs on its family's general variant as
    when it runs on its own."""
    a_img, a = _figure(prog, fig, "0", monkeypatch)
    b_img, b = _figure(prog, fig, "always", monkeypatch)
    assert (a_img is None) == (b_img is None)
    if a_img is not None:
        assert np.array_equal(a_img, b_img)
    for name in BANKS:
        assert (a[name] is None) == (b[name] is None), name
        if a[name] is not None:
            assert np.array_equal(a[name], b[name]), name


def test_the_general_variant_keeps_what_setup_and_colour_depend_on():
    """general() turns every per-fragment stage on but blending and the
    second colour buffer, and keeps Gouraud, colour-map mode, two-sided
    colours and texture; a blending key's general variant has the generic
    blend; a key that is its own general variant is left alone."""
    k = common_key()._replace(ztest=False, zwrite=False, twoside=True)
    g = variants.general(k)
    assert (g.ztest, g.zwrite, g.color, g.stencil, g.logic, g.atest, g.pattern,
            g.cmask) == (True, True, True, 2, True, True, True, True)
    assert (g.blend, g.dual) == (0, False)
    assert (g.gouraud, g.cmode, g.twoside, g.texture) == (True, False, True, False)
    folded = blend.key_code(blend.BF_SA, blend.BF_MSA)
    assert folded != blend.GENERIC
    gb = variants.general(k._replace(blend=folded, dual=True))
    assert (gb.blend, gb.dual) == (blend.GENERIC, True)
    cm = variants.general(k._replace(cmode=True, color=False, blend=folded))
    assert cm.blend == 0 and not cm.atest and not cm.gouraud   # no colour: no planes
    assert variants.general(g) == g and variants.general(gb) == gb


def test_neutral_uses_scratch_banks_only_for_what_the_key_leaves_off():
    """The banks the state uses are passed as they are; the ones it does
    not use are scratch banks of the window's size, never the window's."""
    front = np.zeros((6, 9), np.uint32)
    z = np.zeros((6, 9), np.int32)
    key = common_key()
    planes = (front, variants._DUMMY_C, z, variants._DUMMY_S, variants._SOLID)
    ip = np.zeros(44, np.int64)
    (c0, c1, zb, sb, pat), p = variants.neutral(key, planes, ip, variants.bank_shape(key, planes))
    assert c0 is front and c1 is variants._DUMMY_C and zb is z
    assert sb.shape == (6, 9) and sb is not variants._DUMMY_S
    assert pat.shape == (1, 9) and pat.all()
    assert p is not ip and not ip.any()
    nz = key._replace(ztest=False, zwrite=False)
    (_, _, zb2, _, _), _ = variants.neutral(nz, planes, ip, (6, 9))
    assert zb2 is not z and zb2.shape == (6, 9)


SCENE = LISTEN + r"""
import numpy as np
from irisgl import *
from vgx_emulator import specialise
prefsize(32, 32); winopen("x"); RGBmode(); stensize(4); gconfig()
ortho2(-0.5, 31.5, -0.5, 31.5)
zbuffer(TRUE); czclear(0, getgdesc(GD_ZMAX)); shademodel(GOURAUD)
bgnpolygon(); c3f((1, 0, 0)); v2f((1, 1)); c3f((0, 1, 0)); v2f((30, 2)); c3f((0, 0, 1)); v2f((9, 28))
endpolygon(); gflush()                              # the common state: warmed

def new_states():
    czclear(0x40404040, getgdesc(GD_ZMAX))
    blendfunction(BF_SA, BF_MSA); cpack(0x80ff8000); rectf(4, 4, 20, 20)
    move2(1, 30); draw2(30, 1)                      # a blended line
    blendfunction(BF_ONE, BF_ZERO)
    sclear(0); stencil(TRUE, 1, SF_ALWAYS, 0xf, ST_KEEP, ST_KEEP, ST_INCR)
    cpack(0xff0000ff); rectf(2, 2, 12, 12)
    stencil(FALSE, 0, SF_ALWAYS, 0xf, ST_KEEP, ST_KEEP, ST_KEEP)
    gflush()
    return int(lrectread(0, 0, 31, 31).astype(np.uint64).sum())

def own_loaded():
    # how many of the requested variants this process has loaded
    return sum(bool(specialise.dispatcher(kind, key).overloads)
               for kind, key in specialise._requested)

compiled.names.clear()
first = new_states()
for _ in range(2):                                  # config.SPECIALISE_AFTER passes
    assert new_states() == first
print(first, ",".join(compiled.names) or "-", len(specialise._requested), own_loaded())
specialise.wait(600)
compiled.names.clear()
again = new_states()
print(again, ",".join(compiled.names) or "-", len(specialise._requested), own_loaded())
"""


def _python(code, cache, **env):
    e = dict(os.environ, NUMBA_CACHE_DIR=str(cache), VGX_PRECOMPILE="0", **env)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=1200, env=e, cwd=ROOT)
    assert r.returncode == 0, r.stderr[-3000:]
    return r.stdout.strip().splitlines()


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="no core for a second process")
def test_a_new_state_runs_at_once_and_its_own_variant_follows(tmp_path):
    """With the general variants in the cache (precompile.warm, as the first
    run on a machine leaves them), a process meeting new states (a blend,
    a blended line, stencil counting) compiles no walker and no line kernel:
    it runs them on the general variants and asks a second process for
    their own; once that has finished, the same states load their own
    variants from the cache (still nothing compiled).  The pixels are those
    of a process that compiled every variant itself."""
    _python("from vgx_emulator.precompile import warm; warm()", tmp_path / "c")
    first, again = _python(SCENE, tmp_path / "c")
    ref = _python(SCENE, tmp_path / "ref", VGX_GENERAL="0")
    checksum, names, requested, loaded = first.split()
    assert "walk" not in names and "draw_lines" not in names, names
    assert int(requested) >= 3 and loaded == "0"    # two walker states and a line state
    checksum2, names2, requested2, loaded2 = again.split()
    assert names2 == "-" and requested2 == requested and loaded2 == requested
    assert checksum == checksum2 == ref[0].split()[0]
    # the process that compiled its own variants compiled walkers and lines
    assert "walk" in ref[0] and "draw_lines" in ref[0]
