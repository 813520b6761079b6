"""`netshape demo`: run the bundled default job (until the end-to-end job exists: `info` on the
bundled program examples/demo/part.ngc)."""

from __future__ import annotations

from pathlib import Path


def bundled_dir() -> Path:
    """Folder with the bundled demo files: the installed package's copy, else the source tree's."""
    here = Path(__file__).resolve().parent.parent
    for candidate in (here / "examples" / "demo", here.parents[1] / "examples" / "demo"):
        if (candidate / "part.ngc").is_file():
            return candidate
    raise FileNotFoundError(2, "bundled demo program not found", str(here / "examples" / "demo" / "part.ngc"))


def register(sub) -> None:
    p = sub.add_parser(
        "demo",
        help="run the bundled default job",
        description="Run the bundled default job with no arguments. For now this prints `netshape info` "
        "of the bundled program examples/demo/part.ngc (a 40 x 30 mm pocket with arcs, in mm) and "
        "where the bundled files are.",
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape.cli import info

    folder = bundled_dir()
    program = folder / "part.ngc"
    print(f"netshape demo: bundled files in {folder}")
    print(f"netshape demo: netshape info {program}\n")
    args.program = str(program)
    var = folder / "part.var"  # its G54 (the program selects G54): zero, the part's own origin
    args.var = str(var) if var.is_file() else None
    args.tool_table = None
    return info.run(args)
