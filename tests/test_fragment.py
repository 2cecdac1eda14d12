"""Writemasks, blending, alpha test, logic op and dither (docs/semantics.md §7).

Expectations are computed here from the man-page formulas.
"""

from functools import partial

import pytest

import vgx_emulator
from irisgl import *  # noqa: F401,F403
from irisgl import GLError

from banks import new_window, box, colour, indices, z_bank, stencil_bank


open_win = partial(new_window, pixels=True)      # pixel (i, j)'s centre at (i, j)



def comps(word):
    return [(word >> (8 * k)) & 0xFF for k in range(4)]   # R, G, B, A


def pack(c):
    return c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24)


# -- writemasks -----------------------------------------------------------------
OLD, NEW = 0x12345678, 0xEDCBA987


@pytest.mark.parametrize("mask", [0x000000FF, 0x0000FF00, 0x00FF0000, 0xFF000000,
                                  0x0F0F0F0F, 0xF00FF00F, 0xFFFFFFFF])
def test_wmpack_per_channel(mask):
    open_win(2, 2)
    czclear(OLD, 0)
    wmpack(mask)
    cpack(NEW)
    box(0, 0, 1, 1)
    assert (colour() == ((OLD & ~mask) | (NEW & mask)) & 0xFFFFFFFF).all()


def test_wmpack_zero_draws_no_colour_but_updates_z_and_stencil():
    open_win(2, 2, planes=8)
    zmax = getgdesc(GD_ZMAX)
    czclear(OLD, zmax)
    sclear(0)
    zbuffer(TRUE)
    stencil(TRUE, 42, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_REPLACE)
    wmpack(0)
    cpack(NEW)
    box(0, 0, 1, 1)
    assert (colour() == OLD).all()
    assert (z_bank() != zmax).all()
    assert (stencil_bank() == 42).all()


def test_wmpack_zero_then_depth_test_blocks_later_colour():
    """Heidmann's first pass: lay down z with colour off, then a farther
    primitive fails the z test where the invisible one was drawn."""
    open_win(4, 1)
    czclear(OLD, getgdesc(GD_ZMAX))
    zbuffer(TRUE)
    wmpack(0)
    ortho(-0.5, 3.5, -0.5, 0.5, -10, 10)
    subpixel(TRUE)
    pmv = [(-0.5, -0.5), (1.5, -0.5), (1.5, 0.5), (-0.5, 0.5)]
    polf(4, [(x, y, 5.0) for x, y in pmv])          # near (z = +5 is nearer: -z is depth)
    wmpack(0xFFFFFFFF)
    cpack(NEW)
    full = [(-0.5, -0.5), (3.5, -0.5), (3.5, 0.5), (-0.5, 0.5)]
    polf(4, [(x, y, -5.0) for x, y in full])        # farther
    assert list(colour()[0]) == [OLD, OLD, NEW, NEW]


def test_rgbwritemask_alpha_all_ones_high_bits_ignored():
    open_win(2, 2)
    czclear(OLD, 0)
    RGBwritemask(0x1F0, 0xF0F, 0xAFF)      # bits 8-15 ignored
    mask = 0xFF000000 | (0xFF << 16) | (0x0F << 8) | 0xF0
    assert getwritemask() & 0xFFFFFFFF == mask
    cpack(NEW)
    box(0, 0, 1, 1)
    assert (colour() == ((OLD & ~mask) | (NEW & mask)) & 0xFFFFFFFF).all()


def test_rgb_writemask_calls_are_errors_in_cmode():
    open_win(2, 2, rgb=False)
    with pytest.raises(GLError):
        RGBwritemask(1, 2, 3)
    with pytest.raises(GLError):
        wmpack(0xFF)
    # and writemask is the error in RGB mode
    open_win(2, 2)
    with pytest.raises(GLError):
        writemask(0xF)


@pytest.mark.parametrize("mask", [0x000, 0x00F, 0x0F0, 0xF00, 0xA5A, 0xFFF])
def test_writemask_in_cmode(mask):
    old, new = 0x3C5, 0xA6B
    open_win(2, 2, rgb=False)
    czclear(old, 0)
    writemask(mask)
    color(new)
    box(0, 0, 1, 1)
    assert (indices() == ((old & ~mask) | (new & mask)) & 0xFFF).all()


