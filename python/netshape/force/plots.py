"""Plots of force series (matplotlib, Agg; return Figures, never show)."""

from __future__ import annotations

import numpy as np


def plot_forces(angles, forces, *, title: str = "", rpm: float | None = None):
    """Fx, Fy, Fz [N] against the rotation angle [deg] (and time [ms] on top when rpm is given)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    angles = np.degrees(np.asarray(angles, float))
    forces = np.asarray(forces, float)
    fig = Figure(figsize=(8, 4.5))
    ax = fig.add_subplot(111)
    for j, name in enumerate(("Fx", "Fy", "Fz")):
        ax.plot(angles, forces[:, j], label=name)
    ax.plot(angles, np.linalg.norm(forces, axis=1), "k:", lw=1, label="|F|")
    ax.set_xlabel("immersion of flute 1 at the tip φ [deg]")
    ax.set_ylabel("force on the cutter [N]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", ncol=4, fontsize=8)
    if rpm:
        sec = ax.secondary_xaxis("top", functions=(lambda d: d / 360 * 60000 / rpm, lambda t: t * rpm / 60000 * 360))
        sec.set_xlabel("time [ms]")
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig


def plot_measured_vs_simulated(times, measured, simulated, *, title: str = ""):
    """Three stacked axes (Fx, Fy, Fz): measured and simulated [N] against time [ms]."""
    from matplotlib.figure import Figure

    t = (np.asarray(times, float) - float(times[0])) * 1e3
    fig = Figure(figsize=(9, 6.5))
    axes = fig.subplots(3, 1, sharex=True)
    for j, (ax, name) in enumerate(zip(axes, ("Fx", "Fy", "Fz"))):
        ax.plot(t, measured[:, j], color="0.3", lw=1.2, label="measured")
        ax.plot(t, simulated[:, j], color="C3", lw=1.2, label="model")
        ax.set_ylabel(f"{name} [N]")
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel("time [ms]")
    if title:
        axes[0].set_title(title, fontsize=9)
    fig.tight_layout()
    return fig
