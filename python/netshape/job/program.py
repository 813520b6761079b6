"""The job's program: its blocks in program coordinates, the work offset (G54–G59) in force at each
block and the frames the stages work in.

Frames: the stock and the force/deflection stages work in the work coordinates of G54 (the
program's coordinates when it selects no other offset); the machine stages work in machine
coordinates, program point + active work offset (G54–G59 from the job), with the job's tool length.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from .spec import WORK_OFFSETS, Job


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


def _sub_toolpath(tp, blocks):
    from netshape import toolpath as tpm

    sub = tpm.Toolpath()
    sub.blocks = list(blocks)
    sub.source = tp.source
    return sub