def test_gconfig_resets_colour_writemask():
    open_win(2, 2)
    wmpack(0)
    gconfig()
    cpack(NEW)
    box(0, 0, 1, 1)
    assert (colour() == NEW).all()


def test_zwritemask_zero_colour_written_z_kept():
    """z test still runs with zwritemask(0); colour is written where it
    passes, z is not updated, so a later farther primitive also passes."""
    open_win(3, 1)
    ortho(-0.5, 2.5, -0.5, 0.5, -10, 10)
    zmax = getgdesc(GD_ZMAX)
    czclear(OLD, zmax)
    zbuffer(TRUE)
    zwritemask(0)
    subpixel(TRUE)
    cpack(0xFF0000FF)
    polf(4, [(-0.5, -0.5, 5), (2.5, -0.5, 5), (2.5, 0.5, 5), (-0.5, 0.5, 5)])
    assert (z_bank() == zmax).all()
    cpack(NEW)
    polf(4, [(-0.5, -0.5, -5), (1.5, -0.5, -5), (1.5, 0.5, -5), (-0.5, 0.5, -5)])
    assert list(colour()[0]) == [NEW, NEW, 0xFF0000FF]


@pytest.mark.parametrize("zmask", [0xFF00FF, 0x00FFFF, 0x000001])
def test_zwritemask_per_bit_with_colour(zmask):
    open_win(2, 1)
    ortho(-0.5, 1.5, -0.5, 0.5, -1, 1)
    old_z = 0x7F0F0F
    czclear(OLD, old_z)
    zbuffer(TRUE)
    zfunction(ZF_ALWAYS)
    zwritemask(zmask)
    cpack(NEW)
    box(0, 0, 1, 0)                      # z = 0 plane -> stored value 0
    v = ((old_z & ~zmask) | (0 & zmask)) & 0xFFFFFF
    if v & 0x800000:
        v -= 0x1000000
    assert (z_bank() == v).all()
    assert (colour() == NEW).all()


# -- blending --------------------------------------------------------------------
SRC_FACTORS = ["BF_ZERO", "BF_ONE", "BF_DC", "BF_MDC", "BF_SA", "BF_MSA", "BF_DA",
               "BF_MDA", "BF_MIN_SA_MDA"]
DST_FACTORS = ["BF_ZERO", "BF_ONE", "BF_SC", "BF_MSC", "BF_SA", "BF_MSA", "BF_DA", "BF_MDA"]


def _factor(name, sc, dc, sa, da):
    return {
        "BF_ZERO": 0.0, "BF_ONE": 1.0, "BF_DC": dc, "BF_SC": sc,
        "BF_MDC": 1.0 - dc, "BF_MSC": 1.0 - sc, "BF_SA": sa, "BF_MSA": 1.0 - sa,
        "BF_DA": da, "BF_MDA": 1.0 - da, "BF_MIN_SA_MDA": min(sa, 1.0 - da),
    }[name]


def blend_model(sname, dname, src, dst):
    s = [c / 255.0 for c in comps(src)]
    d = [c / 255.0 for c in comps(dst)]
    out = []
    for k in range(4):
        v = s[k] * _factor(sname, s[k], d[k], s[3], d[3]) + \
            d[k] * _factor(dname, s[k], d[k], s[3], d[3])
        out.append(min(max(v, 0.0), 1.0) * 255.0)
    return out


PAIRS = [  # (source, destination) words 0xAABBGGRR
    (0x80C04020, 0x40206080),
    (0xFF102030, 0x00F0E0D0),
    (0x33FFFF00, 0xCC00FF80),
]


