"""Numeric constants of SGI IRIS GL.

This module collects every symbolic constant of the three public IRIS GL
headers as plain Python integers (or floats where the C header uses a float
literal):

* ``<gl/gl.h>`` (whose constant part is ``<gl/glconsts.h>``),
* ``<gl/get.h>`` (values returned by the ``get*`` queries),
* ``<gl/device.h>`` (device numbers for the event queue).

Names keep their exact C spelling and case.  Values follow the SGI IRIX 4/5
headers (the man pages quote the same values where they give them).  Function-like macros (``ISBUTTON()``...), include guards
(``GLDEF``, ``GETDEF``, ``DEVICEDEF``), the C ``NULL`` and type names are not
constants and are left out.

The module has no imports and no logic, so ``from irisgl.constants import *``
is safe.
"""

# ---------------------------------------------------------------------------
# gl.h: booleans
# ---------------------------------------------------------------------------
FALSE = 0
TRUE = 1

# ---------------------------------------------------------------------------
# gl.h: hardware/software limits
# ---------------------------------------------------------------------------
ATTRIBSTACKDEPTH = 10
VPSTACKDEPTH = 8
MATRIXSTACKDEPTH = 32
NAMESTACKDEPTH = 1025
MAXLIGHTS = 8
MAXRESTRICTIONS = 4

# gl.h (Release 2.3 header): font offset array sizes
MAXFONTNC = 256
MINFONTNC = 128

# ---------------------------------------------------------------------------
# gl.h: special object tags
# ---------------------------------------------------------------------------
STARTTAG = -2
ENDTAG = -3

# ---------------------------------------------------------------------------
# gl.h: colour names of the default colour map (greset/ginit)
# ---------------------------------------------------------------------------
BLACK = 0
RED = 1
GREEN = 2
YELLOW = 3
BLUE = 4
MAGENTA = 5
CYAN = 6
WHITE = 7

# ---------------------------------------------------------------------------
# gl.h: pop-up planes colours
# ---------------------------------------------------------------------------
PUP_CLEAR = 0
PUP_COLOR = 1
PUP_BLACK = 2
PUP_WHITE = 3
PUP_CURSOR = PUP_COLOR  # obsolete alias (= 1)

# ---------------------------------------------------------------------------
# gl.h: drawmode() / mswapbuffers() buffer selectors
# ---------------------------------------------------------------------------
NORMALDRAW = 0x010
PUPDRAW = 0x020
OVERDRAW = 0x040
UNDERDRAW = 0x080
CURSORDRAW = 0x100
DUALDRAW = 0x200
GANGDRAW = 0x200
HYPER0 = 0x10000
HYPER1 = 0x20000
HYPER2 = 0x40000

# ---------------------------------------------------------------------------
# gl.h: defpattern() sizes and mask lengths (in shorts)
# ---------------------------------------------------------------------------
PATTERN_16 = 16
PATTERN_32 = 32
PATTERN_64 = 64
PATTERN_16_SIZE = 16
PATTERN_32_SIZE = 64
PATTERN_64_SIZE = 256

# ---------------------------------------------------------------------------
# gl.h: readsource()
# ---------------------------------------------------------------------------
SRC_NULL = -1
SRC_AUTO = 0
SRC_FRONT = 1
SRC_FRONTLEFT = 1
SRC_BACK = 2
SRC_BACKLEFT = 2
SRC_ZBUFFER = 3
SRC_PUP = 4
SRC_OVER = 5
SRC_UNDER = 6
SRC_FRAMEGRABBER = 7
SRC_FRONTRIGHT = 8
SRC_BACKRIGHT = 9
SRC_ILBUFFER_1 = 1000
SRC_ILBUFFER_2 = 1001
SRC_ILBUFFER_3 = 1002
SRC_ILBUFFER_4 = 1003
SRC_ILBUFFER_5 = 1004
SRC_ILBUFFER_6 = 1005
SRC_ILBUFFER_7 = 1006
SRC_ILBUFFER_8 = 1007
SRC_ILBUFFER_9 = 1008
SRC_ILBUFFER_10 = 1009
SRC_ILBUFFER_11 = 1010
SRC_ILBUFFER_12 = 1011
SRC_ILBUFFER_13 = 1012
SRC_ILBUFFER_14 = 1013
SRC_ILBUFFER_15 = 1014
SRC_ILBUFFER_16 = 1015

# ---------------------------------------------------------------------------
# gl.h: minmax() and hgram()
# ---------------------------------------------------------------------------
MINMAX_ENABLE = 0
MINMAX_DISABLE = 1
MINMAX_INIT = 2
HIST_ENABLE = 0
HIST_DISABLE = 1
HIST_CLEAR = 2

# ---------------------------------------------------------------------------
# gl.h: readcomponent()
# ---------------------------------------------------------------------------
RC_ALPHA = 0
RC_BLUE = 1
RC_GREEN = 2
RC_RED = 3
RC_ABGR = 4

# ---------------------------------------------------------------------------
# gl.h: blendfunction() factors
# ---------------------------------------------------------------------------
BF_ZERO = 0
BF_ONE = 1
BF_DC = 2
BF_SC = 2
BF_MDC = 3
BF_MSC = 3
BF_SA = 4
BF_MSA = 5
BF_DA = 6
BF_MDA = 7
BF_MIN_SA_MDA = 8
BF_CA = 9
BF_MCA = 10
BF_CC = 11
BF_MCC = 12
BF_MIN = 13
BF_MAX = 14

