"""Triangle setup and the triangle walker (the polygon/edge/span processors).

``setup_triangles`` runs once per batch: orientation, backface/frontface
culling, CCW ordering, integer edge equations with the fill rule
(:mod:`scan.fixed`), bounding box clipped to the scissor, 1/area.

``triangle_kernel(key)`` returns the walker compiled for one raster state
(:mod:`raster.variants`).  It runs over framebuffer bands of
``config.BAND_ROWS`` rows on several threads (``run_bands``: the compiled
walker releases the GIL); each band walks every triangle that overlaps it
in submission order, so a pixel sees its triangles in the order they were
drawn whatever the thread count.  Bands are handed out interleaved
(``band_starts``) so that both threads get work when a scene fills only
part of the window.

Per triangle row the walker solves the three integer edge inequalities for
the exact span of covered pixels, so the fill rule is decided per row, not
per pixel: each edge's floor quotient is divided once per triangle and band
and then stepped row to row with its remainder (``edge_dda``/``edge_step``,
exact integers, no rounding).  Along the
span (the span processor):

* z is a fixed-point plane: per triangle, its value at the box corner pixel
  is evaluated in float64 from the exact edge values there and converted
  to ``ZFRAC`` fractional bits, with fixed-point steps per pixel and per
  row (``plane_fixed``); a span starts at ``ref + dy * sy + dx * sx`` (two
  integer multiplies, no float work per row) and steps by sx along x.
  Rounding to the stored integer is ``floor(z + 1/2)`` (docs/semantics.md §5).  The
  error is below 2**-16 of a z unit anywhere in a scissored box.  A
  pixel's z depends only on its triangle and position, never on the band,
  span or thread, so multipass algorithms that redraw the same triangles
  with ZF_EQUAL get the same z in every pass.  A sliver whose plane does
  not fit int64 over its box (plane_fixed) evaluates each span start
  exactly instead.
* spans that cannot pass the z test are skipped against the z bank's
  per-segment maxima when that changes nothing (framebuffer/zmax.py).
* Gouraud colours are the same planes with ``CFRAC`` bits; flat colour is
  one packed word per triangle (the provoking vertex).
* textured triangles compute barycentric weights per pixel in float64
  (texture coordinates perspective-correct: s/w, t/w and 1/w interpolated,
  then divided), sample and apply the texture environment
  (raster/texture.py); their z is the same plane as untextured ones.

Each pixel then goes through the stages of the variant
(:func:`raster.fragment.stage_function`), a pure function written without
branches on runtime state; the walker loads and stores the row views
around it, so the span loop of the common variants (z test and write,
stencil counting, plain colour writes) compiles to SIMD code.  A span shorter than ``config.PAD_SPAN`` runs over a whole number
of vectors (``VEC`` pixels): the extra pixels of the row fail like a 0
pattern bit, so that short spans pay no scalar remainder loop.
"""
import functools
import itertools
import math
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np

from .. import config
from ..jit import add32, helper, kernel, sra32
from ..raster import fragment
from ..raster import texture as _tex
from ..raster.blend import key_terms
from ..framebuffer.zmax import SEGMENT_SHIFT as ZSEG_SHIFT
from .fixed import SHIFT, edge_coefficients, owns_edge

ZFRAC, CFRAC = config.ZFRAC, config.CFRAC
#: their fixed-point ones as floats: the scale to_fixed and plane_fixed
#: take (a float, so that numba compiles each helper once, not once per
#: literal number of bits)
ZONE = float(1 << ZFRAC)
CONE = float(1 << CFRAC)

CULL_NONE, CULL_BACK, CULL_FRONT, CULL_BOTH = 0, 1, 2, 3


