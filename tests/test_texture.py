"""Texture mapping (docs/semantics.md §16, docs/decisions.md "texture ..." rows).

Every expected value is computed here from the rules of docs/semantics.md §16, never read
back from the emulator's tables:

* texel (i, j) covers s in [i/W, (i+1)/W), t in [j/H, (j+1)/H); image row 0 is
  the bottom row, (0, 0) maps to texture (0, 0) (docs/semantics.md §16);
* a window of w x h pixels keeps winopen's ``ortho2(-0.5, w-0.5, -0.5, h-0.5)``,
  so pixel (i, j) has its centre at object (i, j); quads run from -0.5 to w-0.5
  with ``subpixel(TRUE)``, so no pixel centre lies on an edge and pixel i sees
  s = s0 + (i + 0.5) / w * (s1 - s0);
* words read back are 0xAABBGGRR (docs/porting.md §3).

The incoming colour is white (alpha 255) unless a test says otherwise, so with
TV_MODULATE the pixel equals the texel.
"""
import math

import numpy as np
import pytest

from irisgl import *  # noqa: F401,F403  (the C names, docs/porting.md §1)
from irisgl import GLError


# -- helpers -----------------------------------------------------------------------
def rgba(img):
    """(h, w) 0xAABBGGRR words -> (h, w, 4) int R, G, B, A."""
    img = np.asarray(img, np.uint32).astype(np.int64)
    return np.stack([(img >> s) & 0xFF for s in (0, 8, 16, 24)], axis=-1)


def read(w, h):
    return rgba(lrectread(0, 0, w - 1, h - 1))


def words_from_rows(rows):
    """Rows of bytes (bottom row first), each padded to a 32-bit word, as the
    big-endian uint32 words of texdef(3G)."""
    out = []
    for r in rows:
        r = list(r) + [0] * (-len(r) % 4)
        for k in range(0, len(r), 4):
            out.append((r[k] << 24) | (r[k + 1] << 16) | (r[k + 2] << 8) | r[k + 3])
    return np.array(out, np.uint32)


def bytes_from_rows(rows):
    b = bytearray()
    for r in rows:
        b += bytes(r) + bytes(-len(r) % 4)
    return bytes(b)


def rgba_words(tex):
    """(h, w, 4) R G B A -> 4-component texdef words 0xAABBGGRR (row padding is
    never needed for 4 components)."""
    t = np.asarray(tex, np.uint64)
    return (t[..., 0] | (t[..., 1] << 8) | (t[..., 2] << 16) | (t[..., 3] << 24)) \
        .astype(np.uint32).reshape(-1)


