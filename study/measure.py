"""The measures of the study.

* Misclassified shadow pixels, in percent of the pixels the eye sees (the
  reference's visible pixels), split into *false lit* (the method lets
  light reach a point the reference says it does not) and *false shadow*
  (the reverse).  Decisions may be fractional (PCF, accumulated soft
  shadows): a pixel then counts max(m - r, 0) as false lit and
  max(r - m, 0) as false shadow, which for 0/1 decisions is the plain
  count.  For hard shadows a method's decision is taken together with the
  facing test of the visible triangle (N.L > 0), because the lighting
  equation gives no diffuse light elsewhere whatever the method decides.
* Image error against the reference image: RMSE and largest absolute
  difference over every channel of every pixel, in 0..255 units.
* Warm run time: the median of repeated runs after an untimed one.
* Memory: the peak of Python-side allocations during one run
  (``tracemalloc``, which numpy's array allocations report to), plus the
  bytes of the framebuffer banks the method needs (computed from the
  window sizes, see render.fb_bytes).
"""
import statistics
import time
import tracemalloc

import numpy as np


def misclassified(decision, truth, visible, facing=None):
    """Percent false lit and false shadow over the visible pixels."""
    m = np.asarray(decision, np.float64)
    if facing is not None:
        m = m * facing
    r = np.asarray(truth, np.float64)
    n = max(int(np.count_nonzero(visible)), 1)
    over = np.clip(m - r, 0.0, None)[visible].sum()
    under = np.clip(r - m, 0.0, None)[visible].sum()
    return {"false_lit": 100.0 * over / n, "false_shadow": 100.0 * under / n}


def image_error(image, reference):
    """RMSE and max |difference| over all channels and pixels (0..255)."""
    d = np.asarray(image, np.float64) - np.asarray(reference, np.float64)
    return {"rmse": float(np.sqrt(np.mean(d * d))), "max_abs": float(np.abs(d).max())}


def host_peak(fn):
    """(result of fn(), peak bytes of Python allocations during it)."""
    was = tracemalloc.is_tracing()
    if not was:
        tracemalloc.start()
    tracemalloc.reset_peak()
    base = tracemalloc.get_traced_memory()[0]
    try:
        out = fn()
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        if not was:
            tracemalloc.stop()
    return out, max(peak, 0)


def warm_times(fn, repeats=3, budget=20.0):
    """Times (s) of up to ``repeats`` runs of fn(), stopping early once
    ``budget`` seconds have been spent (at least one run)."""
    times = []
    while len(times) < repeats:
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
        if sum(times) > budget:
            break
    return times


def median(xs):
    return statistics.median(xs)


def pareto(points):
    """Indices of the points (time, error) no other point beats on both
    (smaller or equal in both, smaller in one)."""
    pts = list(points)
    front = []
    for i, (t, e) in enumerate(pts):
        beaten = any((t2 <= t and e2 <= e) and (t2 < t or e2 < e)
                     for j, (t2, e2) in enumerate(pts) if j != i)
        if not beaten:
            front.append(i)
    return front
