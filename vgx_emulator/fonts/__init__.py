"""Raster fonts: the font table's entries and the glyph pixels of a string.

A :class:`RasterFont` holds, per character value, the set pixels of its
bitmap relative to the character origin and the spacing added to the
character position after it (defrasterfont(3G), deflfont(3G)).  A bitmap's
lower-left corner lies ``(xoff, yoff)`` from the origin; its rows run bottom
to top, each padded to 16 bits, bits left-justified.  :meth:`layout` turns
a string of character values into the window-relative pixels of all its
glyphs with numpy (no loop over characters or pixels); the machine draws
them (``VGX.char_pixels``).

Font 0 is the X.Org misc-fixed 9x15 font (public domain, see README.md):
characters 0-127, fixed pitch 9, ascent 12, descent 3 (deflfont(3G): "a
fixed-pitch ASCII font with a height of 15, width of 9, character values 0
through 127").  ``loadXfont`` maps X font names onto the X fonts shipped
here (:func:`x_font`).
"""
import base64
import fnmatch
from functools import lru_cache

import numpy as np

from . import xfixed


class RasterFont:
    """One font: glyph pixels, spacing, and the metrics getheight(3G) and
    getdescender(3G) report."""

    def __init__(self, values, offset, w, h, xoff, yoff, xmove, ymove, raster,
                 height, descender=None, encoding="", name=""):
        values = np.asarray(values, np.int64)
        order = np.argsort(values, kind="stable")
        self.values = values[order]
        self.xmove = np.asarray(xmove, np.int64)[order]
        self.ymove = np.asarray(ymove, np.int64)[order]
        w = np.asarray(w, np.int64)[order]
        h = np.asarray(h, np.int64)[order]
        xoff = np.asarray(xoff, np.int64)[order]
        yoff = np.asarray(yoff, np.int64)[order]
        offset = np.asarray(offset, np.int64)[order]
        raster = np.asarray(raster, np.uint16)
        px, py, counts = [], [], []
        for i in range(len(self.values)):           # per glyph, at definition time
            x, y = _glyph_pixels(raster, offset[i], w[i], h[i])
            px.append(x + xoff[i])
            py.append(y + yoff[i])
            counts.append(len(x))
        self.count = np.array(counts, np.int64)
        self.start = np.concatenate(([0], np.cumsum(self.count)[:-1])).astype(np.int64)
        self.px = np.concatenate(px).astype(np.int64) if px else np.zeros(0, np.int64)
        self.py = np.concatenate(py).astype(np.int64) if py else np.zeros(0, np.int64)
        drawn = h > 0
        self.height = int(height)
        self.descender = int(descender) if descender is not None else \
            int(max(0, -yoff[drawn].min())) if drawn.any() else 0
        self.encoding = encoding
        self.name = name

    def glyphs(self, codes):
        """Indices of the glyphs of the defined characters among ``codes``
        (undefined characters have zero size: they are left out)."""
        codes = np.asarray(codes, np.int64)
        if not len(self.values) or not len(codes):
            return np.zeros(0, np.int64)
        i = np.minimum(np.searchsorted(self.values, codes), len(self.values) - 1)
        return i[self.values[i] == codes]

    def advance(self, codes):
        """(dx, dy) the character position moves after drawing ``codes``."""
        g = self.glyphs(codes)
        return int(self.xmove[g].sum()), int(self.ymove[g].sum())

    def layout(self, codes):
        """(xs, ys, dx, dy): every set pixel of the string's glyphs relative to
        the character position, left to right, and the total spacing."""
        g = self.glyphs(codes)
        ox = np.cumsum(self.xmove[g]) - self.xmove[g]      # each character's origin
        oy = np.cumsum(self.ymove[g]) - self.ymove[g]
        cnt = self.count[g]
        total = int(cnt.sum())
        which = np.repeat(np.arange(len(g)), cnt)
        first = np.repeat(np.cumsum(cnt) - cnt, cnt)
        pix = self.start[g][which] + (np.arange(total) - first)
        xs = self.px[pix] + ox[which]
        ys = self.py[pix] + oy[which]
        return xs, ys, int(self.xmove[g].sum()), int(self.ymove[g].sum())


