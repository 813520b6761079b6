"""Type stub of netshape._core.machine (C++ netshape::machine). Units: mm, rad."""

from __future__ import annotations

import enum
from typing import Sequence

import numpy as np
import numpy.typing as npt

class OutOfRange(enum.Enum):
    error = 0
    clamp = 1
    extrapolate = 2

class ErrorFunction:
    class Kind(enum.Enum):
        zero = 0
        polynomial = 1
        table = 2
    kind: ErrorFunction.Kind
    coefficients: list[float]  # ascending powers of q [mm]
    positions: list[float]  # table positions [mm], strictly increasing
    values: list[float]  # [mm] or [rad]
    out_of_range: OutOfRange
    name: str
    def __init__(self) -> None: ...
    @staticmethod
    def zero_function(name: str = "") -> ErrorFunction: ...
    @staticmethod
    def polynomial(coefficients: Sequence[float], name: str = "") -> ErrorFunction: ...
    @staticmethod
    def table(positions: Sequence[float], values: Sequence[float], out_of_range: OutOfRange = ...,
              name: str = "") -> ErrorFunction: ...
    def validate(self) -> None: ...
    def is_zero(self) -> bool: ...
    def __call__(self, q: float) -> float: ...
    def evaluate(self, q: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """e(q) at (n,) positions [mm] → (n,)"""

class Component(enum.Enum):
    ex = 0
    ey = 1
    ez = 2
    ea = 3
    eb = 4
    ec = 5

class Side(enum.Enum):
    tool = 0
    workpiece = 1

class Order(enum.Enum):
    exact = 0
    first = 1

def component_name(component: Component, axis: int) -> str: ...

class Axis:
    travel_min: float  # [mm]
    travel_max: float  # [mm]
    origin: npt.NDArray[np.float64]  # (3,) [mm]
    errors: list[ErrorFunction]  # 6: EXk, EYk, EZk [mm], EAk, EBk, ECk [rad]
    def __init__(self) -> None: ...
    def error(self, component: Component) -> ErrorFunction: ...
    def set_error(self, component: Component, function: ErrorFunction) -> None: ...

class Machine:
    name: str
    axes: list[Axis]  # X, Y, Z
    tool_chain: list[int]  # axis indices, bed outward
    workpiece_chain: list[int]
    ec0y: float  # [rad], reference X
    eb0z: float  # [rad], reference X
    ea0z: float  # [rad], reference Y
    spindle_tilt_a: float  # [rad] about X
    spindle_tilt_b: float  # [rad] about Y
    spindle_nose: npt.NDArray[np.float64]  # (3,) [mm]
    tool_length: float  # [mm]
    tool_direction: npt.NDArray[np.float64]  # (3,) unit
    def __init__(self) -> None: ...
    def axis(self, index: int) -> Axis: ...
    def set_axis(self, index: int, axis: Axis) -> None: ...
    def validate(self) -> None: ...
    def side(self, axis: int) -> Side: ...
    def nominal_tip(self) -> npt.NDArray[np.float64]: ...

def ideal_machine(tool_chain: Sequence[int], workpiece_chain: Sequence[int], tool_length: float = 0.0) -> Machine: ...
def tip_error(machine: Machine, points: npt.ArrayLike, order: Order = ...) -> npt.NDArray[np.float64]:
    """(n, 3) float64 [mm] → (n, 3) tip error relative to the workpiece [mm]"""
def actual_points(machine: Machine, commanded: npt.ArrayLike, order: Order = ...) -> npt.NDArray[np.float64]: ...
def volumetric_error(machine: Machine, points: npt.ArrayLike, order: Order = ...) -> npt.NDArray[np.float64]: ...
def rotation_zyx(a: float, b: float, c: float) -> npt.NDArray[np.float64]: ...
