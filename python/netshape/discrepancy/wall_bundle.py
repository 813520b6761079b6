"""Wall-error bundles (``kind = "wall_error"``, see :mod:`netshape.discrepancy.bundle`): steady
straight cuts described by the cut's numbers, and cuts along a program's contour described by the
program, tool and stock files."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ._manifest import Bundle, _check_keys, _noise_table, _experiment_head, _fail, _mode, _number, _read_csv



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


WALL_TOOL_KEYS = ("type", "diameter_mm", "flutes", "helix_deg", "stick_out_mm", "youngs_modulus_MPa",
                  "holder_compliance_um_per_N", "runout_rho_mm", "runout_lambda_deg")
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
        **_holder_terms(tool, w),
    }


def _holder_terms(tool: dict, w: str) -> dict:
    """The optional tool-in-holder keys of a [tool] table (netshape.cutter): holder compliance
    [mm/N], runout ρ [mm] and λ [rad]."""
    out = {"holder_compliance": 1e-3 * _number(tool, "holder_compliance_um_per_N", w, default=0.0),
           "runout_rho": _number(tool, "runout_rho_mm", w, default=0.0),
           "runout_lambda": math.radians(_number(tool, "runout_lambda_deg", w, default=0.0))}
    for k in ("holder_compliance", "runout_rho"):
        if out[k] < 0:
            raise _fail(w, f"{k} = {out[k]!r}: must be ≥ 0")
    return out


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

    _check_keys(doc, ("kind", "tool", "model", "experiment", "noise"), where)
    noise = _noise_table(doc, "sigma_mm", where)
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
                                youngs_modulus=float(c.youngs_modulus), holder_compliance=float(c.holder_compliance),
                                runout_rho=float(c.runout_rho), runout_lambda=float(c.runout_lambda))
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
                             inertia=model_out["inertia"], load=model_out["load"],
                             holder_compliance=tool_out["holder_compliance"])
        except ValueError as exc:
            raise _fail(we, str(exc)) from None
        cols, z = _wall_csv(e, we, path, z_default=0.5 * ap, axial_depth=ap)
        out.append(
            WallExperiment(file=str(path), feed_per_tooth=c, axial_depth=ap, radial_depth=ae, mode=mode,
                           side=side, x=cols["x_mm"], z=z, errors=cols["error_mm"][:, None], spindle_rpm=rpm)
        )
    return Bundle(kind="wall_error", path=str(root), model=model_out, experiments=out, tool=tool_out, noise=noise)
