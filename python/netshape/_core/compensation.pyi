from __future__ import annotations
import collections.abc
import netshape._core.cutter
import netshape._core.deflection
import netshape._core.force
import netshape._core.machine
import netshape._core.stock
import netshape._core.toolpath
import numpy
import numpy.typing
import typing
__all__: list[str] = ['DeflectionCompensationOptions', 'DeflectionCompensationResult', 'DeflectionScheme', 'DrawingOffsets', 'FeedLimit', 'FeedLimits', 'PathOptions', 'PathWallErrors', 'ProgramOptions', 'ProgramReport', 'ReferenceLevel', 'VolumetricOptions', 'VolumetricResult', 'VolumetricStatus', 'block_end_times', 'compensate_deflection', 'compensate_points', 'compensate_points_status', 'compensate_program', 'deflection_scheme_from_string', 'drawing_offsets', 'feed_limit_name', 'feed_pieces_core', 'feed_samples_core', 'one_d_compensation', 'path_wall_errors', 'reference_level_from_string', 'wall_normals', 'wall_remains']
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
class ProgramOptions:
    """
    Options of compensate_program (lengths [mm]).
    """
    point: VolumetricOptions
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, chord_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.002, point: VolumetricOptions = ..., max_halvings: typing.SupportsInt | typing.SupportsIndex = 30) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def block_times(self) -> list[float]:
        """
        program time at each block's end [s] (empty: from the programmed feeds)
        """
    @block_times.setter
    def block_times(self, arg0: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def chord_tolerance(self) -> float:
        """
        [mm]
        """
    @chord_tolerance.setter
    def chord_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def initial_direction(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        (3,) each −1, 0 or +1
        """
    @initial_direction.setter
    def initial_direction(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def max_halvings(self) -> int:
        ...
    @max_halvings.setter
    def max_halvings(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def rapid_feed(self) -> float:
        """
        [mm/s]
        """
    @rapid_feed.setter
    def rapid_feed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ProgramReport:
    """
    What compensate_program did (lengths [mm]).
    """
    @property
    def arcs_kept(self) -> int:
        ...
    @property
    def arcs_split(self) -> int:
        ...
    @property
    def blocks_in(self) -> int:
        ...
    @property
    def blocks_out(self) -> int:
        ...
    @property
    def commands(self) -> int:
        ...
    @property
    def lines_split(self) -> int:
        ...
    @property
    def max_correction(self) -> float:
        """
        [mm]
        """
    @property
    def max_path_deviation(self) -> float:
        """
        [mm]
        """
    @property
    def max_residual(self) -> float:
        """
        [mm]
        """
    @property
    def source(self) -> str:
        ...
    @property
    def takeup_moves(self) -> int:
        ...
class ReferenceLevel:
    """
    Members:
    
      bottom
    
      middle
    
      top
    """
    __members__: typing.ClassVar[dict[str, ReferenceLevel]]
    bottom: typing.ClassVar[ReferenceLevel]
    middle: typing.ClassVar[ReferenceLevel]
    top: typing.ClassVar[ReferenceLevel]
    @typing.overload
    def __eq__(self, other: ReferenceLevel) -> bool:
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
    def __ne__(self, other: ReferenceLevel) -> bool:
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
class DeflectionScheme:
    """
    Members:
    
      one_d
    
      integrated
    
      sectional
    
      accelerated
    """
    __members__: typing.ClassVar[dict[str, DeflectionScheme]]
    accelerated: typing.ClassVar[DeflectionScheme]
    integrated: typing.ClassVar[DeflectionScheme]
    one_d: typing.ClassVar[DeflectionScheme]
    sectional: typing.ClassVar[DeflectionScheme]
    @typing.overload
    def __eq__(self, other: DeflectionScheme) -> bool:
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
    def __ne__(self, other: DeflectionScheme) -> bool:
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
class PathOptions:
    exact_self_removal: bool
    immersion: netshape._core.stock.ImmersionOptions
    side: netshape._core.deflection.WallSide
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def profile_levels(self) -> int:
        ...
    @profile_levels.setter
    def profile_levels(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class PathWallErrors:
    @property
    def deflection(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def depth(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def engaged(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def error(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def force(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def normal_deflection(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def phi_ex(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def phi_st(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def positions(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def profile(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        ...
    @property
    def tangential_deflection(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def wall_flags(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @property
    def width(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class DeflectionCompensationOptions:
    level: ReferenceLevel
    path: PathOptions
    scheme: DeflectionScheme
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def active(self) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
        ...
    @active.setter
    def active(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 1]"]) -> None:
        ...
    @property
    def anderson_depth(self) -> int:
        ...
    @anderson_depth.setter
    def anderson_depth(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def discount(self) -> float:
        ...
    @discount.setter
    def discount(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
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
class DeflectionCompensationResult:
    @property
    def after(self) -> PathWallErrors:
        ...
    @property
    def before(self) -> PathWallErrors:
        ...
    @property
    def converged(self) -> bool:
        ...
    @property
    def history(self) -> list[float]:
        ...
    @property
    def iterations(self) -> int:
        ...
    @property
    def message(self) -> str:
        ...
    @property
    def normals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def path_evaluations(self) -> int:
        ...
    @property
    def point_evaluations(self) -> int:
        ...
    @property
    def positions(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def scheme(self) -> DeflectionScheme:
        ...
    @property
    def worst_index(self) -> int:
        ...
class DrawingOffsets:
    @property
    def foot_distance(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def normals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def s(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class FeedLimit:
    """
    What sets a piece's feed (docs/feeds.md).
    
    Members:
    
      force
    
      chip
    
      deflection
    
      wall_error
    
      power
    
      torque
    
      max_feed
    
      air
    
      programmed
    """
    __members__: typing.ClassVar[dict[str, FeedLimit]]
    air: typing.ClassVar[FeedLimit]
    chip: typing.ClassVar[FeedLimit]
    deflection: typing.ClassVar[FeedLimit]
    force: typing.ClassVar[FeedLimit]
    max_feed: typing.ClassVar[FeedLimit]
    power: typing.ClassVar[FeedLimit]
    programmed: typing.ClassVar[FeedLimit]
    torque: typing.ClassVar[FeedLimit]
    wall_error: typing.ClassVar[FeedLimit]
    @typing.overload
    def __eq__(self, other: FeedLimit) -> bool:
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
    def __ne__(self, other: FeedLimit) -> bool:
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
class FeedLimits:
    """
    Limits of a feed schedule (forces [N], lengths [mm], feeds [mm/s], power [W], torque [N·m]); inf: not stated.
    """
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def air_feed(self) -> float:
        ...
    @air_feed.setter
    def air_feed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_chip(self) -> float:
        ...
    @max_chip.setter
    def max_chip(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_deflection(self) -> float:
        ...
    @max_deflection.setter
    def max_deflection(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_feed(self) -> float:
        ...
    @max_feed.setter
    def max_feed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_force(self) -> float:
        ...
    @max_force.setter
    def max_force(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_power(self) -> float:
        ...
    @max_power.setter
    def max_power(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_torque(self) -> float:
        ...
    @max_torque.setter
    def max_torque(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_wall_error(self) -> float:
        ...
    @max_wall_error.setter
    def max_wall_error(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def min_chip(self) -> float:
        ...
    @min_chip.setter
    def min_chip(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def min_feed(self) -> float:
        ...
    @min_feed.setter
    def min_feed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def block_end_times(program: netshape._core.toolpath.Toolpath, rapid_feed: typing.SupportsFloat | typing.SupportsIndex = 250.0) -> list[float]:
    """
    program time at each block's end [s] from the programmed feeds (rapids at rapid_feed [mm/s])
    """
def compensate_deflection(model: netshape._core.deflection.DeflectionModel, cutter: netshape._core.cutter.Cutter, stock: netshape._core.stock.ZMap, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: DeflectionCompensationOptions = ...) -> DeflectionCompensationResult:
    """
    compensate the path (n, 3) for tool deflection; converged = False with a message when it fails
    """
def compensate_points(machine: netshape._core.machine.Machine, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: VolumetricOptions = ...) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Commanded points [mm] so the actual tip lands on the nominal (n, 3) points; raises on failure
    """
def compensate_points_status(machine: netshape._core.machine.Machine, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: VolumetricOptions = ...) -> VolumetricResult:
    """
    Like compensate_points, with per-point status instead of raising
    """
def compensate_program(machine: netshape._core.machine.Machine, program: netshape._core.toolpath.Toolpath, options: ProgramOptions = ...) -> tuple[netshape._core.toolpath.Toolpath, ProgramReport]:
    """
    (Toolpath, ProgramReport): the program compensated so the actual tip follows it within chord_tolerance
    """
def deflection_scheme_from_string(name: str) -> DeflectionScheme:
    ...
def drawing_offsets(points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], drawing: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], side: netshape._core.deflection.WallSide, window: typing.SupportsFloat | typing.SupportsIndex = 2.0) -> DrawingOffsets:
    """
    signed offsets C, normals and foot arc lengths of program points against a drawing's contour
    """
