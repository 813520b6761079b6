"""The stages of the main job, one function each. They take and return plain objects (no file
writes); the deflection stage is in :mod:`netshape.job.stage_deflection`. :mod:`netshape.job.run` calls
them in order, times them and writes the outputs.

Frames: the stock and the force/deflection stages work in the work coordinates of G54 (the
program's coordinates when it selects no other offset); the machine stages work in machine
coordinates, program point + active work offset (G54–G59 from the job), with the job's tool length.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .spec import WORK_OFFSETS, Job

if TYPE_CHECKING:
    from .stage_deflection import DeflectionResult

# ---------------------------------------------------------------------------------------------- program


@dataclass
class Program:
    """The job's program: blocks in work coordinates (G54 frame) and per block the offset to machine
    coordinates [mm]."""

    toolpath: object                 # netshape.toolpath.Toolpath, program coordinates, feeds scaled
    offset_index: np.ndarray         # (n,) index into WORK_OFFSETS of the offset active at each block
    offsets: np.ndarray              # (6, 3) work offsets [mm]
    lines: np.ndarray                # (n,) source line of each block

    def block_offsets(self) -> np.ndarray:
        """(n, 3) offset program → machine of each block [mm]."""
        return self.offsets[self.offset_index]

    @property
    def uses_one_offset(self) -> bool:
        return len(np.unique(self.offset_index)) <= 1


def active_work_offsets(path) -> np.ndarray:
    """Index into WORK_OFFSETS (0 = G54) of the work offset in force on each source line of the program
    file (1-based; entry 0 unused). See :func:`work_offsets_per_line`."""
    return work_offsets_per_line(read_program(path), path)


def work_offsets_per_line(tp, source) -> np.ndarray:
    """Index into WORK_OFFSETS (0 = G54) of the work offset in force on each source line of a program
    read by :func:`read_program` (1-based; entry 0 unused), from the reader's work-offset records (a
    G54…G59 word takes effect on its own line). G59.1–G59.3 are refused: the job has no values for them."""
    from netshape import toolpath as tpm

    last_line = max([b.line for b in tp.blocks] + [c.line for c in tp.commands] + [0])
    states = np.zeros(last_line + 1, dtype=np.int64)
    for c in tp.commands:
        if c.kind != tpm.CommandKind.work_offset:
            continue
        k = int(c.value)
        if k >= len(WORK_OFFSETS):
            raise ValueError(f"{source}:{c.line}: {c.text}: this work offset has no key in the job "
                             "(offsets.G54_mm … G59_mm)")
        states[c.line:] = k
    return states


def _copy_block(tpm, b):
    nb = tpm.Block()
    for a in ("kind", "start", "end", "center", "clockwise", "plane", "turns", "feed", "spindle_rpm", "tool", "line"):
        setattr(nb, a, getattr(b, a))
    return nb


def shift_toolpath(tp, delta: np.ndarray):
    """A copy of ``tp`` with block ``i`` moved by ``delta[i]`` [mm] (start, end and arc centre)."""
    from netshape import toolpath as tpm

    out = []
    for b, d in zip(tp.blocks, np.asarray(delta, dtype=float)):
        nb = _copy_block(tpm, b)
        nb.start = np.asarray(b.start) + d
        nb.end = np.asarray(b.end) + d
        nb.center = np.asarray(b.center) + d
        out.append(nb)
    # one new block per old one: the program's non-motion records (comments, M/S/T words, dwells,
    # work offsets) keep their places
    return tp.with_blocks(out, list(range(len(out))))


def read_program(path):
    """A program of the job, arcs kept, in its own coordinates: the job places its G54–G59 words and tool
    length itself (``[offsets]``), so the reader's warning that none were given does not apply."""
    import warnings

    from netshape import toolpath as tpm

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        return tpm.read_gcode(path, arcs="keep")


