"""Feed scheduling from the physics (docs/feeds.md): every feed block's feed set as large as every stated
limit allows, blocks split where the engagement changes.

The C++ core does the work per force sample (netshape::compensation::feed_samples: the engagement read
once from the Z-map, then the largest feed per limit from the force's two parts in the feed per tooth,
in closed form for flat end mills) and splits the blocks (feed_pieces). Here: the limits from a table
(:func:`feed_limits_from_dict`, the CLI and the job's ``[optimize]`` both use it), which walls remain
(the wall-error limit holds on final walls only, netshape.deflection.walls), the refusal of limits no
feed can keep, and the feed plan that caps each piece at what the machine reaches in it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._core import compensation as _c

FeedLimits = _c.FeedLimits
FeedLimit = _c.FeedLimit

#: Keys of a limits table, their FeedLimits field and unit. Feeds are mm/min here, mm/s in FeedLimits.
LIMIT_KEYS = {
    "max_force_N": ("max_force", "N"),
    "max_chip_mm": ("max_chip", "mm"),
    "min_chip_mm": ("min_chip", "mm"),
    "max_deflection_mm": ("max_deflection", "mm"),
    "max_wall_error_mm": ("max_wall_error", "mm"),
    "max_power_W": ("max_power", "W"),
    "max_torque_Nm": ("max_torque", "N·m"),
    "min_feed_mm_min": ("min_feed", "mm/min"),
    "max_feed_mm_min": ("max_feed", "mm/min"),
    "air_feed_mm_min": ("air_feed", "mm/min"),
}
#: Keys of the splitting rule.
SPLIT_KEYS = {"split_tolerance": 0.1, "min_piece_mm": 1.0}
#: The physical limits: FeedLimit codes 0..5 in order.
PHYSICAL = ("max_force_N", "max_chip_mm", "max_deflection_mm", "max_wall_error_mm", "max_power_W",
            "max_torque_Nm")


def limit_name(code: int) -> str:
    """The key of a FeedLimit code (max_force_N, …, air_feed_mm_min, programmed)."""
    return _c.feed_limit_name(int(code))


def feed_limits_from_dict(d: dict, *, source: str = "optimize") -> tuple[FeedLimits, dict]:
    """(FeedLimits, splitting rule {split_tolerance, min_piece_mm}) from a table of LIMIT_KEYS and
    SPLIT_KEYS. ``max_feed_mm_min`` is required; every other limit is optional. A bad key or value
    raises ValueError ``{source}.{key} = value: rule [unit]``."""
    if not isinstance(d, dict):
        raise ValueError(f"{source} = {d!r}: must be a table")
    for k in d:
        if k not in LIMIT_KEYS and k not in SPLIT_KEYS:
            known = ", ".join([*LIMIT_KEYS, *SPLIT_KEYS])
            raise ValueError(f"{source}.{k} = {d[k]!r}: unknown key (known: {known})")
    if "max_feed_mm_min" not in d:
        raise ValueError(f"{source}.max_feed_mm_min: missing (the largest feed a block may get [mm/min])")
    lim = FeedLimits()
    for key, (name, unit) in LIMIT_KEYS.items():
        if key not in d:
            continue
        v = d[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ValueError(f"{source}.{key} = {v!r}: must be a finite number [{unit}]")
        floor_ok = v >= 0 if key.startswith(("min_", "air_")) else v > 0
        if not floor_ok:
            rule = "must be ≥ 0" if key.startswith(("min_", "air_")) else "must be positive"
            raise ValueError(f"{source}.{key} = {v!r}: {rule} [{unit}]")
        setattr(lim, name, float(v) / 60.0 if unit == "mm/min" else float(v))
    if lim.min_feed >= lim.max_feed:
        raise ValueError(f"{source}.min_feed_mm_min = {d.get('min_feed_mm_min')!r}: must be below "
                         f"max_feed_mm_min = {d['max_feed_mm_min']!r} [mm/min]")
    if lim.min_chip >= lim.max_chip:
        raise ValueError(f"{source}.min_chip_mm = {d.get('min_chip_mm')!r}: must be below max_chip_mm = "
                         f"{d.get('max_chip_mm')!r} [mm]")
    split = dict(SPLIT_KEYS)
    for key in SPLIT_KEYS:
        if key in d:
            v = d[key]
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
                raise ValueError(f"{source}.{key} = {v!r}: must be a number ≥ 0")
            split[key] = float(v)
    lim.validate()
    return lim, split


def stated(limits: FeedLimits) -> dict:
    """The limits stated, as table keys and values (feeds in mm/min)."""
    out = {}
    for key, (name, unit) in LIMIT_KEYS.items():
        v = getattr(limits, name)
        if key in ("min_chip_mm", "min_feed_mm_min", "air_feed_mm_min") and v == 0:
            continue
        if math.isinf(v):
            continue
        out[key] = v * 60.0 if unit == "mm/min" else v
    return out


@dataclass
class FeedSchedule:
    """The schedule of a program: per force sample what each limit allows (``samples``, arrays of
    netshape::compensation::FeedSamples, ``final_wall`` where the wall remains) and the pieces
    (``pieces``: block, start, end [-], feed [mm/s], binding code, sample)."""

    samples: dict
    pieces: dict
    limits: FeedLimits
    final_wall: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=bool))


def _final_walls(program, samples: dict, radius: float) -> np.ndarray:
    """(m) bool: the sample generates a wall that remains at the end of the program."""
    from netshape.deflection import walls

    walls_bits = np.asarray(samples["walls"])
    final = np.zeros(len(walls_bits), dtype=bool)
    d = np.asarray(samples["feed_direction"], dtype=float)
    left = np.column_stack([-d[:, 1], d[:, 0]])  # +Y_c = Z × X_c
    owner = np.asarray(samples["block"])
    for bit, normal in ((1, left), (2, -left)):
        on = (walls_bits & bit) > 0
        if not on.any():
            continue
        keep = walls.wall_remains_points(program, owner[on], np.asarray(samples["positions"])[on], normal[on],
                                         np.asarray(samples["depth"])[on], radius)
        idx = np.flatnonzero(on)
        final[idx[keep]] = True
    return final


#: The smallest feed an F word is written with [mm/s] (0.1 mm/min).
MIN_WRITTEN_FEED = 0.1 / 60.0


def _refuse_infeasible(program, samples: dict, allowed: np.ndarray, limits: FeedLimits) -> None:
    """A limit no feed at or above min_feed (and the feed min_chip asks for, and the smallest written
    feed) keeps, named with its block's line."""
    engaged = np.asarray(samples["engaged"]) > 0
    if not engaged.any():
        return
    best = np.minimum(allowed.min(axis=1), limits.max_feed)
    lowest = np.asarray(samples["lowest"])
    low = np.maximum(np.maximum(lowest, limits.min_feed), MIN_WRITTEN_FEED)
    bad = engaged & (best < low * (1 - 1e-9))
    if not bad.any():
        return
    i = int(np.flatnonzero(bad)[0])
    line = int(program.blocks[int(samples["block"][i])].line)
    j = int(np.argmin(allowed[i]))
    key = PHYSICAL[j] if allowed[i, j] <= limits.max_feed else "max_feed_mm_min"
    value = stated(limits).get(key)
    if lowest[i] >= max(limits.min_feed, MIN_WRITTEN_FEED):
        need = "min_chip_mm asks for"
    elif limits.min_feed >= MIN_WRITTEN_FEED:
        need = "min_feed_mm_min asks for"
    else:
        need = "is the smallest feed written"
    raise ValueError(f"{key} = {value:g}: the block on line {line} keeps it only below "
                     f"{best[i] * 60:.4g} mm/min, under the {low[i] * 60:.4g} mm/min that {need}")


