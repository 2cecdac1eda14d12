"""Texture definitions (texdef2d, tevdef) and their packing for the kernels.

docs/semantics.md §16.  A texture is kept as RGBA uint8 levels (level 0 the
image, then each level halved by a 2x2 box filter down to 1x1), packed into
one flat (n, 4) array with a level table, so the raster kernels take plain
arrays.  Components are stored so that one formula serves every component
count: 1 (I) -> (I, I, I, 255); 2 (I, A) -> (I, I, I, A); 3 (RGB) -> (R, G, B,
255); 4 -> (R, G, B, A).

Image layout (texdef2d(3G)): texels left to right, rows bottom to top, 8-bit
components packed back to back, each row starting on a 32-bit word; in
``unsigned long`` words the first byte is the most significant, so byte order
per texel is I / A I / B G R / A B G R.  Sizes that are not powers of two are
resampled bilinearly to the next power of two ([S], docs/semantics.md §16).
"""
import math

import numpy as np

TX_MINFILTER, TX_MAGFILTER, TX_WRAP, TX_WRAP_S, TX_WRAP_T, TX_WRAP_R = (
    0x100, 0x200, 0x300, 0x310, 0x320, 0x330)
TX_POINT, TX_BILINEAR = 0x110, 0x220
TX_MIPMAP, TX_MIPMAP_POINT, TX_MIPMAP_LINEAR, TX_MIPMAP_BILINEAR, TX_MIPMAP_TRILINEAR = (
    0x120, 0x121, 0x122, 0x123, 0x124)
TX_REPEAT, TX_CLAMP, TX_SELECT = 0x301, 0x302, 0x303
TV_MODULATE, TV_BLEND, TV_DECAL, TV_ALPHA, TV_COLOR = 0x101, 0x102, 0x103, 0x105, 0x200

#: property tokens -> number of floats that follow (accepted ones)
TEX_PROPS = {TX_MINFILTER: 1, TX_MAGFILTER: 1, TX_WRAP: 1, TX_WRAP_S: 1, TX_WRAP_T: 1,
             TX_WRAP_R: 1, 0x400: 4, 0x500: 1, 0x600: 1, 0x700: 1, 0x900: 8, 0xa00: 1,
             0xb00: 1, 0xc00: 2, 0xd00: 2, 0xe00: 2, 0xf00: 1}
MIN_FILTERS = {TX_POINT, TX_BILINEAR, TX_MIPMAP, TX_MIPMAP_POINT, TX_MIPMAP_LINEAR,
               TX_MIPMAP_BILINEAR, TX_MIPMAP_TRILINEAR, 0x230, 0x240, 0x270, 0x280}
MAG_FILTERS = {TX_POINT, TX_BILINEAR, 0x230, 0x240, 0x250, 0x260}
WRAPS = {TX_REPEAT, TX_CLAMP, TX_SELECT}

# sampler modes handed to the kernel
POINT, BILINEAR = 0, 1


class Texture:
    """A defined texture: packed levels and its filter/wrap settings."""

    def __init__(self, nc, rgba, props):
        self.nc = nc
        self.minfilter = props.get(TX_MINFILTER, TX_MIPMAP_LINEAR)
        self.magfilter = props.get(TX_MAGFILTER, TX_BILINEAR)
        wrap = props.get(TX_WRAP, TX_REPEAT)
        self.wrap_s = props.get(TX_WRAP_S, wrap)
        self.wrap_t = props.get(TX_WRAP_T, wrap)
        levels = [rgba]
        while levels[-1].shape[0] > 1 or levels[-1].shape[1] > 1:
            levels.append(_halve(levels[-1]))
        self.levels = levels
        self.texels = np.ascontiguousarray(np.concatenate([l.reshape(-1, 4) for l in levels]))
        info = [len(levels)]
        off = 0
        for l in levels:
            info += [off, l.shape[1], l.shape[0]]
            off += l.shape[0] * l.shape[1]
        self.info = np.array(info, np.int64)

    def mode(self, minify):
        """(sampler mode, uses mip levels) for a magnified or minified triangle."""
        f = self.minfilter if minify else self.magfilter
        mip = minify and f in (TX_MIPMAP, TX_MIPMAP_POINT, TX_MIPMAP_LINEAR,
                               TX_MIPMAP_BILINEAR, TX_MIPMAP_TRILINEAR, 0x280)
        bil = f in (TX_BILINEAR, TX_MIPMAP_BILINEAR, TX_MIPMAP_TRILINEAR, 0x230, 0x240, 0x250,
                    0x260, 0x270, 0x280)
        return (BILINEAR if bil else POINT), mip


