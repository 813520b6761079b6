"""The job file (TOML): what to read, what to predict, what to compensate, where to write.

Every key and its unit is documented in docs/job.md. :func:`load_job` reads a file and returns a
validated :class:`Job`; any unknown key or bad value raises one ValueError whose message starts
with the file and names the key (``job.toml: stock.spacing_mm = -1: must be positive [mm]``).
Relative input paths inside the job are resolved against the job file's folder; the output folder
against the current directory.
"""

from __future__ import annotations

import copy
import os
import re
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Any

from netshape import _config as cfg
from netshape._budget import MAX_STL_TRIANGLES
from netshape.motion import PLAN_RULES
from netshape.stock.config import PreCut, stock_from_dict  # noqa: F401  (PreCut: part of the Job API)

#: Work offsets a program may select; the job gives each as ``G54_mm = [x, y, z]``.
WORK_OFFSETS = ("G54", "G55", "G56", "G57", "G58", "G59")
PREDICTIONS = ("forces", "deflection", "volumetric", "feed_plan")
#: Compensations in the order they are applied (deflection first, then volumetric).
COMPENSATIONS = ("deflection", "volumetric")

_TOP = {"name", "program", "output", "tool", "stock", "offsets", "coefficients", "machine", "limits",
        "cutting", "predict", "compensate", "report", "grid", "start_mm", "clearance_mm", "optimize"}
_TOOL_KEYS = {"file", "kind", "diameter_mm", "corner_radius_mm", "flutes", "helix_deg", "flute_length_mm",
              "stick_out_mm", "youngs_modulus_MPa", "holder_compliance_um_per_N", "runout_rho_mm",
              "runout_lambda_deg", "max_power_W", "max_torque_Nm"}
_MACHINE_KEYS = {"file", "error_scale"}
_LIMIT_KEYS = {"vmax_mm_s", "amax_mm_s2", "jmax_mm_s3", "rule", "tolerance_mm", "ts1_s", "ts2_s", "lookahead"}
_CUTTING_KEYS = {"spindle_rpm", "feed_per_tooth_mm", "feed_scale", "step_mm", "samples_per_revolution",
                 "disk_height_mm", "error_spacing_mm"}
_COMP_KEYS = {"deflection", "volumetric", "chord_tolerance_mm", "deflection_scheme", "deflection_level",
              "deflection_unconverged"}
_REPORT_KEYS = {"dpi", "zmap_stl", "plots"}
_COEFF_KEYS = ("Ktc", "Krc", "Kac", "Kte", "Kre", "Kae")


class JobError(ValueError):
    """A bad job file: the message names the file and the key."""


@dataclass
class Job:
    """A validated job. Paths are absolute; tool dicts hold cutter TOML keys (netshape.cutter)."""

    source: Path
    name: str
    program: Path
    output: Path
    tool: dict
    stock: dict                      # min_mm, max_mm, spacing_mm, heights (Path | None), pre_cut
    offsets: dict                    # "G54".. -> (3,) mm; tool_length_mm -> float | None
    coefficients: Any                # str (named set or "Ktc=…") or dict of values, or None
    machine: Path | None
    error_scale: float
    limits: dict | None
    cutting: dict
    predict: dict
    compensate: dict
    report: dict
    grid: dict = field(default_factory=dict)
    raw: dict = field(default_factory=dict)  # the parsed TOML (for batch grids)
    start_mm: list | None = None     # tool tip before the first move, G54 frame (None: above the stock)
    clearance_mm: float = 5.0        # the default start's height above the stock top
    optimize: dict | None = None     # [optimize]: feed scheduling limits (netshape.job.optimize)

    @property
    def compensations(self) -> list[str]:
        """The chosen compensations in the order they are applied."""
        return [c for c in COMPENSATIONS if self.compensate.get(c)]