def _sampling_options(step, samples_per_revolution, bins, disk_height, element_angle_deg, spindle_rpm):
    from netshape._core import force as _f

    return _f.ProgramForceOptions(step=step, samples_per_revolution=samples_per_revolution, bins=bins,
                                  disk_height=disk_height, element_angle=math.radians(element_angle_deg),
                                  feed_per_tooth=0.0, spindle_rpm=spindle_rpm)


def sample_limits(stock, cutter, program, coefficients, limits: FeedLimits, *, step: float = 0.5,
                  samples_per_revolution: int = 72, bins: int = 360, disk_height: float = 0.1,
                  element_angle_deg: float = 2.0, spindle_rpm: float = 0.0,
                  copy_stock: bool = True) -> tuple[dict, np.ndarray]:
    """(samples, final_wall): the C++ sample pass (netshape::compensation::FeedSamples as a dict of
    arrays, ``allowed`` with the wall-error column lifted where the wall does not remain) and (m) bool
    where a sample generates a wall that remains at the end of the program. Also the re-simulation of
    a written program: ``deflection`` and ``wall_error`` are then the values at its own feeds."""
    from netshape._core import force as _f
    from netshape.deflection.chip import SizeEffectCoefficients

    if isinstance(coefficients, SizeEffectCoefficients):
        coefficients = coefficients.coefficients  # the schedule is the linear chip's (docs/feeds.md)
    z = stock.copy() if copy_stock else stock
    opts = _sampling_options(step, samples_per_revolution, bins, disk_height, element_angle_deg, spindle_rpm)
    key = "linear_edge" if isinstance(coefficients, _f.LinearEdgeCoefficients) else "ball_end"
    if key == "ball_end" and not isinstance(coefficients, _f.BallEndCoefficients):
        raise ValueError(f"coefficients = {coefficients!r}: must be LinearEdgeCoefficients or "
                         "BallEndCoefficients")
    s = _c.feed_samples_core(z, cutter, program, limits=limits, sampling=opts, **{key: coefficients})
    s = {k: (np.asarray(v) if not isinstance(v, float) else v) for k, v in s.items()}
    allowed = np.array(s["allowed"], dtype=float)
    final = np.zeros(len(allowed), dtype=bool)
    if math.isfinite(limits.max_wall_error) and len(allowed):
        final = _final_walls(program, s, cutter.radius)
        allowed[~final, 3] = np.inf
    s["allowed"] = allowed
    return s, final


