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
import tomllib
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


def _points(value: Any, field: str) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"{field} = array of shape {arr.shape}: must be (n, 3) [mm]")
    return np.ascontiguousarray(arr)


def from_dict(d: dict[str, Any]) -> NurbsCurve | NurbsSurface:
    """Inverse of :func:`to_dict`. Raises ValueError naming the bad key."""
    kind = d.get("type")
    weights = d.get("weights")
    w = None if weights is None else np.asarray(weights, dtype=float)
    if kind == "surface":
        return NurbsSurface(
            int(_require(d, "degree_u")),
            int(_require(d, "degree_v")),
            np.asarray(_require(d, "knots_u"), dtype=float),
            np.asarray(_require(d, "knots_v"), dtype=float),
            _points(_require(d, "control_points"), "control_points"),
            w,
        )
    if kind == "curve":
        return NurbsCurve(
            int(_require(d, "degree")),
            np.asarray(_require(d, "knots"), dtype=float),
            _points(_require(d, "control_points"), "control_points"),
            w,
        )
    raise ValueError(f"type = {kind!r}: must be 'curve' or 'surface'")


def save_json(shape: NurbsCurve | NurbsSurface, path: str | Path) -> None:
    """Write the dictionary form as JSON (atomically)."""
    from .._json import write_json

    write_json(path, to_dict(shape), indent=1)


def load_json(path: str | Path) -> NurbsCurve | NurbsSurface:
    with open(path, encoding="utf-8") as f:
        return from_dict(json.load(f))


def save_toml(shape: NurbsCurve | NurbsSurface, path: str | Path) -> None:
    """Write the dictionary form as TOML (atomically)."""
    import tomli_w

    with atomic_write(path, "wb") as f:
        f.write(tomli_w.dumps(to_dict(shape)).encode("utf-8"))


def load_toml(path: str | Path) -> NurbsCurve | NurbsSurface:
    with open(path, "rb") as f:
        return from_dict(tomllib.load(f))


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
