"""Which error terms a machine TOML holds and where each came from: a key or ``[[table]]`` written by
``netshape diagnose --update`` has a comment line directly above it starting with :data:`MARK`
(docs/discrepancy.md); anything else comes from the file itself."""

from __future__ import annotations

import os
import re
from pathlib import Path

#: the start of the comment line a diagnosis writes above each key it changes
MARK = "netshape diagnose"

_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\[\]]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z0-9_]+)\s*=\s*(.*)$")
_TERM_TABLES = re.compile(r"^(squareness|spindle|axes\.[XYZxyz](\.polynomials)?)$")


def machine_terms(path: str | os.PathLike) -> list[dict]:
    """[{term, value, source}] of the machine file's error terms in file order: squareness, spindle
    tilt, axis polynomials, tables, backlash (``term`` = TOML key path, ``value`` its text) and each
    ``[[axes.K.cyclic]]`` / ``[[thermal]]`` (``value`` its keys); ``source`` the diagnosis comment
    above it (without "# "), else "machine file"."""
    from netshape._text import read_text

    lines = read_text(Path(path)).splitlines()
    out, table, block = [], "", None

    def origin(i: int) -> str:
        j = i - 1
        while j >= 0 and not lines[j].strip():
            j -= 1
        c = lines[j].strip() if j >= 0 else ""
        return c[1:].strip() if c.startswith("#") and MARK in c else "machine file"

    for i, line in enumerate(lines):
        m = _HEADER.match(line)
        if m:
            table = m.group(2).strip()
            block = None
            if m.group(1) == "[[" and (table == "thermal" or table.endswith(".cyclic")):
                block = {"term": table, "value": "", "source": origin(i)}
                out.append(block)
            continue
        k = _KEY.match(line)
        if not k:
            continue
        value = k.group(2).split("#", 1)[0].strip()
        if block is not None:
            block["value"] = (block["value"] + ", " if block["value"] else "") + f"{k.group(1)} = {value}"
        elif _TERM_TABLES.match(table) and (k.group(1)[:1] == "E" or k.group(1).startswith(("tilt_", "backlash_",
                                                                                              "table"))):
            out.append({"term": f"{table}.{k.group(1)}", "value": value, "source": origin(i)})
    return out
