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

__all__ = ["DEFAULT_MAP", "MapState", "default_colormap", "scanout", "scanout_window",
           "screen_words", "screen_image"]


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


def screen_words(machine, x0, x1, y0, y1):
    """The screen rectangle x0..x1, y0..y1 as displayed (readdisplay(3G)):
    every window at its place, front ones over back ones (machine.stacking),
    the rest black; (h, w) uint32 packed ABGR with alpha 0xFF, row 0 at y0."""
    out = np.full((y1 - y0 + 1, x1 - x0 + 1), 0xFF000000, np.uint32)
    for gid in machine.stacking:
        w = machine.windows[gid]
        img = machine.image(w)[::-1]                   # row 0 = bottom
        words = (0xFF000000 | (img[..., 2].astype(np.uint32) << 16) |
                 (img[..., 1].astype(np.uint32) << 8) | img[..., 0].astype(np.uint32))
        ox, oy = w.origin
        xa, xb = max(x0, ox), min(x1, ox + w.width - 1)
        ya, yb = max(y0, oy), min(y1, oy + w.height - 1)
        if xa <= xb and ya <= yb:
            out[ya - y0:yb - y0 + 1, xa - x0:xb - x0 + 1] = \
                words[ya - oy:yb - oy + 1, xa - ox:xb - ox + 1]
    return out


def screen_image(machine):
    """What the screen shows of every open window: the smallest screen
    rectangle holding them all, composed as screen_words does, as (h, w, 3)
    uint8, top row first; None with no window open (``vgx-run --screen``:
    a program of several windows, pictured whole)."""
    wins = [machine.windows[g] for g in machine.stacking]
    if not wins:
        return None
    x0 = min(w.origin[0] for w in wins)
    y0 = min(w.origin[1] for w in wins)
    x1 = max(w.origin[0] + w.width - 1 for w in wins)
    y1 = max(w.origin[1] + w.height - 1 for w in wins)
    words = screen_words(machine, x0, x1, y0, y1)[::-1]
    return np.stack([(words >> s) & 0xFF for s in (0, 8, 16)], -1).astype(np.uint8)
