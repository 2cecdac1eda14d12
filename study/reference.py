"""The exact reference: ray casting in float64, independent of the rasterizer.

For every pixel of the eye's window the ray through the pixel centre
(window (i, j) is the centre of pixel (i, j), IRIS GL's convention, with
the viewport mapping of the whole window) is built from the same
``perspective`` and ``lookat`` parameters the emulator is given, with the
matrices rebuilt here in float64 from the formulas of the IRIS GL reference
(section 2).  The ray is intersected with every triangle of the scene
(Moller-Trumbore in float64 through a bounding-volume hierarchy, numba);
only hits between the near and far clipping planes count, as the emulator
clips there.  At the visible point a shadow ray goes to the light:

* the triangle the point lies on is skipped, and a blocker must lie
  farther than ``EPS_REL * max(1, |P|)`` along the (unit) shadow ray.
  A ray leaving a surface meets the facets sharing an edge with the hit
  triangle at t ~ 1e-16 |P| (float64 rounding); 1e-9 |P| is far above that
  and far below any real gap of the scenes (the thinnest is 0.04);
* barycentric tests are inclusive, so a shadow ray through a shared edge
  of a closed caster is blocked by one of the two triangles;
* the light reaches a point when the ray is unblocked **and** the point's
  triangle faces the light (N.L > 0): the lighting equation gives no
  diffuse light otherwise, whatever any shadow method decides.

Shadow rays are cast against the casters only when no shadow ray can meet
the ground (every visible point is on or above it and every light
direction points upwards; ``shadow_bvh``), against everything otherwise.

Soft shadows: the area light is a disc of directions, ``L + r*s`` (s in the
unit disc perpendicular to L, r = ``scene.light_radius``), normalized; the
same parameterisation the jittered lights of the accumulation method use.
Per pixel the visible fraction (and the diffuse integral E[max(N.Ls, 0)
vis_s] that the shaded image needs) is estimated by stratified sampling
(jittered k x k strata of the square mapped to the disc by Shirley and
Chiu's concentric map) with k = 4, 8, 16, 32, 64: the estimate is taken as
converged when two successive levels differ by at most ``SOFT_TOL`` in the
visible fraction, with k >= 16 for pixels whose shadow cone (apex P, the
light's angular disc) meets the bounding sphere of any triangle that could
block it (a conservative test through the hierarchy; the triangles of the
point's own mesh are left out when the mesh is convex, since a ray leaving
a facet of a convex solid on its outer side never meets it again).  Where
the cone meets nothing no shadow ray is needed: only the facing test
remains.  The level where each pixel stopped is returned (k = 64 is the
cap, reached without meeting the criterion).  Checked against the closed
form of a straight occluder edge in tests/test_study.py (error < 0.008).
"""
import math
from dataclasses import dataclass

import numba
import numpy as np

from .scenes import disc_basis

EPS_REL = 1e-9
SOFT_TOL = 1.0 / 512.0
LEAF = 8
STACK = 64
MAX_CANDIDATES = 32
_JIT = dict(cache=True, error_model="numpy", fastmath=False)


# ---------------------------------------------------------------------------
# the eye's matrices, float64 (docs/semantics.md §2, row vectors)
def lookat_matrix(v, p):
    """lookat(vx, vy, vz, px, py, pz, 0): T(-v) . R."""
    v, p = np.asarray(v, float), np.asarray(p, float)
    f = (p - v) / np.linalg.norm(p - v)
    up = (0.0, 1.0, 0.0) if abs(f[1]) < 1.0 - 1e-12 else (0.0, 0.0, -1.0)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    r = np.identity(4)
    r[:3, 0], r[:3, 1], r[:3, 2] = s, u, -f
    t = np.identity(4)
    t[3, :3] = -v
    return t @ r


