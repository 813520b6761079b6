"""Measurement bundles: a folder with ``manifest.toml`` and one CSV file per experiment.

``kind = "cutting_force"``::

    kind = "cutting_force"
    [tool]                      # type flat|ball, diameter_mm, flutes, helix_deg
    type = "flat"
    diameter_mm = 10.0
    flutes = 2
    helix_deg = 30.0
    [model]                     # the current linear edge-force coefficients
    Ktc_N_per_mm2 = 958.8
    Krc_N_per_mm2 = 251.1
    Kac_N_per_mm2 = 146.4
    Kte_N_per_mm = 15.8
    Kre_N_per_mm = 19.4
    Kae_N_per_mm = 18.2
    [[experiment]]
    file = "slot_f050.csv"      # columns angle_deg,fx_N,fy_N,fz_N or time_s,fx_N,fy_N,fz_N
    spindle_rpm = 6000.0
    feed_per_tooth_mm = 0.05
    axial_depth_mm = 3.0
    radial_depth_mm = 10.0      # may be left out for mode = "slot"
    mode = "slot"               # up | down | slot

``angle_deg`` is the immersion of flute 1 at the tool tip; forces act on the cutter in the cutting
frame (X feed, Z tool axis into the spindle, Y = Z × X). An experiment may instead name a Kistler
DynoWare export with ``format = "dynoware"`` (and ``to_cutter = "leekunhwee"`` for that set-up's
channel mapping, see :func:`netshape.force.read_dynoware`); it is then a time series. A time series
may be cut to ``time_window_s = [start, end]``: the samples from start to end seconds after its first.

``kind = "volumetric_error"``::

    kind = "volumetric_error"
    [machine]
    tool_side = ["Z"]           # axes from the bed outward to the spindle
    workpiece_side = ["Y", "X"] # axes from the bed outward to the workpiece
    tool_length_mm = 100.0
    [model]                     # known components: polynomial in the axis position [mm] → mm or rad
    EXX = [0.0, 2e-5]
    EC0Y = [1e-6]               # squareness and spindle tilt (spindle_tilt_a, spindle_tilt_b): constants
    [[experiment]]
    file = "grid.csv"           # columns x_mm,y_mm,z_mm,ex_mm,ey_mm,ez_mm[,t_s][,direction]
    tool_length_mm = 150.0      # optional: this experiment's tool length (default [machine])

e = actual − nominal tool tip relative to the workpiece [mm]; ``t_s`` when the point was measured [s];
``direction`` (+1/−1) the approach direction of the moving axis.

``kind = "wall_error"`` (steady straight cuts of a flat end mill, the case of ``netshape deflection
wall``)::

    kind = "wall_error"
    [tool]                      # flat end mill: diameter_mm, flutes, helix_deg, stick_out_mm,
    diameter_mm = 6.0           # youngs_modulus_MPa (default 600000, carbide)
    flutes = 3
    helix_deg = 30.0
    stick_out_mm = 30.0
    [model]
    coefficients = "Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10"   # as deflection --coefficients
    inertia = "square"          # optional: square | equivalent
    load = "distributed"        # optional: resultant | distributed
    [[experiment]]
    file = "cut1.csv"           # columns x_mm,error_mm or x_mm,z_mm,error_mm
    feed_per_tooth_mm = 0.1
    axial_depth_mm = 4.0
    radial_depth_mm = 1.0       # may be left out for mode = "slot"
    mode = "down"               # up | down | slot
    side = "right"              # optional: left | right (default: up → left, down → right; slot: required)
    z_mm = 2.0                  # height of the x_mm,error_mm profile above the tip (default ap/2)
    spindle_rpm = 6000.0        # optional, recorded only

error = the wall's deviation from its nominal position along its normal [mm], + where material is
left; x_mm along the feed from a position where flute 1 generates the wall at the tool tip (z = 0);
z_mm above the tool tip.

An experiment that names a ``program`` is a wall along that program's 2-D contour over a stock (the
case of ``netshape deflection predict``; ``[tool]`` may then be left out)::

    [[experiment]]
    file = "contour1.csv"       # columns x_mm,error_mm or x_mm,z_mm,error_mm
    program = "contour1.ngc"    # one 2-D contour
    tool = "tool.toml"          # cutter TOML of a flat end mill with stick_out_mm, youngs_modulus_MPa
    stock = "stock.toml"        # min_mm, max_mm, spacing_mm, optional [[pre_cut]]
    spindle_rpm = 8000.0
    spacing_mm = 0.5            # optional: prediction point spacing [mm]
    side = "auto"               # optional: auto | left | right
    z_mm = 2.0                  # optional (default: the middle of the cut)

x_mm there is the distance along the contour (XY) from its first point [mm].

Every problem raises one ValueError naming the file and the field (FileNotFoundError for a missing
file).
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

try:  # Python ≥ 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10 needs the tomli package
    import tomli as tomllib

KINDS = ("cutting_force", "volumetric_error", "wall_error")
FORCE_COLUMNS = ("fx_N", "fy_N", "fz_N")
FORCE_MODEL_KEYS = (
    "Ktc_N_per_mm2",
    "Krc_N_per_mm2",
    "Kac_N_per_mm2",
    "Kte_N_per_mm",
    "Kre_N_per_mm",
    "Kae_N_per_mm",
)
VOLUMETRIC_COLUMNS = ("x_mm", "y_mm", "z_mm", "ex_mm", "ey_mm", "ez_mm")
VOLUMETRIC_OPTIONAL = ("t_s", "direction")
_AXES = "XYZ"
#: ISO 230-1 names allowed in a volumetric [model]: the 18 axis components, the three squareness
#: errors and the spindle tilt.
VOLUMETRIC_MODEL_KEYS = tuple(f"E{d}{a}" for a in _AXES for d in "XYZABC") + (
    "EC0Y",
    "EB0Z",
    "EA0Z",
    "spindle_tilt_a",
    "spindle_tilt_b",
)


@dataclass
class ForceExperiment:
    """One cutting-force recording. ``angles`` (n,) [rad] when the file has ``angle_deg``, else None
    and ``times`` (n,) [s]; ``forces`` (n, 3) [N] on the cutter; ``mode`` up|down|slot."""

    file: str
    spindle_rpm: float
    feed_per_tooth: float
    axial_depth: float
    radial_depth: float
    mode: str
    forces: np.ndarray
    angles: np.ndarray | None = None
    times: np.ndarray | None = None

    @property
    def time_based(self) -> bool:
        return self.angles is None


@dataclass
class VolumetricExperiment:
    """One volumetric measurement: nominal points (n, 3) [mm], errors (n, 3) [mm], optional times
    (n,) [s] and directions (n,) (±1), tool length [mm]."""

    file: str
    points: np.ndarray
    errors: np.ndarray
    tool_length: float
    times: np.ndarray | None = None
    directions: np.ndarray | None = None


@dataclass
class WallExperiment:
    """One wall-error measurement of a steady straight cut: positions x (n,) along the feed and z
    (n,) above the tip [mm], errors (n, 1) [mm] (+ material left); the cut's data in mm."""

    file: str
    feed_per_tooth: float
    axial_depth: float
    radial_depth: float
    mode: str
    side: str
    x: np.ndarray
    z: np.ndarray
    errors: np.ndarray
    spindle_rpm: float | None = None


