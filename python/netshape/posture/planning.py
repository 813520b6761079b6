"""Posture planning workflow: tool and machine TOML, CC paths from a NURBS surface, the planner run, its CSV /
JSON / G-code outputs. The computation is in C++ (``netshape._core.posture``); this module parses and writes."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._atomic import atomic_path, atomic_write
from .._config import load_toml, number
from .._core import posture as _p


#: Columns of postures_*.csv: path length of the CC points, tool tip (lowest point of the ball along the axis),
#: unit axis from the tip towards the spindle.
CSV_COLUMNS = ("s_mm", "tip_x_mm", "tip_y_mm", "tip_z_mm", "axis_i", "axis_j", "axis_k")

#: Cutter TOML keys of the assembly beyond the cutter's own (lengths measured from the tip); with
#: ``holder_profile_mm`` (a list of [z, r] pairs) the holder keys are not needed.
ASSEMBLY_KEYS = ("shank_diameter_mm", "shank_length_mm", "holder_diameter_mm", "holder_length_mm")


def assembly_from_dict(d: dict, *, source: str = "tool") -> _p.CutterAssembly:
    """A validated :class:`CutterAssembly` from cutter TOML keys (``kind = "ball"``, ``diameter_mm``, …) plus
    ``shank_diameter_mm``, ``shank_length_mm``, ``holder_diameter_mm``, ``holder_length_mm`` (from the tip): a
    flat-faced cylinder holder; or ``holder_profile_mm = [[z, r], …]`` (from the tip, z non-decreasing, starting
    at ``shank_length_mm``): frustums between consecutive pairs (a shrink-fit taper, a neck)."""
    from ..cutter import cutter_from_dict

    cutter = cutter_from_dict(d, source=source)
    if d.get("kind") != "ball":
        raise ValueError(f"{source}: kind = {d.get('kind')!r}: posture planning needs a ball end mill (\"ball\")")
    profile = d.get("holder_profile_mm")
    for key in ASSEMBLY_KEYS[:2] if profile is not None else ASSEMBLY_KEYS:
        if key not in d:
            raise ValueError(f"{source}: {key}: missing (posture planning needs {', '.join(ASSEMBLY_KEYS)}"
                             " or holder_profile_mm)")
    a = _p.CutterAssembly()
    a.ball_radius = cutter.radius
    a.shank_radius = 0.5 * number(source, "shank_diameter_mm", d["shank_diameter_mm"])
    a.shank_length = number(source, "shank_length_mm", d["shank_length_mm"])
    if profile is not None:
        if not isinstance(profile, list) or not all(isinstance(p, list) and len(p) == 2 for p in profile):
            raise ValueError(f"{source}: holder_profile_mm = {profile!r}: must be a list of [z, r] pairs [mm]")
        a.holder_profile = np.array([[number(source, "holder_profile_mm", v) for v in p] for p in profile])
        a.holder_radius = float(a.holder_profile[:, 1].max())
        a.holder_length = float(a.holder_profile[-1, 0])
    else:
        a.holder_radius = 0.5 * number(source, "holder_diameter_mm", d["holder_diameter_mm"])
        a.holder_length = number(source, "holder_length_mm", d["holder_length_mm"])
    try:
        a.validate()
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return a


def load_tool(path: str | os.PathLike) -> _p.CutterAssembly:
    """Cutter assembly from a cutter TOML file with the assembly keys (see :func:`assembly_from_dict`)."""
    return assembly_from_dict(load_toml(path), source=os.fspath(path))


def default_assembly() -> _p.CutterAssembly:
    """The ball-end assembly sized for the default impeller: Ø6 ball and shank to 35 mm, Ø20 holder to 80 mm."""
    return _p.CutterAssembly(3.0, 3.0, 35.0, 10.0, 80.0)


def kinematics_from_dict(d: dict, *, source: str = "machine") -> _p.Kinematics:
    """Machine kinematics from TOML keys: ``kind`` ("table_ac" or "head_bc"), ``table_centre_mm`` [x, y, z]
    (table_ac), ``pivot_length_mm`` (head_bc), ``tilt_min_deg``, ``tilt_max_deg`` (limits of A or B)."""
    known = ("kind", "table_centre_mm", "pivot_length_mm", "tilt_min_deg", "tilt_max_deg")
    if not isinstance(d, dict):
        raise ValueError(f"{source}: must be a table of keys")
    for key in d:
        if key not in known:
            raise ValueError(f"{source}: {key} = {d[key]!r}: unknown key (known: {', '.join(known)})")
    k = _p.Kinematics()
    kinds = {"table_ac": _p.MachineKind.table_ac, "head_bc": _p.MachineKind.head_bc}
    if d.get("kind") not in kinds:
        raise ValueError(f"{source}: kind = {d.get('kind')!r}: must be \"table_ac\" or \"head_bc\"")
    k.kind = kinds[d["kind"]]
    if "table_centre_mm" in d:
        c = d["table_centre_mm"]
        if not isinstance(c, list) or len(c) != 3:
            raise ValueError(f"{source}: table_centre_mm = {c!r}: must be [x, y, z] [mm]")
        k.table_centre = np.array([number(source, "table_centre_mm", v) for v in c])
    if "pivot_length_mm" in d:
        k.pivot_length = number(source, "pivot_length_mm", d["pivot_length_mm"])
    if "tilt_min_deg" in d:
        k.tilt_min = math.radians(number(source, "tilt_min_deg", d["tilt_min_deg"]))
    if "tilt_max_deg" in d:
        k.tilt_max = math.radians(number(source, "tilt_max_deg", d["tilt_max_deg"]))
    try:
        k.validate()
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return k


def load_kinematics(path: str | os.PathLike) -> _p.Kinematics:
    """Machine kinematics from a TOML file (see :func:`kinematics_from_dict`)."""
    return kinematics_from_dict(load_toml(path), source=os.fspath(path))


def machine_gcode(kinematics: _p.Kinematics, program: _p.MovePlan, *, feed_mm_per_min: float = 1000.0,
                  title: str = "netshape posture plan") -> str:
    """RS274 program of a :func:`plan_program` result: G0 to its first point (the approach point up the tool
    axis), then G1 X Y Z with A C (table_ac) or B C (head_bc) words [deg] through the CL points (rotary moves
    already subdivided to the chord tolerance) to the retract point."""
    if not (math.isfinite(feed_mm_per_min) and feed_mm_per_min > 0):
        raise ValueError(f"feed_mm_per_min = {feed_mm_per_min!r}: must be positive")
    joints = np.asarray(program.joints)
    tilt = "A" if kinematics.kind == _p.MachineKind.table_ac else "B"
    lines = [f"({title}: {kinematics.kind.name}, {len(joints)} points)", "G21 G90 G94"]
    for i, (x, y, z, t, c) in enumerate(joints):
        word = "G0" if i == 0 else "G1"
        feed = f" F{feed_mm_per_min:.1f}" if i == 1 else ""
        lines.append(f"{word} X{x:.4f} Y{y:.4f} Z{z:.4f} {tilt}{math.degrees(t):.4f} C{math.degrees(c):.4f}{feed}")
    lines.append("M30")
    return "\n".join(lines) + "\n"


def surface_cc_path(surface, points: int) -> tuple[np.ndarray, np.ndarray]:
    """CC points (n, 3) and unit normals (n, 3) along the surface's iso-curve at the middle of its v domain,
    u from the start to the end of its domain. The normals must point towards the tool (out of the material)."""
    if isinstance(points, bool) or not isinstance(points, int) or points < 4:
        raise ValueError(f"points = {points!r}: must be an integer ≥ 4")
    u0, u1 = surface.domain_u
    v0, v1 = surface.domain_v
    uv = np.column_stack([np.linspace(u0, u1, points), np.full(points, 0.5 * (v0 + v1))])
    from ..errors import Error

    try:
        pts, nrm = surface.evaluate_with_normals(uv)
    except Error as exc:
        raise ValueError(f"surface: degenerate, no normal along the CC path: {exc}") from None
    pts, nrm = np.asarray(pts), np.asarray(nrm)
    bad = np.flatnonzero(~np.isfinite(nrm).all(axis=1) | (np.linalg.norm(nrm, axis=1) < 0.5))
    if len(bad):
        raise ValueError(f"surface: degenerate at CC point {bad[0]} {pts[bad[0]].tolist()}: no unit normal")
    return pts, nrm


def _stage_table(result, stage) -> np.ndarray:
    return np.column_stack([result.s, stage.tips, stage.axes])


@dataclass
class PostureRun:
    """A planner run with everything the CLI writes."""

    result: _p.PlanResult
    assembly: _p.CutterAssembly
    clearance: float
    obstacle_vertices: np.ndarray
    obstacle_faces: np.ndarray
    kinematics: _p.Kinematics
    program: _p.MovePlan
    extra: dict = field(default_factory=dict)
    feed_mm_per_min: float = 1000.0  # feed of the rotary-axis figures and of program.ngc [mm/min]

    def table(self, stage: str) -> np.ndarray:
        """(n, 7) rows of :data:`CSV_COLUMNS` for stage "raw", "mc", "smoothed" or "final"."""
        if stage not in ("raw", "mc", "smoothed", "final"):
            raise ValueError(f"stage = {stage!r}: must be raw, mc, smoothed or final")
        return _stage_table(self.result, getattr(self.result, stage))

    def max_change_deg_per_mm(self, stage: str) -> float:
        """Largest angle between neighbouring axes per mm of path [deg/mm]."""
        return math.degrees(_p.max_posture_change(self.result.s, getattr(self.result, stage).axes))

    def rotary_rates(self) -> dict:
        """Peak and RMS angular velocity [deg/s] and acceleration [deg/s²] of the rotary axes at
        :attr:`feed_mm_per_min` (see :mod:`netshape.posture.rates`): for "raw", "mc" and "final" from the
        machine joints of the CL points (inverse kinematics on this run's machine), and for "program" from the
        joints of the program (the final postures with the inserted points, between approach and retract)."""
        from .rates import joint_rates

        tilt = "A" if self.kinematics.kind == _p.MachineKind.table_ac else "B"
        radius = self.assembly.ball_radius
        out: dict = {"feed_mm_per_min": self.feed_mm_per_min, "machine": self.kinematics.kind.name}
        for stage in ("raw", "mc", "final"):
            st = getattr(self.result, stage)
            tips, axes = np.asarray(st.tips), np.asarray(st.axes)
            joints = _p.inverse_kinematics(self.kinematics, tips, axes)
            out[stage] = joint_rates(joints, tips + radius * axes, self.feed_mm_per_min, tilt)
        src = np.asarray(self.program.source)
        cl = (src >= 0) & (src <= len(self.result.s) - 1)  # not the approach / retract points
        tips, axes = np.asarray(self.program.tips)[cl], np.asarray(self.program.axes)[cl]
        out["program"] = joint_rates(np.asarray(self.program.joints)[cl], tips + radius * axes,
                                     self.feed_mm_per_min, tilt)
        return out

    def summary(self) -> dict:
        """The summary.json contents."""
        a, r = self.assembly, self.result
        left = r.final.collision_count() + int(np.sum(self.program.move_collides))
        return {
            # "ok" only when every final posture and every move of the written program keeps the clearance
            "status": "ok" if left == 0 else "collisions_left",
            "cutter": {
                "ball_radius_mm": a.ball_radius,
                "shank_radius_mm": a.shank_radius,
                "shank_length_mm": a.shank_length,
                "holder_radius_mm": a.holder_radius,
                "holder_length_mm": a.holder_length,
                **({"holder_profile_mm": np.asarray(a.holder_profile).tolist()} if len(a.holder_profile) else {}),
            },
            "clearance_mm": self.clearance,
            "points": int(len(r.s)),
            "collisions": {"raw": r.raw.collision_count(), "mc": r.mc.collision_count(),
                           "final": r.final.collision_count()},
            "repaired": r.repaired_count(),
            "max_posture_change_deg_per_mm": {k: self.max_change_deg_per_mm(k) for k in ("raw", "mc", "final")},
            "moves": {
                "machine": self.kinematics.kind.name,
                "colliding_before_repair": self.program.colliding_before,
                "inserted": self.program.inserted,
                "program_points": int(len(self.program.tips)),
                "colliding": int(np.sum(self.program.move_collides)),
            },
            "rotary": self.rotary_rates(),
        }

    def write(self, out_dir: str | os.PathLike, *, plot: bool = False, plot_point: int | None = None,
              kinematics: _p.Kinematics | None = None, feed_mm_per_min: float = 1000.0) -> list[Path]:
        """Write obstacles.stl, postures_raw.csv, postures_mc.csv, postures_final.csv, summary.json (and
        program.ngc with kinematics, cspace.png and angles.png with plot) into out_dir, each atomically."""
        from netshape._json import check_finite, write_json

        from ..geometry import write_stl

        check_finite(self.summary(), cause="posture plan")  # before any file: nothing half-written
        for stage in ("raw", "mc", "final"):
            table = np.asarray(self.table(stage), dtype=float)
            if not np.isfinite(table).all():
                check_finite({f"postures_{stage}": table.tolist()}, cause="posture plan")
        out = Path(out_dir)
        if not out.is_dir():
            raise ValueError(f"--out = {str(out)!r}: not a folder")
        written = []
        stl = out / "obstacles.stl"
        with atomic_path(stl) as tmp:
            write_stl(tmp, self.obstacle_vertices, self.obstacle_faces, name="netshape posture obstacles")
        written.append(stl)
        header = ",".join(CSV_COLUMNS)
        for stage in ("raw", "mc", "final"):
            path = out / f"postures_{stage}.csv"
            rows = self.table(stage)
            with atomic_write(path) as fh:
                fh.write(header + "\n")
                for row in rows:
                    fh.write(",".join(f"{v:.9g}" for v in row) + "\n")
            written.append(path)
        path = out / "summary.json"
        write_json(path, self.summary())
        written.append(path)
        if kinematics is not None:
            path = out / "program.ngc"
            text = machine_gcode(kinematics, self.program, feed_mm_per_min=feed_mm_per_min)
            with atomic_write(path) as fh:
                fh.write(text)
            written.append(path)
        if plot:
            from .._atomic import atomic_save_figure
            from .plots import plot_angles, plot_cspace

            i = self.default_plot_point() if plot_point is None else plot_point
            if not 0 <= i < len(self.result.s):
                raise ValueError(f"--plot-point = {i}: must be in [0, {len(self.result.s) - 1}]")
            fig = plot_cspace(self.result, i)
            atomic_save_figure(fig, out / "cspace.png", dpi=110)
            fig2 = plot_angles(self.result)
            atomic_save_figure(fig2, out / "angles.png", dpi=110)
            written += [out / "cspace.png", out / "angles.png"]
        return written

    def default_plot_point(self) -> int:
        """The first CC point whose normal posture collides (else the middle one)."""
        hits = np.flatnonzero(self.result.raw.collides)
        return int(hits[0]) if len(hits) else len(self.result.s) // 2


def plan_postures(cc, normals, obstacle_vertices, obstacle_faces, assembly: _p.CutterAssembly, *,
                  clearance: float = 0.5, options: _p.PlanOptions | None = None,
                  kinematics: _p.Kinematics | None = None, approach_mm: float = 10.0,
                  chord_mm: float = 0.01, feed_mm_per_min: float = 1000.0) -> PostureRun:
    """Run the planner: C-space per CC point, MC-space, MB-spline smoothing, repair; then the CL program on the
    machine (default: table_ac at the origin): the moves between the final postures checked and repaired,
    rotary moves subdivided to `chord_mm`, approach and retract `approach_mm` along the tool axis, every move
    checked (see docs/posture.md); the rotary-axis figures of the summary at `feed_mm_per_min`."""
    from ..geometry import TriangleMesh

    if not (isinstance(clearance, (int, float)) and math.isfinite(clearance) and clearance >= 0):
        raise ValueError(f"clearance = {clearance!r}: must be a finite number ≥ 0 [mm]")
    v = np.ascontiguousarray(obstacle_vertices, float).reshape(-1, 3)
    f = np.ascontiguousarray(obstacle_faces, np.int64).reshape(-1, 3)
    if len(f) == 0:
        raise ValueError("obstacles: the mesh is empty (no triangles)")
    if isinstance(feed_mm_per_min, bool) or not isinstance(feed_mm_per_min, (int, float)) \
            or not math.isfinite(feed_mm_per_min) or feed_mm_per_min <= 0:
        raise ValueError(f"feed_mm_per_min = {feed_mm_per_min!r}: must be a positive number [mm/min]")
    mesh = TriangleMesh(v, f)
    checker = _p.InterferenceChecker(mesh, assembly, float(clearance))
    for key, value, ok in (("approach_mm", approach_mm, lambda x: x >= 0), ("chord_mm", chord_mm, lambda x: x > 0)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or not ok(value):
            raise ValueError(f"{key} = {value!r}: must be a finite number {'≥ 0' if key == 'approach_mm' else '> 0'} [mm]")
    options = options or _p.PlanOptions()
    result = _p.plan(checker, np.ascontiguousarray(cc, float), np.ascontiguousarray(normals, float), options)
    kinematics = kinematics or _p.Kinematics()
    program = _p.plan_program(checker, kinematics, result, options, float(approach_mm), float(chord_mm))
    return PostureRun(result=result, assembly=assembly, clearance=float(clearance), obstacle_vertices=v,
                      obstacle_faces=f, kinematics=kinematics, program=program,
                      feed_mm_per_min=float(feed_mm_per_min))
