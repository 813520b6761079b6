"""How long a program must take at least under given limits, to size the planner's work before it starts.

The planner writes one fine sample per ``ts2``, so the sample count is at least ``T / ts2`` where ``T``
is a lower bound of the cycle time:

- every block runs at most at its feed (rapids and zero feeds at the path speed limit ‖vmax‖₂), so
  ``T ≥ Σ Lᵢ / vᵢ``;
- the program starts and ends at rest with a path acceleration of at most ‖amax‖₂, so
  ``T ≥ 2 √(L / ‖amax‖)`` (bang-bang over the whole length L);
- with a jerk limit, ``T ≥ (32 L / ‖jmax‖)^(1/3)`` (bang-bang jerk, rest to rest);

G4 dwells add time but no samples (they are a gap in ``t``), so they are not counted.

The estimate is a bound from below: a refusal never turns down work that fits, and the real count can
be larger (corners slow the tool down).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass
class MotionTimeBound:
    """Lower bound of a program's cycle time [s] and which limit sets it."""

    time_s: float
    limit: str        # "feed", "vmax", "amax" or "jmax": the term that gives the bound
    block: int        # feed/vmax: the block with the longest time at its speed (−1 for the others)
    block_time_s: float
    block_mm: float   # length of that block [mm]
    path_mm: float


def min_motion_time(arrays, limits) -> MotionTimeBound:
    """The lower bound of the cycle time of block arrays (read_gcode_arrays, feeds [mm/s] already
    scaled) under AxisLimits (module docstring)."""
    from netshape.toolpath import block_lengths

    lengths = block_lengths(arrays)
    feed = np.asarray(arrays["feed"], float)
    kind = np.asarray(arrays["kind"])
    vpath = float(np.linalg.norm(np.asarray(limits.velocity, float)))
    apath = float(np.linalg.norm(np.asarray(limits.acceleration, float)))
    jerk = np.asarray(limits.jerk, float)
    jpath = float(np.linalg.norm(jerk)) if np.all(np.isfinite(jerk)) else math.inf
    speed = np.where((kind == 0) | ~(feed > 0), vpath, np.minimum(feed, vpath))
    with np.errstate(divide="ignore", invalid="ignore"):
        times = np.where(lengths > 0, lengths / speed, 0.0)
    total = float(np.sum(lengths))
    k = int(np.argmax(times)) if times.size else -1
    feed_time = float(np.sum(times))
    feed_limited = k >= 0 and feed[k] > 0 and kind[k] != 0 and feed[k] < vpath
    terms = {"feed" if feed_limited else "vmax": feed_time,
             "amax": 2.0 * math.sqrt(total / apath) if apath > 0 else math.inf,
             "jmax": (32.0 * total / jpath) ** (1.0 / 3.0) if math.isfinite(jpath) else 0.0}
    limit = max(terms, key=terms.get)
    return MotionTimeBound(time_s=terms[limit], limit=limit,
                           block=k if limit in ("feed", "vmax") else -1,
                           block_time_s=float(times[k]) if k >= 0 else 0.0,
                           block_mm=float(lengths[k]) if k >= 0 else 0.0, path_mm=total)
