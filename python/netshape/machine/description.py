"""Machine description files (TOML) and controller error tables (CSV) → :class:`Machine`.

Format (docs/machine.md has a full example)::

    name = "VMC"
    tool_chain = ["Z"]              # axes from the bed outward to the spindle
    workpiece_chain = ["Y", "X"]    # axes from the bed outward to the workpiece

    [tool]
    length_mm = 120.0               # L, gauge point → tip
    nose_mm = [0.0, 0.0, 0.0]       # gauge point in the last tool-side frame (T)
    direction = [0.0, 0.0, -1.0]    # unit vector gauge point → tip

    [spindle]
    tilt_a_rad = 0.0                # about X (Yang & Kweon ε_xs)
    tilt_b_rad = 0.0                # about Y (Yang & Kweon ε_ys)

    [squareness]                    # ISO 230-1; reference axes: EC0Y → X, EB0Z → X, EA0Z → Y
    EC0Y_rad = 0.0
    EB0Z_rad = 0.0
    EA0Z_rad = 0.0

    [axes.X]
    travel_mm = [-400.0, 400.0]
    origin_mm = [0.0, 0.0, 0.0]     # this carriage's frame relative to the frame below it
    table = "x_errors.csv"          # controller table: X_mm,EXX_mm,EYX_mm,...,ECX_rad
    out_of_range = "error"          # table outside its positions: error | clamp | extrapolate
    backlash_um = 0.0               # reversal value: the tip lands backlash/2 along the last direction
    [axes.X.polynomials]            # ascending powers of the axis position q [mm]
    EAX_rad = [0.0, 1.0e-8]
    [[axes.X.cyclic]]               # periodic positioning error: amplitude·sin(2π·q/period + phase)
    period_mm = 10.0
    amplitude_mm = 0.002            # or amplitude_um
    phase_deg = 0.0

    [[thermal]]                     # tip drift with program time t: amplitude·(1 − exp(−t/τ))
    axis = "Z"
    amplitude_mm = 0.01             # or amplitude_um
    time_constant_s = 1800.0

Table columns: the axis position first (``X_mm``), then ISO 230-1 component names of that axis with
a unit suffix: ``_mm`` or ``_um`` for EXX EYX EZX, ``_rad``, ``_urad`` or ``_arcsec`` for EAX EBX ECX.
Components not given are zero.
"""

from __future__ import annotations

import csv
import math
import os
from pathlib import Path
from typing import Any, Mapping

from .._core import machine as _m


AXES = ("X", "Y", "Z")
_COMPONENT_LETTERS = "XYZABC"
_LENGTH_UNITS = {"mm": 1.0, "um": 1e-3}
_ANGLE_UNITS = {"rad": 1.0, "urad": 1e-6, "arcsec": math.pi / 648000.0}
_OUT_OF_RANGE = {"error": _m.OutOfRange.error, "clamp": _m.OutOfRange.clamp,
                 "extrapolate": _m.OutOfRange.extrapolate}
_TOP_KEYS = {"name", "tool_chain", "workpiece_chain", "tool", "spindle", "squareness", "axes", "thermal"}
_AXIS_KEYS = {"travel_mm", "origin_mm", "table", "out_of_range", "polynomials", "backlash_mm", "backlash_um",
              "cyclic"}


def iso_names(axis: str) -> list[str]:
    """The six ISO 230-1 component names of ``axis`` ("X" → EXX, EYX, EZX, EAX, EBX, ECX)."""
    return [f"E{c}{axis}" for c in _COMPONENT_LETTERS]


def _split_unit(key: str, axis: str, where: str) -> tuple[int, float]:
    """'EXX_mm' → (component index, factor to mm or rad); raises ValueError naming the key."""
    name, _, unit = key.partition("_")
    names = iso_names(axis)
    if name.upper() not in names:
        raise ValueError(
            f"{where}: {key!r} is not an error component of axis {axis} (expected one of "
            f"{', '.join(n + '_mm' for n in names[:3])}, {', '.join(n + '_rad' for n in names[3:])})")
    c = names.index(name.upper())
    units = _LENGTH_UNITS if c < 3 else _ANGLE_UNITS
    if unit not in units:
        raise ValueError(f"{where}: {key!r} needs a unit suffix, one of "
                         f"{', '.join('_' + u for u in units)}")
    return c, units[unit]


