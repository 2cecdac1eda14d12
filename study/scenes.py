"""The study's scenes as plain float64 geometry, shared by the exact
reference (ray casting) and the emulator methods (IRIS GL calls).

A scene is a list of indexed triangle meshes (counter-clockwise seen from
outside, flat-shaded: one normal per triangle), a material per mesh
(IRIS GL ``AMBIENT`` and ``DIFFUSE``, no specular), one light at infinity
(``POSITION lx, ly, lz, 0``: the direction *towards* the light, as lmdef
takes it), an area version of that light for soft shadows, and the eye
(``perspective`` + ``lookat`` parameters in IRIS GL units).

Shading model, the same for the emulator and the reference: per channel
``clamp(AMBIENT * model_ambient + DIFFUSE * max(N.L, 0) * visibility)``;
with a light at infinity and one normal per triangle this is constant over
each triangle, so the rasterizer's Gouraud interpolation adds no error.

Every caster is a closed 2-manifold (shared vertices, each edge bounding
exactly two triangles): the shadow volumes need the edge adjacency, and a
shadow ray that leaves a surface towards its back meets the same solid
again.  The ground is open, receives shadows only and casts none.

Scene A is Williams' four spheres (programs/four_spheres.py: radius 1,
32 x 16 latitude/longitude facets, the light turned 100 degrees to the left
of the viewer's bearing) put on a ground plane, with the light raised
30 degrees above the horizon so the ground is lit.  Scene B is the hard
one: a grazing light 6 degrees above the ground, a thin pole and a thin
tilted plate casting long shadows, shadows falling on a large sphere
(a curved receiver) and a torus that shadows itself.

Scenes also come from JSON files (``from_dict``, ``spec_of``; the format:
docs/shadow-study-at-scale.md); ``to_dict`` writes any scene as one.
"""
import math
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Mesh:
    """An indexed triangle mesh with one material."""
    name: str
    verts: np.ndarray                    # (n, 3) float64
    tris: np.ndarray                     # (m, 3) int64, counter-clockwise outside
    material: str
    casts: bool = True                   # False: receives shadows only (the ground)

    @property
    def closed(self):
        """Every directed edge has its reverse (a closed 2-manifold)."""
        e = np.concatenate([self.tris[:, [0, 1]], self.tris[:, [1, 2]], self.tris[:, [2, 0]]])
        fwd = set(map(tuple, e.tolist()))
        return all((b, a) in fwd for a, b in fwd) and len(fwd) == len(e)

    @property
    def convex(self):
        """Closed, and every vertex on the inner side of every triangle's plane."""
        c = self.verts[self.tris]
        n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        side = np.einsum("mvk,mk->mv", self.verts[None, :, :] - c[:, None, 0, :], n)
        scale = np.abs(self.verts).max() + 1.0
        return self.closed and bool((side <= 1e-9 * scale).all())


@dataclass
class View:
    """The eye: lookat(eye, ref, twist 0) and perspective(fovy, w/h, near, far)."""
    eye: tuple
    ref: tuple
    fovy: int                             # tenths of a degree, as perspective takes it
    near: float
    far: float


@dataclass
class Scene:
    name: str
    title: str
    meshes: list
    materials: dict                       # name -> (ambient rgb, diffuse rgb)
    model_ambient: float
    light: np.ndarray                     # (4,) towards the light, w = 0
    light_radius: float                   # area light: disc radius at unit distance
    view: View
    ground_y: float
    notes: str = ""
    _flat: dict = field(default_factory=dict, repr=False)

    @property
    def light_dir(self):
        d = np.asarray(self.light[:3], np.float64)
        return d / np.linalg.norm(d)

    def flat(self):
        """All triangles as arrays: corners (m, 3, 3), unit normals (m, 3),
        mesh index (m,), ambient and diffuse rgb (m, 3) each, ground flag (m,)."""
        if not self._flat:
            corners, mesh_id = [], []
            for k, m in enumerate(self.meshes):
                corners.append(m.verts[m.tris])
                mesh_id.append(np.full(len(m.tris), k))
            c = np.concatenate(corners)
            mid = np.concatenate(mesh_id)
            n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
            n /= np.linalg.norm(n, axis=1, keepdims=True)
            amb = np.array([self.materials[self.meshes[k].material][0] for k in mid], float)
            dif = np.array([self.materials[self.meshes[k].material][1] for k in mid], float)
            ground = np.array([not self.meshes[k].casts for k in mid])
            self._flat.update(corners=c, normals=n, mesh=mid, ambient=amb, diffuse=dif,
                              ground=ground)
        return self._flat

    def bounds(self):
        """Axis-aligned box of every vertex: (lo, hi)."""
        v = np.concatenate([m.verts for m in self.meshes])
        return v.min(axis=0), v.max(axis=0)


