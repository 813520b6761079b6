"""NURBS interop: ``geomdl`` objects and a small JSON / TOML form.

The dictionary form (also the JSON and TOML layout)::

    {"type": "surface", "degree_u": 3, "degree_v": 2,
     "knots_u": [...], "knots_v": [...],
     "control_points": [[x, y, z], ...],   # u-major, (count_u * count_v, 3) [mm]
     "weights": [...]}                      # optional, all 1 when absent

    {"type": "curve", "degree": 3, "knots": [...], "control_points": [[x, y, z], ...], "weights": [...]}
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import atomic_write
from .._core import geometry as _g

NurbsCurve = _g.NurbsCurve
NurbsSurface = _g.NurbsSurface


def to_dict(shape: NurbsCurve | NurbsSurface) -> dict[str, Any]:
    """Plain-Python (JSON/TOML-able) form of a curve or surface."""
    if isinstance(shape, NurbsSurface):
        return {
            "type": "surface",
            "degree_u": int(shape.degree_u),
            "degree_v": int(shape.degree_v),
            "knots_u": [float(k) for k in shape.knots_u],
            "knots_v": [float(k) for k in shape.knots_v],
            "control_points": np.asarray(shape.control_points).tolist(),
            "weights": [float(w) for w in shape.weights],
        }
    if isinstance(shape, NurbsCurve):
        return {
            "type": "curve",
            "degree": int(shape.degree),
            "knots": [float(k) for k in shape.knots],
            "control_points": np.asarray(shape.control_points).tolist(),
            "weights": [float(w) for w in shape.weights],
        }
    raise TypeError(f"to_dict expects a NurbsCurve or NurbsSurface, got {type(shape).__name__}")


def _require(d: dict[str, Any], key: str) -> Any:
    if key not in d:
        raise ValueError(f"NURBS {d.get('type', '?')}: missing key {key!r}")
    return d[key]


def _degree(d: dict[str, Any], key: str) -> int:
    v = _require(d, key)
    if isinstance(v, bool) or not isinstance(v, int):
        raise ValueError(f"{key} = {v!r}: must be an integer")
    return v


def _reals(value: Any, field: str, ndim: int = 1) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.ndim != ndim or not np.all(np.isfinite(arr)):
        shown = repr(value) if len(repr(value)) <= 60 else repr(value)[:57] + "..."
        raise ValueError(f"{field} = {shown}: must be " + ("a list of finite numbers" if ndim == 1 else
                                                           "a list of [x, y, z] points of finite numbers [mm]"))
    return arr


def _points(value: Any, field: str) -> np.ndarray:
    arr = _reals(value, field, 2)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{field} = array of shape {arr.shape}: must be (n, 3) [mm]")
    return np.ascontiguousarray(arr)


def from_dict(d: dict[str, Any]) -> NurbsCurve | NurbsSurface:
    """Inverse of :func:`to_dict`. Raises ValueError naming the bad key."""
    if not isinstance(d, dict):
        raise ValueError(f"document = {type(d).__name__}: must be an object/table with type = 'curve' or 'surface'")
    kind = d.get("type")
    weights = d.get("weights")
    w = None if weights is None else _reals(weights, "weights")
    if kind == "surface":
        return NurbsSurface(
            _degree(d, "degree_u"),
            _degree(d, "degree_v"),
            _reals(_require(d, "knots_u"), "knots_u"),
            _reals(_require(d, "knots_v"), "knots_v"),
            _points(_require(d, "control_points"), "control_points"),
            w,
        )
    if kind == "curve":
        return NurbsCurve(
            _degree(d, "degree"),
            _reals(_require(d, "knots"), "knots"),
            _points(_require(d, "control_points"), "control_points"),
            w,
        )
    raise ValueError(f"type = {kind!r}: must be 'curve' or 'surface'")


def _from_file(doc: Any, path) -> NurbsCurve | NurbsSurface:
    """:func:`from_dict` of a file's document; errors start with the file name."""
    try:
        return from_dict(doc)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"{path}: {' '.join(str(exc).split())}") from None


def save_json(shape: NurbsCurve | NurbsSurface, path: str | Path) -> None:
    """Write the dictionary form as JSON (atomically)."""
    from .._json import write_json

    write_json(path, to_dict(shape), indent=1)


def load_json(path: str | Path) -> NurbsCurve | NurbsSurface:
    from .._text import read_json

    return _from_file(read_json(path), path)


def save_toml(shape: NurbsCurve | NurbsSurface, path: str | Path) -> None:
    """Write the dictionary form as TOML (atomically)."""
    import tomli_w

    with atomic_write(path, "wb") as f:
        f.write(tomli_w.dumps(to_dict(shape)).encode("utf-8"))


def load_toml(path: str | Path) -> NurbsCurve | NurbsSurface:
    from netshape._config import load_toml as read_document

    return _from_file(read_document(path), path)


def to_geomdl(shape: NurbsCurve | NurbsSurface):
    """A ``geomdl.NURBS.Curve`` / ``geomdl.NURBS.Surface`` with the same degree, knots, points, weights."""
    from geomdl import NURBS

    if isinstance(shape, NurbsSurface):
        s = NURBS.Surface()
        s.degree_u, s.degree_v = int(shape.degree_u), int(shape.degree_v)
        cp = np.asarray(shape.control_points)
        w = np.asarray(shape.weights)
        # geomdl stores weighted points (x w, y w, z w, w), u-major like netshape
        cpw = np.hstack([cp * w[:, None], w[:, None]])
        s.set_ctrlpts(cpw.tolist(), int(shape.count_u), int(shape.count_v))
        s.knotvector_u = [float(k) for k in shape.knots_u]
        s.knotvector_v = [float(k) for k in shape.knots_v]
        return s
    if isinstance(shape, NurbsCurve):
        c = NURBS.Curve()
        c.degree = int(shape.degree)
        cp = np.asarray(shape.control_points)
        w = np.asarray(shape.weights)
        c.ctrlptsw = np.hstack([cp * w[:, None], w[:, None]]).tolist()
        c.knotvector = [float(k) for k in shape.knots]
        return c
    raise TypeError(f"to_geomdl expects a NurbsCurve or NurbsSurface, got {type(shape).__name__}")


def from_geomdl(obj) -> NurbsCurve | NurbsSurface:
    """Convert a geomdl ``BSpline``/``NURBS`` curve or surface (3-D) into netshape's."""
    pdim = getattr(obj, "pdimension", None)
    if pdim == 2:
        cp = np.asarray(obj.ctrlpts, dtype=float)
        w = np.asarray(obj.weights, dtype=float) if getattr(obj, "weights", None) else None
        return NurbsSurface(
            int(obj.degree_u),
            int(obj.degree_v),
            np.asarray(obj.knotvector_u, dtype=float),
            np.asarray(obj.knotvector_v, dtype=float),
            _points(cp, "ctrlpts"),
            w,
        )
    if pdim == 1:
        cp = np.asarray(obj.ctrlpts, dtype=float)
        w = np.asarray(obj.weights, dtype=float) if getattr(obj, "weights", None) else None
        return NurbsCurve(int(obj.degree), np.asarray(obj.knotvector, dtype=float), _points(cp, "ctrlpts"), w)
    raise TypeError(f"from_geomdl expects a geomdl curve or surface, got {type(obj).__name__}")
