"""Plots of planned runs (matplotlib Agg; functions return Figures and never show())."""

from __future__ import annotations


def plot_profiles(traj, *, title: str = "", per_minute: bool = True):
    """Feed profile (top) and per-axis velocity profiles (bottom) against time, as in Lee & Lee
    Fig. 12 (b, c) and Fig. 14–15. Feeds in mm/min when `per_minute`, else mm/s."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    k = 60.0 if per_minute else 1.0
    unit = "mm/min" if per_minute else "mm/s"
    fig = Figure(figsize=(8, 6), constrained_layout=True)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    ax1.plot(traj.t, traj.feed * k, lw=1.0, color="k")
    ax1.set_ylabel(f"feed [{unit}]")
    ax1.grid(alpha=0.3)
    if title:
        ax1.set_title(title)
    for i, (name, c) in enumerate(zip("XYZ", ("C0", "C1", "C2"))):
        ax2.plot(traj.t, traj.velocity[:, i] * k, lw=1.0, color=c, label=name)
    ax2.set_ylabel(f"axis velocity [{unit}]")
    ax2.set_xlabel("time [s]")
    ax2.legend(loc="upper right")
    ax2.grid(alpha=0.3)
    return fig


def plot_path(traj, program_points=None, *, title: str = ""):
    """XY path of the samples (and the programmed points if given)."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6, 4), constrained_layout=True)
    ax = fig.subplots()
    if program_points is not None:
        ax.plot(program_points[:, 0], program_points[:, 1], "o-", ms=2, lw=0.5, color="0.6", label="program")
    ax.plot(traj.position[:, 0], traj.position[:, 1], lw=1.0, color="k", label="samples")
    ax.set_aspect("equal")
    ax.set_xlabel("X [mm]")
    ax.set_ylabel("Y [mm]")
    ax.legend()
    if title:
        ax.set_title(title)
    return fig
