"""`netshape batch` keeps what finished (issue 42 item 9): a task killed with its workers is a row with
its stage and reason, the table and the page are written for every row, --parquet and --scheduler are
checked before any run, and a study against a separately started `dask scheduler` + `dask worker`
writes its run folders beside batch.csv even when the workers run in another folder."""

from __future__ import annotations

import contextlib
import csv
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from netshape.cli import main
from netshape.job.batch import run_batch

from .conftest import DEMO

GRID = """
[grid]
"cutting.feed_scale" = [0.5, 1.0, 1.5]
"""


def _study(tmp_path) -> Path:
    d = tmp_path / "demo"
    shutil.copytree(DEMO, d)
    text = (d / "job.toml").read_text()
    text = text.replace("spacing_mm = 0.25", "spacing_mm = 1.0").replace("deflection = true", "deflection = false")
    text = text.replace("forces = true", "forces = false")
    text = text.replace("[cutting]", "[report]\nplots = false\nzmap_stl = false\n\n[cutting]")
    (d / "study.toml").write_text(text + GRID)
    return d / "study.toml"


def _table(folder: Path) -> list[dict]:
    with open(folder / "batch.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def _dies_on_the_second(spec, out_dir):
    """A task that kills its worker process for run study-001 (as the OOM killer would)."""
    if spec["run"].endswith("-001"):
        os._exit(9)
    from netshape.job.batch import run_one

    return run_one(spec, out_dir)


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore")  # dask's warnings about the dying workers and shut-down
def test_killed_worker_is_a_row_and_the_others_are_kept(tmp_path):
    pytest.importorskip("dask.distributed")
    import dask
    from dask.distributed import Client, LocalCluster

    import cloudpickle

    cloudpickle.register_pickle_by_value(sys.modules[__name__])  # the workers cannot import this test module
    study = _study(tmp_path)
    out = tmp_path / "b"
    with dask.config.set({"distributed.scheduler.allowed-failures": 1}):
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        try:
            from netshape.job import batch as nb

            specs = nb.expand([study])
            nb.check_outputs(specs, out)
            rows = nb.run_specs(specs, out, client=client, task=_dies_on_the_second)
            nb.write_outputs(rows, out)
        finally:
            client.close()
            cluster.close()
    assert [r["status"] == "ok" for r in rows] == [True, False, True]
    dead = rows[1]
    assert dead["failed_stage"] == "worker" and dead["status"].startswith("KilledWorker")
    table = _table(out)
    assert [t["run"] for t in table] == ["study-000", "study-001", "study-002"]
    assert table[1]["failed_stage"] == "worker" and table[1]["total_max_before_mm"] == ""
    assert float(table[2]["total_max_before_mm"]) > 0
    page = (out / "batch.html").read_text()
    assert "KilledWorker" in page and 'href="study-000/report.html"' in page


def test_failed_run_row_names_its_stage(tmp_path):
    study = _study(tmp_path)
    study.write_text(study.read_text().replace('"cutting.feed_scale" = [0.5, 1.0, 1.5]',
                                               '"machine.error_scale" = [1.0, 1e300]'))
    rows = run_batch([study], tmp_path / "b", scheduler="none")
    assert [r["failed_stage"] for r in rows] == [None, "volumetric"]
    assert "machine.error_scale = 1e+300" in rows[1]["status"]
    assert [t["failed_stage"] for t in _table(tmp_path / "b")] == ["", "volumetric"]
    assert (tmp_path / "b" / "batch.html").is_file()


def test_interrupted_batch_writes_the_finished_rows(tmp_path, monkeypatch):
    from netshape.job import batch as nb

    calls = []

    def task(spec, out_dir):
        calls.append(spec["run"])
        if len(calls) == 2:
            raise KeyboardInterrupt
        return nb.run_one(spec, out_dir)

    with pytest.raises(KeyboardInterrupt):
        run_batch([_study(tmp_path)], tmp_path / "b", scheduler="none", task=task)
    table = _table(tmp_path / "b")
    assert [t["status"] for t in table][0] == "ok"
    assert [t["failed_stage"] for t in table][1:] == ["interrupted", "interrupted"]
    assert (tmp_path / "b" / "batch.html").is_file()


def test_parquet_without_pandas_refused_before_running(tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "pandas", None)
    study = _study(tmp_path)
    out = tmp_path / "b"
    assert main(["batch", str(study), "--scheduler", "none", "--parquet", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--parquet needs pandas" in err
    assert not out.exists()


def test_unreachable_scheduler_fails_fast(tmp_path, capsys):
    pytest.importorskip("dask.distributed")
    import socket

    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    study = _study(tmp_path)
    t0 = time.perf_counter()
    code = main(["batch", str(study), "--scheduler", f"tcp://127.0.0.1:{port}",
                 "--out", str(tmp_path / "b"), "--quiet"])
    assert code == 2 and time.perf_counter() - t0 < 10
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"--scheduler = tcp://127.0.0.1:{port}: cannot connect" in err
    assert not (tmp_path / "b").exists()
    assert main(["batch", str(study), "--scheduler", "localhost", "--out", str(tmp_path / "b"),
                 "--quiet"]) == 2
    assert "must be tcp://HOST:PORT" in capsys.readouterr().err


def _wait_for(path: Path, proc, seconds: float) -> None:
    """Until ``path`` holds a whole JSON document (the scheduler writes its file in more than one go)."""
    import json

    t0 = time.time()
    while True:
        try:
            json.loads(path.read_text())
            return
        except (OSError, ValueError):
            pass
        if proc.poll() is not None or time.time() - t0 > seconds:
            raise RuntimeError(f"{path} did not appear within {seconds} s")
        time.sleep(0.2)


@pytest.mark.slow
def test_study_on_a_separate_scheduler_and_worker(tmp_path, monkeypatch):
    """`dask scheduler` and `dask worker` as subprocesses on 127.0.0.1, the worker in another folder; the
    client runs with a relative --out. Every run folder lands beside batch.csv."""
    pytest.importorskip("dask.distributed")
    dask_cli = Path(sys.executable).with_name("dask")
    if not dask_cli.exists():
        pytest.skip("the dask command is not installed beside this Python")
    study = _study(tmp_path)
    sched_file = tmp_path / "scheduler.json"
    worker_dir = tmp_path / "worker-cwd"
    client_dir = tmp_path / "client-cwd"
    worker_dir.mkdir()
    client_dir.mkdir()
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    procs = []
    try:
        procs.append(subprocess.Popen([str(dask_cli), "scheduler", "--host", "127.0.0.1", "--port", "0",
                                       "--no-dashboard", "--scheduler-file", str(sched_file)],
                                      cwd=worker_dir, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                      start_new_session=True))
        _wait_for(sched_file, procs[0], 60)
        procs.append(subprocess.Popen([str(dask_cli), "worker", "--scheduler-file", str(sched_file), "--nthreads",
                                       "1", "--nworkers", "1", "--no-dashboard", "--local-directory", str(worker_dir)],
                                      cwd=worker_dir, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                      start_new_session=True))
        import json

        from dask.distributed import Client

        address = json.loads(sched_file.read_text())["address"]
        with Client(address, timeout="30s") as c:
            c.wait_for_workers(1, timeout=60)
        monkeypatch.chdir(client_dir)
        rows = run_batch([study], "study-out", scheduler=address)
    finally:
        for p in reversed(procs):  # each started in its own session: its group holds the nanny's worker too
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGTERM)
        for p in reversed(procs):
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait(timeout=10)
    assert [r["status"] for r in rows] == ["ok"] * 3
    out = client_dir / "study-out"
    for r in rows:
        assert (out / r["run"] / "report.html").is_file(), r["run"]
        assert not (worker_dir / "study-out").exists()
    assert [t["run"] for t in _table(out)] == [r["run"] for r in rows]
