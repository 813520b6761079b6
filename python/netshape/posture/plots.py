"""Plots of a posture plan: the C-space of one CC point (polar: radius = tilt θ, angle = rotation φ) and the
posture angles along the path. Each returns a matplotlib Figure and never calls show()."""

from __future__ import annotations

import math

import numpy as np


def plot_cspace(result, index: int):
    """C-space of CC point `index`: grid states, bisected C-obstacle boundaries (CA1, CA2), and the raw, MC,
    smoothed and final postures of that point."""
    from matplotlib.figure import Figure

    cs = result.cspaces[index]
    fig = Figure(figsize=(6.4, 6.4), constrained_layout=True)
    ax = fig.add_subplot(projection="polar")
    th, ph = np.degrees(cs.thetas), cs.phis
    st = cs.states
    colours = {0: "#cccccc", 1: "#d62728", 2: "#1f77b4"}
    for state, label in ((1, "CA1 (left) grid"), (2, "CA2 (right) grid")):
        j, k = np.nonzero(st == state)
        if len(j):
            ax.scatter(ph[j], th[k], s=10, color=colours[state], alpha=0.35, label=label)
    b = cs.boundary
    for obst, label in ((1, "CA1 boundary"), (2, "CA2 boundary")):
        m = b[:, 2] == obst
        if m.any():
            ax.scatter(b[m, 1], np.degrees(b[m, 0]), s=6, color=colours[obst], label=label)
    marks = (("raw", "o", "k"), ("mc", "s", "#2ca02c"), ("smoothed", "^", "#9467bd"), ("final", "*", "#ff7f0e"))
    for name, marker, colour in marks:
        t, p = getattr(result, name).angles[index]
        ax.scatter([p], [math.degrees(t)], marker=marker, s=70, color=colour, edgecolor="k", label=name, zorder=5)
    ax.set_rmax(math.degrees(cs.options.theta_max))
    ax.set_title(f"C-space at CC point {index} (radius: tilt θ [deg], angle: rotation φ from feed)", fontsize=9)
    fig.legend(loc="outside lower center", fontsize=7, ncol=4)
    return fig


def plot_angles(result):
    """Tilt θ and rotation φ [deg] of the raw, MC and final postures along the path s [mm], and the posture
    change between neighbours [deg/mm]."""
    from matplotlib.figure import Figure

    s = np.asarray(result.s)
    fig = Figure(figsize=(7.0, 7.5), constrained_layout=True)
    axs = fig.subplots(3, 1, sharex=True)
    for name, style in (("raw", "k:"), ("mc", "C2-"), ("final", "C1-")):
        st = getattr(result, name)
        ang = np.degrees(st.angles)
        axs[0].plot(s, ang[:, 0], style, label=name)
        axs[1].plot(s, ang[:, 1], style, label=name)
        a = st.axes
        d = np.degrees(np.arctan2(np.linalg.norm(np.cross(a[:-1], a[1:]), axis=1), np.sum(a[:-1] * a[1:], axis=1)))
        axs[2].plot(0.5 * (s[1:] + s[:-1]), d / np.diff(s), style, label=name)
    hits = np.asarray(result.raw.collides)
    if hits.any():
        axs[0].plot(s[hits], np.zeros(hits.sum()), "rx", label="raw collides")
    axs[0].set_ylabel("tilt θ [deg]")
    axs[1].set_ylabel("rotation φ [deg]")
    axs[2].set_ylabel("posture change [deg/mm]")
    axs[2].set_xlabel("path length s [mm]")
    for a in axs:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7)
    return fig
