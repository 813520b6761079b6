"""Batch studies: many jobs, or one job over a parameter grid, run on Dask (``dask.distributed``).

A job file with a ``[grid]`` table runs once per combination of its values (the Cartesian product,
keys in file order)::

    [grid]
    "cutting.feed_scale" = [0.5, 1.0, 1.5]
    "tool.stick_out_mm" = [25.0, 35.0]
    "machine.error_scale" = [0.5, 1.0, 2.0]

Each key is a dotted job key (docs/job.md); a string ``tool``/``stock``/``machine`` entry is read as
``{file = …}`` so the grid can override the file's keys. Every run writes its own folder
``OUT/<run id>/`` (the job's usual outputs) and one row of ``OUT/batch.csv``: the run id, the grid
values, the error figures of summary.json, the cycle times and the run time. ``OUT/batch.html`` with
``OUT/batch.png`` compares the runs. Runs go to a ``LocalCluster`` (``workers`` processes, one thread
each) or to an existing scheduler by address; ``scheduler="none"`` runs them one by one in this
process. dask is an optional dependency: ``pip install netshape[batch]``.

Before any run starts: the output paths are checked, --parquet's pandas/pyarrow are imported, and a
scheduler address is connected to (a few seconds at most). Every path a task carries is absolute (the
output folder is resolved here, on the client), so workers started in other folders write where the
table is. A run that fails, or whose task dies with its workers (``KilledWorker``) or is lost with the
scheduler, is a row with ``failed_stage`` and the reason in ``status``; the table and the page are
written for every row, also when the batch is interrupted.
"""

from __future__ import annotations

import copy
import csv
import io
import itertools
import os
import socket
import time
from pathlib import Path
from urllib.parse import urlsplit

from .budget import check_job_work
from .spec import JobError, _read_toml, job_from_dict, set_dotted

#: The error and time columns of a batch row, after ``run``, ``job`` and the grid keys.
ERROR_COLUMNS = [f"{src}_{k}" for src in ("deflection", "volumetric", "total")
                 for k in ("max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm")]
TIME_COLUMNS = ["cycle_time_original_s", "cycle_time_compensated_s", "run_time_s"]
#: Files the batch writes into its output folder (beside one folder per run).
TABLE_FILES = ("batch.csv", "batch.png", "batch.html")


class BatchInterrupted(KeyboardInterrupt):
    """Ctrl-C during a batch; ``rows`` holds the finished rows and the others marked not run."""

    def __init__(self, rows: list[dict]):
        super().__init__("batch interrupted")
        self.rows = rows


def study_size(paths) -> int:
    """Runs the job files ask for: one per job, or the product of a job's ``[grid]`` list lengths."""
    total = 0
    for path in paths:
        p = Path(path)
        if not p.is_file():
            raise FileNotFoundError(2, "No such file or directory", os.fspath(path))
        grid = _read_toml(p, os.fspath(path)).get("grid", {})
        n = 1
        for v in (grid.values() if isinstance(grid, dict) else ()):
            n *= len(v) if isinstance(v, list) else 1
        total += n
    return total


def expand(paths, max_runs: int | None = None) -> list[dict]:
    """One run spec per job and grid combination: ``run`` id, ``job`` file, ``params`` (grid values),
    ``doc`` (the job TOML with the values set, without its grid) and ``base_dir``. Every spec is
    validated here, so a bad grid value fails before anything runs, naming the run and the key. A study
    of more than ``max_runs`` runs (default netshape._budget.MAX_BATCH_RUNS) is refused before it is
    expanded."""
    from netshape._budget import MAX_BATCH_RUNS, refuse_over

    limit = MAX_BATCH_RUNS if max_runs is None else max_runs
    size = study_size(paths)
    try:
        cause = f"{paths[0]}: grid" if len(paths) == 1 else f"{len(paths)} job files"
        refuse_over(cause, size, limit, "runs (grid combinations over all jobs)", "raise --max-runs")
    except ValueError as exc:
        raise JobError(str(exc)) from None
    specs = []
    for path in paths:
        p = Path(path)
        if not p.is_file():
            raise FileNotFoundError(2, "No such file or directory", os.fspath(path))
        doc = _read_toml(p, os.fspath(path))
        base = p.resolve().parent
        job_from_dict(doc, source=os.fspath(path), base_dir=base)  # the grid itself and the base job
        grid = doc.get("grid", {})
        keys = list(grid)
        combos = list(itertools.product(*(grid[k] for k in keys))) if keys else [()]
        for i, values in enumerate(combos):
            d = copy.deepcopy(doc)
            d.pop("grid", None)
            for k, v in zip(keys, values):
                try:
                    d = set_dotted(d, k, v)
                except ValueError as exc:
                    raise JobError(f"{path}: grid.{k}: {exc}") from None
            run_id = f"{p.stem}-{i:03d}" if keys else p.stem
            check_job_work(job_from_dict(d, source=f"{path} [{run_id}]", base_dir=base))
            specs.append({"run": run_id, "job": os.fspath(path), "params": dict(zip(keys, values)), "doc": d,
                          "base_dir": str(base)})
    ids = [s["run"] for s in specs]
    dup = {x for x in ids if ids.count(x) > 1}
    if dup:
        raise JobError(f"batch: two jobs give the same run id {sorted(dup)[0]!r}; rename one job file")
    return specs