def _finite(value: Any, where: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{where} = {value!r}: must be a number") from None
    if isinstance(value, bool) or not math.isfinite(v):
        raise ValueError(f"{where} = {value!r}: must be a finite number")
    return v


def _vec3(value: Any, where: str) -> list[float]:
    if not isinstance(value, (list, tuple)) or len(value) != 3:
        raise ValueError(f"{where} = {value!r}: must be a list of 3 numbers")
    return [_finite(v, f"{where}[{i}]") for i, v in enumerate(value)]


def read_error_table(path: str | os.PathLike, axis: str | None = None) -> dict[str, Any]:
    """Read a controller volumetric-compensation table (CSV) as it is.

    Returns ``{"axis": "X", "positions": [...] mm, "components": {"EXX": [...] mm, ..., "EAX": [...] rad}}``.
    Lines starting with ``#`` are comments. Raises ValueError naming the file, row and column on an
    unknown column, a missing or non-finite value, or positions that do not strictly increase.
    """
    p = Path(path)
    from .._text import read_text

    lines = read_text(p).splitlines(keepends=True)
    rows = [r for r in csv.reader(line for line in lines if line.strip() and not line.lstrip().startswith("#"))]
    if not rows:
        raise ValueError(f"{p}: empty error table")
    header = [h.strip() for h in rows[0]]
    pos_name, _, pos_unit = header[0].partition("_")
    if pos_name.upper() not in AXES or pos_unit != "mm":
        raise ValueError(f"{p}: first column {header[0]!r} must be the axis position, e.g. 'X_mm'")
    ax = pos_name.upper()
    if axis is not None and ax != axis.upper():
        raise ValueError(f"{p}: table is for axis {ax}, expected axis {axis.upper()}")
    cols = [_split_unit(h, ax, f"{p}: column") for h in header[1:]]
    seen = [c for c, _ in cols]
    if len(set(seen)) != len(seen):
        raise ValueError(f"{p}: a component appears twice in the header {header}")
    positions: list[float] = []
    values: list[list[float]] = [[] for _ in cols]
    for i, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise ValueError(f"{p}: row {i} has {len(row)} values, the header has {len(header)}")
        q = _finite(row[0].strip(), f"{p}: row {i} {header[0]}")
        if positions and not q > positions[-1]:
            raise ValueError(f"{p}: row {i} {header[0]} = {q}: positions must be strictly increasing")
        positions.append(q)
        for j, (c, f) in enumerate(cols):
            values[j].append(_finite(row[j + 1].strip(), f"{p}: row {i} {header[j + 1]}") * f)
    if len(positions) < 2:
        raise ValueError(f"{p}: an error table needs at least 2 rows of positions")
    names = iso_names(ax)
    return {"axis": ax, "positions": positions,
            "components": {names[c]: values[j] for j, (c, _) in enumerate(cols)}}


def _inline_table(tab: Mapping[str, Any], axis: str, where: str) -> dict[str, Any]:
    key = f"{axis}_mm"
    if key not in tab:
        raise ValueError(f"{where}: an inline table needs the positions {key!r}")
    positions = [_finite(v, f"{where}.{key}[{i}]") for i, v in enumerate(tab[key])]
    comps = {}
    for k, vals in tab.items():
        if k == key:
            continue
        c, f = _split_unit(k, axis, where)
        if not isinstance(vals, list) or len(vals) != len(positions):
            raise ValueError(f"{where}.{k}: must be a list of {len(positions)} numbers (one per position)")
        comps[iso_names(axis)[c]] = [_finite(v, f"{where}.{k}[{i}]") * f for i, v in enumerate(vals)]
    for i in range(1, len(positions)):
        if not positions[i] > positions[i - 1]:
            raise ValueError(f"{where}.{key}[{i}] = {positions[i]}: positions must be strictly increasing")
    return {"axis": axis, "positions": positions, "components": comps}


def _length(d: Mapping[str, Any], stem: str, where: str, default: float | None = 0.0) -> float:
    """``stem_mm`` or ``stem_um`` of ``d`` in mm (not both; ``default`` when neither, None: required)."""
    keys = [k for k in (f"{stem}_mm", f"{stem}_um") if k in d]
    if len(keys) > 1:
        raise ValueError(f"{where}: give {stem}_mm or {stem}_um, not both")
    if not keys:
        if default is None:
            raise ValueError(f"{where}: missing {stem}_mm (or {stem}_um)")
        return default
    return _finite(d[keys[0]], f"{where}.{keys[0]}") * _LENGTH_UNITS[keys[0].rsplit("_", 1)[1]]


def _tables(value: Any, where: str) -> list:
    if not isinstance(value, list) or not all(isinstance(t, dict) for t in value):
        raise ValueError(f"{where}: must be an array of tables ([[{where.split('[')[-1].strip(']')}]])")
    return value


def _cyclic(value: Any, where: str) -> list:
    out = []
    for i, t in enumerate(_tables(value, where)):
        w = f"{where}[{i}]"
        _check_keys(t, {"period_mm", "amplitude_mm", "amplitude_um", "phase_deg"}, w)
        if "period_mm" not in t:
            raise ValueError(f"{w}: missing period_mm")
        period = _finite(t["period_mm"], f"{w}.period_mm")
        if not period > 0:
            raise ValueError(f"{w}.period_mm = {period}: must be > 0")
        amp = _length(t, "amplitude", w, None)
        if amp < 0:
            raise ValueError(f"{w}: amplitude = {amp} mm: must be ≥ 0 (a sign is a phase of 180°)")
        phase = math.radians(_finite(t.get("phase_deg", 0.0), f"{w}.phase_deg"))
        out.append(_m.CyclicTerm(amplitude=amp, period=period, phase=phase))
    return out


def _thermal(value: Any, where: str) -> list:
    out = []
    for i, t in enumerate(_tables(value, where)):
        w = f"{where}[{i}]"
        _check_keys(t, {"axis", "amplitude_mm", "amplitude_um", "time_constant_s"}, w)
        axis = t.get("axis")
        if not isinstance(axis, str) or axis.upper() not in AXES:
            raise ValueError(f"{w}.axis = {axis!r}: must be \"X\", \"Y\" or \"Z\"")
        if "time_constant_s" not in t:
            raise ValueError(f"{w}: missing time_constant_s")
        tau = _finite(t["time_constant_s"], f"{w}.time_constant_s")
        if not tau > 0:
            raise ValueError(f"{w}.time_constant_s = {tau}: must be > 0")
        out.append(_m.ThermalDrift(axis=AXES.index(axis.upper()), amplitude=_length(t, "amplitude", w, None),
                                   time_constant=tau))
    return out


def _chain(value: Any, where: str) -> list[int]:
    if not isinstance(value, list) or not all(isinstance(a, str) for a in value):
        raise ValueError(f"{where} = {value!r}: must be a list of axis names, e.g. [\"X\", \"Y\"]")
    out = []
    for a in value:
        if a.upper() not in AXES:
            raise ValueError(f"{where}: axis {a!r} is not X, Y or Z")
        out.append(AXES.index(a.upper()))
    return out


def _check_keys(d: Mapping[str, Any], allowed: set[str], where: str) -> None:
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r} (allowed: {', '.join(sorted(allowed))})")


