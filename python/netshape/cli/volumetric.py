"""`netshape volumetric`."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("volumetric", help="(not yet available)", description="(not yet available)")
    p.set_defaults(func=run)


def run(args) -> int:
    from netshape.cli import CliError

    raise CliError("'volumetric' is not implemented yet")
