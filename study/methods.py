"""The shadow methods, each drawn through the emulator with IRIS GL calls.

Every method returns an ``Outcome``: the image the window shows at the end
(read back with lrectread) and, when ``want_mask`` is set, the method's own
decision of where the light reaches (1) or not (0), fractional for
filtered and accumulated methods.  How each decision is read:

* planar projection (Tessman 1989, Bentley 1995): the shadow polygons set
  the stencil to 1 on the ground (Bentley's stencil route: every shadowed
  ground pixel darkened once); a pixel is in shadow where the stencil is 1
  and the ground is what the pixel shows (its z is still GD_ZMAX: the
  ground is drawn without z-buffer, as Tessman says, the casters with it);
* shadow z-buffer (Williams 1978, Hart's slides): the decision is the
  host-side comparison itself, and the image is the lit and the
  ambient-only renders blended by it, written back with lrectwrite;
* shadow volumes (Heidmann 1991), and soft shadows accumulating N of them:
  the stencil after the volume pass, read as a flag colour (a white
  rectangle drawn where the stencil equals MYZERO).

The mask read-back is extra work done only when ``want_mask`` is set, so
the timed runs (``want_mask`` False) measure the image alone.
"""
from dataclasses import dataclass, field

import numpy as np

from irisgl import (AC_ACCUMULATE, AC_CLEAR_ACCUMULATE, AC_RETURN, BF_ONE, BF_ZERO, FALSE,
                    LIGHT0, SF_ALWAYS, SF_EQUAL, ST_DECR, ST_INCR, ST_KEEP, ST_REPLACE, TRUE,
                    ZF_LEQUAL, ZF_LESS, acbuf, blendfunction, callobj, lmbind, loadmatrix,
                    lookat, multmatrix, ortho, popmatrix, pushmatrix, sclear, stencil, translate,
                    wmpack, zbuffer, zclear, zfunction, zwritemask)
from programs import shadowbuf as sb
from programs.tessman_flat_shadows import infinite_shadow_matrix

from . import volumes
from .render import MYZERO, SUN, IDENTITY, draw_polygons, fb_bytes
from .scenes import area_light_directions, jittered_disc, vogel_disc

DITHER_SEED = 1978


@dataclass
class Outcome:
    image: np.ndarray                  # (h, w, 3) 0..255, rows bottom first
    lit: np.ndarray = None             # (h, w) 0..1: the method's decision
    fb_bytes: int = 0                  # framebuffer banks the method needs
    info: dict = field(default_factory=dict)


