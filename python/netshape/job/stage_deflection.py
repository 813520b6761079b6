"""The deflection stage of the main job: the wall error tool deflection leaves along each 2-D contour
of the program (Cho & Suh: cantilever tool, surface generation, Z-map engagement) and, when asked, the
deflection-compensated program. Works in the stock frame (G54), like :mod:`netshape.job.stages`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .spec import Job
from .stages import Program, _sub_toolpath, coefficients_for, make_cutter, stock_frame_toolpath


@dataclass
class DeflectionResult:
    """Wall error along the path [mm] before and after deflection compensation, or why there is none."""

    available: bool
    reason: str = ""
    s_mm: np.ndarray = field(default_factory=lambda: np.zeros(0))       # path distance of each point
    before_mm: np.ndarray = field(default_factory=lambda: np.zeros(0))  # signed wall error
    after_mm: np.ndarray | None = None
    compensated: object = None                                          # Toolpath (G54 frame) or None
    info: dict = field(default_factory=dict)
    ranges: list = field(default_factory=list)                          # (s0, s1) [mm] of each contour


def contour_runs(tp) -> list[tuple[int, int]]:
    """(first, last) block indices of the runs of XY cutting moves at one constant Z (lines, and arcs in
    G17), in program order: the 2-D contours whose walls tool deflection shapes."""
    from netshape import toolpath as tpm

    runs: list[tuple[int, int]] = []
    cur: list[int] = []
    z = None
    for i, b in enumerate(tp.blocks):
        st_, en = np.asarray(b.start), np.asarray(b.end)
        ok = (b.kind != tpm.MotionKind.rapid and math.hypot(en[0] - st_[0], en[1] - st_[1]) > 1e-9
              and abs(en[2] - st_[2]) <= 1e-6
              and (b.kind != tpm.MotionKind.arc or b.plane == tpm.Plane.xy))
        if ok and cur and z is not None and abs(st_[2] - z) <= 1e-6:
            cur.append(i)
            continue
        if cur:
            runs.append((cur[0], cur[-1]))
        cur, z = ([i], float(st_[2])) if ok else ([], None)
    if cur:
        runs.append((cur[0], cur[-1]))
    return runs


def stage_deflection(job: Job, stock0, prog: Program, *, compensate: bool) -> DeflectionResult:
    """Wall error from tool deflection along the program (Cho & Suh: cantilever tool, surface
    generation, Z-map engagement) and, when asked, the deflection-compensated program.

    The program is cut in order on a copy of the stock; every contour (a run of XY cutting moves at one
    Z, :func:`contour_runs`) is evaluated on the stock as the moves before it left it, compensated with
    the job's scheme and reference level, and replaced by its compensated moves. A contour the model
    cannot evaluate (it never touches the stock, say) keeps its moves and is listed in ``info``. Where
    the tool is not a flat end mill, the result says so (``available`` False) instead of reporting zero
    error.

    It drives the deflection area's contour API: ``setup_path`` for one contiguous 2-D contour,
    ``predict_path`` (wall errors at the bottom, middle and top levels), ``compensate_path`` and
    ``compensated_blocks`` (the compensated moves and the contour block each came from)."""
    from netshape import deflection as nd
    from netshape import stock as nst
    from netshape.cutter import CutterKind
    from netshape.errors import Error

    cutter = make_cutter(job.tool)
    if cutter.kind != CutterKind.flat:
        return DeflectionResult(available=False, reason="deflection wall error: the model needs a flat end mill "
                                f"(tool.kind = {job.tool['kind']})")
    coeffs = coefficients_for(job, cutter)
    tp = stock_frame_toolpath(prog)
    blocks = list(tp.blocks)
    level = ("bottom", "middle", "top").index(job.compensate["deflection_level"])
    spacing = job.cutting["error_spacing_mm"]
    # path distance along the feed moves at the start of every block (the volumetric samples' measure)
    lengths = np.array([0.0 if b.kind == 0 else float(b.length()) for b in blocks])
    s_start = np.concatenate([[0.0], np.cumsum(lengths)])
    z = stock0.copy()
    out_blocks, s_all, before_all, after_all, skipped = [], [], [], [], []
    origin: list[int] = []  # index in tp.blocks of the block each of out_blocks came from
    unconverged: list[str] = []  # contours whose iteration stopped above the tolerance (where and why)
    iterations = 0
    done = 0
    for first, last in contour_runs(tp):
        if first > done:
            nst.sweep(z, cutter, _sub_toolpath(tp, blocks[done:first]))
            out_blocks.extend(blocks[done:first])
            origin.extend(range(done, first))
        run = blocks[first:last + 1]
        sub = _sub_toolpath(tp, run)
        rpm = job.cutting["spindle_rpm"] or abs(float(run[0].spindle_rpm))
        try:
            setup = nd.setup_path(sub, cutter, z, coefficients=coeffs, rpm=rpm, spacing=spacing)
            pred = nd.predict_path(setup)
        except ValueError as exc:
            skipped.append(f"line {run[0].line}: {' '.join(str(exc).split())}")
            out_blocks.extend(run)
            origin.extend(range(first, last + 1))
        else:
            nominal = np.asarray(setup.nominal, dtype=float)
            arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(nominal[:, :2], axis=0), axis=1))])
            s_all.append(s_start[first] + arc)
            before = np.asarray(pred.error, dtype=float)[:, level]
            before_all.append(before)
            if compensate:
                res = nd.compensate_path(setup, scheme=job.compensate["deflection_scheme"],
                                             level=job.compensate["deflection_level"])
                if not res.converged:
                    where = f"deflection compensation of the contour from line {run[0].line}: {res.message}"
                    if job.compensate["deflection_unconverged"] == "fail":
                        raise Error(where)
                    # the last iterate is written; its residual is the "after" error of these points
                    unconverged.append(" ".join(where.split()))
                iterations = max(iterations, int(res.iterations))
                after_all.append(np.asarray(res.after.error, dtype=float)[:, level])
                new, sub_origin = nd.compensated_blocks(setup, np.asarray(res.positions, dtype=float))
                for b in new:  # keep the source line (work offset, reports) of the contour
                    if b.line <= 0:
                        b.line = run[0].line
                out_blocks.extend(new)
                origin.extend(first + int(k) for k in sub_origin)
            else:
                after_all.append(before)
                out_blocks.extend(run)
                origin.extend(range(first, last + 1))
        nst.sweep(z, cutter, sub)
        done = last + 1
    out_blocks.extend(blocks[done:])
    origin.extend(range(done, len(blocks)))
    info = {"contours": len(s_all), "contours_skipped": skipped}
    if compensate:
        info["iterations"] = iterations
        info["contours_unconverged"] = unconverged
    if not s_all:
        why = skipped[0] if skipped else "the program has no 2-D contour (XY moves at one Z)"
        return DeflectionResult(available=False, reason=f"deflection wall error: no contour evaluated ({why})",
                                info=info)
    res = DeflectionResult(available=True, s_mm=np.concatenate(s_all), before_mm=np.concatenate(before_all),
                           after_mm=np.concatenate(after_all), info=info,
                           ranges=[(float(a[0]), float(a[-1])) for a in s_all])
    if compensate:
        res.compensated = tp.with_blocks(out_blocks, origin)
        if unconverged:
            res.reason = (f"compensation did not converge on {len(unconverged)} contour(s), the last iterate is "
                          f"written and its residual is the error after: {'; '.join(unconverged)}")
    return res