def stage_program(job: Job) -> Program:
    """Read the program (arcs kept), scale its feeds by ``cutting.feed_scale`` and find the work offset
    of every block."""
    from netshape import toolpath as tpm

    tp = read_program(job.program)
    if len(tp.blocks) == 0:
        raise ValueError(f"program = {str(job.program)!r}: no motion blocks")
    scale = job.cutting["feed_scale"]
    if scale != 1.0:
        blocks = []
        for b in tp.blocks:
            nb = _copy_block(tpm, b)
            nb.feed = b.feed * scale
            blocks.append(nb)
        tp = tp.with_blocks(blocks, list(range(len(blocks))))
    tp = _with_start(job, tp)
    lines = np.array([b.line for b in tp.blocks], dtype=np.int64)
    per_line = work_offsets_per_line(tp, job.program)
    idx = per_line[np.clip(lines, 0, len(per_line) - 1)]
    offsets = np.array([job.offsets[g] for g in WORK_OFFSETS], dtype=float)
    return Program(toolpath=tp, offset_index=idx, offsets=offsets, lines=lines)


def _with_start(job: Job, tp):
    """The program with its first move starting where the tool is before it: ``start_mm`` or, by default,
    ``clearance_mm`` above the stock's top at the first move's XY (the reader's (0, 0, 0) would put the
    tool inside the stock and sweep a hole the program never cut). Only the first block's start moves;
    the G-code written is the same (a block gives its end point)."""
    from netshape import toolpath as tpm

    blocks = list(tp.blocks)
    first = blocks[0]
    if job.start_mm is not None:
        start = np.asarray(job.start_mm, dtype=float)
    else:
        top = job.stock["max_mm"][2] if job.stock.get("max_mm") is not None else float(first.end[2])
        end = np.asarray(first.end, dtype=float)
        start = np.array([end[0], end[1], max(top, end[2]) + job.clearance_mm])
    if np.allclose(start, np.asarray(first.start, dtype=float)) or int(first.kind) == 2:
        return tp  # an arc keeps its own start (its centre was given relative to it)
    nb = _copy_block(tpm, first)
    nb.start = start
    return tp.with_blocks([nb] + blocks[1:], list(range(len(blocks))))


def stock_frame_toolpath(prog: Program):
    """The program in the stock's frame (G54 work coordinates)."""
    if prog.uses_one_offset and prog.offset_index[0] == 0:
        return prog.toolpath
    return shift_toolpath(prog.toolpath, prog.block_offsets() - prog.offsets[0])


def machine_frame_toolpath(prog: Program):
    """The program in machine coordinates (program point + active work offset)."""
    return shift_toolpath(prog.toolpath, prog.block_offsets())


# ---------------------------------------------------------------------------------------------- stock


def make_cutter(tool: dict):
    from netshape.cutter import cutter_from_dict

    return cutter_from_dict(tool, source="tool")


def stage_stock(job: Job):
    """The stock before the program: a box or a heights file, then every ``[[stock.pre_cut]]`` swept in
    order. Returns a netshape.stock.ZMap."""
    from netshape import stock as ns

    s = job.stock
    lo, hi = s["min_mm"], s["max_mm"]
    if s["heights"] is not None:
        path = s["heights"]
        if path.suffix.lower() == ".npy":
            h = np.load(path, allow_pickle=False)
        else:
            import io

            from netshape._text import read_text

            h = np.loadtxt(io.StringIO(read_text(path)), delimiter=",", ndmin=2)
        h = np.asarray(h, dtype=float)
        if h.ndim != 2 or min(h.shape) < 2:
            raise ValueError(f"stock.heights = {str(path)!r}: shape {h.shape}, must be (ny, nx) with ny, nx ≥ 2")
        if not np.isfinite(h).all():
            raise ValueError(f"stock.heights = {str(path)!r}: heights must be finite [mm]")
        if h.min() < lo[2]:
            raise ValueError(f"stock.heights = {str(path)!r}: height {h.min():g} below stock.min_mm[2] = {lo[2]:g}")
        z = ns.from_heights(h, lo[0], hi[0], lo[1], hi[1], lo[2])
    else:
        z = ns.ZMap(lo[0], hi[0], lo[1], hi[1], s["spacing_mm"], hi[2], lo[2])
    for pc in s["pre_cut"]:
        ns.sweep(z, make_cutter(pc.tool), read_program(pc.program))
    return z