@dataclass
class WallContourExperiment:
    """One wall-error measurement along a program's 2-D contour cut over a stock (the case of
    ``netshape deflection predict``): the program, tool and stock files, the spindle speed [rpm], the
    contour sampling ``spacing`` [mm] and wall ``side`` (auto | left | right); positions x (n,) along
    the contour from its start and z (n,) above the tip [mm] (NaN: the middle of the cut), errors
    (n, 1) [mm] (+ material left). ``cutter`` is the tool file's Cutter."""

    file: str
    program: str
    tool: str
    stock: str
    spindle_rpm: float
    spacing: float
    side: str
    x: np.ndarray
    z: np.ndarray
    errors: np.ndarray
    cutter: Any = None


@dataclass
class Bundle:
    """A loaded measurement bundle. ``tool`` / ``machine`` / ``model`` are the manifest tables with
    units stripped into plain keys (see :func:`load_bundle`); ``experiments`` one per CSV."""

    kind: str
    path: str
    model: dict
    experiments: list
    tool: dict = field(default_factory=dict)
    machine: dict = field(default_factory=dict)


def _fail(where: str, msg: str) -> ValueError:
    return ValueError(f"{where}: {msg}")


def _number(table: dict, key: str, where: str, *, positive: bool = False, default: Any = None) -> float:
    if key not in table:
        if default is not None:
            return default
        raise _fail(where, f"missing key {key!r}")
    v = table[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise _fail(where, f"{key} = {v!r}: must be a finite number")
    if positive and v <= 0:
        raise _fail(where, f"{key} = {v!r}: must be positive")
    return float(v)


def _check_keys(table: dict, allowed, where: str) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise _fail(where, f"unknown key {unknown[0]!r} (allowed: {', '.join(allowed)})")


def _experiment_head(e: dict, i: int, keys, where: str, root: Path) -> tuple[str, Path]:
    """Checks common to every ``[[experiment]]`` table: known keys and a CSV ``file``. Returns the
    error prefix of the table and the CSV's path (relative paths are relative to the bundle)."""
    we = f"{where}: [[experiment]] {i}"
    _check_keys(e, keys, we)
    if not isinstance(e.get("file"), str) or not e["file"]:
        raise _fail(we, f"file = {e.get('file')!r}: must name a CSV file")
    path = Path(e["file"])
    return we, (path if path.is_absolute() else root / path)


def _mode(e: dict, we: str) -> str:
    mode = e.get("mode")
    if mode not in ("up", "down", "slot"):
        raise _fail(we, f"mode = {mode!r}: must be 'up', 'down' or 'slot'")
    return mode


def _read_csv(path: Path, required: tuple, optional: tuple, alternatives: tuple = ()) -> dict:
    """Read a CSV of numbers with a header row → {column: (n,) float array}. ``alternatives``: a
    tuple of column names of which exactly one must be present (besides ``required``)."""
    if not path.is_file():
        raise FileNotFoundError(2, "No such file or directory", str(path))
    with open(path, newline="", encoding="utf-8") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    if not rows:
        raise _fail(str(path), "empty file (expected a header row and data rows)")
    header = [h.strip() for h in rows[0]]
    allowed = set(required) | set(optional) | set(alternatives)
    for h in header:
        if h not in allowed:
            raise _fail(
                str(path),
                f"unknown column {h!r} (expected {', '.join((*alternatives, *required, *optional))})",
            )
    if len(set(header)) != len(header):
        raise _fail(str(path), f"repeated column in header {header}")
    for r in required:
        if r not in header:
            raise _fail(str(path), f"missing column {r!r}")
    if alternatives and sum(a in header for a in alternatives) != 1:
        raise _fail(str(path), f"needs exactly one of the columns {' or '.join(map(repr, alternatives))}")
    data = rows[1:]
    if len(data) < 2:
        raise _fail(str(path), f"{len(data)} data rows: need at least 2")
    out = np.empty((len(data), len(header)))
    for i, row in enumerate(data, start=2):
        if len(row) != len(header):
            raise _fail(str(path), f"line {i}: {len(row)} fields, header has {len(header)}")
        for j, text in enumerate(row):
            try:
                v = float(text)
            except ValueError:
                raise _fail(
                    str(path), f"line {i}, column {header[j]!r}: {text.strip()!r} is not a number"
                ) from None
            if not math.isfinite(v):
                raise _fail(str(path), f"line {i}, column {header[j]!r}: {text.strip()!r} is not finite")
            out[i - 2, j] = v
    return {h: out[:, j].copy() for j, h in enumerate(header)}


def _load_force(doc: dict, root: Path, where: str) -> Bundle:
    _check_keys(doc, ("kind", "tool", "model", "experiment"), where)
    tool = doc.get("tool")
    if not isinstance(tool, dict):
        raise _fail(where, "missing table [tool] (type, diameter_mm, flutes, helix_deg)")
    w = f"{where}: [tool]"
    _check_keys(tool, ("type", "diameter_mm", "flutes", "helix_deg"), w)
    ttype = tool.get("type")
    if ttype not in ("flat", "ball"):
        raise _fail(w, f"type = {ttype!r}: must be 'flat' or 'ball'")
    flutes = tool.get("flutes")
    if isinstance(flutes, bool) or not isinstance(flutes, int) or not 1 <= flutes <= 64:
        raise _fail(w, f"flutes = {flutes!r}: must be an integer in 1..64")
    helix = _number(tool, "helix_deg", w)
    if not -80.0 < helix < 80.0:
        raise _fail(w, f"helix_deg = {helix}: must be in (-80, 80) [deg]")
    tool_out = {
        "type": ttype,
        "diameter": _number(tool, "diameter_mm", w, positive=True),
        "flutes": flutes,
        "helix": math.radians(helix),
    }
    model = doc.get("model")
    if not isinstance(model, dict):
        raise _fail(where, f"missing table [model] ({', '.join(FORCE_MODEL_KEYS)})")
    _check_keys(model, FORCE_MODEL_KEYS, f"{where}: [model]")
    model_out = {k: _number(model, k, f"{where}: [model]") for k in FORCE_MODEL_KEYS}
    exps = doc.get("experiment")
    if not isinstance(exps, list) or not exps:
        raise _fail(where, "no [[experiment]] tables")
    out = []
    keys = (
        "file",
        "spindle_rpm",
        "feed_per_tooth_mm",
        "axial_depth_mm",
        "radial_depth_mm",
        "mode",
        "format",
        "to_cutter",
        "time_window_s",
    )
    for i, e in enumerate(exps, start=1):
        we, path = _experiment_head(e, i, keys, where, root)
        mode = _mode(e, we)
        rpm = _number(e, "spindle_rpm", we, positive=True)
        c = _number(e, "feed_per_tooth_mm", we, positive=True)
        ap = _number(e, "axial_depth_mm", we, positive=True)
        ae = _number(
            e, "radial_depth_mm", we, positive=True, default=tool_out["diameter"] if mode == "slot" else None
        )
        if mode != "slot" and ae > tool_out["diameter"]:
            raise _fail(
                we, f"radial_depth_mm = {ae}: larger than the tool diameter {tool_out['diameter']} mm"
            )
        fmt = e.get("format", "csv")
        if fmt == "csv":
            if "to_cutter" in e:
                raise _fail(we, "to_cutter is only for format = 'dynoware'")
            cols = _read_csv(path, FORCE_COLUMNS, (), ("angle_deg", "time_s"))
            forces = np.column_stack([cols[k] for k in FORCE_COLUMNS])
            angles = np.radians(cols["angle_deg"]) if "angle_deg" in cols else None
            times = cols.get("time_s")
        elif fmt == "dynoware":
            from netshape.force import read_dynoware

            if not path.is_file():
                raise FileNotFoundError(2, "No such file or directory", str(path))
            to_cutter = e.get("to_cutter")
            if to_cutter not in (None, "leekunhwee"):
                raise _fail(we, f"to_cutter = {to_cutter!r}: must be 'leekunhwee' or left out")
            rec = read_dynoware(path, to_cutter=to_cutter)
            forces, angles, times = np.asarray(rec.forces, float), None, np.asarray(rec.times, float)
        else:
            raise _fail(we, f"format = {fmt!r}: must be 'csv' or 'dynoware'")
        if times is not None and not np.all(np.diff(times) > 0):
            raise _fail(str(path), "column 'time_s': times must increase strictly")
        if "time_window_s" in e:
            win = e["time_window_s"]
            if (
                times is None
                or not isinstance(win, list)
                or len(win) != 2
                or not all(isinstance(v, (int, float)) and math.isfinite(v) for v in win)
                or not win[0] < win[1]
            ):
                raise _fail(
                    we, f"time_window_s = {win!r}: must be [start, end] in s (start < end) of a time series"
                )
            keep = (times - times[0] >= win[0]) & (times - times[0] <= win[1])
            if keep.sum() < 2:
                raise _fail(we, f"time_window_s = {win!r}: holds {int(keep.sum())} samples of {path.name}")
            times, forces = times[keep], forces[keep]
        out.append(
            ForceExperiment(
                file=str(path),
                spindle_rpm=rpm,
                feed_per_tooth=c,
                axial_depth=ap,
                radial_depth=ae,
                mode=mode,
                forces=forces,
                angles=angles,
                times=None if times is None else times - 0.0,
            )
        )
    return Bundle(kind="cutting_force", path=str(root), model=model_out, experiments=out, tool=tool_out)


def _axis_list(value: Any, where: str) -> list:
    if not isinstance(value, list) or not all(isinstance(a, str) and a.upper() in _AXES for a in value):
        raise _fail(where, f'{value!r}: must be a list of axis letters, e.g. ["X", "Y"]')
    return [a.upper() for a in value]


def _load_volumetric(doc: dict, root: Path, where: str) -> Bundle:
    _check_keys(doc, ("kind", "machine", "model", "experiment"), where)
    mach = doc.get("machine")
    if not isinstance(mach, dict):
        raise _fail(where, "missing table [machine] (tool_side, workpiece_side, tool_length_mm)")
    w = f"{where}: [machine]"
    _check_keys(mach, ("tool_side", "workpiece_side", "tool_length_mm"), w)
    for key in ("tool_side", "workpiece_side"):
        if key not in mach:
            raise _fail(w, f"missing key {key!r}")
    ts = _axis_list(mach["tool_side"], f"{w} tool_side")
    ws = _axis_list(mach["workpiece_side"], f"{w} workpiece_side")
    if sorted(ts + ws) != list(_AXES):
        raise _fail(w, f"tool_side {ts} + workpiece_side {ws}: every axis X, Y, Z exactly once")
    length = _number(mach, "tool_length_mm", w)
    if length < 0:
        raise _fail(w, f"tool_length_mm = {length}: must be ≥ 0")
    model = doc.get("model", {})
    if not isinstance(model, dict):
        raise _fail(where, "[model] must be a table of ISO 230-1 name = [c0, c1, ...]")
    wm = f"{where}: [model]"
    _check_keys(model, VOLUMETRIC_MODEL_KEYS, wm)
    model_out = {}
    for k, v in model.items():
        coef = v if isinstance(v, list) else [v]
        if not coef or any(
            isinstance(c, bool) or not isinstance(c, (int, float)) or not math.isfinite(c) for c in coef
        ):
            raise _fail(wm, f"{k} = {v!r}: must be a list of finite coefficients (constant first)")
        if (k[:2] in ("EC", "EB", "EA") and k[2] == "0" or k.startswith("spindle")) and len(coef) != 1:
            raise _fail(wm, f"{k} = {v!r}: a constant, one value")
        model_out[k] = [float(c) for c in coef]
    exps = doc.get("experiment")
    if not isinstance(exps, list) or not exps:
        raise _fail(where, "no [[experiment]] tables")
    out = []
    for i, e in enumerate(exps, start=1):
        we, path = _experiment_head(e, i, ("file", "tool_length_mm"), where, root)
        L = _number(e, "tool_length_mm", we, default=length)
        if L < 0:
            raise _fail(we, f"tool_length_mm = {L}: must be ≥ 0")
        cols = _read_csv(path, VOLUMETRIC_COLUMNS, VOLUMETRIC_OPTIONAL)
        d = cols.get("direction")
        if d is not None and not np.all(np.abs(d) == 1.0):
            j = int(np.argmax(np.abs(d) != 1.0))
            raise _fail(str(path), f"line {j + 2}, column 'direction': {float(d[j])!r} must be +1 or -1")
        out.append(
            VolumetricExperiment(
                file=str(path),
                points=np.column_stack([cols[k] for k in VOLUMETRIC_COLUMNS[:3]]),
                errors=np.column_stack([cols[k] for k in VOLUMETRIC_COLUMNS[3:]]),
                tool_length=L,
                times=cols.get("t_s"),
                directions=d,
            )
        )
    return Bundle(
        kind="volumetric_error",
        path=str(root),
        model=model_out,
        experiments=out,
        machine={"tool_side": ts, "workpiece_side": ws, "tool_length": length},
    )


WALL_TOOL_KEYS = ("type", "diameter_mm", "flutes", "helix_deg", "stick_out_mm", "youngs_modulus_MPa")
WALL_MODEL_KEYS = ("coefficients", "inertia", "load")


def _wall_tool_table(tool: Any, where: str) -> dict:
    """The [tool] table of a wall bundle in plain keys (diameter, flutes, helix_deg, stick_out,
    youngs_modulus)."""
    if not isinstance(tool, dict):
        raise _fail(where, "missing table [tool] (diameter_mm, flutes, helix_deg, stick_out_mm, youngs_modulus_MPa)")
    w = f"{where}: [tool]"
    _check_keys(tool, WALL_TOOL_KEYS, w)
    if tool.get("type", "flat") != "flat":
        raise _fail(w, f"type = {tool['type']!r}: the deflection model needs a flat end mill ('flat')")
    flutes = tool.get("flutes")
    if isinstance(flutes, bool) or not isinstance(flutes, int) or not 1 <= flutes <= 64:
        raise _fail(w, f"flutes = {flutes!r}: must be an integer in 1..64")
    helix = _number(tool, "helix_deg", w)
    if not 0.0 <= helix < 80.0:
        raise _fail(w, f"helix_deg = {helix}: must be in [0, 80) [deg]")
    return {
        "type": "flat",
        "diameter": _number(tool, "diameter_mm", w, positive=True),
        "flutes": flutes,
        "helix_deg": helix,
        "stick_out": _number(tool, "stick_out_mm", w, positive=True),
        "youngs_modulus": _number(tool, "youngs_modulus_MPa", w, positive=True, default=600e3),
    }


def _file_key(e: dict, key: str, we: str, root: Path) -> Path:
    """A file named by key ``key`` of an experiment table (relative to the bundle); must exist."""
    v = e.get(key)
    if not isinstance(v, str) or not v:
        raise _fail(we, f"{key} = {v!r}: must name a file")
    path = Path(v) if Path(v).is_absolute() else root / v
    if not path.is_file():
        raise FileNotFoundError(2, f"No such file or directory ({we}: {key})", str(path))
    return path


def _wall_csv(e: dict, we: str, path: Path, *, z_default: float, axial_depth: float | None = None):
    """The ``x_mm,error_mm[,z_mm]`` CSV of a wall experiment and the height z (n,) of each point [mm]:
    the CSV's z_mm column, else the experiment's ``z_mm`` key, else ``z_default``. A height below 0, or
    above ``axial_depth`` when it is given, is refused naming the CSV line or the key."""
    cols = _read_csv(path, ("x_mm", "error_mm"), ("z_mm",))
    if "z_mm" in cols:
        if "z_mm" in e:
            raise _fail(we, "z_mm: given both here and as a column of the CSV (keep one)")
        z = cols["z_mm"]
    else:
        z = np.full(len(cols["x_mm"]), _number(e, "z_mm", we, default=z_default))
    bad = (z < 0) if axial_depth is None else (z < 0) | (z > axial_depth)
    if bad.any():
        j = int(np.argmax(bad))
        src = f"{path}: line {j + 2}, column 'z_mm'" if "z_mm" in cols else f"{we}: z_mm"
        what = ("must be ≥ 0 (height above the tool tip) [mm]" if axial_depth is None
                else f"must lie within the cut, 0..axial_depth_mm = {axial_depth} [mm]")
        raise ValueError(f"{src}: {float(z[j])!r} {what}")
    return cols, z


WALL_CONTOUR_KEYS = ("file", "program", "tool", "stock", "spindle_rpm", "spacing_mm", "side", "z_mm")


def _load_wall_contour(e: dict, i: int, where: str, root: Path) -> WallContourExperiment:
    """An [[experiment]] of a wall bundle that names a program, a tool TOML and a stock TOML."""
    from netshape.cutter import CutterKind, load_cutter

    we, path = _experiment_head(e, i, WALL_CONTOUR_KEYS, where, root)
    program = _file_key(e, "program", we, root)
    tool = _file_key(e, "tool", we, root)
    stock = _file_key(e, "stock", we, root)
    try:
        cutter = load_cutter(tool)
    except ValueError as exc:
        raise _fail(we, f"tool: {exc}") from None
    if cutter.kind != CutterKind.flat:
        raise _fail(we, f"tool = {str(tool)!r}: the deflection model needs a flat end mill (kind = 'flat')")
    if not cutter.stick_out > 0:
        raise _fail(we, f"tool = {str(tool)!r}: stick_out_mm must be given (the cantilever length) [mm]")
    rpm = _number(e, "spindle_rpm", we, positive=True)
    spacing = _number(e, "spacing_mm", we, positive=True, default=0.5)
    side = e.get("side", "auto")
    if side not in ("auto", "left", "right"):
        raise _fail(we, f"side = {side!r}: must be 'auto', 'left' or 'right'")
    cols, z = _wall_csv(e, we, path, z_default=math.nan)
    bad = cols["x_mm"] < 0
    if bad.any():
        j = int(np.argmax(bad))
        raise ValueError(f"{path}: line {j + 2}, column 'x_mm': {float(cols['x_mm'][j])!r} must be ≥ 0 "
                         "(distance along the contour from its start) [mm]")
    return WallContourExperiment(file=str(path), program=str(program), tool=str(tool), stock=str(stock),
                                 spindle_rpm=rpm, spacing=spacing, side=side, x=cols["x_mm"], z=z,
                                 errors=cols["error_mm"][:, None], cutter=cutter)


def _cutter_table(c) -> dict:
    """Diameter [mm], flutes and helix [deg] of a netshape Cutter in the keys of a [tool] table."""
    return {"diameter": float(c.diameter()), "flutes": int(c.flutes),
            "helix_deg": math.degrees(float(c.helix))}


def _same_tool(tool_out: dict, c, we: str) -> None:
    """Every experiment of a wall bundle uses one tool geometry (the runout and holder parameters are
    the tool's)."""
    mine = _cutter_table(c)
    for k, v in mine.items():
        if not math.isclose(float(tool_out[k]), v, rel_tol=1e-9, abs_tol=1e-9):
            raise _fail(we, f"tool: {k} = {v:g} differs from the bundle's other experiments "
                        f"({tool_out[k]:g}); one bundle holds one tool")


def _load_wall(doc: dict, root: Path, where: str) -> Bundle:
    from netshape import deflection as _defl

    _check_keys(doc, ("kind", "tool", "model", "experiment"), where)
    exps = doc.get("experiment")
    if not isinstance(exps, list) or not exps:
        raise _fail(where, "no [[experiment]] tables")
    contour = [isinstance(e, dict) and "program" in e for e in exps]
    tool_out = _wall_tool_table(doc.get("tool"), where) if ("tool" in doc or not all(contour)) else None
    model = doc.get("model")
    wm = f"{where}: [model]"
    if not isinstance(model, dict):
        raise _fail(where, "missing table [model] (coefficients, inertia, load)")
    _check_keys(model, WALL_MODEL_KEYS, wm)
    if not isinstance(model.get("coefficients"), str):
        raise _fail(wm, f"coefficients = {model.get('coefficients')!r}: must be a set name, 'Ktc=…,…' or 'KT=…,KR=…'")
    try:
        _defl.parse_coefficients(model["coefficients"])
    except ValueError as exc:
        raise _fail(wm, str(exc)) from None
    model_out = {"coefficients": model["coefficients"]}
    for key, allowed in (("inertia", ("square", "equivalent")), ("load", ("resultant", "distributed"))):
        v = model.get(key, allowed[0] if key == "inertia" else allowed[1])
        if v not in allowed:
            raise _fail(wm, f"{key} = {v!r}: must be {' or '.join(map(repr, allowed))}")
        model_out[key] = v
    keys = ("file", "spindle_rpm", "feed_per_tooth_mm", "axial_depth_mm", "radial_depth_mm", "mode", "side", "z_mm")
    out = []
    for i, e in enumerate(exps, start=1):
        if contour[i - 1]:
            ce = _load_wall_contour(e, i, where, root)
            c = ce.cutter
            if tool_out is None:
                tool_out = dict(_cutter_table(c), type="flat", stick_out=float(c.stick_out),
                                youngs_modulus=float(c.youngs_modulus))
            else:
                _same_tool(tool_out, c, f"{where}: [[experiment]] {i}")
            out.append(ce)
            continue
        flutes, helix = tool_out["flutes"], tool_out["helix_deg"]
        we, path = _experiment_head(e, i, keys, where, root)
        mode = _mode(e, we)
        side = e.get("side", {"up": "left", "down": "right"}.get(mode))
        if side not in ("left", "right"):
            raise _fail(we, f"side = {side!r}: must be 'left' or 'right' (required for mode = 'slot')")
        c = _number(e, "feed_per_tooth_mm", we, positive=True)
        ap = _number(e, "axial_depth_mm", we, positive=True)
        ae = _number(e, "radial_depth_mm", we, positive=True, default=tool_out["diameter"] if mode == "slot" else None)
        rpm = _number(e, "spindle_rpm", we, positive=True) if "spindle_rpm" in e else None
        try:
            _defl.make_model(diameter=tool_out["diameter"], flutes=flutes, helix_deg=helix,
                             stick_out=tool_out["stick_out"], youngs_modulus=tool_out["youngs_modulus"],
                             feed_per_tooth=c, ap=ap, ae=ae, mode=mode, coefficients=model["coefficients"],
                             inertia=model_out["inertia"], load=model_out["load"])
        except ValueError as exc:
            raise _fail(we, str(exc)) from None
        cols, z = _wall_csv(e, we, path, z_default=0.5 * ap, axial_depth=ap)
        out.append(
            WallExperiment(file=str(path), feed_per_tooth=c, axial_depth=ap, radial_depth=ae, mode=mode,
                           side=side, x=cols["x_mm"], z=z, errors=cols["error_mm"][:, None], spindle_rpm=rpm)
        )
    return Bundle(kind="wall_error", path=str(root), model=model_out, experiments=out, tool=tool_out)


def load_bundle(path: str | os.PathLike) -> Bundle:
    """Read a bundle folder (or its manifest.toml). Raises FileNotFoundError for a missing folder,
    manifest or CSV, ValueError naming the file and the field for anything malformed."""
    p = Path(path)
    manifest = p if p.is_file() else p / "manifest.toml"
    if not manifest.is_file():
        raise FileNotFoundError(2, "No such file or directory", str(manifest))
    try:
        with open(manifest, "rb") as fh:
            doc = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{manifest}: not valid TOML: {exc}") from None
    kind = doc.get("kind")
    where = str(manifest)
    if kind not in KINDS:
        raise _fail(where, f"kind = {kind!r}: must be one of {', '.join(KINDS)}")
    if kind == "wall_error":
        return _load_wall(doc, manifest.parent, where)
    if kind == "cutting_force":
        return _load_force(doc, manifest.parent, where)
    return _load_volumetric(doc, manifest.parent, where)
