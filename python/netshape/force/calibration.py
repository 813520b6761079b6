"""Calibration workflows on measured forces (the C++ least squares do the fitting).

- :func:`recording_mean_force`: mean force over whole revolutions of a recording.
- :func:`calibrate_mean_forces`: Altintas mean-force regression over recordings at several feeds.
- :func:`fit_recording`: fit the linear edge coefficients, the angle offset and (optionally) the
  helix lag to one force time series, and return the simulated series for comparison.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from netshape._core import force as _f


def recording_mean_force(times: np.ndarray, forces: np.ndarray, rpm: float) -> np.ndarray:
    """Mean (3,) [N] over the largest whole number of spindle revolutions in the record."""
    times = np.asarray(times, float)
    forces = np.asarray(forces, float)
    if not (math.isfinite(rpm) and rpm > 0):
        raise ValueError(f"rpm = {rpm}: must be positive")
    if times.ndim != 1 or forces.shape != (times.size, 3):
        raise ValueError(f"forces shape = {forces.shape}: must be (len(times), 3)")
    dt = float(np.median(np.diff(times)))
    per_rev = 60.0 / rpm / dt
    whole = int(math.floor(times.size / per_rev))
    if whole < 1:
        raise ValueError(f"record length = {times.size} samples: shorter than one revolution ({per_rev:.1f})")
    n = int(round(whole * per_rev))
    return forces[: min(n, times.size)].mean(axis=0)


def calibrate_mean_forces(feeds, mean_forces, *, flutes: int, axial_depth: float,
                          engagement: "_f.AngularEngagement | None" = None) -> "_f.LinearEdgeFit":
    """Mean-force regression (Altintas): feeds (n,) [mm/tooth], mean forces on the cutter (n, 3) [N]
    in the cutting frame (docs/conventions.md §2) → LinearEdgeFit (coefficients, r2 per axis, residuals)."""
    e = engagement if engagement is not None else _f.AngularEngagement(0.0, math.pi)
    return _f.fit_linear_edge_mean_forces(e, int(flutes), float(axial_depth), np.asarray(feeds, float),
                                          np.ascontiguousarray(mean_forces, dtype=float))


@dataclass
class RecordingFit:
    """Result of :func:`fit_recording`: fitted coefficients, phase [rad], helix [rad], angles (n,)
    [rad] used, simulated forces (n, 3) [N], rms residual per axis (3,) [N] and overall [N]."""

    coefficients: "_f.LinearEdgeCoefficients"
    phase: float
    helix: float
    angles: np.ndarray
    simulated: np.ndarray
    rms: np.ndarray
    rms_total: float

    def to_dict(self) -> dict:
        return {"coefficients": self.coefficients.to_dict(), "phase": self.phase, "helix": self.helix,
                "rms": self.rms.tolist(), "rms_total": self.rms_total}


def fit_recording(times, forces, *, rpm: float, feed_per_tooth: float, flutes: int, axial_depth: float,
                  radius: float, helix: float | None = None, helix_grid=None,
                  engagement: "_f.AngularEngagement | None" = None, disk_height: float = 0.05,
                  fixed: "_f.LinearEdgeCoefficients | None" = None, phase_steps: int = 60) -> RecordingFit:
    """Fit one time series: angle θ(t) = 2π·rpm/60·(t − t0) + phase.

    With ``fixed`` coefficients only the phase (and helix) are fitted (the coefficients stay, the
    simulated series is the fixed model's); otherwise the six coefficients are fitted too.
    ``helix`` [rad] fixed, or ``helix_grid`` (iterable of [rad]) scanned for the smallest rms.
    """
    times = np.asarray(times, float)
    forces = np.ascontiguousarray(forces, dtype=float)
    if forces.shape != (times.size, 3):
        raise ValueError(f"forces shape = {forces.shape}: must be (len(times), 3)")
    e = engagement if engagement is not None else _f.AngularEngagement(0.0, math.pi)
    omega = 2.0 * math.pi * rpm / 60.0
    angles = omega * (times - times[0])
    helices = [helix] if helix is not None else list(helix_grid if helix_grid is not None else [math.radians(30)])
    best = None
    for h in helices:
        model = _f.FlatEndModel(radius=radius, flutes=flutes, helix=h, axial_depth=axial_depth,
                                feed_per_tooth=feed_per_tooth, engagement=e, disk_height=disk_height,
                                linear_edge=fixed if fixed is not None else _f.LinearEdgeCoefficients())
        if fixed is None:
            fit = _f.fit_linear_edge_time_series(model, angles, forces, phase_steps)
            k, phase = fit.coefficients, fit.phase
        else:
            k, phase = fixed, _phase_only(model, angles, forces, phase_steps)
        model.linear_edge = k
        sim = _f.flat_end_forces(model, angles + phase)
        rms = np.sqrt(np.mean((forces - sim) ** 2, axis=0))
        total = float(np.sqrt(np.mean((forces - sim) ** 2)))
        if best is None or total < best.rms_total:
            best = RecordingFit(k, float(phase), float(h), angles, sim, rms, total)
    return best


def _phase_only(model, angles, forces, steps):
    ws = _f.FlatEndWorkspace(model)
    period = 2 * math.pi / model.flutes

    def cost(p):
        sim = _f.flat_end_forces(model, angles + p, ws)
        return float(np.sum((forces - sim) ** 2))

    grid = [period * s / steps for s in range(steps)]
    costs = [cost(p) for p in grid]
    p0 = grid[int(np.argmin(costs))]
    lo, hi = p0 - period / steps, p0 + period / steps
    g = (math.sqrt(5) - 1) / 2
    for _ in range(30):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if cost(a) <= cost(b):
            hi = b
        else:
            lo = a
    return 0.5 * (lo + hi) % (2 * math.pi)
