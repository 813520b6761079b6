"""netshape.posture — 5-axis tool posture: C-space, MC-space, MB-spline smoothing, collision repair and
machine rotary angles (C++ namespace ``netshape::posture``; docs/posture.md).

Units: mm and rad in the API; deg only in file keys that say so. Arrays are float64 C-ordered, points (n, 3).
"""

from __future__ import annotations

from .._core import posture as _p
from .impeller import Impeller, ImpellerParams, impeller_params_from_dict, load_impeller, make_impeller
from .planning import (
    CSV_COLUMNS,
    PostureRun,
    assembly_from_dict,
    default_assembly,
    kinematics_from_dict,
    load_kinematics,
    load_tool,
    machine_gcode,
    plan_postures,
    surface_cc_path,
)

CutterAssembly = _p.CutterAssembly
InterferenceChecker = _p.InterferenceChecker
CSpaceOptions = _p.CSpaceOptions
CSpace = _p.CSpace
PostureFrame = _p.PostureFrame
PlanOptions = _p.PlanOptions
PlanResult = _p.PlanResult
PostureSet = _p.PostureSet
Kinematics = _p.Kinematics
MachineKind = _p.MachineKind
classify = _p.classify
compute_cspace = _p.compute_cspace
plan = _p.plan
max_posture_change = _p.max_posture_change
mb_spline_point = _p.mb_spline_point
mb_spline_derivative = _p.mb_spline_derivative
mb_spline_joins = _p.mb_spline_joins
mb_smooth = _p.mb_smooth
inverse_kinematics = _p.inverse_kinematics
MoveCheck = _p.MoveCheck
MovePlan = _p.MovePlan
move_speed_bound = _p.move_speed_bound
check_move = _p.check_move
check_moves = _p.check_moves
plan_program = _p.plan_program
subdivide_rotary = _p.subdivide_rotary
forward_kinematics = _p.forward_kinematics

__all__ = [
    "CSV_COLUMNS",
    "CSpace",
    "CSpaceOptions",
    "CutterAssembly",
    "Impeller",
    "ImpellerParams",
    "InterferenceChecker",
    "Kinematics",
    "MachineKind",
    "MoveCheck",
    "MovePlan",
    "PlanOptions",
    "PlanResult",
    "PostureFrame",
    "PostureRun",
    "PostureSet",
    "assembly_from_dict",
    "check_move",
    "check_moves",
    "classify",
    "compute_cspace",
    "default_assembly",
    "forward_kinematics",
    "impeller_params_from_dict",
    "inverse_kinematics",
    "kinematics_from_dict",
    "load_impeller",
    "load_kinematics",
    "load_tool",
    "machine_gcode",
    "make_impeller",
    "max_posture_change",
    "mb_smooth",
    "mb_spline_derivative",
    "mb_spline_joins",
    "mb_spline_point",
    "move_speed_bound",
    "plan",
    "plan_postures",
    "plan_program",
    "subdivide_rotary",
    "surface_cc_path",
]