def stage_cut(job: Job, stock0, prog: Program, warnings: list | None = None):
    """The stock after the program (Z-map material removal). Returns (ZMap, removed volume [mm³]).
    Rapid moves that remove material are appended to ``warnings`` as ``rapid_through_material`` with
    their program line (each rapid is swept on its own, in order, to tell which)."""
    from netshape import stock as ns

    z = stock0.copy()
    tp = stock_frame_toolpath(prog)
    cutter = make_cutter(job.tool)
    blocks = list(tp.blocks)
    rapid = [i for i, b in enumerate(blocks) if int(b.kind) == 0]
    removed, done = 0.0, 0
    for i in rapid + [len(blocks)]:
        if i > done:
            removed += float(ns.sweep(z, cutter, _sub_toolpath(tp, blocks[done:i])).removed_volume)
        if i < len(blocks):
            st = ns.sweep(z, cutter, _sub_toolpath(tp, blocks[i:i + 1]))
            removed += float(st.removed_volume)
            if st.removed_volume > 1e-9 and warnings is not None:
                b = blocks[i]
                warnings.append({"kind": "rapid_through_material", "line": int(b.line),
                                 "message": f"the rapid (G0) move on line {b.line} to X{b.end[0]:g} Y{b.end[1]:g} "
                                            f"Z{b.end[2]:g} removes {st.removed_volume:.3g} mm^3 of stock"})
        done = i + 1
    if warnings is not None:
        from .warnings import tool_shorter_than_cut

        tool_shorter_than_cut(job, blocks, warnings)
    return z, removed


# ---------------------------------------------------------------------------------------------- forces


def coefficients_for(job: Job, cutter):
    """Force coefficients of the job for its cutter (linear edge for flat/bull, the ball model for ball)."""
    from netshape import force as nf
    from netshape.cutter import CutterKind

    c = job.coefficients
    is_ball = cutter.kind == CutterKind.ball
    if isinstance(c, dict):
        vals = {k.split("_")[0].lower(): v for k, v in c.items()}
        if is_ball:
            raise ValueError("coefficients: a ball end mill takes a named ball set (e.g. kim_zas_ball12)")
        return nf.LinearEdgeCoefficients(**vals)
    if "=" in c:
        if is_ball:
            raise ValueError(f"coefficients = {c!r}: a ball end mill takes a named ball set (e.g. kim_zas_ball12)")
        return nf.parse_coefficients(c)
    if c in nf.ball_end_coefficient_set_names():
        if not is_ball:
            raise ValueError(f"coefficients = {c!r}: a ball-end set, but tool.kind is not ball")
        return nf.ball_end_coefficient_set(c).coefficients
    if is_ball:
        raise ValueError(f"coefficients = {c!r}: a flat-end set, but tool.kind = ball")
    return nf.linear_edge_coefficient_set(c).coefficients


#: Blocks per call of the force simulation: the stage reports progress between calls. The Z-map is
#: carried from call to call; each call starts its sampling at its first block.
FORCE_CHUNK_BLOCKS = 250


def stage_forces(job: Job, stock0, prog: Program, progress=None):
    """Per-revolution forces on the cutter along the program, cut through a copy of the stock
    (netshape.force.simulate_program, :data:`FORCE_CHUNK_BLOCKS` blocks per call; ``progress(k)`` is
    called with the blocks done after each call). Returns a ProgramForceResult."""
    from netshape.force import ProgramForceResult, simulate_program

    cutter = make_cutter(job.tool)
    c = job.cutting
    coeffs = coefficients_for(job, cutter)
    tp = stock_frame_toolpath(prog)
    blocks = list(tp.blocks)
    z = stock0.copy()
    parts = []
    for i0 in range(0, len(blocks), FORCE_CHUNK_BLOCKS):
        chunk = _sub_toolpath(tp, blocks[i0:i0 + FORCE_CHUNK_BLOCKS])
        r = simulate_program(z, cutter, chunk, coeffs, step=c["step_mm"],
                             samples_per_revolution=c["samples_per_revolution"], disk_height=c["disk_height_mm"],
                             feed_per_tooth=c["feed_per_tooth_mm"] or 0.0, spindle_rpm=c["spindle_rpm"] or 0.0,
                             copy_stock=False)
        r.block = np.asarray(r.block) + i0
        parts.append(r)
        if progress is not None:
            progress(min(len(blocks), i0 + FORCE_CHUNK_BLOCKS))
    if len(parts) == 1:
        return parts[0]
    fields = ("positions", "block", "feed_direction", "mean", "peak", "peak_resultant", "mean_resultant",
              "engaged_fraction")
    merged = {f: np.concatenate([np.asarray(getattr(p, f)) for p in parts]) for f in fields}
    return ProgramForceResult(**merged, removed_volume=float(sum(p.removed_volume for p in parts)))