# ---------------------------------------------------------------------------
# mesh builders (closed, counter-clockwise outside)
def _quads_to_tris(quads):
    q = np.asarray(quads, np.int64)
    return np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def sphere(name, centre, r, slices, stacks, material):
    """Latitude/longitude sphere: poles as single vertices, caps as fans."""
    c = np.asarray(centre, float)
    verts = [c + (0.0, -r, 0.0)]
    for i in range(1, stacks):
        phi = math.pi * i / stacks - math.pi / 2
        th = 2 * math.pi * np.arange(slices) / slices
        ring = np.stack([np.cos(phi) * np.cos(th), np.full(slices, math.sin(phi)),
                         -np.cos(phi) * np.sin(th)], axis=1)
        verts.extend(c + r * ring)
    verts.append(c + (0.0, r, 0.0))
    top = len(verts) - 1

    def ring(i, j):
        return 1 + (i - 1) * slices + j % slices
    tris = [(0, ring(1, j + 1), ring(1, j)) for j in range(slices)]
    quads = [(ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j))
             for i in range(1, stacks - 1) for j in range(slices)]
    tris += [(ring(stacks - 1, j), ring(stacks - 1, j + 1), top) for j in range(slices)]
    t = np.concatenate([np.asarray(tris, np.int64), _quads_to_tris(quads)])
    return Mesh(name, np.asarray(verts), t, material)


def torus(name, centre, big, small, n1, n2, material):
    """A torus lying flat (axis along y)."""
    i, j = np.meshgrid(np.arange(n1), np.arange(n2), indexing="ij")
    th, ph = 2 * np.pi * i / n1, 2 * np.pi * j / n2
    rr = big + small * np.cos(ph)
    v = np.stack([rr * np.cos(th), small * np.sin(ph), -rr * np.sin(th)], -1).reshape(-1, 3)

    def k(a, b):
        return (a % n1) * n2 + b % n2
    quads = [(k(a, b), k(a + 1, b), k(a + 1, b + 1), k(a, b + 1))
             for a in range(n1) for b in range(n2)]
    return Mesh(name, v + np.asarray(centre, float), _quads_to_tris(quads), material)


