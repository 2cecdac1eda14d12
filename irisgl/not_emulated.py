"""The IRIS GL calls the emulated VGX does not provide.

Each exists, so a ported program never stops at a NameError; calling one
raises GLError naming the call and saying why (docs/api.md lists them).
Most belong to machines or subsystems other than the IRIS-4D VGX's
graphics: RealityEngine texture and imaging extensions, stereo buffers,
mixed-model X programming, distributed GL.  A call that another module of
irisgl implements is skipped here, so the table only ever names what is
really missing.
"""
from ._current import API, not_emulated

_X = ("mixed-model GL/X programming binds GL to an X server's windows and visuals; "
      "the emulated VGX has windows of its own (winopen)")
_DGL = ("Distributed GL sends the command stream to a remote graphics server over the "
        "network; here the emulator is the graphics")
_NURBS = ("NURBS curves and surfaces (nurbscurve(3G), nurbssurface(3G)) are not "
          "tessellated by this emulator yet; curves and patches of crv(3G)/patch(3G) are")
_IMAGING = ("the IRIX 5 imaging extensions (convolution, histogram, minmax, pixel maps, "
            "image buffers) belong to later machines, not to the VGX's raster subsystem")
_RE_TEXTURE = ("a RealityEngine texture feature (getgdesc(GD_TEXTURE_3D) and "
               "getgdesc(GD_TEXTURE_LUT) are 0 on the VGX)")
_STEREO = "the VGX has no stereo buffers (getgdesc(GD_STEREO) is 0)"

WHY = {
    "GLXgetconfig": _X, "GLXlink": _X, "GLXunlink": _X, "GLXwinset": _X,
    "dglopen": _DGL, "dglclose": _DGL,
    "bgncurve": _NURBS, "endcurve": _NURBS, "bgnsurface": _NURBS, "endsurface": _NURBS,
    "bgntrim": _NURBS, "endtrim": _NURBS, "nurbscurve": _NURBS, "nurbssurface": _NURBS,
    "pwlcurve": _NURBS, "setnurbsproperty": _NURBS, "getnurbsproperty": _NURBS,
    "convolve": _IMAGING, "hgram": _IMAGING, "gethgram": _IMAGING, "minmax": _IMAGING,
    "getminmax": _IMAGING, "pixelmap": _IMAGING, "pixeltransfer": _IMAGING,
    "ilbuffer": _IMAGING, "ildraw": _IMAGING,
    "texdef3d": _RE_TEXTURE, "tlutdef": _RE_TEXTURE, "tlutbind": _RE_TEXTURE,
    "subtexload": "texture subimage loading is a RealityEngine feature; redefine the "
                  "texture with texdef2d(3G)",
    "fbsubtexload": "loading a texture from the framebuffer is a RealityEngine feature",
    "istexloaded": "texture residency is a RealityEngine notion; every texdef2d texture "
                   "of the emulated VGX is always loaded",
    "stereobuffer": _STEREO, "leftbuffer": _STEREO, "rightbuffer": _STEREO,
    "passthrough": "passthrough(3G) marks the feedback buffer, and feedback mode is not "
                   "emulated",
}

__all__ = []
for _name, _why in WHY.items():
    if _name not in API:
        globals()[_name] = not_emulated(_name, _why)
        __all__.append(_name)