def _make_setup():
    @kernel
    def setup_kernel(X, Y, tris, cull, sx0, sx1, sy0, sy1, out):
        """Fill ``out`` (setup_triangles) for the triangles."""
        edges, verts, box, inv_area, back, valid = out
        for i in range(tris.shape[0]):
            a = tris[i, 0]
            b = tris[i, 1]
            c = tris[i, 2]
            area = (X[b] - X[a]) * (Y[c] - Y[a]) - (Y[b] - Y[a]) * (X[c] - X[a])
            if area == 0:
                continue
            is_back = area < 0          # clockwise on the screen (backface(3G))
            if is_back and (cull & 1):
                continue
            if (not is_back) and (cull & 2):
                continue
            if is_back:
                b, c = c, b
                area = -area
            verts[i, 0] = a
            verts[i, 1] = b
            verts[i, 2] = c
            # edge k opposite vertex k: (b->c), (c->a), (a->b)
            e0 = edge_coefficients(X[b], Y[b], X[c], Y[c])
            e1 = edge_coefficients(X[c], Y[c], X[a], Y[a])
            e2 = edge_coefficients(X[a], Y[a], X[b], Y[b])
            edges[i, 0, 0] = e0[0]
            edges[i, 0, 1] = e0[1]
            edges[i, 0, 2] = e0[2]
            edges[i, 1, 0] = e1[0]
            edges[i, 1, 1] = e1[1]
            edges[i, 1, 2] = e1[2]
            edges[i, 2, 0] = e2[0]
            edges[i, 2, 1] = e2[1]
            edges[i, 2, 2] = e2[2]
            xmin = min(X[a], min(X[b], X[c]))
            xmax = max(X[a], max(X[b], X[c]))
            ymin = min(Y[a], min(Y[b], Y[c]))
            ymax = max(Y[a], max(Y[b], Y[c]))
            # pixels whose centre can lie inside: ceil(min), floor(max)
            x0 = max((xmin + (1 << SHIFT) - 1) >> SHIFT, sx0)
            x1 = min(xmax >> SHIFT, sx1)
            y0 = max((ymin + (1 << SHIFT) - 1) >> SHIFT, sy0)
            y1 = min(ymax >> SHIFT, sy1)
            if x0 > x1 or y0 > y1:
                continue
            box[i, 0] = x0
            box[i, 1] = x1
            box[i, 2] = y0
            box[i, 3] = y1
            inv_area[i] = 1.0 / area
            back[i] = is_back
            valid[i] = True

    return setup_kernel


_setup_kernel = _make_setup()


def setup_triangles(X, Y, tris, cull, sx0, sx1, sy0, sy1):
    """Edge equations and boxes for T triangles.

    Returns (edges (T, 3, 3) int64, verts (T, 3) int64 in CCW order, box
    (T, 4) int64 [x0, x1, y0, y1] in pixels, inv_area (T,), back (T,) bool,
    valid (T,) bool); culled, degenerate and off-scissor triangles are not
    valid.  Edge k is opposite vertex k, so E_k / area is the barycentric
    weight of vertex k.  (The arrays are made here, not in the kernel: with
    an empty cache numba's np.zeros in a kernel costs its own compile.)"""
    t = len(tris)
    out = (np.zeros((t, 3, 3), np.int64), np.zeros((t, 3), np.int64),
           np.zeros((t, 4), np.int64), np.zeros(t), np.zeros(t, bool), np.zeros(t, bool))
    _setup_kernel(X, Y, tris, cull, sx0, sx1, sy0, sy1, out)
    return out

_kernels = {}


def triangle_kernel(key):
    """The walker for one raster key (see raster.variants.RasterKey), as a
    callable over every band (run_bands)."""
    k = _kernels.get(key)
    if k is None:
        k = _kernels[key] = functools.partial(run_bands, _make_triangle_kernel(*key))
    return k


@helper
def edge_dda(A, c, S):
    """Start of an edge's exact row walk.  The pixels x of a row with
    ``A * (x << SHIFT) + c >= 0`` are x >= -(c // D) (A > 0) or
    x <= c // D (A < 0), D = |A| << SHIFT; A = 0: every x when c >= 0.
    Returns (q, m, D, sq, sm): q = c // D, m = c - q * D (0 <= m < D), and
    the same of the per-row step S = B << SHIFT, so that each next row's
    quotient is two additions and a compare (edge_step), not a division."""
    D = (A if A > 0 else -A) << SHIFT
    if D == 0:
        D = 1                   # A = 0: q is c itself
    q = c // D
    sq = S // D
    return q, c - q * D, D, sq, S - sq * D


