"""Line width, line style, point size and polygon mode, as geometry.

Everything here happens after the viewport transform and feeds the existing
line and point kernels (scan/lines.py) with more, or shorter, primitives;
no kernel knows about widths, styles or polygon modes
(docs/drawing-2d-and-lines.md):

- polymode(3G): PYM_LINE/PYM_LINE_FAST/PYM_HOLLOW turn a filled batch into
  the edges of its polygons (tmesh triangles, qstrip quads) and send them
  down the line path; PYM_POINT sends its vertices down the point path.
- setlinestyle(3G)/lsrepeat(3G): each window-space segment is cut into the
  runs of pixels whose pattern bit is 1 (least significant bit first, each
  bit ``lsrepeat`` pixels long); the pattern counter runs on through the
  segments of one line, and across lines with resetls(FALSE).
- linewidth(3G): a line n pixels wide is n one-pixel lines, one pixel apart
  along the minor axis.
- pntsize(3G): a point n pixels wide is an n x n square of one-pixel points.

All of it is vectorised over the batch (numpy, no Python loop per segment,
point or pixel).
"""
import numpy as np

from . import assemble, clip, viewport
from .assemble import CLOSEDLINE, POLYGON, QSTRIP, TMESH
from .batch import LINES, POINTS

PYM_FILL, PYM_POINT, PYM_LINE, PYM_HOLLOW, PYM_LINE_FAST = 1, 2, 3, 4, 5
MAX_WIDTH = 255                 # linewidth(3G): aliased widths 1..255 on the VGX
MAX_POINT = 255


def fill_mode(st, klass_filled):
    """How a filled batch is drawn: 'fill', 'line' or 'point' (polymode(3G))."""
    if not klass_filled:
        return None
    m = st.polymode
    if m in (PYM_LINE, PYM_LINE_FAST, PYM_HOLLOW):
        return "line"
    if m == PYM_POINT:
        return "point"
    return "fill"


def used_width(w):
    """linewidth(3G): aliased lines take the width rounded to the nearest
    integer, at least 1 (linewidth 0 is 1), at most 255."""
    if not np.isfinite(w):
        return 1
    return int(min(max(int(np.floor(w + 0.5)), 1), MAX_WIDTH))


def used_point_size(s):
    """pntsize(3G): the size rounded to the nearest integer, 1..255."""
    if not np.isfinite(s):
        return 1
    return int(min(max(int(np.floor(s + 0.5)), 1), MAX_POINT))