def perspective_matrix(fovy, aspect, n, f):
    """perspective(fovy, aspect, near, far), fovy in tenths of a degree."""
    c = 1.0 / math.tan(math.radians(fovy / 20.0))
    return np.array([[c / aspect, 0, 0, 0], [0, c, 0, 0],
                     [0, 0, -(f + n) / (f - n), -1], [0, 0, -2 * f * n / (f - n), 0]])


def eye_rays(view, width, height):
    """Unit rays through the pixel centres (rows bottom first, as lrectread
    returns them) and their [tmin, tmax] between the clipping planes."""
    mv = lookat_matrix(view.eye, view.ref)
    inv = np.linalg.inv(mv @ perspective_matrix(view.fovy, width / height, view.near, view.far))
    ys, xs = np.mgrid[0:height, 0:width].astype(np.float64)
    xn = (xs + 0.5) * 2.0 / width - 1.0            # viewport: xs = -0.5 + (xn+1)/2 * w
    yn = (ys + 0.5) * 2.0 / height - 1.0
    ndc = np.stack([xn, yn, -np.ones_like(xn), np.ones_like(xn)], -1)
    p = ndc @ inv
    p = p[..., :3] / p[..., 3:4]
    eye = np.asarray(view.eye, float)
    d = p - eye
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    fwd = -mv[:3, 2]                               # the viewing direction
    cosang = d @ fwd
    return (np.broadcast_to(eye, d.shape).reshape(-1, 3).copy(), d.reshape(-1, 3),
            (view.near / cosang).reshape(-1), (view.far / cosang).reshape(-1))


# ---------------------------------------------------------------------------
# bounding-volume hierarchy (median split, built with numpy)
@dataclass
class BVH:
    v0: np.ndarray          # triangle corner 0, in BVH order
    e1: np.ndarray          # corner1 - corner0
    e2: np.ndarray          # corner2 - corner0
    ids: np.ndarray         # scene triangle index of each BVH-ordered triangle
    lo: np.ndarray          # node boxes
    hi: np.ndarray
    child: np.ndarray       # (nodes, 2): children, or (start, count) of a leaf
    leaf: np.ndarray        # (nodes,) bool
    centre: np.ndarray      # per-triangle bounding sphere (for the cone test)
    radius: np.ndarray


def build_bvh(corners):
    """A binary hierarchy over triangles ``corners`` (m, 3, 3)."""
    cen = corners.mean(axis=1)
    tlo, thi = corners.min(axis=1), corners.max(axis=1)
    order, lo, hi, child, leaf = [], [], [], [], []

    def node(idx):
        k = len(lo)
        lo.append(tlo[idx].min(axis=0))
        hi.append(thi[idx].max(axis=0))
        child.append([0, 0])
        leaf.append(len(idx) <= LEAF)
        if leaf[k]:
            child[k] = [len(order), len(idx)]
            order.extend(idx.tolist())
            return k
        c = cen[idx]
        axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
        half = len(idx) // 2
        part = np.argpartition(c[:, axis], half)
        a = node(idx[part[:half]])
        b = node(idx[part[half:]])
        child[k] = [a, b]
        return k

    node(np.arange(len(corners)))
    ids = np.asarray(order, np.int64)
    c = corners[ids]
    sc = c.mean(axis=1)
    return BVH(c[:, 0].copy(), c[:, 1] - c[:, 0], c[:, 2] - c[:, 0], ids,
               np.asarray(lo), np.asarray(hi), np.asarray(child, np.int64),
               np.asarray(leaf), sc, np.linalg.norm(c - sc[:, None], axis=2).max(axis=1))


