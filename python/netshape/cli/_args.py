"""How every ``netshape`` subcommand reads and refuses its options.

- Single values are checked while parsing, by the ``type=`` validators here: each takes the option name
  (and the unit) and returns a converter that returns the value or raises argparse.ArgumentTypeError
  with one line ``--opt = value: rule [unit]``, e.g. ``--vmax = -3: must be positive [mm/s]``.
- Checks that relate options to each other stay in the subcommand, after parsing, in one place, as
  ``CliError("--opt = value: rule")``.
- :class:`Parser` (the top-level parser and, through ``add_subparsers``, every subparser) prints any
  parse error as exactly one line ``netshape COMMAND: error: MESSAGE`` on stderr and exits with code 2.

The library still validates what it is given; these checks only name the option the value came from.
"""

from __future__ import annotations

import argparse
import math
import re
import sys

__all__ = ["Parser", "real", "positive", "non_negative", "finite", "integer", "flutes", "counts", "parsed"]


def _shown(text: str) -> str:
    """The value as the user typed it (quoted when empty or holding spaces)."""
    return text if text and not any(c.isspace() for c in text) else repr(text)


def _num(x) -> str:
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e7 else f"{x:g}"


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""


def _refused(option: str, text: str, rule: str) -> argparse.ArgumentTypeError:
    return argparse.ArgumentTypeError(f"{option} = {_shown(text)}: {rule}")


def _bounds_rule(gt, ge, lt, le) -> str:
    lo, lo_open = (gt, True) if gt is not None else (ge, False)
    hi, hi_open = (lt, True) if lt is not None else (le, False)
    if lo is not None and hi is not None:
        return f"must be in {'(' if lo_open else '['}{_num(lo)}, {_num(hi)}{')' if hi_open else ']'}"
    if lo is not None:
        if lo == 0 and lo_open:
            return "must be positive"
        return f"must be {'>' if lo_open else '>='} {_num(lo)}"
    if hi is not None:
        return f"must be {'<' if hi_open else '<='} {_num(hi)}"
    return "must be finite"


