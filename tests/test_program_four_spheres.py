"""programs/four_spheres.py (Williams 1978, fig. 1) runs headless and draws
four spheres lit from the left by a light at infinity turned 100 degrees
from the viewer's bearing."""
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from vgx_emulator import run_program

ROOT = Path(__file__).resolve().parent.parent
PROGRAM = ROOT / "programs" / "four_spheres.py"


@pytest.fixture(scope="module")
def image():
    return run_program(PROGRAM, frames=1)


def _blobs(mask):
    """Column runs of a boolean mask's occupied columns: [(x0, x1), ...]."""
    cols = mask.any(axis=0)
    runs, start = [], None
    for x, on in enumerate(cols):
        if on and start is None:
            start = x
        if not on and start is not None:
            runs.append((start, x - 1))
            start = None
    if start is not None:
        runs.append((start, len(cols) - 1))
    return runs


def test_draws_four_separate_spheres(image):
    assert image.shape == (480, 640, 3)
    lum = image.astype(int).sum(axis=2)
    # the ambient term alone (0.1 model + 0.15 material) makes every sphere
    # pixel non-black; the background stays the czclear colour, black
    assert lum[0, 0] == 0 and lum[-1, -1] == 0
    assert len(_blobs(lum > 0)) == 4


def test_light_comes_from_the_left(image):
    """Light direction (-sin 100deg, 0, cos 100deg): on every sphere the left
    edge is lit (N.L > 0) and the right half is in its own shade."""
    lum = image.astype(int).sum(axis=2)
    for x0, x1 in _blobs(lum > 0):
        rows = np.nonzero((lum[:, x0:x1 + 1] > 0).any(axis=1))[0]
        y = (rows[0] + rows[-1]) // 2
        width = x1 - x0
        left = lum[y, x0 + width // 8]
        right = lum[y, x1 - width // 8]
        assert left > 2 * right, (x0, x1, left, right)


def test_shade_side_is_ambient_only(image):
    """Where N.L <= 0 only the ambient terms remain: material ambient 0.15 x
    model ambient 0.1 + light ambient 0 -> 0.015 * 255 = 3.8 -> 4."""
    lum = image.astype(int)
    x0, x1 = _blobs(lum.sum(axis=2) > 0)[0]
    rows = np.nonzero((lum[:, x0:x1 + 1].sum(axis=2) > 0).any(axis=1))[0]
    y = (rows[0] + rows[-1]) // 2
    px = lum[y, x1 - 3]
    expected = round(0.15 * 0.1 * 255)
    assert all(abs(c - expected) <= 1 for c in px), px


def test_vgx_run_writes_the_png(tmp_path):
    out = tmp_path / "fs.png"
    r = subprocess.run([sys.executable, "-m", "vgx_emulator.runner", str(PROGRAM),
                        "--out", str(out)], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    from PIL import Image
    img = np.asarray(Image.open(out))
    assert img.shape == (480, 640, 3) and img.max() > 100


def test_same_picture_with_one_and_two_threads(tmp_path, image):
    """The banded walker draws each pixel's triangles in submission order, so
    the thread count cannot change a pixel."""
    out = tmp_path / "one.png"
    env = dict(os.environ, NUMBA_NUM_THREADS="1")
    r = subprocess.run([sys.executable, "-m", "vgx_emulator.runner", str(PROGRAM),
                        "--out", str(out)], capture_output=True, text=True, cwd=ROOT, env=env)
    assert r.returncode == 0, r.stderr
    from PIL import Image
    assert np.array_equal(np.asarray(Image.open(out)), image)
