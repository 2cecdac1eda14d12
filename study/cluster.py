"""Where the sweep's tasks run: in this process one after another
(``SerialPool``, the default, no Dask needed) or as tasks on a Dask
cluster (``DaskPool``: a ``LocalCluster`` of worker processes, or an
existing scheduler).  Both take ``submit(tag, fn, *args)`` and yield
``(tag, ok, value)`` as tasks finish, tasks submitted while iterating
included; ``ok`` is False when the task raised (``value``: the exception).

Dask reschedules the tasks of a worker that dies (up to its
``distributed.scheduler.allowed-failures``, then the task fails with
KilledWorker, which the sweep records like any error).

Timing slots: the workers a timing task may run on, at most one timing
task on each and at most ``cores // threads`` of them per host, so a timed
run never shares a core with another task of the sweep.
"""
import heapq
import itertools
import os
import uuid


class SerialPool:
    """Every task in this process, highest priority first, then in
    submission order."""

    description = "serial (this process)"

    def __init__(self):
        self.queue = []
        self.count = itertools.count()

    def submit(self, tag, fn, *args, priority=0, slot=None):
        heapq.heappush(self.queue, (-priority, next(self.count), tag, fn, args))

    def __iter__(self):
        while self.queue:
            _, _, tag, fn, args = heapq.heappop(self.queue)
            try:
                value = fn(*args)
            except Exception as e:
                yield tag, False, e
            else:
                yield tag, True, value

    def timing_slots(self, threads):
        return [None]

    def alive(self, slot):
        return True

    def spare_slot(self, in_use):
        return None

    def close(self):
        from . import tasks
        tasks.reset()


def need_dask():
    """Import distributed, or say how to install it."""
    try:
        import distributed
    except ImportError:
        raise SystemExit("vgx-study --workers/--scheduler needs Dask: "
                         "pip install -e '.[cluster]'") from None
    return distributed


class DaskPool:
    """Tasks on a Dask cluster: ``client`` (used as is), else
    ``scheduler`` (an address), else a LocalCluster of ``workers``
    processes with one thread each (each process its own emulator)."""

    def __init__(self, workers=None, scheduler=None, client=None):
        distributed = need_dask()
        import importlib.util
        dashboard = importlib.util.find_spec("bokeh") is not None    # Dask's own display
        self.cluster = None
        self.own = client is None
        if client is not None:
            self.client = client
        elif scheduler:
            self.client = distributed.Client(scheduler)
        else:
            self.cluster = distributed.LocalCluster(
                n_workers=int(workers), threads_per_worker=1, processes=True,
                dashboard_address=":0")
            self.client = distributed.Client(self.cluster)
        n = len(self.workers())
        kind = ("LocalCluster" if self.cluster is not None
                else f"scheduler {self.client.scheduler.address}")
        self.description = f"Dask {kind}, {n} workers"
        link = getattr(self.client, "dashboard_link", None) if dashboard else None
        if link:
            self.description += f" (dashboard {link})"
        self.ac = None
        self.tags = {}

    def workers(self):
        """{address: info} of the workers the scheduler knows now."""
        try:
            info = self.client.scheduler_info(n_workers=-1)
        except TypeError:
            info = self.client.scheduler_info()
        return info["workers"]

    def submit(self, tag, fn, *args, priority=0, slot=None):
        from distributed import as_completed
        kw = {"priority": priority, "pure": False,
              "key": f"{fn.__name__}-{uuid.uuid4().hex[:12]}"}
        if slot is not None:
            kw.update(workers=[slot], allow_other_workers=True)
        f = self.client.submit(fn, *args, **kw)
        self.tags[f.key] = tag
        if self.ac is None:
            self.ac = as_completed()
        self.ac.add(f)

    def __iter__(self):
        if self.ac is None:
            return
        for f in self.ac:
            tag = self.tags.pop(f.key)
            try:
                value = f.result()
            except Exception as e:
                yield tag, False, e
            else:
                yield tag, True, value
            finally:
                f.release()
        self.ac = None

    def timing_slots(self, threads):
        cores = self.client.run(os.cpu_count)
        by_host = {}
        for addr, w in sorted(self.workers().items()):
            by_host.setdefault(w["host"], []).append(addr)
        slots = []
        for addrs in by_host.values():
            n = max(1, (cores.get(addrs[0]) or 1) // max(1, threads))
            slots += addrs[:n]
        return slots

    def alive(self, slot):
        return slot in self.workers()

    def spare_slot(self, in_use):
        """A live worker not in ``in_use`` (a slot whose worker died is
        replaced by it), or None."""
        spare = [a for a in sorted(self.workers()) if a not in in_use]
        return spare[0] if spare else None

    def close(self):
        if self.own:
            self.client.close()
            if self.cluster is not None:
                self.cluster.close()


def make_pool(workers=None, scheduler=None, client=None):
    """SerialPool without workers, scheduler or client; else a DaskPool."""
    if client is None and scheduler is None and not workers:
        return SerialPool()
    return DaskPool(workers, scheduler, client)
