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
"""

from __future__ import annotations

import copy
import csv
import io
import itertools
import os
import time
from pathlib import Path

from .budget import check_job_work
from .spec import JobError, _read_toml, job_from_dict, set_dotted

#: The error and time columns of a batch row, after ``run``, ``job`` and the grid keys.
ERROR_COLUMNS = [f"{src}_{k}" for src in ("deflection", "volumetric", "total")
                 for k in ("max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm")]
TIME_COLUMNS = ["cycle_time_original_s", "cycle_time_compensated_s", "run_time_s"]


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


def run_one(spec: dict, out_dir: str) -> dict:
    """Run one spec into ``out_dir/<run id>/``; returns its batch row (``status`` ok or why it failed)."""
    from .run import run_job

    t0 = time.perf_counter()
    row = {"run": spec["run"], "job": spec["job"], **spec["params"]}
    try:
        job = job_from_dict(spec["doc"], source=f"{spec['job']} [{spec['run']}]", base_dir=spec["base_dir"])
        s = run_job(job, Path(out_dir) / spec["run"], quiet=True)
    except Exception as exc:  # one failed run is a row, not the end of the study
        row.update({c: None for c in ERROR_COLUMNS + TIME_COLUMNS})
        row["run_time_s"] = round(time.perf_counter() - t0, 4)
        row["status"] = " ".join(str(exc).split()) or type(exc).__name__
        return row
    for src in ("deflection", "volumetric", "total"):
        for k, v in s["errors"][src].items():
            row[f"{src}_{k}"] = v
    row["cycle_time_original_s"] = s["cycle_time_s"]["original"]
    row["cycle_time_compensated_s"] = s["cycle_time_s"]["compensated"]
    row["run_time_s"] = s["run_time_s"]["total"]
    row["status"] = "ok"
    return row


def _client(scheduler: str | None, workers: int):
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        raise ImportError("netshape batch needs dask.distributed: pip install 'netshape[batch]' "
                          "(or pip install 'dask[distributed]'), or run with --scheduler none") from None
    if scheduler:
        return Client(scheduler), None
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None)
    return Client(cluster), cluster


def run_specs(specs: list[dict], out_dir, *, scheduler: str | None = None, workers: int = 2,
              progress: bool = False, client=None) -> list[dict]:
    """Rows of ``specs`` run on Dask (LocalCluster of ``workers`` by default, or the scheduler at
    ``scheduler``, or an open dask.distributed ``client``, which is left open; ``"none"`` runs them
    here one by one), in the order of ``specs``."""
    out_dir = os.fspath(out_dir)
    Path(out_dir).mkdir(parents=True, exist_ok=True)
    if scheduler == "none":
        it = specs
        if progress:
            from tqdm import tqdm

            it = tqdm(specs, unit="run", desc="netshape batch")
        return [run_one(s, out_dir) for s in it]
    if not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers = {workers!r}: must be a positive integer")
    own = client is None
    cluster = None
    if own:
        client, cluster = _client(scheduler, workers)
    try:
        futures = client.map(run_one, specs, out_dir=out_dir, key=[f"netshape-{s['run']}" for s in specs],
                             pure=False)
        if progress:
            from dask.distributed import as_completed
            from tqdm import tqdm

            with tqdm(total=len(futures), unit="run", desc="netshape batch") as bar:
                for _ in as_completed(futures):
                    bar.update(1)
        return client.gather(futures)
    finally:
        if own:
            client.close()
            if cluster is not None:
                cluster.close()


def columns(rows: list[dict]) -> list[str]:
    """Column order: run, job, grid keys (first seen order), errors, times, status."""
    fixed = ["run", "job"] + ERROR_COLUMNS + TIME_COLUMNS + ["status"]
    grid = []
    for r in rows:
        for k in r:
            if k not in fixed and k not in grid:
                grid.append(k)
    return ["run", "job", *grid, *ERROR_COLUMNS, *TIME_COLUMNS, "status"]


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
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("--parquet needs pandas and pyarrow: pip install pandas pyarrow") from None
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


def run_batch(paths, out_dir, *, scheduler: str | None = None, workers: int = 2, parquet: bool = False,
              progress: bool = False, max_runs: int | None = None) -> list[dict]:
    """Expand (at most ``max_runs`` runs, see :func:`expand`), run, and write ``batch.csv`` (+ .parquet),
    ``batch.png`` and ``batch.html`` into ``out_dir``. Returns the rows."""
    specs = expand(paths, max_runs)
    rows = run_specs(specs, out_dir, scheduler=scheduler, workers=workers, progress=progress)
    write_table(rows, Path(out_dir) / "batch.csv", parquet=parquet)
    write_comparison(rows, out_dir)
    return rows