# ---------------------------------------------------------------------------
# gl.h: afunction()
# ---------------------------------------------------------------------------
AF_NEVER = 0
AF_LESS = 1
AF_EQUAL = 2
AF_LEQUAL = 3
AF_GREATER = 4
AF_NOTEQUAL = 5
AF_GEQUAL = 6
AF_ALWAYS = 7

# ---------------------------------------------------------------------------
# gl.h: zfunction()
# ---------------------------------------------------------------------------
ZF_NEVER = 0
ZF_LESS = 1
ZF_EQUAL = 2
ZF_LEQUAL = 3
ZF_GREATER = 4
ZF_NOTEQUAL = 5
ZF_GEQUAL = 6
ZF_ALWAYS = 7

# ---------------------------------------------------------------------------
# gl.h: zsource()
# ---------------------------------------------------------------------------
ZSRC_DEPTH = 0
ZSRC_COLOR = 1

# ---------------------------------------------------------------------------
# gl.h: pntsmooth(), linesmooth(), polysmooth()
# ---------------------------------------------------------------------------
SMP_OFF = 0x0
SMP_ON = 0x1
SMP_SMOOTHER = 0x2

SML_OFF = 0x0
SML_ON = 0x1
SML_SMOOTHER = 0x2
SML_END_CORRECT = 0x4

PYSM_OFF = 0
PYSM_ON = 1
PYSM_SHRINK = 2

# ---------------------------------------------------------------------------
# gl.h: multisampling: msalpha(), mssample(), mspattern()
# ---------------------------------------------------------------------------
MSA_MASK = 0x0
MSA_MASK_ONE = 0x1
MSA_ALPHA = 0x2

MSS_POINT = 0x0
MSS_AREA = 0x1
MSS_CENTER_POINT = 0x2

MSP_DEFAULT = 0x0
MSP_2PASS_0 = 0x1
MSP_2PASS_1 = 0x2
MSP_4PASS_0 = 0x3
MSP_4PASS_1 = 0x4
MSP_4PASS_2 = 0x5
MSP_4PASS_3 = 0x6

# ---------------------------------------------------------------------------
# gl.h: dither()
# ---------------------------------------------------------------------------
DT_OFF = 0
DT_ON = 1

# ---------------------------------------------------------------------------
# gl.h: setpup() entry modes
# ---------------------------------------------------------------------------
PUP_NONE = 0
PUP_GREY = 0x1
PUP_BOX = 0x2
PUP_CHECK = 0x4

# ---------------------------------------------------------------------------
# gl.h: glcompat() modes and values
# ---------------------------------------------------------------------------
GLC_OLDPOLYGON = 0
GLC_ZRANGEMAP = 1
GLC_MQUEUERATE = 2
GLC_SOFTATTACH = 3
GLC_MANAGEBG = 4
GLC_SLOWMAPCOLORS = 5
GLC_INPUTCHANGEBUG = 6
GLC_NOBORDERBUG = 7
GLC_SET_VSYNC = 8
GLC_GET_VSYNC = 9
GLC_VSYNC_SLEEP = 10
GLC_FORCECIMAP = 11
GLC_TABLETSCALE = 12
GLC_ILCMD = 1008
GLC_IL_READCOMPONENT = 0
GLC_IL_RECTZOOMOFF = 1
GLC_IL_CONVOLVE = 2
GLC_IL_LRECTPROC = 3
GLC_IL_HISTOGRAM = 4
GLC_IL_GETHISTOGRAM = 5
GLC_IL_MINMAX = 6
GLC_IL_GETMINMAX = 7
GLC_IL_PIXELMAP = 8
GLC_IL_PIXELTRANSFER = 9
GLC_IL_ILBUFFER = 0xa
GLC_IL_ILDRAW = 0xb
GLC_IL_SUBTEXLOAD = 0xc
GLC_IL_LEFTBUFFER = 0xd
GLC_IL_RIGHTBUFFER = 0xe
GLC_IL_STEREOBUFFER = 0xf
GLC_IL_MONOBUFFER = 0x10
GLC_IL_FBSUBTEXLOAD = 0x11
GLC_IL_ISTEXLOADED = 0x12
GLC_IL_BLENDCOLOR = 0x13
GLC_COMPATRATE = 15
GLC_CMPRESS = 1

# ---------------------------------------------------------------------------
# gl.h: curstype() cursor types
# ---------------------------------------------------------------------------
C16X1 = 0
C16X2 = 1
C32X1 = 2
C32X2 = 3
CCROSS = 4

# ---------------------------------------------------------------------------
# gl.h: shademodel()
# ---------------------------------------------------------------------------
FLAT = 0
GOURAUD = 1

# ---------------------------------------------------------------------------
# gl.h: logicop()
# ---------------------------------------------------------------------------
LO_ZERO = 0x0
LO_AND = 0x1
LO_ANDR = 0x2
LO_SRC = 0x3
LO_ANDI = 0x4
LO_DST = 0x5
LO_XOR = 0x6
LO_OR = 0x7
LO_NOR = 0x8
LO_XNOR = 0x9
LO_NDST = 0xa
LO_ORR = 0xb
LO_NSRC = 0xc
LO_ORI = 0xd
LO_NAND = 0xe
LO_ONE = 0xf

# ---------------------------------------------------------------------------
# gl.h: scrnselect()
# ---------------------------------------------------------------------------
INFOCUSSCRN = -2

# ---------------------------------------------------------------------------
# gl.h: stencil() operations and functions
# ---------------------------------------------------------------------------
ST_KEEP = 0
ST_ZERO = 1
ST_REPLACE = 2
ST_INCR = 3
ST_DECR = 4
ST_INVERT = 5

SF_NEVER = 0
SF_LESS = 1
SF_EQUAL = 2
SF_LEQUAL = 3
SF_GREATER = 4
SF_NOTEQUAL = 5
SF_GEQUAL = 6
SF_ALWAYS = 7

