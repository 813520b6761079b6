"""`--var FILE --tool-table FILE` for the commands that read G-code (info, plan, volumetric compensate),
and reader warnings printed as one stderr line each."""

from __future__ import annotations

import contextlib
import sys
import warnings


def add_offset_options(parser) -> None:
    """Add --var and --tool-table to `parser`."""
    g = parser.add_argument_group("work offsets and tool lengths (LinuxCNC files, mm)")
    g.add_argument("--var", metavar="FILE.var",
                   help="LinuxCNC parameter file: work offsets G54-G59.3 (parameters 5221... ) are applied; "
                   "without it a program that selects one reads with zero offsets and a warning")
    g.add_argument("--tool-table", metavar="FILE.tbl",
                   help="LinuxCNC tool table: G43 H applies the tool's Z length; without it G43 reads as "
                   "zero length and a warning")


def offset_kwargs(args) -> dict:
    """work_offsets / tool_table keywords of the netshape.toolpath readers from the parsed options."""
    return {"work_offsets": getattr(args, "var", None), "tool_table": getattr(args, "tool_table", None)}


@contextlib.contextmanager
def reader_warnings(command: str):
    """Print every GcodeWarning raised inside as `netshape COMMAND: warning: ...` on stderr (once each)."""
    from netshape.toolpath import GcodeWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", GcodeWarning)
        try:
            yield
        finally:
            seen = set()
            for w in caught:
                msg = str(w.message)
                if issubclass(w.category, GcodeWarning) and msg not in seen:
                    seen.add(msg)
                    print(f"netshape {command}: warning: {msg}", file=sys.stderr)
                elif not issubclass(w.category, GcodeWarning):
                    warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
