"""Plots of a Z-map (matplotlib, Agg backend; functions return a Figure and never show it)."""

from __future__ import annotations

import numpy as np


def plot_heights(zmap, *, ax=None, title: str | None = None, cmap: str = "viridis"):
    """Image of the node heights [mm] over the footprint, with a colour bar. Returns the Figure."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    if ax is None:
        fig = Figure(figsize=(7.0, 5.0), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    h = np.asarray(zmap.heights)
    im = ax.imshow(h, origin="lower", extent=(zmap.x0, zmap.x1, zmap.y0, zmap.y1), cmap=cmap,
                   interpolation="nearest", aspect="equal")
    fig.colorbar(im, ax=ax, label="height z [mm]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(title or f"Z-map {zmap.ny} x {zmap.nx} nodes, {zmap.dx:g} x {zmap.dy:g} mm cells")
    return fig
