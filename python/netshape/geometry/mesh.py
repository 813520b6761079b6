"""Triangle meshes (CGAL AABB tree), STL in and out, and 2-D contour offsets (CGAL circle-segment
offsets) — Python side of triangle_mesh.hpp, stl.hpp and contour_offset.hpp."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._core import geometry as _g

TriangleMesh = _g.TriangleMesh


def read_stl(path: str | Path) -> tuple[np.ndarray, np.ndarray, str]:
    """(vertices (v, 3) float64, faces (m, 3) int64, name) of an ASCII or binary STL file."""
    return _g.read_stl(str(path))


def load_stl(path: str | Path) -> TriangleMesh:
    """A :class:`TriangleMesh` (AABB tree built) from an STL file."""
    return _g.load_stl(str(path))


def write_stl(path: str | Path, mesh_or_vertices, faces=None, *, binary: bool = True, name: str = "netshape"):
    """Write a mesh (or vertices (v, 3) + faces (m, 3)) as STL, atomically."""
    if faces is None:
        vertices, faces = mesh_or_vertices.vertices, mesh_or_vertices.faces
    else:
        vertices = mesh_or_vertices
    _g.write_stl(str(path), np.ascontiguousarray(vertices, float), np.ascontiguousarray(faces, np.int64),
                 binary, name)


def surface_mesh(surface, count_u: int = 50, count_v: int = 50) -> TriangleMesh:
    """Triangulate a NURBS surface on a regular (count_u × count_v) parameter grid."""
    if count_u < 2 or count_v < 2:
        raise ValueError(f"count_u, count_v = {count_u}, {count_v}: must be at least 2")
    us = np.linspace(*surface.domain_u, count_u)
    vs = np.linspace(*surface.domain_v, count_v)
    pts = surface.evaluate_grid(us, vs, normals=False)
    i, j = np.meshgrid(np.arange(count_u - 1), np.arange(count_v - 1), indexing="ij")
    a = (i * count_v + j).ravel()
    b, c, d = a + count_v, a + count_v + 1, a + 1
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype(np.int64)
    return TriangleMesh(pts, faces)


@dataclass
class OffsetRing:
    """A closed ring of lines and arcs in the XY plane. kind (n,) 1 line / 2 arc; start, end, center
    (n, 2) [mm]; clockwise (n,); hole: bounds an island; area: signed [mm²] (exact arcs);
    polyline (k, 2): arcs split at 1 µm chord error."""

    kind: np.ndarray
    start: np.ndarray
    end: np.ndarray
    center: np.ndarray
    clockwise: np.ndarray
    hole: bool
    area: float
    polyline: np.ndarray

    @classmethod
    def _from(cls, d) -> "OffsetRing":
        return cls(d["kind"], d["start"], d["end"], d["center"], d["clockwise"], bool(d["hole"]),
                   float(d["area"]), d["polyline"])


def _contour(p, field: str) -> np.ndarray:
    a = np.ascontiguousarray(np.asarray(p, dtype=float))
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError(f"{field} = array of shape {a.shape}: must be (n, 2) [mm]")
    return a


def offset_region(outer, islands=(), distance: float = -1.0, tolerance: float = 1e-6) -> list[OffsetRing]:
    """Offset of a region (outer contour minus islands) by ``distance`` [mm] with round (arc) corners:
    < 0 inward, > 0 outward. Self-intersecting contours raise ValueError."""
    isl = [_contour(x, f"islands[{k}]") for k, x in enumerate(islands)]
    return [OffsetRing._from(d) for d in _g._offset_region(_contour(outer, "outer"), isl, float(distance),
                                                           float(tolerance))]


def pocket_rings(outer, islands=(), tool_radius: float = 1.0, step_over: float = 1.0,
                 tolerance: float = 1e-6) -> list[list[OffsetRing]]:
    """Inward rings at the tool radius, then every ``step_over`` [mm] until the pocket is used up."""
    isl = [_contour(x, f"islands[{k}]") for k, x in enumerate(islands)]
    levels = _g._pocket_rings(_contour(outer, "outer"), isl, float(tool_radius), float(step_over), float(tolerance))
    return [[OffsetRing._from(d) for d in lv] for lv in levels]


def pocket_toolpath(outer, islands=(), *, tool_radius: float, step_over: float, z: float,
                    clearance: float = 2.0, feed: float = 10.0, spindle_rpm: float = 10000.0, tool: int = 1,
                    tolerance: float = 1e-6):
    """Pocket rings as a ``netshape.toolpath.Toolpath`` of lines and XY arcs at height ``z`` [mm]
    (innermost ring first; rapid to ``z + clearance``, plunge, ring, retract). Feed in mm/s. Write it
    with ``netshape.toolpath.write_gcode``."""
    isl = [_contour(x, f"islands[{k}]") for k, x in enumerate(islands)]
    return _g._pocket_toolpath(_contour(outer, "outer"), isl, float(tool_radius), float(step_over), float(z),
                               float(clearance), float(feed), float(spindle_rpm), int(tool), float(tolerance))


def rings_gcode(levels: list[list[OffsetRing]], *, z: float, clearance: float = 2.0, feed: float = 10.0,
                spindle_rpm: float = 10000.0, tool: int = 1, decimals: int = 4) -> str:
    """Pocket rings as RS274 text (G17 XY arcs with I J incremental centres), innermost level first;
    feed [mm/s] written as F in mm/min."""
    f = f"{{:.{decimals}f}}"
    out = ["(netshape.geometry pocket rings)", "G21 G90 G17", f"T{int(tool)} M6", f"S{abs(spindle_rpm):.0f} M3"]
    top = z + clearance
    for level in reversed(levels):
        for ring in level:
            if len(ring.kind) == 0:
                continue
            x0, y0 = ring.start[0]
            out.append(f"G0 Z{f.format(top)}")
            out.append(f"G0 X{f.format(x0)} Y{f.format(y0)}")
            out.append(f"G1 Z{f.format(z)} F{feed * 60.0:.1f}")
            for k in range(len(ring.kind)):
                ex, ey = ring.end[k]
                if ring.kind[k] == 2:
                    i = ring.center[k][0] - ring.start[k][0]
                    j = ring.center[k][1] - ring.start[k][1]
                    code = "G2" if ring.clockwise[k] else "G3"
                    out.append(f"{code} X{f.format(ex)} Y{f.format(ey)} I{f.format(i)} J{f.format(j)}")
                else:
                    out.append(f"G1 X{f.format(ex)} Y{f.format(ey)}")
    out += [f"G0 Z{f.format(top)}", "M5", "M30"]
    return "\n".join(out) + "\n"
