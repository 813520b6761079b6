from __future__ import annotations
import netshape._core.cutter
import netshape._core.toolpath
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Immersion', 'ImmersionOptions', 'SweepOptions', 'SweepStats', 'TipProfile', 'ZMap', 'cutting_frame', 'element_point', 'engaged_elements', 'immersion', 'lowest_reach_line', 'stl_triangle_count', 'sweep', 'sweep_block', 'sweep_line', 'sweep_lines', 'sweep_polyline', 'write_stl']
class ZMap:
    """
    Z-map workpiece: node heights [mm] on a cell-centred grid over [x0, x1] x [y0, y1] [mm].
    """
    @staticmethod
    def from_heights(heights: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], x0: typing.SupportsFloat | typing.SupportsIndex, x1: typing.SupportsFloat | typing.SupportsIndex, y0: typing.SupportsFloat | typing.SupportsIndex, y1: typing.SupportsFloat | typing.SupportsIndex, bottom: typing.SupportsFloat | typing.SupportsIndex) -> ZMap:
        """
        Z-map from an (ny, nx) array of node heights [mm] (copied).
        """
    def __copy__(self) -> ZMap:
        ...
    def __deepcopy__(self, memo: dict) -> ZMap:
        ...
    def __init__(self, x0: typing.SupportsFloat | typing.SupportsIndex, x1: typing.SupportsFloat | typing.SupportsIndex, y0: typing.SupportsFloat | typing.SupportsIndex, y1: typing.SupportsFloat | typing.SupportsIndex, spacing: typing.SupportsFloat | typing.SupportsIndex, top: typing.SupportsFloat | typing.SupportsIndex, bottom: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Flat block: footprint [mm], node spacing at most `spacing` [mm], top and bottom z [mm].
        """
    def __repr__(self) -> str:
        ...
    def cell_height(self, x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        pillar height of the cell holding (x, y) [mm]; NaN outside the footprint
        """
    def cell_height_points(self, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n,) pillar heights
        """
    def copy(self) -> ZMap:
        """
        a deep copy
        """
    def height_at(self, x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        bilinear node height at (x, y) [mm]; NaN outside the footprint
        """
    def height_at_points(self, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        (n,) bilinear heights at (n, 2|3) points
        """
    def height_bound(self, i0: typing.SupportsInt | typing.SupportsIndex, i1: typing.SupportsInt | typing.SupportsIndex) -> float:
        """
        upper bound of the heights of rows i0..i1 [mm] used by the quick reject (>= their maximum)
        """
    def is_material(self, p: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> bool:
        """
        True if p (3,) [mm] is inside the footprint and bottom <= z < pillar height
        """
    def is_material_points(self, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"]) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        (n,) bool for (n, 3) points
        """
    def max_height(self) -> float:
        ...
    def min_height(self) -> float:
        ...
    def node_x(self, j: typing.SupportsInt | typing.SupportsIndex) -> float:
        ...
    def node_y(self, i: typing.SupportsInt | typing.SupportsIndex) -> float:
        ...
    def set_heights(self, heights: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"]) -> None:
        """
        replace all heights ((ny, nx), >= bottom) [mm]
        """
    def volume(self) -> float:
        """
        material volume above the bottom [mm^3]
        """
    @property
    def bottom(self) -> float:
        """
        underside of the stock [mm]
        """
    @property
    def dx(self) -> float:
        """
        cell size along X [mm]
        """
    @property
    def dy(self) -> float:
        """
        cell size along Y [mm]
        """
    @property
    def heights(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (ny, nx) float64 node heights [mm]: a live read-only view (no copy) that follows the sweeps; use .copy() to keep a snapshot
        """
    @property
    def nx(self) -> int:
        ...
    @property
    def ny(self) -> int:
        ...
    @property
    def x0(self) -> float:
        ...
    @property
    def x1(self) -> float:
        ...
    @property
    def y0(self) -> float:
        ...
    @property
    def y1(self) -> float:
        ...
class TipProfile:
    """
    Lower surface g(d) of a cutter above its tip [mm].
    """
    @staticmethod
    def of(cutter: netshape._core.cutter.Cutter) -> TipProfile:
        ...
    def lift(self, d: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    def slope(self, d: typing.SupportsFloat | typing.SupportsIndex) -> float:
        ...
    @property
    def corner_radius(self) -> float:
        ...
    @property
    def flat_radius(self) -> float:
        ...
    @property
    def radius(self) -> float:
        ...
class SweepOptions:
    """
    Options of program sweeps.
    """
    include_rapids: bool
    merge_collinear: bool
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def chord_tolerance(self) -> float:
        """
        [mm] for arcs split into chords
        """
    @chord_tolerance.setter
    def chord_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class SweepStats:
    """
    What a sweep did: counts and removed volume [mm^3].
    """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    @property
    def moves(self) -> int:
        ...
    @property
    def nodes_lowered(self) -> int:
        ...
    @property
    def nodes_visited(self) -> int:
        ...
    @property
    def rapids_cutting(self) -> int:
        ...
    @property
    def removed_volume(self) -> float:
        ...
class ImmersionOptions:
    def __init__(self) -> None:
        ...
    @property
    def angles(self) -> int:
        ...
    @angles.setter
    def angles(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def probe_height(self) -> float:
        """
        [mm]
        """
    @probe_height.setter
    def probe_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class Immersion:
    """
    Radial (phi_st, phi_ex [rad]) and axial [mm] immersion from a Z-map.
    """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        ...
    @property
    def axial_depth(self) -> float:
        ...
    @property
    def engaged(self) -> bool:
        ...
    @property
    def phi_ex(self) -> float:
        ...
    @property
    def phi_st(self) -> float:
        ...
    @property
    def radial_depth(self) -> float:
        ...
def cutting_frame(feed_direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]:
    """
    (X_c, Y_c) unit axes of the cutting frame (docs/conventions.md §2)
    """
def element_point(cutter: netshape._core.cutter.Cutter, tip: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], feed_direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], phi: typing.SupportsFloat | typing.SupportsIndex, z: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    """
    point (3,) [mm] of the element at immersion phi [rad], height z [mm] above the tip
    """
def engaged_elements(zmap: ZMap, cutter: netshape._core.cutter.Cutter, tip: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], feed_direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], phi: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], z: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, n]"]:
    """
    (k, m) bool: element at height z[k] [mm] and angle phi[m] [rad] lies in material
    """
def immersion(zmap: ZMap, cutter: netshape._core.cutter.Cutter, tip: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], feed_direction: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], options: ImmersionOptions = ...) -> Immersion:
    ...
def lowest_reach_line(profile: TipProfile, a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    lowest z [mm] of the tip surface above (x, y) along the line a -> b (inf if never over it)
    """
def stl_triangle_count(zmap: ZMap) -> int:
    ...
def sweep(zmap: ZMap, cutter: netshape._core.cutter.Cutter, program: netshape._core.toolpath.Toolpath, options: SweepOptions = ...) -> SweepStats:
    """
    sweep a whole Toolpath in order
    """
def sweep_block(zmap: ZMap, cutter: netshape._core.cutter.Cutter, block: netshape._core.toolpath.Block, options: SweepOptions = ...) -> SweepStats:
    ...
def sweep_line(zmap: ZMap, cutter: netshape._core.cutter.Cutter, a: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> SweepStats:
    """
    sweep the tip along the line a -> b [mm]
    """
def sweep_lines(zmap: ZMap, cutter: netshape._core.cutter.Cutter, starts: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"], ends: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]", "flags.c_contiguous"]) -> SweepStats:
    """
    sweep the tip along the lines starts[k] -> ends[k] ((n, 3) each [mm]) in order, in one call; the same heights as n sweep_line calls, summed stats
    """
def sweep_polyline(zmap: ZMap, cutter: netshape._core.cutter.Cutter, points: typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]", "flags.c_contiguous"], merge_collinear: bool = True) -> SweepStats:
    """
    sweep the tip along the polyline through (n, 3) points [mm]
    """
def write_stl(zmap: ZMap, path: str) -> None:
    """
    binary STL of the closed solid, written atomically
    """
