"""Smoke test of benchmarks/vs_mesa.py: the module imports, and a tiny
workload run through both sides (emulator and Mesa's llvmpipe) leaves
pictures that are not blank and mostly agree.  Skipped where OSMesa or
PyOpenGL is missing (as tests/test_mesa_crosscheck.py)."""
import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _load_vs_mesa():
    spec = importlib.util.spec_from_file_location("vs_mesa",
                                                  ROOT / "benchmarks" / "vs_mesa.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


try:
    import OpenGL  # noqa: F401
except ImportError as e:
    pytest.skip(f"vs_mesa smoke test skipped: PyOpenGL unavailable ({e})",
                allow_module_level=True)
vs_mesa = _load_vs_mesa()          # an error in the benchmark itself fails, not skips
try:
    vs_mesa.Mesa().close()
except Exception as e:  # missing libOSMesa, context failure
    _reason = (f"vs_mesa smoke test skipped: OSMesa/PyOpenGL unavailable "
               f"({type(e).__name__}: {e}). Install libosmesa6 (apt) and PyOpenGL (pip).")
    print(_reason, file=sys.stderr)
    pytest.skip(_reason, allow_module_level=True)


@pytest.fixture(scope="module")
def mesa():
    """The benchmark's context; closing it gives back the one current before."""
    m = vs_mesa.Mesa()
    yield m
    m.close()


# (workload, largest fraction of pixels whose RGB may differ by more than 8)
CASES = [
    ("fill-z", 0.0),          # affine colours, full-screen quads: exact
    ("fill-stencil", 0.0),    # every pixel counts to 32 on both sides
    ("spheres", 0.05),        # lit; edge pixels follow each side's fill rule
    ("spheres-depth", 0.05),  # the z-buffers, scaled alike
    ("heidmann-spheres", 0.05),  # stencil volumes the 1991 way; edge pixels as spheres
]


@pytest.mark.parametrize("name, tolerance", CASES)
def test_workload_pictures_agree(mesa, name, tolerance):
    r = vs_mesa.run_workload(name, mesa, 64, 64, reps=1)
    emu, gl = r["images"]
    assert emu.shape == gl.shape == (64, 64, 3)
    drawn = (emu.max(axis=2) > 0).mean()
    assert drawn > 0.3, f"{name}: the emulator's picture is nearly blank ({drawn:.0%} drawn)"
    assert r["differs"] <= tolerance, (
        f"{name}: {r['differs']:.2%} of pixels differ by more than "
        f"{vs_mesa.DIFF_THRESHOLD} (allowed {tolerance:.0%})")
    assert len(r["emu"]) == len(r["mesa"]) == 1 and min(r["emu"] + r["mesa"]) > 0

