"""Volumetric compensation (Yang & Kweon §4.2): commanded points and G-code programs such that the
actual tool tip of a machine with geometric errors lands on the nominal path.

    m = ns.machine.load_machine("machine.toml")
    cmd = ns.compensation.compensate_points(m, nominal)               # (n, 3) mm
    report = ns.compensation.compensate_gcode(m, "part.ngc", "part_comp.ngc", chord_tolerance=0.002)

The post-processor reads the program with netshape.toolpath (arcs kept), compensates every block
end point to ``tolerance`` (1e-9 mm), rewrites lines as one or more G1 moves so that the actual path
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

import math
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


def _fail(machine, res, idx: int, nominal: np.ndarray, lines: np.ndarray, source: str,
          tolerance: float) -> None:
    st = int(res.status[idx])
    line = int(lines[idx])
    where = f"{source}:{line}" if line > 0 else source
    p = nominal[idx]
    pt = f"({p[0]:.6g}, {p[1]:.6g}, {p[2]:.6g}) mm"
    if st == int(_c.VolumetricStatus.outside_travel):
        k = int(res.axis[idx])
        a = machine.axes[k]
        q = float(res.commanded[idx][k])
        raise ValueError(f"{where}: compensated axis {AXES[k]} = {q:.6f} mm is outside its travel "
                         f"[{a.travel_min:g}, {a.travel_max:g}] mm (nominal point {pt})")
    if st == int(_c.VolumetricStatus.outside_table):
        try:
            _m.tip_error(machine, np.ascontiguousarray(res.commanded[idx:idx + 1]))
            why = "an error table was left"
        except ValueError as exc:
            why = str(exc)
        raise ValueError(f"{where}: nominal point {pt}: {why}")
    from ..errors import Error

    raise Error(f"{where}: volumetric compensation of {pt} did not converge (residual "
                f"{float(res.residual[idx]):.3g} mm > {tolerance:g} mm)")


class _Compensator:
    def __init__(self, machine, tolerance, source):
        self.machine = machine
        self.opt = _options(tolerance, 50, True)
        self.tolerance = tolerance
        self.source = source
        self.max_residual = 0.0
        self.max_correction = 0.0

    def __call__(self, nominal: np.ndarray, lines: np.ndarray) -> np.ndarray:
        nominal = np.ascontiguousarray(nominal, dtype=np.float64).reshape(-1, 3)
        if len(nominal) == 0:
            return nominal.copy()
        res = _c.compensate_points_status(self.machine, nominal, self.opt)
        i = res.first_failure()
        if i >= 0:
            _fail(self.machine, res, i, nominal, lines, self.source, self.tolerance)
        cmd = np.asarray(res.commanded)
        self.max_residual = max(self.max_residual, float(np.max(res.residual)))
        self.max_correction = max(self.max_correction, float(np.max(np.linalg.norm(cmd - nominal, axis=1))))
        return cmd


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    L2 = np.einsum("ij,ij->i", ab, ab)
    t = np.where(L2 > 0, np.einsum("ij,ij->i", p - a, ab) / np.where(L2 > 0, L2, 1.0), 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def _subdivide(machine, comp: _Compensator, a_nom, b_nom, a_cmd, b_cmd, lines, tol, max_depth=30):
    """Adaptive halving of segments until the actual path between compensated points stays within
    ``tol`` of the nominal segment at t = ¼, ½, ¾. Returns per input segment the list of interior
    commanded points (in order) and the largest deviation seen."""
    n = len(a_nom)
    # each pending item: (segment id, t0, t1, a_nom, b_nom, a_cmd, b_cmd)
    seg = np.arange(n)
    t0 = np.zeros(n)
    t1 = np.ones(n)
    A, B, AC, BC = a_nom.copy(), b_nom.copy(), a_cmd.copy(), b_cmd.copy()
    interior: list[list[tuple[float, np.ndarray]]] = [[] for _ in range(n)]
    worst = 0.0
    for depth in range(max_depth + 1):
        if len(seg) == 0:
            break
        ts = np.array([0.25, 0.5, 0.75])
        c = (AC[:, None, :] + ts[None, :, None] * (BC - AC)[:, None, :]).reshape(-1, 3)
        act = c + _m.tip_error(machine, np.ascontiguousarray(c))
        dev = _segment_distance(act, np.repeat(A, 3, axis=0), np.repeat(B, 3, axis=0)).reshape(-1, 3).max(axis=1)
        bad = dev > tol
        worst = max(worst, float(dev[~bad].max(initial=0.0)))
        if not bad.any():
            break
        if depth == max_depth:
            raise ValueError(f"{comp.source}:{int(lines[seg[bad][0]])}: could not follow the line within "
                             f"chord_tolerance = {tol:g} mm after {max_depth} halvings")
        seg, t0, t1, A, B, AC, BC = (x[bad] for x in (seg, t0, t1, A, B, AC, BC))
        M = 0.5 * (A + B)
        MC = comp(M, lines[seg])
        tm = 0.5 * (t0 + t1)
        for s, t, mc in zip(seg, tm, MC):
            interior[s].append((float(t), mc))
        seg = np.concatenate([seg, seg])
        t0, t1 = np.concatenate([t0, tm]), np.concatenate([tm, t1])
        A, B = np.vstack([A, M]), np.vstack([M, B])
        AC, BC = np.vstack([AC, MC]), np.vstack([MC, BC])
    return [[p for _, p in sorted(lst, key=lambda x: x[0])] for lst in interior], worst


def _radii(start, end, center, axes) -> tuple[float, float]:
    """In-plane distances [mm] of an arc's start and end from its centre (axes: the plane's two)."""
    s = np.asarray(start, dtype=float)[list(axes)] - np.asarray(center, dtype=float)[list(axes)]
    e = np.asarray(end, dtype=float)[list(axes)] - np.asarray(center, dtype=float)[list(axes)]
    return float(np.hypot(*s)), float(np.hypot(*e))


def _arc_count(block, tol: float) -> int:
    r = block.radius()
    sweep = abs(block.sweep())
    if r <= 0 or sweep <= 0:
        return 1
    h = min(max(tol, 1e-12), r)
    step = 2.0 * math.acos(1.0 - h / r)
    return max(1, int(math.ceil(sweep / step)))


def compensate_program(machine: _m.Machine, program: Any, chord_tolerance: float = 0.002,
                       tolerance: float = 1e-9, *, work_offsets: Any = None, tool_table: Any = None):
    """Compensate a program (path or netshape.toolpath.Toolpath). Returns (Toolpath, ProgramReport).
    See the module docstring for what happens to lines, arcs, modal state and commands.
    ``work_offsets`` / ``tool_table``: see :func:`netshape.toolpath.read_gcode` (path input only)."""
    from .. import toolpath as tpm

    tol = float(chord_tolerance)
    if not (tol > 0 and math.isfinite(tol)):
        raise ValueError(f"chord_tolerance = {chord_tolerance!r}: must be a positive number [mm]")
    if isinstance(program, (str, os.PathLike)):
        source = os.fspath(program)
        tp = tpm.read_gcode(program, arcs="keep", work_offsets=work_offsets, tool_table=tool_table)
    else:
        if work_offsets is not None or tool_table is not None:
            raise ValueError("work_offsets / tool_table apply when reading a program path; a Toolpath "
                             "already carries its offsets")
        tp = program
        source = getattr(tp, "source", "") or "<program>"
    blocks = tp.blocks
    report = ProgramReport(source=source, blocks_in=len(blocks), commands=len(tp.commands))
    comp = _Compensator(machine, tolerance, source)
    if not blocks:
        return tp.with_blocks([], []), report
    lines = np.array([b.line for b in blocks], dtype=np.int64)
    starts = np.array([b.start for b in blocks], dtype=float)
    ends = np.array([b.end for b in blocks], dtype=float)
    e_cmd = comp(ends, lines)
    # a block starts where the previous one ended; the first block starts at the reader's initial
    # position, which is not a programmed point: it is left as it is (not compensated, not checked)
    s_cmd = np.empty_like(starts)
    s_cmd[0] = starts[0]
    s_cmd[1:] = e_cmd[:-1]
    jump = np.flatnonzero(np.any(starts[1:] != ends[:-1], axis=1)) + 1
    if len(jump):
        s_cmd[jump] = comp(starts[jump], lines[jump])
    line_ids = [i for i, b in enumerate(blocks) if b.kind == tpm.MotionKind.line]
    new_lists: dict[int, list] = {}
    # arcs: try to keep as moved arcs, else chords (nominal chord error ≤ tol/2, the rest for compensation)
    arc_chords: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for i, b in enumerate(blocks):
        if b.kind != tpm.MotionKind.arc:
            continue
        n_ax = (2, 1, 0)[int(b.plane)]  # normal axis of G17 (xy), G18 (zx), G19 (yz)
        c_s = s_cmd[i] - starts[i]
        c_e = e_cmd[i] - ends[i]
        nb = _copy_block(tpm, b)
        nb.start = s_cmd[i]
        nb.end = e_cmd[i]
        center = np.asarray(b.center, dtype=float) + 0.5 * (c_s + c_e)
        center[n_ax] = s_cmd[i][n_ax]
        nb.center = center
        m = max(8, _arc_count(b, tol / 2))
        fr = np.linspace(0.0, 1.0, m + 1)[1:-1]
        # in-plane radii (a helix' normal-axis travel is not a radius); the moved arc may spiral as much
        # as the nominal one does, plus half the tolerance
        pa = [(0, 1), (2, 0), (1, 2)][int(b.plane)]
        bc = np.asarray(b.center, dtype=float)
        r_nom = _radii(starts[i], ends[i], bc, pa)
        r_cmd = _radii(nb.start, nb.end, center, pa)
        keep = abs((r_cmd[0] - r_cmd[1]) - (r_nom[0] - r_nom[1])) < 0.5 * tol
        dev = np.inf
        if keep:
            pts = np.array([nb.point_at(float(s)) for s in fr])
            nom = np.array([b.point_at(float(s)) for s in fr])
            act = pts + _m.tip_error(machine, np.ascontiguousarray(pts))
            dev = float(np.linalg.norm(act - nom, axis=1).max(initial=0.0))
        if dev <= tol:
            new_lists[i] = [nb]
            report.arcs_kept += 1
            report.max_path_deviation_mm = max(report.max_path_deviation_mm, dev)
        else:
            k = max(2, _arc_count(b, tol / 2))
            fr = np.linspace(0.0, 1.0, k + 1)
            nom = np.array([b.point_at(float(s)) for s in fr])
            nom[0], nom[-1] = starts[i], ends[i]
            cmd = np.vstack([s_cmd[i], comp(nom[1:-1], np.full(k - 1, b.line)), e_cmd[i]])
            arc_chords[i] = (nom, cmd)
            report.arcs_split += 1
    # lines and arc chords: adaptive subdivision in one vectorised pass
    seg_owner: list[tuple[int, int]] = []
    A, B, AC, BC, L = [], [], [], [], []
    for i in line_ids:
        seg_owner.append((i, 0))
        A.append(starts[i]), B.append(ends[i]), AC.append(s_cmd[i]), BC.append(e_cmd[i]), L.append(lines[i])
    for i, (nom, cmd) in arc_chords.items():
        for j in range(len(nom) - 1):
            seg_owner.append((i, j))
            A.append(nom[j]), B.append(nom[j + 1]), AC.append(cmd[j]), BC.append(cmd[j + 1]), L.append(lines[i])
    if seg_owner:
        interior, worst = _subdivide(machine, comp, np.array(A), np.array(B), np.array(AC), np.array(BC),
                                     np.array(L), tol)
        report.max_path_deviation_mm = max(report.max_path_deviation_mm, worst)
        for (i, j), inner, end in zip(seg_owner, interior, BC):
            lst = new_lists.setdefault(i, [])
            for p in [*inner, end]:
                nb = _copy_block(tpm, blocks[i])
                nb.kind = tpm.MotionKind.line
                nb.start = lst[-1].end if lst else s_cmd[i]
                nb.end = p
                lst.append(nb)
        report.lines_split = sum(1 for i in line_ids if len(new_lists[i]) > 1)
    out = []
    origin = []
    for i, b in enumerate(blocks):
        if b.kind == tpm.MotionKind.rapid:
            nb = _copy_block(tpm, b)
            nb.start, nb.end = s_cmd[i], e_cmd[i]
            out.append(nb)
            origin.append(i)
        else:
            out.extend(new_lists[i])
            origin.extend([i] * len(new_lists[i]))
    res = tp.with_blocks(out, origin)
    report.blocks_out = len(out)
    report.max_correction_mm = comp.max_correction
    report.max_residual_mm = comp.max_residual
    return res, report


def _copy_block(tpm, b):
    nb = tpm.Block()
    for a in ("kind", "start", "end", "center", "clockwise", "plane", "turns", "feed", "spindle_rpm", "tool", "line"):
        setattr(nb, a, getattr(b, a))
    return nb


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
    with atomic_write(output, "w") as fh:
        fh.write(text)
    return report
