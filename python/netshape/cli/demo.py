"""`netshape demo`."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("demo", help="(not yet available)", description="(not yet available)")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape.cli import CliError

    raise CliError("'demo' is not implemented yet")
