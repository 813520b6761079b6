"""netshape.compensation — programs rewritten so the part comes out right (C++ netshape::compensation).

Volumetric compensation of machine geometric errors (Yang & Kweon): :mod:`.volumetric`.
"""

from __future__ import annotations

from .._core import compensation as _compensation
from .volumetric import (
    ProgramReport,
    compensate_gcode,
    compensate_points,
    compensate_points_status,
    compensate_program,
    estimate_chords,
)

ProgramOptions = _compensation.ProgramOptions
VolumetricOptions = _compensation.VolumetricOptions
VolumetricResult = _compensation.VolumetricResult
VolumetricStatus = _compensation.VolumetricStatus

__all__ = [
    "ProgramOptions", "ProgramReport", "VolumetricOptions", "VolumetricResult", "VolumetricStatus",
    "compensate_gcode", "compensate_points", "compensate_points_status", "compensate_program",
    "estimate_chords",
]
