"""The shadow study on Dask: a LocalCluster of two worker processes gives
the serial run's records, images and pictures; a worker killed during the
sweep loses no configuration; timing slots; ``vgx-study --workers``.
Skipped without dask.distributed (the ``[cluster]`` extra; ``[test]``
installs it)."""
import os
import signal

import pytest

distributed = pytest.importorskip("distributed")
from distributed.diagnostics.plugin import WorkerPlugin  # noqa: E402

from study import __main__ as cli  # noqa: E402
from study import report  # noqa: E402
from study.cluster import DaskPool  # noqa: E402
from test_study_scale import (FAILING, SIZE, records, same_results, tiny_configs,  # noqa: E402
                              tiny_file)


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    root = tmp_path_factory.mktemp("serial")
    out = root / "out"
    report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
               cfgs=tiny_configs(), stream=None)
    return out, root


def _run(root, out, client, **kw):
    return report.run((tiny_file(root),), SIZE, out_dir=out, repeats=1, budget=1.0,
                      cfgs=tiny_configs(), stream=None, client=client, **kw)


def test_the_parallel_sweep_equals_the_serial_one(serial, client, tmp_path):
    """Every record (measures, the failure and its error), image, decision
    and picture of the run on two worker processes is the serial run's;
    the tasks ran on the workers, each configuration timed on one."""
    whole, root = serial
    out = tmp_path / "par"
    res = _run(root, out, client)
    same_results(out, whole)
    recs = records(out)
    good = [r for r in recs.values() if r["status"] == "ok"]
    # every record keeps where it was drawn, also those that came before the reference
    assert all(r["where"]["worker"] != "serial" and r["fb_bytes"] > 0 for r in good)
    assert recs[FAILING.key]["status"] == "error"
    assert "Dask" in res["meta"]["engine"]
    timed = res["timing"]["machines"][res["timing"]["compared on"]]
    assert timed["rows"] == len(res["scenes"]["T"]["rows"]) - 1      # all but the floor
    assert timed["slots"] == [len(DaskPool(client=client).timing_slots(1))]


class KillAtFirstTask(WorkerPlugin):
    """Kills its worker's process (SIGKILL) when a task starts executing there,
    once in the cluster: the first worker to create ``mark`` is the one."""

    def __init__(self, mark):
        self.mark = str(mark)

    def transition(self, key, start, finish, **kwargs):
        if finish != "executing":
            return
        try:
            fd = os.open(self.mark, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
        except FileExistsError:
            return
        os.write(fd, f"{os.getpid()} {key}".encode())
        os.close(fd)
        os.kill(os.getpid(), signal.SIGKILL)


def test_a_worker_killed_during_the_sweep_loses_nothing(serial, client, tmp_path):
    """The worker process that starts the sweep's first task is killed
    (SIGKILL) in the middle of it; Dask runs its tasks again and the folder
    ends as the serial run's, with every configuration.  (The kill comes from
    a worker plugin at the task's start, so there is always a task to lose:
    killing from the client at the first record raced the tiny sweep's end.)"""
    whole, root = serial
    mark = tmp_path / "killed"
    register = getattr(client, "register_plugin", None) or client.register_worker_plugin
    before = set(client.run(os.getpid).values())
    register(KillAtFirstTask(mark), name="kill-at-first-task")
    try:
        _run(root, tmp_path / "out", client)
    finally:
        client.unregister_worker_plugin("kill-at-first-task")
    pid, key = mark.read_text().split(" ", 1)
    assert int(pid) in before                          # a worker of the sweep, mid-task
    same_results(tmp_path / "out", whole)
    client.wait_for_workers(2, timeout=60)             # the nanny brought it back
    assert int(pid) not in set(client.run(os.getpid).values())


def test_timing_slots_keep_one_task_per_core(client):
    """Two one-thread workers on one host: one slot each while cores allow,
    never more than cores / threads."""
    pool = DaskPool(client=client)
    cores = os.cpu_count()
    assert len(pool.timing_slots(1)) == min(2, cores)
    assert len(pool.timing_slots(cores)) == 1
    assert pool.spare_slot(set(pool.workers())) is None


def test_vgx_study_workers(tmp_path):
    """``vgx-study --workers 2`` starts its LocalCluster, runs there, and
    writes the same records as the serial command."""
    scene = tiny_file(tmp_path)
    args = ["--scenes", scene, "--size", "32x24", "--methods", "planar", "volumes", "--quick",
            "--repeats", "1"]
    cli.main(args + ["--out", str(tmp_path / "one")])
    cli.main(args + ["--out", str(tmp_path / "two"), "--workers", "2"])
    same_results(tmp_path / "two", tmp_path / "one")
    recs = records(tmp_path / "two")
    assert {r["where"]["worker"] for r in recs.values()} <= {"0", "1"}


def test_vgx_study_scheduler(client, tmp_path):
    """``--scheduler ADDRESS`` sends the tasks to a running cluster (here
    the module's) and leaves it running."""
    scene = tiny_file(tmp_path)
    args = ["--scenes", scene, "--size", "32x24", "--methods", "volumes", "--quick",
            "--no-timing"]
    cli.main(args + ["--out", str(tmp_path / "one")])
    cli.main(args + ["--out", str(tmp_path / "far"), "--scheduler", client.scheduler.address])
    same_results(tmp_path / "far", tmp_path / "one")
    assert all(r["where"]["worker"] != "serial" for r in records(tmp_path / "far").values())
    assert len(client.scheduler_info()["workers"]) == 2