def real(option: str, unit: str = "", *, gt=None, ge=None, lt=None, le=None):
    """A finite float with optional bounds: gt/ge the lower (open/closed), lt/le the upper."""
    rule = _bounds_rule(gt, ge, lt, le) + _unit(unit)

    def convert(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise _refused(option, text, "must be a number" + _unit(unit)) from None
        if not math.isfinite(v):
            raise _refused(option, text, "must be finite" + _unit(unit))
        if not ((gt is None or v > gt) and (ge is None or v >= ge) and (lt is None or v < lt)
                and (le is None or v <= le)):
            raise _refused(option, text, rule)
        return v

    return convert


def positive(option: str, unit: str = ""):
    """A finite float > 0."""
    return real(option, unit, gt=0)


def non_negative(option: str, unit: str = ""):
    """A finite float >= 0."""
    return real(option, unit, ge=0)


def finite(option: str, unit: str = ""):
    """Any finite float."""
    return real(option, unit)


def integer(option: str, unit: str = "", *, ge=None, le=None):
    """An integer, optionally in [ge, le] (written ge..le in the message)."""
    if ge is not None and le is not None:
        rule = f"must be in {_num(ge)}..{_num(le)}"
    else:
        rule = _bounds_rule(None, ge, None, le)
    rule += _unit(unit)

    def convert(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise _refused(option, text, "must be an integer" + _unit(unit)) from None
        if (ge is not None and v < ge) or (le is not None and v > le):
            raise _refused(option, text, rule)
        return v

    return convert


def flutes(option: str = "--flutes"):
    """A flute count, checked by the library's one 1..64 check (netshape.cutter.check_flutes)."""
    as_int = integer(option)

    def convert(text: str) -> int:
        v = as_int(text)
        from netshape.cutter import check_flutes

        try:
            check_flutes(v, option)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
        return v

    return convert


def counts(option: str, n: int, *, ge: int = 1, example: str = ""):
    """n comma-separated integers, each >= ge, e.g. ``9,9,5`` → (9, 9, 5)."""
    rule = f"must be {n} comma-separated integers >= {ge}" + (f", e.g. {example}" if example else "")

    def convert(text: str) -> tuple[int, ...]:
        try:
            parts = tuple(int(v) for v in text.split(","))
        except ValueError:
            parts = ()
        if len(parts) != n or min(parts) < ge:
            raise _refused(option, text, rule)
        return parts

    return convert


def parsed(option: str, parse):
    """The value `parse(text)` returns (a library parser); its ValueError becomes the option's error."""

    key = option.lstrip("-").replace("-", "_")

    def convert(text: str):
        try:
            return parse(text)
        except ValueError as exc:
            msg = " ".join(str(exc).split())
            if msg.startswith(key + " "):  # the library named the field itself: `--` + its message
                raise argparse.ArgumentTypeError(f"--{msg}") from None
            raise _refused(option, text, msg) from None

    return convert


_INVALID_CHOICE = re.compile(r"invalid choice: (.+?) \(choose from (.+)\)$")


class Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line on stderr, ``netshape COMMAND: error: MESSAGE``, and
    exit code 2. Subparsers made by ``add_subparsers`` are of this class too. After a successful parse
    ``namespace._prog`` is the prog of the innermost subparser, so that errors found after parsing carry
    the same ``netshape COMMAND`` prefix."""

    def __init__(self, *args, **kwargs):
        kwargs["exit_on_error"] = False  # ArgumentError reaches parse_known_args below, whole
        super().__init__(*args, **kwargs)

    def parse_known_args(self, args=None, namespace=None):
        try:
            ns, rest = super().parse_known_args(args, namespace)
        except argparse.ArgumentError as err:
            self.error(_message(err))
        if getattr(ns, "_prog", None) is None:
            ns._prog = self.prog
        return ns, rest

    def parse_args(self, args=None, namespace=None):
        ns, rest = self.parse_known_args(args, namespace)
        if rest:  # named by the innermost command, whose options the user most likely mistyped
            _fail(ns._prog, f"unrecognized arguments: {' '.join(rest)}")
        return ns

    def error(self, message: str):
        _fail(self.prog, message)


def _fail(prog: str, message: str):
    sys.stderr.write(f"{prog}: error: {' '.join(str(message).split())}\n")
    raise SystemExit(2)


def _message(err: argparse.ArgumentError) -> str:
    """`--opt = value: rule` when a validator said so; argparse's own errors in the same shape where
    it is recognisable (a bad choice), else argparse's text."""
    name, msg = err.argument_name, err.message
    if not name:
        return msg
    names = name.split("/")
    if any(msg.startswith((n + " ", n + ":")) for n in names):  # a validator named the option itself
        return msg
    m = _INVALID_CHOICE.match(msg)
    if m:
        value, choices = m.group(1).strip("'"), m.group(2).replace("'", "")
        return f"{names[-1]} = {value}: must be one of {choices}"
    return f"argument {name}: {msg}"


def check_outputs(args, files: tuple[str, ...] = (), folders: tuple[str, ...] = ()) -> None:
    """Check every output path the user gave before the command does any work (netshape._atomic: a
    folder where a file is expected or the reverse, under a file, a device, not writable), and refuse
    one path given to two options. Options are named as on the command line (``--json``); a
    ``--opt ... (NAME)`` entry is the file NAME inside the folder option ``--opt``."""
    import os

    from netshape._atomic import check_output_file, check_output_folder

    seen: dict[str, str] = {}
    for option, check in [(o, check_output_file) for o in files] + [(o, check_output_folder) for o in folders]:
        dest = option.lstrip("-").replace("-", "_")
        value = getattr(args, dest, None)
        if not value:
            continue
        check(value, option)
        key = os.path.realpath(value)
        if key in seen:
            raise ValueError(f"{option} = {value!r}: the same path as {seen[key]}; give each output its own path")
        seen[key] = option