@helper
def edge_step(q, m, D, sq, sm):
    """(c + S) // D and its remainder from those of c and S."""
    q += sq
    m += sm
    if m >= D:
        m -= D
        q += 1
    return q, m


@helper
def edge_clip(A, q, xl, xr):
    """Narrow [xl, xr] to one edge's covered pixels of the row (q = c // D,
    see edge_dda).  Exact integer arithmetic: the fill rule's bias is in C."""
    if A > 0:
        xl = max(xl, -q)
    elif A < 0:
        xr = min(xr, q)
    elif q < 0:
        xr = xl - 1
    return xl, xr


@helper
def to_fixed(v, one):
    """float -> int64 in fixed point whose one is ``one`` (2**bits; ZONE,
    CONE), rounded to nearest; 0 for steps too large to matter (a span of
    such a triangle is one pixel)."""
    f = v * one
    if not (abs(f) < 4.0e18):
        return np.int64(0)
    return np.int64(math.floor(f + 0.5))


VEC = config.VEC
PLANE_LIMIT = config.PLANE_LIMIT


@helper
def plane_fixed(v0, dvb, dvc, wb, wc, dwb, dwc, dwby, dwcy, one, width, height):
    """A linear attribute ``v0 + dvb * wb + dvc * wc`` (wb, wc: barycentric
    weights of vertices b and c at a reference pixel, the corner of a box of
    width x height pixels) in fixed point whose one is ``one``: (value at the
    reference, step per pixel in x, step per row, ok).  ok is False when the
    plane does not fit PLANE_LIMIT over the box (a degenerate sliver): the
    caller then evaluates each span start exactly."""
    ref = (v0 + dvb * wb + dvc * wc) * one
    sx = (dvb * dwb + dvc * dwc) * one
    sy = (dvb * dwby + dvc * dwcy) * one
    if not (abs(ref) + abs(sx) * width + abs(sy) * height < PLANE_LIMIT):
        return np.int64(0), np.int64(0), np.int64(0), False
    return (np.int64(math.floor(ref + 0.5)), np.int64(math.floor(sx + 0.5)),
            np.int64(math.floor(sy + 0.5)), True)


@functools.lru_cache(maxsize=64)
def band_starts(sy0, sy1):
    """First rows of the bands of rows sy0..sy1, in the order the threads
    take them: a stride coprime with the band count near half of it, so
    that each thread's contiguous share of the list is spread over the
    whole window (load balance), while every band is still drawn exactly
    once."""
    nbands = (sy1 - sy0 + config.BAND_ROWS) // config.BAND_ROWS
    stride = nbands // 2 + 1
    while math.gcd(stride, nbands) != 1:
        stride += 1
    order = (np.arange(nbands) * stride) % nbands
    return sy0 + order * config.BAND_ROWS


_pool = None


def run_bands(walk, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax):
    """Run a compiled walker over every band: the band_starts list cut into
    config.SHARES_PER_THREAD shares per thread, which ``numba.get_num_threads()``
    threads (this one and the others of a thread pool; the walker releases
    the GIL) take in turn until none is left; small batches run on this
    thread alone.  Each band is drawn by one
    thread in submission order, so the pixels do not depend on the number
    of threads or on which thread took which share.  Python threads rather
    than a numba ``prange``: numba's parallel lowering doubled the walker's
    compile time (cold start)."""
    global _pool
    bands = band_starts(int(ip[fragment.P_SY0]), int(ip[fragment.P_SY1]))
    n = min(numba.get_num_threads(), len(bands)) if config.PARALLEL else 1
    if n > 1:
        # a batch whose triangle boxes cover fewer than PARALLEL_MIN_PIXELS
        # pixels runs on this thread alone: waking the others costs more
        # than they save, and when another process holds the other core
        # the batch waits for it (measured: Heidmann's 36 small lit-pass
        # batches took 246 ms on two threads on a busy machine, 45 ms on one)
        box, valid = setup[2], setup[5]
        area = ((box[:, 1] - box[:, 0] + 1) * (box[:, 3] - box[:, 2] + 1))[valid].sum()
        if area < config.PARALLEL_MIN_PIXELS:
            n = 1
    if n <= 1:
        walk(bands, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax)
        return
    if _pool is None or _pool._max_workers < n - 1:
        _pool = ThreadPoolExecutor(max_workers=max(n - 1, 1), thread_name_prefix="vgx-band")
    shares = np.array_split(bands, min(n * config.SHARES_PER_THREAD, len(bands)))
    taken = itertools.count()       # next() is atomic under the GIL

    def worker():
        k = next(taken)
        while k < len(shares):
            walk(shares[k], setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax)
            k = next(taken)

    jobs = [_pool.submit(worker) for _ in range(n - 1)]
    worker()
    for job in jobs:
        # a pool thread the OS has not run yet has no share left to take:
        # cancel it rather than wait a time slice for it (on a busy machine
        # that wait cost more than the second thread saved: Heidmann fig. 6
        # 715 ms a frame against 156 ms on one thread)
        if not job.cancel():
            job.result()