def machine_from_dict(doc: Mapping[str, Any], base_dir: str | os.PathLike = ".",
                      source: str = "<machine>") -> _m.Machine:
    """Build a :class:`Machine` from a parsed TOML document; relative table paths are resolved
    against ``base_dir``. Raises ValueError naming ``source`` and the key on any bad input."""
    _check_keys(doc, _TOP_KEYS, source)
    m = _m.Machine()
    m.name = str(doc.get("name", Path(source).stem))
    for key in ("tool_chain", "workpiece_chain"):
        if key not in doc:
            raise ValueError(f"{source}: missing {key!r} (axes from the bed outward, e.g. [\"X\", \"Y\"])")
    m.tool_chain = _chain(doc["tool_chain"], f"{source}: tool_chain")
    m.workpiece_chain = _chain(doc["workpiece_chain"], f"{source}: workpiece_chain")

    tool = doc.get("tool", {})
    _check_keys(tool, {"length_mm", "nose_mm", "direction"}, f"{source}: [tool]")
    m.tool_length = _finite(tool.get("length_mm", 0.0), f"{source}: tool.length_mm")
    if m.tool_length < 0:
        raise ValueError(f"{source}: tool.length_mm = {m.tool_length}: must be ≥ 0")
    m.spindle_nose = _vec3(tool.get("nose_mm", [0.0, 0.0, 0.0]), f"{source}: tool.nose_mm")
    d = _vec3(tool.get("direction", [0.0, 0.0, -1.0]), f"{source}: tool.direction")
    n = math.sqrt(sum(v * v for v in d))
    if abs(n - 1.0) > 1e-9:
        raise ValueError(f"{source}: tool.direction = {d}: must be a unit vector (norm {n:.6g})")
    m.tool_direction = d

    sp = doc.get("spindle", {})
    _check_keys(sp, {"tilt_a_rad", "tilt_b_rad"}, f"{source}: [spindle]")
    m.spindle_tilt_a = _finite(sp.get("tilt_a_rad", 0.0), f"{source}: spindle.tilt_a_rad")
    m.spindle_tilt_b = _finite(sp.get("tilt_b_rad", 0.0), f"{source}: spindle.tilt_b_rad")

    sq = doc.get("squareness", {})
    _check_keys(sq, {"EC0Y_rad", "EB0Z_rad", "EA0Z_rad"}, f"{source}: [squareness]")
    m.ec0y = _finite(sq.get("EC0Y_rad", 0.0), f"{source}: squareness.EC0Y_rad")
    m.eb0z = _finite(sq.get("EB0Z_rad", 0.0), f"{source}: squareness.EB0Z_rad")
    m.ea0z = _finite(sq.get("EA0Z_rad", 0.0), f"{source}: squareness.EA0Z_rad")

    axes_doc = doc.get("axes", {})
    bad = [k for k in axes_doc if k.upper() not in AXES]
    if bad:
        raise ValueError(f"{source}: [axes.{bad[0]}]: unknown axis (X, Y or Z)")
    axes = m.axes
    for k, name in enumerate(AXES):
        ad = next((v for key, v in axes_doc.items() if key.upper() == name), {})
        where = f"{source}: [axes.{name}]"
        _check_keys(ad, _AXIS_KEYS, where)
        a = axes[k]
        lo, hi = -1e9, 1e9
        if "travel_mm" in ad:
            t = ad["travel_mm"]
            if not isinstance(t, list) or len(t) != 2:
                raise ValueError(f"{where}.travel_mm = {t!r}: must be [min, max]")
            lo, hi = (_finite(v, f"{where}.travel_mm[{i}]") for i, v in enumerate(t))
            if not lo < hi:
                raise ValueError(f"{where}.travel_mm = {t!r}: min must be below max")
        a.travel_min, a.travel_max = lo, hi
        a.origin = _vec3(ad.get("origin_mm", [0.0, 0.0, 0.0]), f"{where}.origin_mm")
        policy = ad.get("out_of_range", "error")
        if policy not in _OUT_OF_RANGE:
            raise ValueError(f"{where}.out_of_range = {policy!r}: must be 'error', 'clamp' or 'extrapolate'")
        funcs = [_m.ErrorFunction.zero_function(n) for n in iso_names(name)]
        given: dict[str, str] = {}
        if "table" in ad:
            t = ad["table"]
            if isinstance(t, str):
                tpath = Path(t) if Path(t).is_absolute() else Path(base_dir) / t
                tab = read_error_table(tpath, name)
                origin = str(tpath)
            elif isinstance(t, dict):
                tab = _inline_table(t, name, f"{where}.table")
                origin = f"{where}.table"
            else:
                raise ValueError(f"{where}.table = {t!r}: must be a CSV file name or an inline table")
            for cname, vals in tab["components"].items():
                c = iso_names(name).index(cname)
                funcs[c] = _m.ErrorFunction.table(tab["positions"], vals, _OUT_OF_RANGE[policy], cname)
                given[cname] = origin
        polys = ad.get("polynomials", {})
        if not isinstance(polys, dict):
            raise ValueError(f"{where}.polynomials: must be a table of KEY = [c0, c1, ...]")
        for key, coef in polys.items():
            c, f = _split_unit(key, name, f"{where}.polynomials")
            cname = iso_names(name)[c]
            if cname in given:
                raise ValueError(f"{where}.polynomials.{key}: {cname} is already given by {given[cname]}")
            if not isinstance(coef, list) or not coef:
                raise ValueError(f"{where}.polynomials.{key} = {coef!r}: must be a list of coefficients")
            vals = [_finite(v, f"{where}.polynomials.{key}[{i}]") * f for i, v in enumerate(coef)]
            funcs[c] = _m.ErrorFunction.polynomial(vals, cname)
            given[cname] = f"{where}.polynomials"
        a.errors = funcs
        a.backlash = _length(ad, "backlash", where)
        a.cyclic = _cyclic(ad.get("cyclic", []), f"{where}.cyclic")
    m.axes = axes
    m.thermal = _thermal(doc.get("thermal", []), f"{source}: thermal")
    try:
        m.validate()
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return m


def load_machine(path: str | os.PathLike) -> _m.Machine:
    """Read a machine description (TOML, see the module docstring) into a :class:`Machine`."""
    p = Path(path)
    if not p.exists():
        raise FileNotFoundError(2, "No such file or directory", str(p))
    from .._text import read_toml

    doc = read_toml(p)
    return machine_from_dict(doc, p.parent, str(p))
