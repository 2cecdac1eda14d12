"""Display Subsystem: what the screen shows of a window.

RGB mode: the colour words are unpacked (0xAABBGGRR).  Colour-map mode: the
indices go through the colour map at scan-out, so ``mapcolor`` recolours
pixels already drawn (reference 15, 21).
"""
import numpy as np

DEFAULT_MAP = [(0, 0, 0), (255, 0, 0), (0, 255, 0), (255, 255, 0),
               (0, 0, 255), (255, 0, 255), (0, 255, 255), (255, 255, 255)]


def default_colormap():
    """The 4096-entry map after ginit/greset: the eight named colours, the
    rest black."""
    lut = np.zeros((4096, 3), np.uint8)
    lut[:8] = DEFAULT_MAP
    return lut


def scanout(words, rgb, colormap):
    """A colour bank -> (h, w, 3) uint8, top row first (as an image file)."""
    if rgb:
        img = np.empty(words.shape + (3,), np.uint8)
        img[..., 0] = words & 0xFF
        img[..., 1] = (words >> 8) & 0xFF
        img[..., 2] = (words >> 16) & 0xFF
    else:
        img = colormap[words & 0xFFF]
    return img[::-1]
