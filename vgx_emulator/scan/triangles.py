"""Triangle setup and the triangle walker (the polygon/edge/span processors).

``setup_triangles`` runs once per batch: orientation, backface/frontface
culling, CCW ordering, integer edge equations with the fill rule
(:mod:`scan.fixed`), bounding box clipped to the scissor, 1/area, and the
fixed-point z and colour planes, one record row per triangle (the ``T_*``
columns).  The walker then only steps what setup computed.

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
exact integers, no rounding; ``span_bounds``).  Along the
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
  per-segment maxima when that changes nothing (``z_hidden``,
  framebuffer/zmax.py).
* Gouraud colours are the same planes with ``CFRAC`` bits, stepped in
  int32 (``colour_dda``, ``gouraud_word``); flat colour is one packed word
  per triangle (the provoking vertex).
* textured triangles compute barycentric weights per pixel in float64
  (texture coordinates perspective-correct: s/w, t/w and 1/w interpolated,
  then divided), sample and apply the texture environment
  (``texel_word``, raster/texture.py), in the texture variants only; their
  z is the same plane as untextured ones.

The walker (``_make_triangle_kernel``'s ``walk``) is a loop over bands,
triangles and rows that calls these pieces: ``edges_at_row``, ``row_span``
and ``next_row`` (the edges' exact row walk), ``z_start`` and
``colours_start`` (the planes at a span's first pixel), ``z_hidden`` (the
z-maxima skip), ``padded_span`` and the span processor ``span``, whose
texture sampling (``texel``) is compiled into the textured variants only.
The per-triangle planes come from setup (``triangle_planes``).

Each pixel then goes through the stages of the variant
(:func:`raster.fragment.stage_function`), a pure function written without
branches on runtime state; the walker loads and stores the row views
around it, so the span loop of the common variants (z test and write,
stencil counting, plain colour writes) compiles to SIMD code.  A span
shorter than ``config.PAD_SPAN`` runs over a whole number of vectors
(``VEC`` pixels; ``padded_span``): the extra pixels of the row fail like a
0 pattern bit, so that short spans pay no scalar remainder loop.  The
helpers called per pixel or per span with arrays are ``inline`` (numba
inlines them before compiling; a call would cost reference counting on
each array), the others ``helper``.
"""
import functools
import math
import sys
import threading

import numba
import numpy as np

from .. import config, pipeline
from ..jit import add32, helper, inline, kernel, sra32
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
#: half a unit of the colour DDAs (they start there so that >> rounds)
CHALF = 1 << (CFRAC - 1)

CULL_NONE, CULL_BACK, CULL_FRONT, CULL_BOTH = 0, 1, 2, 3

# The per-triangle integer record of setup_triangles, column by column.
T_VERTS = 0     # 3: vertices a, b, c in CCW order
T_BOX = 3       # 4: the box in pixels, x0, x1, y0, y1, clipped to the scissor
T_EDGES = 7     # 9: A, B, C of edges 0, 1, 2 (edge k is opposite vertex k)
T_OFFSET = 16   # 3: 0 when edge k owns its pixels (fill rule), else 1 (unbiased weights)
T_Z = 19        # 3: the z plane (ZFRAC bits) at the box corner, per pixel, per row
T_ZOK = 22      # 1: the z plane fits PLANE_LIMIT (else span starts are exact)
T_WORD = 23     # 1: the flat colour word (provoking vertex)
T_COLOUR = 24   # 12: r, g, b, a planes (CFRAC bits): corner, per pixel, per row
T_COK = 36      # 1: every colour plane fits (else span starts are exact)
T_BACK = 37     # 1: the triangle is back-facing (its colours are CB when two-sided)
T_COLUMNS = 38