# ---------------------------------------------------------------------------
def planar(stage, want_mask=False):
    """Tessman's ground matrix for a light at infinity, through Bentley's
    stencil route: ground ambient, shadow polygons -> stencil 1, ground
    diffuse added where the stencil is 0, then the casters z-buffered."""
    sc = stage.scene
    L = sc.light_dir
    stage.eye_view(light=False)
    stage.clear()
    zbuffer(FALSE)                                    # "don't bother z-buffering ground"
    callobj(stage.obj("ground", "full"))              # ambient only: the light is unbound
    sclear(0)
    wmpack(0)
    stencil(TRUE, 1, SF_ALWAYS, 0xFF, ST_KEEP, ST_REPLACE, ST_REPLACE)
    pushmatrix()
    translate(0.0, sc.ground_y, 0.0)                  # the ground plane is y = ground_y
    multmatrix(infinite_shadow_matrix(*L))
    translate(0.0, -sc.ground_y, 0.0)
    callobj(stage.obj("casters", "plain"))
    popmatrix()
    wmpack(0xFFFFFFFF)
    stencil(TRUE, 0, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    blendfunction(BF_ONE, BF_ONE)
    lmbind(LIGHT0, SUN)
    callobj(stage.obj("ground", "diffuse"))
    blendfunction(BF_ONE, BF_ZERO)
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    zbuffer(TRUE)
    callobj(stage.obj("casters", "full"))
    out = Outcome(stage.read_colour(), fb_bytes=fb_bytes(stage.width, stage.height, True))
    if want_mask:
        ground = stage.read_depth() >= sb.ZMAX
        out.lit = (~(stage.stencil_mask(1) & ground)).astype(np.float64)
    return out


# ---------------------------------------------------------------------------
def tiles_of(res, max_tile, pad):
    """The light map's tiles as texel ranges (i0, j0, width, height): one
    tile when the map fits a window of ``max_tile``, else tiles of
    ``max_tile - 2 pad`` (the last of a row or column smaller), each drawn
    with ``pad`` texels of its neighbours around it."""
    if res <= max_tile:
        return [(0, 0, res, res)]
    step = max_tile - 2 * pad
    if step < 1:
        raise ValueError(f"light-map tiles of {max_tile} cannot hold a border of {pad} texels")
    edges = list(range(0, res, step))
    return [(i0, j0, min(step, res - i0), min(step, res - j0)) for j0 in edges for i0 in edges]


def _texel_edge(lo, hi, k, res):
    """Light-box coordinate of texel edge k of res (the box's own ends at 0
    and res)."""
    if k == 0:
        return lo
    if k == res:
        return hi
    return lo + k * ((hi - lo) / res)


def texel_ortho(box, res, x0, x1, y0, y1):
    """ortho() of the texels [x0, x1) x [y0, y1) of a res x res map of the
    light box (indices may run outside 0..res: a tile's border)."""
    l, r, b, t, n, f = box
    ortho(_texel_edge(l, r, x0, res), _texel_edge(l, r, x1, res), _texel_edge(b, t, y0, res),
          _texel_edge(b, t, y1, res), n, f)


def light_tile(stage, light, res, i0, j0, w, h, pad):
    """Williams' first pass for one tile: the light's z-buffer over the
    texels [i0 - pad, i0 + w + pad) x [j0 - pad, ...) in a square window
    (no colour: wmpack(0)), read with readsource(SRC_ZBUFFER) + lrectread.
    Returns (depth (h + 2 pad, w + 2 pad) int64, its origin texel (x, y),
    window size)."""
    eye, at, box = light
    size = max(w, h) + 2 * pad
    stage.light_window(size)
    wmpack(0)
    texel_ortho(box, res, i0 - pad, i0 - pad + size, j0 - pad, j0 - pad + size)
    loadmatrix(IDENTITY)
    lookat(*eye, *at, 0)
    zclear()
    callobj(stage.obj("all", "plain"))
    depth = sb.read_depth(size, size)[:h + 2 * pad, :w + 2 * pad]
    wmpack(0xFFFFFFFF)
    return depth, (i0 - pad, j0 - pad), size


def light_mvp(stage, light, res, size):
    """ModelView.Projection of the whole light map (row vectors)."""
    eye, at, box = light
    stage.light_window(size)
    texel_ortho(box, res, 0, res, 0, res)
    loadmatrix(IDENTITY)
    lookat(*eye, *at, 0)
    return sb.current_mvp()


def light_depth(stage, res, max_tile=None):
    """The whole res x res light depth (int64), assembled from its tiles
    (for tests and pictures: the shadow test itself never holds it)."""
    light = stage.light_box()
    depth = np.empty((res, res), np.int64)
    for i0, j0, w, h in tiles_of(res, max_tile or stage.max_tile, 0):
        d, _, _ = light_tile(stage, light, res, i0, j0, w, h, 0)
        depth[j0:j0 + h, i0:i0 + w] = d
    return depth


def bias_units(box, world):
    """A distance along the light in light-window z units (ortho: linear)."""
    return world / (box[5] - box[4]) * float(sb.ZMAX - sb.ZMIN)


def sample_nearest(zl, origin, res, x, y):
    """Light depth at window (x, y) of the res x res map, nearest texel,
    from a tile ``zl`` whose first texel is ``origin``; +inf outside the
    map (lit: Williams' rule).  As shadowbuf.light_depth_at on the whole map."""
    xi = np.floor(x + 0.5).astype(np.int64)
    yi = np.floor(y + 0.5).astype(np.int64)
    inside = (xi >= 0) & (xi < res) & (yi >= 0) & (yi < res)
    out = np.full(x.shape, np.inf)
    out[inside] = zl[yi[inside] - origin[1], xi[inside] - origin[0]]
    return out


def sample_bilinear(zl, origin, res, x, y):
    """Bilinear light depth of the four texels around (x, y) (Williams
    fig. 4); +inf where one of them is outside the map."""
    x0 = np.floor(x).astype(np.int64)
    y0 = np.floor(y).astype(np.int64)
    fx, fy = x - x0, y - y0
    inside = (x0 >= 0) & (x0 + 1 < res) & (y0 >= 0) & (y0 + 1 < res)
    out = np.full(x.shape, np.inf)
    xs, ys = x0[inside] - origin[0], y0[inside] - origin[1]
    a, b, c, d = (zl[ys + j, xs + i].astype(np.float64)
                  for j, i in ((0, 0), (0, 1), (1, 0), (1, 1)))
    fxi, fyi = fx[inside], fy[inside]
    out[inside] = (a * (1 - fxi) + b * fxi) * (1 - fyi) + (c * (1 - fxi) + d * fxi) * fyi
    return out


def sample_pcf(zl, origin, res, x, y, zp, bias, size):
    """Percentage-closer filtering over size x size texels around (x, y):
    the shadowed fraction (samples outside the map do not shadow).  As
    shadowbuf.pcf on the whole map."""
    xi = np.floor(x + 0.5).astype(np.int64)
    yi = np.floor(y + 0.5).astype(np.int64)
    r = size // 2
    shadowed = np.zeros(x.shape)
    for dj in range(-r, r + 1):
        for di in range(-r, r + 1):
            xs, ys = xi + di, yi + dj
            inside = (xs >= 0) & (xs < res) & (ys >= 0) & (ys < res)
            d = np.full(x.shape, np.inf)
            d[inside] = zl[ys[inside] - origin[1], xs[inside] - origin[0]]
            shadowed += (zp - bias > d)
    return shadowed / (size * size)


def shadow_test(stage, ze, mvp_e, res, bias, bilinear, dither, pcf, bits, seed=None):
    """Williams' second pass on the host, tile by tile: each visible eye
    point carried into the light's window and compared with the depth of
    the tile its nearest texel lies in (drawn with a border wide enough for
    the bilinear and PCF neighbours; tiles no point falls in are not drawn),
    so memory is one tile whatever ``res``.  Returns (lit fraction per
    pixel, tiles drawn, tiles, light window size)."""
    light = stage.light_box()
    box = light[2]
    pad = max(1, pcf // 2)
    tiles = tiles_of(res, stage.max_tile, pad)
    first = max(tiles[0][2], tiles[0][3]) + (2 * pad if len(tiles) > 1 else 0)
    mvp_l = light_mvp(stage, light, res, first)
    h, w = ze.shape
    world = sb.window_to_world(ze, mvp_e, w, h)
    x, y, zp = sb.world_to_window(world, mvp_l, res, res)
    if bits < 24:
        zp = sb.quantize(np.floor(zp + 0.5), bits).astype(np.float64)
    if dither:
        quantum = float(1 << (24 - bits))
        rng = np.random.default_rng(DITHER_SEED if seed is None else seed)
        zp = zp + rng.uniform(-0.5, 0.5, zp.shape) * quantum
    bias = bias_units(box, bias)
    frac = np.ones(ze.shape)
    seen = ze < sb.ZMAX
    hx = np.clip(np.floor(x + 0.5), 0, res - 1)
    hy = np.clip(np.floor(y + 0.5), 0, res - 1)
    drawn, size = 0, first
    for i0, j0, tw, th in tiles:
        sel = seen & (hx >= i0) & (hx < i0 + tw) & (hy >= j0) & (hy < j0 + th)
        if not sel.any():
            continue
        zl, origin, size = light_tile(stage, light, res, i0, j0, tw, th,
                                      pad if len(tiles) > 1 else 0)
        drawn += 1
        if bits < 24:
            zl = sb.quantize(zl, bits)
        xs, ys, zs = x[sel], y[sel], zp[sel]
        if pcf > 1:
            frac[sel] = 1.0 - sample_pcf(zl, origin, res, xs, ys, zs, bias, pcf)
        elif bilinear:
            frac[sel] = (zs - bias <= sample_bilinear(zl, origin, res, xs, ys))
        else:
            frac[sel] = (zs - bias <= sample_nearest(zl, origin, res, xs, ys))
    return frac, drawn, len(tiles), size


def shadow_map(stage, want_mask=False, res=1024, bias=0.05, bilinear=False, dither=False,
               pcf=1, bits=24, seed=None):
    """Williams' shadow z-buffer, Hart's composite: light depth at res x res
    (in tiles, see shadow_test), the eye's lit and ambient-only renders and
    z-buffer, the comparison with ``bias`` (world units along the light),
    nearest or bilinear light depth, optional dither of one depth quantum
    (noise from ``seed``), pcf x pcf percentage-closer filtering, light
    depths quantized to ``bits``."""
    if res < 1 or pcf < 1 or not 1 <= bits <= 24:
        raise ValueError(f"shadow map: res {res}, pcf {pcf}, bits {bits} out of range")
    stage.eye_view(light=True)
    stage.clear()
    callobj(stage.obj("all", "full"))
    lit_img, ze = stage.read_colour(), stage.read_depth()
    mvp_e = sb.current_mvp()
    stage.eye_view(light=False)
    stage.clear()
    callobj(stage.obj("all", "full"))
    amb_img = stage.read_colour()
    size = (stage.width, stage.height)
    frac, drawn, tiles, win = shadow_test(stage, ze, mvp_e, res, bias, bilinear, dither, pcf,
                                          bits, seed)
    stage.eye_view(light=False)
    sb.write_image(amb_img + frac[..., None] * (lit_img - amb_img), *size)
    out = Outcome(stage.read_colour(), fb_bytes=fb_bytes(*size) + fb_bytes(win, win),
                  info={"light tiles drawn": drawn, "light tiles": tiles})
    out.lit = frac if want_mask else None
    return out


def composite(stage, lit):
    """The lit and ambient-only renders blended by a given decision (the
    shadow z-buffer's last step): with the reference's own decision this is
    the error floor of the rasterized image."""
    stage.eye_view(light=True)
    stage.clear()
    callobj(stage.obj("all", "full"))
    lit_img = stage.read_colour()
    stage.eye_view(light=False)
    stage.clear()
    callobj(stage.obj("all", "full"))
    amb_img = stage.read_colour()
    f = np.asarray(lit, np.float64)[..., None]
    sb.write_image(amb_img + f * (lit_img - amb_img), stage.width, stage.height)
    return Outcome(stage.read_colour(), lit=np.asarray(lit, np.float64),
                   fb_bytes=fb_bytes(stage.width, stage.height))


# ---------------------------------------------------------------------------
def draw_volumes(stage, edges, L, zfail):
    """Heidmann's volume pass for the light towards L (z and colour writes
    off): z-pass INCR on faces going in, DECR going out; z-fail (with the
    caps and ZF_LESS) DECR / INCR where the z test fails."""
    E = volumes.extrusion(stage.scene, L)
    polys = [volumes.side_faces(edges, L, E)]
    if zfail:
        polys.append(volumes.caps(edges, L, E))
        zfunction(ZF_LESS)
    eye = stage.scene.view.eye
    for group in polys:
        into = volumes.ingoing(group, eye)
        for going_in in (True, False):
            if zfail:
                stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_DECR if going_in else ST_INCR,
                        ST_KEEP)
            else:
                stencil(TRUE, 0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP,
                        ST_INCR if going_in else ST_DECR)
            draw_polygons(group[into == going_in])
    zfunction(ZF_LEQUAL)
    return sum(len(p) for p in polys)


def heidmann_frame(stage, edges, L, zfail):
    """One light's frame: ambient pass (sets z), sclear(MYZERO), the volume
    pass, the diffuse pass added where the stencil is still MYZERO."""
    stage.eye_view(light=False)
    zwritemask(0xFFFFFFFF)
    stage.clear()
    callobj(stage.obj("all", "full"))
    sclear(MYZERO)
    zwritemask(0)
    wmpack(0)
    faces = draw_volumes(stage, edges, L, zfail)
    zwritemask(0xFFFFFFFF)
    wmpack(0xFFFFFFFF)
    blendfunction(BF_ONE, BF_ONE)
    stencil(TRUE, MYZERO, SF_EQUAL, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)
    lmbind(LIGHT0, SUN)
    callobj(stage.obj("all", "diffuse"))
    stencil(FALSE, 0, 0, 0, 0, 0, 0)
    blendfunction(BF_ONE, BF_ZERO)
    return faces


def shadow_volumes(stage, want_mask=False, zfail=False):
    """Heidmann's stencil shadow volumes, depth-pass or depth-fail."""
    edges = volumes.adjacency(stage.scene)
    faces = heidmann_frame(stage, edges, stage.scene.light_dir, zfail)
    out = Outcome(stage.read_colour(), fb_bytes=fb_bytes(stage.width, stage.height, True),
                  info={"volume polygons": faces})
    if want_mask:
        out.lit = stage.stencil_mask(MYZERO).astype(np.float64)
    return out


def accumulation_weight(n):
    """The acbuf(AC_ACCUMULATE) value per image: 1, or less where n images
    of 255 would overflow the signed 16-bit accumulation buffer (each
    scaled component is rounded to nearest, so round(255 v) <= 32767 / n)."""
    return min(1.0, (32767.0 / n - 0.5) / 255.0)


def soft_shadows(stage, want_mask=False, n=32, zfail=False, seed=None):
    """Heidmann's fig. 6: n frames, each with the light at one of n
    directions spread over the area light's disc (golden-angle spiral, or
    with ``seed`` the spiral jittered: scenes.jittered_disc), accumulated
    with acbuf and returned with weight 1 / (n * value)."""
    sc = stage.scene
    edges = volumes.adjacency(sc)
    value = accumulation_weight(n)
    frac = np.zeros((stage.height, stage.width)) if want_mask else None
    disc = vogel_disc(n) if seed is None else jittered_disc(n, seed)
    for k, d in enumerate(area_light_directions(sc, disc)):
        stage.set_light(d)
        heidmann_frame(stage, edges, d, zfail)
        acbuf(AC_CLEAR_ACCUMULATE if k == 0 else AC_ACCUMULATE, value)
        if want_mask:
            frac += stage.stencil_mask(MYZERO)
    stage.set_light(sc.light_dir)
    acbuf(AC_RETURN, 1.0 / (n * value))
    out = Outcome(stage.read_colour(),
                  fb_bytes=fb_bytes(stage.width, stage.height, True, accum=True))
    if want_mask:
        out.lit = frac / n
    return out


METHODS = {"planar": planar, "shadow map": shadow_map, "volumes": shadow_volumes,
           "soft": soft_shadows}
