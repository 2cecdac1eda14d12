"""Display Subsystem: what the screen shows of a window.

RGB mode: the colour words are unpacked (0xAABBGGRR).  Colour-map mode: the
indices go through the colour map at scan-out, so ``mapcolor`` recolours
pixels already drawn (mapcolor(3G)); in multimap mode through the small
map setmap(3G) selected (colormaps.py).  The pop-up, overlay and underlay
framebuffers are composed per pixel by the rule of overlay(3G) and
underlay(3G): pop-up if its index is non-zero, else overlay if it has
planes and a non-zero index, else normal if its contents are non-zero or
there is no underlay, else underlay.
"""
import numpy as np

from ..framebuffer.layers import OVERDRAW, PUPDRAW, UNDERDRAW
from .colormaps import MMAP_SIZE, MapState

DEFAULT_MAP = [(0, 0, 0), (255, 0, 0), (0, 255, 0), (255, 255, 0),
               (0, 0, 255), (255, 0, 255), (0, 255, 255), (255, 255, 255)]

__all__ = ["DEFAULT_MAP", "MapState", "default_colormap", "scanout", "scanout_window"]


def default_colormap():
    """The 4096-entry map after ginit/greset, as IRIX's makemap(1G) leaves
    it: the eight named colours at 0..7; a black to almost-white grey ramp
    of 24 entries at 32..55 (entry 32 + k is k * 255 / 24, rounded); a
    5 x 8 x 5 colour cube from black to white at 56..255, green changing
    fastest, then red, then blue (entry 56 + g + 8 r + 40 b is (r * 255 / 4,
    g * 255 / 7, b * 255 / 4), rounded).  [S] makemap's pastel desktop
    colours at 8..15 are not given by the man page, and it leaves 16..31
    (the X clients') and the entries past 255 alone: those are black."""
    lut = np.zeros((4096, 3), np.uint8)
    lut[:8] = DEFAULT_MAP
    lut[32:56] = np.round(np.arange(24) * 255 / 24)[:, None]
    b, r, g = np.meshgrid(np.arange(5), np.arange(5), np.arange(8), indexing="ij")
    lut[56:256] = np.round(np.stack([r * 255 / 4, g * 255 / 7, b * 255 / 4], -1)).reshape(-1, 3)
    return lut


def scanout(words, rgb, colormap, base=None):
    """A colour bank -> (h, w, 3) uint8, top row first (as an image file).
    ``base``: in multimap mode, the first entry of the small map shown
    (the low 8 bits of each index select the entry)."""
    return _normal(words, rgb, colormap, base)[::-1]


def _normal(words, rgb, colormap, base):
    if rgb:
        img = np.empty(words.shape + (3,), np.uint8)
        img[..., 0] = words & 0xFF
        img[..., 1] = (words >> 8) & 0xFF
        img[..., 2] = (words >> 16) & 0xFF
        return img
    if base is None:
        return colormap[words & 0xFFF]
    return colormap[base + (words & (MMAP_SIZE - 1))]


def scanout_window(fb, rgb, multimap, colormap, maps):
    """What the screen shows of a window's framebuffers (normal front bank
    in RGB or colour-map mode, then underlay, overlay, pop-up), (h, w, 3)
    uint8, top row first.  ``maps``: the MapState."""
    shown = maps.shown(colormap)
    base = MMAP_SIZE * maps.current if (multimap and not rgb) else None
    img = _normal(fb.front, rgb, shown, base)
    under = fb.layers.get(UNDERDRAW) if fb.layer_planes.get(UNDERDRAW) else None
    if under is not None:
        empty = (fb.front & 0xFFFFFF) == 0 if rgb else (fb.front & 0xFFF) == 0
        sel = empty & (under != 0)
        img[sel] = maps.maps[UNDERDRAW][under[sel] & 0xFF]
    for mode in (OVERDRAW, PUPDRAW):
        bank = fb.layers.get(mode) if fb.layer_planes.get(mode) else None
        if bank is not None:
            sel = bank != 0
            img[sel] = maps.maps[mode][bank[sel] & 0xFF]
    return img[::-1]