def box(name, half, material, centre=(0, 0, 0), rot=None):
    """A box of half sizes ``half``, rotated by the 3x3 ``rot`` (row
    vectors), then moved to ``centre``."""
    hx, hy, hz = half
    v = np.array([(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    if rot is not None:
        v = v @ rot
    return Mesh(name, v + np.asarray(centre, float), _quads_to_tris(quads), material)


def prism(name, base, r, h, n, material):
    """An upright n-sided prism (a pole), base centre ``base``."""
    th = 2 * np.pi * np.arange(n) / n
    ring = np.stack([r * np.cos(th), np.zeros(n), -r * np.sin(th)], 1)
    b = np.asarray(base, float)
    v = np.concatenate([b + ring, b + ring + (0.0, h, 0.0)])
    bottom = [(0, j + 1, j) for j in range(1, n - 1)]
    top = [(n, n + j, n + j + 1) for j in range(1, n - 1)]
    quads = [(j, (j + 1) % n, n + (j + 1) % n, n + j) for j in range(n)]
    t = np.concatenate([np.asarray(bottom + top, np.int64), _quads_to_tris(quads)])
    return Mesh(name, v, t, material)


def ground(name, y, half, material):
    """The ground square (two triangles, facing +y), open: it casts nothing."""
    v = np.array([(-half, y, -half), (-half, y, half), (half, y, half), (half, y, -half)], float)
    return Mesh(name, v, np.array([(0, 1, 2), (0, 2, 3)], np.int64), material, casts=False)


def rotation(axis, degrees):
    """IRIS GL rotate()'s matrix (row vectors), 3x3."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    return {"x": np.array([[1, 0, 0], [0, c, s], [0, -s, c]]),
            "y": np.array([[c, 0, -s], [0, 1, 0], [s, 0, c]]),
            "z": np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])}[axis]


def light_from(azimuth_left, elevation):
    """Direction towards a light at infinity: turned ``azimuth_left`` degrees
    about +y from the viewer's bearing (+z), raised ``elevation`` degrees."""
    a, e = math.radians(azimuth_left), math.radians(elevation)
    return np.array([-math.sin(a) * math.cos(e), math.sin(e), math.cos(a) * math.cos(e), 0.0])


def disc_basis(L):
    """Two unit vectors spanning the plane perpendicular to the unit L."""
    u = np.cross(L, (0.0, 0.0, 1.0))
    if np.linalg.norm(u) < 1e-6:
        u = np.cross(L, (1.0, 0.0, 0.0))
    u /= np.linalg.norm(u)
    return u, np.cross(L, u)


def area_light_directions(scene, disc_points):
    """Directions towards the area light for points ``(n, 2)`` of the unit
    disc: normalize(L + r (x u + y w)), r = scene.light_radius."""
    L = scene.light_dir
    u, w = disc_basis(L)
    p = np.asarray(disc_points, float).reshape(-1, 2)
    d = L + scene.light_radius * (p[:, :1] * u + p[:, 1:] * w)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def vogel_disc(n):
    """n points evenly spread over the unit disc (golden-angle spiral,
    r = sqrt((k + 1/2) / n)); one point is the centre."""
    if n == 1:
        return np.zeros((1, 2))
    k = np.arange(n) + 0.5
    r = np.sqrt(k / n)
    th = k * math.pi * (3.0 - math.sqrt(5.0))
    return np.stack([r * np.cos(th), r * np.sin(th)], axis=1)


def jittered_disc(n, seed):
    """The vogel_disc spiral jittered from ``seed``: turned by a random
    angle, each point at a random radius within its ring (r^2 uniform in
    [k/n, (k+1)/n)): n points stratified over the disc, a different set
    for every seed."""
    rng = np.random.default_rng(seed)
    k = np.arange(n)
    r = np.sqrt((k + rng.uniform(0.0, 1.0, n)) / n)
    th = (k + 0.5) * math.pi * (3.0 - math.sqrt(5.0)) + rng.uniform(0.0, 2.0 * math.pi)
    return np.stack([r * np.cos(th), r * np.sin(th)], axis=1)


# ---------------------------------------------------------------------------
SPHERE_CENTRES = [(-3.45, 0.0, 0.6), (-1.15, 0.0, -0.6), (1.15, 0.0, 0.6), (3.45, 0.0, -0.6)]


def scene_a():
    """Williams' four spheres on a ground plane (y = -1, where they rest)."""
    meshes = [ground("ground", -1.0, 12.0, "ground")]
    meshes += [sphere(f"sphere{k}", c, 1.0, 32, 16, "sphere")
               for k, c in enumerate(SPHERE_CENTRES)]
    return Scene(
        name="A", title="four spheres (Williams 1978) on a ground plane",
        meshes=meshes,
        materials={"ground": ((0.55, 0.60, 0.50), (0.55, 0.60, 0.50)),
                   "sphere": ((0.75, 0.72, 0.68), (0.75, 0.72, 0.68))},
        model_ambient=0.3, light=light_from(100.0, 30.0), light_radius=math.tan(math.radians(3.0)),
        view=View((0.0, 3.0, 12.0), (0.0, 0.0, 0.0), 400, 1.0, 50.0), ground_y=-1.0,
        notes="light at infinity turned 100 degrees left of the viewer's bearing, 30 degrees "
              "up; area light: a disc of 3 degrees angular radius")


def scene_b():
    """Grazing light, thin casters, a curved receiver, self-shadowing."""
    plate_rot = rotation("z", 25.0) @ rotation("y", -20.0)
    meshes = [
        ground("ground", 0.0, 30.0, "ground"),
        sphere("big sphere", (3.0, 2.5, -2.0), 2.5, 48, 24, "sphere"),
        prism("pole", (-3.0, 0.0, 0.1), 0.06, 3.5, 12, "pole"),
        box("plate", (1.0, 0.02, 0.7), "plate", centre=(-1.0, 1.4, 2.0), rot=plate_rot),
        torus("torus", (-4.5, 0.35, 3.0), 1.0, 0.35, 32, 12, "torus"),
    ]
    return Scene(
        name="B", title="grazing light, thin casters, curved receiver",
        meshes=meshes,
        materials={"ground": ((0.55, 0.60, 0.50), (1.0, 1.0, 0.9)),
                   "sphere": ((0.80, 0.78, 0.74), (0.80, 0.78, 0.74)),
                   "pole": ((0.85, 0.55, 0.30), (0.85, 0.55, 0.30)),
                   "plate": ((0.40, 0.60, 0.85), (0.40, 0.60, 0.85)),
                   "torus": ((0.45, 0.80, 0.45), (0.45, 0.80, 0.45))},
        model_ambient=0.2, light=light_from(70.0, 6.0), light_radius=math.tan(math.radians(2.0)),
        view=View((-7.0, 6.0, 13.0), (1.0, 1.2, -2.0), 450, 0.5, 100.0), ground_y=0.0,
        notes="light at infinity 6 degrees above the ground; a pole 0.12 thick and 3.5 high, "
              "a plate 0.04 thick, a sphere of radius 2.5 receiving the pole's shadow, "
              "a torus; area light: a disc of 2 degrees angular radius")


SCENES = {"A": scene_a, "B": scene_b}


def get(name):
    return SCENES[name]()


# ---------------------------------------------------------------------------
# scene files (JSON; the format is documented in docs/shadow-study-at-scale.md)
FORMAT = "vgx-study-scene 1"


def _vec(d, key, n=3):
    v = d[key]
    if len(v) != n:
        raise ValueError(f"{key}: {n} numbers expected, got {v!r}")
    return tuple(float(c) for c in v)


def _mesh_from(d):
    """One entry of a scene file's ``meshes`` list."""
    kind, name, mat = d["kind"], d.get("name", d["kind"]), d["material"]
    if kind == "ground":
        return ground(name, float(d["y"]), float(d["half"]), mat)
    if kind == "sphere":
        return sphere(name, _vec(d, "centre"), float(d["radius"]), int(d.get("slices", 32)),
                      int(d.get("stacks", 16)), mat)
    if kind == "torus":
        return torus(name, _vec(d, "centre"), float(d["radius"]), float(d["tube"]),
                     int(d.get("rings", 32)), int(d.get("sides", 12)), mat)
    if kind == "prism":
        return prism(name, _vec(d, "base"), float(d["radius"]), float(d["height"]),
                     int(d.get("sides", 12)), mat)
    if kind == "box":
        rot = None
        for axis, degrees in d.get("rotate", []):
            r = rotation(axis, float(degrees))
            rot = r if rot is None else rot @ r
        return box(name, _vec(d, "half"), mat, _vec(d, "centre") if "centre" in d else (0, 0, 0),
                   rot)
    if kind == "triangles":
        v = np.asarray(d["verts"], np.float64).reshape(-1, 3)
        t = np.asarray(d["tris"], np.int64).reshape(-1, 3)
        if len(t) and (t.min() < 0 or t.max() >= len(v)):
            raise ValueError(f"mesh {name!r}: a triangle indexes a vertex that does not exist")
        return Mesh(name, v, t, mat, casts=bool(d.get("casts", True)))
    raise ValueError(f"mesh {name!r}: unknown kind {kind!r} (ground, sphere, torus, prism, "
                     f"box, triangles)")


def from_dict(d, default_name="S"):
    """A Scene from the dict of a scene file; ValueError naming what is wrong."""
    if d.get("format", FORMAT) != FORMAT:
        raise ValueError(f"scene format {d.get('format')!r}: {FORMAT!r} expected")
    try:
        mats = {k: (_vec(m, "ambient"), _vec(m, "diffuse")) for k, m in d["materials"].items()}
        meshes = [_mesh_from(m) for m in d["meshes"]]
        light = d["light"]
        if "direction" in light:
            direction = np.array([*_vec(light, "direction"), 0.0])
        else:
            direction = light_from(float(light["azimuth_left"]), float(light["elevation"]))
        v = d["view"]
        view = View(_vec(v, "eye"), _vec(v, "ref"), int(v["fovy"]), float(v["near"]),
                    float(v["far"]))
        scene = Scene(name=str(d.get("name", default_name)), title=str(d.get("title", "")),
                      meshes=meshes, materials=mats, model_ambient=float(d["model_ambient"]),
                      light=direction,
                      light_radius=_light_radius(d),
                      view=view, ground_y=float(d["ground_y"]), notes=str(d.get("notes", "")))
    except KeyError as e:
        raise ValueError(f"scene file: {e.args[0]!r} missing") from None
    for m in scene.meshes:
        if m.material not in mats:
            raise ValueError(f"mesh {m.name!r}: material {m.material!r} is not in materials")
        if m.casts and not m.closed:
            raise ValueError(f"mesh {m.name!r} casts shadows but is not closed (every edge "
                             f"must bound exactly two triangles; give an open mesh "
                             f"\"casts\": false)")
    if not any(m.casts for m in scene.meshes):
        raise ValueError("scene file: no mesh casts a shadow")
    if np.linalg.norm(scene.light[:3]) == 0.0:
        raise ValueError("scene file: the light direction is zero")
    return scene


def _light_radius(d):
    """``light_radius`` (the disc's radius at unit distance) or
    ``light_radius_degrees`` (its angular radius); 0: a point light only."""
    if "light_radius" in d:
        return float(d["light_radius"])
    return math.tan(math.radians(float(d.get("light_radius_degrees", 0.0))))


def to_dict(scene):
    """A scene file dict of any Scene (every mesh as ``triangles``)."""
    return {"format": FORMAT, "name": scene.name, "title": scene.title, "notes": scene.notes,
            "materials": {k: {"ambient": list(a), "diffuse": list(dif)}
                          for k, (a, dif) in scene.materials.items()},
            "model_ambient": scene.model_ambient,
            "light": {"direction": [float(c) for c in scene.light[:3]]},
            "light_radius": float(scene.light_radius),
            "view": {"eye": list(scene.view.eye), "ref": list(scene.view.ref),
                     "fovy": scene.view.fovy, "near": scene.view.near, "far": scene.view.far},
            "ground_y": scene.ground_y,
            "meshes": [{"kind": "triangles", "name": m.name, "material": m.material,
                        "casts": m.casts, "verts": m.verts.tolist(), "tris": m.tris.tolist()}
                       for m in scene.meshes]}


def spec_of(name):
    """What a worker needs to build a scene: a built-in name (``A``, ``B``)
    or the parsed contents of a scene file (checked here, on the client)."""
    if name in SCENES:
        return {"builtin": name}
    import json
    from pathlib import Path
    p = Path(name)
    try:
        d = json.loads(p.read_text())
    except OSError as e:
        raise ValueError(f"scene {name!r}: not a built-in scene ({', '.join(SCENES)}) and "
                         f"not a readable file ({e.strerror})") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"scene file {name}: not JSON ({e})") from None
    d.setdefault("name", p.stem)
    from_dict(d)
    return d


def build(spec):
    """The Scene of a spec_of() result."""
    if "builtin" in spec:
        return get(spec["builtin"])
    return from_dict(spec)
