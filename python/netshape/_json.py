"""The one way netshape writes JSON: strict JSON (no NaN, no Infinity), whole or not at all.

Every command's JSON output goes through :func:`write_json` (a file, atomically) or :func:`dumps_json`
(text, e.g. for stdout). A non-finite number anywhere in the document is refused before anything is
written, with :class:`NonFiniteResult` (a ValueError, so the CLI prints it as its one-line error):

    --stick-out = 1e+300: gives a non-finite result (wall_error_mm.bottom = inf); nothing written

``cause`` names the input that produced the number where the caller knows it (``--stick-out = 1e+300``,
``job.toml: cutting.spindle_rpm = 1e-300``); without it the message names the result key only.
"""

from __future__ import annotations

import json
import math
import os
from typing import Any

__all__ = ["NonFiniteResult", "first_non_finite", "check_finite", "dumps_json", "write_json"]


class NonFiniteResult(ValueError):
    """A result holds NaN or ±inf; ``key`` is its dotted path in the document, ``value`` the number."""

    def __init__(self, key: str, value: float, cause: str | None = None):
        self.key, self.value, self.cause = key, value, cause
        result = f"{key} = {value}" if key else str(value)
        super().__init__(f"{cause}: gives a non-finite result ({result}); nothing written" if cause
                         else f"{result}: the result is not a finite number; nothing written")


def _plain(obj: Any) -> Any:
    """NumPy scalars and arrays as Python numbers and lists (anything else unchanged)."""
    tolist = getattr(obj, "tolist", None)
    if tolist is not None and type(obj).__module__ == "numpy":
        return tolist()
    return obj


def first_non_finite(obj: Any, key: str = "") -> tuple[str, float] | None:
    """The dotted key (``points[3].error_mm``) and value of the first NaN/±inf in ``obj``, or None."""
    obj = _plain(obj)
    if isinstance(obj, float):
        return None if math.isfinite(obj) else (key, obj)
    if isinstance(obj, dict):
        for k, v in obj.items():
            found = first_non_finite(v, f"{key}.{k}" if key else str(k))
            if found:
                return found
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            found = first_non_finite(v, f"{key}[{i}]")
            if found:
                return found
    return None


def check_finite(obj: Any, cause: str | None = None) -> None:
    """Raise :class:`NonFiniteResult` when ``obj`` holds a NaN or ±inf (see the module docstring)."""
    found = first_non_finite(obj)
    if found:
        raise NonFiniteResult(found[0], found[1], cause)


def _default(obj: Any) -> Any:
    plain = _plain(obj)
    if plain is obj:
        raise TypeError(f"{type(obj).__name__} is not JSON serialisable")
    return plain


#: Lists longer than this are written one item per line, each item compact (see :func:`dumps_json`).
LONG_LIST = 64


def _compact(obj: Any) -> str:
    return json.dumps(obj, allow_nan=False, default=_default)


def _indented(obj: Any, indent: str, level: int, out: list[str]) -> None:
    """``json.dumps(obj, indent=len(indent))`` into ``out``, except that each item of a list longer than
    LONG_LIST is one compact line (C encoder): a 2·10⁶-point map is written in seconds, not minutes."""
    obj = _plain(obj)
    if isinstance(obj, dict) and obj:
        pad = "\n" + indent * (level + 1)
        out.append("{")
        for i, (k, v) in enumerate(obj.items()):
            if not isinstance(k, str):
                k = json.loads(_compact({k: 0}))  # json's own key conversion (numbers, bools, None)
                k = next(iter(k))
            out.append(("," if i else "") + pad + _compact(k) + ": ")
            _indented(v, indent, level + 1, out)
        out.append("\n" + indent * level + "}")
    elif isinstance(obj, (list, tuple)) and obj:
        pad = "\n" + indent * (level + 1)
        out.append("[")
        long = len(obj) > LONG_LIST
        for i, v in enumerate(obj):
            out.append(("," if i else "") + pad)
            if long:
                out.append(_compact(v))
            else:
                _indented(v, indent, level + 1, out)
        out.append("\n" + indent * level + "]")
    else:
        out.append(_compact(obj))


def dumps_json(obj: Any, *, indent: int | None = 2, cause: str | None = None) -> str:
    """Strict JSON text of ``obj`` (NumPy values as numbers/lists); refuses NaN/±inf (module docstring).
    With ``indent``, as ``json.dumps(indent=...)`` except that every item of a list longer than
    ``LONG_LIST`` items is one compact line."""
    try:
        if indent is None:
            return _compact(obj)
        out: list[str] = []
        _indented(obj, " " * indent, 0, out)
        return "".join(out)
    except ValueError:  # json's "Out of range float values": find and name the number
        check_finite(obj, cause)
        raise


def write_json(path: str | os.PathLike, obj: Any, *, indent: int | None = 2, cause: str | None = None) -> None:
    """Write ``obj`` as strict JSON to ``path`` atomically, with a final newline; nothing is written when it
    holds a non-finite number (raises :class:`NonFiniteResult`)."""
    from netshape._atomic import atomic_write

    text = dumps_json(obj, indent=indent, cause=cause)
    with atomic_write(path, "w") as fh:
        fh.write(text)
        fh.write("\n")
