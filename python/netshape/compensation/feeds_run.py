"""The feed schedule of a program file, from reading to the text written and its report (the workflow of
``netshape feeds`` and the job's ``[optimize]`` table; docs/feeds.md)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from . import feeds_gcode as fg
from . import feeds_report as fr
from .feeds import FeedLimits, sample_limits, schedule_feeds, stated


@dataclass
class FeedsResult:
    """``text``: the scheduled program; ``summary``: the summary JSON; ``rows``: per program line
    (feeds_report.CSV_COLUMNS); ``schedule``: the FeedSchedule; ``pieces``: the pieces written;
    ``after``: the re-simulated written program (ProgramForceResult)."""

    text: str
    summary: dict
    rows: list
    schedule: object
    pieces: dict
    after: object
    program: object


def read_program_text(text: str, source: str):
    """A program in its own coordinates (work offsets and tool lengths not applied), arcs kept."""
    from netshape import toolpath as tpm

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        return tpm.parse_gcode(text, source=source, arcs="keep")


def stock_frame(tp, work_offsets=None):
    """The program ``tp`` (program coordinates) in the stock's frame, the work coordinates of G54, as
    the job reads it (netshape.job.program.stock_frame_toolpath): each block moved by the work offset
    in force there less G54's (``work_offsets``: (9, 3) rows G54…G59.3 [mm]; None: all zero). A tool
    length (G43) moves the spindle, not the tip against the part: read without a tool table, its
    commands are zero here."""
    if work_offsets is None:
        return tp
    w = np.asarray(work_offsets, dtype=float)
    if w.shape != (9, 3) or not np.all(np.isfinite(w)):
        raise ValueError(f"work_offsets shape = {w.shape}: must be (9, 3) finite [mm] (G54 … G59.3)")
    return tp.to_machine(w - w[0])


def with_start(tp, stock, clearance: float = 5.0):
    """The program with its first move starting ``clearance`` above the stock's top at the first move's
    XY (the reader's start at the origin would put the tool inside the stock)."""
    blocks = list(tp.blocks)
    if not blocks or int(blocks[0].kind) == 2:
        return tp
    end = np.asarray(blocks[0].end, dtype=float)
    nb = fg.copy_block(blocks[0])
    nb.start = np.array([end[0], end[1], max(float(stock.max_height()), end[2]) + clearance])
    return tp.with_blocks([nb] + blocks[1:], list(range(len(blocks))))


def _plan(tp, axis_limits, options):
    from netshape import motion as nmo
    from netshape._budget import MAX_PLAN_SAMPLES

    return nmo.plan(tp, axis_limits, options, with_deviation=False, max_samples=MAX_PLAN_SAMPLES)


def _deflection_check(stock, cutter, written, coefficients, limits: FeedLimits, sampling: dict) -> dict:
    """The written program cut again with the deflection model (flat end mills): the largest tip
    deflection and the largest wall error on the walls that remain, at the written feeds [mm]."""
    import math

    stated_d, stated_w = math.isfinite(limits.max_deflection), math.isfinite(limits.max_wall_error)
    if str(cutter.kind).split(".")[-1] != "flat" or not (stated_d or stated_w):
        return {}
    s, final = sample_limits(stock, cutter, written, coefficients, limits, **sampling)
    out = {}
    if stated_d:
        out["max_deflection_mm"] = float(np.max(s["deflection"], initial=0.0))
    if stated_w:
        out["max_wall_error_mm"] = float(np.max(np.asarray(s["wall_error"])[final], initial=0.0))
    return out


def optimize_program(text: str, source: str, stock, cutter, coefficients, limits: FeedLimits, *, axis_limits,
                     plan_options, split: dict | None = None, sampling: dict | None = None,
                     work_offsets=None) -> FeedsResult:
    """Schedule the feeds of the program ``text`` (named ``source`` in errors), cut through ``stock``
    (ZMap in G54 work coordinates, not modified) by ``cutter``; cap each piece at what the feed plan
    (``axis_limits``, ``plan_options``) reaches in it; write the text (lossless, feeds_gcode) and
    re-simulate it. ``work_offsets``: (9, 3) G54…G59.3 [mm] the program's G55…G59 words select
    (:func:`stock_frame`)."""
    from netshape.force import simulate_program

    split = split or {}
    sampling = sampling or {}
    prog = read_program_text(text, source)
    tp = with_start(stock_frame(prog, work_offsets), stock)
    sched = schedule_feeds(stock, cutter, tp, coefficients, limits,
                           split_tolerance=split.get("split_tolerance", 0.1),
                           min_piece_mm=split.get("min_piece_mm", 1.0), **sampling)
    pieces = fg.merge_unsplittable(sched.pieces, fg.splittable_blocks(text, tp))
    pieces["feed"] = fg.round_feeds(pieces["feed"])
    opt_tp, which = fg.pieces_toolpath(tp, pieces)
    pieces = fg.cap_to_plan(pieces, which, _plan(opt_tp, axis_limits, plan_options))
    pieces["feed"] = fg.round_feeds(pieces["feed"])
    pieces = fg.merge_equal(pieces)
    opt_tp, which = fg.pieces_toolpath(tp, pieces)
    cycle_after = float(_plan(opt_tp, axis_limits, plan_options).stats["cycle_time_s"])
    cycle_before = float(_plan(tp, axis_limits, plan_options).stats["cycle_time_s"])
    lines, src = fg.scheduled_gcode_lines(text, tp.to_program(), pieces,
                                          fg.header_comment(stated(limits)))
    out_text = "\n".join(lines) + "\n"
    # the independent check: the written text read back and cut again by the force simulation
    written = with_start(stock_frame(read_program_text(out_text, source), work_offsets), stock)
    after = simulate_program(stock, cutter, written, coefficients, copy_stock=True, **sampling)
    src = np.asarray(src + [0], dtype=np.int64)
    a_line = src[np.clip([int(written.blocks[int(b)].line) - 1 for b in after.block], 0, len(src) - 1)]
    after_forces = (np.asarray(a_line, dtype=np.int64), np.asarray(after.peak_resultant, dtype=float))
    rows = fr.per_line(tp, cutter, sched.samples, pieces, after_forces)
    summ = fr.summary(source, "", limits, pieces, rows, cycle_before, cycle_after, sched.samples,
                      after_forces, _deflection_check(stock, cutter, written, coefficients, limits, sampling))
    return FeedsResult(text=out_text, summary=summ, rows=rows, schedule=sched, pieces=pieces, after=after,
                       program=tp)