# ---------------------------------------------------------------------------
# gl.h: scrsubdivide()
# ---------------------------------------------------------------------------
SS_OFF = 0
SS_DEPTH = 1

# ---------------------------------------------------------------------------
# gl.h: polymode()
# ---------------------------------------------------------------------------
PYM_FILL = 1
PYM_POINT = 2
PYM_LINE = 3
PYM_HOLLOW = 4
PYM_LINE_FAST = 5

# ---------------------------------------------------------------------------
# gl.h: fogvertex()
# ---------------------------------------------------------------------------
FG_OFF = 0
FG_ON = 1
FG_DEFINE = 2
FG_VTX_EXP = 2
FG_VTX_LIN = 3
FG_PIX_EXP = 4
FG_PIX_LIN = 5
FG_VTX_EXP2 = 6
FG_PIX_EXP2 = 7

# ---------------------------------------------------------------------------
# gl.h: pixmode() tokens
# ---------------------------------------------------------------------------
PM_SHIFT = 0
PM_EXPAND = 1
PM_C0 = 2
PM_C1 = 3
PM_ADD24 = 4
PM_SIZE = 5
PM_OFFSET = 6
PM_STRIDE = 7
PM_TTOB = 8
PM_RTOL = 9
PM_ZDATA = 10
PM_WARP = 11
PM_RDX = 12
PM_RDY = 13
PM_CDX = 14
PM_CDY = 15
PM_XSTART = 16
PM_YSTART = 17
PM_VO1 = 1000

# gl.h: pixmode() float-path formats/types (same numbers as PM_WARP.. above)
PM_INPUT_FORMAT = 11
PM_INPUT_TYPE = 12
PM_OUTPUT_FORMAT = 13
PM_OUTPUT_TYPE = 14

PM_ABGR = 0
PM_BGR = 1
PM_RGBA = 2
PM_RGB = 3
PM_LUMINANCE = 4
PM_LUMINANCEA = 5
PM_ALPHA = 6
PM_COLOR_INDEX = 7
PM_STENCIL_INDEX = 8
PM_DEPTH = 9
PM_RED = 10
PM_GREEN = 11
PM_BLUE = 12

PM_BITMAP = 0
PM_BYTE = 1
PM_UNSIGNED_BYTE = 2
PM_SHORT_12 = 3
PM_UNSIGNED_SHORT_12 = 4
PM_SHORT = 5
PM_UNSIGNED_SHORT = 6
PM_INT = 7
PM_UNSIGNED_INT = 8
PM_FLOAT = 9

# ---------------------------------------------------------------------------
# gl.h: convolve()
# ---------------------------------------------------------------------------
CV_OFF = 0
CV_GENERAL = 1
CV_SEPARABLE = 2
CV_REDUCE = 1

# ---------------------------------------------------------------------------
# gl.h: pixelmap()
# ---------------------------------------------------------------------------
MAP_I_TO_I = 0
MAP_I_TO_R = 1
MAP_I_TO_G = 2
MAP_I_TO_B = 3
MAP_I_TO_A = 4
MAP_R_TO_R = 5
MAP_G_TO_G = 6
MAP_B_TO_B = 7
MAP_A_TO_A = 8

# ---------------------------------------------------------------------------
# gl.h: pixeltransfer()
# ---------------------------------------------------------------------------
PT_MAP_COLOR = 0
PT_MAP_DISABLE = 0
PT_MAP_CLAMP = 1
PT_MAP_ENABLE = 2

PT_RED_SCALE = 1
PT_RED_BIAS = 2
PT_GREEN_SCALE = 3
PT_GREEN_BIAS = 4
PT_BLUE_SCALE = 5
PT_BLUE_BIAS = 6
PT_ALPHA_SCALE = 7
PT_ALPHA_BIAS = 8

# ---------------------------------------------------------------------------
# gl.h: nmode()
# ---------------------------------------------------------------------------
NAUTO = 0
NNORMALIZE = 1

# ---------------------------------------------------------------------------
# gl.h: acbuf()
# ---------------------------------------------------------------------------
AC_CLEAR = 0
AC_ACCUMULATE = 1
AC_CLEAR_ACCUMULATE = 2
AC_RETURN = 3
AC_MULT = 4
AC_ADD = 5

# ---------------------------------------------------------------------------
# gl.h: clipplane()
# ---------------------------------------------------------------------------
CP_OFF = 0
CP_ON = 1
CP_DEFINE = 2

# ---------------------------------------------------------------------------
# gl.h: scrbox()
# ---------------------------------------------------------------------------
SB_RESET = 0
SB_TRACK = 1
SB_HOLD = 2

# ---------------------------------------------------------------------------
# gl.h: readdisplay() flags
# ---------------------------------------------------------------------------
RD_FREEZE = 0x00000001
RD_ALPHAONE = 0x00000002
RD_IGNORE_UNDERLAY = 0x00000004
RD_IGNORE_OVERLAY = 0x00000008
RD_IGNORE_PUP = 0x00000010
RD_OFFSCREEN = 0x00000020

# ---------------------------------------------------------------------------
# gl.h: getgconfig() inquiries
# ---------------------------------------------------------------------------
GC_BITS_CMODE = 0
GC_BITS_RED = 1
GC_BITS_GREEN = 2
GC_BITS_BLUE = 3
GC_BITS_ALPHA = 4
GC_BITS_ZBUFFER = 5
GC_ZMIN = 6
GC_ZMAX = 7
GC_BITS_STENCIL = 8
GC_BITS_ACBUF = 9
GC_MS_SAMPLES = 10
GC_BITS_MS_ZBUFFER = 11
GC_MS_ZMIN = 12
GC_MS_ZMAX = 13
GC_BITS_MS_STENCIL = 14
GC_STEREO = 15
GC_DOUBLE = 16