# the shared field readers (netshape._config), raising JobError
_err = partial(cfg.field_error, error=JobError)
_MISSING = cfg.MISSING
_check_keys = partial(cfg.check_keys, error=JobError)
_number = partial(cfg.number, error=JobError)
_vec3 = partial(cfg.vec3, error=JobError)
_bool = partial(cfg.boolean, error=JobError)
_path = partial(cfg.file_path, error=JobError)
_read_toml = cfg.load_toml


def _tool(src: str, base: Path, where: str, v: Any) -> dict:
    """Cutter keys from a path string, or a table with ``file`` and/or cutter keys (keys override)."""
    from netshape.cutter import tool_table

    return tool_table(src, base, where, v, known=_TOOL_KEYS, error=JobError)


def _stock(src: str, base: Path, v: Any) -> dict:
    """``[stock]``: netshape.stock.config's one stock format, pre-cut tools read as ``[tool]`` is."""
    return stock_from_dict(v, source=src, base=base, prefix="stock.", error=JobError, read_tool=_tool)


def _coefficients(src: str, v: Any):
    if v is None:
        return None
    if isinstance(v, str):
        from netshape.force import (ball_end_coefficient_set_names, linear_edge_coefficient_set_names,
                                    parse_coefficients)

        if "=" in v:
            try:
                parse_coefficients(v)
            except ValueError as exc:
                raise _err(src, "coefficients", v, str(exc)) from None
            return v
        names = list(linear_edge_coefficient_set_names()) + list(ball_end_coefficient_set_names())
        if v not in names:
            raise _err(src, "coefficients", v, f"unknown coefficient set (known: {', '.join(names)}; "
                       "or give Ktc=…,Krc=…,Kac=…,Kte=…,Kre=…,Kae=…)")
        return v
    if isinstance(v, dict):
        known = ({f"{k}_N_mm2" for k in _COEFF_KEYS[:3]} | {f"{k}_N_mm" for k in _COEFF_KEYS[3:]}
                 | {"chip_exponent", "reference_chip_mm"})
        _check_keys(src, "coefficients", v, known)
        if not v:
            raise _err(src, "coefficients", v, "empty table")
        out = {k: _number(src, f"coefficients.{k}", x) for k, x in v.items()}
        if "chip_exponent" in out and not 0.0 < out["chip_exponent"] <= 2.0:
            raise _err(src, "coefficients.chip_exponent", out["chip_exponent"], "must be in (0, 2]")
        if "reference_chip_mm" in out and not out["reference_chip_mm"] > 0.0:
            raise _err(src, "coefficients.reference_chip_mm", out["reference_chip_mm"], "must be > 0 [mm]")
        return out
    raise _err(src, "coefficients", v, "must be a named set, a string Ktc=…,… or a table of values")


def _limits(src: str, v: Any) -> dict:
    t = _check_keys(src, "limits", v, _LIMIT_KEYS)
    out: dict = {"rule": "blend", "tolerance_mm": 0.01, "ts1_s": 2e-3, "ts2_s": 1e-3, "lookahead": 64}
    for key in ("vmax_mm_s", "amax_mm_s2"):
        if key not in t:
            raise _err(src, f"limits.{key}", _MISSING, "missing (a number, or [x, y, z])")
    for key in ("vmax_mm_s", "amax_mm_s2", "jmax_mm_s3"):
        if key not in t:
            continue
        x = t[key]
        vals = x if isinstance(x, list) else [x] * 3
        if len(vals) != 3:
            raise _err(src, f"limits.{key}", x, "must be a number or a list of 3 numbers")
        out[key] = [_number(src, f"limits.{key}", y, positive=True) for y in vals]
    if "rule" in t:
        out["rule"] = cfg.one_of(src, "limits.rule", t["rule"], PLAN_RULES, error=JobError)
    for key in ("tolerance_mm", "ts1_s", "ts2_s"):
        if key in t:
            out[key] = _number(src, f"limits.{key}", t[key], positive=True)
    if out["ts2_s"] > out["ts1_s"]:
        raise _err(src, "limits.ts2_s", out["ts2_s"], f"must not exceed limits.ts1_s = {out['ts1_s']} [s]")
    if "lookahead" in t:
        la = t["lookahead"]
        if isinstance(la, bool) or not isinstance(la, int) or not 1 <= la <= 100000:
            raise _err(src, "limits.lookahead", la, "must be an integer in 1..100000")
        out["lookahead"] = la
    return out