def _make_setup():
    @kernel
    def setup_kernel(X, Y, Z, C, CB, prov, tris, cull, sx0, sx1, sy0, sy1, flags,
                     rec, inv_area, rows):
        """Fill ``rec``, ``inv_area`` and ``rows`` (setup_triangles).
        flags: (Gouraud planes wanted, colour-map mode, two-sided)."""
        interp = flags[0] != 0
        cmode = flags[1] != 0
        twoside = flags[2] != 0
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
            rec[i, T_VERTS] = a
            rec[i, T_VERTS + 1] = b
            rec[i, T_VERTS + 2] = c
            rec[i, T_BOX] = x0
            rec[i, T_BOX + 1] = x1
            rec[i, T_BOX + 2] = y0
            rec[i, T_BOX + 3] = y1
            # edge k opposite vertex k: (b->c), (c->a), (a->b)
            e = (edge_coefficients(X[b], Y[b], X[c], Y[c]),
                 edge_coefficients(X[c], Y[c], X[a], Y[a]),
                 edge_coefficients(X[a], Y[a], X[b], Y[b]))
            for k in range(3):
                rec[i, T_EDGES + 3 * k] = e[k][0]
                rec[i, T_EDGES + 3 * k + 1] = e[k][1]
                rec[i, T_EDGES + 3 * k + 2] = e[k][2]
            rec[i, T_OFFSET] = 0 if owns_edge(X[b], Y[b], X[c], Y[c]) else 1
            rec[i, T_OFFSET + 1] = 0 if owns_edge(X[c], Y[c], X[a], Y[a]) else 1
            rec[i, T_OFFSET + 2] = 0 if owns_edge(X[a], Y[a], X[b], Y[b]) else 1
            ia = 1.0 / area
            inv_area[i] = ia
            rec[i, T_BACK] = is_back
            rows[i, 0] = y0
            rows[i, 1] = y1
            triangle_planes(rec, i, X, Y, Z, CB if (twoside and is_back) else C, prov[i],
                            ia, interp, cmode)

    return setup_kernel


@inline
def triangle_planes(rec, i, X, Y, Z, cols, pv, ia, interp, cmode):
    """The fixed-point planes of one set-up triangle (row ``i`` of ``rec``): z and,
    when ``interp``, the four Gouraud colours, each as its value at the box
    corner pixel with its steps per pixel and per row (plane_fixed), from
    the barycentric weights of vertices b and c there; and the flat colour
    word of the provoking vertex ``pv``."""
    a = rec[i, T_VERTS]
    b = rec[i, T_VERTS + 1]
    c = rec[i, T_VERTS + 2]
    step = float(1 << SHIFT) * ia
    dwb = rec[i, T_EDGES + 3] * step
    dwc = rec[i, T_EDGES + 6] * step
    dwby = rec[i, T_EDGES + 4] * step
    dwcy = rec[i, T_EDGES + 7] * step
    xb = rec[i, T_BOX]
    yb = rec[i, T_BOX + 2]
    wbr = (rec[i, T_EDGES + 3] * (xb << SHIFT) + rec[i, T_EDGES + 4] * (yb << SHIFT)
           + rec[i, T_EDGES + 5] + rec[i, T_OFFSET + 1]) * ia
    wcr = (rec[i, T_EDGES + 6] * (xb << SHIFT) + rec[i, T_EDGES + 7] * (yb << SHIFT)
           + rec[i, T_EDGES + 8] + rec[i, T_OFFSET + 2]) * ia
    bw = rec[i, T_BOX + 1] - xb + 1
    bh = rec[i, T_BOX + 3] - yb + 1
    za = Z[a]
    zba = Z[b] - za
    zca = Z[c] - za
    zref, dz, dzy, zok = plane_fixed(za, zba, zca, wbr, wcr, dwb, dwc, dwby, dwcy, ZONE, bw, bh)
    if not zok:
        dz = to_fixed(zba * dwb + zca * dwc, ZONE)
    rec[i, T_Z] = zref
    rec[i, T_Z + 1] = dz
    rec[i, T_Z + 2] = dzy
    rec[i, T_ZOK] = zok
    rec[i, T_WORD] = fragment.colour_word(cmode, cols[pv, 0], cols[pv, 1], cols[pv, 2],
                                          cols[pv, 3])
    if not interp:
        for k in range(13):             # the colour planes and T_COK: unused, but defined
            rec[i, T_COLOUR + k] = 0
        return
    cok = True
    for k in range(4):
        ca = cols[a, k]
        ref, d, dy, ok = plane_fixed(ca, cols[b, k] - ca, cols[c, k] - ca,
                                     wbr, wcr, dwb, dwc, dwby, dwcy, CONE, bw, bh)
        rec[i, T_COLOUR + 3 * k] = ref
        rec[i, T_COLOUR + 3 * k + 1] = d
        rec[i, T_COLOUR + 3 * k + 2] = dy
        cok = cok and ok
    rec[i, T_COK] = cok
    if not cok:
        for k in range(4):
            ca = cols[a, k]
            rec[i, T_COLOUR + 3 * k + 1] = to_fixed(
                (cols[b, k] - ca) * dwb + (cols[c, k] - ca) * dwc, CONE)


