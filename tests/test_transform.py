"""The vertex transform of the Geometry Engine (docs/semantics.md §2): every
vertex, a row vector (x, y, z, w), times the modelview matrix in force when
it was sent (eye coordinates) and times modelview x projection (clip
coordinates).  geometry._transform multiplies in chunks and run by run; the
expectations here are the products written out row by row."""
import importlib

import numpy as np
import pytest

from vgx_emulator.geometry.batch import RECORD, Transform

G = importlib.import_module("vgx_emulator.geometry")


def _expected(pos, xf, xforms):
    eye = np.array([[sum(p[i] * xforms[k].modelview[i, j] for i in range(4)) for j in range(4)]
                    for p, k in zip(pos, xf)]).reshape(-1, 4)
    clp = np.array([[sum(p[i] * xforms[k].clip[i, j] for i in range(4)) for j in range(4)]
                    for p, k in zip(pos, xf)]).reshape(-1, 4)
    return eye, clp


def _case(n, runs, nx, seed):
    rng = np.random.default_rng(seed)
    xforms = [Transform(rng.normal(size=(4, 4)), rng.normal(size=(4, 4))) for _ in range(nx)]
    pos = rng.normal(size=(n, 4))
    # runs of vertices under one transform, as a program changing matrices
    # between primitives sends them
    bounds = np.sort(rng.choice(np.arange(1, n), runs - 1, replace=False)) if runs > 1 else []
    xf = np.zeros(n, np.int64)
    for k, b in enumerate(bounds):
        xf[b:] = (k + 1) % nx
    attrs = np.zeros((n, RECORD))
    attrs[:, 8] = xf
    return pos, attrs, xf, xforms


@pytest.mark.parametrize("n, runs, nx", [
    (9000, 1, 1),        # one transform, more rows than one chunk (_PRODUCT_ROWS)
    (300, 7, 3),         # a few runs, multiplied run by run
    (400, 90, 5),        # a matrix change every few vertices: one einsum
    (5000, 3, 2),        # runs longer than a chunk
])
def test_eye_and_clip_coordinates_of_every_vertex(n, runs, nx):
    pos, attrs, xf, xforms = _case(n, runs, nx, seed=n + runs)
    eye, clp, got_xf = G._transform(pos, attrs, xforms)
    want_eye, want_clp = _expected(pos, xf, xforms)
    assert (got_xf == xf).all()
    # the sums of four products in a different order: a few ulps apart
    assert np.allclose(eye, want_eye, rtol=1e-12, atol=1e-12)
    assert np.allclose(clp, want_clp, rtol=1e-12, atol=1e-12)


def test_an_empty_batch_transforms_to_nothing():
    pos, attrs = np.zeros((0, 4)), np.zeros((0, RECORD))
    xforms = [Transform(np.eye(4), np.eye(4)), Transform(2 * np.eye(4), np.eye(4))]
    eye, clp, xf = G._transform(pos, attrs, xforms)
    assert eye.shape == clp.shape == (0, 4) and len(xf) == 0


def test_non_finite_input_stays_non_finite():
    """A vertex with an infinite coordinate gives non-finite coordinates (the
    batch then drops its triangles with a warning), not an error."""
    pos = np.array([[np.inf, 0.0, 0.0, 1.0], [1.0, 2.0, 3.0, 1.0]])
    attrs = np.zeros((2, RECORD))
    with np.errstate(all="ignore"):
        eye, clp, _ = G._transform(pos, attrs, [Transform(np.eye(4), np.eye(4))])
    assert not np.isfinite(eye[0]).all() and np.isfinite(eye[1]).all()
    assert (eye[1] == [1.0, 2.0, 3.0, 1.0]).all()
