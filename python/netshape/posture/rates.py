"""Rotary-axis angular velocity and acceleration along a 5-axis program at a stated feed.

The machine moves linearly in its joints between consecutive points, so over segment k the rotary axis q
(A or B, and C) turns at the constant rate ω_k = Δq_k / Δt_k. The time of a segment is the length of the
ball-centre chord divided by the feed, Δt_k = |O_{k+1} − O_k| / F (O = tip + R·axis: the feed held at the
tool centre point, the same time base for every posture of one CC path). The acceleration at an interior
point i is the change of rate over the mean of its two segments' times,
a_i = (ω_i − ω_{i−1}) / ((Δt_{i−1} + Δt_i) / 2) — the second-order finite difference on a non-uniform grid,
exact for a quadratic q(t). Peaks are max |·|; RMS values are time-weighted (segment times for ω, the
half-sums for a). Segments of zero ball-centre length (no feed motion) are skipped.
"""

from __future__ import annotations

import math

import numpy as np

#: Keys of one axis's figures (deg/s, deg/s²).
RATE_KEYS = ("peak_velocity_deg_s", "rms_velocity_deg_s", "peak_acceleration_deg_s2", "rms_acceleration_deg_s2")


def axis_rates(angles, centres, feed_mm_per_min: float) -> dict:
    """Peak and RMS angular velocity and acceleration of one rotary axis.

    Parameters
    ----------
    angles : (n,) float64 — the axis value at each point [rad], unwrapped (no 2π jumps).
    centres : (n, 3) float64 — ball-centre positions [mm] whose chord lengths give the segment times.
    feed_mm_per_min : float — feed along the ball-centre path [mm/min], > 0.

    Returns
    -------
    dict of :data:`RATE_KEYS` [deg/s, deg/s²] (zeros when fewer than 2 or 3 timed points).
    """
    if not (isinstance(feed_mm_per_min, (int, float)) and math.isfinite(feed_mm_per_min) and feed_mm_per_min > 0):
        raise ValueError(f"feed_mm_per_min = {feed_mm_per_min!r}: must be a positive number [mm/min]")
    q = np.degrees(np.asarray(angles, float).ravel())
    c = np.asarray(centres, float).reshape(-1, 3)
    if len(q) != len(c):
        raise ValueError(f"angles ({len(q)}) and centres ({len(c)}): must have the same length")
    dt = np.linalg.norm(np.diff(c, axis=0), axis=1) / (feed_mm_per_min / 60.0)
    keep = dt > 0
    dq = np.diff(q)[keep]
    dt = dt[keep]
    out = dict.fromkeys(RATE_KEYS, 0.0)
    if len(dt) == 0:
        return out
    w = dq / dt
    out["peak_velocity_deg_s"] = float(np.abs(w).max())
    out["rms_velocity_deg_s"] = float(math.sqrt(np.sum(w * w * dt) / np.sum(dt)))
    if len(dt) >= 2:
        tau = 0.5 * (dt[:-1] + dt[1:])
        a = np.diff(w) / tau
        out["peak_acceleration_deg_s2"] = float(np.abs(a).max())
        out["rms_acceleration_deg_s2"] = float(math.sqrt(np.sum(a * a * tau) / np.sum(tau)))
    return out


def joint_rates(joints, centres, feed_mm_per_min: float, tilt_name: str = "A") -> dict:
    """:func:`axis_rates` of the tilt (joints[:, 3], named `tilt_name`) and of C (joints[:, 4]).

    joints : (n, 5) float64 — X, Y, Z [mm], tilt, C [rad] (as from ``inverse_kinematics``).
    """
    j = np.asarray(joints, float).reshape(-1, 5)
    return {tilt_name: axis_rates(j[:, 3], centres, feed_mm_per_min),
            "C": axis_rates(j[:, 4], centres, feed_mm_per_min)}


__all__ = ["RATE_KEYS", "axis_rates", "joint_rates"]
