"""`netshape run JOB.toml [--out DIR] [--quiet]`: the main job end to end."""

from __future__ import annotations

import argparse
import sys

_DESCRIPTION = """\
Run a job file (docs/job.md): read the program, tool, stock and machine; simulate the cut (Z-map
material removal, forces, deflection wall error, volumetric error, feed plan and cycle time); apply
the chosen compensations (deflection first, then volumetric); re-predict the compensated program; and
write into the output folder: the compensated program, summary.json, the final Z-map as STL, PNG
plots and report.html. Every file is written whole or not at all; a failed stage is named.
"""


def register(sub) -> None:
    p = sub.add_parser("run", help="run a job file: predictions, compensated program, report",
                       description=_DESCRIPTION,
                       epilog="example: netshape run job.toml --out results/",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("job", metavar="JOB.toml", help="job file (docs/job.md)")
    p.add_argument("--out", metavar="DIR", help="output folder (default: the job's `output` key)")
    p.add_argument("--quiet", action="store_true", help="no progress bar, no closing lines")
    p.set_defaults(func=run)


def execute(job_path, out, quiet: bool) -> tuple[int, dict | None]:
    """Run a job for the CLI: (exit code, summary). Stage failures print one line naming the stage."""
    from netshape._atomic import check_output_folder
    from netshape.job import StageFailed, load_job, run_job

    if out is not None:
        check_output_folder(out, "--out")
    job = load_job(job_path)
    if job.grid:
        n = 1
        for v in job.grid.values():
            n *= len(v)
        print(f"netshape run: warning: {job_path}: [grid] ({', '.join(job.grid)}; {n} combinations) is not "
              "used by run, which runs the job once without it; run the grid with netshape batch",
              file=sys.stderr)
    try:
        summary = run_job(job, out, quiet=quiet)
    except StageFailed as exc:
        if isinstance(exc.cause, ValueError):
            raise ValueError(str(exc)) from None
        print(f"netshape run: error: {exc}", file=sys.stderr)
        return 1, None
    for w in summary.get("warnings", []):
        print(f"netshape run: warning: {w['kind']}: {w['message']}", file=sys.stderr)
    if summary.get("stale_files"):
        print(f"netshape run: warning: the output folder also holds files this run did not write: "
              f"{', '.join(summary['stale_files'])}", file=sys.stderr)
    return 0, summary


def print_summary(summary: dict, folder) -> None:
    e = summary["errors"]

    def um(v):
        return "n/a" if v is None else f"{1e3 * v:.3f} µm"

    for src in ("deflection", "volumetric", "total"):
        print(f"{src:<11} max error {um(e[src]['max_before_mm'])} -> {um(e[src]['max_after_mm'])}, "
              f"RMS {um(e[src]['rms_before_mm'])} -> {um(e[src]['rms_after_mm'])}")
    for k, v in summary.get("stages", {}).items():
        if v != "ok":
            print(f"{k}: {v}")
    ct = summary["cycle_time_s"]
    if ct["original"] is not None:
        print(f"cycle time {ct['original']:.2f} s original, {ct['compensated']:.2f} s compensated")
    print(f"run time {summary['run_time_s']['total']:.1f} s; report: {folder / 'report.html'}")


def run(args) -> int:
    from pathlib import Path

    from netshape.job import load_job

    code, summary = execute(args.job, args.out, args.quiet)
    if code == 0 and not args.quiet:
        folder = Path(args.out) if args.out else load_job(args.job).output
        print_summary(summary, folder.resolve())
    return code
