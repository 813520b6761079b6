"""Deflection compensation judged on the program it writes.

:func:`compensate_checked` compensates a contour at the setup's samples, writes the compensated moves,
samples the written contour ``density`` times more densely and measures its wall against the drawing
(:func:`netshape.deflection.walls.check_against_drawing`). Where the written program misses the
tolerance at the reference level between samples (the offset curve bends at engagement entries and
exits) or is worse than the uncompensated program, samples of a denser drawing are added there and
the contour is compensated again, up to ``max_rounds`` times; a round that does not make the written
program better ends the refinement, and the best written program is kept. Last, where the written
program is worse than the uncompensated one between samples, the offsets of the samples around are
halved (then zeroed) until it is nowhere worse. What it reports is the last written
program's check, at every level: a 2-D offset moves the whole tool, so it cannot remove the taper
between the bottom and the top of the wall that the tool's bending leaves.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .. import _core
from .walls import (DrawingCheck, check_against_drawing, final_wall_points, generates_wall,
                    wall_remains_points)

_comp = _core.compensation
_LEVELS = ("bottom", "middle", "top")


@dataclass
class CheckedCompensation:
    """A compensation and the check of what it wrote.

    ``result`` the last compensation (its ``after`` at its own samples), ``setup`` the setup of its
    samples, ``blocks``/``origin`` the written moves (see ``compensated_blocks``), ``check`` the written
    program against the drawing at ``density``× the samples, ``before`` the uncompensated program's
    check on the same drawing, ``rounds`` the compensations run, ``final`` the final-wall flag of each
    dense drawing sample, ``active`` which of the setup's samples are compensated (final walls),
    ``offsets`` the offsets written at them [mm] (None: the result's), ``normals`` the samples' wall normals
    (None: the result's; set where samples were added after the compensation, see _refine_entries)."""

    result: object
    setup: object
    blocks: list
    origin: list
    check: DrawingCheck
    before: DrawingCheck
    rounds: int
    final: np.ndarray
    level: int
    tolerance: float
    active: np.ndarray | None = None
    offsets: np.ndarray | None = None
    normals: np.ndarray | None = None

    @property
    def after_mm(self) -> dict:
        return self.check.max_mm()

    @property
    def before_mm(self) -> dict:
        return self.before.max_mm()

    @property
    def converged(self) -> bool:
        return bool(self.result.converged) and self.after_mm[_LEVELS[self.level]] <= self.tolerance * (1 + 1e-9)

    @property
    def sample_normals(self) -> np.ndarray:
        """The wall normal of each of ``setup``'s samples (n × 2)."""
        return np.asarray(self.result.normals if self.normals is None else self.normals, dtype=float)

    @property
    def worse_points(self) -> int:
        """Written-program samples whose |error| at the reference level exceeds the uncompensated one's
        (by more than 1 % of the tolerance) — 0 when the never-worse rule holds."""
        b = np.interp(self.check.s, self.before.s, np.abs(self.before.error[:, self.level]))
        a = np.abs(self.check.error[:, self.level])
        return int(np.sum(self.check.final & (a > b + 0.01 * self.tolerance)))


def dense_drawing(setup, density: int):
    """The setup's contour sampled ``density`` times more densely: (points, owner, coarse) with coarse
    marking the setup's own samples."""
    from . import contour_samples

    pts, owner, first, last, _ = contour_samples(setup.program, setup.spacing, density)
    # in each block the samples j = d, 2d, … (and the contour's first point) are the sparse ones
    coarse = np.zeros(len(pts), dtype=bool)
    coarse[0] = True
    count = 0
    for i in range(1, len(pts)):
        count = count + 1 if owner[i] == owner[i - 1] else 1
        coarse[i] = count % density == 0
    return pts, owner, coarse


def _block_flags(owner_from, flags_from, owner_to):
    """Per-point flags of one sampling carried to another by block (final-wall status is per block,
    plus the start of each final-wall block, see walls.final_wall_points). A block's last point is the
    next block's start and carries that block's flag, so a block's own status is read before it."""
    owner_from, owner_to = np.asarray(owner_from), np.asarray(owner_to)
    flags_from = np.asarray(flags_from, dtype=bool)
    block = {}
    for b in np.unique(owner_from):
        sel = owner_from == b
        block[int(b)] = bool(np.any(flags_from[sel][:-1])) if np.sum(sel) > 1 else bool(flags_from[sel][0])
    out = np.array([block.get(int(b), False) for b in owner_to], dtype=bool)
    starts = np.flatnonzero(out[1:] & (owner_to[1:] != owner_to[:-1]))
    out[starts] = True
    return out


def compensate_checked(setup, *, scheme: str = "accelerated", level: str = "middle", tolerance: float = 5e-4,
                       discount: float = 1.0, max_iterations: int = 50, anderson_depth: int = 5,
                       density: int = 4, max_rounds: int = 4, final=None, later_program=None,
                       block_offset: int = 0, arc_tolerance: float | None = None) -> CheckedCompensation:
    """Compensate ``setup``'s contour and check the written program (module docstring).

    The drawing is sampled ``density`` times more densely than the setup for the checks, and the
    samples that refinement may add come from a pool 4 × ``density`` times denser. ``final``: per
    point of the ``density``-times denser drawing, whether its wall is a final wall (None: computed
    from ``later_program`` — the program whose later moves may cut the wall, default the setup's
    program — whose block b is the setup program's block b − ``block_offset``)."""
    from . import compensation_options

    lv = _LEVELS.index(level)
    arc_tol = tolerance if arc_tolerance is None else arc_tolerance
    d_pts, d_owner, _ = dense_drawing(setup, density)
    p_pts, p_owner, selected = dense_drawing(setup, 4 * density)
    opt = setup.options
    normals = np.asarray(_comp.wall_normals(d_pts, setup.side))
    before_r = _comp.path_wall_errors(setup.model, setup.cutter, setup.stock, d_pts, normals,
                                      np.zeros(len(d_pts)), opt)
    if final is None:
        prog = setup.program if later_program is None else later_program
        remains = wall_remains_points(prog, d_owner + block_offset, d_pts, normals, np.asarray(before_r.depth),
                                      setup.cutter.radius)
        final = final_wall_points(d_owner, remains, generates_wall(before_r, setup.side))
    final = np.asarray(final, dtype=bool)
    p_final = _block_flags(d_owner, final, p_owner)
    before = check_against_drawing(setup.model, setup.cutter, setup.stock, d_pts, d_pts, final, setup.side, opt)
    p_arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(p_pts[:, 0]), np.diff(p_pts[:, 1])))])
    rounds = 0

    def finish(out, sel):
        # the unrefined written program, the wall starts refined (_refine_entries) and the refined one
        # corrected by its check (_check_corrected), each after never-worse: the best of them
        best = _never_worse(out, d_pts, density, arc_tol)
        if not out.result.converged:
            return best
        refined = _refine_entries(out, p_pts, sel, d_pts, density, arc_tol)
        for cand in (refined, _check_corrected(refined, d_pts, density, arc_tol)):
            if cand is not out:
                cand = _never_worse(cand, d_pts, density, arc_tol)
                best = cand if _better(cand, best) else best
        return best

    best = None  # (largest written-program error on final walls, + 1 when not converged; result)
    while True:
        rounds += 1
        o = compensation_options(setup, scheme=scheme, level=level, tolerance=tolerance, discount=discount,
                                 max_iterations=max_iterations, anderson_depth=anderson_depth,
                                 active=p_final[selected])
        nominal = p_pts[selected]
        res = _comp.compensate_deflection(setup.model, setup.cutter, setup.stock, nominal, o)
        sub = replace(setup, nominal=nominal, owner=p_owner[selected])
        active = p_final[selected]
        C = _entry_offsets(sub, res, active, lv, tolerance)
        positions = nominal.copy()
        positions[:, :2] += C[:, None] * np.asarray(res.normals, dtype=float)
        blocks, origin, check = _write_and_check(sub, positions, d_pts, final, density, arc_tol, active)
        out = CheckedCompensation(res, sub, blocks, origin, check, before, rounds, final, lv, float(tolerance),
                                  active, C)
        b_ref = np.interp(check.s, before.s, np.abs(before.error[:, lv]))
        a_ref = np.abs(check.error[:, lv])
        bad = check.final & ((a_ref > tolerance) | (a_ref > b_ref + 0.01 * tolerance))
        score = float(np.max(a_ref[check.final], initial=0.0)) + (0.0 if res.converged else 1.0)
        if best is not None and score >= best[0]:
            return finish(best[1], best[2])  # refining did not help: the best one
        best = (score, out, selected)
        if not np.any(bad) or rounds >= max_rounds or not res.converged:
            return finish(out, selected)
        # the pool's samples within one check spacing of each miss (largest misses first, at most as
        # many new samples as the setup has)
        grow = np.zeros(len(p_pts), dtype=bool)
        budget = int(np.sum(selected))
        for i in np.flatnonzero(bad)[np.argsort(-a_ref[bad])]:
            near = (np.abs(p_arc - check.s[i]) <= setup.spacing / density) & ~selected & ~grow
            if np.sum(near) > budget:
                break
            grow |= near
            budget -= int(np.sum(near))
        if not np.any(grow):
            return finish(out, selected)
        selected = selected | grow


