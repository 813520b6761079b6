"""`netshape info`."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("info", help="(not yet available)", description="(not yet available)")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape.cli import CliError

    raise CliError("'info' is not implemented yet")
