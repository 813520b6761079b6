"""Axis limits from a TOML file (`netshape plan --limits MACHINE.toml`).

Two layouts are read; the machine TOML of `netshape.machine` may carry either, its other keys are
ignored:

    [axes.x]                 # one table per axis, x/y/z or X/Y/Z
    vmax_mm_s = 250.0
    amax_mm_s2 = 3000.0
    jmax_mm_s3 = 1.0e6       # optional: jerk-limited (S-curve) profiles

    [limits]                 # or all axes at once: a number, or [x, y, z]
    vmax_mm_s = 250.0
    amax_mm_s2 = [3000.0, 3000.0, 2000.0]
    jmax_mm_s3 = 1.0e6       # optional

Per-axis tables override `[limits]`. Every axis needs a velocity and an acceleration.
"""

from __future__ import annotations

import math
import os

from .._config import load_toml, number
from .._core import motion as _m

_KEYS = (("vmax_mm_s", "velocity"), ("amax_mm_s2", "acceleration"), ("jmax_mm_s3", "jerk"))


def limits_from_dict(doc: dict, path: str = "<limits>") -> _m.AxisLimits:
    """AxisLimits from a parsed TOML document (see the module docstring)."""
    vals: dict[str, list[float | None]] = {name: [None, None, None] for _, name in _KEYS}
    common = doc.get("limits", {})
    if not isinstance(common, dict):
        raise ValueError(f"{path}: limits must be a table")
    for key, name in _KEYS:
        if key in common:
            v = common[key]
            if isinstance(v, list):
                if len(v) != 3:
                    raise ValueError(f"{path}: limits.{key} = {v!r}: must be a number or a list of 3 numbers")
                vals[name] = [number(path, f"limits.{key}[{i}]", x, positive=True) for i, x in enumerate(v)]
            else:
                vals[name] = [number(path, f"limits.{key}", v, positive=True)] * 3
    axes = doc.get("axes", {})
    if not isinstance(axes, dict):
        raise ValueError(f"{path}: axes must be a table")
    for i, ax in enumerate("xyz"):
        tab = axes.get(ax, axes.get(ax.upper()))
        if tab is None:
            continue
        for key, name in _KEYS:
            if key in tab:
                vals[name][i] = number(path, f"axes.{ax}.{key}", tab[key], positive=True)
    for key, name in _KEYS[:2]:
        for i, ax in enumerate("xyz"):
            if vals[name][i] is None:
                raise ValueError(f"{path}: axes.{ax}.{key} is missing (or give limits.{key})")
    jerk = [math.inf if j is None else j for j in vals["jerk"]]
    return _m.AxisLimits(vals["velocity"], vals["acceleration"], jerk)


def read_limits(path: str | os.PathLike) -> _m.AxisLimits:
    """Read AxisLimits from a TOML file; ValueError naming the file and key on bad content."""
    p = os.fspath(path)
    doc = load_toml(p)
    return limits_from_dict(doc, p)
