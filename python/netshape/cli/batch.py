"""`netshape batch JOBS... [--scheduler ADDRESS]`: many jobs or a parameter grid on Dask."""

from __future__ import annotations

import argparse
import sys

from netshape.cli import _args as a

_DESCRIPTION = """\
Run job files (docs/job.md) on Dask (dask.distributed): every job, and for a job with a [grid] table
every combination of its values (e.g. feeds x tool stick-outs x machine error scalings). Each run
writes its own folder OUT/<run>/; the results gather into OUT/batch.csv (one row per run: grid values,
errors before/after [mm], cycle times [s], run time [s], status) and a comparison page OUT/batch.html.
A LocalCluster with --workers processes is started unless --scheduler names an existing scheduler
(tcp://host:8786); --scheduler none runs the jobs one by one here. Needs: pip install 'netshape[batch]'.
"""


def register(sub) -> None:
    p = sub.add_parser("batch", help="many jobs or a parameter grid on Dask, one table",
                       description=_DESCRIPTION,
                       epilog="example: netshape batch study.toml --workers 2 --out study/",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("jobs", nargs="+", metavar="JOB.toml", help="job files (with an optional [grid])")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="address of a running Dask scheduler (default: a LocalCluster); 'none' runs here")
    p.add_argument("--workers", type=a.integer("--workers", ge=1), default=2, metavar="N",
                   help="LocalCluster worker processes, >= 1 (2)")
    p.add_argument("--out", default="netshape-batch", metavar="DIR", help="output folder (netshape-batch)")
    p.add_argument("--parquet", action="store_true", help="also write batch.parquet (needs pandas, pyarrow)")
    p.add_argument("--max-runs", type=a.integer("--max-runs", "runs", ge=1), default=None, metavar="N",
                   help="refuse a study of more than N runs, counted before any runs (10000)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from pathlib import Path

    from netshape._atomic import check_output_folder
    from netshape.cli import CliError
    from netshape.job.batch import run_batch, study_size

    check_output_folder(args.out, "--out")
    if not args.quiet:
        print(f"netshape batch: {study_size(args.jobs)} runs", file=sys.stderr)
    try:
        rows = run_batch(args.jobs, args.out, scheduler=args.scheduler, workers=args.workers,
                         parquet=args.parquet, progress=not args.quiet, max_runs=args.max_runs)
    except ImportError as exc:
        raise CliError(str(exc)) from None
    failed = [r for r in rows if r["status"] != "ok"]
    out = Path(args.out).resolve()
    print(f"netshape batch: {len(rows)} runs, {len(failed)} failed; table {out / 'batch.csv'}, "
          f"report {out / 'batch.html'}")
    for r in failed:
        print(f"  {r['run']}: {r['status']}")
    return 1 if failed else 0
