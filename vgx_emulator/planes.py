"""The bitplanes of a window as numpy arrays, and a false-colour picture of
each (docs/trace.md).

``planes(gid)`` gives every bank that exists (framebuffer/__init__.py):
``front``, ``back`` (colour words), ``z`` (signed 24-bit values in int32),
``stencil`` (uint8), ``accum`` (int16, R G B A), ``pup``, ``overlay``,
``underlay`` (colour indices), each a copy with row 0 the bottom row.
``.picture(name)`` (or ``.pictures()``) renders one with a legend:

- colour banks as the screen would show them (RGB words, or indices
  through the colour map);
- z as depth, near bright and far dark over the range of values present,
  cleared pixels (GD_ZMAX) black; the legend gives the range;
- stencil as exact counts: one colour per value, keyed on a reference
  value (grey = the reference, warm = above it, cool = below); the legend
  lists every value present with its pixel count;
- accumulation as signed values: R G B scaled by 255 / the largest
  component, negative components shown magenta; the legend gives the range;
- pop-up/overlay/underlay through their colour maps, 0 (transparent) black.

A picture, a window (``machine().current``) and a trace step have
``_repr_png_``, so Jupyter shows them inline.
"""
import io

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from .framebuffer import ZMAX
from .framebuffer.layers import OVERDRAW, PUPDRAW, UNDERDRAW

__all__ = ["planes", "Planes", "Picture", "picture", "banks", "window_picture",
           "stencil_colours"]

LAYER_NAMES = {PUPDRAW: "pup", OVERDRAW: "overlay", UNDERDRAW: "underlay"}
ORDER = ("front", "back", "z", "stencil", "accum", "pup", "overlay", "underlay")
TITLES = {"front": "front colour bank", "back": "back colour bank", "z": "z bank",
          "stencil": "stencil bank", "accum": "accumulation bank",
          "pup": "pop-up bank", "overlay": "overlay bank", "underlay": "underlay bank"}

_WARM = np.array([(230, 60, 40), (250, 150, 30), (250, 230, 60), (150, 230, 60),
                  (250, 120, 200), (200, 60, 160), (255, 255, 255)], np.uint8)
_COOL = np.array([(40, 110, 240), (40, 210, 230), (120, 90, 230), (30, 160, 120),
                  (90, 160, 255), (20, 60, 150), (170, 170, 255)], np.uint8)
_KEY = (70, 70, 70)
_NEG = (255, 0, 255)
_RAMP = np.array([(255, 250, 210), (250, 190, 60), (210, 80, 60), (110, 30, 110),
                  (30, 20, 70)], float)          # near ... far


def _machine():
    from irisgl._current import machine
    return machine


def banks(win):
    """The banks of a window that exist, name -> the live array (no copy)."""
    fb = win.fb
    out = {"front": fb.front}
    for name in ("back", "z", "stencil", "accum"):
        a = getattr(fb, name)
        if a is not None:
            out[name] = a
    for mode, name in LAYER_NAMES.items():
        a = fb.layers.get(mode) if fb.layer_planes.get(mode) else None
        if a is not None:
            out[name] = a
    return out


class Picture:
    """An (h, w, 3) uint8 image, top row first, with a title and a legend
    (list of (swatch rgb or None, text)); ``_repr_png_`` for notebooks."""

    def __init__(self, image, title, legend=()):
        self.image = np.ascontiguousarray(image, np.uint8)
        self.title = title
        self.legend = list(legend)

    def composed(self):
        """The image with its title above and its legend below (PIL Image)."""
        return _compose(self.image, self.title, self.legend)

    def to_png(self):
        buf = io.BytesIO()
        self.composed().save(buf, "PNG", compress_level=1)
        return buf.getvalue()

    def _repr_png_(self):
        return self.to_png()

    def save(self, path):
        self.composed().save(path, "PNG", compress_level=1)
        return path

    def __repr__(self):
        return f"<Picture {self.title!r} {self.image.shape[1]}x{self.image.shape[0]}>"