def failed_row(spec: dict, stage: str, reason: str, run_time_s: float | None = None) -> dict:
    """The row of a run that did not finish: no figures, ``failed_stage`` and the reason in ``status``."""
    row = {"run": spec["run"], "job": spec["job"], **spec["params"]}
    row.update({c: None for c in ERROR_COLUMNS + TIME_COLUMNS})
    row["run_time_s"] = run_time_s
    row["failed_stage"] = stage
    row["status"] = " ".join(str(reason).split()) or "failed"
    return row


def run_one(spec: dict, out_dir: str) -> dict:
    """Run one spec into ``out_dir/<run id>/``; returns its batch row (``status`` ok or why it failed)."""
    from .run import StageFailed, run_job

    t0 = time.perf_counter()
    row = {"run": spec["run"], "job": spec["job"], **spec["params"]}
    try:
        job = job_from_dict(spec["doc"], source=f"{spec['job']} [{spec['run']}]", base_dir=spec["base_dir"])
        s = run_job(job, Path(out_dir) / spec["run"], quiet=True)
    except Exception as exc:  # one failed run is a row, not the end of the study
        stage = exc.stage if isinstance(exc, StageFailed) else "setup"
        return failed_row(spec, stage, " ".join(str(exc).split()) or type(exc).__name__,
                          round(time.perf_counter() - t0, 4))
    for src in ("deflection", "volumetric", "total"):
        for k, v in s["errors"][src].items():
            row[f"{src}_{k}"] = v
    row["cycle_time_original_s"] = s["cycle_time_s"]["original"]
    row["cycle_time_compensated_s"] = s["cycle_time_s"]["compensated"]
    row["run_time_s"] = s["run_time_s"]["total"]
    row["failed_stage"] = None
    # a stage that ran but did not finish cleanly (deflection unconverged or skipped) marks the row
    trouble = [f"{k}: {v}" for k, v in s.get("stages", {}).items() if v != "ok"]
    row["status"] = "; ".join(trouble) if trouble else "ok"
    return row


def check_scheduler(address: str, timeout_s: float = 5.0) -> None:
    """Refuse, within ``timeout_s``, a scheduler address that is malformed or where nothing listens
    (ValueError naming --scheduler); the Dask client's own wait is 30 s and ends in a traceback."""
    u = urlsplit(address if "://" in address else f"tcp://{address}")
    if u.scheme not in ("tcp", "tls"):
        raise ValueError(f"--scheduler = {address}: must be tcp://HOST:PORT (or tls://), 'none', or omitted "
                         "for a LocalCluster")
    try:
        host, port = u.hostname, u.port
    except ValueError:
        host, port = None, None
    if not host or port is None:
        raise ValueError(f"--scheduler = {address}: must be tcp://HOST:PORT, e.g. tcp://127.0.0.1:8786")
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            pass
    except OSError as exc:
        why = "timed out" if isinstance(exc, socket.timeout) else (exc.strerror or str(exc))
        raise ValueError(f"--scheduler = {address}: cannot connect ({why}); is `dask scheduler` running "
                         "there?") from None


def _client(scheduler: str | None, workers: int):
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ImportError("netshape batch needs dask.distributed: pip install 'netshape[batch]' "
                          "(or pip install 'dask[distributed]'), or run with --scheduler none") from None
    if scheduler:
        check_scheduler(scheduler)
        try:
            return Client(scheduler, timeout="10s"), None
        except Exception as exc:  # noqa: BLE001 - refused, timed out, or something else answers there
            why = " ".join(str(exc).split())[:200] or type(exc).__name__
            if isinstance(exc, MemoryError):
                why = "what answers there does not speak the Dask protocol"
            raise ValueError(f"--scheduler = {scheduler}: cannot connect ({why}); is `dask scheduler` running "
                             "there?") from None
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def _task_failure(exc: BaseException) -> tuple[str, str]:
    """(failed_stage, reason) of a task that raised on the Dask side instead of returning its row."""
    name = type(exc).__name__
    if name == "KilledWorker":
        return "worker", ("KilledWorker: the workers running this run died (out of memory or killed) as "
                          "many times as the scheduler allows")
    if name in ("CancelledError", "FutureCancelledError"):
        return "scheduler", f"{name}: the task was lost (scheduler or client disconnected)"
    first = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return "worker", f"{name}: {first}" if first else name


