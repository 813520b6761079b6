"""Volumetric error maps (Yang & Kweon eq. 16) over a grid and along a program, and their plots
(Yang & Kweon Fig. 6–7). Plots return matplotlib Figures (Agg) and never show them."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Sequence

import numpy as np

from .._core import machine as _m

_ORDERS = {"exact": _m.Order.exact, "first": _m.Order.first}


def _order(order: str):
    if order not in _ORDERS:
        raise ValueError(f"order = {order!r}: must be 'exact' or 'first'")
    return _ORDERS[order]


def _points(points: Any) -> np.ndarray:
    p = np.ascontiguousarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points shape = {p.shape}: must be (n, 3) [mm]")
    if not np.isfinite(p).all():
        raise ValueError("points: must be finite numbers [mm]")
    return p


def tip_error(machine: _m.Machine, points: Any, order: str = "exact") -> np.ndarray:
    """Tool-tip error relative to the workpiece e(p) [mm] at program points p, (n, 3) → (n, 3)."""
    return _m.tip_error(machine, _points(points), _order(order))


def actual_points(machine: _m.Machine, commanded: Any, order: str = "exact") -> np.ndarray:
    """Where the tip lands for commanded points, p + e(p) [mm], (n, 3) → (n, 3)."""
    return _m.actual_points(machine, _points(commanded), _order(order))


def volumetric_error(machine: _m.Machine, points: Any, order: str = "exact") -> np.ndarray:
    """VE = |e(p)| [mm] (Yang & Kweon eq. 16), (n, 3) → (n,)."""
    return _m.volumetric_error(machine, _points(points), _order(order))


def compare_orders(machine: _m.Machine, points: Any) -> dict[str, float]:
    """Exact vs first-order synthesis at ``points``: largest and RMS |exact − first| [mm] and the
    largest |exact| [mm] for scale."""
    p = _points(points)
    e = _m.tip_error(machine, p, _m.Order.exact)
    f = _m.tip_error(machine, p, _m.Order.first)
    d = np.linalg.norm(e - f, axis=1)
    return {"max_difference_mm": float(d.max(initial=0.0)),
            "rms_difference_mm": float(np.sqrt(np.mean(d**2))) if len(d) else 0.0,
            "max_error_mm": float(np.linalg.norm(e, axis=1).max(initial=0.0))}


def grid_points(machine: _m.Machine, grid: Sequence[int] = (5, 5, 5),
                bounds: Any = None) -> np.ndarray:
    """Regular grid over ``bounds`` ((3, 2) [mm]: min, max per axis; default the axes' travel),
    ``grid`` = (nx, ny, nz) points per axis, ≥ 1 each. Returns (nx·ny·nz, 3), x fastest."""
    g = [int(v) for v in grid]
    if len(g) != 3 or min(g) < 1:
        raise ValueError(f"grid = {tuple(grid)}: must be 3 counts ≥ 1")
    if np.prod(g) > 50_000_000:
        raise ValueError(f"grid = {tuple(g)}: more than 5e7 points")
    if bounds is None:
        b = np.array([[a.travel_min, a.travel_max] for a in machine.axes])
        if np.any(np.abs(b) >= 1e9):
            raise ValueError("grid bounds: the machine has unlimited travel on an axis; give bounds")
    else:
        b = np.asarray(bounds, dtype=float)
        if b.shape != (3, 2) or not np.isfinite(b).all() or np.any(b[:, 0] > b[:, 1]):
            raise ValueError(f"bounds = {bounds!r}: must be [[xmin, xmax], [ymin, ymax], [zmin, zmax]] [mm]")
    axes = [np.linspace(b[k, 0], b[k, 1], g[k]) for k in range(3)]
    z, y, x = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


@dataclass
class ErrorMap:
    """Tip errors at points: ``points`` (n, 3) [mm], ``errors`` (n, 3) [mm] (exact), ``volumetric``
    (n,) [mm] = |errors|, ``first_order_difference`` (n,) [mm] = |exact − first order|."""

    points: np.ndarray
    errors: np.ndarray
    volumetric: np.ndarray
    first_order_difference: np.ndarray
    shape: tuple = ()
    label: str = ""
    meta: dict = field(default_factory=dict)

    def summary(self) -> dict[str, Any]:
        ve = self.volumetric
        return {
            "label": self.label,
            "points": int(len(ve)),
            "min_um": float(ve.min() * 1e3) if len(ve) else 0.0,
            "max_um": float(ve.max() * 1e3) if len(ve) else 0.0,
            "mean_um": float(ve.mean() * 1e3) if len(ve) else 0.0,
            "max_exact_minus_first_order_um": float(self.first_order_difference.max(initial=0.0) * 1e3),
            **self.meta,
        }

    def to_dict(self, points: bool = False) -> dict[str, Any]:
        d: dict[str, Any] = {"summary": self.summary(), "shape": list(self.shape)}
        if points:
            d["points_mm"] = self.points.tolist()
            d["errors_mm"] = self.errors.tolist()
        return d


def error_map(machine: _m.Machine, points: Any, shape: tuple = (), label: str = "") -> ErrorMap:
    """:class:`ErrorMap` at ``points`` (n, 3) [mm]."""
    p = _points(points)
    e = _m.tip_error(machine, p, _m.Order.exact)
    f = _m.tip_error(machine, p, _m.Order.first)
    with np.errstate(over="ignore", invalid="ignore"):  # a non-finite model is the caller's to name
        return ErrorMap(p, e, np.linalg.norm(e, axis=1), np.linalg.norm(e - f, axis=1), tuple(shape), label)


def grid_error_map(machine: _m.Machine, grid: Sequence[int] = (5, 5, 5), bounds: Any = None) -> ErrorMap:
    """:class:`ErrorMap` over a regular grid (see :func:`grid_points`); shape (nz, ny, nx)."""
    p = grid_points(machine, grid, bounds)
    g = tuple(int(v) for v in grid)
    return error_map(machine, p, (g[2], g[1], g[0]), f"grid {g[0]}x{g[1]}x{g[2]}")


def program_points(program: Any, chord_tolerance: float = 0.01) -> np.ndarray:
    """Points along a program (path or Toolpath): block start and end points, arcs split into
    chords within ``chord_tolerance`` [mm]. Rapids included. (n, 3) [mm]."""
    from .. import toolpath as tpm

    if isinstance(program, (str, os.PathLike)):
        arr = tpm.read_gcode_arrays(program, arcs="split", chord_tolerance=chord_tolerance)
        if len(arr["kind"]) == 0:
            return np.zeros((0, 3))
        return np.vstack([arr["start"][:1], arr["end"]])
    tp = program.split_arcs(float(chord_tolerance))
    blocks = tp.blocks
    if not blocks:
        return np.zeros((0, 3))
    return np.vstack([np.asarray(blocks[0].start)[None, :]] + [np.asarray(b.end)[None, :] for b in blocks])


def program_error_map(machine: _m.Machine, program: Any, chord_tolerance: float = 0.01) -> ErrorMap:
    """:class:`ErrorMap` along a program (see :func:`program_points`)."""
    return error_map(machine, program_points(program, chord_tolerance), label="program")


def plot_error_map(emap: ErrorMap, scale: float | None = None, title: str | None = None):
    """Yang & Kweon Fig. 6: the workspace points coloured by volumetric error [µm] with the error
    vectors drawn ×``scale`` (default: the longest arrow is 10 % of the workspace diagonal)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    p, e, ve = emap.points, emap.errors, emap.volumetric * 1e3
    fig = Figure(figsize=(7.5, 6))
    ax = fig.add_subplot(projection="3d")
    if len(p):
        diag = float(np.linalg.norm(p.max(0) - p.min(0))) or 1.0
        s = scale if scale is not None else 0.1 * diag / max(float(np.abs(e).max()), 1e-30) / np.sqrt(3)
        sc = ax.scatter(p[:, 0], p[:, 1], p[:, 2], c=ve, cmap="viridis", s=12)
        step = max(1, int(np.ceil(len(p) / 400)))  # at most ~400 arrows
        q, d = p[::step], e[::step] * s
        ax.quiver(q[:, 0], q[:, 1], q[:, 2], d[:, 0], d[:, 1], d[:, 2], color="0.3", linewidth=0.6,
                  arrow_length_ratio=0.2)
        fig.colorbar(sc, ax=ax, shrink=0.7, pad=0.12, label="volumetric error [µm]")
        ax.set_title(title or f"Volumetric error map: {ve.min():.1f} – {ve.max():.1f} µm "
                     f"(arrows ×{s:.3g})", fontsize=10)
    ax.set_xlabel("X [mm]")
    ax.set_ylabel("Y [mm]")
    ax.set_zlabel("Z [mm]")
    return fig


def plot_surface_error(surface: Any, errors: Any, scale: float = 10.0, title: str | None = None,
                       compensated: Any = None):
    """Yang & Kweon Fig. 7/9/10: a gridded surface (nu, nv, 3) [mm] as a solid wireframe and the same
    surface moved by its errors (nu, nv, 3) [mm] ×``scale`` dashed; optionally a second error
    field ``compensated`` (after compensation) in red."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    s = np.asarray(surface, dtype=float)
    e = np.asarray(errors, dtype=float)
    if s.ndim != 3 or s.shape[2] != 3 or e.shape != s.shape:
        raise ValueError(f"surface shape = {s.shape}, errors shape = {e.shape}: must both be (nu, nv, 3)")
    fig = Figure(figsize=(7.5, 6))
    ax = fig.add_subplot(projection="3d")
    ax.plot_wireframe(s[..., 0], s[..., 1], s[..., 2], color="0.2", linewidth=0.6, label="nominal")
    m = s + scale * e
    ax.plot_wireframe(m[..., 0], m[..., 1], m[..., 2], color="tab:blue", linewidth=0.6, linestyle="--",
                      label=f"with error ×{scale:g}")
    if compensated is not None:
        c = s + scale * np.asarray(compensated, dtype=float)
        ax.plot_wireframe(c[..., 0], c[..., 1], c[..., 2], color="tab:red", linewidth=0.6,
                          label=f"after compensation ×{scale:g}")
    ve = np.linalg.norm(e, axis=2) * 1e3
    ax.set_title(title or f"Offset surface, volumetric error {ve.min():.1f} – {ve.max():.1f} µm", fontsize=10)
    ax.set_xlabel("X [mm]")
    ax.set_ylabel("Y [mm]")
    ax.set_zlabel("Z [mm]")
    ax.legend(loc="upper left", fontsize=8)
    return fig
