"""netshape.stock — the Z-map workpiece (C++ ``netshape::stock``; docs/stock.md;
Kim et al. §2, docs/references.md).

A :class:`ZMap` is a regular grid of material heights [mm] over a rectangle of the machine XY plane.
Sweeping a cutter (flat, ball, bull-nose; tool axis +Z) along lines, polylines, blocks or whole
programs lowers every node to the lowest point the cutter's tip surface reaches over the move,
computed exactly per node (not sampled). Engagement queries say which cutter elements are in
material at a cutter position, in the cutting frame of docs/conventions.md §2.

    import numpy as np
    import netshape as ns
    z = ns.stock.ZMap(0, 100, 0, 60, spacing=0.1, top=20, bottom=0)
    tool = ns.stock.Cutter.ball_end(10.0, 2, 0.5236)
    ns.stock.sweep_line(z, tool, (-10, 30, 17), (110, 30, 17))
    h = z.heights                      # (ny, nx) live read-only view [mm]
    z.to_stl("part.stl")               # closed solid, written atomically
    m = ns.stock.engaged_elements(z, tool, tip, feed_dir, phi, zs)   # (k, m) bool

Units: mm, rad. See docs/stock.md.
"""

from __future__ import annotations

import os

import numpy as np

from .._core import cutter as _cutter_mod
from .._core import stock as _stock

#: The cutter class, re-exported from netshape.cutter for convenience.
Cutter = _cutter_mod.Cutter

ZMap = _stock.ZMap
TipProfile = _stock.TipProfile
SweepOptions = _stock.SweepOptions
SweepStats = _stock.SweepStats
Immersion = _stock.Immersion
ImmersionOptions = _stock.ImmersionOptions

lowest_reach_line = _stock.lowest_reach_line
sweep_line = _stock.sweep_line
sweep_lines = _stock.sweep_lines
sweep_polyline = _stock.sweep_polyline
sweep_block = _stock.sweep_block
sweep = _stock.sweep
cutting_frame = _stock.cutting_frame
element_point = _stock.element_point
engaged_elements = _stock.engaged_elements
immersion = _stock.immersion
stl_triangle_count = _stock.stl_triangle_count


def node_coordinates(zmap: ZMap) -> tuple[np.ndarray, np.ndarray]:
    """Node coordinates of the grid: ``xs`` (nx,) and ``ys`` (ny,) [mm] (cell centres)."""
    xs = zmap.x0 + (np.arange(zmap.nx) + 0.5) * zmap.dx
    ys = zmap.y0 + (np.arange(zmap.ny) + 0.5) * zmap.dy
    return xs, ys


def from_heights(heights, x0: float, x1: float, y0: float, y1: float, bottom: float) -> ZMap:
    """A Z-map from an (ny, nx) array of node heights [mm] over [x0, x1] x [y0, y1] [mm] (copied)."""
    h = np.ascontiguousarray(heights, dtype=np.float64)
    if h.ndim != 2:
        raise ValueError(f"heights.ndim = {h.ndim}: must be 2 (ny, nx)")
    return ZMap.from_heights(h, x0, x1, y0, y1, bottom)


def to_stl(zmap: ZMap, path: str | os.PathLike) -> None:
    """Write the Z-map as a closed binary STL solid [mm] (written whole or not at all)."""
    _stock.write_stl(zmap, os.fspath(path))


def read_stl(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """Read a binary STL: ``(normals (n, 3), triangles (n, 3, 3))`` as float32 [mm]."""
    data = np.fromfile(os.fspath(path), dtype=np.uint8)
    if data.size < 84:
        raise ValueError(f"path = {os.fspath(path)!r}: too short for a binary STL ({data.size} bytes)")
    n = int(data[80:84].view("<u4")[0])
    if data.size != 84 + 50 * n:
        raise ValueError(f"path = {os.fspath(path)!r}: {data.size} bytes, expected {84 + 50 * n} for {n} triangles")
    rec = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    tris = data[84:].view(rec)
    return tris["normal"].copy(), tris["v"].copy()


def plot_heights(zmap: ZMap, *, ax=None, title: str | None = None, cmap: str = "viridis"):
    """Figure of the height field (image of the node heights with a colour bar [mm]).

    Returns the matplotlib Figure (Agg; never shown).
    """
    from .plot import plot_heights as _plot

    return _plot(zmap, ax=ax, title=title, cmap=cmap)


# bound as methods too, for ``z.to_stl(path)`` and ``z.plot()``
ZMap.to_stl = to_stl
ZMap.plot = plot_heights

__all__ = [
    "Cutter",
    "ZMap",
    "TipProfile",
    "SweepOptions",
    "SweepStats",
    "Immersion",
    "ImmersionOptions",
    "lowest_reach_line",
    "sweep_line",
    "sweep_lines",
    "sweep_polyline",
    "sweep_block",
    "sweep",
    "cutting_frame",
    "element_point",
    "engaged_elements",
    "immersion",
    "stl_triangle_count",
    "node_coordinates",
    "from_heights",
    "to_stl",
    "read_stl",
    "plot_heights",
]