# ---------------------------------------------------------------------------
# gl.h: getgdesc() inquiries (numbers 20, 29, 32, 34, 38, 45-47, 49, 56,
# 59, 60, 65 and 75 are unused)
# ---------------------------------------------------------------------------
GD_XPMAX = 0
GD_YPMAX = 1
GD_XMMAX = 2
GD_YMMAX = 3
GD_ZMIN = 4
GD_ZMAX = 5
GD_BITS_NORM_SNG_RED = 6
GD_BITS_NORM_SNG_GREEN = 7
GD_BITS_NORM_SNG_BLUE = 8
GD_BITS_NORM_DBL_RED = 9
GD_BITS_NORM_DBL_GREEN = 10
GD_BITS_NORM_DBL_BLUE = 11
GD_BITS_NORM_SNG_CMODE = 12
GD_BITS_NORM_DBL_CMODE = 13
GD_BITS_NORM_SNG_MMAP = 14
GD_BITS_NORM_DBL_MMAP = 15
GD_BITS_NORM_ZBUFFER = 16
GD_BITS_OVER_SNG_CMODE = 17
GD_BITS_UNDR_SNG_CMODE = 18
GD_BITS_PUP_SNG_CMODE = 19
GD_BITS_NORM_SNG_ALPHA = 21
GD_BITS_NORM_DBL_ALPHA = 22
GD_BITS_CURSOR = 23
GD_OVERUNDER_SHARED = 24
GD_BLEND = 25
GD_CIFRACT = 26
GD_CROSSHAIR_CINDEX = 27
GD_DITHER = 28
GD_LINESMOOTH_CMODE = 30
GD_LINESMOOTH_RGB = 31
GD_LOGICOP = 33
GD_NSCRNS = 35
GD_NURBS_ORDER = 36
GD_NBLINKS = 37
GD_NVERTEX_POLY = 39
GD_PATSIZE_64 = 40
GD_PNTSMOOTH_CMODE = 41
GD_PNTSMOOTH_RGB = 42
GD_PUP_TO_OVERUNDER = 43
GD_READSOURCE = 44
GD_READSOURCE_ZBUFFER = 48
GD_STEREO = 50
GD_SUBPIXEL_LINE = 51
GD_SUBPIXEL_PNT = 52
GD_SUBPIXEL_POLY = 53
GD_TRIMCURVE_ORDER = 54
GD_WSYS = 55
GD_ZDRAW_GEOM = 57
GD_ZDRAW_PIXELS = 58
GD_SCRNTYPE = 61
GD_TEXTPORT = 62
GD_NMMAPS = 63
GD_FRAMEGRABBER = 64
GD_TIMERHZ = 66
GD_DBBOX = 67
GD_AFUNCTION = 68
GD_ALPHA_OVERUNDER = 69
GD_BITS_ACBUF = 70
GD_BITS_ACBUF_HW = 71
GD_BITS_STENCIL = 72
GD_CLIPPLANES = 73
GD_FOGVERTEX = 74
GD_LIGHTING_TWOSIDE = 76
GD_POLYMODE = 77
GD_POLYSMOOTH = 78
GD_SCRBOX = 79
GD_TEXTURE = 80
GD_FOGPIXEL = 81
GD_TEXTURE_PERSP = 82
GD_MUXPIPES = 83
GD_MULTISAMPLE = 84
GD_TEXTURE_3D = 85
GD_TEXTURE_LUT = 86
GD_TEXTURE_SHARP = 87
GD_TEXTURE_DETAIL = 88
GD_STEREO_IN_WINDOW = 89
GD_BLENDCOLOR = 90
GD_LIGHTING_SPOTLIGHT = 91
GD_LIGHTING_ATT2 = 92
GD_AFUNCTION_MODES = 93
# later IRIX 6 headers only (seen in the IGL copy of gl.h)
GD_TEXTURE_MEMORY_SIZE = 94
GD_IS_IGLOO = 95

# gl.h: getgdesc() return values
GD_NOLIMIT = -2
GD_WSYS_NONE = 0
GD_WSYS_4S = 1
GD_SCRNTYPE_WM = 0
GD_SCRNTYPE_NOWM = 1

# ---------------------------------------------------------------------------
# gl.h: NURBS rendering properties (setnurbsproperty)
# ---------------------------------------------------------------------------
N_PIXEL_TOLERANCE = 1
N_CULLING = 2
N_DISPLAY = 3
N_ERRORCHECKING = 4
N_SUBDIVISIONS = 5
N_S_STEPS = 6
N_T_STEPS = 7
N_TILES = 8
N_TMP1 = 9
N_TMP2 = 10
N_TMP3 = 11
N_TMP4 = 12
N_TMP5 = 13
N_TMP6 = 14

# gl.h: N_DISPLAY values (float literals in C)
N_FILL = 1.0
N_OUTLINE_POLY = 2.0
N_OUTLINE_PATCH = 5.0
N_ISOLINE_S = 12.0

# gl.h: NURBS curve/surface data types: (type << 6) | (ncoords << 2) | rational
N_ST = 0x8
N_STW = 0xd
N_XYZ = 0x4c
N_XYZW = 0x51
N_TEX = 0x88
N_TEXW = 0x8d
N_RGBA = 0xd0
N_RGBAW = 0xd5