def _gather(client, futures, specs: list[dict], progress: bool) -> list[dict]:
    """Rows in the order of ``specs``: a task's own row, or a failed row for a task that raised, was
    killed or was lost. Ctrl-C: BatchInterrupted with the rows finished so far."""
    from dask.distributed import as_completed

    rows: list[dict | None] = [None] * len(specs)
    where = {f.key: i for i, f in enumerate(futures)}
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(futures), unit="run", desc="netshape batch")
    try:
        for fut in as_completed(futures):
            i = where[fut.key]
            try:
                rows[i] = fut.result()
            except Exception as exc:  # noqa: BLE001 - KilledWorker, lost futures, a worker's crash
                rows[i] = failed_row(specs[i], *_task_failure(exc))
            if bar is not None:
                bar.update(1)
    except KeyboardInterrupt:
        raise BatchInterrupted(_fill(rows, specs, "interrupted", "not run: the batch was interrupted")) from None
    except Exception as exc:  # the scheduler went away: what finished stays
        stage, reason = _task_failure(exc)
        rows = _fill(rows, specs, stage, reason)
    finally:
        if bar is not None:
            bar.close()
    return _fill(rows, specs, "scheduler", "not run")


def _fill(rows: list, specs: list[dict], stage: str, reason: str) -> list[dict]:
    return [r if r is not None else failed_row(s, stage, reason) for r, s in zip(rows, specs)]


def run_specs(specs: list[dict], out_dir, *, scheduler: str | None = None, workers: int = 2,
              progress: bool = False, client=None, task=None) -> list[dict]:
    """Rows of ``specs`` run on Dask (LocalCluster of ``workers`` by default, or the scheduler at
    ``scheduler``, or an open dask.distributed ``client``, which is left open; ``"none"`` runs them
    here one by one), in the order of ``specs``. ``out_dir`` is made absolute here, before any task is
    sent. ``task`` (default :func:`run_one`) is what each task runs."""
    out_dir = os.path.abspath(os.fspath(out_dir))
    task = run_one if task is None else task
    if scheduler == "none":
        Path(out_dir).mkdir(parents=True, exist_ok=True)
        it = specs
        if progress:
            from tqdm import tqdm

            it = tqdm(specs, unit="run", desc="netshape batch")
        rows: list = [None] * len(specs)
        try:
            for i, s in enumerate(it):
                rows[i] = task(s, out_dir)
        except KeyboardInterrupt:
            raise BatchInterrupted(_fill(rows, specs, "interrupted", "not run: the batch was interrupted")) from None
        return rows
    if not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers = {workers!r}: must be a positive integer")
    own = client is None
    cluster = None
    if own:
        client, cluster = _client(scheduler, workers)
    try:
        Path(out_dir).mkdir(parents=True, exist_ok=True)
        futures = client.map(task, specs, out_dir=out_dir, key=[f"netshape-{s['run']}" for s in specs],
                             pure=False)
        return _gather(client, futures, specs, progress)
    finally:
        if own:
            client.close()
            if cluster is not None:
                cluster.close()


def columns(rows: list[dict]) -> list[str]:
    """Column order: run, job, grid keys (first seen order), errors, times, status."""
    fixed = ["run", "job"] + ERROR_COLUMNS + TIME_COLUMNS + ["status", "failed_stage"]
    grid = []
    for r in rows:
        for k in r:
            if k not in fixed and k not in grid:
                grid.append(k)
    return ["run", "job", *grid, *ERROR_COLUMNS, *TIME_COLUMNS, "status", "failed_stage"]


def write_table(rows: list[dict], path, *, parquet: bool = False) -> None:
    """``path`` (CSV, empty cell for a missing value); with ``parquet`` also ``path`` with suffix
    .parquet (needs pandas and pyarrow)."""
    from netshape._atomic import atomic_write

    cols = columns(rows)
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: ("" if r.get(k) is None else (repr(r[k]) if isinstance(r[k], float) else r[k]))
                    for k in cols})
    with atomic_write(path, "w") as fh:
        fh.write(buf.getvalue())
    if parquet:
        pd = _parquet_modules()
        target = Path(path).with_suffix(".parquet")
        with atomic_write(target, "wb") as fh:
            pd.DataFrame(rows, columns=cols).to_parquet(fh)


