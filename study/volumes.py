"""Shadow volumes of closed triangle meshes for a light at infinity
(Heidmann 1991, generalised from programs/heidmann_shadow_volumes.py, whose
functions work on that program's module globals and local lights only).

For a light towards L: a triangle faces the light when N.L > 0; an edge is
a silhouette edge when its two triangles face the light differently.  Each
silhouette edge (a, b), taken in the direction it has in its light-facing
triangle, gives the face (b, a, a - E L, b - E L) whose normal points out
of the volume (Heidmann's fig. 2 rule).  The caps that close the volume
for depth-fail counting are the light-facing triangles (near cap) and the
triangles facing away pushed by -E L (far cap), both outward.

E, the extrusion, is the distance along -L at which every caster vertex
is below the ground, so the volumes reach every receiver (nothing is below
the ground) and end just under it, inside the far clipping plane.
"""
import numpy as np


class Edges:
    """Edge adjacency of a closed mesh: each undirected edge once, (a, b)
    as it runs in triangle t0, and t1 the triangle where it runs b -> a."""

    def __init__(self, mesh):
        t = mesh.tris
        a = np.concatenate([t[:, 0], t[:, 1], t[:, 2]])
        b = np.concatenate([t[:, 1], t[:, 2], t[:, 0]])
        tri = np.tile(np.arange(len(t)), 3)
        nv = len(mesh.verts)
        fwd, rev = a * nv + b, b * nv + a
        order = np.argsort(fwd)
        pos = np.searchsorted(fwd[order], rev)
        if not (pos < len(fwd)).all() or not (fwd[order][np.minimum(pos, len(fwd) - 1)]
                                              == rev).all():
            raise ValueError(f"{mesh.name}: not closed; shadow volumes need closed casters")
        twin = order[pos]
        keep = a < b
        self.a, self.b, self.t0, self.t1 = a[keep], b[keep], tri[keep], tri[twin[keep]]
        c = mesh.verts[t]
        n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        self.normals = n / np.linalg.norm(n, axis=1, keepdims=True)
        self.verts, self.corners = mesh.verts, c


def adjacency(scene):
    """Edges of every casting mesh."""
    return [Edges(m) for m in scene.meshes if m.casts]


def extrusion(scene, L):
    """Distance along -L that takes the highest caster vertex below the ground."""
    top = max(m.verts[:, 1].max() for m in scene.meshes if m.casts)
    return 1.05 * (top - scene.ground_y) / L[1] + 0.1


def side_faces(edges, L, E):
    """(n, 4, 3) volume side faces for the light towards L."""
    quads = []
    for e in edges:
        f = e.normals @ L > 0
        sil = f[e.t0] != f[e.t1]
        lit0 = f[e.t0][sil]
        a = np.where(lit0, e.a[sil], e.b[sil])
        b = np.where(lit0, e.b[sil], e.a[sil])
        va, vb = e.verts[a], e.verts[b]
        quads.append(np.stack([vb, va, va - E * L, vb - E * L], axis=1))
    return np.concatenate(quads) if quads else np.zeros((0, 4, 3))


def caps(edges, L, E):
    """(n, 3, 3) near and far caps for the light towards L."""
    out = []
    for e in edges:
        f = e.normals @ L > 0
        out.append(e.corners[f])
        out.append(e.corners[~f] - E * L)
    return np.concatenate(out)


def ingoing(polys, eye):
    """Polygons front-facing from the eye (going into the volume)."""
    p = np.asarray(polys)
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 1])
    return ((np.asarray(eye) - p[:, 1]) * n).sum(axis=1) > 0