def _cutting(src: str, v: Any) -> dict:
    t = _check_keys(src, "cutting", v, _CUTTING_KEYS)
    out = {"spindle_rpm": None, "feed_per_tooth_mm": None, "feed_scale": 1.0, "step_mm": 0.5,
           "samples_per_revolution": 36, "disk_height_mm": 0.25, "error_spacing_mm": 0.5}
    for key in ("spindle_rpm", "feed_per_tooth_mm", "feed_scale", "step_mm", "disk_height_mm", "error_spacing_mm"):
        if key in t:
            out[key] = _number(src, f"cutting.{key}", t[key], positive=True)
    if "samples_per_revolution" in t:
        n = t["samples_per_revolution"]
        if isinstance(n, bool) or not isinstance(n, int) or not 8 <= n <= 3600:
            raise _err(src, "cutting.samples_per_revolution", n, "must be an integer in 8..3600")
        out["samples_per_revolution"] = n
    return out


def _predict(src: str, v: Any) -> dict:
    if isinstance(v, list):
        for x in v:
            if x not in PREDICTIONS:
                raise _err(src, "predict", x, f"unknown prediction (known: {', '.join(PREDICTIONS)})")
        return {p: p in v for p in PREDICTIONS}
    t = _check_keys(src, "predict", v, set(PREDICTIONS))
    return {p: _bool(src, f"predict.{p}", t.get(p, False)) for p in PREDICTIONS}


def _compensate(src: str, v: Any) -> dict:
    if isinstance(v, list):
        for x in v:
            if x not in COMPENSATIONS:
                raise _err(src, "compensate", x, f"unknown compensation (known: {', '.join(COMPENSATIONS)})")
        v = {c: c in v for c in COMPENSATIONS}
    t = _check_keys(src, "compensate", v, _COMP_KEYS)
    out = {c: _bool(src, f"compensate.{c}", t.get(c, False)) for c in COMPENSATIONS}
    out["chord_tolerance_mm"] = _number(src, "compensate.chord_tolerance_mm", t.get("chord_tolerance_mm", 0.002),
                                        positive=True)
    scheme = t.get("deflection_scheme", "integrated")
    if scheme not in ("one-d", "integrated", "sectional", "accelerated"):
        raise _err(src, "compensate.deflection_scheme", scheme, "must be one-d, integrated, sectional or accelerated")
    level = t.get("deflection_level", "middle")
    if level not in ("bottom", "middle", "top"):
        raise _err(src, "compensate.deflection_level", level, "must be bottom, middle or top")
    out["deflection_scheme"], out["deflection_level"] = scheme, level
    unconverged = t.get("deflection_unconverged", "report")
    if unconverged not in ("report", "fail"):
        raise _err(src, "compensate.deflection_unconverged", unconverged, "must be report or fail")
    out["deflection_unconverged"] = unconverged
    return out


#: Largest work offset or tool length accepted [mm] (100 m: beyond any machine's travel).
MAX_OFFSET_MM = 1e5


def _offsets(src: str, v: Any) -> dict:
    known = {f"{g}_mm" for g in WORK_OFFSETS} | {"tool_length_mm"}
    t = _check_keys(src, "offsets", v, known)
    out: dict = {g: [0.0, 0.0, 0.0] for g in WORK_OFFSETS}
    for g in WORK_OFFSETS:
        if f"{g}_mm" in t:
            out[g] = _vec3(src, f"offsets.{g}_mm", t[f"{g}_mm"])
            for i, x in enumerate(out[g]):
                if abs(x) > MAX_OFFSET_MM:
                    raise _err(src, f"offsets.{g}_mm[{i}]", x, f"must be within ±{MAX_OFFSET_MM:g} [mm]")
    out["tool_length_mm"] = None
    if "tool_length_mm" in t:
        out["tool_length_mm"] = _number(src, "offsets.tool_length_mm", t["tool_length_mm"], nonneg=True)
        if out["tool_length_mm"] > MAX_OFFSET_MM:
            raise _err(src, "offsets.tool_length_mm", t["tool_length_mm"], f"must be at most {MAX_OFFSET_MM:g} [mm]")
    return out


