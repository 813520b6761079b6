"""The deflection stage of the main job: the wall error tool deflection leaves along each 2-D contour
of the program (Cho & Suh: cantilever tool, surface generation, Z-map engagement) and, when asked, the
deflection-compensated program. Works in the stock frame (G54), like :mod:`netshape.job.stages`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .spec import Job
from .program import Program, _sub_toolpath, stock_frame_toolpath
from .stages import coefficients_for, make_cutter


@dataclass
class DeflectionResult:
    """Wall error of the part's final walls [mm] before and after deflection compensation, or why there
    is none. ``s_mm``/``before_mm`` are the uncompensated program's samples on final walls (path
    distance along the feed moves, signed error at the reference level), ``s_after_mm``/``after_mm``
    the written program's; ``points_mm``/``normals`` the stock-frame positions and wall normals of the
    ``before`` samples; ``contours`` one entry per contour piece (see :func:`stage_deflection`)."""

    available: bool
    reason: str = ""
    s_mm: np.ndarray = field(default_factory=lambda: np.zeros(0))       # path distance of each point
    before_mm: np.ndarray = field(default_factory=lambda: np.zeros(0))  # signed wall error
    after_mm: np.ndarray | None = None
    s_after_mm: np.ndarray | None = None
    compensated: object = None                                          # Toolpath (G54 frame) or None
    info: dict = field(default_factory=dict)
    ranges: list = field(default_factory=list)                          # (s0, s1) [mm] of each final wall
    points_mm: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    normals: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    levels_mm: dict = field(default_factory=dict)                       # {"before"/"after": {level: max}}
    unconverged_points: list = field(default_factory=list)              # {"line", "x_mm", "y_mm", "error_mm"}
    status: str = "ok"                                                  # ok, unconverged, skipped


#: Unconverged points listed per contour run in the job's deflection block (the largest first); the
#: block counts the rest in ``unconverged_points_omitted``.
UNCONVERGED_POINTS_LISTED = 50


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


def unconverged_points(check, level: int, tol: float, pieces: list, arc, owner,
                       limit: int = UNCONVERGED_POINTS_LISTED):
    """The written program's final-wall samples of one contour run whose |error| at ``level`` exceeds
    ``tol``, largest first: ``(points, left_out)`` with at most ``limit`` points ``{"line", "x_mm",
    "y_mm", "error_mm"}`` and the number not listed. ``line`` is the first line of the contour piece
    (walls.contour_pieces, the entries of ``info["contours"]``) holding the block of the drawing that
    the sample's foot ``check.s`` lies on (the segment of the samples ``arc`` [mm] that ends at sample
    k belongs to block ``owner[k]``)."""
    err = np.asarray(check.error, dtype=float)[:, level]
    bad = np.flatnonzero(np.asarray(check.final, dtype=bool) & (np.abs(err) > tol))
    bad = bad[np.argsort(-np.abs(err[bad]), kind="stable")]
    arc, owner = np.asarray(arc, dtype=float), np.asarray(owner)
    out = []
    for i in bad[:limit]:
        block = owner[int(np.clip(np.searchsorted(arc, check.s[i], side="left"), 1, len(arc) - 1))]
        pc = next((p for p in pieces if p["first_block"] <= block <= p["last_block"]), pieces[-1])
        out.append({"line": int(pc["line"]), "x_mm": float(check.points[i, 0]),
                    "y_mm": float(check.points[i, 1]), "error_mm": float(err[i])})
    return out, int(max(len(bad) - limit, 0))


def stage_deflection(job: Job, stock0, prog: Program, *, compensate: bool) -> DeflectionResult:
    """Wall error from tool deflection along the program (Cho & Suh: cantilever tool, surface
    generation, Z-map engagement) and, when asked, the deflection-compensated program.

    The program is cut in order on a copy of the stock; every contour (a run of XY cutting moves at one
    Z, :func:`contour_runs`) is evaluated on the stock as the moves before it left it, its own earlier
    moves removed exactly (the tool's swept discs). Only the walls that remain at the end of the
    program count (netshape.deflection.walls): a block whose wall a later move cuts away (clearing
    rings, roughing steps) is reported with ``final_wall`` false, keeps its moves and adds nothing to
    the error. Contours with final walls are compensated with the job's scheme and reference level
    and the written moves are checked against the drawing at four times the sample density
    (netshape.deflection.checked); that check is the error after.

    ``info["contours"]`` lists every contour piece (a run of blocks with one final-wall status):
    ``line``, ``final_wall``, ``converged``, ``iterations``, ``max_residual_mm``;
    ``info["contours_skipped"]`` the contours that could not be evaluated, with the reason. A tool
    that is not a flat end mill makes the result unavailable (``available`` False) rather than zero."""
    from netshape import deflection as nd
    from netshape import stock as nst
    from netshape.cutter import CutterKind
    from netshape.deflection import walls
    from netshape.deflection.checked import compensate_checked
    from netshape.errors import Error

    cutter = make_cutter(job.tool)
    if cutter.kind != CutterKind.flat:
        return DeflectionResult(available=False, status="skipped",
                                reason="deflection wall error: the model needs a flat end mill "
                                f"(tool.kind = {job.tool['kind']})")
    coeffs = coefficients_for(job, cutter)
    tp = stock_frame_toolpath(prog)
    blocks = list(tp.blocks)
    level_name = job.compensate["deflection_level"]
    level = ("bottom", "middle", "top").index(level_name)
    tol = 5e-4
    spacing = job.cutting["error_spacing_mm"]
    # path distance along the feed moves at the start of every block (the volumetric samples' measure)
    lengths = np.array([0.0 if int(b.kind) == 0 else float(b.length()) for b in blocks])
    s_start = np.concatenate([[0.0], np.cumsum(lengths)])
    z = stock0.copy()
    out_blocks, skipped, contours = [], [], []
    s_b, e_b, s_a, e_a, pts_b, nrm_b, ranges, unconv_pts = [], [], [], [], [], [], [], []
    lv_before, lv_after = np.zeros(3), np.zeros(3)
    origin: list[int] = []  # index in tp.blocks of the block each of out_blocks came from
    iterations = 0
    unconv_omitted = 0
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
            setup = nd.setup_path(sub, cutter, z, coefficients=coeffs, rpm=rpm, spacing=spacing,
                                  feed_per_tooth=job.cutting["feed_per_tooth_mm"])
            pred = nd.predict_path(setup)
        except ValueError as exc:
            skipped.append({"line": int(run[0].line), "reason": " ".join(str(exc).split())})
            out_blocks.extend(run)
            origin.extend(range(first, last + 1))
            nst.sweep(z, cutter, sub)
            done = last + 1
            continue
        nominal = np.asarray(setup.nominal, dtype=float)
        normals = np.asarray(nd.wall_normals(nominal, setup.side))
        remains = walls.wall_remains_points(tp, setup.owner + first, nominal, normals, np.asarray(pred.depth),
                                            cutter.radius)
        final = walls.final_wall_points(setup.owner, remains, walls.generates_wall(pred, setup.side))
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(nominal[:, :2], axis=0), axis=1))])
        err = np.asarray(pred.error, dtype=float)
        pieces = walls.contour_pieces(setup.owner, final, lambda b: run[b].line)
        chk = None
        if compensate and np.any(final):
            chk = compensate_checked(setup, scheme=job.compensate["deflection_scheme"], level=level_name,
                                     tolerance=tol, later_program=tp, block_offset=first)
            res = chk.result
            iterations = max(iterations, int(res.iterations))
            if not chk.converged and job.compensate["deflection_unconverged"] == "fail":
                raise Error(f"deflection compensation of the contour from line {run[0].line}: {res.message}")
            new, sub_origin = chk.blocks, chk.origin
            for b in new:  # keep the source line (work offset, reports) of the contour
                if b.line <= 0:
                    b.line = run[0].line
            out_blocks.extend(new)
            origin.extend(first + int(k) for k in sub_origin)
            # the written program's samples on final walls: after; the drawing's: before
            d_arc = chk.before.s
            fin_b, fin_a = chk.before.final & chk.before.engaged, chk.check.final
            s_b.append(s_start[first] + d_arc[fin_b])
            e_b.append(chk.before.error[fin_b, level])
            s_a.append(s_start[first] + chk.check.s[fin_a])
            e_a.append(chk.check.error[fin_a, level])
            pts_b.append(chk.before.points[fin_b])
            nrm_b.append(np.asarray(nd.wall_normals(chk.before.points, setup.side))[fin_b])
            lv_before = np.maximum(lv_before, list(chk.before_mm.values()))
            lv_after = np.maximum(lv_after, list(chk.after_mm.values()))
            listed, left_out = unconverged_points(chk.check, level, tol, pieces, arc, setup.owner)
            unconv_pts.extend(listed)
            unconv_omitted += left_out
        else:
            fin = final & np.asarray(pred.engaged, dtype=bool)
            s_b.append(s_start[first] + arc[fin])
            e_b.append(err[fin, level])
            s_a.append(s_start[first] + arc[fin])
            e_a.append(err[fin, level])
            pts_b.append(nominal[fin])
            nrm_b.append(normals[fin])
            if np.any(fin):
                mx = np.abs(err[fin]).max(axis=0)
                lv_before = np.maximum(lv_before, mx)
                lv_after = np.maximum(lv_after, mx)
            out_blocks.extend(run)
            origin.extend(range(first, last + 1))
        for pc in pieces:
            entry = {"line": pc["line"], "final_wall": pc["final_wall"]}
            if pc["final_wall"]:
                fin = final[pc["points"]]
                ranges.append((float(s_start[first] + arc[pc["points"]][fin][0]),
                               float(s_start[first] + arc[pc["points"]][fin][-1])))
                if chk is not None:
                    lo, hi = arc[pc["points"]][0], arc[pc["points"]][-1]
                    on = chk.check.final & (chk.check.s >= lo - 1e-9) & (chk.check.s <= hi + 1e-9)
                    resid = float(np.max(np.abs(chk.check.error[on, level]))) if np.any(on) else 0.0
                    entry.update({"converged": bool(chk.converged), "iterations": int(chk.result.iterations),
                                  "max_residual_mm": resid})
                else:
                    entry.update({"converged": None, "iterations": 0, "max_residual_mm": None})
            contours.append(entry)
        nst.sweep(z, cutter, sub)
        done = last + 1
    out_blocks.extend(blocks[done:])
    origin.extend(range(done, len(blocks)))
    unconverged = [c for c in contours if c["final_wall"] and c["converged"] is False]
    info = {"contours": contours, "contours_skipped": skipped}
    if compensate:
        info["iterations"] = iterations
        info["contours_unconverged"] = [c["line"] for c in unconverged]
        info["unconverged_points_omitted"] = unconv_omitted
    if not contours:
        why = skipped[0]["reason"] if skipped else "the program has no 2-D contour (XY moves at one Z)"
        return DeflectionResult(available=False, status="skipped", info=info,
                                reason=f"deflection wall error: no contour evaluated ({why})")
    cat = (lambda xs, w=None: np.concatenate(xs) if xs else np.zeros(0 if w is None else (0, w)))
    res = DeflectionResult(available=True, s_mm=cat(s_b), before_mm=cat(e_b), s_after_mm=cat(s_a),
                           after_mm=cat(e_a), info=info, ranges=ranges, points_mm=cat(pts_b, 3),
                           normals=cat(nrm_b, 2), unconverged_points=unconv_pts,
                           levels_mm={"before": dict(zip(("bottom", "middle", "top"), map(float, lv_before))),
                                      "after": dict(zip(("bottom", "middle", "top"), map(float, lv_after)))})
    if compensate:
        res.compensated = tp.with_blocks(out_blocks, origin)
    if unconverged:
        res.status = "unconverged"
        res.reason = (f"compensation did not reach the tolerance on {len(unconverged)} final-wall contour(s) "
                      f"(lines {', '.join(str(c['line']) for c in unconverged)}); the best iterate is written")
    elif skipped:
        res.status = "skipped"
        res.reason = f"{len(skipped)} contour(s) skipped: " + "; ".join(
            f"line {c['line']}: {c['reason']}" for c in skipped)
    return res