def write_comparison(rows: list[dict], folder) -> None:
    """``batch.png`` (largest total error before/after and cycle time per run) and ``batch.html``
    (the table and the plot; every run links to its own report)."""
    import html

    import numpy as np
    from matplotlib.figure import Figure

    from netshape._atomic import atomic_save_figure, atomic_write

    folder = Path(folder)
    ids = [r["run"] for r in rows]
    x = np.arange(len(rows))

    def col(name):
        return np.array([np.nan if r.get(name) is None else float(r[name]) for r in rows])

    fig = Figure(figsize=(max(6.0, 0.45 * len(rows) + 2), 5.2), layout="constrained")
    a1, a2 = fig.subplots(2, 1, sharex=True)
    a1.bar(x - 0.2, 1e3 * col("total_max_before_mm"), 0.4, label="before")
    a1.bar(x + 0.2, 1e3 * col("total_max_after_mm"), 0.4, label="after")
    a1.set_ylabel("largest total error [µm]")
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3, axis="y")
    a2.bar(x - 0.2, col("cycle_time_original_s"), 0.4, label="original")
    a2.bar(x + 0.2, col("cycle_time_compensated_s"), 0.4, label="compensated")
    a2.set_ylabel("cycle time [s]")
    a2.set_xticks(x, ids, rotation=60, ha="right", fontsize=7)
    a2.legend(fontsize=8)
    a2.grid(alpha=0.3, axis="y")
    atomic_save_figure(fig, folder / "batch.png", dpi=100)
    cols = columns(rows)
    out = ['<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>netshape batch</title>',
           "<style>body{font-family:sans-serif;margin:1em}table{border-collapse:collapse;font-size:80%}"
           "td,th{border:1px solid #bbb;padding:.15em .4em;text-align:right}img{max-width:100%}</style></head><body>",
           f"<h1>netshape batch: {len(rows)} runs</h1>", '<img src="batch.png" alt="comparison of the runs">',
           '<table id="runs"><tr>' + "".join(f"<th>{html.escape(c)}</th>" for c in cols) + "</tr>"]
    for r in rows:
        cells = []
        for c in cols:
            v = r.get(c)
            text = "" if v is None else (f"{v:.6g}" if isinstance(v, float) else str(v))
            if c == "run" and r.get("status") == "ok":
                text = f'<a href="{html.escape(str(v))}/report.html">{html.escape(text)}</a>'
            else:
                text = html.escape(text)
            cells.append(f"<td>{text}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table></body></html>")
    with atomic_write(folder / "batch.html", "w") as fh:
        fh.write("\n".join(out) + "\n")


def _parquet_modules():
    try:
        import pandas as pd
        import pyarrow  # noqa: F401
    except ImportError:
        raise ImportError("--parquet needs pandas and pyarrow: pip install pandas pyarrow") from None
    return pd


def check_outputs(specs: list[dict], out_dir, *, parquet: bool = False, option: str = "--out") -> Path:
    """Refuse, before any run, an output folder (or a table file or run folder in it) that cannot be
    written; ValueError naming the option and the path."""
    from netshape._atomic import check_output_file, check_output_folder

    out = check_output_folder(out_dir, option)
    for name in TABLE_FILES + (("batch.parquet",) if parquet else ()):
        check_output_file(out / name, f"{option} ({name})", make_parent=True)
    for s in specs:
        check_output_folder(out / s["run"], f"{option} ({s['run']})")
    return out


def write_outputs(rows: list[dict], out_dir, *, parquet: bool = False) -> None:
    """batch.csv (+ .parquet), batch.png and batch.html, all or none."""
    from netshape._atomic import all_or_nothing

    Path(out_dir).mkdir(parents=True, exist_ok=True)
    with all_or_nothing():
        write_table(rows, Path(out_dir) / "batch.csv", parquet=parquet)
        write_comparison(rows, out_dir)


def run_batch(paths, out_dir, *, scheduler: str | None = None, workers: int = 2, parquet: bool = False,
              progress: bool = False, task=None, max_runs: int | None = None) -> list[dict]:
    """Expand (at most ``max_runs`` runs, see :func:`expand`), check the outputs (and pandas for ``parquet``, and the scheduler), run, and write
    ``batch.csv`` (+ .parquet), ``batch.png`` and ``batch.html`` into ``out_dir`` for every row, also
    when runs failed or the batch was interrupted. Returns the rows."""
    specs = expand(paths, max_runs)
    out_dir = os.path.abspath(os.fspath(out_dir))
    if parquet:
        _parquet_modules()
    check_outputs(specs, out_dir, parquet=parquet)
    try:
        rows = run_specs(specs, out_dir, scheduler=scheduler, workers=workers, progress=progress, task=task)
    except BatchInterrupted as exc:
        write_outputs(exc.rows, out_dir, parquet=parquet)
        raise
    write_outputs(rows, out_dir, parquet=parquet)
    return rows