def schedule_feeds(stock, cutter, program, coefficients, limits: FeedLimits, *, split_tolerance: float = 0.1,
                   min_piece_mm: float = 1.0, step: float = 0.5, samples_per_revolution: int = 72,
                   bins: int = 360, disk_height: float = 0.1, element_angle_deg: float = 2.0,
                   spindle_rpm: float = 0.0, copy_stock: bool = True) -> FeedSchedule:
    """Schedule the feeds of ``program`` (a Toolpath, program coordinates = the stock's) cut through
    ``stock`` (ZMap, copied unless ``copy_stock`` is False) by ``cutter`` with ``coefficients``
    (LinearEdgeCoefficients or BallEndCoefficients) under ``limits``. Sampling as
    netshape.force.simulate_program. Raises ValueError naming the limit and the block's line when a
    limit cannot be kept at any feed the limits allow."""
    s, final = sample_limits(stock, cutter, program, coefficients, limits, step=step,
                             samples_per_revolution=samples_per_revolution, bins=bins,
                             disk_height=disk_height, element_angle_deg=element_angle_deg,
                             spindle_rpm=spindle_rpm, copy_stock=copy_stock)
    allowed = s["allowed"]
    _refuse_infeasible(program, s, allowed, limits)
    p = _c.feed_pieces_core(program, s["block"], s["fraction"], s["engaged"], s["walls"], s["depth"],
                            s["chip_factor"], s["engaged_share"], allowed, limits, split_tolerance,
                            min_piece_mm)
    p = {k: np.asarray(v) for k, v in p.items()}
    floor = np.where(p["binding"] == int(FeedLimit.programmed), 0.0, limits.min_feed)
    p["feed"] = np.maximum(p["feed"], floor)
    return FeedSchedule(samples=s, pieces=p, limits=limits, final_wall=final)
