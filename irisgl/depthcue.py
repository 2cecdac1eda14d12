"""Depth cueing (depthcue(3G), lshaderange(3G), lRGBrange(3G); docs/colour-map-and-depthcue.md).

With depthcue(TRUE) the colour of points, lines and polygons comes from
their screen z only: z in [znear, zfar] maps linearly onto the ramp (the
high end at znear), z beyond either end takes that end.  Colour-map mode
uses the index ramp of lshaderange, RGB mode the colour ramp of lRGBrange.
The ramp is computed per vertex after the viewport transform and
interpolated across the primitive (vgx_emulator/geometry/depthcue.py).
"""
from vgx_emulator.errors import fail

from ._current import boolean, glcall, integer, machine, screen_z, win

__all__ = ["depthcue", "getdcm", "lshaderange", "shaderange", "lRGBrange", "RGBrange",
           "setshade", "getshade"]


@glcall
def depthcue(mode):
    """depthcue(3G): TRUE draws lines, points and polygons depth-cued."""
    w = win("depthcue")
    v = boolean("depthcue", mode)
    if w.st.depthcue != v:
        machine.state_change(w)
        w.st.depthcue = v


@glcall
def getdcm():
    """getdcm(3G): 1 when depth-cue mode is on, else 0."""
    return 1 if win("getdcm").st.depthcue else 0


def _index(call, v, what):
    """A Colorindex of the ramp: an unsigned short, clamped to the 12 planes ([S])."""
    return min(max(integer(call, v, what), 0), 0xFFF)


def _set_shaderange(call, lowin, highin, znear, zfar):
    w = win(call)
    r = (_index(call, lowin, "lowin"), _index(call, highin, "highin"),
         screen_z(call, znear, "znear"), screen_z(call, zfar, "zfar"))
    if w.st.shaderange != r:
        machine.state_change(w)
        w.st.shaderange = r


@glcall
def lshaderange(lowin, highin, znear, zfar):
    """lshaderange(3G): screen z znear -> index highin, zfar -> lowin,
    linear between, clamped beyond; default (0, 7, GD_ZMIN, GD_ZMAX)."""
    _set_shaderange("lshaderange", lowin, highin, znear, zfar)


@glcall
def shaderange(lowindex, highindex, z1, z2):
    """shaderange(3G): the old form of lshaderange (Screencoord z1, z2): z1
    -> highindex, z2 -> lowindex."""
    _set_shaderange("shaderange", lowindex, highindex, z1, z2)


def _set_rgbrange(call, args):
    w = win(call)
    names = ("rmin", "gmin", "bmin", "rmax", "gmax", "bmax")
    comps = tuple(min(max(integer(call, v, n), 0), 255) for v, n in zip(args[:6], names))
    r = comps + (screen_z(call, args[6], "znear"), screen_z(call, args[7], "zfar"))
    if w.st.rgbrange != r:
        machine.state_change(w)
        w.st.rgbrange = r


@glcall
def lRGBrange(rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar):
    """lRGBrange(3G): RGB-mode ramp: znear -> (rmax, gmax, bmax), zfar ->
    (rmin, gmin, bmin); components clamped to 0..255.  Default ([S]):
    black at GD_ZMAX to white at GD_ZMIN."""
    _set_rgbrange("lRGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))


@glcall
def RGBrange(rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar):
    """RGBrange(3G): the old form of lRGBrange (Screencoord znear, zfar)."""
    _set_rgbrange("RGBrange", (rmin, gmin, bmin, rmax, gmax, bmax, znear, zfar))


@glcall(inside=True)
def setshade(shade):
    """setshade(3G): the old GL's current shade, a colour index for the
    vertices that follow (spclos/splf shade with it): the current index of
    color(3G).  An error in RGB mode."""
    from .primitives import color_limit
    w = win("setshade")
    i = integer("setshade", shade, "shade")
    if w.st.rgb:
        fail("setshade", "colour index in RGB mode", "colour-map mode only")
    machine.set_colour(w, (float(min(max(i, 0), color_limit(w))), 0.0, 0.0, 0.0))


@glcall
def getshade():
    """getshade(3G): the current shade (colour index); 0 in RGB mode."""
    st = win("getshade").st
    return 0 if st.rgb else int(st.colour[0] + 0.5)