# ---------------------------------------------------------------------------
# kernels
@numba.njit(**_JIT)
def _tri(o, d, v0, e1, e2):
    """Moller-Trumbore: t of the hit (inclusive edges), or inf."""
    px = d[1] * e2[2] - d[2] * e2[1]
    py = d[2] * e2[0] - d[0] * e2[2]
    pz = d[0] * e2[1] - d[1] * e2[0]
    det = e1[0] * px + e1[1] * py + e1[2] * pz
    if det == 0.0:
        return np.inf
    inv = 1.0 / det
    tx, ty, tz = o[0] - v0[0], o[1] - v0[1], o[2] - v0[2]
    u = (tx * px + ty * py + tz * pz) * inv
    if u < 0.0 or u > 1.0:
        return np.inf
    qx = ty * e1[2] - tz * e1[1]
    qy = tz * e1[0] - tx * e1[2]
    qz = tx * e1[1] - ty * e1[0]
    v = (d[0] * qx + d[1] * qy + d[2] * qz) * inv
    if v < 0.0 or u + v > 1.0:
        return np.inf
    return (e2[0] * qx + e2[1] * qy + e2[2] * qz) * inv


@numba.njit(**_JIT)
def _box(o, ix, iy, iz, lo, hi, k, tmin, tmax):
    """Slab test of the ray (origin o, inverse direction) against node k's
    box, inside [tmin, tmax]."""
    t0, t1 = (lo[k, 0] - o[0]) * ix, (hi[k, 0] - o[0]) * ix
    if t0 > t1:
        t0, t1 = t1, t0
    tmin, tmax = max(tmin, t0), min(tmax, t1)
    t0, t1 = (lo[k, 1] - o[1]) * iy, (hi[k, 1] - o[1]) * iy
    if t0 > t1:
        t0, t1 = t1, t0
    tmin, tmax = max(tmin, t0), min(tmax, t1)
    t0, t1 = (lo[k, 2] - o[2]) * iz, (hi[k, 2] - o[2]) * iz
    if t0 > t1:
        t0, t1 = t1, t0
    return max(tmin, t0) <= min(tmax, t1)


@numba.njit(**_JIT)
def _trace(o, d, tmin, tmax, skip, any_hit, stack, v0, e1, e2, ids, lo, hi, child, leaf):
    """Closest (or any, with ``any_hit``) triangle hit in (tmin, tmax],
    skipping scene triangle ``skip``: (t, scene triangle id or -1).
    ``stack``: scratch of STACK node indices."""
    ix, iy, iz = 1.0 / d[0], 1.0 / d[1], 1.0 / d[2]
    stack[0] = 0
    sp = 1
    best, who = tmax, -1
    while sp > 0:
        sp -= 1
        k = stack[sp]
        if not _box(o, ix, iy, iz, lo, hi, k, tmin, best):
            continue
        if leaf[k]:
            for j in range(child[k, 0], child[k, 0] + child[k, 1]):
                if ids[j] == skip:
                    continue
                t = _tri(o, d, v0[j], e1[j], e2[j])
                if t > tmin and t <= best and t < np.inf:
                    best, who = t, ids[j]
                    if any_hit:
                        return best, who
        else:
            stack[sp] = child[k, 0]
            stack[sp + 1] = child[k, 1]
            sp += 2
    return best, who


@numba.njit(parallel=True, **_JIT)
def _closest(orig, dirs, tmin, tmax, v0, e1, e2, ids, lo, hi, child, leaf):
    n = len(orig)
    t_out = np.full(n, np.inf)
    id_out = np.full(n, -1, np.int64)
    for i in numba.prange(n):
        stack = np.empty(STACK, np.int64)
        t, w = _trace(orig[i], dirs[i], tmin[i], tmax[i], -1, False, stack,
                      v0, e1, e2, ids, lo, hi, child, leaf)
        if w >= 0:
            t_out[i], id_out[i] = t, w
    return t_out, id_out


@numba.njit(parallel=True, **_JIT)
def _blocked(points, dirs, tmax, skip, v0, e1, e2, ids, lo, hi, child, leaf):
    n = len(points)
    out = np.zeros(n, np.bool_)
    for i in numba.prange(n):
        p = points[i]
        eps = EPS_REL * max(1.0, math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2))
        _, w = _trace(p, dirs[i], eps, tmax[i], skip[i], True, np.empty(STACK, np.int64),
                      v0, e1, e2, ids, lo, hi, child, leaf)
        out[i] = w >= 0
    return out


