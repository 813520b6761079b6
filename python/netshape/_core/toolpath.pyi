"""
Motion blocks, the RS274/NGC reader and writer (C++ netshape::toolpath).
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Block', 'BlockArrays', 'Command', 'CommandKind', 'GcodeReader', 'MotionKind', 'Plane', 'ReaderOptions', 'Summary', 'Toolpath', 'WriterOptions', 'block_bounds', 'chord_count', 'format_gcode', 'max_feed_mm_per_min', 'parse_gcode', 'parse_gcode_arrays', 'read_gcode', 'read_gcode_arrays', 'summarize_gcode', 'summarize_gcode_text']
class MotionKind:
    """
    Kind of motion block (values are the `kind` array codes).
    
    Members:
    
      rapid
    
      line
    
      arc
    """
    __members__: typing.ClassVar[dict[str, MotionKind]]
    arc: typing.ClassVar[MotionKind]
    line: typing.ClassVar[MotionKind]
    rapid: typing.ClassVar[MotionKind]
    @typing.overload
    def __eq__(self, other: MotionKind) -> bool:
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
    def __ne__(self, other: MotionKind) -> bool:
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
class Plane:
    """
    Arc plane: xy (G17), zx (G18), yz (G19).
    
    Members:
    
      xy
    
      zx
    
      yz
    """
    __members__: typing.ClassVar[dict[str, Plane]]
    xy: typing.ClassVar[Plane]
    yz: typing.ClassVar[Plane]
    zx: typing.ClassVar[Plane]
    @typing.overload
    def __eq__(self, other: Plane) -> bool:
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
    def __ne__(self, other: Plane) -> bool:
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
class Block:
    """
    One motion block in program coordinates [mm]; feed in mm/s.
    """
    kind: MotionKind
    plane: Plane
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def curvature(self) -> float:
        """
        curvature [1/mm]
        """
    def length(self) -> float:
        """
        path length [mm]
        """
    def point_at(self, s: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        point at fraction s in [0, 1] [mm]
        """
    def radius(self) -> float:
        """
        arc radius at the start [mm]
        """
    def sweep(self) -> float:
        """
        signed sweep angle [rad] (negative clockwise)
        """
    def tangent_at(self, s: typing.SupportsFloat | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        unit tangent at fraction s
        """
    def validate(self) -> None:
        ...
    @property
    def center(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        arc centre [mm], shape (3,)
        """
    @center.setter
    def center(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def clockwise(self) -> bool:
        """
        arcs: G2 (True) or G3 (False)
        """
    @clockwise.setter
    def clockwise(self, arg0: bool) -> None:
        ...
    @property
    def end(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        end point [mm], shape (3,)
        """
    @end.setter
    def end(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def feed(self) -> float:
        """
        programmed feed [mm/s]
        """
    @feed.setter
    def feed(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def line(self) -> int:
        """
        1-based source line (0 = not from a file)
        """
    @line.setter
    def line(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def spindle_rpm(self) -> float:
        """
        spindle speed [rev/min]; negative for M4, 0 off
        """
    @spindle_rpm.setter
    def spindle_rpm(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def start(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        start point [mm], shape (3,)
        """
    @start.setter
    def start(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def tool(self) -> int:
        ...
    @tool.setter
    def tool(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def turns(self) -> int:
        """
        arcs: number of turns (P word)
        """
    @turns.setter
    def turns(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class CommandKind:
    """
    What a non-motion record is (values are stable).
    
    Members:
    
      comment
    
      word
    
      dwell
    
      work_offset
    
      tool_length
    
      program_end
    """
    __members__: typing.ClassVar[dict[str, CommandKind]]
    comment: typing.ClassVar[CommandKind]
    dwell: typing.ClassVar[CommandKind]
    program_end: typing.ClassVar[CommandKind]
    tool_length: typing.ClassVar[CommandKind]
    word: typing.ClassVar[CommandKind]
    work_offset: typing.ClassVar[CommandKind]
    @typing.overload
    def __eq__(self, other: CommandKind) -> bool:
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
    def __ne__(self, other: CommandKind) -> bool:
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
class Command:
    """
    A non-motion record (comment, M/S/T word, dwell, offset …) placed before block `before`.
    """
    kind: CommandKind
    @typing.overload
    def __init__(self) -> None:
        ...
    @typing.overload
    def __init__(self, before: typing.SupportsInt | typing.SupportsIndex, kind: CommandKind, text: str, value: typing.SupportsFloat | typing.SupportsIndex = 0.0, line: typing.SupportsInt | typing.SupportsIndex = 0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    @property
    def before(self) -> int:
        """
        index of the motion block it precedes (len(blocks): at the end)
        """
    @before.setter
    def before(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def line(self) -> int:
        """
        1-based source line (0 = not from a file)
        """
    @line.setter
    def line(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def text(self) -> str:
        """
        as written out, e.g. 'M8', 'G64 P0.1', 'G4 P0.5', '(finish)'
        """
    @text.setter
    def text(self, arg0: str) -> None:
        ...
    @property
    def value(self) -> float:
        """
        dwell [s], work offset index 0-8, or tool length [mm]
        """
    @value.setter
    def value(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class ReaderOptions:
    """
    Options of the G-code reader (offsets [mm]).
    """
    has_tool_table: bool
    has_work_offsets: bool
    keep_commands: bool
    keep_line_numbers: bool
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def initial_position(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        [mm], program coordinates
        """
    @initial_position.setter
    def initial_position(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"]) -> None:
        ...
    @property
    def max_line_length(self) -> int:
        ...
    @max_line_length.setter
    def max_line_length(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tool_lengths(self) -> dict[int, float]:
        """
        {tool: length along Z [mm]}
        """
    @tool_lengths.setter
    def tool_lengths(self, arg0: collections.abc.Mapping[typing.SupportsInt | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def work_offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[9, 3]"]:
        """
        (9, 3) G54 … G59.3 [mm]
        """
    @work_offsets.setter
    def work_offsets(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[9, 3]"]) -> None:
        ...
class Summary:
    """
    Whole-program figures: counts, lengths [mm], bounding box [mm], times [s].
    """
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def to_dict(self) -> dict:
        """
        Plain dict with unit-suffixed keys (JSON-ready).
        """
    @property
    def arcs(self) -> int:
        ...
    @property
    def bbox_max(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        [mm], shape (3,)
        """
    @property
    def bbox_min(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        [mm], shape (3,)
        """
    @property
    def blocks(self) -> int:
        ...
    @property
    def dwell_time(self) -> float:
        """
        G4 dwell time [s]
        """
    @property
    def dwells(self) -> int:
        ...
    @property
    def feed_length(self) -> float:
        """
        [mm]
        """
    @property
    def feed_time(self) -> float:
        """
        time of feed moves at programmed feed [s]
        """
    @property
    def lines(self) -> int:
        ...
    @property
    def rapid_length(self) -> float:
        """
        [mm]
        """
    @property
    def rapids(self) -> int:
        ...
    @property
    def source_lines(self) -> int:
        ...
    @property
    def total_time(self) -> float:
        """
        feed time + dwell time [s]
        """
    @property
    def warnings(self) -> list[str]:
        ...
class Toolpath:
    """
    A program: its motion blocks in order and the name of its source.
    """
    source: str
    def __getitem__(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> Block:
        ...
    def __init__(self) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def block_offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        (n, 3) float64 offset program → machine at each block [mm]: work_offsets row in force + tool length.
        """
    def sample(self, spacing: typing.SupportsFloat | typing.SupportsIndex, feeds_only: bool = True, chord_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.0001) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
        """
        (points (m, 3) [mm], s (m,) [mm]): points every <= spacing along the moves (feed moves only when feeds_only; arcs as chords within chord_tolerance), s the distance along them.
        """
    def split_arcs(self, chord_tolerance: typing.SupportsFloat | typing.SupportsIndex) -> Toolpath:
        """
        A copy with every arc replaced by chords within chord_tolerance [mm].
        """
    def summary(self) -> Summary:
        ...
    def to_machine(self, offsets: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[9, 3]"]) -> Toolpath:
        """
        A copy in machine coordinates: each block moved by the work offset (rows of offsets, (9, 3) [mm]) and tool length in force; carries offsets as work_offsets.
        """
    def to_program(self) -> Toolpath:
        """
        A copy in program coordinates: each block moved back by the offset in force (work_offsets zero).
        """
    def with_blocks(self, blocks: collections.abc.Sequence[Block], origin: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> Toolpath:
        """
        A copy with new blocks; origin[i] = index of the block new block i came from (commands follow).
        """
    def work_offset_index(self) -> list[int]:
        """
        (n,) index 0…8 (G54…G59.3) of the work offset in force at each block (0 before any G54…).
        """
    @property
    def blocks(self) -> list[Block]:
        """
        list of Block (a copy on each access)
        """
    @blocks.setter
    def blocks(self, arg0: collections.abc.Sequence[Block]) -> None:
        ...
    @property
    def commands(self) -> list[Command]:
        """
        list of Command (a copy on each access)
        """
    @commands.setter
    def commands(self, arg0: collections.abc.Sequence[Command]) -> None:
        ...
    @property
    def dwell_time(self) -> float:
        """
        G4 dwell time [s]
        """
    @dwell_time.setter
    def dwell_time(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def dwells(self) -> int:
        ...
    @dwells.setter
    def dwells(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def warnings(self) -> list[str]:
        ...
    @warnings.setter
    def warnings(self, arg0: collections.abc.Sequence[str]) -> None:
        ...
    @property
    def work_offsets(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[9, 3]"]:
        """
        (9, 3) offsets the blocks include [mm]
        """
    @work_offsets.setter
    def work_offsets(self, arg0: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[9, 3]"]) -> None:
        ...
class BlockArrays:
    """
    A tool path as a structure of arrays (row i = block i); columns are NumPy views.
    """
    @staticmethod
    def from_blocks(blocks: collections.abc.Sequence[Block]) -> BlockArrays:
        ...
    def __init__(self) -> None:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def to_blocks(self) -> list[Block]:
        """
        list of Block
        """
    def to_dict(self) -> dict:
        """
        dict of n-row NumPy views: kind uint8, start/end/center (n, 3) [mm], clockwise bool, plane uint8, turns int32, feed [mm/s], spindle_rpm [rev/min], tool int32, line int64, dwell/dwell_after [s]
        """
    @property
    def warnings(self) -> list[str]:
        ...
class GcodeReader:
    """
    Streaming reader: iterate to get Blocks one at a time.
    """
    @staticmethod
    def from_string(text: str, source: str = '<string>') -> GcodeReader:
        ...
    @staticmethod
    def open(path: str) -> GcodeReader:
        ...
    def __iter__(self) -> GcodeReader:
        ...
    def __next__(self) -> Block:
        ...
    def take_commands(self) -> list[Command]:
        """
        The comments and non-motion commands read so far, and forget them (bounded memory when streaming).
        """
    @property
    def lines_read(self) -> int:
        ...
    @property
    def source(self) -> str:
        ...
    @property
    def warnings(self) -> list[str]:
        ...
class WriterOptions:
    """
    Options of the G-code writer.
    """
    absolute_arc_centers: bool
    header_comment: str
    split_arcs: bool
    def __init__(self) -> None:
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
    def decimals(self) -> int:
        """
        -1: shortest exact form; else fixed decimals
        """
    @decimals.setter
    def decimals(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def work_offset_word(self) -> bool:
        """
        write G54 after the header when no work offset is selected before the first block
        """
    @work_offset_word.setter
    def work_offset_word(self, arg0: bool) -> None:
        ...
def block_bounds(block: Block) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]:
    ...
def chord_count(radius: typing.SupportsFloat | typing.SupportsIndex, sweep: typing.SupportsFloat | typing.SupportsIndex, tol: typing.SupportsFloat | typing.SupportsIndex) -> int:
    ...
def format_gcode(toolpath: Toolpath, options: WriterOptions = ...) -> str:
    ...
def parse_gcode(text: str, source: str = '<string>', options: ReaderOptions = ...) -> Toolpath:
    ...
def parse_gcode_arrays(text: str, source: str = '<string>', split_arcs: bool = False, chord_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.002, options: ReaderOptions = ...) -> BlockArrays:
    ...
def read_gcode(path: str, options: ReaderOptions = ...) -> Toolpath:
    ...
def read_gcode_arrays(path: str, split_arcs: bool = False, chord_tolerance: typing.SupportsFloat | typing.SupportsIndex = 0.002, options: ReaderOptions = ...) -> BlockArrays:
    ...
def summarize_gcode(path: str, options: ReaderOptions = ...) -> Summary:
    ...
def summarize_gcode_text(text: str, source: str = '<string>', options: ReaderOptions = ...) -> Summary:
    ...
max_feed_mm_per_min: float = 100000000.0