def job_from_dict(doc: dict, *, source: str | os.PathLike = "<job>", base_dir: str | os.PathLike = ".",
                  check_grid: bool = True) -> Job:
    """A validated :class:`Job` from a parsed TOML document (see docs/job.md)."""
    src = os.fspath(source)
    base = Path(base_dir).resolve()
    _check_keys(src, "", doc, _TOP)
    if "program" not in doc:
        raise _err(src, "program", _MISSING, "missing (the G-code program to run)")
    program = _path(src, base, "program", doc["program"])
    if "tool" not in doc:
        raise _err(src, "tool", _MISSING, "missing (a cutter TOML path or table)")
    tool = _tool(src, base, "tool", doc["tool"])
    if "stock" not in doc:
        raise _err(src, "stock", _MISSING, "missing (the stock box, pre-cuts or heights file)")
    stock = _stock(src, base, doc["stock"])
    name = doc.get("name", Path(src).stem)
    if not isinstance(name, str):
        raise _err(src, "name", name, "must be a string")
    out = doc.get("output", "out")
    if not isinstance(out, str) or not out:
        raise _err(src, "output", out, "must be a folder path (string)")
    output = Path(out) if Path(out).is_absolute() else Path.cwd() / out  # outputs: where the user runs
    offsets = _offsets(src, doc.get("offsets", {}))
    coefficients = _coefficients(src, doc.get("coefficients"))
    machine, scale = None, 1.0
    if "machine" in doc:
        m = doc["machine"]
        if isinstance(m, str):
            m = {"file": m}
        _check_keys(src, "machine", m, _MACHINE_KEYS)
        if "file" not in m:
            raise _err(src, "machine.file", _MISSING, "missing (a machine TOML, docs/machine.md)")
        machine = _path(src, base, "machine.file", m["file"])
        from netshape.machine import load_machine

        try:
            load_machine(machine)
        except ValueError as exc:
            raise _err(src, "machine.file", m["file"], " ".join(str(exc).split())) from None
        scale = _number(src, "machine.error_scale", m.get("error_scale", 1.0), nonneg=True)
    limits = _limits(src, doc["limits"]) if "limits" in doc else None
    cutting = _cutting(src, doc.get("cutting", {}))
    predict = _predict(src, doc.get("predict", {"forces": True, "volumetric": True, "feed_plan": True,
                                                 "deflection": True}))
    compensate = _compensate(src, doc.get("compensate", {}))
    rep = _check_keys(src, "report", doc.get("report", {}), _REPORT_KEYS)
    report = {"dpi": 100, "zmap_stl": True, "plots": True}
    if "dpi" in rep:
        d = rep["dpi"]
        if isinstance(d, bool) or not isinstance(d, int) or not 30 <= d <= 600:
            raise _err(src, "report.dpi", d, "must be an integer in 30..600")
        report["dpi"] = d
    for key in ("zmap_stl", "plots"):
        if key in rep:
            report[key] = _bool(src, f"report.{key}", rep[key])
    triangles = 2.0 * stock.get("nodes", 0.0)  # two per Z-map cell (the sides and base add few)
    if report["zmap_stl"] and triangles > MAX_STL_TRIANGLES:
        raise _err(src, "report.zmap_stl", True, f"the Z-map STL would hold {triangles:.3g} triangles "
                   f"({stock['nodes']:.3g} nodes), over the limit of 1e7 (500 MB); set report.zmap_stl = false "
                   "or use a coarser stock")
    # what each prediction and compensation needs
    if (predict["forces"] or predict["deflection"]) and coefficients is None:
        which = "forces" if predict["forces"] else "deflection"
        raise _err(src, "coefficients", _MISSING, f"missing: predict.{which} needs cutting coefficients")
    if predict["volumetric"] and machine is None:
        raise _err(src, "machine", _MISSING, "missing: predict.volumetric needs a machine TOML")
    if predict["feed_plan"] and limits is None:
        raise _err(src, "limits", _MISSING, "missing: predict.feed_plan needs [limits] vmax_mm_s, amax_mm_s2")
    if compensate["volumetric"] and not predict["volumetric"]:
        raise _err(src, "compensate.volumetric", True, "needs predict.volumetric = true")
    if compensate["deflection"] and not predict["deflection"]:
        raise _err(src, "compensate.deflection", True, "needs predict.deflection = true")
    if predict["deflection"] and not predict["forces"]:
        raise _err(src, "predict.deflection", True, "needs predict.forces = true")
    start = _vec3(src, "start_mm", doc["start_mm"]) if "start_mm" in doc else None
    clearance = _number(src, "clearance_mm", doc.get("clearance_mm", 5.0), positive=True)
    if clearance > 1e5:
        raise _err(src, "clearance_mm", clearance, "must be at most 100000 [mm]")
    if start is not None and max(abs(x) for x in start) > 1e5:
        raise _err(src, "start_mm", start, "must lie within ±100000 mm")
    from .optimize import check_optimize_needs, optimize_from_dict

    optimize = optimize_from_dict(src, doc["optimize"]) if "optimize" in doc else None
    check_optimize_needs(src, optimize, limits, coefficients)
    grid = {}
    if "grid" in doc:
        grid = _check_grid(src, doc) if check_grid else doc["grid"]
    return Job(source=Path(src), name=name, program=program, output=output, tool=tool, stock=stock,
               offsets=offsets, coefficients=coefficients, machine=machine, error_scale=scale, limits=limits,
               cutting=cutting, predict=predict, compensate=compensate, report=report, grid=grid,
               raw=copy.deepcopy(doc), start_mm=start, clearance_mm=clearance, optimize=optimize)


