"""Lighting calls: lmdef, lmbind, lmcolor, nmode (docs/semantics.md §9).

Definitions are global (every window sees them); bindings belong to the
window.  A light's POSITION and SPOTDIRECTION are taken through the
ModelView matrix current at ``lmbind``.  Lighting is computed only while a
material and a light model are bound, in MVIEWING.
"""
from vgx_emulator.errors import fail
from vgx_emulator.geometry import lighting as L

from . import constants as K
from ._current import glcall, integer, machine, token, win

__all__ = ["lmdef", "lmbind", "lmcolor", "nmode", "getlmbind"]

_DEFTYPES = {K.DEFMATERIAL: "DEFMATERIAL", K.DEFLIGHT: "DEFLIGHT", K.DEFLMODEL: "DEFLMODEL"}
_TARGETS = {K.MATERIAL: "MATERIAL", K.BACKMATERIAL: "BACKMATERIAL", K.LMODEL: "LMODEL",
            **{K.LIGHT0 + i: f"LIGHT{i}" for i in range(8)}}
_TARGET_TYPE = {K.MATERIAL: K.DEFMATERIAL, K.BACKMATERIAL: K.DEFMATERIAL,
                K.LMODEL: K.DEFLMODEL, **{K.LIGHT0 + i: K.DEFLIGHT for i in range(8)}}
_LMC = {K.LMC_COLOR: "LMC_COLOR", K.LMC_EMISSION: "LMC_EMISSION", K.LMC_AMBIENT: "LMC_AMBIENT",
        K.LMC_DIFFUSE: "LMC_DIFFUSE", K.LMC_SPECULAR: "LMC_SPECULAR", K.LMC_AD: "LMC_AD",
        K.LMC_NULL: "LMC_NULL"}


@glcall(inside=True)
def lmdef(deftype, index, np, props):
    """lmdef(3G): define or change material, light or light-model ``index``.

    ``props``: tokens each followed by their floats, ending with LMNULL;
    ``np`` counts the floats including LMNULL, a hint only: the list is read
    to LMNULL whatever it says (lmdef(3G): 0 is ignored, a correct np only
    speeds a network connection).  Only the
    listed properties change; ``None`` (or 0, C's NULL) or an empty list
    (LMNULL first) restores the defaults.  Index 0 is the null definition and cannot be
    redefined.
    """
    d = token("lmdef", deftype, _DEFTYPES, "definition type")
    i = integer("lmdef", index, "index")
    n = integer("lmdef", np, "np")
    if i <= 0 or i > 65535:
        fail("lmdef", f"index {i}", "1..65535 (0 is the null definition)")
    parsed = None
    if isinstance(props, int) and props == 0:
        props = None                      # C's NULL written as 0: lmdef(DEFLIGHT, 1, 0, 0)
    if props is not None:
        try:
            seq = list(props)
        except TypeError:
            fail("lmdef", "props is not a sequence", "a list of floats ending with LMNULL")
        parsed = L.parse_properties("lmdef", d, n, seq)
        if not parsed:
            parsed = None
    machine.lmdef(d, i, parsed)


@glcall(inside=True)
def lmbind(target, index):
    """lmbind(3G): bind definition ``index`` (0 = none) to MATERIAL,
    BACKMATERIAL, LIGHT0..LIGHT7 or LMODEL.  An undefined index binds 0."""
    w = win("lmbind")
    t = token("lmbind", target, _TARGETS, "target")
    i = integer("lmbind", index, "index")
    machine.lmbind(w, t, i)


@glcall
def getlmbind(target):
    """getlmbind(3G): the definition bound to a target (0 when none)."""
    w = win("getlmbind")
    t = token("getlmbind", target, _TARGETS, "target")
    st = w.st
    if t == K.MATERIAL:
        return st.material
    if t == K.BACKMATERIAL:
        return st.backmaterial
    if t == K.LMODEL:
        return st.lmodel
    b = st.lights.get(t - K.LIGHT0)
    return b.index if b else 0


_LMC_TARGETS = {K.LMC_EMISSION: (K.EMISSION,), K.LMC_AMBIENT: (K.AMBIENT,),
                K.LMC_DIFFUSE: (K.DIFFUSE,), K.LMC_SPECULAR: (K.SPECULAR,),
                K.LMC_AD: (K.AMBIENT, K.DIFFUSE)}


@glcall(inside=True)
def lmcolor(mode):
    """lmcolor(3G): where RGB colour calls go while lighting is on."""
    w = win("lmcolor")
    m = token("lmcolor", mode, _LMC, "lmcolor mode")
    # no flush: the following vertices take a new record whose material
    # entry holds the mode (VertexBatch.material_ref), and each vertex is
    # lit with its own entry's mode
    st = w.st
    # a colour already sent under a material mode stays in the bound material
    # until the next material bind (docs/semantics.md §9), whatever lmcolor says next
    if st.colour_since_bind and st.lmcolor in _LMC_TARGETS:
        rgb = tuple(c / 255.0 for c in st.colour[:3])
        ov = dict(st.mat_override)
        for prop in _LMC_TARGETS[st.lmcolor]:
            ov[prop] = rgb
        if st.lmcolor in (K.LMC_DIFFUSE, K.LMC_AD):
            ov[K.ALPHA] = (st.colour[3] / 255.0,)
        st.mat_override = ov
    if m != st.lmcolor:
        st.colour_since_bind = False
    st.lmcolor = m
    machine.attributes_changed(w)


@glcall
def nmode(mode):
    """nmode(3G): NAUTO renormalises transformed normals only when ModelView
    is not orthonormal; NNORMALIZE always."""
    w = win("nmode")
    m = token("nmode", mode, {K.NAUTO: "NAUTO", K.NNORMALIZE: "NNORMALIZE"}, "normal mode")
    machine.state_change(w)
    w.st.nmode = m
