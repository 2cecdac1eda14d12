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
                    lookat, multmatrix, popmatrix, pushmatrix, sclear, stencil, translate,
                    wmpack, zbuffer, zclear, zfunction, zwritemask)
from programs import shadowbuf as sb
from programs.tessman_flat_shadows import infinite_shadow_matrix

from . import volumes
from .render import MAX_TILE, MYZERO, SUN, IDENTITY, draw_polygons, fb_bytes, light_ortho
from .scenes import area_light_directions, vogel_disc

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
def light_depth(stage, res):
    """Williams' first pass: the light's z-buffer at res x res (no colour:
    wmpack(0)), drawn in tiles of at most MAX_TILE pixels (each tile an
    ortho() sub-box of the light's box), read with readsource(SRC_ZBUFFER)
    and lrectread.  Returns (depth (res, res) int32, ModelView.Projection
    of the whole box)."""
    eye, at, box = stage.light_box()
    tile = min(res, MAX_TILE)
    tiles = res // tile
    stage.light_window(tile)
    wmpack(0)
    depth = np.empty((res, res), np.int32)
    for j in range(tiles):
        for i in range(tiles):
            light_ortho(box, i, j, tiles)
            loadmatrix(IDENTITY)
            lookat(*eye, *at, 0)
            zclear()
            callobj(stage.obj("all", "plain"))
            depth[j * tile:(j + 1) * tile, i * tile:(i + 1) * tile] = sb.read_depth(tile, tile)
    wmpack(0xFFFFFFFF)
    light_ortho(box, 0, 0, 1)
    loadmatrix(IDENTITY)
    lookat(*eye, *at, 0)
    return depth, sb.current_mvp(), box


def bias_units(box, world):
    """A distance along the light in light-window z units (ortho: linear)."""
    return world / (box[5] - box[4]) * float(sb.ZMAX - sb.ZMIN)


def shadow_test(ze, mvp_e, zl, mvp_l, size, res, bias, bilinear, dither, pcf, bits):
    """Williams' second pass on the host: each visible eye point carried
    into the light's window and compared with the light's depth.  Returns
    the lit fraction per pixel."""
    world = sb.window_to_world(ze, mvp_e, *size)
    x, y, zp = sb.world_to_window(world, mvp_l, res, res)
    if bits < 24:
        zl = sb.quantize(zl, bits)
        zp = sb.quantize(np.floor(zp + 0.5), bits).astype(np.float64)
    if dither:
        quantum = float(1 << (24 - bits))
        zp = zp + np.random.default_rng(DITHER_SEED).uniform(-0.5, 0.5, zp.shape) * quantum
    if pcf > 1:
        return 1.0 - sb.pcf(zl, x, y, zp, bias, pcf)
    return (zp - bias <= sb.light_depth_at(zl, x, y, bilinear)).astype(np.float64)


def shadow_map(stage, want_mask=False, res=1024, bias=0.05, bilinear=False, dither=False,
               pcf=1, bits=24):
    """Williams' shadow z-buffer, Hart's composite: light depth at res x res,
    the eye's lit and ambient-only renders and z-buffer, the comparison
    with ``bias`` (world units along the light), nearest or bilinear light
    depth, optional dither of one depth quantum, pcf x pcf percentage-closer
    filtering, light depths quantized to ``bits``."""
    zl, mvp_l, box = light_depth(stage, res)
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
    frac = shadow_test(ze, mvp_e, zl, mvp_l, size, res, bias_units(box, bias), bilinear,
                       dither, pcf, bits)
    frac[ze >= sb.ZMAX] = 1.0
    sb.write_image(amb_img + frac[..., None] * (lit_img - amb_img), *size)
    tile = min(res, MAX_TILE)
    out = Outcome(stage.read_colour(), fb_bytes=fb_bytes(*size) + fb_bytes(tile, tile))
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


def soft_shadows(stage, want_mask=False, n=32, zfail=False):
    """Heidmann's fig. 6: n frames, each with the light at one of n
    directions spread over the area light's disc (golden-angle spiral),
    accumulated with acbuf and returned with weight 1 / (n * value)."""
    sc = stage.scene
    edges = volumes.adjacency(sc)
    value = accumulation_weight(n)
    frac = np.zeros((stage.height, stage.width)) if want_mask else None
    for k, d in enumerate(area_light_directions(sc, vogel_disc(n))):
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