def _never_worse(out: CheckedCompensation, d_pts, density: int, arc_tol: float) -> CheckedCompensation:
    """Where the written program is worse than the uncompensated one between samples, halve the offset
    of the sample nearer each worse point, once per round however many worse points it is nearest to
    (six rounds at most, then zero both samples around each), write and check again."""
    setup, res = out.setup, out.result
    nominal = np.asarray(setup.nominal, dtype=float)
    normals = out.sample_normals
    C = np.asarray(res.offsets if out.offsets is None else out.offsets, dtype=float).copy()
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(nominal[:, 0]), np.diff(nominal[:, 1])))])
    for attempt in range(7):
        b = np.interp(out.check.s, out.before.s, np.abs(out.before.error[:, out.level]))
        worse = out.check.final & (np.abs(out.check.error[:, out.level]) > b + 0.01 * out.tolerance)
        if not np.any(worse):
            return out
        # once per sample and round: the sample nearer each worse point (whose offset the written line
        # there follows most), both neighbours in the last round (zeroed: the program as written)
        hit = np.zeros(len(C), dtype=bool)
        for s in out.check.s[worse]:
            k = int(np.clip(np.searchsorted(arc, s), 1, len(arc) - 1))
            if attempt == 6:
                hit[k - 1:k + 1] = True
            else:
                hit[k - 1 if s - arc[k - 1] <= arc[k] - s else k] = True
        C[hit] = 0.0 if attempt == 6 else 0.5 * C[hit]
        positions = nominal.copy()
        positions[:, :2] += C[:, None] * normals
        blocks, origin, check = _write_and_check(setup, positions, d_pts, out.final, density, arc_tol,
                                                 out.active)
        out = CheckedCompensation(res, setup, blocks, origin, check, out.before, out.rounds, out.final, out.level,
                                  out.tolerance, out.active, C.copy(), out.normals)
    return out


