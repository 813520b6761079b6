from __future__ import annotations
import netshape._core.geometry
import numpy
import numpy.typing
import typing
__all__: list[str] = ['CSpace', 'CSpaceOptions', 'CutterAssembly', 'InterferenceChecker', 'Kinematics', 'MachineKind', 'MoveCheck', 'MovePlan', 'PlanOptions', 'PlanResult', 'PostureFrame', 'PostureSet', 'check_move', 'check_moves', 'classify', 'compute_cspace', 'forward_kinematics', 'inverse_kinematics', 'max_posture_change', 'mb_smooth', 'mb_spline_derivative', 'mb_spline_joins', 'mb_spline_point', 'move_speed_bound', 'plan', 'plan_program', 'subdivide_rotary']
class CutterAssembly:
    """
    Ball-end cutter assembly: ball + shank cylinder + holder (flat-faced cylinder or a (z, r) profile of frustums), solids of revolution; lengths from the tip [mm]
    """
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, ball_radius: typing.SupportsFloat | typing.SupportsIndex, shank_radius: typing.SupportsFloat | typing.SupportsIndex, shank_length: typing.SupportsFloat | typing.SupportsIndex, holder_radius: typing.SupportsFloat | typing.SupportsIndex, holder_length: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def distance(self, z: typing.SupportsFloat | typing.SupportsIndex, rho: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        exact distance [mm] from the meridian point (z, rho) to the solid (0 inside)
        """
    def reach(self) -> float:
        """
        largest distance of a point of the solid from the tip [mm]
        """
    def validate(self) -> None:
        ...
    @property
    def ball_radius(self) -> float:
        """
        [mm]
        """
    @ball_radius.setter
    def ball_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def holder_length(self) -> float:
        """
        tip to the end of the holder [mm]
        """
    @holder_length.setter
    def holder_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def holder_profile(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        """
        (k, 2) (z [mm] from the tip, r [mm]) of the holder; empty = the flat-faced cylinder
        """
    @holder_profile.setter
    def holder_profile(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 2]"]) -> None:
        ...
    @property
    def holder_radius(self) -> float:
        """
        [mm]
        """
    @holder_radius.setter
    def holder_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sections(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (k, 4): z0, z1, r0, r1 [mm] of the shank and holder frustums, bottom to top (the ball is separate)
        """
    @property
    def shank_length(self) -> float:
        """
        tip to the end of the shank [mm]
        """
    @shank_length.setter
    def shank_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shank_radius(self) -> float:
        """
        [mm]
        """
    @shank_radius.setter
    def shank_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class InterferenceChecker:
    def __init__(self, obstacles: netshape._core.geometry.TriangleMesh, assembly: CutterAssembly, clearance: typing.SupportsFloat | typing.SupportsIndex, tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.001) -> None:
        ...
    def clear_by(self, tip: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], margin: typing.SupportsFloat | typing.SupportsIndex) -> int:
        """
        +1 gap certainly >= clearance + margin, -1 certainly < clearance, 0 undecided
        """
    def collides(self, tips: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], axes: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> numpy.typing.NDArray[numpy.bool]:
        """
        (n,) bool: closer than the clearance, tips/axes (n, 3)
        """
    def gap(self, tip: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> float:
        """
        least distance between assembly and mesh [mm] (to the tolerance)
        """
    @property
    def assembly(self) -> CutterAssembly:
        ...
    @property
    def clearance(self) -> float:
        ...
    @property
    def gjk_runs(self) -> int:
        """
        frustum-triangle GJK runs of all queries so far (the work; shared by copies)
        """
    @property
    def obstacles(self) -> netshape._core.geometry.TriangleMesh:
        ...
    @property
    def tolerance(self) -> float:
        ...
class CSpaceOptions:
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def phi_step(self) -> float:
        """
        [rad]
        """
    @phi_step.setter
    def phi_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def theta_max(self) -> float:
        """
        [rad]
        """
    @theta_max.setter
    def theta_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def theta_step(self) -> float:
        """
        [rad]
        """
    @theta_step.setter
    def theta_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def tolerance(self) -> float:
        """
        bisection tolerance [rad]
        """
    @tolerance.setter
    def tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PostureFrame:
    @staticmethod
    def make(cc: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], normal: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], feed: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> PostureFrame:
        ...
    def axis(self, theta: typing.SupportsFloat | typing.SupportsIndex, phi: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    def posture(self, axis: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        ...
    @property
    def cc(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def feed(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def left(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def normal(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
class CSpace:
    def mc_posture(self, posture: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        ...
    def nearest_boundary(self, posture: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[2, 1]"], obstacle: typing.SupportsInt | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
        ...
    @property
    def boundary(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (m, 3): theta [rad], phi [rad], obstacle (1 or 2)
        """
    @property
    def checks(self) -> int:
        ...
    @property
    def frame(self) -> PostureFrame:
        ...
    @property
    def options(self) -> CSpaceOptions:
        ...
    @property
    def phis(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (count_phi,) [rad]
        """
    @property
    def states(self) -> numpy.typing.NDArray[numpy.int8]:
        """
        (count_phi, count_theta) int8: 0 free, 1 CA1 (left), 2 CA2 (right)
        """
    @property
    def thetas(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (count_theta,) [rad]
        """
class PlanOptions:
    cspace: CSpaceOptions
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def passes(self) -> int:
        """
        MB-spline smoothing passes
        """
    @passes.setter
    def passes(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def vector_length(self) -> float:
        """
        posture vector length [mm], 0 = holder_length
        """
    @vector_length.setter
    def vector_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PostureSet:
    def collision_count(self) -> int:
        ...
    @property
    def angles(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        """
        (n, 2) theta, phi [rad]
        """
    @property
    def axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n, 3) unit
        """
    @property
    def collides(self) -> numpy.typing.NDArray[numpy.bool]:
        ...
    @property
    def tips(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n, 3) [mm]
        """
class PlanResult:
    def repaired_count(self) -> int:
        ...
    @property
    def cc(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def checks(self) -> int:
        ...
    @property
    def cspaces(self) -> list[CSpace]:
        ...
    @property
    def feeds(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def final(self) -> PostureSet:
        ...
    @property
    def mc(self) -> PostureSet:
        ...
    @property
    def normals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def raw(self) -> PostureSet:
        ...
    @property
    def repaired(self) -> numpy.typing.NDArray[numpy.bool]:
        ...
    @property
    def s(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n,) path length [mm]
        """
    @property
    def smoothed(self) -> PostureSet:
        ...
class MachineKind:
    """
    Members:
    
      table_ac
    
      head_bc
    """
    __members__: typing.ClassVar[dict[str, MachineKind]]
    head_bc: typing.ClassVar[MachineKind]
    table_ac: typing.ClassVar[MachineKind]
    @typing.overload
    def __eq__(self, other: MachineKind) -> bool:
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
    def __ne__(self, other: MachineKind) -> bool:
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
class Kinematics:
    kind: MachineKind
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def pivot_length(self) -> float:
        """
        [mm]
        """
    @pivot_length.setter
    def pivot_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def table_centre(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        [mm]
        """
    @table_centre.setter
    def table_centre(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def tilt_max(self) -> float:
        """
        [rad]
        """
    @tilt_max.setter
    def tilt_max(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def tilt_min(self) -> float:
        """
        [rad]
        """
    @tilt_min.setter
    def tilt_min(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class MoveCheck:
    @property
    def at(self) -> float:
        """
        lambda of the colliding pose found
        """
    @property
    def checks(self) -> int:
        ...
    @property
    def collides(self) -> bool:
        ...
class MovePlan:
    @property
    def axes(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (m, 3) unit
        """
    @property
    def checks(self) -> int:
        ...
    @property
    def colliding_before(self) -> int:
        ...
    @property
    def inserted(self) -> int:
        ...
    @property
    def joints(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        (m, 5) X, Y, Z [mm], tilt, C [rad]
        """
    @property
    def move_collides(self) -> numpy.typing.NDArray[numpy.bool]:
        """
        (m - 1,) bool: certified check of every move
        """
    @property
    def source(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (m,) CC index + fraction to the next (-1 approach, n retract)
        """
    @property
    def tips(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (m, 3) [mm]
        """
def check_move(checker: InterferenceChecker, kinematics: Kinematics, j0: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], j1: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], min_step: typing.SupportsFloat | typing.SupportsIndex = 0.0001) -> MoveCheck:
    ...
def check_moves(checker: InterferenceChecker, kinematics: Kinematics, joints: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"], min_step: typing.SupportsFloat | typing.SupportsIndex = 0.0001) -> numpy.typing.NDArray[numpy.bool]:
    """
    (n - 1,) bool: certified check of the joint-linear moves between joints (n, 5)
    """
def classify(checker: InterferenceChecker, frame: PostureFrame, theta: typing.SupportsFloat | typing.SupportsIndex, phi: typing.SupportsFloat | typing.SupportsIndex) -> int:
    """
    0 free, 1 CA1, 2 CA2
    """
def compute_cspace(checker: InterferenceChecker, frame: PostureFrame, options: CSpaceOptions = ...) -> CSpace:
    ...
def forward_kinematics(kinematics: Kinematics, joints: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]]:
    """
    (tips (n, 3), axes (n, 3))
    """
def inverse_kinematics(kinematics: Kinematics, tips: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], axes: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], c_start: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
    """
    (n, 5): X, Y, Z [mm], tilt (A or B) [rad], C [rad]
    """
def max_posture_change(s: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], axes: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> float:
    """
    [rad/mm]
    """
def mb_smooth(points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], passes: typing.SupportsInt | typing.SupportsIndex = 1) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    ...
def mb_spline_derivative(control: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], span: typing.SupportsInt | typing.SupportsIndex, u: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    ...
def mb_spline_joins(control: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    ...
def mb_spline_point(control: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], span: typing.SupportsInt | typing.SupportsIndex, u: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    ...
def move_speed_bound(kinematics: Kinematics, assembly: CutterAssembly, j0: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], j1: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> float:
    """
    largest displacement of any assembly point per unit lambda [mm]
    """
def plan(checker: InterferenceChecker, cc: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], normals: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], options: PlanOptions = ...) -> PlanResult:
    ...
def plan_program(checker: InterferenceChecker, kinematics: Kinematics, plan: PlanResult, options: PlanOptions = ..., approach: typing.SupportsFloat | typing.SupportsIndex = 10.0, chord: typing.SupportsFloat | typing.SupportsIndex = 0.01, max_depth: typing.SupportsInt | typing.SupportsIndex = 4) -> MovePlan:
    ...
def subdivide_rotary(kinematics: Kinematics, tips: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], axes: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], chord: typing.SupportsFloat | typing.SupportsIndex) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
    """
    (tips (m, 3), axes (m, 3), source (m,)): CL points inserted where the tip leaves a chord by > chord mm
    """