def feed_limit_name(code: typing.SupportsInt | typing.SupportsIndex) -> str:
    """
    The limit's key (max_force_N, …, air_feed_mm_min, programmed) of a FeedLimit code.
    """
def feed_pieces_core(program: netshape._core.toolpath.Toolpath, block: typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"], fraction: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], engaged: typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"], walls: typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"], depth: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], chip_factor: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], engaged_share: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], allowed: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"], limits: FeedLimits, tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.1, min_length: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> dict:
    """
    Pieces of the feed blocks and their feeds [mm/s] (netshape.compensation.feeds).
    """
def feed_samples_core(stock: netshape._core.stock.ZMap, cutter: netshape._core.cutter.Cutter, program: netshape._core.toolpath.Toolpath, limits: FeedLimits, sampling: netshape._core.force.ProgramForceOptions, linear_edge: netshape._core.force.LinearEdgeCoefficients = None, ball_end: netshape._core.force.BallEndCoefficients = None) -> dict:
    """
    Per force sample, the largest feed [mm/s] each limit allows (netshape.compensation.feeds).
    """
def one_d_compensation(model: netshape._core.deflection.DeflectionModel, side: netshape._core.deflection.WallSide, width: typing.SupportsFloat | typing.SupportsIndex, level_z: typing.SupportsFloat | typing.SupportsIndex, tolerance: typing.SupportsFloat | typing.SupportsIndex = 1e-07, max_iterations: typing.SupportsInt | typing.SupportsIndex = 100) -> float:
    """
    C [mm] with D[W + C] - C = 0 for a steady cut of width W [mm] (eq. 8)
    """
def path_wall_errors(model: netshape._core.deflection.DeflectionModel, cutter: netshape._core.cutter.Cutter, stock: netshape._core.stock.ZMap, nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], normals: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]", "flags.c_contiguous"], offsets: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], options: PathOptions = ...) -> PathWallErrors:
    """
    wall error along P_i = R_i + C_i n_i over a copy of the stock swept move by move
    """
def reference_level_from_string(name: str) -> ReferenceLevel:
    ...
def wall_normals(nominal: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], side: netshape._core.deflection.WallSide) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
    """
    (n, 2) unit wall normals of a polyline
    """
def wall_remains(wall: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], top: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], first_later: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 1]"], path: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], cutting: typing.Annotated[numpy.typing.ArrayLike, numpy.int32, "[m, 1]"], radius: typing.SupportsFloat | typing.SupportsIndex, clearance: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, 1]"]:
    """
    (n) 1 where wall point k (XY, bottom z; top[k]) is not cut away by a cutting move j >= first_later[k]
    """