_FONT = None


def _font():
    global _FONT
    if _FONT is None:
        _FONT = ImageFont.load_default()
    return _FONT


def _compose(img, title, legend, line=14):
    h, w = img.shape[:2]
    width = max(w, 300)
    rows = [(None, title)] + list(legend)
    out = Image.new("RGB", (width, h + line * len(rows) + 8), (24, 24, 24))
    d = ImageDraw.Draw(out)
    d.text((4, 2), title, fill=(235, 235, 235), font=_font())
    out.paste(Image.fromarray(img, "RGB"), (0, line + 2))
    y = h + line + 6
    for sw, text in legend:
        x = 4
        if sw is not None:
            d.rectangle([x, y + 1, x + 10, y + 11], fill=tuple(int(c) for c in sw),
                        outline=(200, 200, 200))
            x += 16
        d.text((x, y), text, fill=(220, 220, 220), font=_font())
        y += line
    return out


def stencil_colours(values, key):
    """The colour (n, 3) uint8 of each stencil value: grey for ``key``,
    warm colours for key+1, key+2 ..., cool ones for key-1, key-2 ..."""
    d = np.asarray(values, np.int64) - int(key)
    out = np.empty((len(d), 3), np.uint8)
    out[d == 0] = _KEY
    pos, neg = d > 0, d < 0
    out[pos] = _WARM[(d[pos] - 1) % len(_WARM)]
    out[neg] = _COOL[(-d[neg] - 1) % len(_COOL)]
    return out


def _stencil(a, key, planes_n):
    vals, counts = np.unique(a, return_counts=True)
    lut = np.zeros((256, 3), np.uint8)
    lut[vals] = stencil_colours(vals, key)
    legend = []
    cols = stencil_colours(vals, key)
    shown = vals if len(vals) <= 14 else vals[np.argsort(-counts)[:14]]
    for v in sorted(shown.tolist()):
        i = int(np.searchsorted(vals, v))
        rel = "= key" if v == key else f"key{v - key:+d}"
        legend.append((cols[i], f"{v} ({rel}): {int(counts[i])} px"))
    if len(vals) > len(shown):
        legend.append((None, f"... {len(vals) - len(shown)} more values"))
    head = (None, f"{planes_n} planes, key (reference) {key}; exact counts per value")
    return lut[a], [head] + legend


def _depth(a):
    z = a.astype(np.int64)
    drawn = z != ZMAX
    img = np.zeros(z.shape + (3,), np.uint8)
    legend = []
    if drawn.any():
        lo, hi = int(z[drawn].min()), int(z[drawn].max())
        t = (z[drawn] - lo) / max(hi - lo, 1)
        xs = np.linspace(0.0, 1.0, len(_RAMP))
        img[drawn] = np.stack([np.interp(t, xs, _RAMP[:, c]) for c in range(3)],
                              -1).round().astype(np.uint8)
        legend += [(_RAMP[0], f"near: {lo} ({lo / ZMAX:+.6f} of GD_ZMAX)"),
                   (_RAMP[-1], f"far:  {hi} ({hi / ZMAX:+.6f} of GD_ZMAX)")]
    legend.append(((0, 0, 0), f"GD_ZMAX {ZMAX:#x} (cleared): {int((~drawn).sum())} px"))
    return img, legend


def _accum(a):
    rgb = a[..., :3].astype(np.int64)
    hi = int(rgb.max()) if rgb.size else 0
    lo = int(rgb.min()) if rgb.size else 0
    s = 255.0 / max(hi, 1)
    img = np.clip(rgb * s, 0, 255).round().astype(np.uint8)
    neg = (rgb < 0).any(-1)
    if neg.any():
        m = (-rgb.min(-1)[neg]).astype(float) / max(-lo, 1)
        img[neg] = (np.outer(0.35 + 0.65 * m, _NEG)).round().astype(np.uint8)
    al = a[..., 3]
    legend = [(None, f"R G B from {lo} to {hi}, shown x 255/{max(hi, 1)}"),
              (_NEG, f"a negative component: {int(neg.sum())} px"),
              (None, f"A from {int(al.min())} to {int(al.max())}")]
    return img, legend


