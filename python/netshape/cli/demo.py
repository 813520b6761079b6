"""`netshape demo`: run the bundled default job (examples/demo/job.toml) into ./netshape-demo/."""

from __future__ import annotations

from pathlib import Path


def bundled_dir() -> Path:
    """Folder with the bundled demo files: the installed package's copy, else the source tree's."""
    here = Path(__file__).resolve().parent.parent
    for candidate in (here / "examples" / "demo", here.parents[1] / "examples" / "demo"):
        if (candidate / "job.toml").is_file():
            return candidate
    raise FileNotFoundError(2, "bundled demo job not found", str(here / "examples" / "demo" / "job.toml"))


def register(sub) -> None:
    p = sub.add_parser(
        "demo",
        help="run the bundled default job",
        description="Run the bundled default job with no arguments: a 40 x 30 mm pocket with 8 mm corner "
        "radii milled in stock that a round roughing pass has pre-shaped with arcs, on a vertical machining "
        "centre with geometric errors of a realistic size. Writes the compensated program, summary.json, "
        "plots and report.html into ./netshape-demo/ (or --out) and prints where the report is.",
    )
    p.add_argument("--out", metavar="DIR", default="netshape-demo", help="output folder (default ./netshape-demo)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape.cli.run import execute, print_summary

    folder = bundled_dir()
    job = folder / "job.toml"
    out = Path(args.out)
    print(f"netshape demo: bundled job {job}")
    code, summary = execute(job, out, args.quiet)
    if code == 0:
        print_summary(summary, out.resolve())
        print(f"netshape demo: open {(out / 'report.html').resolve()}")
    return code