def _sub_toolpath(tp, blocks):
    from netshape import toolpath as tpm

    sub = tpm.Toolpath()
    sub.blocks = list(blocks)
    sub.source = tp.source
    return sub


# ---------------------------------------------------------------------------------------------- machine


def load_job_machine(job: Job):
    """The job's machine with its errors scaled by ``machine.error_scale`` and its tool length from
    ``offsets.tool_length_mm`` when given."""
    from netshape import machine as nm

    m = nm.load_machine(job.machine)
    if job.offsets.get("tool_length_mm") is not None:
        m.tool_length = job.offsets["tool_length_mm"]
    if job.error_scale != 1.0:
        scale_machine_errors(m, job.error_scale)
    m.validate()
    return m


def scale_machine_errors(m, s: float) -> None:
    """Multiply every error of ``m`` (the 18 error motions, squareness, spindle tilt, cyclic amplitudes,
    backlash, thermal drift amplitudes) by ``s``."""
    axes = []
    for ax in m.axes:
        funcs = []
        for f in ax.errors:
            kind = f.kind.name
            if kind == "polynomial":
                f.coefficients = [s * c for c in f.coefficients]
            elif kind == "table":
                f.values = [s * v for v in f.values]
            funcs.append(f)
        ax.errors = funcs
        ax.cyclic = [type(t)(amplitude=s * t.amplitude, period=t.period, phase=t.phase) for t in ax.cyclic]
        ax.backlash = s * ax.backlash
        axes.append(ax)
    m.axes = axes
    m.ec0y, m.eb0z, m.ea0z = s * m.ec0y, s * m.eb0z, s * m.ea0z
    m.thermal = [type(t)(axis=t.axis, amplitude=s * t.amplitude, time_constant=t.time_constant) for t in m.thermal]
    m.spindle_tilt_a, m.spindle_tilt_b = s * m.spindle_tilt_a, s * m.spindle_tilt_b


