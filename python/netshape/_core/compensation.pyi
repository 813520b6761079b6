"""Type stub of netshape._core.compensation — volumetric part (C++ netshape::compensation,
volumetric_compensation.hpp). Units: mm."""

from __future__ import annotations

import enum

import numpy as np
import numpy.typing as npt

from .machine import Machine

# --- volumetric compensation -------------------------------------------------------------------
class VolumetricOptions:
    tolerance: float  # [mm]
    max_iterations: int
    check_travel: bool
    def __init__(self, tolerance: float = 1e-9, max_iterations: int = 50, check_travel: bool = True) -> None: ...
    def validate(self) -> None: ...

class VolumetricStatus(enum.Enum):
    ok = 0
    not_converged = 1
    outside_travel = 2
    outside_table = 3

class VolumetricResult:
    commanded: npt.NDArray[np.float64]  # (n, 3) [mm]
    residual: npt.NDArray[np.float64]  # (n,) [mm]
    iterations: npt.NDArray[np.int32]  # (n,)
    status: npt.NDArray[np.int32]  # (n,) VolumetricStatus values
    axis: npt.NDArray[np.int32]  # (n,) offending axis or -1
    def all_ok(self) -> bool: ...
    def first_failure(self) -> int: ...

def compensate_points(machine: Machine, nominal: npt.ArrayLike, options: VolumetricOptions = ...) -> npt.NDArray[np.float64]: ...
def compensate_points_status(machine: Machine, nominal: npt.ArrayLike, options: VolumetricOptions = ...) -> VolumetricResult: ...