def _entry_offsets(setup, res, active, level: int, tolerance: float, iterations: int = 4) -> np.ndarray:
    """The compensation's offsets with the first sample of each final wall (where ``active`` starts)
    solved for its own error at ``level``, the other samples held (fixed-point steps C ← C + e, at most
    ``iterations``). The C++ schemes tie a corner's offset to the next sample's, since at a corner
    between two walls a polyline cannot follow the turn's one-instant engagement on both sides; where
    the wall starts after a move written as programmed, the written program reaches the corner along
    the offset (compensated_blocks), so the corner's own offset is written exactly there and the wall's
    first stretch, still in the corner's engagement, ramps from it to the next sample's offset."""
    C = np.asarray(res.offsets, dtype=float).copy()
    active = np.asarray(active, dtype=bool)
    entries = np.flatnonzero(active[1:] & ~active[:-1]) + 1
    e = np.asarray(res.after.error, dtype=float)[:, level]
    normals = np.asarray(res.normals, dtype=float)
    for _ in range(iterations):
        if not entries.size or np.max(np.abs(e[entries])) <= tolerance:
            break
        C[entries] += e[entries]  # e = −C − δ·n: δ held for the step
        r = _comp.path_wall_errors(setup.model, setup.cutter, setup.stock, setup.nominal, normals, C,
                                   setup.options)
        e = np.asarray(r.error, dtype=float)[:, level]
    return C