def feed_segments(tp, chord_tolerance: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """Start and end points (m, 3) of the feed moves of ``tp`` with arcs split into chords [mm]."""
    from netshape import toolpath as tpm

    split = tp.split_arcs(chord_tolerance)
    a, b = [], []
    for blk in split.blocks:
        if blk.kind == tpm.MotionKind.rapid:
            continue
        a.append(blk.start)
        b.append(blk.end)
    if not a:
        return np.zeros((0, 3)), np.zeros((0, 3))
    return np.asarray(a, dtype=float), np.asarray(b, dtype=float)


def sample_segments(a: np.ndarray, b: np.ndarray, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Points every ≤ ``spacing`` mm along the segments (ends included) and their path distance [mm]."""
    if len(a) == 0:
        return np.zeros((0, 3)), np.zeros(0)
    L = np.linalg.norm(b - a, axis=1)
    n = np.maximum(1, np.ceil(L / spacing).astype(np.int64))
    seg = np.repeat(np.arange(len(a)), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    k = np.arange(seg.size) - np.repeat(first, n)
    t = k / np.repeat(n, n)
    pts = a[seg] + t[:, None] * (b[seg] - a[seg])
    s0 = np.concatenate([[0.0], np.cumsum(L)[:-1]])
    s = s0[seg] + t * L[seg]
    pts = np.vstack([pts, b[-1:]])
    s = np.concatenate([s, [s0[-1] + L[-1]]])
    return pts, s


def distance_to_path(points: np.ndarray, a: np.ndarray, b: np.ndarray, spacing: float) -> np.ndarray:
    """Distance [mm] of each point to the polyline segments (a[i], b[i]): candidate segments from a
    k-d tree of points every ``spacing`` mm along them, then the exact point-to-segment distance."""
    from scipy.spatial import cKDTree

    if len(points) == 0:
        return np.zeros(0)
    L = np.linalg.norm(b - a, axis=1)
    n = np.maximum(1, np.ceil(L / spacing).astype(np.int64)) + 1
    owner = np.repeat(np.arange(len(a)), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    t = (np.arange(owner.size) - np.repeat(first, n)) / np.repeat(n - 1, n)
    samples = a[owner] + t[:, None] * (b[owner] - a[owner])
    k = min(16, len(samples))
    _, idx = cKDTree(samples).query(points, k=k)
    idx = np.atleast_2d(idx).reshape(len(points), -1)
    segs = owner[idx]                                     # (p, k)
    A, B = a[segs], b[segs]                               # (p, k, 3)
    AB = B - A
    L2 = np.einsum("pkj,pkj->pk", AB, AB)
    tt = np.einsum("pkj,pkj->pk", points[:, None, :] - A, AB) / np.where(L2 > 0, L2, 1.0)
    tt = np.clip(np.where(L2 > 0, tt, 0.0), 0.0, 1.0)
    d = np.linalg.norm(points[:, None, :] - (A + tt[..., None] * AB), axis=2)
    return d.min(axis=1)


@dataclass
class VolumetricResult:
    """Deviation of the actual tool-tip path from the nominal path [mm] (machine frame)."""

    s_before_mm: np.ndarray
    before_mm: np.ndarray
    points_mm: np.ndarray                 # nominal sample points, machine frame
    error_vectors_mm: np.ndarray          # tip error e(p) at them
    s_after_mm: np.ndarray | None = None
    after_mm: np.ndarray | None = None
    compensated: object = None            # Toolpath, machine frame
    report: dict = field(default_factory=dict)


#: Largest volumetric error accepted [mm]: larger ones come from a wrong machine file or error_scale.
MAX_TIP_ERROR_MM = 1e3


def check_tip_errors(job: Job, pts: np.ndarray, e: np.ndarray) -> None:
    """Refuse volumetric errors that are not finite or exceed MAX_TIP_ERROR_MM, naming the job key that
    made them (machine.error_scale when it is not 1, else machine.file) and the first such point."""
    with np.errstate(over="ignore", invalid="ignore"):
        size = np.linalg.norm(e, axis=1)
    bad = ~(size <= MAX_TIP_ERROR_MM)
    if not bad.any():
        return
    i = int(np.argmax(bad))
    p = pts[i]
    what = (f"a volumetric error of {size[i]:.3g} mm at machine point ({p[0]:g}, {p[1]:g}, {p[2]:g}) mm "
            f"(more than {MAX_TIP_ERROR_MM:g} mm is refused)")
    if job.error_scale != 1.0:
        raise ValueError(f"machine.error_scale = {job.error_scale:g}: gives {what}")
    raise ValueError(f"machine.file = {str(job.machine)!r}: gives {what}")


def state_offsets(machine, tp, pts: np.ndarray, s: np.ndarray, departing: bool = False) -> np.ndarray:
    """Backlash and thermal drift (n, 3) [mm] at points ``pts`` sampled along the feed moves of ``tp`` at
    feed-path distances ``s`` [mm] (sample_segments): each axis' direction along the samples, arriving
    at the point (or ``departing`` from it; steps below 1 µm ignored: a compensation's own corrections),
    the program time interpolated in the feed-path distance between the feed blocks' ends
    (block_end_times, programmed feeds)."""
    if not machine.has_state_errors() or len(pts) == 0:
        return np.zeros_like(pts)
    from netshape import machine as nm
    from netshape._core import compensation as _c

    t_end = np.asarray(_c.block_end_times(tp), dtype=float)
    feed = [i for i, b in enumerate(tp.blocks) if b.kind.name != "rapid"]
    dist = np.cumsum([tp.blocks[i].length() for i in feed])
    t = np.interp(s, np.concatenate([[0.0], dist]), np.concatenate([[0.0], t_end[feed]]))
    if departing:
        d = nm.approach_directions(pts[::-1], [1.0, 1.0, 1.0], 1e-3)[::-1] * -1.0
    else:
        d = nm.approach_directions(pts, [1.0, 1.0, 1.0], 1e-3)
    return nm.state_error(machine, np.ascontiguousarray(d), t)


def state_deviation(machine, tp, pts: np.ndarray, s: np.ndarray, a: np.ndarray, b: np.ndarray,
                    spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """(distance [mm] of the actual tip to the nominal segments (a, b), tip error (n, 3)) at the samples.
    With backlash the direction at a point where an axis reverses is ambiguous (it arrives one way and
    leaves the other; a compensation's take-up move sits there): the state that gives the smaller
    distance is taken, arriving elsewhere."""
    from netshape import machine as nm

    e = nm.tip_error(machine, pts)
    arr = e + state_offsets(machine, tp, pts, s)
    dev = distance_to_path(pts + arr, a, b, spacing)
    if not any(ax.backlash for ax in machine.axes):
        return dev, arr
    dep = e + state_offsets(machine, tp, pts, s, departing=True)
    dev_dep = distance_to_path(pts + dep, a, b, spacing)
    return np.minimum(dev, dev_dep), np.where((dev_dep < dev)[:, None], dep, arr)


def stage_volumetric(job: Job, machine, tp_machine) -> VolumetricResult:
    """Volumetric error along the feed moves: at points every ``cutting.error_spacing_mm`` the actual tip
    p + e(p) and its distance to the nominal path (machine frame)."""
    from netshape import machine as nm

    a, b = feed_segments(tp_machine)
    pts, s = sample_segments(a, b, job.cutting["error_spacing_mm"])
    if len(pts) == 0:
        raise ValueError(f"program = {str(job.program)!r}: no feed moves to predict the volumetric error of")
    check_tip_errors(job, pts, nm.tip_error(machine, pts))
    dev, e = state_deviation(machine, tp_machine, pts, s, a, b, job.cutting["error_spacing_mm"])
    return VolumetricResult(s_before_mm=s, before_mm=dev, points_mm=pts, error_vectors_mm=e)


def stage_volumetric_compensation(job: Job, machine, tp_machine, vol: VolumetricResult) -> VolumetricResult:
    """Compensate the program (machine frame) so the actual tip lands on the nominal path
    (netshape.compensation.compensate_program), then re-predict: sample the compensated program, move
    every point by the machine's error and measure its distance to the nominal path."""
    from netshape import compensation as nc

    comp, report = nc.compensate_program(machine, tp_machine, job.compensate["chord_tolerance_mm"])
    a, b = feed_segments(tp_machine)
    ca, cb = feed_segments(comp)
    pts, s = sample_segments(ca, cb, job.cutting["error_spacing_mm"])
    vol.after_mm, _ = state_deviation(machine, comp, pts, s, a, b, job.cutting["error_spacing_mm"])
    vol.s_after_mm = s
    vol.compensated = comp
    vol.report = report.to_dict()
    return vol


def to_program_frame(tp_machine, prog: Program):
    """Blocks in machine coordinates back into the program's coordinates, block by block with the work
    offset active at the block's source line."""
    per_line = np.zeros(int(prog.lines.max()) + 2, dtype=np.int64)
    per_line[prog.lines] = prog.offset_index
    lines = np.array([b.line for b in tp_machine.blocks], dtype=np.int64)
    idx = per_line[np.clip(lines, 0, len(per_line) - 1)]
    return shift_toolpath(tp_machine, -prog.offsets[idx]), idx


def write_program_text(tp, idx: np.ndarray, header: str) -> str:
    """G-code of ``tp`` (program coordinates) with the program's non-motion records (comments, M/S/T
    words, dwells, G54–G59) at their places. A tool path without records (built by hand) is written in
    runs of one work offset, each with its G54–G59 word, so each runs under the offset it was written
    for."""
    from netshape import toolpath as tpm

    blocks = tp.blocks
    if len(blocks) == 0 or len(tp.commands) > 0:
        # the program's own records carry its G54-G59 words at their places
        return tpm.format_gcode(tp, header_comment=header)
    cuts = [0] + [i for i in range(1, len(blocks)) if idx[i] != idx[i - 1]] + [len(blocks)]
    parts = []
    for r, (i0, i1) in enumerate(zip(cuts[:-1], cuts[1:])):
        sub = tpm.Toolpath()
        sub.blocks = blocks[i0:i1]
        text = tpm.format_gcode(sub, header_comment=header if r == 0 else "")
        lines = text.splitlines()
        if r > 0:  # drop the repeated header lines and program end of the later runs
            lines = [ln for ln in lines if ln.strip() and not ln.startswith(("(", "%"))]
            lines = [ln for ln in lines if not re.fullmatch(r"\s*G21 G90 G17 G94( G91\.1)?\s*", ln)]
        # each run names its work offset, as the original program selected it
        k = 0
        while k < len(lines) and (lines[k].startswith(("(", "%")) or lines[k].startswith("G21")):
            k += 1
        lines.insert(k, WORK_OFFSETS[int(idx[i0])])
        if r < len(cuts) - 2:
            lines = [ln for ln in lines if ln.strip() not in ("M30", "M2", "%")]
        parts.extend(lines)
    return "\n".join(parts) + "\n"


# ---------------------------------------------------------------------------------------------- motion


def stage_feed_plan(job: Job, tp):
    """Look-ahead feed plan and interpolation of ``tp`` under the job's limits. Returns a
    netshape.motion.Trajectory (``stats['cycle_time_s']``)."""
    from netshape import motion as nmo

    lim = job.limits
    jerk = lim.get("jmax_mm_s3", [math.inf] * 3)
    limits = nmo.AxisLimits(lim["vmax_mm_s"], lim["amax_mm_s2"], jerk)
    options = nmo.make_options(lim["rule"], ts1=lim["ts1_s"], ts2=lim["ts2_s"], lookahead=lim["lookahead"],
                               tolerance=lim["tolerance_mm"])
    from netshape._budget import MAX_PLAN_SAMPLES

    try:
        return nmo.plan(tp, limits, options, with_deviation=False, max_samples=MAX_PLAN_SAMPLES)
    except ValueError as exc:  # the planner's own bound, reached where the estimate before the run was low
        if str(exc).startswith("max_samples = "):
            raise ValueError(f"{job.source}: limits: the feed plan needs more than {MAX_PLAN_SAMPLES} fine samples "
                             f"(limits.ts2_s = {lim['ts2_s']!r}, jmax_mm_s3 = {lim.get('jmax_mm_s3')!r}); "
                             "use a larger ts2_s or limits the program can run under") from None
        raise


# ---------------------------------------------------------------------------------------------- errors


def error_stats(before, after) -> dict:
    """max and RMS [mm] of |error| before and after (None where there is no value)."""

    def mx(v):
        return None if v is None or len(v) == 0 else float(np.max(np.abs(v)))

    def rms(v):
        return None if v is None or len(v) == 0 else float(np.sqrt(np.mean(np.square(v))))

    return {"max_before_mm": mx(before), "max_after_mm": mx(after),
            "rms_before_mm": rms(before), "rms_after_mm": rms(after)}


def total_error(defl: DeflectionResult | None, vol: VolumetricResult | None, which: str, machine=None,
                to_machine=None):
    """Total error [mm] from the sources predicted, at the points where they act on the part.

    On the final walls (the deflection samples) the errors add along the wall normal n: before
    compensation the wall error minus the machine's tip error along n (``machine`` and ``to_machine``,
    stock-frame points → machine frame, give it; a tip moved towards the wall cuts more), after it the
    wall error plus the volumetric residual distance in the adverse direction (that residual has no
    direction), interpolated by path distance. Elsewhere on the path the volumetric error alone. One
    source alone is the total."""
    d_s = d_v = None
    if defl is not None and defl.available:
        if which == "before":
            d_s, d_v = defl.s_mm, defl.before_mm
        else:
            d_s = defl.s_after_mm if defl.s_after_mm is not None else defl.s_mm
            d_v = defl.after_mm
    v_s = v_v = None
    if vol is not None:
        v_s, v_v = (vol.s_before_mm, vol.before_mm) if which == "before" else (vol.s_after_mm, vol.after_mm)
    if d_v is None and v_v is None:
        return None
    if v_v is None or len(v_v) == 0:
        return d_v
    if d_v is None or len(d_v) == 0:
        return v_v
    if which == "before" and machine is not None and to_machine is not None and len(defl.points_mm) == len(d_v):
        from netshape import machine as nm

        e = np.asarray(nm.tip_error(machine, to_machine(defl.points_mm)), dtype=float)
        on_wall = d_v - np.einsum("ij,ij->i", e[:, :2], defl.normals)
    else:
        v_on_d = np.interp(d_s, v_s, v_v)
        on_wall = d_v + np.where(d_v >= 0, 1.0, -1.0) * v_on_d
    # volumetric samples off the final walls keep their own error
    inside = np.zeros(len(v_s), dtype=bool)
    for s0, s1 in defl.ranges:
        inside |= (v_s >= s0) & (v_s <= s1)
    return np.concatenate([on_wall, v_v[~inside]])
