"""The Raster Subsystem's own thread: geometry and raster work pipelined.

On the VGX the Geometry Subsystem hands each primitive to the Raster
Subsystem through a FIFO and goes on with the next; the host program and
the geometry engines run ahead of the pixels.  The emulator does the same
with one worker thread: ``VGX._flush`` runs the geometry and triangle setup
of a batch on the calling thread and queues the rest of its pass (the z
maxima, the walker, lines, points) here, and the clears and acbuf queue
their kernels, so the program's Python calls and the next batch's geometry
run while the walker of the last one fills pixels (the numba kernels release the GIL).  Work runs one item
at a time in the order it was queued, so the pixels are those of running
it at once.

Everything that reads or writes a bank's contents outside this thread waits
first (:func:`sync`): the Framebuffer's banks and z maxima are attributes
that wait when read or set (framebuffer.Framebuffer), so a read-back, a
swap, a reconfiguration, a picture or a test reading ``fb.back`` sees every
pass queued before it.  Only the code that queues work takes the banks
without waiting (it hands them to the work).

``config.PIPELINE`` off (environment ``VGX_PIPELINE=0`` or
``VGX_PARALLEL=0``, or a one-core machine) or one numba thread
(``numba.set_num_threads(1)`` on the calling thread) runs every item at
once on the calling thread instead.  A failure inside queued work is raised
by the next :func:`sync` (the call that waits), with its own traceback.
"""
import itertools
import threading
from collections import deque
from concurrent.futures import ThreadPoolExecutor

import numba
from numba.np.ufunc import parallel as _numba_parallel

from . import config

_lock = threading.Condition()
_items = deque()
_state = {"sent": 0, "done": 0, "running": False, "error": None, "thread": None,
          "ident": None, "offer": None, "waits": 0, "waiting": 0}
_inside = threading.local()     # .item: this thread is running a queued item


class Shares:
    """Work of one pass that a waiting thread may help with: ``run(k)``
    for k in 0 .. n-1, each k taken by exactly one thread (the triangle
    walker's shares of bands: scan.triangles.run_bands).  The raster
    thread offers them (:func:`shared`); a thread waiting in :func:`sync`
    takes shares until none is left, so while the program waits its core
    fills pixels too, and while it runs Python the raster thread works
    alone."""

    def __init__(self, run, n):
        self.run = run
        self.next = iter(range(n)).__next__     # atomic under the GIL
        self.helpers = 0
        self.closed = False
        self.error = None

    def take(self):
        """Run shares until none is left (StopIteration ends it)."""
        try:
            while True:
                self.run(self.next())
        except StopIteration:
            self.closed = True          # no share left: nothing for a helper

    def help(self):
        with _lock:
            if self.closed:
                return
            self.helpers += 1
        try:
            self.take()
        except BaseException as e:      # the pass's failure (raised by shared())
            self.error = self.error or e
        finally:
            with _lock:
                self.helpers -= 1
                _lock.notify_all()


def shared(run, n):
    """Run ``run(k)`` for every k < n on the raster thread, offering the
    shares to a thread waiting in :func:`sync`; returns when all are done."""
    offer = Shares(run, n)
    with _lock:
        _state["offer"] = offer
        _lock.notify_all()
    try:
        offer.take()
    finally:
        with _lock:
            offer.closed = True
            while offer.helpers:
                _lock.wait()
            _state["offer"] = None
    if offer.error is not None:
        raise offer.error


def _run_head():
    """Run the item at the head of the queue (called with _lock held and
    no item running; returns with it held): items run one at a time, in
    the order they were queued, whichever thread runs them."""
    s = _state
    fn, args = _items.popleft()
    s["running"] = True
    _lock.release()
    try:
        _as_item(fn, args)
    finally:
        _lock.acquire()
        s["running"] = False
        s["done"] += 1
        _lock.notify_all()


def _as_item(fn, args):
    """fn(*args) as a queued item on this thread: the banks it reads do
    not wait, and a failure is kept for the next sync() to raise."""
    _inside.item = True
    try:
        fn(*args)
    except BaseException as e:      # raised by the next sync()
        if _state["error"] is None:
            _state["error"] = e
    finally:
        _inside.item = False


def _worker():
    _state["ident"] = threading.get_ident()
    with _lock:
        while True:
            while not _items or _state["running"]:
                _lock.wait()
            _run_head()


def num_threads():
    """numba.get_num_threads(): the calling thread's count (set_num_threads
    is per thread).  Once numba's threads are launched it is read directly,
    without get_num_threads' check of the launch under two locks (1.3 us,
    called a few times a flush); any other numba falls back to the call."""
    if getattr(_numba_parallel, "_is_initialized", False):
        n = _numba_parallel._get_num_threads()
        if n > 0:
            return n
    return numba.get_num_threads()