N_P2D = 0x8
N_P2DR = 0xd
N_V3D = 0x4c
N_V3DR = 0x51
N_T2D = 0x88
N_T2DR = 0x8d
N_C4D = 0xd0
N_C4DR = 0xd5

# ---------------------------------------------------------------------------
# gl.h: lighting: terminator and matrix modes
# ---------------------------------------------------------------------------
LMNULL = 0.0

MSINGLE = 0
MPROJECTION = 1
MVIEWING = 2
MTEXTURE = 3

# gl.h: lmdef() material properties
DEFMATERIAL = 0
EMISSION = 1
AMBIENT = 2
DIFFUSE = 3
SPECULAR = 4
SHININESS = 5
COLORINDEXES = 6
ALPHA = 7

# gl.h: lmdef() light properties
DEFLIGHT = 100
LCOLOR = 101
POSITION = 102
SPOTDIRECTION = 103
SPOTLIGHT = 104

# gl.h: lmdef() lighting-model properties
DEFLMODEL = 200
LOCALVIEWER = 201
ATTENUATION = 202
ATTENUATION2 = 203
TWOSIDE = 204

# gl.h: lmbind() targets
MATERIAL = 1000
BACKMATERIAL = 1001
LIGHT0 = 1100
LIGHT1 = 1101
LIGHT2 = 1102
LIGHT3 = 1103
LIGHT4 = 1104
LIGHT5 = 1105
LIGHT6 = 1106
LIGHT7 = 1107
LMODEL = 1200

# gl.h: lmcolor() modes
LMC_COLOR = 0
LMC_EMISSION = 1
LMC_AMBIENT = 2
LMC_DIFFUSE = 3
LMC_SPECULAR = 4
LMC_AD = 5
LMC_NULL = 6

# ---------------------------------------------------------------------------
# gl.h: texdef2d()/texdef3d() property tokens
# ---------------------------------------------------------------------------
TX_NULL = 0x000
TX_MINFILTER = 0x100
TX_MAGFILTER = 0x200
TX_MAGFILTER_COLOR = 0xa00
TX_MAGFILTER_ALPHA = 0xb00
TX_WRAP = 0x300
TX_WRAP_S = 0x310
TX_WRAP_T = 0x320
TX_WRAP_R = 0x330
TX_TILE = 0x400
TX_BORDER = 0x500
TX_DETAIL = 0xe00
TX_FAST_DEFINE = 0x0f00
TX_NOCOPY = TX_FAST_DEFINE  # obsolete alias (= 0xf00)
TX_FRAMEBUFFER_SRC = 0x1000
TX_SUBTEXLOAD = 0x2000
TX_FORMATTED_16bit_64x64 = 0x2000
TX_FORMATTED_ABGR_8_128x128 = 0x2010
TX_CONTROL_POINT = 0xc00
TX_CONTROL_CLAMP = 0xd00
TX_MIPMAP_FILTER_KERNEL = 0x900

# gl.h: texture external formats
TX_EXTERNAL_FORMAT = 0x700
TX_PACK_8 = 0x710
TX_PACK_16 = 0x720
TX_NOPACK_12 = 0x730
TX_PIXMODE = 0x3000
TX_BICUBIC_FILTER = 0x4000

# gl.h: texture internal formats (TX_INTERNAL_FORMAT choices)
TX_INTERNAL_FORMAT = 0x600
TX_I_12 = 0x610
TX_I_12A_4 = 0x610
TX_I_8 = 0x620
TX_IA_8 = 0x620
TX_RGB_5 = 0x630
TX_RGBA_4 = 0x640
TX_IA_12 = 0x650
TX_RGBA_8 = 0x660
TX_RGB_8 = 0x660
TX_RGBA_12 = 0x670
TX_RGB_12 = 0x680
TX_I_16 = 0x690

# gl.h: texture filters
TX_POINT = 0x110
TX_MIPMAP = 0x120
TX_MIPMAP_POINT = 0x121
TX_MIPMAP_LINEAR = 0x122
TX_MIPMAP_BILINEAR = 0x123
TX_MIPMAP_TRILINEAR = 0x124
TX_BILINEAR = 0x220
TX_BICUBIC = 0x230
TX_SHARPEN = 0x240
TX_MODULATE_DETAIL = 0x250
TX_ADD_DETAIL = 0x260
TX_TRILINEAR = 0x270
TX_MIPMAP_QUADLINEAR = 0x280
TX_BICUBIC_GEQUAL = 0x290
TX_BICUBIC_LEQUAL = 0x2a0
TX_BILINEAR_GEQUAL = 0x2b0
TX_BILINEAR_LEQUAL = 0x2c0

# gl.h: texture wrap modes
TX_REPEAT = 0x301
TX_CLAMP = 0x302
TX_SELECT = 0x303

# gl.h: texbind() targets
TX_TEXTURE_0 = 0
TX_TEXTURE_DETAIL = 1
TX_TEXTURE_IDLE = 2

# gl.h: tevdef() tokens
TV_NULL = 0x000
TV_MODULATE = 0x101
TV_BLEND = 0x102
TV_DECAL = 0x103
TV_SHADOW = 0x104
TV_ALPHA = 0x105
TV_COLOR = 0x200
TV_COMPONENT_SELECT = 0x300
TV_I_GETS_R = 0x310
TV_I_GETS_G = 0x320
TV_I_GETS_B = 0x330
TV_I_GETS_A = 0x340
TV_IA_GETS_RG = 0x350
TV_IA_GETS_BA = 0x360
TV_I_GETS_I = 0x370

# gl.h: tlutdef()/tlutbind()
TL_NULL = 0x0
TL_TLUT_0 = 0

# gl.h: tevbind() targets
TV_ENV0 = 0

