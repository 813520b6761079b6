"""Measurement bundles: a folder with ``manifest.toml`` and one CSV file per experiment.

``kind = "cutting_force"``::

    kind = "cutting_force"
    [tool]                      # type flat|ball, diameter_mm, flutes, helix_deg
    type = "flat"
    diameter_mm = 10.0
    flutes = 2
    helix_deg = 30.0
    runout_rho_mm = 0.0         # optional: the tool's runout, offset [mm] and angle [deg]
    runout_lambda_deg = 0.0
    [model]                     # the current linear edge-force coefficients
    Ktc_N_per_mm2 = 958.8
    Krc_N_per_mm2 = 251.1
    Kac_N_per_mm2 = 146.4
    Kte_N_per_mm = 15.8
    Kre_N_per_mm = 19.4
    Kae_N_per_mm = 18.2
    chip_exponent = 1.0         # optional: chip-size effect exponent p and its
    reference_chip_mm = 0.05    # reference h_ref (default: the geometric mean feed per tooth)
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

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np


from ._manifest import Bundle, _check_keys, _noise_table, _experiment_head, _fail, _mode, _number, _read_csv
from .wall_bundle import WallContourExperiment, WallExperiment, _load_wall

__all__ = ["Bundle", "ForceExperiment", "VolumetricExperiment", "WallExperiment", "WallContourExperiment",
           "load_bundle", "KINDS"]


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
#: optional [model] keys: the chip-size effect g(h) = h_ref·(h/h_ref)^p (netshape.force.RunoutSizeEffect)
FORCE_MODEL_OPTIONAL = ("chip_exponent", "reference_chip_mm")
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


def _load_force(doc: dict, root: Path, where: str) -> Bundle:
    _check_keys(doc, ("kind", "tool", "model", "experiment", "noise"), where)
    noise = _noise_table(doc, "sigma_N", where)
    tool = doc.get("tool")
    if not isinstance(tool, dict):
        raise _fail(where, "missing table [tool] (type, diameter_mm, flutes, helix_deg)")
    w = f"{where}: [tool]"
    _check_keys(tool, ("type", "diameter_mm", "flutes", "helix_deg", "runout_rho_mm", "runout_lambda_deg"), w)
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
        "runout_rho": _number(tool, "runout_rho_mm", w, default=0.0),
        "runout_lambda": math.radians(_number(tool, "runout_lambda_deg", w, default=0.0)),
    }
    if tool_out["runout_rho"] < 0:
        raise _fail(w, f"runout_rho_mm = {tool_out['runout_rho']}: must be ≥ 0 [mm]")
    model = doc.get("model")
    if not isinstance(model, dict):
        raise _fail(where, f"missing table [model] ({', '.join(FORCE_MODEL_KEYS)})")
    _check_keys(model, FORCE_MODEL_KEYS + FORCE_MODEL_OPTIONAL, f"{where}: [model]")
    model_out = {k: _number(model, k, f"{where}: [model]") for k in FORCE_MODEL_KEYS}
    for k in FORCE_MODEL_OPTIONAL:
        if k in model:
            model_out[k] = _number(model, k, f"{where}: [model]", positive=True)
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
        if angles is not None and (len(angles) < 2 or not np.median(np.abs(np.diff(angles))) > 0):
            raise _fail(str(path), "column 'angle_deg': the angle must advance from row to row (the median step "
                        "is 0)")
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
    return Bundle(kind="cutting_force", path=str(root), model=model_out, experiments=out, tool=tool_out, noise=noise)


def _axis_list(value: Any, where: str) -> list:
    if not isinstance(value, list) or not all(isinstance(a, str) and a.upper() in _AXES for a in value):
        raise _fail(where, f'{value!r}: must be a list of axis letters, e.g. ["X", "Y"]')
    return [a.upper() for a in value]


def _load_volumetric(doc: dict, root: Path, where: str) -> Bundle:
    _check_keys(doc, ("kind", "machine", "model", "experiment", "noise"), where)
    noise = _noise_table(doc, "sigma_mm", where)
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
        noise=noise,
    )


def load_bundle(path: str | os.PathLike) -> Bundle:
    """Read a bundle folder (or its manifest.toml). Raises FileNotFoundError for a missing folder,
    manifest or CSV, ValueError naming the file and the field for anything malformed."""
    p = Path(path)
    manifest = p if p.is_file() else p / "manifest.toml"
    if not manifest.is_file():
        raise FileNotFoundError(2, "No such file or directory", str(manifest))
    from netshape._text import read_toml

    doc = read_toml(manifest)
    kind = doc.get("kind")
    where = str(manifest)
    if kind not in KINDS:
        raise _fail(where, f"kind = {kind!r}: must be one of {', '.join(KINDS)}")
    if kind == "wall_error":
        return _load_wall(doc, manifest.parent, where)
    if kind == "cutting_force":
        return _load_force(doc, manifest.parent, where)
    return _load_volumetric(doc, manifest.parent, where)
