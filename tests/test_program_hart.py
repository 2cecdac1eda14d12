"""programs/hart_shadow_buffer.py (Hart, CS418 slides on shadows): the
shadow buffer from a lit and an ambient-only eye render and the light's
perspective z-buffer; percentage-closer filtering; the perspective depth
mapping z_window = ALPHA + BETA / z_eye.

Expected places are computed here with numpy from the program's constants:
the sphere's centre projected from the light onto the ground, then through
the eye's lookat and perspective (docs/semantics.md §2) to window pixels.
"""
import ast
import re
from pathlib import Path

import numpy as np
import pytest

import programs.hart_shadow_buffer as H
from vgx_emulator import run_program

from reference.camera import lookat_matrix, perspective_matrix

PROGRAM = H.__file__
W, HT = H.WIDTH, H.HEIGHT
ZMIN, ZMAX = -0x800000, 0x7FFFFF


# -- camera (docs/semantics.md §2, row vectors) ----------------------------------


EYE_MVP = lookat_matrix(H.EYE, H.EYE_AT) @ perspective_matrix(H.FOVY, W / HT, H.NEAR, H.FAR)


def to_pixel(p):
    """Nearest eye-window pixel (x, y) of a world point, and the image row."""
    c = np.append(np.asarray(p, float), 1.0) @ EYE_MVP
    x = (c[0] / c[3] + 1) / 2 * W - 0.5
    y = (c[1] / c[3] + 1) / 2 * HT - 0.5
    xi, yi = int(round(x)), int(round(y))
    return xi, yi, HT - 1 - yi        # images are top row first


def shadow_geometry():
    """The ground point G on the line from the light through the sphere's
    centre, a horizontal unit vector across the shadow, and the shadow's
    half width there (the sphere's radius scaled by the central projection)."""
    L, S = np.asarray(H.LIGHT_POS, float), np.asarray(H.SPHERE_C, float)
    t = L[1] / (L[1] - S[1])
    G = L + t * (S - L)
    d = (S - L)[[0, 2]]
    d /= np.linalg.norm(d)
    across = np.array([-d[1], 0.0, d[0]])
    if across[2] < 0:                 # towards the viewer
        across = -across
    return G, across, H.SPHERE_R * t


@pytest.fixture(scope="module")
def images():
    return {f: run_program(PROGRAM, frames=1, argv=["--figure", f]).astype(int)
            for f in ("lit", "ambient", "hard", "pcf")}


def test_figures_literal():
    tree = ast.parse(Path(PROGRAM).read_text())
    figs = next(ast.literal_eval(n.value) for n in tree.body if isinstance(n, ast.Assign)
                and any(getattr(t, "id", None) == "FIGURES" for t in n.targets))
    assert [f["name"] for f in figs] == ["light_depth", "lit", "ambient", "hard", "pcf",
                                         "depth_mapping"]
    assert all(f["args"][0] == "--figure" and f["caption"] for f in figs)


def test_images_are_eye_view(images):
    for img in images.values():
        assert img.shape == (HT, W, 3)


def test_light_depth_figure_is_light_window():
    img = run_program(PROGRAM, frames=1, argv=["--figure", "light"])
    assert img.shape == (H.LSIZE, H.LSIZE, 3)
    assert img.max() == 255 and (img.sum(axis=-1) == 0).any()


def test_sphere_shadow_centre_is_ambient(images):
    G, _, _ = shadow_geometry()
    assert abs(G[0]) < H.GROUND_HALF and abs(G[2]) < H.GROUND_HALF
    x, y, row = to_pixel(G)
    assert 0 <= x < W and 0 <= y < HT
    lit, amb, hard = images["lit"][row, x], images["ambient"][row, x], images["hard"][row, x]
    assert (lit - amb).max() > 20, "the spot light must reach the shadowed ground"
    assert np.array_equal(hard, amb)
    assert np.array_equal(images["pcf"][row, x], amb)


def test_lit_ground_beside_the_shadow_is_lit(images):
    G, across, half = shadow_geometry()
    P = G + across * (half + 0.9)
    x, y, row = to_pixel(P)
    lit, amb, hard = images["lit"][row, x], images["ambient"][row, x], images["hard"][row, x]
    assert (lit - amb).max() > 20
    assert np.array_equal(hard, lit)
    assert np.array_equal(images["pcf"][row, x], lit)


def test_no_acne_on_lit_ground(images):
    """A 21 x 21 patch of open ground beside the shadow: every pixel lit."""
    G, across, half = shadow_geometry()
    x, y, row = to_pixel(G + across * (half + 1.2))
    sl = (slice(row - 10, row + 11), slice(x - 10, x + 11))
    assert np.array_equal(images["hard"][sl], images["lit"][sl])
    assert np.array_equal(images["pcf"][sl], images["lit"][sl])