# gl.h: texgen() coordinates and modes
TX_S = 0
TX_T = 1
TX_R = 2
TX_Q = 3
TG_OFF = 0
TG_ON = 1
TG_CONTOUR = 2
TG_LINEAR = 3
TG_SPHEREMAP = 4
TG_REFRACTMAP = 5

# ---------------------------------------------------------------------------
# gl.h: lcharstr()/lstrwidth() character types
# ---------------------------------------------------------------------------
STR_B = 0x000
STR_2B = 0x001
STR_3B = 0x010
STR_4B = 0x011
STR_16 = 0x100
STR_32 = 0x101

# ---------------------------------------------------------------------------
# gl.h: Distributed GL (dglopen) connection types
# ---------------------------------------------------------------------------
DGLSINK = 0
DGLLOCAL = 1
DGLTSOCKET = 2
DGL4DDN = 3

# ---------------------------------------------------------------------------
# gl.h: obsolete error classes
# ---------------------------------------------------------------------------
FATAL = 1
WARNING = 2
ASK_CONT = 3
ASK_RESTART = 4

# ---------------------------------------------------------------------------
# gl.h: obsolete screen limits (the Release 2.3 gl.h had 1023 x 767; the
# 4D headers and the man pages use the high-resolution 1279 x 1023)
# ---------------------------------------------------------------------------
XMAXSCREEN = 1279
YMAXSCREEN = 1023
XMAXMEDIUM = 1023
YMAXMEDIUM = 767
XMAX170 = 645
YMAX170 = 484
XMAXPAL = 779
YMAXPAL = 574

# ---------------------------------------------------------------------------
# get.h: getbuffer() bits
# ---------------------------------------------------------------------------
BCKBUFFER = 0x1
FRNTBUFFER = 0x2
DRAWZBUFFER = 0x4
NOBUFFER = 0x0    # obsolete
BOTHBUFFERS = 0x3  # obsolete

# ---------------------------------------------------------------------------
# get.h: getdisplaymode() results
# ---------------------------------------------------------------------------
DMRGB = 0
DMSINGLE = 1
DMDOUBLE = 2
DMINTENSITYSINGLE = 3  # obsolete
DMINTENSITYDOUBLE = 4  # obsolete
DMRGBDOUBLE = 5

# ---------------------------------------------------------------------------
# get.h: getmonitor()/setmonitor() video formats
# ---------------------------------------------------------------------------
HZ30 = 0
HZ60 = 1
NTSC = 2
HDTV = 3
VGA = 4
IRIS3K = 5
PR60 = 6
PAL = 9
HZ30_SG = 11
A343 = 14
STR_RECT = 15
VOF0 = 16
VOF1 = 17
VOF2 = 18
VOF3 = 19
SGI0 = 20
SGI1 = 21
SGI2 = 22
HZ72 = 23
HZ50 = 24
HZ76 = 25
HZ70 = 26
STR_BOT = 27
STR_TOP = 28
PRESENTER = 29
HZ48 = 30
SGI_VIDEO_FORMAT_OTHER = 999

# get.h: obsolete monitor codes
MONSPECIAL = 0x20
MONA = 5
MONB = 6
MONC = 7
MOND = 8
MON_ALL = 12
MON_GEN_ALL = 13

# ---------------------------------------------------------------------------
# get.h: getvideo(GL_VIDEO_REG) bits
# ---------------------------------------------------------------------------
GL_VIDEO_REG = 0x00800000
GLV_GENLOCK = 0x00000001
GLV_UNBLANK = 0x00000002
GLV_SRED = 0x00000004
GLV_SGREEN = 0x00000008
GLV_SBLUE = 0x00000010
GLV_SALPHA = 0x00000020
GLV_TTLGENLOCK = 0x00000080
GLV_TTLSYNC = GLV_TTLGENLOCK  # obsolete alias (= 0x80)
GLV_GREENGENLOCK = 0x0000100

# ---------------------------------------------------------------------------
# get.h: gethitcode() clipping-plane bits
# ---------------------------------------------------------------------------
LEFTPLANE = 0x0001
RIGHTPLANE = 0x0002
BOTTOMPLANE = 0x0004
TOPPLANE = 0x0008
NEARPLANE = 0x0010
FARPLANE = 0x0020

# ---------------------------------------------------------------------------
# get.h: obsolete getmap() results
# ---------------------------------------------------------------------------
CMAPMULTI = 0
CMAPONE = 1

# ---------------------------------------------------------------------------
# device.h: device-number space (IRIX 4/5 header; the Release 2.3 header had
# BUTCOUNT 172, VALCOUNT 20 and a misspelt XKBBDCOUNT 28)
# ---------------------------------------------------------------------------
NULLDEV = 0
BUTOFFSET = 1
VALOFFSET = 256
PSEUDOFFSET = 512
TIMOFFSET = 515
XKBDOFFSET = 143
BUT2OFFSET = 3840
USERBUTOFFSET = 4096
USERVALOFFSET = 12288
USERPSEUDOFFSET = 16384
BUTCOUNT = 255
VALCOUNT = 256
TIMCOUNT = 4
XKBDCOUNT = 28
MAXSGIDEVICE = 20000

# device.h (Release 2.3 header): input/output channel devices
INOFFSET = 1024
OUTOFFSET = 1033
INCOUNT = 8
OUTCOUNT = 8

