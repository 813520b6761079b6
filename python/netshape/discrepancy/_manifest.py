"""Reading a bundle's manifest and CSV files: the Bundle record and the checks every kind of
experiment shares (keys, numbers, the experiment's file, the milling mode, CSV columns); every error
names the manifest field or the CSV line (see :mod:`netshape.discrepancy.bundle`)."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from netshape._config import number


@dataclass
class Bundle:
    """A loaded measurement bundle. ``tool`` / ``machine`` / ``model`` are the manifest tables with
    units stripped into plain keys (see :func:`load_bundle`); ``experiments`` one per CSV."""

    kind: str
    path: str
    model: dict
    experiments: list
    tool: dict = field(default_factory=dict)
    machine: dict = field(default_factory=dict)
    #: the manifest's ``[noise]`` table: {"sigma": stated instrument standard uncertainty in the data's
    #: unit} (``sigma_mm`` for volumetric and wall bundles, ``sigma_N`` for forces), empty if not stated
    noise: dict = field(default_factory=dict)


def _fail(where: str, msg: str) -> ValueError:
    return ValueError(f"{where}: {msg}")


def _number(table: dict, key: str, where: str, *, positive: bool = False, default: Any = None) -> float:
    """``table[key]`` read by netshape._config.number (``default`` when missing and given)."""
    if key not in table:
        if default is not None:
            return default
        raise _fail(where, f"missing key {key!r}")
    return number(where, key, table[key], positive=positive)


def _noise_table(doc: dict, key: str, where: str) -> dict:
    """The optional ``[noise]`` table: ``sigma_mm`` or ``sigma_N`` (``key``), the instrument's stated
    standard uncertainty of one measured value (> 0)."""
    if "noise" not in doc:
        return {}
    t = doc["noise"]
    w = f"{where}: [noise]"
    if not isinstance(t, dict):
        raise _fail(where, f"[noise] must be a table with {key}")
    _check_keys(t, (key,), w)
    return {"sigma": _number(t, key, w, positive=True)}


def _check_keys(table: dict, allowed, where: str) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise _fail(where, f"unknown key {unknown[0]!r} (allowed: {', '.join(allowed)})")


def _experiment_head(e: dict, i: int, keys, where: str, root: Path) -> tuple[str, Path]:
    """Checks common to every ``[[experiment]]`` table: known keys and a CSV ``file``. Returns the
    error prefix of the table and the CSV's path (relative paths are relative to the bundle)."""
    we = f"{where}: [[experiment]] {i}"
    _check_keys(e, keys, we)
    if not isinstance(e.get("file"), str) or not e["file"]:
        raise _fail(we, f"file = {e.get('file')!r}: must name a CSV file")
    path = Path(e["file"])
    return we, (path if path.is_absolute() else root / path)


def _mode(e: dict, we: str) -> str:
    mode = e.get("mode")
    if mode not in ("up", "down", "slot"):
        raise _fail(we, f"mode = {mode!r}: must be 'up', 'down' or 'slot'")
    return mode


def _read_csv(path: Path, required: tuple, optional: tuple, alternatives: tuple = ()) -> dict:
    """Read a CSV of numbers with a header row → {column: (n,) float array}. ``alternatives``: a
    tuple of column names of which exactly one must be present (besides ``required``)."""
    if not path.is_file():
        raise FileNotFoundError(2, "No such file or directory", str(path))
    from netshape._text import read_text

    text = read_text(path)
    rows = [r for r in csv.reader(io.StringIO(text, newline="")) if r and not r[0].lstrip().startswith("#")]
    if not rows:
        raise _fail(str(path), "empty file (expected a header row and data rows)")
    header = [h.strip() for h in rows[0]]
    allowed = set(required) | set(optional) | set(alternatives)
    for h in header:
        if h not in allowed:
            raise _fail(
                str(path),
                f"unknown column {h!r} (expected {', '.join((*alternatives, *required, *optional))})",
            )
    if len(set(header)) != len(header):
        raise _fail(str(path), f"repeated column in header {header}")
    for r in required:
        if r not in header:
            raise _fail(str(path), f"missing column {r!r}")
    if alternatives and sum(a in header for a in alternatives) != 1:
        raise _fail(str(path), f"needs exactly one of the columns {' or '.join(map(repr, alternatives))}")
    data = rows[1:]
    if len(data) < 2:
        raise _fail(str(path), f"{len(data)} data rows: need at least 2")
    out = np.empty((len(data), len(header)))
    for i, row in enumerate(data, start=2):
        if len(row) != len(header):
            raise _fail(str(path), f"line {i}: {len(row)} fields, header has {len(header)}")
        for j, text in enumerate(row):
            try:
                v = float(text)
            except ValueError:
                raise _fail(
                    str(path), f"line {i}, column {header[j]!r}: {text.strip()!r} is not a number"
                ) from None
            if not math.isfinite(v):
                raise _fail(str(path), f"line {i}, column {header[j]!r}: {text.strip()!r} is not finite")
            out[i - 2, j] = v
    return {h: out[:, j].copy() for j, h in enumerate(header)}
