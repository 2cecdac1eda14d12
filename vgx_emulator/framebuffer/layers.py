"""The four GL framebuffers of a window: normal, pop-up, overlay, underlay.

drawmode(3G) picks the one that drawing and the colour, writemask and
colour-map calls address.  The normal framebuffer is the window's banks
(front/back, z, stencil ...) and the fields of its WindowState; the other
three are one colour-index bank each (``Framebuffer.layer``), single
buffered, with their own current index, writemask and colour map.

While a drawmode other than NORMALDRAW is current, the fields of
``SWAPPED`` in the WindowState hold that framebuffer's values and the
normal ones wait in ``st.saved[NORMALDRAW]`` (and the other way round):
so color/getcolor/writemask/getwritemask and the raster set-up read the
framebuffer being drawn without knowing about drawmodes.

Plane counts on the emulated VGX (docs/colour-map-and-depthcue.md): pop-up
2 (fixed), overlay 0/2/4/8 (default 2), underlay 0/2/4/8 (default 0,
underlay(3G)); overlay and underlay share the 8 auxiliary (alpha) planes.
The cursor has 2 planes and no bank (getplanes gives 0 in CURSORDRAW).
"""
NORMALDRAW, PUPDRAW, OVERDRAW, UNDERDRAW, CURSORDRAW = 0x10, 0x20, 0x40, 0x80, 0x100
DRAWMODES = {NORMALDRAW: "NORMALDRAW", PUPDRAW: "PUPDRAW", OVERDRAW: "OVERDRAW",
             UNDERDRAW: "UNDERDRAW", CURSORDRAW: "CURSORDRAW"}
#: drawmodes with a colour-index bank of their own
LAYERS = (PUPDRAW, OVERDRAW, UNDERDRAW)

PUP_PLANES = 2
CURSOR_PLANES = 2
AUX_PLANES = 8                  # shared by overlay and underlay
LAYER_SIZES = (0, 2, 4, 8)      # overlay(3G), underlay(3G)
DEFAULT_PLANES = {PUPDRAW: PUP_PLANES, OVERDRAW: 2, UNDERDRAW: 0}

#: WindowState fields kept per framebuffer (drawmode(3G): color, writemask,
#: cmode/RGBmode, single/doublebuffer, frontbuffer/backbuffer)
SWAPPED = ("colour", "cmask", "rgb", "double", "front_enabled", "back_enabled")


def fresh(mode):
    """The per-framebuffer fields of a framebuffer after gconfig: index 0,
    writemask all ones, colour-map mode, single-buffered."""
    return {"colour": (0.0, 0.0, 0.0, 0.0), "cmask": 0xFFFFFFFF, "rgb": False,
            "double": False, "front_enabled": True, "back_enabled": False}


def switch(st, mode):
    """Make ``mode`` the current drawmode of the state ``st`` (no checks)."""
    if mode == st.drawmode:
        return
    st.saved[st.drawmode] = {k: getattr(st, k) for k in SWAPPED}
    incoming = st.saved.pop(mode, None) or fresh(mode)
    for k, v in incoming.items():
        setattr(st, k, v)
    st.drawmode = mode


def normal(st, field):
    """A field of the normal framebuffer, whatever the drawmode."""
    if st.drawmode == NORMALDRAW:
        return getattr(st, field)
    return st.saved[NORMALDRAW][field]


def reset_layers(st):
    """gconfig(3G): the index of every drawmode is 0 and every writemask all
    ones (called while NORMALDRAW is current)."""
    for mode in (PUPDRAW, OVERDRAW, UNDERDRAW, CURSORDRAW):
        st.saved[mode] = fresh(mode)


def resolve(overlay, underlay):
    """gconfig's reconciliation of the overlay and underlay requests: the
    overlay is granted first; the underlay gets what is left of the 8
    auxiliary planes, rounded down to a legal size ([S])."""
    under = min(underlay, AUX_PLANES - overlay)
    under = max(s for s in LAYER_SIZES if s <= under)
    return overlay, under


def planes(win):
    """getplanes(3G) for the window's current drawmode and configuration:
    RGB 24, colour map 12 (8 in multimap mode); the bank's planes in
    PUPDRAW/OVERDRAW/UNDERDRAW; 0 in CURSORDRAW."""
    st = win.st
    mode = st.drawmode
    if mode == NORMALDRAW:
        if st.rgb:
            return 24
        return 8 if st.multimap else 12
    if mode == CURSORDRAW:
        return 0
    return win.fb.layer_planes[mode]


def index_bits(win):
    """The bits a colour word of the current drawmode may hold: 0xFFFFFFFF
    in RGB mode, 2**planes - 1 in colour-map mode."""
    st = win.st
    if st.rgb:
        return 0xFFFFFFFF
    return (1 << planes(win)) - 1
