from __future__ import annotations
import collections.abc
import netshape._core.cutter
import netshape._core.stock
import netshape._core.toolpath
import numpy
import numpy.typing
import typing
__all__: list[str] = ['AngularEngagement', 'BallEndCoefficientSet', 'BallEndCoefficients', 'BallEndFit', 'BallEndModel', 'BallEndWorkspace', 'EngagementMap', 'FlatCoefficientModel', 'FlatEndModel', 'FlatEndWorkspace', 'KlineDevorCoefficients', 'LinearEdgeCoefficientSet', 'LinearEdgeCoefficients', 'LinearEdgeFit', 'MillingMode', 'ProgramForceOptions', 'RunoutSizeEffect', 'TimeSeriesFit', 'ball_end_coefficient_set', 'ball_end_coefficient_set_names', 'ball_end_forces', 'ball_end_mean_slot_force', 'fit_ball_end_mean_forces', 'fit_linear_edge_mean_forces', 'fit_linear_edge_time_series', 'flat_end_forces', 'flat_end_forces_extended', 'flat_end_moments', 'linear_edge_basis', 'linear_edge_coefficient_set', 'linear_edge_coefficient_set_names', 'mean_force', 'mean_force_matrix', 'milling_mode_from_string', 'resultant', 'rotation_angles', 'simulate_program_core', 'summarize', 'summarize_revolutions']
class MillingMode:
    """
    Up, down or slot milling (docs/conventions.md §2).
    
    Members:
    
      up
    
      down
    
      slot
    """
    __members__: typing.ClassVar[dict[str, MillingMode]]
    down: typing.ClassVar[MillingMode]
    slot: typing.ClassVar[MillingMode]
    up: typing.ClassVar[MillingMode]
    @typing.overload
    def __eq__(self, other: MillingMode) -> bool:
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
    def __ne__(self, other: MillingMode) -> bool:
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
class FlatCoefficientModel:
    """
    Members:
    
      linear_edge
    
      kline_devor
    """
    __members__: typing.ClassVar[dict[str, FlatCoefficientModel]]
    kline_devor: typing.ClassVar[FlatCoefficientModel]
    linear_edge: typing.ClassVar[FlatCoefficientModel]
    @typing.overload
    def __eq__(self, other: FlatCoefficientModel) -> bool:
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
    def __ne__(self, other: FlatCoefficientModel) -> bool:
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
class LinearEdgeCoefficients:
    """
    Linear edge-force coefficients: ktc krc kac [N/mm²], kte kre kae [N/mm].
    """
    def __init__(self, ktc: typing.SupportsFloat | typing.SupportsIndex = 0.0, krc: typing.SupportsFloat | typing.SupportsIndex = 0.0, kac: typing.SupportsFloat | typing.SupportsIndex = 0.0, kte: typing.SupportsFloat | typing.SupportsIndex = 0.0, kre: typing.SupportsFloat | typing.SupportsIndex = 0.0, kae: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def as_array(self) -> typing.Annotated[list[float], "FixedSize(6)"]:
        ...
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        ...
    @property
    def kac(self) -> float:
        ...
    @kac.setter
    def kac(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def kae(self) -> float:
        ...
    @kae.setter
    def kae(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def krc(self) -> float:
        ...
    @krc.setter
    def krc(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def kre(self) -> float:
        ...
    @kre.setter
    def kre(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def ktc(self) -> float:
        ...
    @ktc.setter
    def ktc(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def kte(self) -> float:
        ...
    @kte.setter
    def kte(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class KlineDevorCoefficients:
    """
    Kline–DeVor K_T [N/mm²] and K_R [-] (Cho & Suh eq. 1).
    """
    def __init__(self, kt: typing.SupportsFloat | typing.SupportsIndex, kr: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def to_linear_edge(self) -> LinearEdgeCoefficients:
        ...
    def validate(self) -> None:
        ...
    @property
    def kr(self) -> float:
        ...
    @kr.setter
    def kr(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def kt(self) -> float:
        ...
    @kt.setter
    def kt(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class BallEndCoefficients:
    """
    Feng–Menq ball-end coefficients (Kim et al. eq. 6–7): K_T(ψ) = Σ a_i ψ^i, K_R(ψ) = Σ b_i ψ^i, exponents m_t, m_r.
    """
    def __init__(self, a: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(4)"], b: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(4)"], m_t: typing.SupportsFloat | typing.SupportsIndex, m_r: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def kr(self, psi: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        K_R(ψ), ψ [rad]
        """
    def kt(self, psi: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> typing.Any:
        """
        K_T(ψ), ψ [rad]
        """
    def to_dict(self) -> dict:
        ...
    def validate(self) -> None:
        ...
    @property
    def a(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        ...
    @a.setter
    def a(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(4)"]) -> None:
        ...
    @property
    def b(self) -> typing.Annotated[list[float], "FixedSize(4)"]:
        ...
    @b.setter
    def b(self, arg0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(4)"]) -> None:
        ...
    @property
    def m_r(self) -> float:
        ...
    @m_r.setter
    def m_r(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def m_t(self) -> float:
        ...
    @m_t.setter
    def m_t(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class BallEndCoefficientSet:
    @property
    def coefficients(self) -> BallEndCoefficients:
        ...
    @property
    def diameter(self) -> float:
        ...
    @property
    def flutes(self) -> int:
        ...
    @property
    def helix(self) -> float:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def source(self) -> str:
        ...
class LinearEdgeCoefficientSet:
    @property
    def coefficients(self) -> LinearEdgeCoefficients:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def source(self) -> str:
        ...
class AngularEngagement:
    """
    Engagement window [phi_st, phi_ex] [rad], immersion clockwise from +Y.
    """
    @staticmethod
    def from_mode(mode: MillingMode, radius: typing.SupportsFloat | typing.SupportsIndex, radial_depth: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> AngularEngagement:
        ...
    def __init__(self, phi_st: typing.SupportsFloat | typing.SupportsIndex = 0.0, phi_ex: typing.SupportsFloat | typing.SupportsIndex = 3.141592653589793) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def validate(self) -> None:
        ...
    @property
    def phi_ex(self) -> float:
        ...
    @phi_ex.setter
    def phi_ex(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def phi_st(self) -> float:
        ...
    @phi_st.setter
    def phi_st(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class EngagementMap:
    """
    Per-disk (row) angular bins in material, mask (rows, bins) uint8.
    """
    @staticmethod
    def from_window(window: AngularEngagement, disks: typing.SupportsInt | typing.SupportsIndex, bins: typing.SupportsInt | typing.SupportsIndex) -> EngagementMap:
        ...
    def __init__(self, mask: typing.Annotated[numpy.typing.ArrayLike, numpy.uint8, "[m, n]"]) -> None:
        ...
    def bins(self) -> int:
        ...
    def disks(self) -> int:
        ...
    @property
    def mask(self) -> typing.Annotated[numpy.typing.NDArray[numpy.uint8], "[m, n]"]:
        ...
    @mask.setter
    def mask(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.uint8, "[m, n]"]) -> None:
        ...
class FlatEndModel:
    """
    Flat end mill force model (immutable inputs of a sweep).
    """
    coefficient_model: FlatCoefficientModel
    engagement: AngularEngagement
    kline_devor: KlineDevorCoefficients
    linear_edge: LinearEdgeCoefficients
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex = 5.0, flutes: typing.SupportsInt | typing.SupportsIndex = 2, helix: typing.SupportsFloat | typing.SupportsIndex = 0.5235987755982988, axial_depth: typing.SupportsFloat | typing.SupportsIndex = 1.0, feed_per_tooth: typing.SupportsFloat | typing.SupportsIndex = 0.05, engagement: AngularEngagement = ..., coefficient_model: FlatCoefficientModel = ..., linear_edge: LinearEdgeCoefficients = ..., kline_devor: KlineDevorCoefficients = ..., disk_height: typing.SupportsFloat | typing.SupportsIndex = 0.05) -> None:
        ...
    def disks(self) -> int:
        ...
    def k_beta(self) -> float:
        ...
    def validate(self) -> None:
        ...
    @property
    def axial_depth(self) -> float:
        ...
    @axial_depth.setter
    def axial_depth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def disk_height(self) -> float:
        ...
    @disk_height.setter
    def disk_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def feed_per_tooth(self) -> float:
        ...
    @feed_per_tooth.setter
    def feed_per_tooth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flutes(self) -> int:
        ...
    @flutes.setter
    def flutes(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def helix(self) -> float:
        ...
    @helix.setter
    def helix(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def radius(self) -> float:
        ...
    @radius.setter
    def radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class FlatEndWorkspace:
    """
    Preallocated buffers for a FlatEndModel.
    """
    def __init__(self, model: FlatEndModel) -> None:
        ...
    def disk_height(self) -> float:
        ...
    def disks(self) -> int:
        ...
    def elements(self) -> int:
        ...
    def heights(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def reset(self, model: FlatEndModel) -> None:
        ...
class RunoutSizeEffect:
    """
    Cutter runout (rho [mm], lambda [rad]) and chip-size effect (exponent p, reference chip [mm], 0: the feed per tooth)
    """
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, runout_rho: typing.SupportsFloat | typing.SupportsIndex = 0.0, runout_lambda: typing.SupportsFloat | typing.SupportsIndex = 0.0, chip_exponent: typing.SupportsFloat | typing.SupportsIndex = 1.0, reference_chip: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def none(self) -> bool:
        ...
    def validate(self) -> None:
        ...
    @property
    def chip_exponent(self) -> float:
        """
        p in (0, 2]
        """
    @chip_exponent.setter
    def chip_exponent(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def reference_chip(self) -> float:
        """
        h_ref [mm]; 0: the feed per tooth
        """
    @reference_chip.setter
    def reference_chip(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_lambda(self) -> float:
        """
        [rad]
        """
    @runout_lambda.setter
    def runout_lambda(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_rho(self) -> float:
        """
        [mm]
        """
    @runout_rho.setter
    def runout_rho(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class BallEndModel:
    """
    Ball end mill force model (Kim et al.).
    """
    coefficients: BallEndCoefficients
    engagement: AngularEngagement
    def __init__(self, radius: typing.SupportsFloat | typing.SupportsIndex = 6.0, flutes: typing.SupportsInt | typing.SupportsIndex = 2, helix: typing.SupportsFloat | typing.SupportsIndex = 0.5235987755982988, axial_depth: typing.SupportsFloat | typing.SupportsIndex = 3.0, feed_per_tooth: typing.SupportsFloat | typing.SupportsIndex = 0.05, inclination: typing.SupportsFloat | typing.SupportsIndex = 0.0, engagement: AngularEngagement = ..., coefficients: BallEndCoefficients = ..., element_angle: typing.SupportsFloat | typing.SupportsIndex = 0.017453292519943295, disk_height: typing.SupportsFloat | typing.SupportsIndex = 0.05, runout_rho: typing.SupportsFloat | typing.SupportsIndex = 0.0, runout_lambda: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def k_beta(self) -> float:
        ...
    def validate(self) -> None:
        ...
    @property
    def axial_depth(self) -> float:
        ...
    @axial_depth.setter
    def axial_depth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def disk_height(self) -> float:
        ...
    @disk_height.setter
    def disk_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def element_angle(self) -> float:
        ...
    @element_angle.setter
    def element_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def feed_per_tooth(self) -> float:
        ...
    @feed_per_tooth.setter
    def feed_per_tooth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flutes(self) -> int:
        ...
    @flutes.setter
    def flutes(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def helix(self) -> float:
        ...
    @helix.setter
    def helix(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def inclination(self) -> float:
        ...
    @inclination.setter
    def inclination(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def radius(self) -> float:
        ...
    @radius.setter
    def radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_lambda(self) -> float:
        """
        lambda [rad]
        """
    @runout_lambda.setter
    def runout_lambda(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_rho(self) -> float:
        """
        rho, offset of the tool axis [mm]; flute j cuts at + rho cos(lambda - j 2pi/N)
        """
    @runout_rho.setter
    def runout_rho(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class BallEndWorkspace:
    def __init__(self, model: BallEndModel) -> None:
        ...
    def heights(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def position_angles(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def radii(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def reset(self, model: BallEndModel) -> None:
        ...
    def rows(self) -> int:
        ...
    def widths(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
class LinearEdgeFit:
    @property
    def coefficients(self) -> LinearEdgeCoefficients:
        ...
    @property
    def r2(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def residuals(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
class BallEndFit:
    @property
    def coefficients(self) -> BallEndCoefficients:
        ...
    @property
    def rms_x(self) -> float:
        ...
    @property
    def rms_y(self) -> float:
        ...
class TimeSeriesFit:
    @property
    def coefficients(self) -> LinearEdgeCoefficients:
        ...
    @property
    def phase(self) -> float:
        ...
    @property
    def rms(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        ...
    @property
    def rms_total(self) -> float:
        ...
class ProgramForceOptions:
    """
    Options of simulate_program (sizes [mm], angles [rad]).
    """
    def __init__(self, step: typing.SupportsFloat | typing.SupportsIndex = 0.5, samples_per_revolution: typing.SupportsInt | typing.SupportsIndex = 72, bins: typing.SupportsInt | typing.SupportsIndex = 360, disk_height: typing.SupportsFloat | typing.SupportsIndex = 0.1, element_angle: typing.SupportsFloat | typing.SupportsIndex = 0.0349065850398866, feed_per_tooth: typing.SupportsFloat | typing.SupportsIndex = 0.0, spindle_rpm: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    @property
    def bins(self) -> int:
        ...
    @bins.setter
    def bins(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def disk_height(self) -> float:
        ...
    @disk_height.setter
    def disk_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def element_angle(self) -> float:
        ...
    @element_angle.setter
    def element_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def feed_per_tooth(self) -> float:
        ...
    @feed_per_tooth.setter
    def feed_per_tooth(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def samples_per_revolution(self) -> int:
        ...
    @samples_per_revolution.setter
    def samples_per_revolution(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def spindle_rpm(self) -> float:
        ...
    @spindle_rpm.setter
    def spindle_rpm(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        ...
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def ball_end_coefficient_set(name: str) -> BallEndCoefficientSet:
    ...
def ball_end_coefficient_set_names() -> list[str]:
    ...
def ball_end_forces(model: BallEndModel, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], workspace: BallEndWorkspace = None, engagement_map: EngagementMap = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Forces on the cutter (n, 3) [N] (Fz = 0) at rotation angles (n) [rad].
    """
def ball_end_mean_slot_force(model: BallEndModel) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    ...
def fit_ball_end_mean_forces(geometry: BallEndModel, depths: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], feeds: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mean_fx: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mean_fy: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], m_min: typing.SupportsFloat | typing.SupportsIndex = 0.05, m_max: typing.SupportsFloat | typing.SupportsIndex = 1.5) -> BallEndFit:
    ...
def fit_linear_edge_mean_forces(engagement: AngularEngagement, flutes: typing.SupportsInt | typing.SupportsIndex, axial_depth: typing.SupportsFloat | typing.SupportsIndex, feeds: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], mean_forces: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> LinearEdgeFit:
    ...
def fit_linear_edge_time_series(model: FlatEndModel, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], forces: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], phase_steps: typing.SupportsInt | typing.SupportsIndex = 90) -> TimeSeriesFit:
    ...
def flat_end_forces(model: FlatEndModel, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], workspace: FlatEndWorkspace = None, engagement_map: EngagementMap = None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Forces on the cutter (n, 3) [N] at rotation angles (n) [rad] (flute 1 at the tip).
    """
def flat_end_forces_extended(model: FlatEndModel, extension: RunoutSizeEffect, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    Forces on the cutter (n, 3) [N] at rotation angles (n) [rad] with cutter runout and the chip-size effect (netshape/force/runout_size_effect.hpp).
    """
def flat_end_moments(model: FlatEndModel, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
    ...
def linear_edge_basis(model: FlatEndModel, angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> numpy.typing.NDArray[numpy.float64]:
    """
    (6, n, 3): force per unit ktc, krc, kac, kte, kre, kae
    """
def linear_edge_coefficient_set(name: str) -> LinearEdgeCoefficientSet:
    ...
def linear_edge_coefficient_set_names() -> list[str]:
    ...
def mean_force(coefficients: LinearEdgeCoefficients, engagement: AngularEngagement, feed_per_tooth: typing.SupportsFloat | typing.SupportsIndex, flutes: typing.SupportsInt | typing.SupportsIndex, axial_depth: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    ...
def mean_force_matrix(engagement: AngularEngagement, feed_per_tooth: typing.SupportsFloat | typing.SupportsIndex, flutes: typing.SupportsInt | typing.SupportsIndex, axial_depth: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 6]"]:
    ...
def milling_mode_from_string(text: str) -> MillingMode:
    ...
def resultant(forces: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    ...
def rotation_angles(count: typing.SupportsInt | typing.SupportsIndex, revolutions: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    ...
def simulate_program_core(stock: netshape._core.stock.ZMap, cutter: netshape._core.cutter.Cutter, program: netshape._core.toolpath.Toolpath, linear_edge: LinearEdgeCoefficients = None, ball_end: BallEndCoefficients = None, options: ProgramForceOptions = ..., chip: RunoutSizeEffect = None) -> dict:
    ...
def summarize(forces: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> dict:
    """
    dict: mean (3), peak (3), peak_resultant, mean_resultant, peak_resultant_xy [N]
    """
def summarize_revolutions(angles: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], forces: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> list:
    ...