# ---------------------------------------------------------------------------
# device.h: raw buttons, BUTn = n + BUTOFFSET
# ---------------------------------------------------------------------------
BUT0 = 1
BUT1 = 2
BUT2 = 3
BUT3 = 4
BUT4 = 5
BUT5 = 6
BUT6 = 7
BUT7 = 8
BUT8 = 9
BUT9 = 10
BUT10 = 11
BUT11 = 12
BUT12 = 13
BUT13 = 14
BUT14 = 15
BUT15 = 16
BUT16 = 17
BUT17 = 18
BUT18 = 19
BUT19 = 20
BUT20 = 21
BUT21 = 22
BUT22 = 23
BUT23 = 24
BUT24 = 25
BUT25 = 26
BUT26 = 27
BUT27 = 28
BUT28 = 29
BUT29 = 30
BUT30 = 31
BUT31 = 32
BUT32 = 33
BUT33 = 34
BUT34 = 35
BUT35 = 36
BUT36 = 37
BUT37 = 38
BUT38 = 39
BUT39 = 40
BUT40 = 41
BUT41 = 42
BUT42 = 43
BUT43 = 44
BUT44 = 45
BUT45 = 46
BUT46 = 47
BUT47 = 48
BUT48 = 49
BUT49 = 50
BUT50 = 51
BUT51 = 52
BUT52 = 53
BUT53 = 54
BUT54 = 55
BUT55 = 56
BUT56 = 57
BUT57 = 58
BUT58 = 59
BUT59 = 60
BUT60 = 61
BUT61 = 62
BUT62 = 63
BUT63 = 64
BUT64 = 65
BUT65 = 66
BUT66 = 67
BUT67 = 68
BUT68 = 69
BUT69 = 70
BUT70 = 71
BUT71 = 72
BUT72 = 73
BUT73 = 74
BUT74 = 75
BUT75 = 76
BUT76 = 77
BUT77 = 78
BUT78 = 79
BUT79 = 80
BUT80 = 81
BUT81 = 82
BUT82 = 83
MAXKBDBUT = 83

BUT100 = 101
BUT101 = 102
BUT102 = 103
BUT103 = 104
BUT104 = 105
BUT105 = 106
BUT106 = 107
BUT107 = 108
BUT108 = 109
BUT109 = 110

BUT110 = 111
BUT111 = 112
BUT112 = 113
BUT113 = 114
BUT114 = 115
BUT115 = 116
BUT116 = 117
BUT117 = 118
BUT118 = 119
BUT119 = 120
BUT120 = 121
BUT121 = 122
BUT122 = 123
BUT123 = 124
BUT124 = 125
BUT125 = 126
BUT126 = 127
BUT127 = 128
BUT128 = 129
BUT129 = 130
BUT130 = 131
BUT131 = 132
BUT132 = 133
BUT133 = 134
BUT134 = 135
BUT135 = 136
BUT136 = 137
BUT137 = 138
BUT138 = 139
BUT139 = 140
BUT140 = 141
BUT141 = 142

BUT142 = 143
BUT143 = 144
BUT144 = 145
BUT145 = 146
BUT146 = 147
BUT147 = 148
BUT148 = 149
BUT149 = 150
BUT150 = 151
BUT151 = 152
BUT152 = 153
BUT153 = 154
BUT154 = 155
BUT155 = 156
BUT156 = 157
BUT157 = 158
BUT158 = 159
BUT159 = 160
BUT160 = 161
BUT161 = 162
BUT162 = 163
BUT163 = 164
BUT164 = 165
BUT165 = 166
BUT166 = 167
BUT167 = 168
BUT168 = 169
BUT169 = 170  # Release 2.3 header only; later headers reserve it

BUT181 = 182
BUT182 = 183
BUT183 = 184
BUT184 = 185
BUT185 = 186
BUT186 = 187
BUT187 = 188
BUT188 = 189
BUT189 = 190

# ---------------------------------------------------------------------------
# device.h: mouse, light pen and bitpad buttons
# ---------------------------------------------------------------------------
MOUSE1 = 101
MOUSE2 = 102
MOUSE3 = 103
LEFTMOUSE = 103
MIDDLEMOUSE = 102
RIGHTMOUSE = 101
MENUBUTTON = RIGHTMOUSE  # = 101, the button dopup() uses
LPENBUT = 104
BPAD0 = 105
BPAD1 = 106
BPAD2 = 107
BPAD3 = 108
LPENVALID = 109

# ---------------------------------------------------------------------------
# device.h: button box switches
# ---------------------------------------------------------------------------
SWBASE = 111
SW0 = 111
SW1 = 112
SW2 = 113
SW3 = 114
SW4 = 115
SW5 = 116
SW6 = 117
SW7 = 118
SW8 = 119
SW9 = 120
SW10 = 121
SW11 = 122
SW12 = 123
SW13 = 124
SW14 = 125
SW15 = 126
SW16 = 127
SW17 = 128
SW18 = 129
SW19 = 130
SW20 = 131
SW21 = 132
SW22 = 133
SW23 = 134
SW24 = 135
SW25 = 136
SW26 = 137
SW27 = 138
SW28 = 139
SW29 = 140
SW30 = 141
SW31 = 142

# ---------------------------------------------------------------------------
# device.h: Spaceball buttons
# ---------------------------------------------------------------------------
SBBASE = 182
SBPICK = 182
SBBUT1 = 183
SBBUT2 = 184
SBBUT3 = 185
SBBUT4 = 186
SBBUT5 = 187
SBBUT6 = 188
SBBUT7 = 189
SBBUT8 = 190

# ---------------------------------------------------------------------------
# device.h: standard keyboard, letters
# ---------------------------------------------------------------------------
AKEY = 11
BKEY = 36
CKEY = 28
DKEY = 18
EKEY = 17
FKEY = 19
GKEY = 26
HKEY = 27
IKEY = 40
JKEY = 34
KKEY = 35
LKEY = 42
MKEY = 44
NKEY = 37
OKEY = 41
PKEY = 48
QKEY = 10
RKEY = 24
SKEY = 12
TKEY = 25
UKEY = 33
VKEY = 29
WKEY = 16
XKEY = 21
YKEY = 32
ZKEY = 20

