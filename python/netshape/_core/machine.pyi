from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Axis', 'Component', 'CyclicTerm', 'ErrorFunction', 'Machine', 'Order', 'OutOfRange', 'Side', 'ThermalDrift', 'actual_points', 'approach_directions', 'component_name', 'ideal_machine', 'rotation_zyx', 'state_error', 'tip_error', 'volumetric_error']
class OutOfRange:
    """
    What a table does outside its positions
    
    Members:
    
      error
    
      clamp
    
      extrapolate
    """
    __members__: typing.ClassVar[dict[str, OutOfRange]]
    clamp: typing.ClassVar[OutOfRange]
    error: typing.ClassVar[OutOfRange]
    extrapolate: typing.ClassVar[OutOfRange]
    @typing.overload
    def __eq__(self, other: OutOfRange) -> bool:
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
    def __ne__(self, other: OutOfRange) -> bool:
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
class ErrorFunction:
    """
    One error component e(q) of an axis: zero, polynomial (ascending powers of q [mm]) or table (linear interpolation). Values [mm] or [rad].
    """
    class Kind:
        """
        Members:
        
          zero
        
          polynomial
        
          table
        """
        __members__: typing.ClassVar[dict[str, ErrorFunction.Kind]]
        polynomial: typing.ClassVar[ErrorFunction.Kind]
        table: typing.ClassVar[ErrorFunction.Kind]
        zero: typing.ClassVar[ErrorFunction.Kind]
        @typing.overload
        def __eq__(self, other: ErrorFunction.Kind) -> bool:
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
        def __ne__(self, other: ErrorFunction.Kind) -> bool:
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
    kind: ErrorFunction.Kind
    name: str
    out_of_range: OutOfRange
    @staticmethod
    def polynomial(coefficients: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], name: str = '') -> ErrorFunction:
        ...
    @staticmethod
    def table(positions: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], values: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], out_of_range: OutOfRange = ..., name: str = '') -> ErrorFunction:
        ...
    @staticmethod
    def zero_function(name: str = '') -> ErrorFunction:
        ...
    def __call__(self, q: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def __init__(self) -> None:
        ...
    def evaluate(self, q: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        e(q) at many positions q [mm], (n,) → (n,)
        """
    def is_zero(self) -> bool:
        ...
    def validate(self) -> None:
        ...
    @property
    def coefficients(self) -> list[float]:
        ...
    @coefficients.setter
    def coefficients(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def positions(self) -> list[float]:
        ...
    @positions.setter
    def positions(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def values(self) -> list[float]:
        ...
    @values.setter
    def values(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
class Component:
    """
    Members:
    
      ex
    
      ey
    
      ez
    
      ea
    
      eb
    
      ec
    """
    __members__: typing.ClassVar[dict[str, Component]]
    ea: typing.ClassVar[Component]
    eb: typing.ClassVar[Component]
    ec: typing.ClassVar[Component]
    ex: typing.ClassVar[Component]
    ey: typing.ClassVar[Component]
    ez: typing.ClassVar[Component]
    @typing.overload
    def __eq__(self, other: Component) -> bool:
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
    def __ne__(self, other: Component) -> bool:
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
class Side:
    """
    Members:
    
      tool
    
      workpiece
    """
    __members__: typing.ClassVar[dict[str, Side]]
    tool: typing.ClassVar[Side]
    workpiece: typing.ClassVar[Side]
    @typing.overload
    def __eq__(self, other: Side) -> bool:
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
    def __ne__(self, other: Side) -> bool:
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
class Order:
    """
    Members:
    
      exact
    
      first
    """
    __members__: typing.ClassVar[dict[str, Order]]
    exact: typing.ClassVar[Order]
    first: typing.ClassVar[Order]
    @typing.overload
    def __eq__(self, other: Order) -> bool:
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
    def __ne__(self, other: Order) -> bool:
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
class CyclicTerm:
    """
    Periodic positioning error amplitude·sin(2π·q/period + phase)
    """
    def __init__(self, amplitude: typing.SupportsFloat | typing.SupportsIndex = 0.0, period: typing.SupportsFloat | typing.SupportsIndex = 1.0, phase: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    @property
    def amplitude(self) -> float:
        """
        [mm]
        """
    @amplitude.setter
    def amplitude(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def period(self) -> float:
        """
        [mm]
        """
    @period.setter
    def period(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def phase(self) -> float:
        """
        [rad]
        """
    @phase.setter
    def phase(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ThermalDrift:
    """
    Tip drift along an axis: amplitude·(1 − exp(−t/time_constant))
    """
    def __init__(self, axis: typing.SupportsInt | typing.SupportsIndex = 0, amplitude: typing.SupportsFloat | typing.SupportsIndex = 0.0, time_constant: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        ...
    @property
    def amplitude(self) -> float:
        """
        [mm]
        """
    @amplitude.setter
    def amplitude(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def axis(self) -> int:
        """
        0 = X, 1 = Y, 2 = Z
        """
    @axis.setter
    def axis(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def time_constant(self) -> float:
        """
        [s]
        """
    @time_constant.setter
    def time_constant(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Axis:
    """
    A linear axis: travel [mm], frame origin [mm], six error components
    """
    def __init__(self) -> None:
        ...
    def error(self, component: Component) -> ErrorFunction:
        ...
    def set_error(self, component: Component, function: ErrorFunction) -> None:
        ...
    @property
    def backlash(self) -> float:
        """
        reversal value [mm]
        """
    @backlash.setter
    def backlash(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def cyclic(self) -> list[CyclicTerm]:
        """
        periodic terms of the positioning component (a copy: assign back)
        """
    @cyclic.setter
    def cyclic(self, arg0: collections.abc.Sequence[CyclicTerm]) -> None:
        ...
    @property
    def errors(self) -> list[ErrorFunction]:
        """
        EXk, EYk, EZk, EAk, EBk, ECk (a copy: change an element, then assign the list back)
        """
    @errors.setter
    def errors(self, arg1: collections.abc.Sequence[ErrorFunction]) -> None:
        ...
    @property
    def origin(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @origin.setter
    def origin(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def travel_max(self) -> float:
        ...
    @travel_max.setter
    def travel_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def travel_min(self) -> float:
        ...
    @travel_min.setter
    def travel_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Machine:
    """
    3-axis machine: two chains of linear axes from the bed with ISO 230-1 errors
    """
    name: str
    def __init__(self) -> None:
        ...
    def axis(self, index: typing.SupportsInt | typing.SupportsIndex) -> Axis:
        ...
    def has_state_errors(self) -> bool:
        ...
    def nominal_tip(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    def set_axis(self, index: typing.SupportsInt | typing.SupportsIndex, axis: Axis) -> None:
        ...
    def side(self, axis: typing.SupportsInt | typing.SupportsIndex) -> Side:
        ...
    def validate(self) -> None:
        ...
    @property
    def axes(self) -> list[Axis]:
        """
        X, Y, Z axes (a copy: change an element, then assign the list back)
        """
    @axes.setter
    def axes(self, arg1: collections.abc.Sequence[Axis]) -> None:
        ...
    @property
    def ea0z(self) -> float:
        ...
    @ea0z.setter
    def ea0z(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def eb0z(self) -> float:
        ...
    @eb0z.setter
    def eb0z(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ec0y(self) -> float:
        ...
    @ec0y.setter
    def ec0y(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def spindle_nose(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @spindle_nose.setter
    def spindle_nose(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def spindle_tilt_a(self) -> float:
        ...
    @spindle_tilt_a.setter
    def spindle_tilt_a(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def spindle_tilt_b(self) -> float:
        ...
    @spindle_tilt_b.setter
    def spindle_tilt_b(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def thermal(self) -> list[ThermalDrift]:
        """
        thermal drift terms (a copy: assign back)
        """
    @thermal.setter
    def thermal(self, arg0: collections.abc.Sequence[ThermalDrift]) -> None:
        ...
    @property
    def tool_chain(self) -> list[int]:
        ...
    @tool_chain.setter
    def tool_chain(self, arg0: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> None:
        ...
    @property
    def tool_direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @tool_direction.setter
    def tool_direction(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def tool_length(self) -> float:
        ...
    @tool_length.setter
    def tool_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def workpiece_chain(self) -> list[int]:
        ...
    @workpiece_chain.setter
    def workpiece_chain(self, arg0: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> None:
        ...
def actual_points(machine: Machine, commanded: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], order: Order = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Where the tip lands, p + e(p) [mm], (n, 3) → (n, 3)
    """
def approach_directions(path: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], initial: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"] = [1, 1, 1], resolution: typing.SupportsFloat | typing.SupportsIndex = 1e-09) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Per point of a path (n, 3) [mm]: the sign of each axis' last motion (n, 3)
    """
def component_name(component: Component, axis: typing.SupportsInt | typing.SupportsIndex) -> str:
    ...
def ideal_machine(tool_chain: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex], workpiece_chain: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex], tool_length: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> Machine:
    ...
def rotation_zyx(a: typing.SupportsFloat | typing.SupportsIndex, b: typing.SupportsFloat | typing.SupportsIndex, c: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 3]"]:
    """
    Rz(c)·Ry(b)·Rx(a) [rad] → (3, 3)
    """
def state_error(machine: Machine, directions: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], times: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Backlash + thermal tip offset s(d, t) [mm]: directions (n, 3) (±1), times (n,) [s] → (n, 3)
    """
def tip_error(machine: Machine, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], order: Order = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Tool-tip error relative to the workpiece e(p) [mm], (n, 3) float64 → (n, 3)
    """
def volumetric_error(machine: Machine, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], order: Order = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    |e(p)| [mm] (Yang & Kweon eq. 16), (n, 3) → (n,)
    """