_setup_kernel = _make_setup()


#: setup records of earlier batches, for the next ones to take once no pass
#: holds them any more (a display list replayed every frame, the passes of a
#: multipass frame: a new array faults its pages in again, 0.4 ms of a
#: 40k-triangle setup); a batch takes the first rows of the shortest free
#: one long enough.  At most _SPARE_BYTES are kept.
_spare = []
_spare_lock = threading.Lock()
_SPARE_BYTES = 48 << 20


def _records(t):
    """A (t, T_COLUMNS) int64 array for setup_triangles: the first rows of
    a kept one when nothing else refers to it, else a new one (kept)."""
    with _spare_lock:
        best = None
        for base in _spare:
            # the references of a free one: the list, ``base`` and
            # getrefcount's argument; a queued or running pass holding its
            # setup (a view of it) adds its own
            if len(base) >= t and sys.getrefcount(base) == 3 and \
                    (best is None or len(base) < len(best)):
                best = base
        if best is not None:
            return best[:t]
        rec = np.zeros((t, T_COLUMNS), np.int64)
        _spare.append(rec)
        total = sum(x.nbytes for x in _spare)
        for old in list(_spare[:-1]):           # the oldest first
            if total <= _SPARE_BYTES:
                break
            _spare.remove(old)
            total -= old.nbytes
        return rec


def setup_triangles(X, Y, Z, C, CB, prov, tris, cull, sx0, sx1, sy0, sy1,
                    interp=False, cmode=False, twoside=False):
    """Triangle setup for T triangles: (rec (T, T_COLUMNS) int64, inv_area
    (T,), rows (T, 2) int32: each triangle's first and last row, y0 > y1
    when it is not drawn).  ``rec`` holds, per the T_* columns, the CCW
    vertices, the box, the integer edge equations with the fill rule, and
    the fixed-point z and colour planes the walker steps (computed once per
    triangle, not once per band).  Culled, degenerate and off-scissor
    triangles have no rows.  Edge k is opposite vertex k, so E_k / area is
    the barycentric weight of vertex k.  (The arrays are made here, not in
    the kernel: with an empty cache numba's np.zeros in a kernel costs its
    own compile.)  A large batch is set up in shares on the thread pool of
    the walker (config.SETUP_SHARE) while the raster thread is idle.  The
    records of a drawn triangle are written whole; those of a triangle
    without rows are not read."""
    t = len(tris)
    rec = _records(t)
    inv_area = np.zeros(t)
    rows = np.empty((t, 2), np.int32)
    rows[:, 0], rows[:, 1] = 1, 0           # no row: culled, degenerate, off-scissor
    flags = np.array([interp, cmode, twoside], np.int64)

    def share(lo, hi):
        _setup_kernel(X, Y, Z, C, CB, prov[lo:hi], tris[lo:hi], cull, sx0, sx1, sy0, sy1,
                      flags, rec[lo:hi], inv_area[lo:hi], rows[lo:hi])
    pipeline.in_shares(share, t, config.SETUP_SHARE)
    return rec, inv_area, rows


def drawn(setup):
    """How many triangles of a setup_triangles result are drawn (valid)."""
    rows = setup[2]
    return int(np.count_nonzero(rows[:, 0] <= rows[:, 1]))

_kernels = {}
_walkers = {}


