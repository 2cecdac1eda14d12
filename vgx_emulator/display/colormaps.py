"""The colour maps of the display hardware and their animation.

- the normal map: 4096 entries (``VGX.colormap``).  In multimap mode it is
  read as 16 maps of 256 entries: map ``m`` entry ``i`` is physical entry
  ``256 * m + i`` ([S], docs/colour-map-and-depthcue.md); setmap(3G)
  selects the map the normal framebuffer is shown through.
- the pop-up, overlay, underlay and cursor maps: 256 entries each (only the
  first 2**planes are reachable).
- cyclemap(3G) chains small maps; blink(3G) alternates entries.  Both count
  vertical retraces; the emulator has no clock, so every frame point
  (swapbuffers, gflush, finish) is ``RETRACES_PER_FRAME`` retraces: a
  program paced at 30 frames a second on a 60 Hz monitor ([S]).  This makes
  both deterministic.
"""
import numpy as np

from ..framebuffer.layers import CURSORDRAW, OVERDRAW, PUPDRAW, UNDERDRAW

NMMAPS = 16
MMAP_SIZE = 256
MAX_BLINKS = 20                 # blink(3G): up to 20 entries blink at once
RETRACES_PER_FRAME = 2


def _small_default(plane=None):
    """A small map's power-on entries: the eight default colours.  The
    pop-up map's first four are what gl.h names them (PUP_CLEAR 0, PUP_COLOR
    1, PUP_BLACK 2, PUP_WHITE 3): black and white at 2 and 3, as SGI's menu
    code draws black text on PUP_WHITE; [S] PUP_COLOR (PUP_CURSOR) red."""
    from . import DEFAULT_MAP
    lut = np.zeros((MMAP_SIZE, 3), np.uint8)
    lut[:8] = DEFAULT_MAP
    if plane == PUPDRAW:
        lut[2] = (0, 0, 0)
        lut[3] = (255, 255, 255)
    return lut


class MapState:
    """Colour maps other than the normal one, and the animation state."""

    def __init__(self):
        self.maps = {m: _small_default(m) for m in (PUPDRAW, OVERDRAW, UNDERDRAW, CURSORDRAW)}
        self.current = 0            # setmap(3G): the small map shown in multimap mode
        self.cycles = {}            # cyclemap: map -> (duration, nextmap)
        self.cycle_count = 0        # retraces spent on the current map
        self.blinks = {}            # blink: physical index -> (rate, (r, g, b))
        self.retrace = 0            # vertical retraces since power-on

    def tick(self, n=RETRACES_PER_FRAME):
        """n vertical retraces go by: cyclemap moves along its chain."""
        for _ in range(n):
            self.retrace += 1
            link = self.cycles.get(self.current)
            if link is None:
                self.cycle_count = 0
                continue
            self.cycle_count += 1
            if self.cycle_count >= link[0]:
                self.current = link[1]
                self.cycle_count = 0

    def shown(self, colormap):
        """The normal map as the screen shows it now: blinking entries in
        their alternate phase take their blink colour."""
        if not self.blinks:
            return colormap
        out = colormap.copy()
        for index, (rate, rgb) in self.blinks.items():
            if (self.retrace // rate) % 2 == 1:
                out[index] = rgb
        return out
