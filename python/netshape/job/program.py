"""The job's program: its blocks in program coordinates, the work offset (G54–G59) in force at each
block and the frames the stages work in.

Frames: the stock and the force/deflection stages work in the work coordinates of G54 (the
program's coordinates when it selects no other offset); the machine stages work in machine
coordinates, program point + active work offset (G54–G59 from the job), with the job's tool length.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .spec import WORK_OFFSETS, Job


@dataclass
class Program:
    """The job's program in its own coordinates, and the job's work offsets. Its frames are operations
    of the tool path (netshape.toolpath.Toolpath.to_machine / to_program): machine coordinates are
    program point + the offset in force at the block (its G54…G59 word, the job's values)."""

    toolpath: object                 # netshape.toolpath.Toolpath, program coordinates, feeds scaled
    offsets: np.ndarray              # (9, 3) work offsets G54…G59.3 [mm] (G59.1–G59.3 zero: refused)


def active_work_offsets(path) -> np.ndarray:
    """Index into WORK_OFFSETS (0 = G54) of the work offset in force on each source line of the program
    file (1-based; entry 0 unused). See :func:`work_offsets_per_line`."""
    return work_offsets_per_line(read_program(path), path)


def work_offsets_per_line(tp, source) -> np.ndarray:
    """Index into WORK_OFFSETS (0 = G54) of the work offset in force on each source line of a program
    read by :func:`read_program` (1-based; entry 0 unused), from the reader's work-offset records (a
    G54…G59 word takes effect on its own line). G59.1–G59.3 are refused: the job has no values for them."""
    from netshape import toolpath as tpm

    _refuse_unknown_offsets(tp, source)
    last_line = max([b.line for b in tp.blocks] + [c.line for c in tp.commands] + [0])
    states = np.zeros(last_line + 1, dtype=np.int64)
    for c in tp.commands:
        if c.kind == tpm.CommandKind.work_offset:
            states[c.line:] = int(c.value)
    return states


def _refuse_unknown_offsets(tp, source) -> None:
    """ValueError ``SOURCE:LINE: G59.1: …`` for a work offset the job has no key for (G59.1–G59.3)."""
    from netshape import toolpath as tpm

    for c in tp.commands:
        if c.kind == tpm.CommandKind.work_offset and int(c.value) >= len(WORK_OFFSETS):
            raise ValueError(f"{source}:{c.line}: {c.text}: this work offset has no key in the job "
                             "(offsets.G54_mm … G59_mm)")


def _copy_block(tpm, b):
    nb = tpm.Block()
    for a in ("kind", "start", "end", "center", "clockwise", "plane", "turns", "feed", "spindle_rpm", "tool", "line"):
        setattr(nb, a, getattr(b, a))
    return nb


def read_program(path):
    """A program of the job, arcs kept, in its own coordinates: the job places its G54–G59 words and tool
    length itself (``[offsets]``), so the reader's warning that none were given does not apply."""
    import warnings

    from netshape import toolpath as tpm

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        return tpm.read_gcode(path, arcs="keep")


def stage_program(job: Job) -> Program:
    """Read the program (arcs kept), scale its feeds by ``cutting.feed_scale``, place its first move's
    start (:func:`_with_start`) and refuse work offsets the job has no values for."""
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
    _refuse_unknown_offsets(tp, job.program)
    return Program(toolpath=tp, offsets=job_work_offsets(job))


def job_work_offsets(job: Job) -> np.ndarray:
    """(9, 3) work offsets G54…G59.3 [mm] of the job's ``[offsets]`` (G59.1–G59.3 zero)."""
    offsets = np.zeros((9, 3))
    offsets[:len(WORK_OFFSETS)] = [job.offsets[g] for g in WORK_OFFSETS]
    return offsets


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
    """The program in the stock's frame (G54 work coordinates): machine coordinates less the G54 offset,
    a tool path that carries those offsets (``to_program`` brings a transform of it back)."""
    return prog.toolpath.to_machine(prog.offsets - prog.offsets[0])


def machine_frame_toolpath(prog: Program):
    """The program in machine coordinates (program point + the work offset in force)."""
    return prog.toolpath.to_machine(prog.offsets)


def write_program_text(tp, header: str) -> str:
    """G-code of ``tp`` (program coordinates or a frame that carries its offsets) with the program's
    non-motion records (comments, M/S/T words, dwells, G54–G59) at their places; G54 named after the
    header when the program selects no offset before its first block (netshape.toolpath.format_gcode)."""
    from netshape import toolpath as tpm

    return tpm.format_gcode(tp, header_comment=header, work_offset_word=True)


def _sub_toolpath(tp, blocks):
    from netshape import toolpath as tpm

    sub = tpm.Toolpath()
    sub.blocks = list(blocks)
    sub.source = tp.source
    return sub
