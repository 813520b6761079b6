"""Plots of netshape.deflection results (matplotlib, Agg): paths, wall error, width, forces."""

from __future__ import annotations

import os

import numpy as np


def _fig(rows: int = 2, cols: int = 2, size=(11, 7.5)):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(rows, cols, figsize=size, squeeze=False)


def _s(nominal: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(nominal[:, 0]), np.diff(nominal[:, 1])))])


def plot_case(nominal, before, after=None, *, positions=None, normals=None, title: str = "", level: int = 1,
              exaggerate: float = 100.0):
    """Four panels: nominal / deflected / compensated paths (normal offsets × `exaggerate`), wall error
    at bottom/middle/top before and after [µm], cutting width [mm], forces [N], against path length."""
    fig, ax = _fig()
    s = _s(nominal)
    a = ax[0][0]
    a.plot(nominal[:, 0], nominal[:, 1], "k-", lw=1, label="nominal")
    if normals is not None:
        nd = np.asarray(before.normal_deflection)
        d = nominal[:, :2] + exaggerate * nd[:, None] * normals
        a.plot(d[:, 0], d[:, 1], "r--", lw=1, label=f"deflected (×{exaggerate:g})")
        if positions is not None:
            off = np.sum((np.asarray(positions)[:, :2] - nominal[:, :2]) * normals, axis=1)
            c = nominal[:, :2] + exaggerate * off[:, None] * normals
            a.plot(c[:, 0], c[:, 1], "b-.", lw=1, label=f"compensated (×{exaggerate:g})")
    a.set_aspect("equal", adjustable="datalim")
    a.set_xlabel("x [mm]")
    a.set_ylabel("y [mm]")
    a.legend(fontsize=7)
    a.set_title("paths")
    b = ax[0][1]
    e = np.asarray(before.error) * 1e3
    for k, (name, st) in enumerate(zip(("bottom", "middle", "top"), (":", "-", "--"))):
        b.plot(s, e[:, k], "r" + st, lw=1, label=f"before, {name}")
    if after is not None:
        ea = np.asarray(after.error) * 1e3
        b.plot(s, ea[:, level], "b-", lw=1.2, label="after, reference level")
    b.axhline(0, color="k", lw=0.5)
    b.set_xlabel("path length [mm]")
    b.set_ylabel("wall error [µm] (+ material left)")
    b.legend(fontsize=7)
    b.set_title("wall error")
    c = ax[1][0]
    c.plot(s, before.width, "r-", lw=1, label="before")
    if after is not None:
        c.plot(s, after.width, "b--", lw=1, label="after")
    c.set_xlabel("path length [mm]")
    c.set_ylabel("cutting width [mm]")
    c.legend(fontsize=7)
    c.set_title("radial depth of cut")
    d = ax[1][1]
    f = np.asarray(before.force)
    d.plot(s, f[:, 0], "r-", lw=1, label="Fx before")
    d.plot(s, f[:, 1], "m-", lw=1, label="Fy before")
    if after is not None:
        fa = np.asarray(after.force)
        d.plot(s, fa[:, 0], "b--", lw=1, label="Fx after")
        d.plot(s, fa[:, 1], "c--", lw=1, label="Fy after")
    d.set_xlabel("path length [mm]")
    d.set_ylabel("force on the cutter [N] (mid-depth instant)")
    d.legend(fontsize=7)
    d.set_title("forces")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def plot_prediction(setup, r, directory) -> None:
    """Write wall_error.png (paths, error, width, forces) and profile.png (error over z) into directory."""
    from netshape._atomic import atomic_save_figure

    os.makedirs(directory, exist_ok=True)
    from netshape.deflection import wall_normals

    normals = np.asarray(wall_normals(setup.nominal, setup.side))
    fig = plot_case(setup.nominal, r, normals=normals, title="netshape deflection predict")
    atomic_save_figure(fig, os.path.join(directory, "wall_error.png"), dpi=100)
    prof = np.asarray(r.profile)
    if prof.shape[1] > 1:
        fig2, ax = _fig(1, 1, (6, 4))
        a = ax[0][0]
        worst = int(np.argmax(np.max(np.abs(prof), axis=1)))
        z = np.linspace(0, r.depth[worst], prof.shape[1])
        a.plot(prof[worst] * 1e3, z, "r-")
        a.set_xlabel("wall error [µm]")
        a.set_ylabel("height above the tip [mm]")
        a.set_title(f"profile at the worst point ({worst})")
        fig2.tight_layout()
        atomic_save_figure(fig2, os.path.join(directory, "profile.png"), dpi=100)
