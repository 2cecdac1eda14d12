"""Shadow z-buffer helpers shared by the Williams, Hart and Bentley programs.

What a 1991 IRIS GL programmer would have written on the host side: read a
window's z-buffer back with ``readsource(SRC_ZBUFFER)`` + ``lrectread``,
turn window coordinates back into world points with the inverse of the
matrices used to draw, carry them into the light's window, and compare
depths.  The per-pixel work is numpy over whole images (the C of the day
looped; the arithmetic is the same).

Conventions: IRIS GL row vectors (``p' = p . M``); window z in the
lsetdepth range (default GD_ZMIN..GD_ZMAX, the signed 24-bit VGX range);
the viewport maps NDC to window pixels with pixel centres at integers.
"""
import numpy as np

from irisgl import (MPROJECTION, MVIEWING, SRC_AUTO, SRC_ZBUFFER, getgdesc, getmatrix,
                    GD_ZMAX, GD_ZMIN, lrectread, mmode, readsource)

ZMIN = getgdesc(GD_ZMIN)
ZMAX = getgdesc(GD_ZMAX)


def current_mvp():
    """ModelView . Projection of the current window (row vectors), read with
    getmatrix in MPROJECTION and MVIEWING; the window is left in MVIEWING."""
    mmode(MPROJECTION)
    p = getmatrix()
    mmode(MVIEWING)
    return np.asarray(getmatrix(), np.float64) @ np.asarray(p, np.float64)


def read_depth(width, height):
    """The window's z-buffer as int32 (row 0 at the bottom)."""
    readsource(SRC_ZBUFFER)
    z = lrectread(0, 0, width - 1, height - 1)
    readsource(SRC_AUTO)
    return z.astype(np.int64)


def read_colour(width, height):
    """The window's colour as (h, w, 3) floats 0..255 (row 0 at the bottom)."""
    c = lrectread(0, 0, width - 1, height - 1).astype(np.int64)
    return np.stack((c & 255, (c >> 8) & 255, (c >> 16) & 255), axis=-1).astype(np.float64)


def window_to_world(z, mvp, width, height, near=ZMIN, far=ZMAX):
    """World points (h, w, 3) of every pixel of a depth image drawn with the
    row-vector matrix ``mvp`` (ModelView . Projection) and a full-window
    viewport."""
    h, w = z.shape
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float64)
    xn = (xs + 0.5) / width * 2.0 - 1.0
    yn = (ys + 0.5) / height * 2.0 - 1.0
    zn = (z - (far + near) / 2.0) / ((far - near) / 2.0)
    ndc = np.stack((xn, yn, zn, np.ones_like(xn)), axis=-1)
    p = ndc @ np.linalg.inv(np.asarray(mvp, np.float64))
    return p[..., :3] / p[..., 3:4]


def world_to_window(p, mvp, width, height, near=ZMIN, far=ZMAX):
    """Window x, y (pixel centres at integers) and window z of world points."""
    ph = np.concatenate((p, np.ones(p.shape[:-1] + (1,))), axis=-1) @ np.asarray(mvp, np.float64)
    n = ph[..., :3] / ph[..., 3:4]
    x = (n[..., 0] + 1.0) * 0.5 * width - 0.5
    y = (n[..., 1] + 1.0) * 0.5 * height - 0.5
    zw = (far + near) / 2.0 + n[..., 2] * (far - near) / 2.0
    return x, y, zw


def quantize(z, bits):
    """Depth reduced to ``bits`` (16 for Williams' pictures, 24 = the VGX)."""
    shift = 24 - bits
    return (np.asarray(z, np.int64) >> shift) << shift


def light_depth_at(zl, x, y, bilinear=False):
    """Light depth image sampled at window (x, y): nearest pixel, or bilinear
    interpolation of the four around (Williams fig. 4).  Outside the light's
    view: +inf (lit: Williams' rule, "points outside the viewing volume of the
    light source are illuminated")."""
    h, w = zl.shape
    if not bilinear:
        xi = np.floor(x + 0.5).astype(np.int64)
        yi = np.floor(y + 0.5).astype(np.int64)
        inside = (xi >= 0) & (xi < w) & (yi >= 0) & (yi < h)
        out = np.full(x.shape, np.inf)
        out[inside] = zl[yi[inside], xi[inside]]
        return out
    x0 = np.floor(x).astype(np.int64)
    y0 = np.floor(y).astype(np.int64)
    fx, fy = x - x0, y - y0
    inside = (x0 >= 0) & (x0 + 1 < w) & (y0 >= 0) & (y0 + 1 < h)
    out = np.full(x.shape, np.inf)
    a, b, c, d = (zl[y0[inside] + j, x0[inside] + i].astype(np.float64)
                  for j, i in ((0, 0), (0, 1), (1, 0), (1, 1)))
    fxi, fyi = fx[inside], fy[inside]
    out[inside] = (a * (1 - fxi) + b * fxi) * (1 - fyi) + (c * (1 - fxi) + d * fxi) * fyi
    return out


def pcf(zl, x, y, zp, bias, size=3):
    """Percentage-closer filtering: the fraction of the size x size light
    depth samples around (x, y) that the point at light depth ``zp`` lies
    behind (Reeves et al.; Bentley; Hart's 3x3)."""
    h, w = zl.shape
    xi = np.floor(x + 0.5).astype(np.int64)
    yi = np.floor(y + 0.5).astype(np.int64)
    r = size // 2
    shadowed = np.zeros(x.shape)
    for dj in range(-r, r + 1):
        for di in range(-r, r + 1):
            xs, ys = xi + di, yi + dj
            inside = (xs >= 0) & (xs < w) & (ys >= 0) & (ys < h)
            d = np.full(x.shape, np.inf)
            d[inside] = zl[ys[inside], xs[inside]]
            shadowed += (zp - bias > d)
    return shadowed / (size * size)


def box_blur(mask, radius):
    """Low-pass filter of a shadow mask (Williams fig. 5)."""
    if radius <= 0:
        return mask
    k = 2 * radius + 1
    p = np.pad(mask, radius, mode="edge")
    c = np.cumsum(np.cumsum(p, axis=0), axis=1)
    c = np.pad(c, ((1, 0), (1, 0)))
    s = c[k:, k:] - c[:-k, k:] - c[k:, :-k] + c[:-k, :-k]
    return s / (k * k)


def write_image(rgb, width, height):
    """Put an (h, w, 3) 0..255 image (row 0 at the bottom) into the window."""
    from irisgl import lrectwrite
    img = np.clip(np.floor(rgb + 0.5), 0, 255).astype(np.uint32)
    words = 0xFF000000 | (img[..., 2] << 16) | (img[..., 1] << 8) | img[..., 0]
    lrectwrite(0, 0, width - 1, height - 1, words.astype(np.uint32))