@pytest.mark.parametrize("dname", DST_FACTORS)
@pytest.mark.parametrize("sname", SRC_FACTORS)
def test_blendfunction_formula(sname, dname):
    open_win(len(PAIRS), 1)
    for x, (_, dst) in enumerate(PAIRS):
        scrmask(x, x, 0, 0)
        czclear(dst, 0)
    scrmask(0, len(PAIRS) - 1, 0, 0)
    blendfunction(globals()[sname], globals()[dname])
    for x, (src, _) in enumerate(PAIRS):
        cpack(src)
        box(x, 0, x, 0)
    got = colour()[0]
    for x, (src, dst) in enumerate(PAIRS):
        want = blend_model(sname, dname, src, dst)
        g = comps(int(got[x]))
        for k in range(4):
            assert abs(g[k] - want[k]) <= 1.0, (x, k, g, want)


def test_blend_default_is_replace():
    open_win(1, 1)
    czclear(0x80808080, 0)
    cpack(0x11223344)
    box(0, 0, 0, 0)
    assert colour()[0, 0] == 0x11223344


def test_heidmann_additive_blend_saturates():
    open_win(2, 1)
    czclear(0x00000000, 0)
    blendfunction(BF_ONE, BF_ONE)
    cpack(0x40302010)
    for _ in range(3):
        box(0, 0, 1, 0)
    assert (colour() == 0xC0906030).all()
    for _ in range(3):
        box(0, 0, 0, 0)
    assert colour()[0, 0] == pack([min(0x10 * 6, 255), min(0x20 * 6, 255),
                                   min(0x30 * 6, 255), 255])


def test_blendfunction_illegal_placements_raise_and_keep_state():
    open_win(1, 1)
    blendfunction(BF_ONE, BF_ONE)
    with pytest.raises(GLError):
        blendfunction(BF_ONE, BF_MIN_SA_MDA)        # source only
    for bad in (9, 13, 14, 99, -1):
        with pytest.raises(GLError):
            blendfunction(bad, BF_ZERO)
        with pytest.raises(GLError):
            blendfunction(BF_ONE, bad)
    # still additive after the failed calls
    czclear(0x01010101, 0)
    cpack(0x01010101)
    box(0, 0, 0, 0)
    assert colour()[0, 0] == 0x02020202


def test_bf_sc_as_source_is_the_same_token_as_bf_dc():
    """BF_SC and BF_DC share the value 2 (gl.h): as a source it can only mean
    BF_DC, so 'BF_SC as source' cannot be told apart and is accepted."""
    assert BF_SC == BF_DC and BF_MSC == BF_MDC
    open_win(1, 1)
    czclear(0xFF804020, 0)
    blendfunction(BF_SC, BF_ZERO)          # == (BF_DC, BF_ZERO): src * dst
    cpack(0xFF808080)
    box(0, 0, 0, 0)
    want = blend_model("BF_DC", "BF_ZERO", 0xFF808080, 0xFF804020)
    g = comps(int(colour()[0, 0]))
    assert all(abs(g[k] - want[k]) <= 1 for k in range(4))


def test_blendfunction_in_cmode_raises():
    open_win(1, 1, rgb=False)
    with pytest.raises(GLError):
        blendfunction(BF_SA, BF_MSA)


# -- afunction ---------------------------------------------------------------------
AFUNCS = {
    "AF_NEVER": lambda a, r: False, "AF_LESS": lambda a, r: a < r,
    "AF_EQUAL": lambda a, r: a == r, "AF_LEQUAL": lambda a, r: a <= r,
    "AF_GREATER": lambda a, r: a > r, "AF_NOTEQUAL": lambda a, r: a != r,
    "AF_GEQUAL": lambda a, r: a >= r, "AF_ALWAYS": lambda a, r: True,
}


@pytest.mark.parametrize("fname", list(AFUNCS))
def test_afunction_incoming_alpha_against_ref(fname):
    alphas = [0, 99, 100, 101, 255]
    ref = 100
    open_win(len(alphas), 1)
    czclear(0x00000000, 0)
    afunction(ref, globals()[fname])
    for x, a in enumerate(alphas):
        cpack((a << 24) | 0x0000FF)
        box(x, 0, x, 0)
    got = list(colour()[0])
    want = [((a << 24) | 0xFF) if AFUNCS[fname](a, ref) else 0 for a in alphas]
    assert got == want


