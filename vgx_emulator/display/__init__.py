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
    """The 4096-entry map after ginit/greset: the eight named colours, the
    rest black."""
    lut = np.zeros((4096, 3), np.uint8)
    lut[:8] = DEFAULT_MAP
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
