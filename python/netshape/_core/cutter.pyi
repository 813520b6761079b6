"""
End mills: flat, ball and bull-nose (C++ netshape::cutter).
"""
from __future__ import annotations
import typing
__all__: list[str] = ['Cutter', 'CutterKind', 'check_flutes', 'cutter_kind_from_string']
class CutterKind:
    """
    Members:
    
      flat
    
      ball
    
      bull
    """
    __members__: typing.ClassVar[dict[str, CutterKind]]
    ball: typing.ClassVar[CutterKind]
    bull: typing.ClassVar[CutterKind]
    flat: typing.ClassVar[CutterKind]
    @typing.overload
    def __eq__(self, other: CutterKind) -> bool:
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
    def __ne__(self, other: CutterKind) -> bool:
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
class Cutter:
    """
    An end mill; lengths [mm], helix [rad], Young's modulus [MPa].
    """
    kind: CutterKind
    @staticmethod
    def ball_end(diameter: typing.SupportsFloat | typing.SupportsIndex, flutes: typing.SupportsInt | typing.SupportsIndex, helix: typing.SupportsFloat | typing.SupportsIndex) -> Cutter:
        ...
    @staticmethod
    def bull_nose(diameter: typing.SupportsFloat | typing.SupportsIndex, corner_radius: typing.SupportsFloat | typing.SupportsIndex, flutes: typing.SupportsInt | typing.SupportsIndex, helix: typing.SupportsFloat | typing.SupportsIndex) -> Cutter:
        ...
    @staticmethod
    def flat_end(diameter: typing.SupportsFloat | typing.SupportsIndex, flutes: typing.SupportsInt | typing.SupportsIndex, helix: typing.SupportsFloat | typing.SupportsIndex) -> Cutter:
        ...
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def diameter(self) -> float:
        """
        [mm]
        """
    def helix_lag(self) -> float:
        """
        tan(helix) / R [rad/mm]
        """
    def radius_at(self, z: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        envelope radius at height z above the tip [mm]
        """
    def validate(self) -> None:
        ...
    @property
    def corner_radius(self) -> float:
        """
        [mm]: flat 0, ball = radius, bull 0 < r < radius
        """
    @corner_radius.setter
    def corner_radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flute_length(self) -> float:
        """
        [mm]
        """
    @flute_length.setter
    def flute_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def flutes(self) -> int:
        ...
    @flutes.setter
    def flutes(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def helix(self) -> float:
        """
        helix angle [rad]
        """
    @helix.setter
    def helix(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def holder_compliance(self) -> float:
        """
        clamp/holder compliance [mm/N]: the tool translates by holder_compliance * F
        """
    @holder_compliance.setter
    def holder_compliance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def radius(self) -> float:
        """
        nominal radius R = D/2 [mm]
        """
    @radius.setter
    def radius(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_lambda(self) -> float:
        """
        runout angle [rad]: flute j cuts at R + rho cos(lambda - j 2 pi / N)
        """
    @runout_lambda.setter
    def runout_lambda(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def runout_rho(self) -> float:
        """
        radial runout, tool-axis offset [mm]
        """
    @runout_rho.setter
    def runout_rho(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stick_out(self) -> float:
        """
        holder face to tip [mm]
        """
    @stick_out.setter
    def stick_out(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def youngs_modulus(self) -> float:
        """
        [MPa]
        """
    @youngs_modulus.setter
    def youngs_modulus(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def check_flutes(flutes: typing.SupportsInt | typing.SupportsIndex, field: str = 'flutes') -> None:
    """
    ValueError 'field = N: must be between 1 and 64' unless 1 <= flutes <= 64 (the one flute-count check)
    """
def cutter_kind_from_string(name: str) -> CutterKind:
    ...
