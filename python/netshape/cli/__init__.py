"""The ``netshape`` command. Each subcommand lives in its own module here with a
``register(subparsers)`` function that adds its parser and sets ``func``.

Exit codes: 0 success, 2 bad input (one clear line on stderr), 1 other failure. :func:`main` returns
the code (it does not raise SystemExit); the ``netshape`` script exits with it.

Bad input, one convention for every subcommand (netshape.cli._args):
- a single value is checked while parsing by a ``type=`` validator of ``_args`` (positive, non_negative,
  finite, real with bounds, integer with bounds, flutes, counts, parsed by a library parser);
- options checked against each other are checked after parsing, in one place per subcommand, by
  raising ``CliError("--opt = value: rule")``; the library's own ValueError is the backstop;
- either way stderr gets exactly one line ``netshape COMMAND: error: --opt = value: rule [unit]``,
  e.g. ``netshape plan: error: --vmax = -3: must be positive [mm/s]`` (COMMAND the innermost one, e.g.
  ``deflection wall``); argparse's own errors (a value that is not a number, a missing option or
  action, a bad choice, an unknown option) get the same one line, printed by ``_args.Parser``, the
  class of the top-level parser and, through ``add_subparsers``, of every subparser.
A new subcommand follows it by passing ``type=_args.<validator>("--opt", "unit")`` for every value
option and raising CliError for cross-option checks at the top of its ``run``.
"""

from __future__ import annotations

import argparse
import sys
from importlib import import_module

# name of the module in netshape.cli, in the order they appear in --help
_COMMANDS = ("info", "forces", "deflection", "volumetric", "plan", "feeds", "posture", "diagnose", "run", "batch", "demo")

_EPILOG = """\
examples:
  netshape demo                              run the bundled default job into ./netshape-demo/
  netshape run job.toml --out results/       predictions, compensated program and report of a job
  netshape batch study.toml                  a job over a parameter grid on Dask, one table
  netshape info part.ngc --json              block counts, lengths, bounding box, time
  netshape <command> --help                  what a command does and its options

Units: mm, s, N, MPa, rad; feeds in mm/min on the command line where the option says so.
"""


def build_parser() -> argparse.ArgumentParser:
    from netshape.cli._args import Parser

    parser = Parser(
        prog="netshape",
        description="Predict the shape errors a CNC program will produce and rewrite it so the part "
        "comes out right.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    from netshape import __version__

    parser.add_argument("--version", action="version", version=f"netshape {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in _COMMANDS:
        import_module(f"netshape.cli.{name}").register(sub)
    return parser


class CliError(Exception):
    """Bad input detected by the CLI itself; printed as one line, exit code 2."""


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # 2 after the one-line parse error, 0 after --help / --version
        return int(exc.code or 0)
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    from netshape._progress import progress

    try:
        # run, batch and demo show their own bars, by stage of the job
        with progress(args._prog, None if args.command not in ("run", "batch", "demo") else False):
            result = args.func(args)
    except (ValueError, CliError, FileNotFoundError, IsADirectoryError, PermissionError) as exc:
        print(f"{args._prog}: error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except RecursionError:  # backstop: input readers refuse deep nesting themselves, naming the file
        print(f"{args._prog}: error: input nested too deeply to read", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("netshape: interrupted", file=sys.stderr)
        return 130
    return int(result or 0)


def _one_line(exc: BaseException) -> str:
    if isinstance(exc, FileNotFoundError) and exc.filename:
        return f"{exc.filename}: no such file"
    if isinstance(exc, (IsADirectoryError, PermissionError)) and exc.filename:
        return f"{exc.filename}: {exc.strerror}"
    return " ".join(str(exc).split()) or type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