# device.h: standard keyboard, digits
ZEROKEY = 46
ONEKEY = 8
TWOKEY = 14
THREEKEY = 15
FOURKEY = 22
FIVEKEY = 23
SIXKEY = 30
SEVENKEY = 31
EIGHTKEY = 38
NINEKEY = 39

# device.h: standard keyboard, control and punctuation keys
BREAKKEY = 1
SETUPKEY = 2
CTRLKEY = 3
LEFTCTRLKEY = CTRLKEY  # = 3
CAPSLOCKKEY = 4
RIGHTSHIFTKEY = 5
LEFTSHIFTKEY = 6
ESCKEY = 7
TABKEY = 9
NOSCRLKEY = 13
RETKEY = 51
SPACEKEY = 83
LINEFEEDKEY = 60
BACKSPACEKEY = 61
DELKEY = 62
SEMICOLONKEY = 43
PERIODKEY = 52
COMMAKEY = 45
QUOTEKEY = 50
ACCENTGRAVEKEY = 55
MINUSKEY = 47
VIRGULEKEY = 53
BACKSLASHKEY = 57
EQUALKEY = 54
LEFTBRACKETKEY = 49
RIGHTBRACKETKEY = 56

# device.h: arrow keys
LEFTARROWKEY = 73
DOWNARROWKEY = 74
RIGHTARROWKEY = 80
UPARROWKEY = 81

# device.h: numeric keypad
PAD0 = 59
PAD1 = 58
PAD2 = 64
PAD3 = 65
PAD4 = 63
PAD5 = 69
PAD6 = 70
PAD7 = 67
PAD8 = 68
PAD9 = 75
PADPF1 = 72
PADPF2 = 71
PADPF3 = 79
PADPF4 = 78
PADPERIOD = 66
PADMINUS = 76
PADCOMMA = 77
PADENTER = 82

# ---------------------------------------------------------------------------
# device.h: extended keyboard
# ---------------------------------------------------------------------------
LEFTALTKEY = 143
RIGHTALTKEY = 144
RIGHTCTRLKEY = 145
F1KEY = 146
F2KEY = 147
F3KEY = 148
F4KEY = 149
F5KEY = 150
F6KEY = 151
F7KEY = 152
F8KEY = 153
F9KEY = 154
F10KEY = 155
F11KEY = 156
F12KEY = 157
PRINTSCREENKEY = 158
SCROLLLOCKKEY = 159
PAUSEKEY = 160
INSERTKEY = 161
HOMEKEY = 162
PAGEUPKEY = 163
ENDKEY = 164
PAGEDOWNKEY = 165
NUMLOCKKEY = 166
PADVIRGULEKEY = 167
PADASTERKEY = 168
PADPLUSKEY = 169

# ---------------------------------------------------------------------------
# device.h: valuators, n + VALOFFSET
# ---------------------------------------------------------------------------
SGIRESERVED = 256
DIAL0 = 257
DIAL1 = 258
DIAL2 = 259
DIAL3 = 260
DIAL4 = 261
DIAL5 = 262
DIAL6 = 263
DIAL7 = 264
DIAL8 = 265
MOUSEX = 266
MOUSEY = 267
LPENX = 268
LPENY = 269
BPADX = 270
BPADY = 271
CURSORX = 272
CURSORY = 273
GHOSTX = 274
GHOSTY = 275

# device.h: Spaceball valuators
SBTX = 276
SBTY = 277
SBTZ = 278
SBRX = 279
SBRY = 280
SBRZ = 281
SBPERIOD = 282

# ---------------------------------------------------------------------------
# device.h: timers, n + TIMOFFSET
# ---------------------------------------------------------------------------
TIMER0 = 515
TIMER1 = 516
TIMER2 = 517
TIMER3 = 518

# ---------------------------------------------------------------------------
# device.h: pseudo devices (keyboard, window-manager events)
# ---------------------------------------------------------------------------
KEYBD = 513
RAWKEYBD = 514
VALMARK = 523
GERROR = 524
REDRAW = 528
WMSEND = 529
WMREPLY = 530
WMGFCLOSE = 531
WMTXCLOSE = 532
MODECHANGE = 533
INPUTCHANGE = 534
QFULL = 535
PIECECHANGE = 536
WINCLOSE = 537
QREADERROR = 538
WINFREEZE = 539
WINTHAW = 540
REDRAWICONIC = 541
WINQUIT = 542
DEPTHCHANGE = 543
KEYBDFNAMES = 544
KEYBDFSTRINGS = 545
WINSHUT = 546
DRAWOVERLAY = 547
VIDEO = 548

# ---------------------------------------------------------------------------
# device.h (Release 2.3 header): input and output channels (INPUT7 really is
# 1032 in the header; 1031 is unused)
# ---------------------------------------------------------------------------
INPUT0 = 1024
INPUT1 = 1025
INPUT2 = 1026
INPUT3 = 1027
INPUT4 = 1028
INPUT5 = 1029
INPUT6 = 1030
INPUT7 = 1032

OUTPUT0 = 1033
OUTPUT1 = 1034
OUTPUT2 = 1035
OUTPUT3 = 1036
OUTPUT4 = 1037
OUTPUT5 = 1038
OUTPUT6 = 1039
OUTPUT7 = 1040

# ---------------------------------------------------------------------------
__all__ = sorted(n for n in list(globals()) if n[:1].isupper())
