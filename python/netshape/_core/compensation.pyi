from __future__ import annotations
import netshape._core.machine
import numpy
import numpy.typing
import typing
__all__: list[str] = ['VolumetricOptions', 'VolumetricResult', 'VolumetricStatus', 'compensate_points', 'compensate_points_status']
class VolumetricOptions:
    check_travel: bool
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-09, max_iterations: typing.SupportsInt | typing.SupportsIndex = 50, check_travel: bool = True) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        ...
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class VolumetricStatus:
    """
    Members:
    
      ok
    
      not_converged
    
      outside_travel
    
      outside_table
    """
    __members__: typing.ClassVar[dict[str, VolumetricStatus]]
    not_converged: typing.ClassVar[VolumetricStatus]
    ok: typing.ClassVar[VolumetricStatus]
    outside_table: typing.ClassVar[VolumetricStatus]
    outside_travel: typing.ClassVar[VolumetricStatus]
    @typing.overload
    def __eq__(self, other: VolumetricStatus) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: VolumetricStatus) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class VolumetricResult:
    def all_ok(self) -> bool:
        ...
    def first_failure(self) -> int:
        ...
    @property
    def axis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def commanded(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def iterations(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def residual(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def status(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
def compensate_points(machine: netshape._core.machine.Machine, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: VolumetricOptions = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Commanded points [mm] so the actual tip lands on the nominal (n, 3) points; raises on failure
    """
def compensate_points_status(machine: netshape._core.machine.Machine, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: VolumetricOptions = ...) -> VolumetricResult:
    """
    Like compensate_points, with per-point status instead of raising
    """