# -- which segments ------------------------------------------------------------
def segments(batch, pos, table, outline):
    """(segs (S, 2), provoking (S,), line (S,)): the segments of a line batch
    (polylines) or, with ``outline``, the edges of a filled batch's polygons,
    tmesh triangles and qstrip quads; ``line`` numbers the line (polyline or
    polygon outline) each segment belongs to, in submission order."""
    kinds, starts, counts = table[:, 0], table[:, 1], table[:, 2]
    if not outline:
        segs, prov = assemble.polylines(starts, counts, kinds == CLOSEDLINE)
        nseg = np.where(counts >= 2, counts - 1 + ((kinds == CLOSEDLINE) & (counts >= 3)), 0)
        return segs, prov, np.repeat(np.arange(len(table)), nseg)
    parts, provs, lines, order = [], [], [], []
    seq = np.arange(len(table))
    sel = kinds == POLYGON
    if sel.any():
        c = counts[sel]
        s, p = assemble.polylines(starts[sel], c, np.ones(len(c), bool))
        nseg = np.where(c >= 2, c - 1 + (c >= 3), 0)
        owner = np.repeat(seq[sel], nseg)
        parts.append(s)
        provs.append(np.repeat(starts[sel] + c - 1, nseg))   # FLAT: the polygon's last vertex
        lines.append(owner * 0)                               # placeholder, renumbered below
        order.append(owner)
    sel = kinds == QSTRIP
    if sel.any():
        tris, prov = assemble.qstrips(starts[sel], counts[sel])
        quads = np.stack((tris[0::2, 0], tris[0::2, 1], tris[0::2, 2], tris[1::2, 2]), axis=1)
        e = np.stack((quads, np.roll(quads, -1, axis=1)), axis=2).reshape(-1, 2)
        nq = np.maximum((counts[sel] - 2) // 2, 0)
        parts.append(e)
        provs.append(np.repeat(prov[0::2], 4))
        owner = np.repeat(seq[sel], 4 * nq)
        lines.append(np.repeat(np.arange(len(quads)), 4))
        order.append(owner)
    sel = kinds == TMESH
    if sel.any():
        sw = np.asarray(batch.swaps, np.int64)
        swap = np.bincount(sw[sw < len(pos)], minlength=len(pos)) % 2 == 1
        tris, prov, src = assemble.tmeshes(starts[sel], counts[sel], swap)
        e = np.stack((tris, np.roll(tris, -1, axis=1)), axis=2).reshape(-1, 2)
        parts.append(e)
        provs.append(np.repeat(prov, 3))
        lines.append(np.repeat(np.arange(len(tris)), 3))
        order.append(np.repeat(seq[sel][src], 3))
    if not parts:
        z = np.zeros(0, np.int64)
        return np.zeros((0, 2), np.int64), z, z
    segs = np.concatenate(parts)
    prov = np.concatenate(provs)
    owner = np.concatenate(order)
    # each polygon, quad and triangle is its own outline ("line")
    sub = np.concatenate(lines)
    key = owner * (int(sub.max(initial=0)) + 1) + sub
    o = np.argsort(owner, kind="stable")
    segs, prov, key = segs[o], prov[o], key[o]
    line = np.cumsum(np.r_[True, key[1:] != key[:-1]]) - 1 if len(key) else key
    return segs, prov, line


def line_work(batch, st, table, pos, clp, col, bad, gx, gy, ud, vp, near_far, snap,
              outline, closed, linestyles):
    """The line path of process_batch: segments, clipping, window rows, then
    style and width.  Returns (seg0, seg1, segflat, dropped)."""
    from . import _window_rows
    segs, prov, line = segments(batch, pos, table, outline)
    drop = bad[segs].any(axis=1) if len(segs) else np.zeros(0, bool)
    dropped = int(drop.sum())
    segs, prov, line = segs[~drop], prov[~drop], line[~drop]
    p0, p1, kept = clip.clip_segments(clp, col, segs, gx, gy, ud)
    seg0 = _window_rows(p0, vp, near_far, snap)
    seg1 = _window_rows(p1, vp, near_far, snap)
    ok = viewport.placed(seg0) & viewport.placed(seg1)
    if not ok.all():                # a cut point the divide cannot place (viewport.placed)
        dropped += int((~ok).sum())
        seg0, seg1, kept = seg0[ok], seg1[ok], kept[ok]
    flat = np.ascontiguousarray(col[prov[kept]])
    hollow = outline and st.polymode == PYM_HOLLOW
    pattern = 0xFFFF if hollow else (linestyles or {}).get(st.linestyle, 0xFFFF) & 0xFFFF
    styled = pattern != 0xFFFF or st.lsbackup
    if (styled or not st.resetls) and len(segs):
        start = _pattern_start(st, segs, line, clp, vp, near_far, snap, seg0, kept)
        if styled:
            seg0, seg1, flat, _ = stipple(seg0, seg1, flat, start, line[kept], pattern,
                                          st.lsrepeat, st.lsbackup, closed)
        if not st.resetls:          # the counter runs on, solid lines included
            st.ls_phase = int(start[1])
    width = 1 if hollow else used_width(st.linewidth)
    if width > 1:
        seg0, seg1, flat = widen(seg0, seg1, flat, width, centred=not snap)
    return (np.ascontiguousarray(seg0), np.ascontiguousarray(seg1),
            np.ascontiguousarray(flat), dropped)


# -- line style ------------------------------------------------------------------
def _major(p0, p1):
    """Per segment: True where x is the major axis, the rounded start and end
    along it (the line kernel's own rule)."""
    dx = p1[:, 0] - p0[:, 0]
    dy = p1[:, 1] - p0[:, 1]
    xm = np.abs(dx) >= np.abs(dy)
    s = np.where(xm, p0[:, 0], p0[:, 1])
    e = np.where(xm, p1[:, 0], p1[:, 1])
    return xm, np.floor(s + 0.5), np.floor(e + 0.5)


def _pattern_start(st, segs, line, clp, vp, near_far, snap, seg0, kept):
    """The pattern counter at the first pixel of every kept segment: the
    pixels of the earlier segments of its line (unclipped lengths along the
    major axis), plus what clipping cut off its start; with resetls(FALSE)
    the counter carried from the earlier lines too."""
    with np.errstate(all="ignore"):
        a = np.empty((len(segs), 7))
        b = np.empty((len(segs), 7))
        a[:, 0], a[:, 1], a[:, 2] = viewport.to_window(clp[segs[:, 0]], vp, near_far, snap)
        b[:, 0], b[:, 1], b[:, 2] = viewport.to_window(clp[segs[:, 1]], vp, near_far, snap)
        xm, s, e = _major(a, b)
        length = np.abs(e - s)
        ok = np.isfinite(length) & (clp[segs[:, 0], 3] > 0) & (clp[segs[:, 1], 3] > 0)
        length = np.where(ok, length, 0.0).astype(np.int64)
    before = np.cumsum(length) - length                 # pixels of all earlier segments
    if st.resetls:
        first = np.r_[True, line[1:] != line[:-1]] if len(line) else np.zeros(0, bool)
        line_start = np.maximum.accumulate(np.where(first, np.arange(len(line)), 0))
        before = before - before[line_start]
    else:
        before = before + st.ls_phase
    start = before[kept]
    # clipping moved the start of a kept segment: count the pixels cut off
    with np.errstate(all="ignore"):
        cs = np.floor(np.where(xm[kept], seg0[:, 0], seg0[:, 1]) + 0.5)
        cut = np.abs(cs - s[kept])
        cut = np.where(ok[kept] & np.isfinite(cut), cut, 0.0).astype(np.int64)
    total = int(before[-1] + length[-1]) if len(before) else st.ls_phase
    return start + cut, total


def stipple(seg0, seg1, flat, start_total, line, pattern, factor, backup, closed):
    """Cut each segment into the runs of pixels whose linestyle bit is 1.

    Pixel k of a segment has counter c = start + k and bit (c // factor) % 16
    of the pattern (bit 0 first, deflinestyle(3G)); lsbackup(3G) forces the
    last two pixels of each line on.  A run becomes a segment from the centre
    of its first pixel to the centre of its last one (one past it for
    half-open lines), on the same exact line, so the kernel draws the same
    pixels it would have drawn for the whole segment."""
    start, total = start_total
    factor = int(min(max(factor, 1), 255))
    xm, a0, a1 = _major(seg0, seg1)
    step = np.where(a1 >= a0, 1, -1)
    npix = (np.abs(a1 - a0) + (1 if closed else 0)).astype(np.int64)
    n = len(npix)
    tot = int(npix.sum())
    if tot == 0:
        z = seg0[:0]
        return z, z.copy(), flat[:0], total
    seg = np.repeat(np.arange(n), npix)
    k = np.arange(tot) - np.repeat(np.cumsum(npix) - npix, npix)
    bits = (pattern >> (((start[seg] + k) // factor) % 16)) & 1
    on = bits.astype(bool)
    if backup:
        last = np.r_[line[1:] != line[:-1], True] if n else np.zeros(0, bool)
        end = npix[seg] - k                         # 1 for the last pixel, 2 for the one before
        on |= last[seg] & (end <= 2)
    # runs: on-pixels whose predecessor (same segment) is off or absent
    prev_on = np.r_[False, on[:-1]] & np.r_[False, seg[1:] == seg[:-1]]
    next_on = np.r_[on[1:], False] & np.r_[seg[1:] == seg[:-1], False]
    rs = np.nonzero(on & ~prev_on)[0]
    re = np.nonzero(on & ~next_on)[0]
    s = seg[rs]
    m0 = a0[s] + k[rs] * step[s]
    m1 = a0[s] + k[re] * step[s] + (0 if closed else step[s])
    p0, p1 = seg0[s], seg1[s]
    q0 = _at(p0, p1, xm[s], m0)
    q1 = _at(p0, p1, xm[s], m1)
    return q0, q1, flat[s], total


def _at(p0, p1, xmajor, m):
    """The row (x, y, z, r, g, b, a) of the segment p0-p1 where its major
    coordinate is m, computed as the line kernel computes its pixels (the
    same t, not clamped: a half-open run may end one pixel past p1)."""
    start = np.where(xmajor, p0[:, 0], p0[:, 1])
    span = np.where(xmajor, p1[:, 0] - p0[:, 0], p1[:, 1] - p0[:, 1])
    with np.errstate(all="ignore"):
        t = np.where(span != 0.0, (m - start) / np.where(span != 0.0, span, 1.0), 0.0)
    out = p0 + t[:, None] * (p1 - p0)
    out[:, 0] = np.where(xmajor, m, out[:, 0])
    out[:, 1] = np.where(xmajor, out[:, 1], m)
    return out


# -- width -----------------------------------------------------------------------
def offsets(n):
    """Minor-axis offsets of the n one-pixel lines (or point rows) of width n:
    j - (n - 1) // 2 for j = 0..n-1, so an odd width is centred and an even
    width has its extra pixel on the positive side."""
    return np.arange(n) - (n - 1) // 2


def widen(seg0, seg1, flat, width, centred=False):
    """linewidth(3G): each segment becomes ``width`` copies shifted along its
    minor axis (y for an x-major segment, x for a y-major one).  Snapped
    segments take the whole-pixel offsets of ``offsets``; a sub-pixel one
    (``centred``) takes j - (width - 1) / 2, so an even width lands on the
    rows nearest its exact position, "centered as nearly as possible on the
    infinitely thin mathematical line" (linewidth(3G)): a 2-pixel line at
    y = 10.7 fills rows 10 and 11, at y = 10.3 rows 10 and 11 too."""
    xm = np.abs(seg1[:, 0] - seg0[:, 0]) >= np.abs(seg1[:, 1] - seg0[:, 1])
    off = np.arange(width) - (width - 1) / 2 if centred else offsets(width)
    S = len(seg0)
    q0 = np.repeat(seg0, width, axis=0)
    q1 = np.repeat(seg1, width, axis=0)
    o = np.tile(off, S).astype(np.float64)
    ax = np.where(np.repeat(xm, width), 1, 0)
    rows = np.arange(S * width)
    q0[rows, ax] += o
    q1[rows, ax] += o
    return q0, q1, np.repeat(flat, width, axis=0)


def grow_points(points, size):
    """pntsize(3G): every point becomes a size x size square of points at
    the pixel offsets of ``offsets(size)`` in x and in y."""
    if size <= 1 or not len(points):
        return points
    off = offsets(size).astype(np.float64)
    ox, oy = np.meshgrid(off, off)
    n = size * size
    out = np.repeat(points, n, axis=0)
    # centre on the point's own pixel first, as the point kernel rounds it
    out[:, 0] = np.floor(out[:, 0] + 0.5) + np.tile(ox.ravel(), len(points))
    out[:, 1] = np.floor(out[:, 1] + 0.5) + np.tile(oy.ravel(), len(points))
    return out


# -- antialiasing -------------------------------------------------------------------
SML_ON, SMP_ON = 1, 1


def smooth(work, st, closed, outline):
    """linesmooth(3G)/pntsmooth(3G), the last geometry step (after depth
    cueing, whose colour-map index the coverage bits then refine): smooth
    lines become their coverage fragments as point rows, for the point
    kernel; smooth one-pixel points spread over 2 x 2 pixels."""
    if work.klass == LINES and st.linesmooth & SML_ON and work.seg0 is not None and \
            not (outline and st.polymode == PYM_HOLLOW):
        work.points = np.ascontiguousarray(smooth_line_points(
            work.seg0, work.seg1, work.segflat, st.gouraud or bool(st.depthcue), closed,
            not st.rgb))
        work.klass = POINTS
    elif work.klass == POINTS and st.pntsmooth & SMP_ON and work.points is not None and \
            used_point_size(st.pntsize) == 1:
        work.points = np.ascontiguousarray(smooth_points(work.points, not st.rgb))


def _coverage_rows(rows, cover, cmode):
    """Rows (x, y, z, r, g, b, a) with their coverage folded in: RGB alpha
    times the coverage; in colour-map mode the low 4 bits of the index
    replaced by the coverage (0..15), linesmooth(3G)/pntsmooth(3G)."""
    keep = cover > 0.0
    rows, cover = rows[keep], cover[keep]
    if cmode:
        idx = np.floor(rows[:, 3] + 0.5).astype(np.int64) & ~0xF
        rows[:, 3] = idx | np.floor(cover * 15.0 + 0.5).astype(np.int64)
    else:
        rows[:, 6] = rows[:, 6] * cover
    return rows


def smooth_line_points(seg0, seg1, flat, gouraud, closed, cmode):
    """linesmooth(3G): the fragments of antialiased one-pixel lines as point
    rows.  At each step along the major axis the two pixels that straddle
    the exact line on the minor axis share the coverage (1 - f, f), f the
    fraction of the line's minor coordinate past the first pixel's centre."""
    xm, a0, a1 = _major(seg0, seg1)
    step = np.where(a1 >= a0, 1, -1)
    npix = (np.abs(a1 - a0) + (1 if closed else 0)).astype(np.int64)
    tot = int(npix.sum())
    if tot == 0:
        return np.zeros((0, 7))
    s = np.repeat(np.arange(len(npix)), npix)
    k = np.arange(tot) - np.repeat(np.cumsum(npix) - npix, npix)
    m = a0[s] + k * step[s]
    p0, p1 = seg0[s], seg1[s]
    start = np.where(xm[s], p0[:, 0], p0[:, 1])
    span = np.where(xm[s], p1[:, 0] - p0[:, 0], p1[:, 1] - p0[:, 1])
    with np.errstate(all="ignore"):
        t = np.where(span != 0.0, (m - start) / np.where(span != 0.0, span, 1.0), 0.0)
    t = np.clip(t, 0.0, 1.0)[:, None]
    row = p0 + t * (p1 - p0)
    if not gouraud:
        row[:, 3:7] = flat[s]
    minor = np.where(xm[s], row[:, 1], row[:, 0])
    lo = np.floor(minor)
    f = minor - lo
    out = np.concatenate((row, row))
    cover = np.concatenate((1.0 - f, f))
    mm = np.concatenate((m, m)).astype(np.float64)
    mi = np.concatenate((lo, lo + 1.0))
    xmm = np.concatenate((xm[s], xm[s]))
    out[:, 0] = np.where(xmm, mm, mi)
    out[:, 1] = np.where(xmm, mi, mm)
    return _coverage_rows(out, cover, cmode)


def smooth_points(points, cmode):
    """pntsmooth(3G): a one-pixel point spread over the 2 x 2 pixels around
    it with bilinear coverage (a point at a pixel centre covers that pixel
    alone)."""
    if not len(points):
        return points
    x0 = np.floor(points[:, 0])
    y0 = np.floor(points[:, 1])
    fx = points[:, 0] - x0
    fy = points[:, 1] - y0
    out = np.concatenate([points] * 4)
    out[:, 0] = np.concatenate((x0, x0 + 1, x0, x0 + 1))
    out[:, 1] = np.concatenate((y0, y0, y0 + 1, y0 + 1))
    cover = np.concatenate(((1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy))
    return _coverage_rows(out, cover, cmode)