def _colour(a, win, m):
    from . import display
    from .framebuffer import layers
    st = win.st
    rgb = layers.normal(st, "rgb")
    shown = m.maps.shown(m.colormap)
    base = display.MMAP_SIZE * m.maps.current if (st.multimap and not rgb) else None
    img = display.scanout(a, rgb, shown, base)[::-1]
    return img, [(None, "RGB words 0xAABBGGRR" if rgb else "indices through the colour map")]


def _layer(a, mode, m):
    lut = m.maps.maps[mode]
    img = lut[a & 0xFF].astype(np.uint8)
    img[a == 0] = 0
    vals, counts = np.unique(a, return_counts=True)
    legend = [(lut[int(v) & 0xFF] if v else (0, 0, 0),
               f"index {int(v)}{' (transparent)' if v == 0 else ''}: {int(c)} px")
              for v, c in list(zip(vals, counts))[:10]]
    return img, legend


def picture(name, a, win, key=0, m=None):
    """The false-colour Picture of bank ``name`` (array ``a``, row 0 at the
    bottom) of window ``win``; ``key``: the stencil reference value."""
    m = m or _machine()
    if name == "stencil":
        img, legend = _stencil(a, key, win.fb.stencil_planes)
    elif name == "z":
        img, legend = _depth(a)
    elif name == "accum":
        img, legend = _accum(a)
    elif name in ("front", "back"):
        img, legend = _colour(a, win, m)
    else:
        mode = {v: k for k, v in LAYER_NAMES.items()}[name]
        img, legend = _layer(a, mode, m)
    return Picture(img[::-1], f"{TITLES[name]} of window {win.gid}", legend)


def stencil_key(win, default=0):
    """The reference a stencil picture is keyed on: the stencil(3G) ref
    while a comparing test is on, else ``default`` (the last sclear)."""
    st = win.st
    if st.stencil_on and st.stencil[1] not in (0, 7):      # not SF_NEVER/SF_ALWAYS
        return int(st.stencil[0]) & 0xFF
    return default


class Planes(dict):
    """planes(): bank name -> numpy array (a copy), and their pictures."""

    def __init__(self, arrays, win, key):
        super().__init__(arrays)
        self.win = win
        self.key = key

    def picture(self, name):
        return picture(name, self[name], self.win, self.key)

    def pictures(self):
        return {n: self.picture(n) for n in self}

    def _repr_png_(self):
        return _side_by_side([self.picture(n) for n in self])


def _side_by_side(pics):
    ims = [p.composed() for p in pics]
    out = Image.new("RGB", (sum(i.width for i in ims) + 4 * (len(ims) - 1),
                            max(i.height for i in ims)), (24, 24, 24))
    x = 0
    for i in ims:
        out.paste(i, (x, 0))
        x += i.width + 4
    buf = io.BytesIO()
    out.save(buf, "PNG", compress_level=1)
    return buf.getvalue()


def planes(gid=None, key=None):
    """Every bank of window ``gid`` (default: the current window) that
    exists, as a Planes dict of numpy copies (primitives issued so far are
    drawn first).  ``key``: the stencil pictures' reference (default: the
    stencil(3G) ref when a comparing test is on, else 0)."""
    from .errors import GLError
    m = _machine()
    win = m.windows.get(gid) if gid is not None else m.current
    if win is None:
        raise GLError("planes: no such window" if gid is not None else
                      "planes: no window is open; call winopen first")
    m._flush(win)
    arrays = {n: a.copy() for n, a in banks(win).items()}
    return Planes(arrays, win, stencil_key(win) if key is None else key)


def window_picture(win):
    """What the screen shows of a window, as a Picture."""
    m = _machine()
    return Picture(m.image(win), f"window {win.gid} {win.name!r}")