def submit(fn, *args, now=False):
    """Queue ``fn(*args)`` for the raster thread (or run it now when
    config.PIPELINE is off, or inside a queued item, or, with ``now``, when
    that thread has nothing queued or running: work too small to be worth
    handing over, which then runs in the same order, as a queued item: a
    failure is raised by the next :func:`sync`)."""
    s = _state
    if getattr(_inside, "item", False):
        fn(*args)
        return
    if not config.PIPELINE or num_threads() < 2:
        sync()                  # (after what was queued while it was on)
        fn(*args)
        return
    if now and s["sent"] == s["done"]:
        # (only the program's thread queues work: with nothing queued the
        # raster thread stays asleep, and is not woken to find nothing)
        _as_item(fn, args)
        return
    if s["thread"] is None:
        t = threading.Thread(target=_worker, name="vgx-raster", daemon=True)
        s["thread"] = t
        t.start()
    with _lock:
        _items.append((fn, args))
        s["sent"] += 1
        _lock.notify_all()


def idle():
    """Whether the raster thread has nothing queued or running (the
    program's thread may then use the other cores itself)."""
    return _state["sent"] == _state["done"]


def split(count, least):
    """(threads n, shares m) for ``count`` items of work on the program's
    thread, in shares of at least ``least``: config.SHARES_PER_THREAD per
    thread, and m = 1 (run it at once) when there are fewer than two shares
    or the raster thread is busy (it holds the other core)."""
    if count < 2 * least or not config.PARALLEL or not idle():
        return 1, 1                     # (before num_threads)
    n = num_threads()
    return n, (min(n * config.SHARES_PER_THREAD, count // least) if n > 1 else 1)


def in_shares(run, count, least):
    """run(lo, hi) over [0, count): at once, or in shares of at least
    ``least`` (each share writes its own rows of the outputs).  On the
    raster thread the shares are offered to a thread waiting in
    :func:`sync` (:func:`shared`; none waiting: at once, since the other
    core runs the program); elsewhere they are the ones :func:`split`
    gives, on :func:`on_threads`."""
    raster = on_raster_thread()
    if raster:
        n = 2 if config.PARALLEL and helper_waiting() else 1
        m = min(n * config.SHARES_PER_THREAD, count // least) if n > 1 else 1
    else:
        n, m = split(count, least)
    if m <= 1:
        run(0, count)
        return
    cuts = [count * k // m for k in range(m + 1)]
    share = lambda k: run(cuts[k], cuts[k + 1])     # noqa: E731
    if raster:
        shared(share, m)
    else:
        on_threads(share, m, n)


_pool = None


def on_threads(share, m, n):
    """share(0) .. share(m - 1) on this thread and n - 1 of a pool's, each
    share run once, taken in turn until none is left (the kernels they
    call release the GIL)."""
    global _pool
    if _pool is None or _pool._max_workers < n - 1:
        _pool = ThreadPoolExecutor(max_workers=max(n - 1, 1), thread_name_prefix="vgx-band")
    taken = itertools.count()       # next() is atomic under the GIL

    def worker():
        k = next(taken)
        while k < m:
            share(k)
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


def helper_waiting():
    """Whether a thread is waiting in :func:`sync` (and would take shares
    of a pass: :func:`shared`).  While none waits the raster thread walks a
    pass in one piece: a thread coming back from a kernel to take its next
    share waits for the GIL while the program runs Python."""
    return _state["waiting"] > 0


def on_raster_thread():
    """Whether this is the raster thread (its passes share their bands only
    with a thread waiting in sync: the other core runs the program)."""
    return threading.get_ident() == _state["ident"]


def waits():
    """How many times a thread has waited for queued work (sync with work
    pending): the tests check that drawing a frame waits only where it must."""
    return _state["waits"]


def pending():
    """Whether queued work has not finished."""
    return _state["sent"] != _state["done"]


def sync():
    """Wait until every queued item has run; raise the first failure of one.
    The waiting thread works meanwhile: it runs the next item itself when
    the raster thread has not started it (a pass queued just before a wait
    would otherwise wait for that thread to wake) and takes shares of the
    one running (:func:`shared`).  A no-op inside a queued item (the item
    sees the banks as the items before it left them)."""
    s = _state
    if s["sent"] != s["done"]:
        if getattr(_inside, "item", False):
            return
        s["waits"] += 1
        with _lock:
            s["waiting"] += 1
            try:
                while s["sent"] != s["done"]:
                    offer = s["offer"]
                    if _items and not s["running"]:
                        _run_head()
                    elif offer is not None and not offer.closed:
                        _lock.release()
                        try:
                            offer.help()
                        finally:
                            _lock.acquire()
                    else:
                        _lock.wait()
            finally:
                s["waiting"] -= 1
    if s["error"] is not None:
        e, s["error"] = s["error"], None
        raise e
