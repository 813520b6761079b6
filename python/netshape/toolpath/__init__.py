"""netshape.toolpath — motion blocks and RS274/NGC G-code reading and writing (C++ netshape::toolpath).

Units: mm, mm/s (G-code ``F`` is mm/min or in/min and is converted), s, rev/min.

    import netshape as ns
    tp = ns.toolpath.read_gcode("part.ngc")             # Toolpath (list of Block)
    arrays = ns.toolpath.read_gcode_arrays("part.ngc")  # dict of NumPy arrays, no per-block objects
    print(ns.toolpath.summary("part.ngc").to_dict())    # streaming, bounded memory
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping
from typing import Any, Literal

import numpy as np

from .._atomic import atomic_write
from .._core import toolpath as _tp

Block = _tp.Block
Toolpath = _tp.Toolpath
Summary = _tp.Summary
MotionKind = _tp.MotionKind
Plane = _tp.Plane
GcodeReader = _tp.GcodeReader
WriterOptions = _tp.WriterOptions
ReaderOptions = _tp.ReaderOptions
Command = _tp.Command
CommandKind = _tp.CommandKind
chord_count = _tp.chord_count
#: Largest feed the writer writes, F [mm/min] (C++ ``max_feed_mm_per_min``).
max_feed_mm_per_min = float(_tp.max_feed_mm_per_min)
block_bounds = _tp.block_bounds

#: Names of the ``kind`` codes in :func:`read_gcode_arrays` (index = code).
KIND_NAMES = ("rapid", "line", "arc")

#: Work offset codes in row order of ``work_offsets`` arrays (LinuxCNC parameters 5221 + 20·row).
WORK_OFFSET_CODES = ("G54", "G55", "G56", "G57", "G58", "G59", "G59.1", "G59.2", "G59.3")


class GcodeWarning(UserWarning):
    """A program uses a work offset or tool length that was not given (taken as zero)."""


def read_var_file(path: str | os.PathLike) -> np.ndarray:
    """Work offsets G54 … G59.3 from a LinuxCNC parameter file (``.var``: lines ``number value``).

    Returns a (9, 3) array [mm] (rows in :data:`WORK_OFFSET_CODES` order; parameters 5221–5223 for
    G54, +20 for each next system). Parameters not in the file are 0. Refused with ValueError naming
    the line: malformed lines, a rotation (XY rotation parameter 5230 + 20·row non-zero), or an active
    G92 offset (5210 = 1 with a non-zero 5211–5213), which change geometry this reader does not model.
    """
    from netshape._text import read_controller_text

    p = _path(path)
    values: dict[int, float] = {}
    for i, raw in enumerate(read_controller_text(p).splitlines(), 1):
        text = raw.split(";")[0].split("#")[0].strip()
        if not text:
            continue
        parts = text.split()
        try:
            num, val = int(parts[0]), float(parts[1])
        except (ValueError, IndexError):
            raise ValueError(f"{p}:{i}: {raw.strip()!r}: expected 'parameter value'") from None
        if not math.isfinite(val):
            raise ValueError(f"{p}:{i}: parameter {num} = {parts[1]}: must be a finite number")
        values[num] = val
    out = np.zeros((9, 3))
    for row, code in enumerate(WORK_OFFSET_CODES):
        base = 5221 + 20 * row
        out[row] = [values.get(base + k, 0.0) for k in range(3)]
        rot = values.get(base + 9, 0.0)
        if rot != 0.0:
            raise ValueError(f"{p}: parameter {base + 9} = {rot:g}: {code} XY rotation is not supported")
    if values.get(5210, 0.0) != 0.0 and any(values.get(5211 + k, 0.0) != 0.0 for k in range(3)):
        raise ValueError(f"{p}: parameters 5210-5213: an active G92 offset is not supported")
    cs = values.get(5220, 1.0)
    if cs != 1.0:
        warnings.warn(f"{p}: parameter 5220 = {cs:g} (current coordinate system) is not used: programs "
                      "are read starting in G54", GcodeWarning, stacklevel=2)
    return out


def read_tool_table(path: str | os.PathLike) -> dict[int, float]:
    """Tool lengths [mm] by tool number from a LinuxCNC tool table (lines ``T1 P1 D10 Z120.5 ;comment``:
    ``T`` the tool number, ``Z`` its length offset; a tool without ``Z`` has length 0). Refused with
    ValueError naming the line: a line without ``T``, a malformed word, or a tool given twice."""
    from netshape._text import read_controller_text

    p = _path(path)
    out: dict[int, float] = {}
    for i, raw in enumerate(read_controller_text(p).splitlines(), 1):
        text = raw.split(";")[0].strip()
        if not text:
            continue
        words: dict[str, float] = {}
        for w in text.split():
            try:
                words[w[0].upper()] = float(w[1:])
            except (ValueError, IndexError):
                raise ValueError(f"{p}:{i}: word {w!r}: expected a letter and a number") from None
        t = words.get("T")
        if t is None or t < 0 or t != int(t):
            raise ValueError(f"{p}:{i}: {raw.strip()!r}: needs T with a non-negative tool number")
        z = words.get("Z", 0.0)
        if not math.isfinite(z):
            raise ValueError(f"{p}:{i}: Z = {z}: must be a finite length [mm]")
        if int(t) in out:
            raise ValueError(f"{p}:{i}: tool T{int(t)} is given twice")
        out[int(t)] = z
    return out


def reader_options(work_offsets: Any = None, tool_table: Any = None, line_numbers: bool = False) -> ReaderOptions:
    """ReaderOptions with work offsets and tool lengths applied.

    work_offsets : None, a LinuxCNC ``.var`` path (:func:`read_var_file`), a (9, 3) array [mm] in
        :data:`WORK_OFFSET_CODES` order, or a mapping ``{"G55": (x, y, z)}`` (others 0).
    tool_table : None, a LinuxCNC tool table path (:func:`read_tool_table`) or ``{tool: length_mm}``.
    line_numbers : keep N words as commands ("N10").
    """
    o = ReaderOptions()
    o.keep_line_numbers = bool(line_numbers)
    if work_offsets is not None:
        if isinstance(work_offsets, (str, os.PathLike)):
            w = read_var_file(work_offsets)
        elif isinstance(work_offsets, Mapping):
            w = np.zeros((9, 3))
            for code, xyz in work_offsets.items():
                c = str(code).upper()
                if c not in WORK_OFFSET_CODES:
                    raise ValueError(f"work_offsets key {code!r}: must be one of {', '.join(WORK_OFFSET_CODES)}")
                w[WORK_OFFSET_CODES.index(c)] = np.asarray(xyz, dtype=float).reshape(3)
        else:
            w = np.asarray(work_offsets, dtype=float)
            if w.shape != (9, 3):
                raise ValueError(f"work_offsets shape = {w.shape}: must be (9, 3) [mm] (G54 ... G59.3)")
        if not np.all(np.isfinite(w)):
            raise ValueError("work_offsets: must be finite numbers [mm]")
        o.has_work_offsets = True
        o.work_offsets = w
    if tool_table is not None:
        t = read_tool_table(tool_table) if isinstance(tool_table, (str, os.PathLike)) else dict(tool_table)
        o.has_tool_table = True
        o.tool_lengths = {int(k): float(v) for k, v in t.items()}
    o.validate()
    return o


def _warn(messages) -> None:
    for m in messages:
        warnings.warn(m, GcodeWarning, stacklevel=3)


def _path(path: str | os.PathLike) -> str:
    p = os.fspath(path)
    if not isinstance(p, str):
        p = os.fsdecode(p)
    if not os.path.exists(p):
        raise FileNotFoundError(2, "No such file or directory", p)
    if os.path.isdir(p):
        raise IsADirectoryError(21, "Is a directory", p)
    return p


def gcode_encoding(path: str | os.PathLike) -> str:
    """``"utf-8"`` when the program file is UTF-8 (or ASCII), else ``"latin-1"``: G-code words are ASCII,
    so only comments can hold other bytes, and a program that is not UTF-8 is read with its comments as
    Latin-1 (ISO 8859-1, one character per byte). Writers given this encoding put every comment back
    byte for byte."""
    with open(_path(path), "rb") as fh:
        data = fh.read()
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return "latin-1"
    return "utf-8"


def _read_latin1(path: str) -> str | None:
    """The program text decoded as Latin-1 when the file is not UTF-8; None when it is UTF-8."""
    with open(path, "rb") as fh:
        data = fh.read()
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        return data.decode("latin-1")
    return None


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
    work_offsets: Any = None,
    tool_table: Any = None,
    line_numbers: bool = False,
) -> Toolpath:
    """Read an RS274/NGC program into a :class:`Toolpath`: motion blocks, and every comment and
    non-motion word (M, S, T, G4 dwells, G43/G49, G54-G59.3, G61/G64, G40, G80 ...) as
    :class:`Command` records at their place among the blocks (``tp.commands``).

    Parameters
    ----------
    path : program file.
    arcs : ``"keep"`` (G2/G3 stay arcs) or ``"split"`` (arcs become G1 chords).
    chord_tolerance : largest chord error when splitting arcs [mm].
    work_offsets, tool_table : see :func:`reader_options`. When given, blocks are in machine axis
        positions (program + work offset + tool length along Z); when a program selects a work offset
        or a tool length that was not given, it is taken as zero and a :class:`GcodeWarning` names
        the line (once per kind).
    line_numbers : also keep N words as commands (``"N10"``; the writer puts each on its own line).

    Raises
    ------
    netshape.ParseError
        (a ``ValueError``) with ``source``, ``line``, ``column`` for bad or unsupported G-code.
    """
    split = _arcs_mode(arcs, chord_tolerance)
    p = _path(path)
    latin1 = _read_latin1(p)
    opts = reader_options(work_offsets, tool_table, line_numbers)
    tp = _tp.read_gcode(p, opts) if latin1 is None else _tp.parse_gcode(latin1, p, opts)
    _warn(tp.warnings)
    return tp.split_arcs(float(chord_tolerance)) if split else tp


def parse_gcode(
    text: str,
    *,
    source: str = "<string>",
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
    work_offsets: Any = None,
    tool_table: Any = None,
    line_numbers: bool = False,
) -> Toolpath:
    """Parse program text (see :func:`read_gcode`); ``source`` names it in error messages."""
    split = _arcs_mode(arcs, chord_tolerance)
    tp = _tp.parse_gcode(text, source, reader_options(work_offsets, tool_table, line_numbers))
    _warn(tp.warnings)
    return tp.split_arcs(float(chord_tolerance)) if split else tp


def read_gcode_arrays(
    path: str | os.PathLike,
    *,
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
    work_offsets: Any = None,
    tool_table: Any = None,
) -> dict:
    """Read a program straight into NumPy arrays (filled in C++, no per-block Python objects).

    Returns a dict of n-row arrays: ``kind`` uint8 (0 rapid, 1 line, 2 arc; see KIND_NAMES),
    ``start``, ``end``, ``center`` float64 (n, 3) [mm], ``clockwise`` bool, ``plane`` uint8 (0 xy,
    1 zx, 2 yz), ``turns`` int32, ``feed`` float64 [mm/s], ``spindle_rpm`` float64 [rev/min, negative
    for M4], ``tool`` int32, ``line`` int64 (1-based source line), ``dwell`` float64 [s] (G4 dwell
    time executed before block i), ``dwell_after`` float64 [s] (dwell after block i that precedes no
    other block: only the last entry can be non-zero); their sum is the program's dwell time. ``work_offsets``, ``tool_table``: see :func:`read_gcode`.
    """
    split = _arcs_mode(arcs, chord_tolerance)
    a = _tp.read_gcode_arrays(_path(path), split, float(chord_tolerance), reader_options(work_offsets, tool_table))
    _warn(a.warnings)
    return a.to_dict()


def parse_gcode_arrays(
    text: str,
    *,
    source: str = "<string>",
    arcs: Literal["keep", "split"] = "keep",
    chord_tolerance: float = 0.002,
    work_offsets: Any = None,
    tool_table: Any = None,
) -> dict:
    """Like :func:`read_gcode_arrays` for program text."""
    split = _arcs_mode(arcs, chord_tolerance)
    a = _tp.parse_gcode_arrays(text, source, split, float(chord_tolerance), reader_options(work_offsets, tool_table))
    _warn(a.warnings)
    return a.to_dict()


def summary(path: str | os.PathLike, *, work_offsets: Any = None, tool_table: Any = None) -> Summary:
    """Counts, lengths [mm], exact bounding box [mm], time at programmed feed and G4 dwell time [s]
    of a program file, computed while streaming it (memory does not grow with the program's length).
    Offsets as in :func:`read_gcode` (warnings in ``.warnings`` and as :class:`GcodeWarning`)."""
    s = _tp.summarize_gcode(_path(path), reader_options(work_offsets, tool_table))
    _warn(s.warnings)
    return s


def summary_of_text(text: str, *, source: str = "<string>", work_offsets: Any = None,
                    tool_table: Any = None) -> Summary:
    """:func:`summary` of program text."""
    s = _tp.summarize_gcode_text(text, source, reader_options(work_offsets, tool_table))
    _warn(s.warnings)
    return s


def non_motion(toolpath: Toolpath) -> list[tuple[int, str]]:
    """The program's non-motion records as ``(before, text)`` pairs in order (what a lossless
    transform must keep: same texts, same order, same place among the motion blocks)."""
    return [(c.before, c.text) for c in toolpath.commands]


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
    encoding: str = "utf-8",
) -> None:
    """Write ``toolpath`` as G-code to ``path``, whole or not at all (temporary file + rename).

    Header ``G21 G90 G17 G94 G91.1``; every command (comment, M/S/T word, dwell, offset ...) on its own
    line before the block it precedes; one line per block with only the words that change; F in
    mm/min rounded to 1e-6; arcs as G2/G3 with I/J/K centre offsets (or G90.1 absolute centres), or as
    G1 chords within ``chord_tolerance`` [mm] when ``split_arcs``; the program's own M2/M30, else M2.
    Coordinates are written in program coordinates (the tool path's work offsets and tool lengths in
    force subtracted). ``decimals=-1`` writes the shortest numbers that read back exactly, so read ->
    write -> read gives the same blocks and the same commands. ``encoding``: that of the program the
    tool path was read from (:func:`gcode_encoding`), so its comments are written back byte for byte.
    """
    text = format_gcode(
        toolpath,
        split_arcs=split_arcs,
        chord_tolerance=chord_tolerance,
        decimals=decimals,
        absolute_arc_centers=absolute_arc_centers,
        header_comment=header_comment,
    )
    with atomic_write(path, "w", encoding=encoding, errors="replace") as fh:
        fh.write(text)


def block_lengths(arrays: Mapping[str, Any]) -> np.ndarray:
    """Path length of every row of block arrays (:func:`read_gcode_arrays`) [mm], shape (n,): lines and
    rapids their chord, arcs their helix (radius at the start, sweep with ``turns``), cubic rows (kind 3)
    their chord (a lower bound). Used to size work before it starts."""
    start, end = np.asarray(arrays["start"], float), np.asarray(arrays["end"], float)
    out = np.linalg.norm(end - start, axis=1)
    kind = np.asarray(arrays["kind"])
    arc = np.flatnonzero(kind == 2)
    if arc.size:
        axes = np.array([[0, 1, 2], [2, 0, 1], [1, 2, 0]])[np.asarray(arrays["plane"])[arc]]  # a, b, normal
        rows = np.arange(arc.size)[:, None]
        s, e, c = start[arc][rows, axes], end[arc][rows, axes], np.asarray(arrays["center"], float)[arc][rows, axes]
        a0 = np.arctan2(s[:, 1] - c[:, 1], s[:, 0] - c[:, 0])
        a1 = np.arctan2(e[:, 1] - c[:, 1], e[:, 0] - c[:, 0])
        cw = np.asarray(arrays["clockwise"], bool)[arc]
        sweep = np.where(cw, a0 - a1, a1 - a0) % (2 * np.pi)
        sweep = np.where(sweep <= 1e-12, 2 * np.pi, sweep) + 2 * np.pi * (np.asarray(arrays["turns"])[arc] - 1)
        r = np.hypot(s[:, 0] - c[:, 0], s[:, 1] - c[:, 1])
        out[arc] = np.hypot(r * sweep, e[:, 2] - s[:, 2])
    return out


__all__ = [
    "Block",
    "Command",
    "CommandKind",
    "GcodeReader",
    "GcodeWarning",
    "ReaderOptions",
    "WORK_OFFSET_CODES",
    "KIND_NAMES",
    "MotionKind",
    "Plane",
    "Summary",
    "Toolpath",
    "WriterOptions",
    "block_bounds",
    "block_lengths",
    "chord_count",
    "max_feed_mm_per_min",
    "format_gcode",
    "gcode_encoding",
    "iter_gcode",
    "non_motion",
    "parse_gcode",
    "parse_gcode_arrays",
    "read_gcode",
    "read_gcode_arrays",
    "read_tool_table",
    "read_var_file",
    "reader_options",
    "summary",
    "summary_of_text",
    "write_gcode",
]