def _halve(a):
    h, w = a.shape[:2]
    b = a.astype(np.uint32)
    if h > 1:
        b = b[0::2] + b[1::2]
    else:
        b = b * 2
    if w > 1:
        b = b[:, 0::2] + b[:, 1::2]
    else:
        b = b * 2
    return ((b + 2) // 4).astype(np.uint8)


def _next_pow2(n):
    return 1 << max(0, math.ceil(math.log2(n)))


def _resample(a, h, w):
    """Bilinear resampling of an (H, W, 4) image to (h, w)."""
    H, W = a.shape[:2]
    if (H, W) == (h, w):
        return a
    ys = (np.arange(h) + 0.5) * H / h - 0.5
    xs = (np.arange(w) + 0.5) * W / w - 0.5
    y0 = np.clip(np.floor(ys).astype(int), 0, H - 1)
    x0 = np.clip(np.floor(xs).astype(int), 0, W - 1)
    y1 = np.clip(y0 + 1, 0, H - 1)
    x1 = np.clip(x0 + 1, 0, W - 1)
    fy = np.clip(ys - y0, 0, 1)[:, None, None]
    fx = np.clip(xs - x0, 0, 1)[None, :, None]
    f = a.astype(np.float64)
    top = f[y0][:, x0] * (1 - fx) + f[y0][:, x1] * fx
    bot = f[y1][:, x0] * (1 - fx) + f[y1][:, x1] * fx
    return np.clip(np.floor(top * (1 - fy) + bot * fy + 0.5), 0, 255).astype(np.uint8)


def unpack_image(nc, width, height, image):
    """texdef2d image -> (height, width, 4) RGBA uint8 (row 0 at the bottom).

    Accepts the C layout as uint32 words or big-endian bytes, or an
    (height, width, nc) uint8 array ([S])."""
    a = np.asarray(image)
    if a.ndim == 3:
        if a.shape != (height, width, nc):
            raise ValueError(f"image array is {a.shape}, expected {(height, width, nc)}")
        comps = a.astype(np.uint8)
    else:
        if isinstance(image, (bytes, bytearray)):
            raw = np.frombuffer(bytes(image), np.uint8)
        else:
            if a.ndim == 0:
                raise ValueError("image is not an array")
            if a.dtype == object:           # Python ints of any size: C's unsigned long
                a = np.array([int(v) & 0xFFFFFFFF for v in a.reshape(-1)], np.int64)
            raw = a.astype(np.int64).astype(">u4").view(np.uint8).reshape(-1)
        stride = -(-width * nc // 4) * 4
        if raw.size < stride * height:
            raise ValueError(f"image has {raw.size} bytes, expected {stride * height}")
        rows = raw[:stride * height].reshape(height, stride)[:, :width * nc]
        comps = rows.reshape(height, width, nc)
        order = {1: [0], 2: [1, 0], 3: [2, 1, 0], 4: [3, 2, 1, 0]}[nc]
        comps = comps[:, :, order]            # -> I / I A / R G B / R G B A
    out = np.empty((height, width, 4), np.uint8)
    if nc == 1:
        out[..., :3] = comps[..., :1]
        out[..., 3] = 255
    elif nc == 2:
        out[..., :3] = comps[..., :1]
        out[..., 3] = comps[..., 1]
    elif nc == 3:
        out[..., :3] = comps
        out[..., 3] = 255
    else:
        out[...] = comps
    return _resample(out, _next_pow2(height), _next_pow2(width))


class Environment:
    """A tevdef environment: mode and constant colour (0..1)."""

    def __init__(self, mode=TV_MODULATE, colour=(1.0, 1.0, 1.0, 1.0)):
        self.mode = mode
        self.colour = colour
