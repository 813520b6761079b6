"""netshape.force — mechanistic cutting-force models, engagement and calibration (docs/force.md).

Frame and signs (docs/conventions.md §2–3): X along the feed, Z along the tool axis from the tip into
the spindle, Y = Z × X; the cutter turns clockwise seen from the spindle; the immersion φ of a flute is
measured clockwise from +Y; forces are those acting ON THE CUTTER [N]. Angles in the API are radians.

C++ core (``netshape._core.force``): :class:`FlatEndModel` / :class:`FlatEndWorkspace`,
:class:`BallEndModel` / :class:`BallEndWorkspace`, coefficient types and named sets, engagement,
summaries and the least-squares calibrations. Python adds the DynoWare reader, calibration
workflows, force along a program and plots. See docs/force.md.
"""

from __future__ import annotations

from netshape._core.force import (  # noqa: F401
    AngularEngagement,
    BallEndCoefficients,
    BallEndCoefficientSet,
    BallEndFit,
    BallEndModel,
    BallEndWorkspace,
    EngagementMap,
    FlatCoefficientModel,
    FlatEndModel,
    FlatEndWorkspace,
    KlineDevorCoefficients,
    LinearEdgeCoefficients,
    LinearEdgeCoefficientSet,
    LinearEdgeFit,
    MillingMode,
    ProgramForceOptions,
    TimeSeriesFit,
    ball_end_coefficient_set,
    ball_end_coefficient_set_names,
    ball_end_forces,
    ball_end_mean_slot_force,
    fit_ball_end_mean_forces,
    fit_linear_edge_mean_forces,
    fit_linear_edge_time_series,
    flat_end_forces,
    flat_end_forces_extended,
    RunoutSizeEffect,
    flat_end_moments,
    linear_edge_basis,
    linear_edge_coefficient_set,
    linear_edge_coefficient_set_names,
    mean_force,
    mean_force_matrix,
    milling_mode_from_string,
    resultant,
    rotation_angles,
    summarize,
    summarize_revolutions,
)

from .calibration import (  # noqa: F401
    calibrate_mean_forces,
    fit_recording,
    recording_mean_force,
)
from .dynoware import (  # noqa: F401
    DYNAMOMETER_TO_CUTTER_LEEKUNHWEE,
    DynoWareRecording,
    read_dynoware,
)
from .program import ProgramForceResult, simulate_program  # noqa: F401
from .simulate import cutter_forces, parse_coefficients  # noqa: F401

__all__ = [
    "AngularEngagement",
    "BallEndCoefficients",
    "BallEndCoefficientSet",
    "BallEndFit",
    "BallEndModel",
    "BallEndWorkspace",
    "DYNAMOMETER_TO_CUTTER_LEEKUNHWEE",
    "DynoWareRecording",
    "EngagementMap",
    "FlatCoefficientModel",
    "FlatEndModel",
    "FlatEndWorkspace",
    "KlineDevorCoefficients",
    "LinearEdgeCoefficients",
    "LinearEdgeCoefficientSet",
    "LinearEdgeFit",
    "MillingMode",
    "ProgramForceOptions",
    "TimeSeriesFit",
    "ball_end_coefficient_set",
    "ball_end_coefficient_set_names",
    "ball_end_forces",
    "ball_end_mean_slot_force",
    "calibrate_mean_forces",
    "cutter_forces",
    "fit_ball_end_mean_forces",
    "fit_linear_edge_mean_forces",
    "fit_linear_edge_time_series",
    "fit_recording",
    "flat_end_forces",
    "flat_end_forces_extended",
    "RunoutSizeEffect",
    "flat_end_moments",
    "linear_edge_basis",
    "linear_edge_coefficient_set",
    "linear_edge_coefficient_set_names",
    "mean_force",
    "mean_force_matrix",
    "milling_mode_from_string",
    "parse_coefficients",
    "ProgramForceResult",
    "simulate_program",
    "read_dynoware",
    "recording_mean_force",
    "resultant",
    "rotation_angles",
    "summarize",
    "summarize_revolutions",
]
