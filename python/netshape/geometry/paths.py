"""Offsets, CC→CL and raster tool paths over NURBS design surfaces (Python side of
``netshape::geometry`` offset.hpp, cutter_location.hpp, raster.hpp)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._core import cutter as _cutter
from .._core import geometry as _g

_KINDS = ("flat", "ball", "bull")


def _as_cutter(cutter: Any) -> _cutter.Cutter:
    """The netshape Cutter itself (passed whole to C++), or one made from a mapping
    ``{"kind", "radius", "corner_radius"}`` or a tuple ``(kind, radius[, corner_radius])`` [mm] with the
    Cutter factories' flutes, helix and lengths (the geometry uses only the shape)."""
    if isinstance(cutter, _cutter.Cutter):
        return cutter
    if isinstance(cutter, dict):
        kind, radius, corner = cutter.get("kind"), cutter.get("radius"), cutter.get("corner_radius", 0.0)
    elif isinstance(cutter, (tuple, list)):
        kind, radius = cutter[0], cutter[1]
        corner = cutter[2] if len(cutter) > 2 else 0.0
    else:
        raise ValueError(f"cutter = {cutter!r}: must be a netshape Cutter, a dict or a (kind, radius[, corner_radius]) "
                         "tuple [mm]")
    kind = str(getattr(kind, "name", kind)).split(".")[-1].lower()
    if kind in ("bullnose", "bull-nose"):
        kind = "bull"
    if kind not in _KINDS:
        raise ValueError(f"cutter.kind = {kind!r}: must be one of flat, ball, bull")
    if radius is None:
        raise ValueError("cutter.radius = None: must be a positive number [mm]")
    d = 2.0 * float(radius)
    helix = _cutter.Cutter().helix
    if kind == "ball":
        return _cutter.Cutter.ball_end(d, 2, helix)
    if kind == "bull":
        return _cutter.Cutter.bull_nose(d, float(corner or 0.0), 2, helix)
    return _cutter.Cutter.flat_end(d, 2, helix)


def _axis(axis) -> np.ndarray:
    a = np.asarray(axis, dtype=float).reshape(3)
    return a


def cc_to_cl(cutter: Any, cc, normals, axis=(0.0, 0.0, 1.0)) -> np.ndarray:
    """CL (tool-tip) points for CC points with unit surface normals (pointing out of the material).

    Parameters
    ----------
    cutter : netshape Cutter, dict or tuple (kind, radius [mm], corner_radius [mm])
    cc, normals : float64 (m, 3) [mm], (m, 3)
    axis : (3,) tool axis from the tip into the spindle (any length)

    Returns
    -------
    float64 (m, 3) tool-tip positions [mm]: ``tip = cc + r n + (R - r) e - r a`` (docs/geometry.md).
    """
    c = _as_cutter(cutter)
    cc = np.ascontiguousarray(np.atleast_2d(cc), dtype=float)
    normals = np.ascontiguousarray(np.atleast_2d(normals), dtype=float)
    return _g._cc_to_cl(c, cc, normals, _axis(axis))


def cutter_signed_distance(cutter: Any, tip, axis, points) -> np.ndarray:
    """Signed distance [mm] from points (m, 3) to the cutter solid with its tip at ``tip``: < 0 inside."""
    pts = np.ascontiguousarray(np.atleast_2d(points), dtype=float)
    return _g._cutter_signed_distance(_as_cutter(cutter), np.asarray(tip, dtype=float), _axis(axis), pts)


@dataclass
class RasterPath:
    """A raster tool path as block arrays: kind (n,) uint8 (0 rapid, 1 line), start/end (n, 3) tool-tip
    positions [mm], feed (n,) [mm/s]. ``spindle_rpm`` and ``tool`` apply to every block."""

    kind: np.ndarray
    start: np.ndarray
    end: np.ndarray
    feed: np.ndarray
    spindle_rpm: float = 10000.0
    tool: int = 1
    meta: dict[str, Any] = field(default_factory=dict)
    toolpath: Any = None  #: the same path as a netshape.toolpath.Toolpath

    def __len__(self) -> int:
        return int(self.kind.shape[0])

    def cl_points(self) -> np.ndarray:
        """(n + 1, 3) polyline of tool-tip positions."""
        return np.vstack([self.start[:1], self.end])

    def feed_length(self) -> float:
        m = self.kind == 1
        return float(np.linalg.norm(self.end[m] - self.start[m], axis=1).sum())

    def to_gcode(self, **kwargs) -> str:
        """G-code text through the toolpath area's writer (``netshape.toolpath.format_gcode``; F in
        mm/min, only changed words per line). Keyword arguments go to the writer."""
        from .. import toolpath as tp

        kwargs.setdefault("header_comment", "netshape.geometry raster tool path: tool-tip positions")
        return tp.format_gcode(self.to_toolpath(), **kwargs)

    def write_gcode(self, path: str | Path, **kwargs) -> None:
        """Write the G-code to ``path`` whole or not at all (``netshape.toolpath.write_gcode``)."""
        from .. import toolpath as tp

        kwargs.setdefault("header_comment", "netshape.geometry raster tool path: tool-tip positions")
        tp.write_gcode(self.to_toolpath(), path, **kwargs)

    def to_toolpath(self):
        """The path as a ``netshape.toolpath.Toolpath`` (blocks with kind, start, end, feed, rpm, tool)."""
        if self.toolpath is None:
            raise ValueError("toolpath = None: this RasterPath was not made by raster_toolpath")
        return self.toolpath


def raster_toolpath(
    surface,
    cutter: Any,
    *,
    axis=(0.0, 0.0, 1.0),
    scallop_height: float = 0.01,
    step_over: float = 0.0,
    chord_tolerance: float = 0.005,
    stock_allowance: float = 0.0,
    along_u: bool = True,
    zigzag: bool = True,
    feed: float = 20.0,
    plunge_feed: float = 0.0,
    clearance: float = 5.0,
    spindle_rpm: float = 10000.0,
    tool: int = 1,
) -> RasterPath:
    """Iso-parametric raster over ``surface`` (see raster.hpp): passes along u (or v), step-over from the
    scallop height (ball radius / bull corner radius, curvature-adjusted) or a fixed ``step_over`` [mm],
    CC points offset by ``stock_allowance`` [mm] along the normal, CL = tool tip. Feeds in mm/s."""
    c = _as_cutter(cutter)
    arrays, tp = _g._raster_toolpath(
        surface, c, _axis(axis), float(scallop_height), float(step_over), float(chord_tolerance),
        float(stock_allowance), bool(along_u), bool(zigzag), float(feed), float(plunge_feed), float(clearance),
        float(spindle_rpm), int(tool),
    )
    d = arrays.to_dict()
    return RasterPath(
        d["kind"], d["start"], d["end"], d["feed"], float(spindle_rpm), int(tool),
        {"cutter": (_KINDS[int(c.kind)], c.radius, c.corner_radius), "scallop_height": scallop_height, "step_over": step_over}, tp,
    )