def _glyph_pixels(raster, offset, w, h):
    """(x, y) of the set bits of one bitmap: h rows from raster[offset],
    bottom row first, each (w + 15) // 16 words, bits left-justified."""
    if w <= 0 or h <= 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    words = (int(w) + 15) // 16
    rows = raster[offset:offset + h * words].astype(">u2").reshape(h, words)
    bits = np.unpackbits(rows.view(np.uint8), axis=1)[:, :w]
    y, x = np.nonzero(bits)
    return x.astype(np.int64), y.astype(np.int64)


def _decode(entry, key, dtype):
    return np.frombuffer(base64.b64decode("".join(entry[key])), dtype)


@lru_cache(maxsize=None)
def x_font_data(name):
    """(chars (N, 7), raster, ascent, descent, xlfd) of a shipped X font."""
    e = xfixed.FONTS[name]
    chars = _decode(e, "chars", "<i4").reshape(-1, 7).astype(np.int64)
    return chars, _decode(e, "raster", "<u2").astype(np.uint16), e["ascent"], \
        e["descent"], e["xlfd"]


def _from_x(name):
    chars, raster, ascent, descent, xlfd = x_font_data(name)
    reg = xlfd.split("-")
    enc = "-".join(reg[-2:]) if len(reg) > 2 else ""
    return RasterFont(chars[:, 0], chars[:, 1], chars[:, 2], chars[:, 3], chars[:, 4],
                      chars[:, 5], chars[:, 6], np.zeros(len(chars)), raster,
                      ascent + descent, descent, enc, xlfd)


@lru_cache(maxsize=None)
def default_font():
    """Font 0: the 9x15 font's characters 0-127 (deflfont(3G) says all of
    them are defined; 127, which the X font lacks, is blank, 9 wide)."""
    chars, raster, ascent, descent, xlfd = x_font_data("9x15")
    chars = chars[chars[:, 0] < 128]
    missing = np.setdiff1d(np.arange(128), chars[:, 0])
    blank = np.zeros((len(missing), 7), np.int64)
    blank[:, 0], blank[:, 6] = missing, 9
    chars = np.concatenate((chars, blank))
    return RasterFont(chars[:, 0], chars[:, 1], chars[:, 2], chars[:, 3], chars[:, 4],
                      chars[:, 5], chars[:, 6], np.zeros(len(chars)), raster,
                      ascent + descent, descent, "ISO8859-1", "default (misc-fixed 9x15)")


#: X font names loadXfont(3G) accepts (fnmatch patterns, any case), and the
#: shipped font each one loads.  Every other name raises GLError.
X_NAMES = (("*9x15bold*", "9x15bold"), ("*9x15b", "9x15bold"), ("*9x15b-*", "9x15bold"),
           ("*-fixed-bold-r-normal--15-*", "9x15bold"),
           ("*9x15*", "9x15"), ("fixed", "9x15"),
           ("*-fixed-medium-r-normal--15-*", "9x15"))


@lru_cache(maxsize=None)
def x_font(name):
    """The RasterFont loadXfont(3G) gives for an X font name, or None."""
    low = name.strip().lower()
    for pattern, shipped in X_NAMES:
        if fnmatch.fnmatchcase(low, pattern):
            return _from_x(shipped)
    return None


def user_font(ht, chars, raster):
    """A defrasterfont font: ``chars`` (nc, 6) rows offset, w, h, xoff,
    yoff, width, character value = row index; ``raster`` uint16."""
    chars = np.asarray(chars, np.int64).reshape(-1, 6)
    n = len(chars)
    return RasterFont(np.arange(n), chars[:, 0], chars[:, 1], chars[:, 2], chars[:, 3],
                      chars[:, 4], chars[:, 5], np.zeros(n), raster, ht)


def long_font(chars, raster):
    """A deflfont font: ``chars`` (nc, 8) rows value, offset, w, h, xoff,
    yoff, xmove, ymove.  getheight is the tallest extent above the lowest
    descender ([S]: deflfont has no height argument)."""
    chars = np.asarray(chars, np.int64).reshape(-1, 8)
    drawn = chars[:, 3] > 0
    ht = int((chars[drawn, 5] + chars[drawn, 3]).max() - min(0, chars[drawn, 5].min())) \
        if drawn.any() else 0
    return RasterFont(chars[:, 0], chars[:, 1], chars[:, 2], chars[:, 3], chars[:, 4],
                      chars[:, 5], chars[:, 6], chars[:, 7], raster, ht)
