from __future__ import annotations
import netshape._core.force
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Cantilever', 'DeflectionModel', 'DeflectionWorkspace', 'InertiaModel', 'LoadModel', 'WallErrors', 'WallSide', 'cut_levels', 'deflection_at', 'disk_forces', 'generation_angle', 'inertia_model_from_string', 'load_model_from_string', 'max_force', 'second_moment', 'wall_angle', 'wall_errors', 'wall_side_from_string']
class InertiaModel:
    """
    Second moment of the fluted section: square D^4/48 or equivalent 0.8 D
    
    Members:
    
      square
    
      equivalent
    """
    __members__: typing.ClassVar[dict[str, InertiaModel]]
    equivalent: typing.ClassVar[InertiaModel]
    square: typing.ClassVar[InertiaModel]
    @typing.overload
    def __eq__(self, other: InertiaModel) -> bool:
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
    def __ne__(self, other: InertiaModel) -> bool:
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
class LoadModel:
    """
    resultant at L - A/2 (eq. 7) or distributed element loads
    
    Members:
    
      resultant
    
      distributed
    """
    __members__: typing.ClassVar[dict[str, LoadModel]]
    distributed: typing.ClassVar[LoadModel]
    resultant: typing.ClassVar[LoadModel]
    @typing.overload
    def __eq__(self, other: LoadModel) -> bool:
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
    def __ne__(self, other: LoadModel) -> bool:
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
class WallSide:
    """
    left wall (+Y_c, phi = 0, up milling) or right wall (-Y_c, phi = pi, down milling)
    
    Members:
    
      left
    
      right
    """
    __members__: typing.ClassVar[dict[str, WallSide]]
    left: typing.ClassVar[WallSide]
    right: typing.ClassVar[WallSide]
    @typing.overload
    def __eq__(self, other: WallSide) -> bool:
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
    def __ne__(self, other: WallSide) -> bool:
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
class Cantilever:
    """
    Uniform cantilever clamped at x = 0; x from the clamp [mm]
    """
    @staticmethod
    def tool(diameter: typing.SupportsFloat | typing.SupportsIndex, stick_out: typing.SupportsFloat | typing.SupportsIndex, youngs_modulus: typing.SupportsFloat | typing.SupportsIndex, model: InertiaModel) -> Cantilever:
        ...
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, length: typing.SupportsFloat | typing.SupportsIndex, youngs_modulus: typing.SupportsFloat | typing.SupportsIndex, inertia: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def deflection(self, force: typing.SupportsFloat | typing.SupportsIndex, x: typing.SupportsFloat | typing.SupportsIndex, l: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        eq. 6: deflection at x of a load force [N] at l [mm]
        """
    def influence(self, x: typing.SupportsFloat | typing.SupportsIndex, a: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        deflection at x per unit load at a (both from the clamp) [mm/N]
        """
    def rigidity(self) -> float:
        """
        E I [N mm^2]
        """
    def validate(self) -> None:
        ...
    @property
    def inertia(self) -> float:
        """
        I [mm^4]
        """
    @inertia.setter
    def inertia(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def length(self) -> float:
        """
        L, holder face to tip [mm]
        """
    @length.setter
    def length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def youngs_modulus(self) -> float:
        """
        E [MPa]
        """
    @youngs_modulus.setter
    def youngs_modulus(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class DeflectionModel:
    """
    Force model of the cut + the cantilever that carries it
    """
    beam: Cantilever
    force: netshape._core.force.FlatEndModel
    load: LoadModel
    smooth_edges: bool
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def chip(self) -> netshape._core.force.RunoutSizeEffect:
        """
        runout and chip-size effect of the element chips
        """
    @chip.setter
    def chip(self, arg0: netshape._core.force.RunoutSizeEffect) -> None:
        ...
    @property
    def holder_compliance(self) -> float:
        """
        clamp/holder compliance [mm/N]: the tool also translates by holder_compliance * F
        """
    @holder_compliance.setter
    def holder_compliance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class DeflectionWorkspace:
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, model: DeflectionModel) -> None:
        ...
    def reset(self, model: DeflectionModel) -> None:
        ...
    @property
    def disk_height(self) -> float:
        ...
    @property
    def disks(self) -> int:
        ...
    @property
    def forces(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def heights(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class WallErrors:
    @property
    def deflection(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def error(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    @property
    def force(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
        ...
    @property
    def z(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
def cut_levels(axial_depth: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    (bottom, middle, top) heights [mm]
    """
def deflection_at(model: DeflectionModel, workspace: DeflectionWorkspace, theta: typing.SupportsFloat | typing.SupportsIndex, z: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[2, 1]"]:
    """
    (dx_c, dy_c) [mm] at height z [mm] above the tip at rotation theta [rad]
    """
def disk_forces(model: DeflectionModel, workspace: DeflectionWorkspace, theta: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
    """
    (disks, 2) forces (Fx_c, Fy_c) [N] at rotation theta [rad]
    """
def generation_angle(model: DeflectionModel, side: WallSide, z: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    rotation angle [rad] at which flute 1 generates the wall at height z [mm]
    """
def inertia_model_from_string(name: str) -> InertiaModel:
    ...
def load_model_from_string(name: str) -> LoadModel:
    ...
def max_force(model: DeflectionModel, workspace: DeflectionWorkspace, samples: typing.SupportsInt | typing.SupportsIndex = 720) -> float:
    """
    largest |(Fx, Fy)| [N] over one tooth period
    """
def second_moment(diameter: typing.SupportsFloat | typing.SupportsIndex, model: InertiaModel) -> float:
    """
    I [mm^4] of a tool of diameter [mm]
    """
def wall_angle(side: WallSide) -> float:
    """
    wall angle phi_w [rad]: 0 (left) or pi (right)
    """
def wall_errors(model: DeflectionModel, workspace: DeflectionWorkspace, side: WallSide, z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> WallErrors:
    """
    wall error e = -delta.n [mm] (+ material left) at heights z [mm]
    """
def wall_side_from_string(name: str) -> WallSide:
    ...