def _check_grid(src: str, doc: dict) -> dict:
    grid = doc["grid"]
    if not isinstance(grid, dict) or not grid:
        raise _err(src, "grid", grid, "must be a table of dotted keys to lists of values")
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            raise _err(src, f"grid.{key}", values, "must be a non-empty list of values")
        if key.split(".")[0] == "grid":
            raise _err(src, f"grid.{key}", values, "a grid cannot vary itself")
    return grid


def set_dotted(doc: dict, key: str, value: Any) -> dict:
    """A copy of ``doc`` with the dotted ``key`` (``tool.stick_out_mm``) set to ``value``. A string tool,
    stock or machine entry is turned into a ``{file = …}`` table first, so its keys can be overridden."""
    out = copy.deepcopy(doc)
    parts = key.split(".")
    if not all(re.fullmatch(r"[A-Za-z0-9_]+", p) for p in parts):
        raise ValueError(f"grid key = {key!r}: must be dotted names like tool.stick_out_mm")
    node = out
    for p in parts[:-1]:
        cur = node.get(p)
        if isinstance(cur, str) and p in ("tool", "stock", "machine"):
            cur = {"file": cur}
        if cur is None:
            cur = {}
        if not isinstance(cur, dict):
            raise ValueError(f"grid key = {key!r}: {p} is not a table")
        node[p] = cur
        node = cur
    node[parts[-1]] = value
    return out


def load_job(path: str | os.PathLike, *, check_grid: bool = True) -> Job:
    """Read and validate a job file. Raises FileNotFoundError or JobError (a ValueError) naming the key."""
    p = Path(path)
    if not p.is_file():
        raise FileNotFoundError(2, "No such file or directory", os.fspath(path))
    doc = _read_toml(p, os.fspath(path))
    return job_from_dict(doc, source=os.fspath(path), base_dir=p.resolve().parent, check_grid=check_grid)