def walker(key):
    """The compiled walker of one raster key (see raster.variants.RasterKey):
    a numba dispatcher over a list of bands."""
    w = _walkers.get(key)
    if w is None:
        w = _walkers[key] = _make_triangle_kernel(*key)
    return w


def triangle_kernel(key):
    """The walker for one raster key, as a callable over every band
    (run_bands)."""
    k = _kernels.get(key)
    if k is None:
        k = _kernels[key] = functools.partial(run_bands, walker(key))
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
PAD_MIN = config.PAD_MIN
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


#: about this many triangles' boxes estimate a batch's area (run_bands)
AREA_SAMPLE = 1024


def run_bands(walk, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax):
    """Run a compiled walker over every band: the band_starts list cut into
    config.SHARES_PER_THREAD shares per thread, which the threads take in
    turn until none is left; small batches run on one thread.  On the
    raster thread (pipeline.py) the other thread is the program's, which
    helps only while it waits for the raster work (pipeline.shared);
    otherwise ``numba.get_num_threads()`` threads (this one and a thread
    pool's; the walker releases the GIL).  Each band is drawn by one thread
    in submission order, so the pixels do not depend on the number of
    threads or on which thread took which share.  Python threads rather
    than a numba ``prange``: numba's parallel lowering doubled the walker's
    compile time (cold start)."""
    bands = band_starts(int(ip[fragment.P_SY0]), int(ip[fragment.P_SY1]))
    raster_thread = pipeline.on_raster_thread()
    n = 1
    if config.PARALLEL:
        n = min((2 if pipeline.helper_waiting() else 1) if raster_thread else
                pipeline.num_threads(), len(bands))
    if n > 1:
        # a batch whose triangle boxes cover fewer than PARALLEL_MIN_PIXELS
        # pixels runs on this thread alone: waking the others costs more
        # than they save, and when another process holds the other core
        # the batch waits for it (measured: Heidmann's 36 small lit-pass
        # batches took 246 ms on two threads on a busy machine, 45 ms on one)
        # (estimated from every step-th triangle, about AREA_SAMPLE: the
        # boxes are columns of the wide setup records, and reading all of
        # them cost 0.5 ms a 40k-triangle batch; only the thread count
        # depends on it, never a pixel)
        rec, rows = setup[0], setup[2]
        step = max(1, len(rec) // AREA_SAMPLE)
        rec, rows = rec[::step], rows[::step]
        area = ((rec[:, T_BOX + 1] - rec[:, T_BOX] + 1) *
                np.maximum(rows[:, 1] - rows[:, 0] + 1, 0)).sum() * step
        if area < config.PARALLEL_MIN_PIXELS:
            n = 1
    if n <= 1:
        walk(bands, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax)
        return
    m = min(n * config.SHARES_PER_THREAD, len(bands))
    cuts = [len(bands) * j // m for j in range(m + 1)]

    def share(k):
        walk(bands[cuts[k]:cuts[k + 1]], setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax)

    if raster_thread:
        pipeline.shared(share, m)
        return
    pipeline.on_threads(share, m, n)


@helper
def span_bounds(A0, q0, A1, q1, A2, q2, xl, xr):
    """The covered pixels [xl, xr] of a row of the box [xl, xr]: the three
    edges' exact quotients for the row (edge_dda, edge_step); xl > xr when
    the row is empty."""
    xl, xr = edge_clip(A0, q0, xl, xr)
    xl, xr = edge_clip(A1, q1, xl, xr)
    return edge_clip(A2, q2, xl, xr)


@helper
def exact_start(v0, dvb, dvc, wb, wc, one):
    """A linear attribute at a span's first pixel from its exact weights wb,
    wc (a sliver whose plane does not fit int64, plane_fixed)."""
    return to_fixed(v0 + dvb * wb + dvc * wc, one)


@inline
def colour_dda(ref, d, dy, ox, oy, early, ok, va, vb, vc, wb, wc):
    """The int32 DDA of one Gouraud colour at the loop's first pixel, ``early``
    pixels before the span's first (padded_span), half a unit up so that
    ``>> CFRAC`` rounds: from the triangle's plane (ref at the box corner,
    steps d per pixel, dy per row; the span starts ox, oy from the corner)
    or, for a sliver whose plane does not fit (not ok), from the exact
    weights.  (The padding pixels may wrap; they are never stored.)"""
    v = ref + dy * oy + d * ox if ok else exact_start(va, vb - va, vc - va, wb, wc, CONE)
    return np.int32(v + CHALF - d * early)


@inline
def z_hidden(zf, dz, xl, xr, zlo, zhi, zrow):
    """True when no pixel of the span [xl, xr] can pass a LESS/LEQUAL z test:
    the span's least quantized z (at one end: z is monotonic along it) is
    above the maxima of every z segment it covers (framebuffer/zmax.py)."""
    least = min(max(min(zf, zf + dz * (xr - xl)) >> ZFRAC, zlo), zhi)
    most = zrow[xl >> ZSEG_SHIFT]
    for seg in range((xl >> ZSEG_SHIFT) + 1, (xr >> ZSEG_SHIFT) + 1):
        most = max(most, zrow[seg])
    return least > most


@helper
def padded_span(xl, xr, padspan, wid):
    """(first pixel, count) of the loop over the span [xl, xr]: a span of
    config.PAD_MIN pixels or more but shorter than ``padspan``
    (config.PAD_SPAN) runs over whole vectors of VEC pixels, at least two,
    inside a row of ``wid`` pixels: the loop ends late or, near the row's
    end, starts early.  The pixels outside [xl, xr] fail like a 0 pattern
    bit and store what they hold."""
    lo = xl
    nv = xr + 1 - xl
    if PAD_MIN <= nv < padspan:
        n = max((nv + VEC - 1) & -VEC, 2 * VEC)
        if n <= wid:
            return min(xl, wid - n), n
    return lo, nv


@inline
def gouraud_word(cmode, cmax, r32, g32, b32, a32):
    """The packed colour of a pixel from its colour DDAs (CFRAC bits),
    clamped: 0xAABBGGRR, or the index in colour-map mode."""
    ri = min(max(sra32(r32, CFRAC), np.int32(0)), np.int32(cmax))
    if cmode:
        return ri & 0xFFF
    gi = min(max(sra32(g32, CFRAC), np.int32(0)), np.int32(255))
    bi = min(max(sra32(b32, CFRAC), np.int32(0)), np.int32(255))
    ai = min(max(sra32(a32, CFRAC), np.int32(0)), np.int32(255))
    return (ai << 24) | (bi << 16) | (gi << 8) | ri


@inline
def texel_word(cmode, gouraud, w0, w1, w2, cols, a, b, c, pv, TC, tex, tlevel, tbil):
    """A textured pixel's colour word (texture(3G), tevdef(3G)): the
    texture coordinates interpolated perspective-correct from the
    barycentric weights w0, w1, w2 (s/w, t/w, 1/w, then divided), sampled
    (raster/texture.py) and combined with the pixel's Gouraud or flat
    colour by the environment."""
    texels, tinfo, tsel, tp = tex
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
    tr, tg, tb, ta = _tex.sample(texels, tinfo, tlevel, tbil, ts, tt, tp[0] != 0, tp[1] != 0)
    r, g, bb, al = _tex.environment(int(tp[2]), r, g, bb, al, tr, tg, tb, ta,
                                    tp[3], tp[4], tp[5])
    return fragment.colour_word(cmode, r, g, bb, al)


@inline
def edges_at_row(rec, i, y0):
    """Triangle i's three edges at row y0 (edge k is opposite vertex k):
    what stays fixed over its rows, (A0, A1, A2, S0, S1, S2, D0, D1, D2,
    sq0, sq1, sq2, sm0, sm1, sm2), and the row state, (ev0, ev1, ev2, q0,
    q1, q2, m0, m1, m2): each edge's value at the row's pixel x = 0 and its
    exact quotient DDA (edge_dda), for row_span and next_row."""
    A0, B0, C0 = rec[i, T_EDGES], rec[i, T_EDGES + 1], rec[i, T_EDGES + 2]
    A1, B1, C1 = rec[i, T_EDGES + 3], rec[i, T_EDGES + 4], rec[i, T_EDGES + 5]
    A2, B2, C2 = rec[i, T_EDGES + 6], rec[i, T_EDGES + 7], rec[i, T_EDGES + 8]
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
    return ((A0, A1, A2, S0, S1, S2, D0, D1, D2, sq0, sq1, sq2, sm0, sm1, sm2),
            (ev0, ev1, ev2, q0, q1, q2, m0, m1, m2))


@inline
def row_span(edge, row, bx0, bx1):
    """(xl, xr, e0, e1, e2): the covered pixels of the row within the box
    columns [bx0, bx1] (span_bounds; xl > xr: none) and the three exact
    edge values at its first pixel."""
    A0, A1, A2 = edge[0], edge[1], edge[2]
    ev0, ev1, ev2, q0, q1, q2 = row[0], row[1], row[2], row[3], row[4], row[5]
    xl, xr = span_bounds(A0, q0, A1, q1, A2, q2, bx0, bx1)
    px = xl << SHIFT
    return xl, xr, A0 * px + ev0, A1 * px + ev1, A2 * px + ev2


@inline
def next_row(edge, row):
    """The row state of edges_at_row one row up: the values step by S, the
    quotients by edge_step (two additions and a compare each)."""
    q0, m0 = edge_step(row[3], row[6], edge[6], edge[9], edge[12])
    q1, m1 = edge_step(row[4], row[7], edge[7], edge[10], edge[13])
    q2, m2 = edge_step(row[5], row[8], edge[8], edge[11], edge[14])
    return (row[0] + edge[3], row[1] + edge[4], row[2] + edge[5], q0, q1, q2, m0, m1, m2)


@inline
def z_start(zplane, Z, a, b, c, ox, oy, wb, wc):
    """The span's first z in ZFRAC bits, half a unit up (floor rounds):
    from the triangle's z plane (zref at the box corner, dz a pixel, dzy a
    row; the span starts ox, oy from the corner) or, for a sliver whose
    plane does not fit (plane_fixed), from the exact weights wb, wc."""
    zref, dz, dzy, zok = zplane
    if zok:
        return zref + dzy * oy + dz * ox + (1 << (ZFRAC - 1))
    return exact_start(Z[a], Z[b] - Z[a], Z[c] - Z[a], wb, wc, ZONE) + (1 << (ZFRAC - 1))


@inline
def colour_planes(rec, i):
    """Triangle i's r, g, b, a planes (corner, per pixel, per row; CFRAC
    bits) and whether every one fits (else span starts are exact)."""
    return ((rec[i, T_COLOUR], rec[i, T_COLOUR + 1], rec[i, T_COLOUR + 2]),
            (rec[i, T_COLOUR + 3], rec[i, T_COLOUR + 4], rec[i, T_COLOUR + 5]),
            (rec[i, T_COLOUR + 6], rec[i, T_COLOUR + 7], rec[i, T_COLOUR + 8]),
            (rec[i, T_COLOUR + 9], rec[i, T_COLOUR + 10], rec[i, T_COLOUR + 11]),
            rec[i, T_COK] != 0)


@inline
def colours_start(planes, ox, oy, early, cols, a, b, c, wb, wc):
    """The four int32 colour DDAs at the span loop's first pixel
    (colour_dda of each plane)."""
    pr, pg, pb, pa, ok = planes
    return (colour_dda(pr[0], pr[1], pr[2], ox, oy, early, ok, cols[a, 0], cols[b, 0],
                       cols[c, 0], wb, wc),
            colour_dda(pg[0], pg[1], pg[2], ox, oy, early, ok, cols[a, 1], cols[b, 1],
                       cols[c, 1], wb, wc),
            colour_dda(pb[0], pb[1], pb[2], ox, oy, early, ok, cols[a, 2], cols[b, 2],
                       cols[c, 2], wb, wc),
            colour_dda(pa[0], pa[1], pa[2], ox, oy, early, ok, cols[a, 3], cols[b, 3],
                       cols[c, 3], wb, wc))


def _make_triangle_kernel(ztest, zwrite, color, gouraud, cmode, twoside,
                          stencil, blend, logic, atest, pattern, cmask, texture, dual):
    key = (ztest, zwrite, color, gouraud, cmode, twoside, stencil, blend, logic, atest,
           pattern, cmask, texture, dual)
    stages = fragment.stage_function(ztest, zwrite, stencil, blend, logic, atest, cmask, cmode)
    bterms = key_terms(blend)          # the blend factors of a folded pair
    band_rows = config.BAND_ROWS
    interp = gouraud and color and not texture
    cmax = 0xFFF if cmode else 255
    pad = not texture       # texture sampling needs the pixel inside the triangle

    @inline
    def texel(k, textured):
        """The colour word of the span's k-th pixel of a textured triangle
        (texel_word), from the exact edge values ``e`` at the span's first
        pixel (no padding: x = xl + k)."""
        e, edge, off, ia, cols, a, b, c, pv, TC, tex, tlevel, tbil = textured
        sk = k << SHIFT
        return texel_word(cmode, gouraud, (e[0] + edge[0] * sk + off[0]) * ia,
                          (e[1] + edge[1] * sk + off[1]) * ia,
                          (e[2] + edge[2] * sk + off[2]) * ia,
                          cols, a, b, c, pv, TC, tex, tlevel, tbil)

    @inline
    def span(banks, y, lo, nv, kin0, kin1, zf, dz, zlo32, zhi32, word, dda, steps, prow,
             textured, bt, prm):
        """The span processor: pixels lo .. lo + nv - 1 of row y through
        the variant's stages (kin0 .. kin1 inside the span, the rest
        padding that stores what it holds), loading and storing the row
        views of the banks the variant uses.  ``dda``/``steps``: the int32
        colour DDAs and their steps; ``textured``: what texel() reads of
        the triangle and span (0 in the variants without texture).
        Returns whether a z value changed."""
        cb0, cb1, zb, sb = banks
        cr0 = cb0[y] if color else cb0[0]
        cr1 = cb1[y] if (color and dual) else cb1[0]
        zr = zb[y] if ztest else zb[0]
        sr = sb[y] if stencil else sb[0]
        r32, g32, b32, a32 = dda
        dr32, dg32, db32, da32 = steps
        zchg = np.int32(0)
        for k in range(nv):
            # truncated to int32 before the clamp (32-bit vector lanes):
            # exact inside the triangle, whose z lies between its
            # vertices' (|Z| < viewport.Z_LIMIT)
            zq = min(max(np.int32(zf >> ZFRAC), zlo32), zhi32)
            zf += dz
            w = word
            if interp:
                w = gouraud_word(cmode, cmax, r32, g32, b32, a32)
                r32 = add32(r32, dr32)
                if not cmode:
                    g32 = add32(g32, dg32)
                    b32 = add32(b32, db32)
                    a32 = add32(a32, da32)
            if texture:
                w = texel(k, textured)
            kk = np.int32(k)        # (an int32 test: 8 lanes)
            patbit = np.int32((kk >= kin0) & (kk <= kin1)) if pad else np.int32(1)
            u = np.uint64(lo + k)   # unsigned index: no wraparound test
            if pattern:
                patbit &= np.int32(prow[u])     # (pattern_rows: aligned in x)
            zold = np.int32(zr[u]) if ztest else np.int32(0)
            sold = np.int32(sr[u]) if stencil else np.int32(0)
            c0 = np.int64(cr0[u]) if color else np.int64(0)
            c1 = np.int64(cr1[u]) if (color and dual) else np.int64(0)
            ok, zn, sn, n0, n1 = stages(patbit, zq, zold, sold, c0, c1, w, bt, prm)
            if stencil == 2:        # (1: the stencil is only tested)
                sr[u] = sn
            if zwrite:
                zchg |= np.int32(zn != zold)
                zr[u] = zn
            if color:
                cr0[u] = n0
                if dual:
                    cr1[u] = n1
        return zchg

    @kernel(variant=key)
    def walk(bands, setup, X, Y, Z, C, CB, prov, planes, ip, TC, tex, zmax):
        """Rows of every triangle in the bands starting at rows ``bands``
        (run_bands), in submission order; the triangles' edges and planes
        come from setup_triangles."""
        rec, inv_area, rows = setup
        cb0, cb1, zb, sb, pat = planes
        banks = (cb0, cb1, zb, sb)
        prm = fragment.params(ip)
        bt = fragment.blend_terms(blend, bterms, prm)
        zlo, zhi = prm[fragment.P_ZLO], prm[fragment.P_ZHI]
        zlo32, zhi32 = np.int32(zlo), np.int32(zhi)
        skip = ztest and prm[fragment.P_ZMAX] != 0
        padspan = prm[fragment.P_PADSPAN] if pad else 0
        # the row length the padded spans stay inside (0: no padding)
        wid = zb.shape[1] if ztest else (cb0.shape[1] if color else
                                         (sb.shape[1] if stencil else 0))
        for ylo in bands:
            yhi = min(ylo + band_rows - 1, prm[fragment.P_SY1])
            for i in range(rows.shape[0]):
                # (each triangle's rows from their own compact array: rec's
                # 304-byte rows would each take a cache line; the walker of
                # 40k small triangles 6.5 -> 3.7 ms)
                y0, y1 = max(rows[i, 0], ylo), min(rows[i, 1], yhi)
                if y0 > y1:
                    continue
                a, b, c = rec[i, T_VERTS], rec[i, T_VERTS + 1], rec[i, T_VERTS + 2]
                ia = inv_area[i]
                cols = CB if (twoside and rec[i, T_BACK] != 0) else C
                off = (rec[i, T_OFFSET], rec[i, T_OFFSET + 1], rec[i, T_OFFSET + 2])
                bx0, bx1, by0 = rec[i, T_BOX], rec[i, T_BOX + 1], rec[i, T_BOX + 2]
                zplane = (rec[i, T_Z], rec[i, T_Z + 1], rec[i, T_Z + 2], rec[i, T_ZOK] != 0)
                dz = zplane[1]
                cplanes = colour_planes(rec, i)
                # per-pixel colour steps in int32: two covered pixels of a
                # row differ by at most 0xFFF, so a step of a longer span fits
                steps = (np.int32(cplanes[0][1]), np.int32(cplanes[1][1]),
                         np.int32(cplanes[2][1]), np.int32(cplanes[3][1]))
                word = rec[i, T_WORD]
                tlevel = tex[2][i] >> 1 if texture else 0
                tbil = (tex[2][i] & 1) == 1 if texture else False
                edge, row = edges_at_row(rec, i, y0)
                for y in range(y0, y1 + 1):
                    xl, xr, e0, e1, e2 = row_span(edge, row, bx0, bx1)
                    row = next_row(edge, row)
                    if xl > xr:
                        continue
                    # the span's start values: the planes at (xl, y), or for
                    # a sliver outside their bounds the exact weights
                    ox, oy = xl - bx0, y - by0
                    wb = (e1 + off[1]) * ia
                    wc = (e2 + off[2]) * ia
                    zf = z_start(zplane, Z, a, b, c, ox, oy, wb, wc)
                    if skip and zplane[3] and z_hidden(zf, dz, xl, xr, zlo, zhi, zmax[y]):
                        continue
                    lo, nv = padded_span(xl, xr, padspan, wid)
                    early = xl - lo
                    dda = colours_start(cplanes, ox, oy, early, cols, a, b, c, wb, wc) \
                        if interp else (np.int32(0), np.int32(0), np.int32(0), np.int32(0))
                    prow = pat[(y + prm[fragment.P_ORGY]) % prm[fragment.P_PATSIZE]] \
                        if pattern else pat[0]
                    textured = ((e0, e1, e2), edge, off, ia, cols, a, b, c, prov[i], TC, tex,
                                tlevel, tbil) if texture else 0
                    if span(banks, y, lo, nv, np.int32(early), np.int32(xr - lo),
                            zf - dz * early, dz, zlo32, zhi32, word, dda, steps, prow,
                            textured, bt, prm) != 0 and zwrite:
                        ip[fragment.P_ZCHANGED] = 1     # (any thread: the same value)

    return walk
