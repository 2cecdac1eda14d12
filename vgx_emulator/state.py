"""Plain records of the state the IRIS GL calls write, per window.

Calls set fields here (after validation); the machine derives what the
pipeline needs (combined matrices, eye-space lights, the raster key) when a
batch is flushed.  Initial values are those of a freshly opened window
(docs/semantics.md §15; §4 for gconfig).
"""
from .framebuffer import ZMAX, ZMIN
from .geometry.fog import FogState
from .geometry.stack import MatrixState
from .raster.blend import LO_SRC, REPLACE
from .raster.depth import AF_ALWAYS, SF_ALWAYS, ZF_LEQUAL
from .raster.stencil import ST_KEEP

#: scrbox(3G) after SB_RESET: left/bottom greater than right/top
SCRBOX_EMPTY = (1 << 30, -(1 << 30), 1 << 30, -(1 << 30))


def _current_attribute(name, doc):
    """A current vertex attribute.  irisgl's per-vertex calls (n3f, c*, cpack,
    RGBcolor, t*) do not write it: they append an event to the window's
    batch (geometry/batch.py), and reading or writing the attribute first
    takes the newest value from those events (``VertexBatch.sync``)."""
    slot = "_" + name

    def get(self):
        b = self.events
        if b is not None and b.synced != len(b.ev):
            b.sync(self)
        return self.__dict__[slot]

    def put(self, value):
        b = self.events
        if b is not None and b.synced != len(b.ev):
            b.sync(self)
        self.__dict__[slot] = value
    return property(get, put, doc=doc)


class WindowState:
    """Everything a window remembers between calls (one graphics context)."""

    colour = _current_attribute("colour", "RGBA 0..255, or (index, 0, 0, 0)")
    normal = _current_attribute("normal", "n3f(3G): nx, ny, nz")
    texcoord = _current_attribute("texcoord", "t*(3G): s, t, r, q")
    last_was_normal = _current_attribute(
        "last_was_normal", "whether n3f came after the last colour call (lmcolor(3G))")
    colour_since_bind = _current_attribute(
        "colour_since_bind", "a colour call since the material was bound (lmcolor(3G))")

    def __init__(self, width, height):
        self.events = None             # the batch whose events may hold newer attributes
        # configuration requests, effective at gconfig()
        self.req_rgb = False
        self.req_double = False
        self.req_stencil = 0
        self.req_accum = 0
        # configuration in force
        self.rgb = False
        self.double = False
        # geometry subsystem
        self.matrices = MatrixState()
        self.viewport = (0, width - 1, 0, height - 1)
        self.scrmask = (0, width - 1, 0, height - 1)
        self.viewport_stack = []
        self.depth_range = (ZMIN, ZMAX)
        self.backface = False
        self.frontface = False
        self.gouraud = True
        self.subpixel = False
        self.concave = False
        self.nmode = 0                 # NAUTO
        # current vertex attributes
        self.colour = (0.0, 0.0, 0.0, 255.0)   # RGBA 0..255, or (index, 0, 0, 0)
        self.normal = (0.0, 0.0, 1.0)
        self.texcoord = (0.0, 0.0, 0.0, 1.0)    # t*(): s, t, r, q
        self.last_was_normal = False
        self.colour_since_bind = False
        # lighting bindings: target -> index; lights: slot -> LightBinding
        self.material = 0
        self.backmaterial = 0
        self.lmodel = 0
        self.lights = {}
        self.lmcolor = 0               # LMC_COLOR
        self.mat_override = {}         # material properties set through lmcolor
        # raster subsystem
        self.zbuffer = False
        self.zfunc = ZF_LEQUAL
        self.zwritemask = 0xFFFFFF
        self.zdraw = False                         # zdraw(3G): colour into z
        self.zsource = 0                           # zsource(3G): ZSRC_DEPTH
        self.front_enabled = True
        self.back_enabled = False
        # stencil(3G): enable, ref, func, mask, fail, pass, zpass; swritemask
        self.stencil_on = False
        self.stencil = (0, SF_ALWAYS, 0xFF, ST_KEEP, ST_KEEP, ST_KEEP)   # ref, func, mask, ops
        self.swritemask = 0xFF
        # colour writemask: wmpack/RGBwritemask (RGB) or writemask (cmode)
        self.cmask = 0xFFFFFFFF
        self.blendfunc = REPLACE                   # (BF_ONE, BF_ZERO)
        self.afunc = (0, AF_ALWAYS)                # ref, function
        self.logicop = LO_SRC
        self.dither = True
        self.pattern = 0                           # setpattern index; 0 = solid
        self.zoom = (1.0, 1.0)                     # rectzoom
        # texture mapping: bound texture / environment, texgen per coordinate
        self.texture = 0
        self.tev = 0
        self.texgen = {}                           # coord -> (mode, plane (4,), enabled)
        # graphics position (move/draw) and character position
        self.gpos = None
        # cmov(3G): window x, y and z of the character position, and whether
        # strings may be drawn there ([S] start: pixel (0, 0), z 0, valid)
        self.cpos = (0.0, 0.0)
        self.cpos_z = 0.0
        self.cpos_valid = True
        self.font = 0                              # font(3G) selection
        # lines, points and polygon modes (docs/drawing-2d-and-lines.md)
        self.linewidth = 1.0                       # linewidth/linewidthf, as given
        self.linestyle = 0                         # setlinestyle index (0 = 0xFFFF)
        self.lsrepeat = 1                          # lsrepeat factor 1..255
        self.resetls = True                        # resetls(TRUE): pattern restarts per line
        self.lsbackup = False                      # lsbackup(TRUE): last 2 pixels always on
        self.ls_phase = 0                          # pattern counter carried when resetls FALSE
        self.linesmooth = 0                        # SML_OFF
        self.pntsize = 1.0                         # pntsize/pntsizef, as given
        self.pntsmooth = 0                         # SMP_OFF
        self.polysmooth = 0                        # PYSM_OFF
        self.polymode = 1                          # PYM_FILL
        # clipplane(3G): per index (eye-space plane or None, enabled); the
        # enabled defined planes as a (K, 4) array (None when there are none)
        self.clipplanes = [(None, False)] * 6
        self.user_planes = None
        # fogvertex(3G) (geometry/fog.py) and scrbox(3G) (left, right, bottom, top)
        self.fog = FogState()
        self.scrbox_mode = 0                       # SB_RESET
        self.scrbox = SCRBOX_EMPTY
        # drawmode(3G) and the other framebuffers (framebuffer/layers.py):
        # the fields of layers.SWAPPED of the drawmodes not current
        self.drawmode = 0x10                       # NORMALDRAW
        self.saved = {}
        self.req_overlay = 2                       # overlay(3G), at gconfig
        self.req_underlay = 0                      # underlay(3G), at gconfig
        self.req_multimap = False                  # multimap/onemap(3G), at gconfig
        self.multimap = False
        # depthcue(3G): lshaderange (low, high, znear, zfar), lRGBrange
        # (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar)
        self.depthcue = False
        self.shaderange = (0, 7, ZMIN, ZMAX)
        self.rgbrange = (0, 0, 0, 255, 255, 255, ZMIN, ZMAX)