def _make_triangle_kernel(ztest, zwrite, color, gouraud, cmode, twoside,
                          stencil, blend, logic, atest, pattern, cmask, texture, dual):
    key = (ztest, zwrite, color, gouraud, cmode, twoside, stencil, blend, logic, atest,
           pattern, cmask, texture, dual)
    stages = fragment.stage_function(ztest, zwrite, stencil, blend, logic, atest, cmask, cmode)
    bterms = key_terms(blend)          # the blend factors of a folded pair
    band_rows = config.BAND_ROWS
    zhalf = 1 << (ZFRAC - 1)
    chalf = 1 << (CFRAC - 1)
    interp = gouraud and color and not texture
    cmax = 0xFFF if cmode else 255
    pad = not texture

    @kernel(variant=key)
    def walk(bands, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax):
        """Rows of every triangle in the bands starting at rows ``bands``
        (run_bands), in submission order."""
        edges, verts, box, inv_area, back, valid = setup
        texels, tinfo, tsel, tp = tex
        cb0, cb1, zb, sb, pat = planes
        prm = fragment.params(ip)
        bt = fragment.blend_terms(blend, bterms, prm)
        npat = prm[fragment.P_PATSIZE]
        orgx = prm[fragment.P_ORGX]
        orgy = prm[fragment.P_ORGY]
        zlo = prm[fragment.P_ZLO]
        zhi = prm[fragment.P_ZHI]
        zlo32 = np.int32(zlo)
        zhi32 = np.int32(zhi)
        sy1 = prm[fragment.P_SY1]
        skip = ztest and prm[fragment.P_ZMAX] != 0
        padspan = prm[fragment.P_PADSPAN]
        cr0_dummy = cb0[0]
        cr1_dummy = cb1[0]
        zr_dummy = zb[0]
        sr_dummy = sb[0]
        # the row length the padded spans stay inside (0: no padding)
        wid = zb.shape[1] if ztest else (cb0.shape[1] if color else
                                         (sb.shape[1] if stencil else 0))
        for ylo in bands:
            yhi = min(ylo + band_rows - 1, sy1)
            for i in range(valid.shape[0]):
                if not valid[i]:
                    continue
                y0 = max(box[i, 2], ylo)
                y1 = min(box[i, 3], yhi)
                if y0 > y1:
                    continue
                a = verts[i, 0]
                b = verts[i, 1]
                c = verts[i, 2]
                ia = inv_area[i]
                cols = CB if (twoside and back[i]) else C
                A0 = edges[i, 0, 0]
                B0 = edges[i, 0, 1]
                C0 = edges[i, 0, 2]
                A1 = edges[i, 1, 0]
                B1 = edges[i, 1, 1]
                C1 = edges[i, 1, 2]
                A2 = edges[i, 2, 0]
                B2 = edges[i, 2, 1]
                C2 = edges[i, 2, 2]
                # unbiased offsets for the weights (the fill bias is 0 or -1)
                o0 = 0 if owns_edge(X[b], Y[b], X[c], Y[c]) else 1
                o1 = 0 if owns_edge(X[c], Y[c], X[a], Y[a]) else 1
                o2 = 0 if owns_edge(X[a], Y[a], X[b], Y[b]) else 1
                # per-pixel and per-row steps of the barycentric weights of b
                # and c, and the weights at the box corner pixel (xb, yb)
                step = float(1 << SHIFT) * ia
                dwb = A1 * step
                dwc = A2 * step
                dwby = B1 * step
                dwcy = B2 * step
                xb = box[i, 0]
                yb = box[i, 2]
                wbr = (A1 * (xb << SHIFT) + B1 * (yb << SHIFT) + C1 + o1) * ia
                wcr = (A2 * (xb << SHIFT) + B2 * (yb << SHIFT) + C2 + o2) * ia
                za = Z[a]
                zba = Z[b] - za
                zca = Z[c] - za
                bw = box[i, 1] - xb + 1
                bh = box[i, 3] - yb + 1
                zref, dz, dzy, zok = plane_fixed(za, zba, zca, wbr, wcr, dwb, dwc,
                                                 dwby, dwcy, ZONE, bw, bh)
                if not zok:
                    dz = to_fixed(zba * dwb + zca * dwc, ZONE)
                # flat colour: the provoking vertex
                pv = prov[i]
                word = fragment.colour_word(cmode, cols[pv, 0], cols[pv, 1],
                                            cols[pv, 2], cols[pv, 3])
                dr = dg = db = da = np.int64(0)
                rref = gref = bref = aref = np.int64(0)
                dry = dgy = dby = day = np.int64(0)
                cok = False
                if interp:
                    ra = cols[a, 0]
                    ga = cols[a, 1]
                    ba = cols[a, 2]
                    aa = cols[a, 3]
                    rref, dr, dry, rok = plane_fixed(ra, cols[b, 0] - ra, cols[c, 0] - ra,
                                                     wbr, wcr, dwb, dwc, dwby, dwcy, CONE, bw, bh)
                    gref, dg, dgy, gok = plane_fixed(ga, cols[b, 1] - ga, cols[c, 1] - ga,
                                                     wbr, wcr, dwb, dwc, dwby, dwcy, CONE, bw, bh)
                    bref, db, dby, bok = plane_fixed(ba, cols[b, 2] - ba, cols[c, 2] - ba,
                                                     wbr, wcr, dwb, dwc, dwby, dwcy, CONE, bw, bh)
                    aref, da, day, aok = plane_fixed(aa, cols[b, 3] - aa, cols[c, 3] - aa,
                                                     wbr, wcr, dwb, dwc, dwby, dwcy, CONE, bw, bh)
                    cok = rok and gok and bok and aok
                    if not cok:
                        dr = to_fixed((cols[b, 0] - ra) * dwb + (cols[c, 0] - ra) * dwc, CONE)
                        dg = to_fixed((cols[b, 1] - ga) * dwb + (cols[c, 1] - ga) * dwc, CONE)
                        db = to_fixed((cols[b, 2] - ba) * dwb + (cols[c, 2] - ba) * dwc, CONE)
                        da = to_fixed((cols[b, 3] - aa) * dwb + (cols[c, 3] - aa) * dwc, CONE)
                # per-pixel colour steps in int32: two covered pixels of a row
                # differ by at most 0xFFF, so a step of a longer span fits
                dr32 = np.int32(dr)
                dg32 = np.int32(dg)
                db32 = np.int32(db)
                da32 = np.int32(da)
                tlevel = tsel[i] >> 1 if texture else 0
                tbil = (tsel[i] & 1) == 1 if texture else False
                # the edges' row values and their exact quotients, stepped per row
                py = y0 << SHIFT
                ev0 = B0 * py + C0
                ev1 = B1 * py + C1
                ev2 = B2 * py + C2
                S0 = B0 << SHIFT
                S1 = B1 << SHIFT
                S2 = B2 << SHIFT
                q0, m0, D0, sq0, sm0 = edge_dda(A0, ev0, S0)
                q1, m1, D1, sq1, sm1 = edge_dda(A1, ev1, S1)
                q2, m2, D2, sq2, sm2 = edge_dda(A2, ev2, S2)
                for y in range(y0, y1 + 1):
                    r0 = ev0
                    r1 = ev1
                    r2 = ev2
                    xl, xr = edge_clip(A0, q0, box[i, 0], box[i, 1])
                    xl, xr = edge_clip(A1, q1, xl, xr)
                    xl, xr = edge_clip(A2, q2, xl, xr)
                    ev0 += S0
                    ev1 += S1
                    ev2 += S2
                    q0, m0 = edge_step(q0, m0, D0, sq0, sm0)
                    q1, m1 = edge_step(q1, m1, D1, sq1, sm1)
                    q2, m2 = edge_step(q2, m2, D2, sq2, sm2)
                    if xl > xr:
                        continue
                    # row views of the banks the variant uses (the others are
                    # 1 x 1 dummies, viewed once per call)
                    cr0 = cb0[y] if color else cr0_dummy
                    cr1 = cb1[y] if (color and dual) else cr1_dummy
                    zr = zb[y] if ztest else zr_dummy
                    sr = sb[y] if stencil else sr_dummy
                    px = xl << SHIFT
                    # exact edge values at the span's first pixel
                    e0 = A0 * px + r0
                    e1 = A1 * px + r1
                    e2 = A2 * px + r2
                    # span start values: the fixed-point planes at (xl, y), or
                    # for a sliver outside their bounds the exact weights
                    ox = xl - xb
                    oy = y - yb
                    if zok:
                        z0 = zref + dzy * oy + dz * ox
                    else:
                        z0 = to_fixed(za + zba * ((e1 + o1) * ia) + zca * ((e2 + o2) * ia),
                                      ZONE)
                    cr = cg = cbl = ca = np.int64(0)
                    if interp:
                        if cok:
                            cr = rref + dry * oy + dr * ox
                            cg = gref + dgy * oy + dg * ox
                            cbl = bref + dby * oy + db * ox
                            ca = aref + day * oy + da * ox
                        else:
                            wb = (e1 + o1) * ia
                            wc = (e2 + o2) * ia
                            cr = to_fixed(cols[a, 0] + (cols[b, 0] - cols[a, 0]) * wb
                                          + (cols[c, 0] - cols[a, 0]) * wc, CONE)
                            cg = to_fixed(cols[a, 1] + (cols[b, 1] - cols[a, 1]) * wb
                                          + (cols[c, 1] - cols[a, 1]) * wc, CONE)
                            cbl = to_fixed(cols[a, 2] + (cols[b, 2] - cols[a, 2]) * wb
                                           + (cols[c, 2] - cols[a, 2]) * wc, CONE)
                            ca = to_fixed(cols[a, 3] + (cols[b, 3] - cols[a, 3]) * wb
                                          + (cols[c, 3] - cols[a, 3]) * wc, CONE)
                    # the DDAs start half a unit up so that >> rounds to nearest
                    zf = z0 + zhalf
                    if skip and zok:
                        # quantized z is monotonic along the span: its least
                        # value is at one end (zok: dz is bounded, no overflow)
                        zq_least = min(max(min(zf, zf + dz * (xr - xl)) >> ZFRAC, zlo), zhi)
                        zrow = zmax[y]
                        most = zrow[xl >> ZSEG_SHIFT]
                        for seg in range((xl >> ZSEG_SHIFT) + 1, (xr >> ZSEG_SHIFT) + 1):
                            most = max(most, zrow[seg])
                        if zq_least > most:
                            continue
                    # a span shorter than P_PADSPAN runs over whole vectors
                    # (config.PAD_SPAN): its loop ends late, or near the end of
                    # the row starts early, inside the row; the pixels outside
                    # [xl, xr] fail like a 0 pattern bit and store what they
                    # hold.  (Not for textures: their sampling needs the
                    # pixel inside the triangle.)
                    lo = xl
                    nv = xr + 1 - xl
                    if pad and nv < padspan:
                        nv = max((nv + VEC - 1) & -VEC, 2 * VEC)
                        if nv <= wid:
                            lo = min(xl, wid - nv)
                        else:
                            nv = xr + 1 - xl
                    early = xl - lo
                    kin0 = np.int32(early)
                    kin1 = np.int32(xr - lo)
                    zf -= dz * early
                    # colours step in int32 (CFRAC = 16 keeps 0xFFF << 16 inside
                    # it; numba widens int32 operations, hence the casts; the
                    # padding pixels may wrap, they are never stored)
                    r32 = np.int32(cr + chalf - dr * early)
                    g32 = np.int32(cg + chalf - dg * early)
                    b32 = np.int32(cbl + chalf - db * early)
                    a32 = np.int32(ca + chalf - da * early)
                    for k in range(nv):
                        x = lo + k
                        # truncated to int32 before the clamp (32-bit vector
                        # lanes): exact inside the triangle, whose z lies
                        # between its vertices' (|Z| < viewport.Z_LIMIT)
                        zq = min(max(np.int32(zf >> ZFRAC), zlo32), zhi32)
                        zf += dz
                        w = word
                        if interp:
                            ri = min(max(sra32(r32, CFRAC), np.int32(0)), np.int32(cmax))
                            r32 = add32(r32, dr32)
                            if cmode:
                                w = ri & 0xFFF
                            else:
                                gi = min(max(sra32(g32, CFRAC), np.int32(0)), np.int32(255))
                                bi = min(max(sra32(b32, CFRAC), np.int32(0)), np.int32(255))
                                ai = min(max(sra32(a32, CFRAC), np.int32(0)), np.int32(255))
                                g32 = add32(g32, dg32)
                                b32 = add32(b32, db32)
                                a32 = add32(a32, da32)
                                w = (ai << 24) | (bi << 16) | (gi << 8) | ri
                        if texture:
                            w0 = (e0 + o0) * ia
                            w1 = (e1 + o1) * ia
                            w2 = (e2 + o2) * ia
                            e0 += A0 << SHIFT
                            e1 += A1 << SHIFT
                            e2 += A2 << SHIFT
                            if gouraud:
                                r = w0 * cols[a, 0] + w1 * cols[b, 0] + w2 * cols[c, 0]
                                g = w0 * cols[a, 1] + w1 * cols[b, 1] + w2 * cols[c, 1]
                                bb = w0 * cols[a, 2] + w1 * cols[b, 2] + w2 * cols[c, 2]
                                al = w0 * cols[a, 3] + w1 * cols[b, 3] + w2 * cols[c, 3]
                            else:
                                r = cols[pv, 0]
                                g = cols[pv, 1]
                                bb = cols[pv, 2]
                                al = cols[pv, 3]
                            iw = w0 * TC[a, 2] + w1 * TC[b, 2] + w2 * TC[c, 2]
                            ts = (w0 * TC[a, 0] + w1 * TC[b, 0] + w2 * TC[c, 0]) / iw
                            tt = (w0 * TC[a, 1] + w1 * TC[b, 1] + w2 * TC[c, 1]) / iw
                            tr, tg, tb, ta = _tex.sample(texels, tinfo, tlevel, tbil,
                                                         ts, tt, tp[0] != 0, tp[1] != 0)
                            r, g, bb, al = _tex.environment(int(tp[2]), r, g, bb, al,
                                                            tr, tg, tb, ta,
                                                            tp[3], tp[4], tp[5])
                            w = fragment.colour_word(cmode, r, g, bb, al)
                        kk = np.int32(k)        # (an int32 test: 8 lanes)
                        patbit = np.int32((kk >= kin0) & (kk <= kin1)) if pad else np.int32(1)
                        if pattern:
                            patbit &= pat[(y + orgy) % npat, (x + orgx) % npat]
                        u = np.uint64(x)      # unsigned index: no wraparound test
                        zold = np.int32(zr[u]) if ztest else np.int32(0)
                        sold = np.int32(sr[u]) if stencil else np.int32(0)
                        c0 = np.int64(cr0[u]) if color else np.int64(0)
                        c1 = np.int64(cr1[u]) if (color and dual) else np.int64(0)
                        ok, zn, sn, n0, n1 = stages(patbit, zq, zold, sold, c0, c1,
                                                    w, bt, prm)
                        if stencil == 2:        # (1: the stencil is only tested)
                            sr[u] = sn
                        if zwrite:
                            zr[u] = zn
                        if color:
                            cr0[u] = n0
                            if dual:
                                cr1[u] = n1

    return walk
