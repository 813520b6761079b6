"""Volumetric compensation (Yang & Kweon §4.2): commanded points and G-code programs such that the
actual tool tip of a machine with geometric errors lands on the nominal path.

    m = ns.machine.load_machine("machine.toml")
    cmd = ns.compensation.compensate_points(m, nominal)               # (n, 3) mm
    report = ns.compensation.compensate_gcode(m, "part.ngc", "part_comp.ngc", chord_tolerance=0.002)

The post-processor reads the program with netshape.toolpath (arcs kept) and runs C++
``netshape::compensation::compensate_program`` on it, which compensates every block end point to
``tolerance`` (1e-9 mm), rewrites lines as one or more G1 moves so that the actual path
between compensated points stays within ``chord_tolerance`` of the nominal line (checked at ¼, ½,
¾ of every output segment, adaptive halving), keeps an arc as a (moved) arc where its actual path
stays within ``chord_tolerance`` of the nominal arc and otherwise rewrites it as compensated chords,
and carries the modal state (feed, spindle, tool) of each source block. Every comment and
non-motion word of the program (M codes, S, T, G4 dwells, G43/G49, G54-G59.3, G61/G64 P Q, G40, G80,
M2/M30 ...) is written in the same order and at the same place among the moves: a command that
preceded source block i precedes the first output move of block i. A compensated point outside
an axis' travel is refused with a ValueError naming the source line and the axis. Output is written
whole or not at all (the writer's header is G21 G90 G17 G94 G91.1). With ``work_offsets`` /
``tool_table`` the blocks are machine axis positions (what the error model is indexed by) and the
output is written back in program coordinates.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._atomic import atomic_write
from .._core import compensation as _c
from .._core import machine as _m

AXES = "XYZ"


def _options(tolerance: float, max_iterations: int, check_travel: bool):
    return _c.VolumetricOptions(float(tolerance), int(max_iterations), bool(check_travel))


def _points(points: Any) -> np.ndarray:
    p = np.ascontiguousarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"nominal shape = {p.shape}: must be (n, 3) [mm]")
    return p


def compensate_points(machine: _m.Machine, nominal: Any, tolerance: float = 1e-9, max_iterations: int = 50,
                      check_travel: bool = True) -> np.ndarray:
    """Commanded points (n, 3) [mm] whose actual tip position equals ``nominal`` (n, 3) [mm] to
    ``tolerance`` [mm]. Raises ValueError (outside travel or a table) or netshape.Error (no
    convergence) naming the point."""
    return _c.compensate_points(machine, _points(nominal), _options(tolerance, max_iterations, check_travel))


def compensate_points_status(machine: _m.Machine, nominal: Any, tolerance: float = 1e-9,
                             max_iterations: int = 50, check_travel: bool = True):
    """Like :func:`compensate_points` but never raises per point: returns a VolumetricResult with
    ``commanded``, ``residual``, ``iterations``, ``status`` (0 ok, 1 not converged, 2 outside travel,
    3 outside a table) and ``axis``."""
    return _c.compensate_points_status(machine, _points(nominal),
                                       _options(tolerance, max_iterations, check_travel))


@dataclass
class ProgramReport:
    """What :func:`compensate_program` did."""

    source: str
    blocks_in: int = 0
    blocks_out: int = 0
    lines_split: int = 0
    arcs_kept: int = 0
    arcs_split: int = 0
    max_correction_mm: float = 0.0
    max_residual_mm: float = 0.0
    max_path_deviation_mm: float = 0.0
    commands: int = 0  # comments and non-motion words carried over (all of the program's)
    extra: dict = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {k: v for k, v in self.__dict__.items() if k != "extra"} | self.extra


def compensate_program(machine: _m.Machine, program: Any, chord_tolerance: float = 0.002,
                       tolerance: float = 1e-9, *, work_offsets: Any = None, tool_table: Any = None,
                       block_times: Any = None):
    """Compensate a program (path or netshape.toolpath.Toolpath). Returns (Toolpath, ProgramReport).
    See the module docstring for what happens to lines, arcs, modal state and commands (the work is
    C++ ``netshape::compensation::compensate_program``).
    ``work_offsets`` / ``tool_table``: see :func:`netshape.toolpath.read_gcode` (path input only).
    ``block_times``: program time at each block's end [s] for a machine with thermal drift (a feed
    plan's time stamps); default: from the programmed feeds (``_core.compensation.block_end_times``).
    A machine with backlash gets take-up moves at reversals (``extra["takeup_moves"]``)."""
    from .. import toolpath as tpm

    options = _c.ProgramOptions(float(chord_tolerance), _options(tolerance, 50, True))
    if isinstance(program, (str, os.PathLike)):
        source = os.fspath(program)
        tp = tpm.read_gcode(program, arcs="keep", work_offsets=work_offsets, tool_table=tool_table)
        if tp.source != source:
            tp.source = source
    else:
        if work_offsets is not None or tool_table is not None:
            raise ValueError("work_offsets / tool_table apply when reading a program path; a Toolpath "
                             "already carries its offsets")
        tp = program
        source = getattr(tp, "source", "") or "<program>"
    if block_times is not None:
        options.block_times = [float(t) for t in np.asarray(block_times, dtype=float).reshape(-1)]
    out, rep = _c.compensate_program(machine, tp, options)
    report = ProgramReport(source=source, blocks_in=rep.blocks_in, blocks_out=rep.blocks_out,
                           lines_split=rep.lines_split, arcs_kept=rep.arcs_kept, arcs_split=rep.arcs_split,
                           max_correction_mm=rep.max_correction, max_residual_mm=rep.max_residual,
                           max_path_deviation_mm=rep.max_path_deviation, commands=rep.commands)
    if rep.takeup_moves:
        report.extra["takeup_moves"] = rep.takeup_moves
    return out, report


def estimate_chords(machine: _m.Machine, arrays: dict, chord_tolerance: float) -> float:
    """About how many output moves :func:`compensate_program` writes for block arrays (read with arcs
    kept; machine axis positions) at ``chord_tolerance`` [mm], computed before the work from a few
    error evaluations per block: a line whose actual path leaves the nominal one by d at its middle
    needs about √(d / tol) pieces (the deviation of a piece falls with the square of its length); an arc
    that is split becomes chords within tol / 2 (r·(1 − cos(θ/2)) per chord). Rapids count once."""
    kind = np.asarray(arrays["kind"])
    start, end = np.asarray(arrays["start"], float), np.asarray(arrays["end"], float)
    tol = float(chord_tolerance)
    if len(kind) == 0:
        return 0.0
    mid = 0.5 * (start + end)
    pts = np.vstack([start, mid, end])
    if not np.isfinite(pts).all():
        return float(len(kind))  # the compensation refuses these points itself
    e = np.asarray(_m.tip_error(machine, pts, _m.Order.exact))
    n = len(kind)
    ea, em, eb = e[:n], e[n:2 * n], e[2 * n:]
    dev = np.linalg.norm(em - 0.5 * (ea + eb), axis=1)
    with np.errstate(over="ignore", invalid="ignore"):
        pieces = np.maximum(1.0, np.ceil(np.sqrt(dev / tol)))
    arc = np.flatnonzero(kind == 2)
    if arc.size:
        from ..toolpath import block_lengths

        axes = np.array([[0, 1], [2, 0], [1, 2]])[np.asarray(arrays["plane"])[arc]]
        rows = np.arange(arc.size)[:, None]
        c = np.asarray(arrays["center"], float)[arc][rows, axes]
        r = np.hypot(*(start[arc][rows, axes] - c).T)
        length = block_lengths(arrays)[arc]
        sweep = np.where(r > 0, length / np.maximum(r, 1e-300), 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            theta = np.where(0.5 * tol >= r, 0.5 * np.pi, 2.0 * np.arccos(1.0 - 0.5 * tol / r))
            chords = np.where(sweep > 0, np.ceil(sweep / theta), 1.0)
        pieces[arc] = np.where(dev[arc] > tol, np.maximum(chords, pieces[arc]), 1.0)
    pieces[kind == 0] = 1.0
    return float(np.sum(pieces))


def compensate_gcode(machine: _m.Machine, program: str | os.PathLike, output: str | os.PathLike,
                     chord_tolerance: float = 0.002, tolerance: float = 1e-9, *, work_offsets: Any = None,
                     tool_table: Any = None) -> ProgramReport:
    """Read ``program``, compensate it (:func:`compensate_program`) and write G-code to ``output``
    (whole or not at all; the first line is a comment naming the source and the machine, then the
    program's own commands and the compensated moves). Returns the report."""
    from .. import toolpath as tpm

    tp, report = compensate_program(machine, program, chord_tolerance, tolerance, work_offsets=work_offsets,
                                    tool_table=tool_table)
    text = tpm.format_gcode(tp, header_comment=f"netshape volumetric compensation of {os.path.basename(os.fspath(program))} "
                            f"for machine {machine.name}, chord tolerance {chord_tolerance:g} mm")
    encoding = tpm.gcode_encoding(program)
    with atomic_write(output, "w", encoding=encoding, errors="replace") as fh:
        fh.write(text)
    return report