def test_afunction_failing_pixel_changes_no_bank():
    open_win(2, 1, planes=8)
    zmax = getgdesc(GD_ZMAX)
    czclear(OLD, zmax)
    sclear(3)
    zbuffer(TRUE)
    stencil(TRUE, 9, SF_ALWAYS, 0xFF, ST_REPLACE, ST_REPLACE, ST_REPLACE)
    afunction(200, AF_GEQUAL)
    cpack(0x10FFFFFF)                 # alpha 16 fails
    box(0, 0, 1, 0)
    assert (colour() == OLD).all()
    assert (z_bank() == zmax).all()
    assert (stencil_bank() == 3).all()


def test_afunction_bad_token_raises():
    open_win(1, 1)
    with pytest.raises(GLError):
        afunction(0, 8)


# -- logicop ---------------------------------------------------------------------
LOGIC = {
    "LO_ZERO": lambda s, d: 0, "LO_AND": lambda s, d: s & d,
    "LO_ANDR": lambda s, d: s & ~d, "LO_SRC": lambda s, d: s,
    "LO_ANDI": lambda s, d: ~s & d, "LO_DST": lambda s, d: d,
    "LO_XOR": lambda s, d: s ^ d, "LO_OR": lambda s, d: s | d,
    "LO_NOR": lambda s, d: ~(s | d), "LO_XNOR": lambda s, d: ~(s ^ d),
    "LO_NDST": lambda s, d: ~d, "LO_ORR": lambda s, d: s | ~d,
    "LO_NSRC": lambda s, d: ~s, "LO_ORI": lambda s, d: ~s | d,
    "LO_NAND": lambda s, d: ~(s & d), "LO_ONE": lambda s, d: -1,
}


def test_logicop_values():
    for k, name in enumerate(LOGIC):
        assert globals()[name] == k, name


@pytest.mark.parametrize("name", list(LOGIC))
def test_logicop_rgb_packed_words(name):
    s, d = 0xC3A55A3C, 0x0FF0CC33
    open_win(1, 1)
    czclear(d, 0)
    logicop(globals()[name])
    cpack(s)
    box(0, 0, 0, 0)
    assert colour()[0, 0] == LOGIC[name](s, d) & 0xFFFFFFFF


@pytest.mark.parametrize("name", list(LOGIC))
def test_logicop_cmode_indices(name):
    s, d = 0xA5C, 0x3F0
    open_win(1, 1, rgb=False)
    czclear(d, 0)
    logicop(globals()[name])
    color(s)
    box(0, 0, 0, 0)
    assert indices()[0, 0] == LOGIC[name](s, d) & 0xFFF


def test_logicop_default_is_src_and_honours_writemask():
    open_win(1, 1)
    czclear(0xFFFFFFFF, 0)
    cpack(0x12345678)
    box(0, 0, 0, 0)
    assert colour()[0, 0] == 0x12345678
    logicop(LO_XOR)
    wmpack(0x0000FFFF)
    cpack(0xFFFFFFFF)
    box(0, 0, 0, 0)
    assert colour()[0, 0] == (0x12345678 & 0xFFFF0000) | ((0x12345678 ^ 0xFFFFFFFF) & 0xFFFF)


def test_logicop_bad_token_raises():
    open_win(1, 1)
    with pytest.raises(GLError):
        logicop(16)


# -- dither --------------------------------------------------------------------------
def test_dither_accepted_and_changes_nothing():
    open_win(4, 4)
    shademodel(GOURAUD)
    results = []
    for mode in (DT_ON, DT_OFF):
        dither(mode)
        czclear(0, 0)
        subpixel(TRUE)
        bgnpolygon()
        c3f((1, 0, 0)); v2f((-0.5, -0.5))
        c3f((0, 1, 0)); v2f((3.5, -0.5))
        c3f((0, 0, 1)); v2f((3.5, 3.5))
        c3f((1, 1, 1)); v2f((-0.5, 3.5))
        endpolygon()
        results.append(colour())
    assert (results[0] == results[1]).all()
    assert len(set(results[0].ravel().tolist())) > 4