def unique_texture(w, h):
    """A 4-component texture whose texel (i, j) has R = i*step+off, G = j*step+off,
    B = 77, A = 255: every texel can be identified from a pixel."""
    sx, sy = 256 // w, 256 // h
    tex = np.zeros((h, w, 4), np.int64)
    for j in range(h):
        for i in range(w):
            tex[j, i] = (i * sx + sx // 2, j * sy + sy // 2, 77, 255)
    return tex


def define(index, tex, props=(), nc=4):
    """texdef2d from an (h, w, 4) RGBA array (4 components, word layout)."""
    tex = np.asarray(tex)
    h, w = tex.shape[:2]
    texdef2d(index, nc, w, h, rgba_words(tex), 0, list(props) + [TX_NULL])


def bind(tex_index=1, env_index=1, env_props=(TV_MODULATE,)):
    tevdef(env_index, 0, list(env_props) + [TV_NULL])
    tevbind(TV_ENV0, env_index)
    texbind(TX_TEXTURE_0, tex_index)


POINT = [TX_MINFILTER, TX_POINT, TX_MAGFILTER, TX_POINT]
BILIN = [TX_MINFILTER, TX_BILINEAR, TX_MAGFILTER, TX_BILINEAR]


def quad(w, h, s0=0.0, t0=0.0, s1=1.0, t1=1.0, texcoords=True):
    """A quad covering the whole w x h window, texture (s0, t0)..(s1, t1)."""
    subpixel(TRUE)
    bgnpolygon()
    for x, y, s, t in ((-0.5, -0.5, s0, t0), (w - 0.5, -0.5, s1, t0),
                       (w - 0.5, h - 0.5, s1, t1), (-0.5, h - 0.5, s0, t1)):
        if texcoords:
            t2f((s, t))
        v2f((x, y))
    endpolygon()


def white():
    cpack(0xFFFFFFFF)


def wrap_index(k, n, repeat):
    return k % n if repeat else min(max(k, 0), n - 1)


def point_texel(s, t, w, h, rs=True, rt=True):
    """docs/semantics.md §16: POINT = the texel under (s, t); CLAMP clamps to the edges."""
    if not rs:
        s = min(max(s, 0.0), 1.0)
    if not rt:
        t = min(max(t, 0.0), 1.0)
    return wrap_index(math.floor(s * w), w, rs), wrap_index(math.floor(t * h), h, rt)


def bilinear(tex, s, t, rs=True, rt=True):
    """docs/semantics.md §16 (OpenGL LINEAR): weights of the four nearest texel centres."""
    h, w = tex.shape[:2]
    if not rs:
        s = min(max(s, 0.0), 1.0)
    if not rt:
        t = min(max(t, 0.0), 1.0)
    u, v = s * w - 0.5, t * h - 0.5
    i0, j0 = math.floor(u), math.floor(v)
    fu, fv = u - i0, v - j0
    out = np.zeros(4)
    for di, wu in ((0, 1 - fu), (1, fu)):
        for dj, wv in ((0, 1 - fv), (1, fv)):
            i = wrap_index(i0 + di, w, rs)
            j = wrap_index(j0 + dj, h, rt)
            out += wu * wv * tex[j, i]
    return out


def centre_s(i, n, s0=0.0, s1=1.0):
    return s0 + (i + 0.5) / n * (s1 - s0)


# -- point and bilinear sampling on a pixel-exact window -----------------------------
def test_point_sampling_each_pixel_is_its_texel(open_window):
    open_window(8, 4)
    tex = unique_texture(8, 4)
    define(1, tex, POINT)
    bind()
    white()
    quad(8, 4)
    np.testing.assert_array_equal(read(8, 4), tex)


def test_bilinear_at_texel_centres_is_exact(open_window):
    open_window(8, 4)
    tex = unique_texture(8, 4)
    define(1, tex, BILIN)
    bind()
    white()
    quad(8, 4)
    np.testing.assert_array_equal(read(8, 4), tex)


def test_bilinear_between_texel_centres(open_window):
    """8x8 pixels over a 4x4 texture: each pixel centre lies a quarter texel from
    the nearest texel centres (weights 1/4 and 3/4 each way; REPEAT wraps the
    outer pixels onto the opposite edge)."""
    open_window(8, 8)
    rng = np.random.default_rng(5)
    tex = rng.integers(0, 256, (4, 4, 4))
    tex[..., 3] = 255
    define(1, tex, BILIN)
    bind()
    white()
    quad(8, 8)
    got = read(8, 8)
    exp = np.array([[bilinear(tex, centre_s(i, 8), centre_s(j, 8)) for i in range(8)]
                    for j in range(8)])
    assert np.abs(got - exp).max() <= 1.0
    # the values really are mixtures: not equal to the point-sampled texels
    pts = np.array([[tex[point_texel(centre_s(i, 8), centre_s(j, 8), 4, 4)[::-1]]
                     for i in range(8)] for j in range(8)])
    assert np.abs(got - pts).max() > 10


def test_bilinear_half_way_between_two_texels(open_window):
    """A 2x1 black/white texture seen through 4 pixels at s in [0.25, 0.75]:
    pixel centres at s = 5/16, 7/16, 9/16, 11/16 -> u = s*2 - 0.5 =
    0.125, 0.375, 0.625, 0.875 between texel 0 (black) and 1 (white)."""
    open_window(4, 1)
    tex = np.array([[[0, 0, 0, 255], [255, 255, 255, 255]]])
    define(1, tex, BILIN)
    bind()
    white()
    quad(4, 1, 0.25, 0.5, 0.75, 0.5)
    got = read(4, 1)[0, :, 0]
    exp = np.array([0.125, 0.375, 0.625, 0.875]) * 255
    assert np.abs(got - exp).max() <= 1.0


# -- image layouts -------------------------------------------------------------------
def layout_case(nc, w, h, seed):
    """(memory rows bottom first, expected RGBA (h, w, 4)) for nc components."""
    rng = np.random.default_rng(seed)
    comps = rng.integers(0, 256, (h, w, nc))   # in memory order per texel
    rows = [list(comps[j].reshape(-1)) for j in range(h)]
    exp = np.zeros((h, w, 4), np.int64)
    if nc == 1:                         # I
        exp[..., 0] = exp[..., 1] = exp[..., 2] = comps[..., 0]
        exp[..., 3] = 255
    elif nc == 2:                       # A I
        exp[..., 0] = exp[..., 1] = exp[..., 2] = comps[..., 1]
        exp[..., 3] = comps[..., 0]
    elif nc == 3:                       # B G R
        exp[..., 0], exp[..., 1], exp[..., 2] = comps[..., 2], comps[..., 1], comps[..., 0]
        exp[..., 3] = 255
    else:                               # A B G R
        exp[..., 0], exp[..., 1], exp[..., 2], exp[..., 3] = (
            comps[..., 3], comps[..., 2], comps[..., 1], comps[..., 0])
    return rows, exp, comps


def array_form(comps, nc):
    """The (h, w, nc) array form: components in the texel's logical order
    (I / I A / R G B / R G B A), i.e. the memory order reversed per texel for
    2..4 components."""
    return np.ascontiguousarray(comps[..., ::-1]).astype(np.uint8)


# power-of-two sizes (no resampling) whose rows need padding where possible
LAYOUTS = [(1, 2, 4), (1, 1, 2), (2, 1, 4), (3, 2, 2), (3, 1, 2), (4, 2, 2)]


@pytest.mark.parametrize("nc,w,h", LAYOUTS)
@pytest.mark.parametrize("form", ["words", "bytes"])
def test_image_layout_packed(open_window, nc, w, h, form):
    rows, exp, comps = layout_case(nc, w, h, seed=nc * 100 + w * 10 + h)
    if nc < 4:                          # the case really exercises row padding
        assert all(len(r) % 4 for r in rows)
    image = words_from_rows(rows) if form == "words" else bytes_from_rows(rows)
    open_window(w, h)
    texdef2d(1, nc, w, h, image, 0, POINT + [TX_NULL])
    bind()
    white()
    quad(w, h)
    np.testing.assert_array_equal(read(w, h), exp)


def test_image_layout_one_component_brick_sample(open_window):
    """PG brick sample: a 1-component row of 8 texels is two words, texel 0 in
    bits 31-24; 0x00ffffff = texel 0 black, texels 1-3 white."""
    open_window(8, 1)
    texdef2d(1, 1, 8, 1, [0x00FFFFFF, 0xFF00FF00], 0, POINT + [TX_NULL])
    bind()
    white()
    quad(8, 1)
    np.testing.assert_array_equal(read(8, 1)[0, :, 0], [0, 255, 255, 255, 255, 0, 255, 0])


def test_image_layout_four_components_is_cpack_format(open_window):
    open_window(2, 1)
    texdef2d(1, 4, 2, 1, [0x40302010, 0x80706050], 0, POINT + [TX_NULL])
    bind()
    white()
    quad(2, 1)
    assert list(lrectread(0, 0, 1, 0)[0]) == [0x40302010, 0x80706050]


@pytest.mark.parametrize("nc", [1, 2, 3, 4])
def test_image_layout_array_form(open_window, nc):
    w, h = 2, 2
    rows, exp, comps = layout_case(nc, w, h, seed=7 + nc)
    open_window(w, h)
    texdef2d(1, nc, w, h, array_form(comps, nc), 0, POINT + [TX_NULL])
    bind()
    white()
    quad(w, h)
    np.testing.assert_array_equal(read(w, h), exp)


@pytest.mark.parametrize("nc", [1, 2, 3, 4])
def test_image_layout_width_three_padded_rows(open_window, nc):
    """3 texels wide (padded rows for nc 1..3), resampled to 4 wide: the corner
    texels of each row survive unchanged, so a row-padding error shows in the
    top row.  All three forms give the same picture."""
    w, h = 3, 2
    rows, exp, comps = layout_case(nc, w, h, seed=30 + nc)
    open_window(4, 2)
    pics = []
    for form in (words_from_rows(rows), bytes_from_rows(rows), array_form(comps, nc)):
        texdef2d(1, nc, w, h, form, 0, POINT + [TX_NULL])
        bind()
        white()
        quad(4, 2)
        pics.append(read(4, 2))
    for p in pics:
        np.testing.assert_array_equal(p[:, 0], exp[:, 0])
        np.testing.assert_array_equal(p[:, 3], exp[:, 2])
    np.testing.assert_array_equal(pics[0], pics[1])
    np.testing.assert_array_equal(pics[0], pics[2])


# -- wrap ----------------------------------------------------------------------------
def test_repeat_coordinates_0_to_2_show_the_image_twice(open_window):
    open_window(8, 8)
    tex = unique_texture(4, 4)
    define(1, tex, POINT + [TX_WRAP, TX_REPEAT])
    bind()
    white()
    quad(8, 8, 0, 0, 2, 2)
    got = read(8, 8)
    exp = np.array([[tex[j % 4, i % 4] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(got, exp)


def test_repeat_is_the_default_wrap(open_window):
    open_window(8, 4)
    tex = unique_texture(4, 4)
    define(1, tex, POINT)
    bind()
    white()
    quad(8, 4, 0, 0, 2, 1)
    exp = np.array([[tex[j, i % 4] for i in range(8)] for j in range(4)])
    np.testing.assert_array_equal(read(8, 4), exp)


def test_clamp_smears_edge_texels(open_window):
    """Coordinates -0.5..1.5 over 8 pixels on a 4x4 texture: s = (i+0.5)/4 - 0.5;
    outside 0..1 the edge texels repeat."""
    open_window(8, 8)
    tex = unique_texture(4, 4)
    define(1, tex, POINT + [TX_WRAP, TX_CLAMP])
    bind()
    white()
    quad(8, 8, -0.5, -0.5, 1.5, 1.5)
    got = read(8, 8)
    exp = np.empty_like(got)
    for j in range(8):
        for i in range(8):
            ti, tj = point_texel(centre_s(i, 8, -0.5, 1.5), centre_s(j, 8, -0.5, 1.5),
                                 4, 4, False, False)
            exp[j, i] = tex[tj, ti]
    np.testing.assert_array_equal(got, exp)
    # columns 0-1 and 6-7 are the smeared edges
    assert (got[:, 0] == got[:, 1]).all() and (got[:, 6] == got[:, 7]).all()
    assert (got[:, 0, 0] == tex[0, 0, 0]).all() and (got[:, 7, 0] == tex[0, 3, 0]).all()


def test_clamp_with_bilinear_far_outside_is_the_edge_texel(open_window):
    open_window(4, 1)
    tex = np.array([[[10, 20, 30, 255], [200, 100, 50, 255]]])
    define(1, tex, BILIN + [TX_WRAP, TX_CLAMP])
    bind()
    white()
    quad(4, 1, -3, 0.5, -2, 0.5)
    assert (read(4, 1)[0] == tex[0, 0]).all()
    quad(4, 1, 2, 0.5, 3, 0.5)
    assert (read(4, 1)[0] == tex[0, 1]).all()


@pytest.mark.parametrize("ws,wt", [(TX_REPEAT, TX_CLAMP), (TX_CLAMP, TX_REPEAT)])
def test_wrap_s_and_wrap_t_separately(open_window, ws, wt):
    open_window(8, 8)
    tex = unique_texture(4, 4)
    define(1, tex, POINT + [TX_WRAP_S, ws, TX_WRAP_T, wt])
    bind()
    white()
    quad(8, 8, -0.5, -0.5, 1.5, 1.5)
    got = read(8, 8)
    rs, rt = ws == TX_REPEAT, wt == TX_REPEAT
    exp = np.empty_like(got)
    for j in range(8):
        for i in range(8):
            ti, tj = point_texel(centre_s(i, 8, -0.5, 1.5), centre_s(j, 8, -0.5, 1.5),
                                 4, 4, rs, rt)
            exp[j, i] = tex[tj, ti]
    np.testing.assert_array_equal(got, exp)


def test_wrap_s_overrides_wrap(open_window):
    open_window(8, 1)
    tex = unique_texture(4, 1)
    define(1, tex, POINT + [TX_WRAP, TX_CLAMP, TX_WRAP_S, TX_REPEAT])
    bind()
    white()
    quad(8, 1, 0, 0.5, 2, 0.5)
    exp = np.array([tex[0, i % 4] for i in range(8)])
    np.testing.assert_array_equal(read(8, 1)[0], exp)


# -- environments --------------------------------------------------------------------
CIN = (200, 120, 40, 160)             # incoming colour R, G, B, A (0..255)


def env_texel(nc):
    """One texel per component count: (components in logical order, RGBA)."""
    return {1: ((180,), (180, 180, 180, 255)),
            2: ((180, 90), (180, 180, 180, 90)),
            3: ((30, 150, 240), (30, 150, 240, 255)),
            4: ((30, 150, 240, 64), (30, 150, 240, 64))}[nc]


def draw_env(open_window, nc, env_props):
    open_window(2, 2)
    comps, _ = env_texel(nc)
    image = np.array(comps, np.uint8).reshape(1, 1, nc).repeat(2, 0).repeat(2, 1)
    texdef2d(1, nc, 2, 2, image, 0, POINT + [TX_NULL])
    bind(env_props=env_props)
    r, g, b, a = CIN
    cpack((a << 24) | (b << 16) | (g << 8) | r)
    quad(2, 2)
    return read(2, 2).reshape(-1, 4)


def expected_env(env, nc, const=(1.0, 1.0, 1.0, 1.0)):
    """docs/semantics.md §16, the environment table (Cin, Ctex, Cconst in 0..1)."""
    comps, _ = env_texel(nc)
    cin = np.array(CIN) / 255.0
    c = [v / 255.0 for v in comps]
    rgb_in, a_in = cin[:3], cin[3]
    if env == "MODULATE":
        if nc == 1:
            out = list(rgb_in * c[0]) + [a_in]
        elif nc == 2:
            out = list(rgb_in * c[0]) + [a_in * c[1]]
        elif nc == 3:
            out = list(rgb_in * np.array(c)) + [a_in]
        else:
            out = list(rgb_in * np.array(c[:3])) + [a_in * c[3]]
    elif env == "DECAL":
        if nc == 3:
            out = c + [a_in]
        else:
            at = c[3]
            out = list(rgb_in * (1 - at) + np.array(c[:3]) * at) + [a_in]
    else:                                   # BLEND
        i = c[0]
        out = list(rgb_in * (1 - i) + np.array(const[:3]) * i)
        out += [a_in] if nc == 1 else [a_in * c[1]]
    return np.array(out) * 255.0


@pytest.mark.parametrize("nc", [1, 2, 3, 4])
def test_modulate(open_window, nc):
    got = draw_env(open_window, nc, (TV_MODULATE,))
    assert np.abs(got - expected_env("MODULATE", nc)).max() <= 1.0


def test_modulate_is_the_default_environment(open_window):
    got = draw_env(open_window, 4, ())
    assert np.abs(got - expected_env("MODULATE", 4)).max() <= 1.0


@pytest.mark.parametrize("nc", [3, 4])
def test_decal(open_window, nc):
    got = draw_env(open_window, nc, (TV_DECAL,))
    assert np.abs(got - expected_env("DECAL", nc)).max() <= 1.0


@pytest.mark.parametrize("nc", [1, 2])
def test_blend_with_tv_color(open_window, nc):
    const = (0.25, 0.5, 1.0, 1.0)
    got = draw_env(open_window, nc, (TV_BLEND, TV_COLOR) + const)
    assert np.abs(got - expected_env("BLEND", nc, const)).max() <= 1.0
    # the constant colour matters (not the default white)
    assert np.abs(got - expected_env("BLEND", nc)).max() > 10


@pytest.mark.parametrize("nc", [1, 2])
def test_blend_default_constant_is_white(open_window, nc):
    got = draw_env(open_window, nc, (TV_BLEND,))
    assert np.abs(got - expected_env("BLEND", nc)).max() <= 1.0


@pytest.mark.parametrize("nc", [1, 2])
def test_decal_with_one_or_two_components_falls_back_to_modulate(open_window, nc):
    got = draw_env(open_window, nc, (TV_DECAL,))
    assert np.abs(got - expected_env("MODULATE", nc)).max() <= 1.0


@pytest.mark.parametrize("nc", [3, 4])
def test_blend_with_three_or_four_components_falls_back_to_modulate(open_window, nc):
    got = draw_env(open_window, nc, (TV_BLEND, TV_COLOR, 0.25, 0.5, 1.0, 1.0))
    assert np.abs(got - expected_env("MODULATE", nc)).max() <= 1.0


# -- perspective correctness ----------------------------------------------------------
def rot_x(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return np.array([[1, 0, 0, 0], [0, c, s, 0], [0, -s, c, 0], [0, 0, 0, 1]], float)


def transl(x, y, z):
    m = np.eye(4)
    m[3, :3] = (x, y, z)
    return m


def perspective_matrix(fovy_tenths, aspect, near, far):
    f = 1.0 / math.tan(math.radians(fovy_tenths / 20.0))
    return np.array([[f / aspect, 0, 0, 0], [0, f, 0, 0],
                     [0, 0, -(far + near) / (far - near), -1],
                     [0, 0, -2 * far * near / (far - near), 0]], float)


PW, PH, PN = 32, 32, 8                 # window and texture size


def _tilted_plane_setup(open_window):
    """A 2x2 square in the object plane z = 0, (x, y) in [-1, 1]^2, texture
    s = (x+1)/2, t = (y+1)/2, rotated -60 degrees about x (its top recedes)
    and pushed to z = -3; perspective(600, 1, 1, 10).  Drawn as two
    triangles (-1,-1)(1,-1)(1,1) and (-1,-1)(1,1)(-1,1)."""
    open_window(PW, PH)
    mmode(MVIEWING)
    perspective(600, 1.0, 1.0, 10.0)
    translate(0.0, 0.0, -3.0)
    rotate(-600, 'x')
    # C <- T . C for each call: MV = Rx . T (rotate acts first on the vertex)
    mv = rot_x(-60.0) @ transl(0.0, 0.0, -3.0)
    proj = perspective_matrix(600, 1.0, 1.0, 10.0)
    tex = unique_texture(PN, PN)
    define(1, tex, POINT)
    bind()
    white()
    return tex, mv, proj, _draw_tilted()


def _draw_tilted():
    tris = [[(-1, -1), (1, -1), (1, 1)], [(-1, -1), (1, 1), (-1, 1)]]
    subpixel(TRUE)                      # vertices not snapped to pixel centres
    for tri in tris:
        bgnpolygon()
        for x, y in tri:
            t2f(((x + 1) / 2, (y + 1) / 2))
            v3f((x, y, 0.0))
        endpolygon()
    return tris


def _window_xy(p, mv, proj):
    c = np.array([p[0], p[1], 0.0, 1.0]) @ mv @ proj
    xn, yn = c[0] / c[3], c[1] / c[3]
    return -0.5 + (xn + 1) / 2 * PW, -0.5 + (yn + 1) / 2 * PH


def _ray_hit(i, j, mv, proj):
    """Object (x, y) where the eye ray through pixel centre (i, j) meets z = 0."""
    xn = 2 * (i + 0.5) / PW - 1
    yn = 2 * (j + 0.5) / PH - 1
    d_eye = np.array([xn / proj[0, 0], yn / proj[1, 1], -1.0, 0.0])
    inv = np.linalg.inv(mv)
    o = np.array([0.0, 0.0, 0.0, 1.0]) @ inv
    d = d_eye @ inv
    lam = -o[2] / d[2]
    p = o + lam * d
    return p[0], p[1]


def _affine_st(i, j, tri, mv, proj):
    """Screen-linear (s, t) inside triangle ``tri`` at pixel centre (i, j)."""
    pts = [_window_xy(p, mv, proj) for p in tri]
    (x0, y0), (x1, y1), (x2, y2) = pts
    den = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    b1 = ((i - x0) * (y2 - y0) - (x2 - x0) * (j - y0)) / den
    b2 = ((x1 - x0) * (j - y0) - (i - x0) * (y1 - y0)) / den
    b0 = 1 - b1 - b2
    st = [((x + 1) / 2, (y + 1) / 2) for x, y in tri]
    return (b0 * st[0][0] + b1 * st[1][0] + b2 * st[2][0],
            b0 * st[0][1] + b1 * st[1][1] + b2 * st[2][1])


def _in_tri(x, y, k, margin):
    if not (-1 + margin < x < 1 - margin and -1 + margin < y < 1 - margin):
        return False
    return (y < x - margin) if k == 0 else (y > x + margin)


def _safe(v, n=PN, eps=0.02):
    f = v * n
    return abs(f - round(f)) > eps


def test_perspective_correct_on_receding_plane(open_window):
    tex, mv, proj, tris = _tilted_plane_setup(open_window)
    got = read(PW, PH)
    checked = affine_wrong = 0
    for j in range(PH):
        for i in range(PW):
            x, y = _ray_hit(i, j, mv, proj)
            k = 0 if _in_tri(x, y, 0, 0.02) else 1 if _in_tri(x, y, 1, 0.02) else None
            if k is None:
                continue
            s, t = (x + 1) / 2, (y + 1) / 2
            if not (_safe(s) and _safe(t)):
                continue
            ti, tj = point_texel(s, t, PN, PN)
            assert tuple(got[j, i]) == tuple(tex[tj, ti]), (i, j, s, t)
            checked += 1
            sa, ta = _affine_st(i, j, tris[k], mv, proj)
            if point_texel(sa, ta, PN, PN) != (ti, tj):
                affine_wrong += 1
    # enough pixels were checked, and screen-linear interpolation would have
    # sampled a different texel at many of them
    assert checked > 150
    assert affine_wrong > 30


def test_perspective_texel_rows_are_compressed_with_distance(open_window):
    """Along the centre column the texture rows (t) take fewer pixels as the
    plane recedes: the first row (near) spans more pixels than the last (far),
    whereas affine interpolation gives them equal spans within a triangle."""
    tex, mv, proj, tris = _tilted_plane_setup(open_window)
    got = read(PW, PH)
    step = 256 // PN
    col = PW // 2
    rows = [(int(g) - step // 2) // step for g, a in zip(got[:, col, 1], got[:, col, 3]) if a]
    counts = {r: rows.count(r) for r in set(rows)}
    near, far = counts[min(counts)], counts[max(counts)]
    assert near >= 2 * far


def test_perspective_correct_after_near_plane_clipping(open_window):
    """A floor y = -1 from z = 2 (behind the eye) to z = -10, eye at the origin,
    perspective(600, 1, 1, 20): the near plane cuts the quad, and the texture
    coordinates at the new vertices must keep the mapping s = (x + 2)/4,
    t = (z + 10)/12 (REPEAT not involved: every visible point lies in 0..1)."""
    open_window(PW, PH)
    mmode(MVIEWING)
    perspective(600, 1.0, 1.0, 20.0)
    proj = perspective_matrix(600, 1.0, 1.0, 20.0)
    tex = unique_texture(PN, PN)
    define(1, tex, POINT)
    bind()
    white()
    subpixel(TRUE)
    bgnpolygon()
    for x, z in ((-2, 2), (2, 2), (2, -10), (-2, -10)):
        t2f(((x + 2) / 4, (z + 10) / 12))
        v3f((x, -1.0, z))
    endpolygon()
    got = read(PW, PH)
    checked = 0
    for j in range(PH):
        yn = 2 * (j + 0.5) / PH - 1
        dy = yn / proj[1, 1]
        if dy >= 0:
            continue
        for i in range(PW):
            dx = (2 * (i + 0.5) / PW - 1) / proj[0, 0]
            lam = -1.0 / dy                    # ray (dx, dy, -1) meets y = -1
            x, z = lam * dx, -lam
            if not (-1.97 < x < 1.97 and -9.9 < z < -1.05):
                continue
            s, t = (x + 2) / 4, (z + 10) / 12
            if not (_safe(s) and _safe(t)):
                continue
            ti, tj = point_texel(s, t, PN, PN)
            assert tuple(got[j, i]) == tuple(tex[tj, ti]), (i, j, s, t)
            checked += 1
    assert checked > 100


def test_scrsubdivide_is_accepted_and_changes_nothing(open_window):
    """docs/decisions.md: texture coordinates are already perspective-correct;
    scrsubdivide(SS_DEPTH, ...) is accepted as a no-op."""
    _tilted_plane_setup(open_window)
    before = read(PW, PH)
    scrsubdivide(SS_DEPTH, [0.0, 1.0, 4.0])
    cpack(0)
    clear()
    assert (read(PW, PH) == 0).all()
    white()
    _draw_tilted()
    np.testing.assert_array_equal(read(PW, PH), before)


# -- when texturing happens ----------------------------------------------------------
def _red_texture_setup(open_window):
    open_window(4, 4)
    tex = np.zeros((4, 4, 4), np.int64)
    tex[...] = (0, 0, 255, 255)
    tex[0, 0] = (255, 0, 0, 255)
    define(1, tex, POINT)
    tevdef(1, 0, [TV_MODULATE, TV_NULL])


GREEN = (0, 255, 0, 255)               # untextured incoming colour


def _green():
    cpack(0xFF00FF00)


def test_textured_when_both_bound(open_window):
    _red_texture_setup(open_window)
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    white()
    quad(4, 4)
    assert (read(4, 4)[1, 1] == (0, 0, 255, 255)).all()
    assert (read(4, 4)[0, 0] == (255, 0, 0, 255)).all()


def test_omitting_t_does_not_turn_texturing_off(open_window):
    """No t*() call: the current texture coordinate (0, 0) is used for every
    vertex, so every pixel gets texel (0, 0) (red), modulated by white."""
    _red_texture_setup(open_window)
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    white()
    quad(4, 4, texcoords=False)
    assert (read(4, 4) == (255, 0, 0, 255)).all()


def test_texbind_zero_turns_texturing_off(open_window):
    _red_texture_setup(open_window)
    tevbind(TV_ENV0, 1)
    texbind(TX_TEXTURE_0, 1)
    texbind(TX_TEXTURE_0, 0)
    _green()
    quad(4, 4)
    assert (read(4, 4) == GREEN).all()


def test_tevbind_zero_turns_texturing_off(open_window):
    _red_texture_setup(open_window)
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    tevbind(TV_ENV0, 0)
    _green()
    quad(4, 4)
    assert (read(4, 4) == GREEN).all()


def test_texture_without_environment_is_not_applied(open_window):
    _red_texture_setup(open_window)
    texbind(TX_TEXTURE_0, 1)
    _green()
    quad(4, 4)
    assert (read(4, 4) == GREEN).all()


def test_environment_without_texture_is_not_applied(open_window):
    _red_texture_setup(open_window)
    tevbind(TV_ENV0, 1)
    _green()
    quad(4, 4)
    assert (read(4, 4) == GREEN).all()


def test_rebinding_turns_texturing_back_on(open_window):
    _red_texture_setup(open_window)
    tevbind(TV_ENV0, 1)
    texbind(TX_TEXTURE_0, 0)
    texbind(TX_TEXTURE_0, 1)
    white()
    quad(4, 4, texcoords=False)
    assert (read(4, 4) == (255, 0, 0, 255)).all()


def test_colour_map_mode_is_not_textured(open_window):
    open_window(4, 4, rgb=False)
    tex = np.zeros((4, 4, 4), np.int64)
    define(1, tex, POINT)                  # black texture: would zero the colour
    tevdef(1, 0, [TV_MODULATE, TV_NULL])
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    color(5)
    quad(4, 4)
    assert (lrectread(0, 0, 3, 3) & 0xFFF == 5).all()


# -- texgen --------------------------------------------------------------------------
def test_texgen_linear_object_plane(open_window):
    """s = x/8 + 1/16, t = y/8 + 1/16 puts pixel (i, j) on texel (i, j)."""
    open_window(8, 8)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_LINEAR, [1 / 8, 0, 0, 1 / 16])
    texgen(TX_T, TG_LINEAR, [0, 1 / 8, 0, 1 / 16])
    texgen(TX_S, TG_ON, None)
    texgen(TX_T, TG_ON, None)
    white()
    quad(8, 8, 0.9, 0.9, 0.9, 0.9)        # t2f values are replaced
    np.testing.assert_array_equal(read(8, 8), tex)


def test_texgen_linear_is_in_object_coordinates(open_window):
    """translate(2, 0, 0) then a quad at object x -2.5..5.5: pixel i has object
    x = i - 2, so s = (i - 2)/8 + 1/16 -> texel (i - 2) mod 8 (REPEAT)."""
    open_window(8, 8)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_LINEAR, [1 / 8, 0, 0, 1 / 16])
    texgen(TX_S, TG_ON, None)
    white()
    translate(2.0, 0.0, 0.0)
    subpixel(TRUE)
    bgnpolygon()
    for x, y in ((-2.5, -0.5), (5.5, -0.5), (5.5, 7.5), (-2.5, 7.5)):
        t2f((0.0, 0.3))
        v2f((x, y))
    endpolygon()
    got = read(8, 8)
    exp = np.array([[tex[2, (i - 2) % 8] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(got, exp)


def test_texgen_off_restores_t_values_per_coordinate(open_window):
    open_window(8, 8)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_LINEAR, [1 / 8, 0, 0, 1 / 16])
    texgen(TX_T, TG_LINEAR, [0, 1 / 8, 0, 1 / 16])
    texgen(TX_S, TG_ON, None)
    texgen(TX_T, TG_ON, None)
    texgen(TX_T, TG_OFF, None)             # t from t2f again: 0.3 -> row 2
    white()
    quad(8, 8, 0.3, 0.3, 0.3, 0.3)
    exp = np.array([[tex[2, i] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(read(8, 8), exp)
    texgen(TX_S, TG_OFF, None)             # both from t2f: texel (2, 2)
    quad(8, 8, 0.3, 0.3, 0.3, 0.3)
    assert (read(8, 8) == tex[2, 2]).all()


def test_texgen_linear_defined_but_not_enabled_does_nothing(open_window):
    open_window(8, 8)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_LINEAR, [1 / 8, 0, 0, 1 / 16])
    white()
    quad(8, 8, 0.3, 0.3, 0.3, 0.3)
    assert (read(8, 8) == tex[2, 2]).all()


def _mviewing_window(open_window, w=8, h=8):
    open_window(w, h)
    mmode(MVIEWING)
    ortho2(-0.5, w - 0.5, -0.5, h - 0.5)


def test_texgen_contour_plane_taken_through_modelview_at_definition(open_window):
    """Plane (1/8, 0, 0, 1/16) given while ModelView = translate(-3, 0, 0): the
    eye-space plane is P . M^-1, so at drawing with ModelView = identity
    s = (x_eye + 3)/8 + 1/16 -> pixel i on texel (i + 3) mod 8."""
    _mviewing_window(open_window)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    pushmatrix()
    translate(-3.0, 0.0, 0.0)
    texgen(TX_S, TG_CONTOUR, [1 / 8, 0, 0, 1 / 16])
    popmatrix()
    texgen(TX_S, TG_ON, None)
    white()
    quad(8, 8, 0.0, 0.3, 0.0, 0.3)
    exp = np.array([[tex[2, (i + 3) % 8] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(read(8, 8), exp)


def test_texgen_contour_is_fixed_in_eye_space(open_window):
    """Defined with ModelView = identity, the contour plane stays in eye space:
    moving the object with translate(2, 0, 0) does not move the texture (unlike
    TG_LINEAR)."""
    _mviewing_window(open_window)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_CONTOUR, [1 / 8, 0, 0, 1 / 16])
    texgen(TX_S, TG_ON, None)
    white()
    translate(2.0, 0.0, 0.0)
    subpixel(TRUE)
    bgnpolygon()
    for x, y in ((-2.5, -0.5), (5.5, -0.5), (5.5, 7.5), (-2.5, 7.5)):
        t2f((0.0, 0.3))
        v2f((x, y))
    endpolygon()
    exp = np.array([[tex[2, i] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(read(8, 8), exp)


# -- the texture matrix --------------------------------------------------------------
def test_texture_matrix_translate(open_window):
    _mviewing_window(open_window)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    mmode(MTEXTURE)
    translate(0.25, 0.5, 0.0)               # (s, t) + (0.25, 0.5): +2, +4 texels
    mmode(MVIEWING)
    white()
    quad(8, 8)
    exp = np.array([[tex[(j + 4) % 8, (i + 2) % 8] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(read(8, 8), exp)


def test_texture_matrix_scale_then_translate_order(open_window):
    """scale(0.5) then translate(0.25): the matrix is T . S, so s' = (s + 0.25)/2
    (translate acts first).  Pixel i: s'*8 = (i + 0.5)/2 + 1."""
    _mviewing_window(open_window, 8, 1)
    tex = unique_texture(8, 1)
    define(1, tex, POINT)
    bind()
    mmode(MTEXTURE)
    scale(0.5, 1.0, 1.0)
    translate(0.25, 0.0, 0.0)
    mmode(MVIEWING)
    white()
    quad(8, 1, 0, 0.5, 1, 0.5)
    exp = [tex[0, math.floor((i + 0.5) / 2 + 1) % 8] for i in range(8)]
    np.testing.assert_array_equal(read(8, 1)[0], np.array(exp))


def test_texture_matrix_applies_to_texgen_values(open_window):
    _mviewing_window(open_window)
    tex = unique_texture(8, 8)
    define(1, tex, POINT)
    bind()
    texgen(TX_S, TG_LINEAR, [1 / 8, 0, 0, 1 / 16])
    texgen(TX_S, TG_ON, None)
    mmode(MTEXTURE)
    translate(0.375, 0.0, 0.0)              # +3 texels
    mmode(MVIEWING)
    white()
    quad(8, 8, 0.0, 0.3, 0.0, 0.3)
    exp = np.array([[tex[2, (i + 3) % 8] for i in range(8)] for j in range(8)])
    np.testing.assert_array_equal(read(8, 8), exp)


# -- minification and magnification ---------------------------------------------------
def checker(n):
    tex = np.zeros((n, n, 4), np.int64)
    ii, jj = np.meshgrid(np.arange(n), np.arange(n))
    v = np.where((ii + jj) % 2 == 0, 255, 0)
    tex[..., 0] = tex[..., 1] = tex[..., 2] = v
    tex[..., 3] = 255
    return tex


@pytest.mark.parametrize("size", [8, 16, 32])
def test_minification_mipmap_point_gives_box_filtered_grey(open_window, size):
    """A 64x64 one-texel checker on size x size pixels: a mipmapped filter uses
    a smaller level, every texel of which averages 2x2 black/white -> 127.5."""
    open_window(size, size)
    define(1, checker(64), [TX_MINFILTER, TX_MIPMAP_POINT, TX_MAGFILTER, TX_POINT])
    bind()
    white()
    quad(size, size)
    got = read(size, size)
    assert np.abs(got[..., :3] - 127.5).max() <= 1.5
    assert (got[..., 3] == 255).all()


def test_minification_with_point_filter_uses_the_full_image(open_window):
    """TX_POINT as min filter: no mipmap; 64 texels over 8 pixels, pixel i takes
    texel 8i + 4 in both directions -> (8i + 4 + 8j + 4) even -> all white."""
    open_window(8, 8)
    define(1, checker(64), [TX_MINFILTER, TX_POINT, TX_MAGFILTER, TX_POINT])
    bind()
    white()
    quad(8, 8)
    assert (read(8, 8)[..., :3] == 255).all()


def test_default_min_filter_is_mipmapped(open_window):
    """Only the mag filter given (TX_POINT): the default min filter still
    mipmaps (a non-mipmapped one would sample level 0 -> all white, as above)."""
    open_window(8, 8)
    define(1, checker(64), [TX_MAGFILTER, TX_POINT])
    bind()
    white()
    quad(8, 8)
    assert np.abs(read(8, 8)[..., :3] - 127.5).max() <= 1.5


@pytest.mark.parametrize("magf", [TX_POINT, TX_BILINEAR])
def test_magnification_uses_mag_filter(open_window, magf):
    """2x2 texture over 8x8 pixels (magnified) with a mipmapped min filter."""
    open_window(8, 8)
    tex = np.array([[[0, 0, 0, 255], [255, 0, 0, 255]],
                    [[0, 255, 0, 255], [0, 0, 255, 255]]])
    define(1, tex, [TX_MINFILTER, TX_MIPMAP_POINT, TX_MAGFILTER, magf])
    bind()
    white()
    quad(8, 8)
    got = read(8, 8)
    exp = np.zeros((8, 8, 4))
    for j in range(8):
        for i in range(8):
            s, t = centre_s(i, 8), centre_s(j, 8)
            if magf == TX_POINT:
                ti, tj = point_texel(s, t, 2, 2)
                exp[j, i] = tex[tj, ti]
            else:
                exp[j, i] = bilinear(tex, s, t)
    assert np.abs(got - exp).max() <= 1.0


def test_default_mag_filter_is_bilinear(open_window):
    open_window(8, 1)
    tex = np.array([[[0, 0, 0, 255], [255, 255, 255, 255]]])
    define(1, tex, [TX_MINFILTER, TX_POINT])
    bind()
    white()
    quad(8, 1, 0, 0.5, 1, 0.5)
    exp = [bilinear(tex, centre_s(i, 8), 0.5)[0] for i in range(8)]
    assert np.abs(read(8, 1)[0, :, 0] - np.array(exp)).max() <= 1.0


# -- non-power-of-two sizes ----------------------------------------------------------
def test_non_power_of_two_is_resampled_3x3_to_4x4(open_window):
    open_window(4, 4)
    rng = np.random.default_rng(11)
    tex = rng.integers(0, 256, (3, 3, 4))
    tex[..., 3] = 255
    tex[0, 0, :3] = (0, 0, 0)
    tex[0, 1, :3] = (255, 255, 255)
    define(1, tex, POINT)
    bind()
    white()
    quad(4, 4)
    got = read(4, 4)
    # each pixel is one texel of a 4x4 image whose corners are the 3x3 corners
    for (pj, pi), (tj, ti) in (((0, 0), (0, 0)), ((0, 3), (0, 2)),
                               ((3, 0), (2, 0)), ((3, 3), (2, 2))):
        np.testing.assert_array_equal(got[pj, pi], tex[tj, ti])
    # pixel (1, 0) lies between source texels 0 (black) and 1 (white): a
    # bilinear resampling gives a grey strictly between them
    assert 0 < got[0, 1, 0] < 255


# -- errors --------------------------------------------------------------------------
def _defined_red(vgx, open_window):
    open_window(2, 2)
    red = np.zeros((2, 2, 4), np.int64)
    red[...] = (255, 0, 0, 255)
    define(1, red, POINT)
    before = dict(vgx.textures)
    return before


def _still_red(vgx, before):
    assert vgx.textures == before
    assert vgx.textures[1] is before[1]
    bind()
    white()
    quad(2, 2)
    assert (read(2, 2) == (255, 0, 0, 255)).all()


def test_error_index_zero(vgx, open_window):
    before = _defined_red(vgx, open_window)
    with pytest.raises(GLError, match="^texdef2d"):
        texdef2d(0, 1, 2, 2, [0, 0], 0, [TX_NULL])
    assert 0 not in vgx.textures
    _still_red(vgx, before)


def test_error_five_components(vgx, open_window):
    before = _defined_red(vgx, open_window)
    with pytest.raises(GLError, match="^texdef2d"):
        texdef2d(1, 5, 2, 2, np.zeros((2, 2, 5), np.uint8), 0, [TX_NULL])
    _still_red(vgx, before)


@pytest.mark.parametrize("props", [[TX_MINFILTER, 0x999, TX_NULL],
                                   [TX_MAGFILTER, TX_MIPMAP_POINT, TX_NULL],
                                   [TX_WRAP, 0x999, TX_NULL]])
def test_error_bad_filter_or_wrap_token(vgx, open_window, props):
    before = _defined_red(vgx, open_window)
    with pytest.raises(GLError, match="^texdef2d"):
        texdef2d(1, 4, 2, 2, [0] * 4, 0, props)
    _still_red(vgx, before)


@pytest.mark.parametrize("nc,w,h,words", [(1, 3, 2, 1),       # needs 2 words (padded rows)
                                          (4, 2, 2, 3),
                                          (3, 2, 2, 3)])      # needs 2 words per row
def test_error_image_too_short(vgx, open_window, nc, w, h, words):
    before = _defined_red(vgx, open_window)
    with pytest.raises(GLError, match="^texdef2d"):
        texdef2d(1, nc, w, h, [0] * words, 0, [TX_NULL])
    _still_red(vgx, before)


def test_error_image_too_short_bytes(vgx, open_window):
    before = _defined_red(vgx, open_window)
    with pytest.raises(GLError, match="^texdef2d"):
        texdef2d(1, 1, 3, 2, bytes(7), 0, [TX_NULL])  # 2 rows of 4 bytes = 8 needed
    _still_red(vgx, before)


@pytest.mark.parametrize("bad", [float("nan"), float("inf")])
def test_non_finite_texture_coordinate_drops_the_primitive(open_window, bad):
    """Porting conventions 5 (non-finite input): the primitive is dropped with
    a warning naming the calls, and nothing is drawn."""
    import numpy as np
    from vgx_emulator import VGXWarning
    open_window(8, 8)
    texdef2d(1, 4, 1, 1, np.full((1, 1, 4), 255, np.uint8), 0, [0])
    tevdef(1, 0, [0])
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    cpack(0)
    clear()
    cpack(0xFFFFFFFF)
    with pytest.warns(VGXWarning, match="t\\*"):
        bgnpolygon()
        for x, y in ((-0.5, -0.5), (7.5, -0.5), (7.5, 7.5), (-0.5, 7.5)):
            t2f((bad, 0.5))
            v2f((x, y))
        endpolygon()
        img = lrectread(0, 0, 7, 7)
    assert (img == 0).all()


def test_texture_coordinates_in_an_object_compile_and_replay(open_window):
    """t2f inside makeobj is compiled with the geometry (no call-by-call
    replay) and draws what the immediate calls draw; after callobj the
    current texture coordinate is the object's last one (as after the
    calls)."""
    from vgx_emulator import objects as O
    open_window(8, 4)
    tex = unique_texture(8, 4)
    define(1, tex, POINT)
    bind()
    white()
    quad(8, 4, 0.0, 0.0, 1.0, 1.0)
    immediate = read(8, 4)
    makeobj(7)
    quad(8, 4, 0.0, 0.0, 1.0, 1.0)
    closeobj()
    ops = _machine_objects()[7].ops
    assert [op[0] for op in ops if op[0] == "run"] == ["run"]
    assert all(op[0] != "call" or op[1].__name__ not in O.TEXCOORD for op in ops)
    czclear(0, getgdesc(GD_ZMAX))
    callobj(7)
    np.testing.assert_array_equal(read(8, 4), immediate)
    np.testing.assert_array_equal(immediate, tex)
    # the state after callobj: the last t2f of the object, (0, 1)
    makeobj(8)
    subpixel(TRUE)
    bgnpolygon()
    for x, y in ((-0.5, -0.5), (7.5, -0.5), (7.5, 3.5), (-0.5, 3.5)):
        v2f((x, y))
    endpolygon()
    closeobj()
    callobj(8)
    expect = tex[point_texel(0.0, 1.0, 8, 4)[1], point_texel(0.0, 1.0, 8, 4)[0]]
    assert (read(8, 4) == expect).all()


def _machine_objects():
    import vgx_emulator
    return vgx_emulator.machine().objects


def test_property_lists_are_read_to_their_null_whatever_np(open_window):
    """texdef(3G), tevdef(3G): np only speeds a network connection and is
    ignored when 0; the list is read up to TX_NULL / TV_NULL, so a program
    that passed np = 1 with a longer list (SGI's nurbtex) defines the
    same texture and environment as with np = 0."""
    from irisgl._current import machine
    open_window(4, 4, rgb=True)
    props = [TX_MINFILTER, TX_POINT, TX_MAGFILTER, TX_POINT, TX_NULL]
    texdef2d(1, 1, 2, 1, [0x00FF00FF], 1, props)
    texdef2d(2, 1, 2, 1, [0x00FF00FF], 0, props)
    a, b = machine.textures[1], machine.textures[2]
    assert (a.minfilter, a.magfilter) == (b.minfilter, b.magfilter) == (TX_POINT, TX_POINT)
    tevdef(1, 1, [TV_BLEND, TV_COLOR, 0.5, 0.25, 0.125, 1.0, TV_NULL])
    tevdef(2, 0, [TV_BLEND, TV_COLOR, 0.5, 0.25, 0.125, 1.0, TV_NULL])
    assert vars(machine.environments[1]) == vars(machine.environments[2])


def test_q_divides_per_pixel_so_projected_textures_land_where_projected(open_window):
    """t(3G)'s q (t4f, texgen TX_Q, the texture matrix): the coordinates
    are s/q, t/q at each pixel, interpolated as s, t, q over the polygon
    (a projected texture, RealityEngine-era projtex); dividing at the
    vertices bent it.  A 16-texel ramp (red = 16 * texel) across a quad
    whose q goes from 1 (left) to 2 (right) with s from 0 to 2."""
    import math
    open_window(160, 20)
    ramp = [0xFF000000 | (16 * i) for i in range(16)]
    texdef2d(1, 4, 16, 1, ramp, 0, [TX_MINFILTER, TX_POINT, TX_MAGFILTER, TX_POINT,
                                    TX_WRAP, TX_CLAMP, TX_NULL])
    tevdef(1, 0, [TV_DECAL, TV_NULL])
    texbind(TX_TEXTURE_0, 1)
    tevbind(TV_ENV0, 1)
    ortho2(0, 160, 0, 20)
    bgnpolygon()
    for tc, v in (((0, 0, 0, 1), (0, 0)), ((2, 0, 0, 2), (160, 0)),
                  ((2, 0, 0, 2), (160, 20)), ((0, 0, 0, 1), (0, 20))):
        t4f(tc)
        v2f(v)
    endpolygon()
    row = lrectread(0, 10, 159, 10)[0] & 0xFF
    checked = 0
    for x in range(160):
        f = x / 160                              # the snapped corners are at window 0 and 160
        u = 16 * (2 * f) / (1 + f)               # s/q in texels
        if abs(u - round(u)) < 0.05:
            continue                             # too near a texel edge to call
        assert row[x] == 16 * min(int(math.floor(u)), 15), x
        checked += 1
    assert checked > 100
    assert row[80] == 160                        # per vertex it read 128
