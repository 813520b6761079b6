"""netshape.toolpath — motion blocks and RS274/NGC G-code reading and writing (C++ netshape::toolpath).

Units: mm, mm/s (G-code ``F`` is mm/min or in/min and is converted), s, rev/min.

    import netshape as ns
    tp = ns.toolpath.read_gcode("part.ngc")             # Toolpath (list of Block)
    arrays = ns.toolpath.read_gcode_arrays("part.ngc")  # dict of NumPy arrays, no per-block objects
    print(ns.toolpath.summary("part.ngc").to_dict())    # streaming, bounded memory
"""

from __future__ import annotations

import os
from typing import Literal

from ._atomic import atomic_write
from ._core import toolpath as _tp

Block = _tp.Block
Toolpath = _tp.Toolpath
Summary = _tp.Summary
MotionKind = _tp.MotionKind
Plane = _tp.Plane
GcodeReader = _tp.GcodeReader
WriterOptions = _tp.WriterOptions
chord_count = _tp.chord_count
block_bounds = _tp.block_bounds

#: Names of the ``kind`` codes in :func:`read_gcode_arrays` (index = code).
KIND_NAMES = ("rapid", "line", "arc")


def _path(path: str | os.PathLike) -> str:
    p = os.fspath(path)
    if not isinstance(p, str):
        p = os.fsdecode(p)
    if not os.path.exists(p):
        raise FileNotFoundError(2, "No such file or directory", p)
    if os.path.isdir(p):
        raise IsADirectoryError(21, "Is a directory", p)
    return p


def _arcs_mode(arcs: str, chord_tolerance: float) -> bool:
    if arcs not in ("keep", "split"):
        raise ValueError(f"arcs = {arcs!r}: must be 'keep' or 'split'")
    tol = float(chord_tolerance)
    if not (tol > 0.0 and tol < float("inf")):
        raise ValueError(f"chord_tolerance = {chord_tolerance!r}: must be a positive number [mm]")
    return arcs == "split"


def read_gcode(
    path: str | os.PathLike,
    *,
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
) -> Toolpath:
    """Read an RS274/NGC program into a :class:`Toolpath`.

    Parameters
    ----------
    path : program file.
    arcs : ``"keep"`` (G2/G3 stay arcs) or ``"split"`` (arcs become G1 chords).
    chord_tolerance : largest chord error when splitting arcs [mm].

    Raises
    ------
    netshape.ParseError
        (a ``ValueError``) with ``source``, ``line``, ``column`` for bad or unsupported G-code.
    """
    split = _arcs_mode(arcs, chord_tolerance)
    tp = _tp.read_gcode(_path(path))
    return tp.split_arcs(float(chord_tolerance)) if split else tp


def parse_gcode(
    text: str,
    *,
    source: str = "<string>",
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
) -> Toolpath:
    """Parse program text (see :func:`read_gcode`); ``source`` names it in error messages."""
    split = _arcs_mode(arcs, chord_tolerance)
    tp = _tp.parse_gcode(text, source)
    return tp.split_arcs(float(chord_tolerance)) if split else tp


def read_gcode_arrays(
    path: str | os.PathLike,
    *,
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
) -> dict:
    """Read a program straight into NumPy arrays (filled in C++, no per-block Python objects).

    Returns a dict of n-row arrays: ``kind`` uint8 (0 rapid, 1 line, 2 arc; see KIND_NAMES),
    ``start``, ``end``, ``center`` float64 (n, 3) [mm], ``clockwise`` bool, ``plane`` uint8 (0 xy,
    1 zx, 2 yz), ``turns`` int32, ``feed`` float64 [mm/s], ``spindle_rpm`` float64 [rev/min, negative
    for M4], ``tool`` int32, ``line`` int64 (1-based source line).
    """
    split = _arcs_mode(arcs, chord_tolerance)
    return _tp.read_gcode_arrays(_path(path), split, float(chord_tolerance))


def parse_gcode_arrays(
    text: str,
    *,
    source: str = "<string>",
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
) -> dict:
    """Like :func:`read_gcode_arrays` for program text."""
    split = _arcs_mode(arcs, chord_tolerance)
    return _tp.parse_gcode_arrays(text, source, split, float(chord_tolerance))


def summary(path: str | os.PathLike) -> Summary:
    """Counts, lengths [mm], exact bounding box [mm] and time at programmed feed [s] of a program
    file, computed while streaming it (memory does not grow with the program's length)."""
    return _tp.summarize_gcode(_path(path))


def summary_of_text(text: str, *, source: str = "<string>") -> Summary:
    """:func:`summary` of program text."""
    return _tp.summarize_gcode_text(text, source)


def iter_gcode(path: str | os.PathLike) -> GcodeReader:
    """Iterate over the blocks of a program file one at a time (streaming)."""
    return GcodeReader.open(_path(path))


def format_gcode(
    toolpath: Toolpath,
    *,
    split_arcs: bool = False,
    chord_tolerance: float = 0.002,
    decimals: int = -1,
    absolute_arc_centers: bool = False,
    header_comment: str = "",
) -> str:
    """G-code text of ``toolpath`` (mm, G90, modal; see :func:`write_gcode`)."""
    opt = WriterOptions()
    opt.split_arcs = bool(split_arcs)
    opt.chord_tolerance = float(chord_tolerance)
    opt.decimals = int(decimals)
    opt.absolute_arc_centers = bool(absolute_arc_centers)
    opt.header_comment = str(header_comment)
    return _tp.format_gcode(toolpath, opt)


def write_gcode(
    toolpath: Toolpath,
    path: str | os.PathLike,
    *,
    split_arcs: bool = False,
    chord_tolerance: float = 0.002,
    decimals: int = -1,
    absolute_arc_centers: bool = False,
    header_comment: str = "",
) -> None:
    """Write ``toolpath`` as G-code to ``path``, whole or not at all (temporary file + rename).

    Header ``G21 G90 G17 G94 G91.1``; one line per block with only the words that change; F in
    mm/min; arcs as G2/G3 with I/J/K centre offsets (or G90.1 absolute centres), or as G1 chords
    within ``chord_tolerance`` [mm] when ``split_arcs``. ``decimals=-1`` writes the shortest numbers
    that read back exactly, so read -> write -> read gives the same blocks.
    """
    text = format_gcode(
        toolpath,
        split_arcs=split_arcs,
        chord_tolerance=chord_tolerance,
        decimals=decimals,
        absolute_arc_centers=absolute_arc_centers,
        header_comment=header_comment,
    )
    with atomic_write(path, "w") as fh:
        fh.write(text)


__all__ = [
    "Block",
    "GcodeReader",
    "KIND_NAMES",
    "MotionKind",
    "Plane",
    "Summary",
    "Toolpath",
    "WriterOptions",
    "block_bounds",
    "chord_count",
    "format_gcode",
    "iter_gcode",
    "parse_gcode",
    "parse_gcode_arrays",
    "read_gcode",
    "read_gcode_arrays",
    "summary",
    "summary_of_text",
    "write_gcode",
]