@numba.njit(**_JIT)
def _sphere_in_cone(p, axis, sin_a, cos_a, c, r):
    """A sphere meets the half-cone if it holds the apex or its angular
    distance from the axis is below a + asin(r / |c - p|)."""
    vx, vy, vz = c[0] - p[0], c[1] - p[1], c[2] - p[2]
    dist = math.sqrt(vx * vx + vy * vy + vz * vz)
    if dist <= r:
        return True
    cos_t = (vx * axis[0] + vy * axis[1] + vz * axis[2]) / dist
    sin_s = r / dist
    cos_s = math.sqrt(1.0 - sin_s * sin_s)
    # inside when theta <= a + s, i.e. cos(theta) >= cos(a + s) (a + s <= pi)
    return cos_t >= cos_a * cos_s - sin_a * sin_s


@numba.njit(**_JIT)
def _hash01(a, b):
    """splitmix64 of (a, b) -> uniform [0, 1)."""
    x = np.uint64(a) * np.uint64(0x9E3779B97F4A7C15) + np.uint64(b) + np.uint64(0x632BE59BD9B4E019)
    x = (x ^ (x >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    x = (x ^ (x >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    x = x ^ (x >> np.uint64(31))
    return float(x >> np.uint64(11)) * (1.0 / 9007199254740992.0)


@numba.njit(**_JIT)
def concentric(a, b):
    """Shirley-Chiu concentric map of the square [-1, 1]^2 to the unit disc."""
    if a == 0.0 and b == 0.0:
        return 0.0, 0.0
    if abs(a) > abs(b):
        r, phi = a, (math.pi / 4) * (b / a)
    else:
        r, phi = b, math.pi / 2 - (math.pi / 4) * (a / b)
    return r * math.cos(phi), r * math.sin(phi)


@numba.njit(**_JIT)
def _collect(p, axis, sin_a, cos_a, skip, own, ids, mesh, lo, hi, child, leaf, centre, radius,
             out):
    """The BVH slots of the triangles whose bounding sphere meets the cone
    (apex p, unit axis, half-angle a): their count, or -1 when there are
    more than ``out`` holds.  Left out: triangle ``skip`` and the triangles
    of mesh ``own`` (the point's mesh when it is convex: a ray leaving a
    facet of a convex solid on its outer side never meets the solid again)."""
    stack = np.empty(STACK, np.int64)
    stack[0] = 0
    sp, n = 1, 0
    while sp > 0:
        sp -= 1
        k = stack[sp]
        if leaf[k]:
            for j in range(child[k, 0], child[k, 0] + child[k, 1]):
                if ids[j] != skip and mesh[j] != own and _sphere_in_cone(
                        p, axis, sin_a, cos_a, centre[j], radius[j]):
                    if n == len(out):
                        return -1
                    out[n] = j
                    n += 1
            continue
        c = 0.5 * (lo[k] + hi[k])
        r = 0.5 * math.sqrt((hi[k, 0] - lo[k, 0]) ** 2 + (hi[k, 1] - lo[k, 1]) ** 2
                            + (hi[k, 2] - lo[k, 2]) ** 2)
        if _sphere_in_cone(p, axis, sin_a, cos_a, c, r):
            stack[sp] = child[k, 0]
            stack[sp + 1] = child[k, 1]
            sp += 2
    return n


@numba.njit(**_JIT)
def _sample_blocked(p, d, eps, skip, cand, nc, stack, v0, e1, e2, ids, lo, hi, child, leaf):
    """Any hit along the shadow ray: against the cone's candidates, or the
    whole hierarchy when there were too many (nc < 0)."""
    if nc < 0:
        _, who = _trace(p, d, eps, np.inf, skip, True, stack, v0, e1, e2, ids, lo, hi, child,
                        leaf)
        return who >= 0
    for m in range(nc):
        j = cand[m]
        t = _tri(p, d, v0[j], e1[j], e2[j])
        if t > eps and t < np.inf:
            return True
    return False


@numba.njit(**_JIT)
def _level(p, n, skip, L, u, w, rad, k, seed, cand, nc, v0, e1, e2, ids, lo, hi, child, leaf):
    """One stratified level of k x k samples: (visible fraction, diffuse
    integral E[max(N.Ls, 0) vis])."""
    eps = EPS_REL * max(1.0, math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2))
    d = np.empty(3)
    stack = np.empty(STACK, np.int64)
    vis = 0.0
    dif = 0.0
    for s in range(k * k):
        a = ((s % k) + _hash01(seed, 2 * s)) / k * 2.0 - 1.0
        b = ((s // k) + _hash01(seed, 2 * s + 1)) / k * 2.0 - 1.0
        x, y = concentric(a, b)
        for c in range(3):
            d[c] = L[c] + rad * (x * u[c] + y * w[c])
        d /= math.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
        nl = n[0] * d[0] + n[1] * d[1] + n[2] * d[2]
        if nl <= 0.0:
            continue
        if nc != 0 and _sample_blocked(p, d, eps, skip, cand, nc, stack, v0, e1, e2, ids, lo,
                                       hi, child, leaf):
            continue
        vis += 1.0
        dif += nl
    return vis / (k * k), dif / (k * k)


@numba.njit(parallel=True, **_JIT)
def _soft(points, normals, skip, own, L, u, w, rad, tol, v0, e1, e2, ids, lo, hi, child, leaf,
          mesh, centre, radius):
    n = len(points)
    frac = np.zeros(n)
    diff = np.zeros(n)
    level = np.zeros(n, np.int64)
    half = math.atan(rad)
    sin_a, cos_a = math.sin(half), math.cos(half)
    for i in numba.prange(n):
        if skip[i] < 0:
            continue
        p = points[i]
        cand = np.empty(MAX_CANDIDATES, np.int64)
        nc = _collect(p, L, sin_a, cos_a, skip[i], own[i], ids, mesh, lo, hi, child, leaf, centre,
                      radius, cand)
        kmin = 4 if nc == 0 else 16
        prev = -1.0
        k, lg = 4, 2
        while True:
            f, dd = _level(p, normals[i], skip[i], L, u, w, rad, k, i * 8 + lg, cand, nc,
                           v0, e1, e2, ids, lo, hi, child, leaf)
            if (k >= kmin and abs(f - prev) <= tol) or k >= 64:
                break
            prev = f
            k *= 2
            lg += 1
        frac[i], diff[i], level[i] = f, dd, k
    return frac, diff, level


# ---------------------------------------------------------------------------
@dataclass
class Reference:
    """What the eye sees and where the light reaches, per pixel (rows bottom
    first, as lrectread returns them)."""
    width: int
    height: int
    tri: np.ndarray         # (h, w) visible triangle, -1 background
    point: np.ndarray       # (h, w, 3) the visible point
    facing: np.ndarray      # (h, w) its triangle faces the light (N.L > 0)
    lit: np.ndarray         # (h, w) the light reaches it (facing and unblocked)
    image: np.ndarray       # (h, w, 3) float64 0..255, hard shadows
    soft_fraction: np.ndarray = None    # (h, w) visible fraction of the area light
    soft_image: np.ndarray = None
    soft_levels: np.ndarray = None      # k of the converged level (0 background)

    @property
    def visible(self):
        return self.tri >= 0


def _bvh_args(b):
    return (b.v0, b.e1, b.e2, b.ids, b.lo, b.hi, b.child, b.leaf)


def shade(scene, tri, diffuse_term):
    """The shading model per pixel: 255 * clamp(Am*A + Dm*diffuse_term)."""
    f = scene.flat()
    t = np.maximum(tri, 0)
    c = f["ambient"][t] * scene.model_ambient + f["diffuse"][t] * diffuse_term[..., None]
    c = 255.0 * np.clip(c, 0.0, 1.0)
    c[tri < 0] = 0.0
    return c


def visible_surface(scene, width, height, bvh=None):
    """Eye rays -> (visible triangle (h, w), visible point (h, w, 3))."""
    bvh = bvh or build_bvh(scene.flat()["corners"])
    o, d, tmin, tmax = eye_rays(scene.view, width, height)
    t, tri = _closest(o, d, tmin, tmax, *_bvh_args(bvh))
    p = o + np.where(tri >= 0, t, 0.0)[:, None] * d
    return tri.reshape(height, width), p.reshape(height, width, 3)


def hard_lit(scene, tri, point, light, bvh):
    """Light reaches each point (facing and unblocked) for a light given
    homogeneously: w = 0 a direction towards it, w = 1 a position."""
    f = scene.flat()
    tri, p = tri.reshape(-1), point.reshape(-1, 3)
    light = np.asarray(light, float)
    if light[3] == 0.0:
        d = np.broadcast_to(light[:3] / np.linalg.norm(light[:3]), p.shape).copy()
        tmax = np.full(len(p), np.inf)
    else:
        d = light[:3] - p
        tmax = np.linalg.norm(d, axis=1)
        d /= np.maximum(tmax, 1e-300)[:, None]
        tmax = tmax * (1.0 - EPS_REL)
    ndotl = (f["normals"][np.maximum(tri, 0)] * d).sum(axis=1)
    facing = (tri >= 0) & (ndotl > 0)
    blocked = _blocked(p, d, tmax, tri, *_bvh_args(bvh))
    return facing, facing & ~blocked, np.where(facing, ndotl, 0.0)


def shadow_bvh(scene, elevation_margin):
    """The hierarchy the shadow rays are cast against: the casters only,
    when no shadow ray can meet the ground (every visible point is on or
    above it and every light direction, widened by ``elevation_margin``
    radians for an area light, points upwards); the whole scene otherwise."""
    f = scene.flat()
    L = scene.light_dir
    upward = scene.light[3] == 0.0 and math.asin(L[1]) > elevation_margin
    keep = ~f["ground"] if upward else np.ones(len(f["ground"]), bool)
    b = build_bvh(f["corners"][keep])
    b.ids = np.flatnonzero(keep)[b.ids]
    return b


def compute(scene, width, height, soft=True):
    """The reference of a scene at an image size (hard, and soft if asked)."""
    tri, point = visible_surface(scene, width, height)
    margin = math.atan(scene.light_radius) if soft else 0.0
    sbvh = shadow_bvh(scene, margin)
    facing, lit, ndotl = hard_lit(scene, tri, point, scene.light, sbvh)
    shape = (height, width)
    ref = Reference(width, height, tri, point, facing.reshape(shape), lit.reshape(shape),
                    shade(scene, tri, (ndotl * lit).reshape(shape)))
    if soft:
        frac, diff, level = soft_visibility(scene, tri, point, sbvh)
        ref.soft_fraction, ref.soft_levels = frac, level
        ref.soft_image = shade(scene, tri, diff)
    return ref


def soft_visibility(scene, tri, point, bvh):
    """Visible fraction of the area light, diffuse integral and the
    converged level k per pixel."""
    L = scene.light_dir
    u, w = disc_basis(L)
    f = scene.flat()
    t = tri.reshape(-1)
    convex = np.array([m.convex for m in scene.meshes])
    own = np.where(convex[f["mesh"][np.maximum(t, 0)]], f["mesh"][np.maximum(t, 0)], -1)
    frac, diff, level = _soft(point.reshape(-1, 3), f["normals"][np.maximum(t, 0)], t, own,
                              L, u, w, float(scene.light_radius), SOFT_TOL, *_bvh_args(bvh),
                              f["mesh"][bvh.ids], bvh.centre, bvh.radius)
    return frac.reshape(tri.shape), diff.reshape(tri.shape), level.reshape(tri.shape)