def _write_and_check(setup, positions, d_pts, final, density: int, arc_tol: float, active=None):
    """The compensated moves through ``positions`` (``active``: the compensated samples, see
    ``compensated_blocks``) and their check against the drawing ``d_pts``: the written program at
    ``density`` times its own sample density (every written block in at least ``density`` pieces).
    Returns (blocks, origin, DrawingCheck)."""
    from . import compensated_blocks, contour_samples

    blocks, origin = compensated_blocks(setup, positions, arc_tolerance=arc_tol, active=active)
    written = setup.program.with_blocks(blocks, origin)
    w_pts = contour_samples(written, setup.spacing, density)[0]
    check = check_against_drawing(setup.model, setup.cutter, setup.stock, w_pts, d_pts, final, setup.side,
                                  setup.options)
    return blocks, origin, check


def _refine_entries(out: CheckedCompensation, p_pts, selected, d_pts, density: int, arc_tol: float,
                    iterations: int = 4) -> CheckedCompensation:
    """Samples added where a final wall starts and its offsets solved point by point in path order.

    Entering a wall, the engagement ramps up over about one tool diameter of travel and the offset the
    wall needs bends within the first sample spacings, where the written straight ramp between two
    samples misses it. In each sample interval within one diameter after an entry where the written
    program's check misses the tolerance, samples of the check's density are added (offsets interpolated
    from the interval's ends); the added samples and each refined interval's end are solved for their own
    errors, in path order, with the offsets before them held: a point's engagement depends only on the
    moves before it, so this Gauss-Seidel sweep in path order is a triangular solve, where the schemes'
    simultaneous update of dense samples is driven by the strong coupling of a sample to the one just
    before it (that one's disc sets how much wall is left to cut) and diverges. The entry corner is tied to
    the first sample after it: its engagement is the turn's, one instant, and its own offset (solved by
    _entry_offsets) overcuts the stretch after it, where the engagement has already fallen. Per sample: a
    fixed-point step C ← C + e, then secant steps bounded by 2|e|. compensate_checked keeps it only when,
    never-worse applied to both, its written program's largest error on final walls at the reference
    level is below the unrefined one's with no more worse points."""
    setup, res, lv, tol = out.setup, out.result, out.level, out.tolerance
    if out.active is None:
        return out
    active = np.asarray(out.active, dtype=bool)
    C = np.asarray(res.offsets if out.offsets is None else out.offsets, dtype=float)
    normals = out.sample_normals
    idx = np.flatnonzero(selected)  # pool index of each sample
    p_arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(p_pts[:, 0]), np.diff(p_pts[:, 1])))])
    arc = p_arc[idx]
    chk = out.check
    miss = chk.final & (np.abs(chk.error[:, lv]) > tol)
    reach = 2.0 * setup.cutter.radius
    step = max(1, (len(p_pts) - 1) // max(1, len(d_pts) - 1))  # pool points per check spacing
    add, ends, solve_from, solve_to = [], [], [], []
    for k0 in np.flatnonzero(active[1:] & ~active[:-1]) + 1:
        last = None
        for k in range(k0, len(idx) - 1):
            if arc[k] - arc[k0] > reach or not active[k + 1]:
                break
            if np.any(miss & (chk.s > arc[k]) & (chk.s < arc[k + 1])):
                add.extend(range(idx[k] + step, idx[k + 1] - step // 2, step))
                ends.append(idx[k + 1])
                last = k + 1
        if last is not None:
            solve_from.append(p_arc[idx[k0]])
            solve_to.append(p_arc[idx[min(last + 1, len(idx) - 1)]])
    if not add:
        return out
    sel2 = selected.copy()
    sel2[np.asarray(add, dtype=np.int64)] = True
    idx2 = np.flatnonzero(sel2)
    old = np.isin(idx2, idx)
    arc2 = p_arc[idx2]
    nominal2 = p_pts[idx2]
    C2 = np.interp(arc2, arc, C)
    normals2 = np.asarray(_comp.wall_normals(nominal2, setup.side), dtype=float)
    normals2[old] = normals
    active2 = np.interp(arc2, arc, active.astype(float)) > 0.5
    active2[old] = active
    owner = np.asarray(setup.owner)
    owner2 = np.empty(len(idx2), dtype=owner.dtype)
    owner2[old] = owner
    pos = np.searchsorted(idx, idx2[~old])  # an added sample lies inside the block of the sample after it
    owner2[~old] = owner[np.minimum(pos, len(idx) - 1)]
    sub = replace(setup, nominal=nominal2, owner=owner2)

    def errors(c):
        r = _comp.path_wall_errors(setup.model, setup.cutter, setup.stock, nominal2, normals2, c,
                                   setup.options)
        return np.asarray(r.error, dtype=float)[:, lv]

    for a0, a1 in zip(solve_from, solve_to):
        k0 = int(np.argmin(np.abs(arc2 - a0)))
        solve = ~old | np.isin(idx2, ends)  # the added samples and the ends of their intervals
        solve[min(k0 + 1, len(solve) - 1)] = True  # the corner's tie
        for j in np.flatnonzero((arc2 > a0 + 1e-12) & (arc2 <= a1 + 1e-12) & active2 & solve):
            prev = None
            if j == k0 + 1:
                C2[k0] = C2[j]
            for _ in range(iterations):
                e = errors(C2)[j]
                if abs(e) <= 0.5 * tol:
                    break
                if prev is None or abs(e - prev[1]) < 1e-12:
                    dc = e  # e = −C − δ·n: δ held
                else:
                    dc = -e * (C2[j] - prev[0]) / (e - prev[1])
                    dc = float(np.clip(dc, -2 * abs(e), 2 * abs(e)))
                prev = (C2[j], e)
                C2[j] += dc
                if j == k0 + 1:
                    C2[k0] = C2[j]
    positions = nominal2.copy()
    positions[:, :2] += C2[:, None] * normals2
    blocks, origin, check = _write_and_check(sub, positions, d_pts, out.final, density, arc_tol, active2)
    new = CheckedCompensation(res, sub, blocks, origin, check, out.before, out.rounds, out.final, lv, tol,
                              active2, C2, normals2)
    return new


def _better(a: CheckedCompensation, b: CheckedCompensation, count_worse: bool = True,
            slack: float = 0.0) -> bool:
    """Whether written program ``a`` is better than ``b`` at the reference level on final walls: a largest
    |error| no larger (by more than ``slack``), no more worse points (unless not ``count_worse``), and a
    smaller mean |error|."""
    ea = np.abs(a.check.error[a.check.final, a.level])
    eb = np.abs(b.check.error[b.check.final, b.level])
    if not ea.size or not eb.size:
        return False
    return (ea.max() <= eb.max() + slack + 1e-9 and (not count_worse or a.worse_points <= b.worse_points)
            and float(np.mean(ea)) < float(np.mean(eb)))


def _check_corrected(out: CheckedCompensation, d_pts, density: int, arc_tol: float,
                     iterations: int = 3) -> CheckedCompensation:
    """The offsets moved by the written program's checked error at the samples (C ← C + e, e read from
    the check at each compensated sample's arc length), while that lowers the largest error on final
    walls. A sample's own error is −C − δ·n; the check's is the deepest cut of the deflected circles,
    which on a curved wall also moves with the tangential deflection (a circle shifted along a concave
    arc of centre radius ρ by t cuts t²/(2ρ) deeper). The correction is that difference: small and
    smooth along the wall, unlike a full update of dense samples."""
    if out.active is None:
        return out
    setup, lv = out.setup, out.level
    nominal = np.asarray(setup.nominal, dtype=float)
    normals = out.sample_normals
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(nominal[:, 0]), np.diff(nominal[:, 1])))])
    active = np.asarray(out.active, dtype=bool)
    inner = active.copy()  # a wall's first and last samples are written with the moves along the offset
    inner[1:] &= active[:-1]
    inner[:-1] &= active[1:]
    inner[[0, -1]] = False
    best = out
    for _ in range(iterations):
        chk = best.check
        fin = chk.final  # the check's other points (lead-ins, walls cut away later) are no target
        e = np.interp(arc, chk.s[fin], chk.error[fin, lv]) if np.any(fin) else np.zeros(len(arc))
        C = np.asarray(best.result.offsets if best.offsets is None else best.offsets, dtype=float).copy()
        C[inner] += e[inner]
        positions = nominal.copy()
        positions[:, :2] += C[:, None] * normals
        blocks, origin, check = _write_and_check(setup, positions, d_pts, out.final, density, arc_tol, active)
        new = replace(best, blocks=blocks, origin=origin, check=check, offsets=C)
        # never-worse, after, takes the worse points; compensate_checked compares the end results
        if not _better(new, best, count_worse=False, slack=out.tolerance):
            break
        best = new
    return best