def test_pcf_fractional_along_shadow_edge(images):
    """Crossing the shadow's edge from G outwards: the hard shadow jumps from
    ambient to lit, PCF passes through values strictly between."""
    G, across, half = shadow_geometry()
    lit, amb, hard, pcf = (images[k] for k in ("lit", "ambient", "hard", "pcf"))
    fracs, seen = [], set()
    for s in np.linspace(0.0, half + 0.9, 400):
        x, y, row = to_pixel(G + across * s)
        if (x, row) in seen:
            continue
        seen.add((x, row))
        a, l, h, p = amb[row, x], lit[row, x], hard[row, x], pcf[row, x]
        assert np.array_equal(h, a) or np.array_equal(h, l)
        span = l - a
        k = int(np.argmax(span))
        assert span[k] > 20
        f = (p[k] - a[k]) / span[k]
        assert -0.02 <= f <= 1.02
        # every channel between ambient and lit
        assert np.all(np.minimum(a, l) - 1 <= p) and np.all(p <= np.maximum(a, l) + 1)
        fracs.append(f)
    fracs = np.array(fracs)
    assert fracs[0] == 0.0 and fracs[-1] == 1.0
    inner = fracs[(fracs > 0.05) & (fracs < 0.95)]
    assert len(inner) >= 1
    # the whole image: a soft band along every shadow edge
    ch = 1
    span = lit[..., ch] - amb[..., ch]
    strict = (span > 20) & (pcf[..., ch] > amb[..., ch] + 2) & (pcf[..., ch] < lit[..., ch] - 2)
    hard_strict = (span > 20) & (hard[..., ch] > amb[..., ch] + 2) & (hard[..., ch] < lit[..., ch] - 2)
    assert strict.sum() > 300
    assert hard_strict.sum() == 0


# -- the depth mapping -------------------------------------------------------------
def expected_alpha_beta(n, f, zn, zf):
    """z_window = (zf+zn)/2 + (zf-zn)/2 * z_ndc with z_ndc = (f+n)/(f-n) + 2fn/((f-n) z)."""
    return (zf + zn) / 2 + (zf - zn) / 2 * (f + n) / (f - n), (zf - zn) * f * n / (f - n)


def test_slide_alpha_beta():
    a, b = H.slide_alpha_beta(H.LNEAR, H.LFAR)
    P = perspective_matrix(H.LFOVY, 1.0, H.LNEAR, H.LFAR)
    assert a == pytest.approx(P[2][2]) and b == pytest.approx(P[3][2])
    A, B = H.window_alpha_beta(H.LNEAR, H.LFAR, ZMIN, ZMAX)
    assert (A, B) == pytest.approx(expected_alpha_beta(H.LNEAR, H.LFAR, ZMIN, ZMAX), rel=1e-12)


@pytest.mark.parametrize("zrange", [None, (0, 0x7FFFFF), (-0x400000, 0x600000)])
def test_readback_z_equals_alpha_plus_beta_over_z(zrange):
    H.open_light_window()
    from irisgl import lsetdepth, lgetdepth
    if zrange:
        lsetdepth(*zrange)
    zn, zf = lgetdepth()
    assert (zn, zf) == (zrange or (ZMIN, ZMAX))
    A, B = expected_alpha_beta(H.LNEAR, H.LFAR, zn, zf)
    Ap, Bp, a, b = H.depth_constants()          # from getmatrix + lgetdepth
    assert Ap == pytest.approx(A, rel=1e-6) and Bp == pytest.approx(B, rel=1e-6)
    got = H.depth_probe(H.PROBE_DISTANCES, H.LFOVY, 1.0, H.LSIZE, H.LSIZE)
    for d, z in zip(H.PROBE_DISTANCES, got):
        assert abs(z - (A + B / -d)) <= 1.0, (d, z, A + B / -d)


def test_depth_figure_prints_agreement(capsys):
    img = run_program(PROGRAM, frames=1, argv=["--figure", "depth"])
    assert img.shape == (HT, W, 3)
    out = capsys.readouterr().out
    rows = re.findall(r"^\s+([\d.]+)\s+(-?\d+)\s+(-?[\d.]+)\s+([+-][\d.]+)$", out, re.M)
    assert len(rows) == len(H.PROBE_DISTANCES)
    assert all(abs(float(r[3])) <= 1.0 for r in rows)
    A, B = expected_alpha_beta(H.LNEAR, H.LFAR, ZMIN, ZMAX)
    caption = next(f["caption"] for f in H.FIGURES if f["name"] == "depth_mapping")
    assert f"ALPHA = {A:.1f}" in caption and f"BETA = {B:.1f}" in caption
