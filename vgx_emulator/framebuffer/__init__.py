"""The bitplanes of one window.

A bank exists only when the configuration asks for it (issue: "a buffer
exists only once the configuration asks for it"):

============ ===================================================== ============
bank         created by                                            array
============ ===================================================== ============
front colour winopen                                               uint32 (h, w)
back colour  gconfig() after doublebuffer()                        uint32 (h, w)
z            first zbuffer(TRUE), zclear, czclear or lsetdepth use int32 (h, w)
stencil      gconfig() after stensize(n > 0)                       uint8 (h, w)
accumulation gconfig() after acsize(16)                            int16 (h, w, 4)
pop-up,      first drawing or reading in PUPDRAW/OVERDRAW/UNDERDRAW uint32 (h, w)
overlay,     when the framebuffer has planes (layers.py; overlay(3G),
underlay     underlay(3G) at gconfig)
============ ===================================================== ============

Colour words are packed ``0xAABBGGRR`` in RGB mode and hold the colour index
in colour-map mode.  Row 0 is the bottom row of the window (IRIS GL's origin
is the lower left), so ``plane[y, x]`` is window pixel (x, y).
The z plane holds the signed 24-bit VGX value sign-extended in an int32
(docs/semantics.md §5).  Its per-segment maxima (zmax.py) are an aid of the emulator,
not a VGX bank: built from z only when a pass can use them.
"""
import numpy as np

from .. import pipeline
from . import layers as _layers
from . import zmax

ZMIN = -0x800000
ZMAX = 0x7FFFFF


def _plane(h, w, dtype, fill=0):
    return np.full((h, w), fill, dtype=dtype)


class _Waited:
    """A bank (or its z maxima) of a Framebuffer: reading or setting it
    first waits for the raster work already queued (pipeline.py), so what
    it holds is what every pass issued before drew.  The code that queues
    raster work takes the banks with :meth:`Framebuffer.queued` instead."""

    def __set_name__(self, owner, name):
        self.raw = "_" + name

    def __get__(self, fb, owner=None):
        if fb is None:
            return self
        pipeline.sync()
        return fb.__dict__[self.raw]

    def __set__(self, fb, value):
        pipeline.sync()
        fb.__dict__[self.raw] = value


class Framebuffer:
    """Allocation of the banks of one window, per its configuration."""

    front = _Waited()
    back = _Waited()
    z = _Waited()
    stencil = _Waited()
    accum = _Waited()
    layers = _Waited()
    zmax = _Waited()
    zmax_dirty = _Waited()
    zmax_uniform = _Waited()

    def __init__(self, width, height):
        self.width = width
        self.height = height
        self.front = _plane(height, width, np.uint32)
        self.back = None
        self.z = None
        self.zmax = None            # zmax.py: per-segment maxima of z
        self.zmax_dirty = None      # the rectangle of z written since zmax was built
        self.zmax_uniform = None    # the value of every maximum after a whole clear
        self.stencil = None
        self.stencil_planes = 0
        self.accum = None
        self.layer_planes = dict(_layers.DEFAULT_PLANES)
        self.layers = {}            # drawmode -> colour-index bank (layers.py)

    def queued(self, name):
        """The bank ``name`` ("front", "back", "stencil", ...) or None,
        without waiting: for the code that hands it to queued raster work
        (pipeline.py), which runs after the work queued before it."""
        return self.__dict__["_" + name]

    def has(self, name):
        """Whether the bank ``name`` exists (no wait: banks are made and
        dropped only by the calling thread)."""
        return self.__dict__["_" + name] is not None

    def layer(self, mode, queued=False):
        """The bank of the pop-up, overlay or underlay framebuffer (created,
        all 0 = transparent, on first use), or None when it has no planes.
        ``queued``: for queued work, without waiting (see :meth:`queued`)."""
        if not self.layer_planes.get(mode):
            return None
        layers = self.queued("layers") if queued else self.layers
        bank = layers.get(mode)
        if bank is None:
            bank = layers[mode] = _plane(self.height, self.width, np.uint32)
        return bank

    def configure_layers(self, overlay, underlay):
        """gconfig(): overlay and underlay plane counts (layers.resolve);
        a bank whose size changes starts again all 0."""
        for mode, n in ((_layers.OVERDRAW, overlay), (_layers.UNDERDRAW, underlay)):
            if self.layer_planes.get(mode) != n:
                self.layer_planes[mode] = n
                self.layers.pop(mode, None)

    def configure(self, double, stencil_planes, accum_planes):
        """Apply gconfig(): create or drop the back, stencil and accumulation banks."""
        h, w = self.height, self.width
        if double and self.back is None:
            self.back = _plane(h, w, np.uint32)
        elif not double:
            self.back = None
        self.stencil_planes = stencil_planes
        self.stencil = _plane(h, w, np.uint8) if stencil_planes else None
        self.accum = np.zeros((h, w, 4), np.int16) if accum_planes else None

    def ensure_z(self, queued=False):
        """The z bank, created on first use (initial contents: GD_ZMAX).
        ``queued``: for queued work, without waiting (see :meth:`queued`)."""
        if self.__dict__["_z"] is None:
            self.__dict__["_z"] = _plane(self.height, self.width, np.int32, ZMAX)
        return self.queued("z") if queued else self.z

    def z_maxima(self):
        """The per-segment z maxima (zmax.py), rebuilt where z was written
        since they were last built (zmax_dirty)."""
        z = self.ensure_z()
        if self.zmax is None:
            self.zmax = zmax.empty(self.height, self.width)
            self.zmax_dirty = (0, self.width - 1, 0, self.height - 1)
        d = self.zmax_dirty
        if d is not None:
            zmax.build(z, self.zmax, d[0], d[1], d[2], d[3])
            self.zmax_dirty = None
            self.zmax_uniform = None
        return self.zmax

    @property
    def zmax_fresh(self):
        """Whether the maxima match the z bank (no z written since built)."""
        return self.zmax is not None and self.zmax_dirty is None

    def z_written(self, rect=None, value=None, box=None):
        """A pass or clear writes the z bank: the maxima must be rebuilt
        before their next use, over ``box`` (x0, x1, y0, y1 inclusive: the
        pixels the writes may have touched; None: anywhere) joined to what
        was written since they were built.  A clear of the whole bank to
        ``value`` (rect = x0, x1, y0, y1) sets them instead; a partial clear
        marks its ``rect``; an empty ``box`` changes nothing."""
        if box is not None and (box[0] > box[1] or box[2] > box[3]):
            return
        whole = rect is not None and rect[0] == 0 and rect[2] == 0 and \
            rect[1] == self.width - 1 and rect[3] == self.height - 1
        self.zmax_uniform = value if whole else None
        if whole and self.zmax is not None:
            self.zmax[:] = value
            self.zmax_dirty = None
            return
        r = box if box is not None else rect if rect is not None else \
            (0, self.width - 1, 0, self.height - 1)
        d = self.zmax_dirty
        if d is not None:
            r = (min(d[0], r[0]), max(d[1], r[1]), min(d[2], r[2]), max(d[3], r[3]))
        self.zmax_dirty = r

    def swap(self):
        """swapbuffers(): exchange front and back."""
        if self.back is not None:
            self.front, self.back = self.back, self.front

    def nbytes(self):
        """Memory held by the banks that exist."""
        return sum(a.nbytes for a in (self.front, self.back, self.z, self.stencil,
                                      self.accum, *self.layers.values()) if a is not None)
