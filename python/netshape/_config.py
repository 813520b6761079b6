"""One configuration layer: reading a TOML file and the field readers every area's ``*_from_dict`` uses,
so that every input file refuses a bad value the same way.

A refusal is one line ``SOURCE: KEY = VALUE: WHY`` (``SOURCE: KEY: WHY`` for a missing key; no
``SOURCE: `` when the caller adds it), raised as ``error`` (a ValueError subclass chosen by the area,
e.g. netshape.job.JobError; ValueError by default). Files are read by :func:`load_toml`
(netshape._text: UTF-8, nesting depth, the file and line named on a syntax error).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

#: The value of a key that is not there (no ``= VALUE`` in the message).
MISSING = object()


def field_error(source: str | None, key: str, value: Any, why: str, error: type = ValueError) -> ValueError:
    """``error("SOURCE: KEY = VALUE: WHY")``; without ``= VALUE`` when value is MISSING, without
    ``SOURCE: `` when source is None or empty."""
    shown = "" if value is MISSING else f" = {value!r}"
    prefix = f"{source}: " if source else ""
    return error(f"{prefix}{key}{shown}: {why}")


def load_toml(path: str | os.PathLike, source: str | None = None) -> dict:
    """The TOML document of ``path`` (``source`` names it in errors; default the path)."""
    from netshape._text import read_toml

    return read_toml(path, source)


def check_keys(source: str | None, where: str, table: Any, known, error: type = ValueError) -> dict:
    """``table`` when it is a table whose keys are all in ``known``; else ``where = …: must be a table``
    or ``where.KEY = …: unknown key (known: …)`` (``known`` listed sorted)."""
    if not isinstance(table, dict):
        raise field_error(source, where, table, "must be a table", error)
    for k in table:
        if k not in known:
            raise field_error(source, f"{where}.{k}" if where else k, table[k],
                              f"unknown key (known: {', '.join(sorted(known))})", error)
    return table


def number(source: str | None, key: str, value: Any, *, positive: bool = False, nonneg: bool = False,
           error: type = ValueError) -> float:
    """``value`` as a float: a finite int or float (not a bool); ``positive``: > 0, ``nonneg``: ≥ 0."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise field_error(source, key, value, "must be a finite number", error)
    if positive and value <= 0:
        raise field_error(source, key, value, "must be positive", error)
    if nonneg and value < 0:
        raise field_error(source, key, value, "must be ≥ 0", error)
    return float(value)


def vec3(source: str | None, key: str, value: Any, error: type = ValueError) -> list[float]:
    """A list of 3 finite numbers [mm] (``key[i]`` named for a bad entry)."""
    if not isinstance(value, list) or len(value) != 3:
        raise field_error(source, key, value, "must be a list of 3 numbers [x, y, z] in mm", error)
    return [number(source, f"{key}[{i}]", x, error=error) for i, x in enumerate(value)]


def boolean(source: str | None, key: str, value: Any, error: type = ValueError) -> bool:
    if not isinstance(value, bool):
        raise field_error(source, key, value, "must be true or false", error)
    return value


def file_path(source: str | None, base: Path, key: str, value: Any, *, must_exist: bool = True,
              error: type = ValueError) -> Path:
    """A path string, relative ones taken from ``base``; ``must_exist``: an existing file."""
    if not isinstance(value, str) or not value:
        raise field_error(source, key, value, "must be a file path (string)", error)
    p = Path(value)
    if not p.is_absolute():
        p = base / p
    if must_exist and not p.is_file():
        raise field_error(source, key, value, f"no such file ({p})", error)
    return p


def one_of(source: str | None, key: str, value: Any, names, error: type = ValueError) -> str:
    """``value`` when it is one of ``names``; else ``must be one of a, b, c``."""
    if value not in names:
        raise field_error(source, key, value, f"must be one of {', '.join(names)}", error)
    return value
