"""netshape.geometry — NURBS curves and surfaces, normals, offsets, CC→CL, raster tool paths,
2-D contour offsets and triangle meshes (C++ namespace ``netshape::geometry``; docs/geometry.md).

Units: mm; parameters (u, v) are the NURBS's own. Arrays are float64 C-ordered, points (n, 3).
"""

from __future__ import annotations

from .._core import geometry as _g
from .paths import RasterPath, cc_to_cl, cutter_signed_distance, raster_toolpath
from .mesh import (
    OffsetRing,
    TriangleMesh,
    load_stl,
    offset_region,
    pocket_rings,
    pocket_toolpath,
    read_stl,
    rings_gcode,
    surface_mesh,
    write_stl,
)
from .samples import random_surface
from .interop import from_dict, from_geomdl, load_json, load_toml, save_json, save_toml, to_dict, to_geomdl

CurveProjection = _g.CurveProjection
SurfaceProjection = _g.SurfaceProjection
NurbsCurve = _g.NurbsCurve
NurbsSurface = _g.NurbsSurface
find_span = _g.find_span
basis_function_derivatives = _g.basis_function_derivatives
circular_arc = _g.circular_arc
revolve = _g.revolve
bilinear = _g.bilinear
offset_points = _g.offset_points
offset_grid = _g.offset_grid
scallop_step = _g.scallop_step

__all__ = [
    "OffsetRing",
    "TriangleMesh",
    "load_stl",
    "offset_region",
    "pocket_rings",
    "pocket_toolpath",
    "read_stl",
    "rings_gcode",
    "surface_mesh",
    "write_stl",
    "random_surface",
    "CurveProjection",
    "SurfaceProjection",
    "NurbsCurve",
    "NurbsSurface",
    "find_span",
    "basis_function_derivatives",
    "circular_arc",
    "revolve",
    "bilinear",
    "offset_points",
    "offset_grid",
    "scallop_step",
    "cc_to_cl",
    "cutter_signed_distance",
    "raster_toolpath",
    "RasterPath",
    "to_dict",
    "from_dict",
    "save_json",
    "load_json",
    "save_toml",
    "load_toml",
    "to_geomdl",
    "from_geomdl",
]
