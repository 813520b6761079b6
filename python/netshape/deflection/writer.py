"""The compensated program a deflection compensation writes: the contour's blocks replaced by lines and
arcs through the compensated points, the moves into and out of a final wall run along its offset, and
the program's other records kept in place (netshape.deflection re-exports both functions)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from . import PathSetup


def compensated_program(setup: PathSetup, positions: np.ndarray, *, arc_tolerance: float = 5e-4, active=None):
    """The program with its contour replaced by the compensated points ``positions`` (n, 3): along an XY
    arc block of the original, the longest runs of points that lie within ``arc_tolerance`` [mm] of one
    arc about the same centre (same direction, radius interpolated by angle between the run's ends, as
    netshape.toolpath reads such arcs) become arcs, the rest lines; every other block becomes lines
    through its points. Each new block carries the feed, spindle, tool and plane of the block its
    points came from; the blocks before and after the contour are kept, joined by a line where the
    compensated ends differ from the nominal ones. The program's non-motion records (comments, M/S/T
    words, dwells, offsets) stay where they were relative to the moves they came with.

    ``active`` (n) bool, optional: the points that are compensated (final walls). Where the path passes
    from a point written as programmed to a compensated one (a lead-in into the finish wall), it runs
    to the compensated point's programmed position and then along its offset; where a compensated run
    ends, it returns along the offset to the programmed position first. So no move written as
    programmed (a lead-in, a lead-out) crosses the drawing's wall line next to the wall, and the wall's
    offset starts and ends exactly where the final wall does."""
    new, origin = compensated_blocks(setup, positions, arc_tolerance=arc_tolerance, active=active)
    return setup.program.with_blocks(new, origin)


def compensated_blocks(setup: PathSetup, positions: np.ndarray, *, arc_tolerance: float = 5e-4, active=None):
    """The blocks of :func:`compensated_program` and, for each, the index of the program block it came
    from (non-decreasing): what ``Toolpath.with_blocks`` needs to keep the non-motion records in place."""
    blocks = list(setup.program.blocks)
    contour = blocks[setup.first:setup.last + 1]
    nominal = np.asarray(setup.nominal, dtype=float)
    positions = np.asarray(positions, dtype=float)
    # the contour block each sampled point ends
    if setup.owner is not None and len(setup.owner) == len(nominal):
        owner = np.asarray(setup.owner, dtype=np.int64) - setup.first
    else:  # by arc length along the nominal contour
        ends = np.cumsum([b.length() for b in contour])
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(nominal[:, 0]), np.diff(nominal[:, 1])))])
        scale = ends[-1] / arc[-1] if arc[-1] > 0 else 1.0
        owner = np.minimum(np.searchsorted(ends, arc * scale - 1e-9), len(contour) - 1)
    if active is not None:
        positions, owner = _enter_along_offsets(nominal, positions, owner, active)
    new = blocks[:setup.first]
    origin = list(range(setup.first))  # index of the original block each new block came from
    start = np.asarray(contour[0].start, dtype=float)
    if np.linalg.norm(positions[0] - start) > 1e-6:
        new.append(_line(contour[0], start, positions[0]))
        origin.append(setup.first)
    i = 1
    n = len(positions)
    while i < n:
        bi = owner[i]
        j = i
        while j + 1 < n and owner[j + 1] == bi:
            j += 1
        blk = contour[bi]
        pts = positions[i - 1:j + 1]
        if int(blk.kind) == 2 and blk.turns == 1 and str(blk.plane).split(".")[-1] == "xy":
            # greedy: the longest runs of points that stay within the tolerance of one arc; a run of two
            # points is an arc too (its chord would cut inside the arc by its sagitta, 9 µm for 0.47 mm at
            # R3), a line only where the ends are not on one arc (a move along the offset)
            a = 0
            while a < len(pts) - 1:
                b = a + 1
                while b + 1 < len(pts) and _fits_arc(blk, pts[a:b + 2], arc_tolerance):
                    b += 1
                arc_ok = b - a >= 2 or _fits_arc(blk, pts[a:b + 1], arc_tolerance)
                new.append(_arc(blk, pts[a], pts[b]) if arc_ok else _line(blk, pts[a], pts[b]))
                origin.append(setup.first + int(bi))
                a = b
        else:
            for k in range(1, len(pts)):
                new.append(_line(blk, pts[k - 1], pts[k]))
                origin.append(setup.first + int(bi))
        i = j + 1
    end = np.asarray(contour[-1].end, dtype=float)
    if np.linalg.norm(positions[-1] - end) > 1e-6:
        new.append(_line(contour[-1], positions[-1], end))
        origin.append(setup.last)
    new.extend(blocks[setup.last + 1:])
    origin.extend(range(setup.last + 1, len(blocks)))
    return new, origin


def _enter_along_offsets(nominal, positions, owner, active):
    """``positions``/``owner`` with the programmed position of a compensated point inserted where the
    compensation starts (before it) and ends (after it): the path from or to a point written as
    programmed then reaches the compensated point along its offset (see compensated_program)."""
    active = np.asarray(active, dtype=bool)
    if len(active) != len(positions):
        raise ValueError(f"active: {len(active)} flags for {len(positions)} points")
    rows, own = [positions[0]], [owner[0]]
    for i in range(1, len(positions)):
        if active[i] and not active[i - 1] and np.linalg.norm(positions[i] - nominal[i]) > 1e-9:
            rows.append(nominal[i])       # into the wall: to the programmed point, then along the offset
            own.append(owner[i])
        elif active[i - 1] and not active[i] and np.linalg.norm(positions[i - 1] - nominal[i - 1]) > 1e-9:
            rows.append(nominal[i - 1])   # out of the wall: back along the offset first
            own.append(owner[i])
        rows.append(positions[i])
        own.append(owner[i])
    return np.vstack(rows), np.asarray(own, dtype=np.int64)


def _fits_arc(blk, pts, tol: float) -> bool:
    """All points within tol [mm] of the arc about blk's centre from pts[0] to pts[-1], its radius
    linear in the swept angle (as netshape.toolpath reads an arc whose ends lie at different radii)."""
    c = np.asarray(blk.center, dtype=float)[:2]
    r = np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1])
    ang = np.unwrap(np.arctan2(pts[:, 1] - c[1], pts[:, 0] - c[0]))
    sweep = ang[-1] - ang[0]
    if abs(sweep) < 1e-12:
        return False
    frac = (ang - ang[0]) / sweep
    if np.any(np.diff(frac) <= 0):
        return False
    # the ends' radii must agree as closely as a G-code reader accepts (1e-3 of the radius, and well
    # within netshape's own reader tolerance), so that the written arc reads back
    if abs(r[-1] - r[0]) > 5e-4 * r[0]:
        return False
    return bool(np.max(np.abs(r - (r[0] + (r[-1] - r[0]) * frac))) <= tol)


def _arc(template, a, b):
    blk = _line(template, a, b)
    from netshape.toolpath import MotionKind

    blk.kind = MotionKind.arc
    blk.center = np.asarray(template.center, dtype=float)
    blk.clockwise = template.clockwise
    blk.turns = 1
    return blk


def _line(template, a, b):
    from netshape.toolpath import Block, MotionKind

    blk = Block()
    blk.kind = MotionKind.line
    blk.start = np.asarray(a, dtype=float)
    blk.end = np.asarray(b, dtype=float)
    blk.feed = template.feed
    blk.spindle_rpm = template.spindle_rpm
    blk.tool = template.tool
    blk.plane = template.plane
    return blk
