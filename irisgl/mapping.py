"""Screen-space helpers: scrbox, getscrbox (scrbox(3G), getscrbox(3G)),
screenspace (screenspace(3G)), and the GL1 point-transform calls xfpt*.

scrbox tracks the window-coordinate box of what is scan converted while
SB_TRACK is in force (vgx_emulator/geometry/scrbox.py computes it from the
batches' window geometry after clipping).  xfpt* returned points through
the feedback buffer of the older Geometry Engines; feedback mode is not
emulated, so they raise GLError, as blendcolor does (the VGX has no
constant blend colour).  See docs/clip-planes-fog-and-extras.md.
"""
from vgx_emulator.state import SCRBOX_EMPTY

from . import constants as K
from ._current import glcall, machine, not_emulated, token, win
from .matrix import ortho2, viewport
from .window import GDESC

__all__ = ["scrbox", "getscrbox", "screenspace", "xfpt", "xfpti", "xfpts", "xfpt2", "xfpt2i",
           "xfpt2s", "xfpt4", "xfpt4i", "xfpt4s", "blendcolor"]

_SB = {K.SB_RESET: "SB_RESET", K.SB_TRACK: "SB_TRACK", K.SB_HOLD: "SB_HOLD"}


@glcall
def scrbox(arg):
    """scrbox(3G): SB_RESET empties the screen box and stops tracking,
    SB_TRACK grows it by every pixel scan converted from now on, SB_HOLD
    stops tracking and keeps the box.  Clears do not change it."""
    a = token("scrbox", arg, _SB, "arg")
    w = win("scrbox")
    machine.state_change(w)           # what was drawn before is tracked (or not) as it was
    w.st.scrbox_mode = a
    if a == K.SB_RESET:
        w.st.scrbox = SCRBOX_EMPTY


@glcall
def getscrbox():
    """getscrbox(3G): ``left, right, bottom, top = getscrbox()``, window
    coordinates of the box tracked since SB_RESET; left > right or
    bottom > top when nothing was drawn."""
    w = win("getscrbox")
    machine.state_change(w)           # pending primitives are part of the box
    return tuple(int(v) for v in w.st.scrbox)


@glcall(immediate=True)
def screenspace():
    """screenspace(3G): viewport and projection mapping world coordinates to
    absolute screen pixels, as the man page's equivalent code:
    viewport(-xmin, XPMAX - xmin, -ymin, YPMAX - ymin) and
    ortho2(-0.5, XPMAX + 0.5, -0.5, YPMAX + 0.5), (xmin, ymin) = getorigin()."""
    w = win("screenspace")
    xmin, ymin = w.origin
    xp, yp = GDESC[K.GD_XPMAX], GDESC[K.GD_YPMAX]
    viewport.__wrapped__(-xmin, xp - xmin, -ymin, yp - ymin)
    ortho2.__wrapped__(-0.5, xp + 0.5, -0.5, yp + 0.5)


_XFPT = ("xfpt(3G) transforms points into the feedback buffer of the IRIS 1000-3000 "
         "Geometry Engines; feedback mode is not emulated (transform points with "
         "getmatrix and numpy instead)")
for _n in __all__[3:-1]:
    globals()[_n] = not_emulated(_n, _XFPT)
del _n

#: blendcolor(3G): "IRIS-4D G, GT, GTX, VGX, and VGXT models ... do not support
#: blendcolor" (getgdesc(GD_BLENDCOLOR) is 0 here).
blendcolor = not_emulated(
    "blendcolor", "the IRIS-4D VGX has no constant blend colour (getgdesc(GD_BLENDCOLOR) is 0; "
    "blendcolor(3G) lists the VGX among the models without it)")
