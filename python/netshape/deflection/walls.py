"""The part's wall: which passes leave it, and the written program judged against the drawing.

- **Final wall.** The wall a pass generates at a point touches the tool's side at W = P + R·n (P the
  tool centre, n the wall normal, R the radius), from the cut's bottom up to the top of the material.
  It is part of the finished part unless a later cutting move of the program passes closer than
  R − ``clearance`` to W in XY with its tip below the top of that wall: a clearing ring or a roughing
  step whose wall the finish pass cuts away is not a wall of the part. A block is a final-wall block
  when most of its engaged points leave a wall that remains; only those are reported and compensated.
- **Against the drawing.** A program (compensated or not) is measured against the drawing's contour
  (the nominal program): each sample's signed offset C from the drawing along the drawing's wall
  normal, the deflection evaluated at the sample, and the wall error e = −C − δ·n, as the compensation
  defines it, so the compensated program a user runs is checked by the same model that predicted the
  error, at a density of its own choosing rather than at the compensation's samples. Every written
  point is evaluated in order, the moves along the offset where a wall starts or ends too, so the
  material each move removes is gone for the points after it.
- **The wall that remains** at a point of the drawing is the deepest cut of the deflected tool's
  circles there (:func:`wall_envelope`), what a CMM would measure: where the offset drops faster than
  the tool's curvature follows, a sample whose own circle no longer reaches the wall is not the wall.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._core import compensation as _comp

#: A later move must come this much closer than the radius to take a wall away [mm]: a pass at
#: exactly one radius (the next step down along the same wall) leaves it.
FINAL_WALL_CLEARANCE_MM = 0.005

_LEVELS = ("bottom", "middle", "top")


def program_polyline(program, spacing: float):
    """Every move of ``program`` as tool-tip rows at most ``spacing`` [mm] apart: ``(rows (m, 3),
    cutting (m), first_row (blocks + 1))``; move j (rows j − 1 → j) is a feed move when cutting[j],
    and block b's rows are first_row[b] … first_row[b + 1] − 1."""
    blocks = list(program.blocks)
    rows = [np.asarray(blocks[0].start, dtype=float)] if blocks else [np.zeros(3)]
    cutting = [0]
    first_row = []
    for b in blocks:
        first_row.append(len(rows))
        k = max(1, math.ceil(float(b.length()) / spacing)) if int(b.kind) == 2 else 1
        for j in range(1, k + 1):
            rows.append(np.asarray(b.point_at(j / k) if k > 1 else b.end, dtype=float))
            cutting.append(0 if int(b.kind) == 0 else 1)
    first_row.append(len(rows))
    return np.vstack(rows), np.asarray(cutting, dtype=np.int32), np.asarray(first_row, dtype=np.int64)


def wall_remains_points(program, owner, nominal, normals, depth, radius: float, *,
                        clearance: float = FINAL_WALL_CLEARANCE_MM, spacing: float = 0.25) -> np.ndarray:
    """(n) bool: the wall point i generates (tool centre ``nominal[i]`` of block ``owner[i]`` of
    ``program``, wall normal ``normals[i]``, cut depth ``depth[i]``) remains at the end of the program.
    Points that cut nothing (depth 0) generate no wall (False)."""
    nominal = np.asarray(nominal, dtype=float)
    normals = np.asarray(normals, dtype=float)
    depth = np.asarray(depth, dtype=float)
    rows, cutting, first_row = program_polyline(program, spacing)
    wall = nominal.copy()
    wall[:, :2] += radius * normals
    top = nominal[:, 2] + depth
    later = first_row[np.minimum(np.asarray(owner, dtype=np.int64) + 1, len(first_row) - 1)]
    keep = np.asarray(_comp.wall_remains(wall, top, later.astype(np.int32), rows, cutting, float(radius),
                                         float(clearance)), dtype=bool)
    return keep & (depth > 1e-9)


def generates_wall(r, side) -> np.ndarray:
    """(n) bool: the point of the path evaluation ``r`` (PathWallErrors) generates a wall on ``side``
    (WallSide): it cuts, and its engaged window holds that side's wall angle. A move that cuts only
    ahead of it, its wall side in air (a lead-in through a cleared pocket), leaves no wall."""
    bit = 1 if str(side).split(".")[-1] == "left" else 2
    return np.asarray(r.engaged, dtype=bool) & (np.asarray(r.wall_flags) & bit > 0)


def final_wall_points(owner, point_remains, engaged) -> np.ndarray:
    """(n) bool per point from its block: a block is a final-wall block when most of its points that
    generate a wall (``engaged``, see :func:`generates_wall`) leave a wall that remains (a block that
    generates none is not); its last point, where the next block starts (at a corner in that block's
    frame), does not vote. The point where a final-wall block starts counts too, whichever block it
    ends, so that the compensated offset is in place at the start of the final wall instead of ramping
    up along it."""
    owner = np.asarray(owner)
    engaged = np.asarray(engaged, dtype=bool)
    remains = np.asarray(point_remains, dtype=bool)
    out = np.zeros(len(owner), dtype=bool)
    for b in np.unique(owner):
        sel = np.flatnonzero(owner == b)
        votes = sel[:-1] if len(sel) > 1 else sel
        n_eng = int(np.sum(engaged[votes]))
        out[sel] = n_eng > 0 and int(np.sum(remains[votes] & engaged[votes])) * 2 > n_eng
    starts = np.flatnonzero(out[1:] & (owner[1:] != owner[:-1]))
    out[starts] = True
    return out


def contour_pieces(owner, final, first_line) -> list[dict]:
    """Maximal runs of consecutive blocks with the same final-wall status: ``{"first_block",
    "last_block", "final_wall", "points": slice}`` (``first_line`` maps a block index to its line)."""
    owner = np.asarray(owner)
    final = np.asarray(final, dtype=bool)
    pieces: list[dict] = []
    start = 0
    for i in range(1, len(owner) + 1):
        if i == len(owner) or final[i] != final[start] and owner[i] != owner[i - 1]:
            pieces.append({"first_block": int(owner[start]), "last_block": int(owner[i - 1]),
                           "line": int(first_line(int(owner[start]))), "final_wall": bool(final[start]),
                           "points": slice(start, i)})
            start = i
    return pieces


#: Tool circles whose wall normals differ by more than this from a sample's are another wall (a lead-in
#: or the next side beyond a corner): their deflection is known only along their own normal.
ENVELOPE_SAME_WALL_DEG = 30.0


def wall_envelope(foot, normals, error, radius: float) -> np.ndarray:
    """The wall the tool leaves, as the envelope of its circles: per sample j (foot on the drawing
    ``foot[j]``, wall normal ``normals[j]`` towards the material, wall errors ``error[j]`` (n, k) [mm], +
    material left) the smallest error over the circles of radius ``radius`` that cut across the
    drawing's normal line at W_j = foot_j + R·n_j, each at its own sample's centre moved by the
    deflection, Q_i = foot_i − e_i·n_i (per level). Circle i reaches t = (Q_i − W_j)·n_j +
    √(R² − ((Q_i − W_j)·t_j)²) past W_j, an error of −t; for i = j that is e_j, so the envelope is never
    above a sample's own error: where a neighbour's circle cuts deeper (the offset drops faster than the
    tool's curvature follows) it is that cut that remains, and material left only counts where no
    circle removes it. Circles of samples whose normal turns more than ENVELOPE_SAME_WALL_DEG from n_j
    (another wall) are left out; a sample's deflection is known only along its own normal."""
    foot = np.asarray(foot, dtype=float)[:, :2]
    n = np.asarray(normals, dtype=float)
    err = np.asarray(error, dtype=float)
    if err.ndim == 1:
        return wall_envelope(foot, n, err[:, None], radius)[:, 0]
    out = err.copy()
    if len(foot) < 2:
        return out
    from scipy.spatial import cKDTree

    R = float(radius)
    W = foot + R * n
    reach = R + float(np.max(np.abs(err))) + 1e-6
    pairs = cKDTree(foot).query_ball_point(W, r=reach)
    j = np.repeat(np.arange(len(foot)), [len(p) for p in pairs])
    i = np.concatenate([np.asarray(p, dtype=np.int64) for p in pairs]) if len(j) else np.zeros(0, np.int64)
    same = np.einsum("ij,ij->i", n[i], n[j]) >= math.cos(math.radians(ENVELOPE_SAME_WALL_DEG))
    i, j = i[same], j[same]
    tj = np.c_[-n[j, 1], n[j, 0]]
    for k in range(err.shape[1]):
        d = foot[i] - err[i, k][:, None] * n[i] - W[j]
        along, across = np.einsum("ij,ij->i", d, n[j]), np.einsum("ij,ij->i", d, tj)
        hit = np.abs(across) < R
        e_ij = -(along[hit] + np.sqrt(R * R - across[hit] ** 2))
        np.minimum.at(out[:, k], j[hit], e_ij)
    return out


@dataclass
class DrawingCheck:
    """A program's wall against a drawing: per sample of the program (``points``) the error at the
    bottom, middle and top of the wall the program leaves there (``error`` (n, 3) [mm], + material left:
    the envelope of the deflected tool's circles, :func:`wall_envelope`, and so ``profile`` (n,
    levels); ``sample_error`` the sample's own circle), the signed offset from the drawing ``offsets``,
    the foot's arc length ``s`` along the drawing and ``final`` (the drawing's final-wall status
    there)."""

    points: np.ndarray
    error: np.ndarray
    offsets: np.ndarray
    s: np.ndarray
    final: np.ndarray
    engaged: np.ndarray
    profile: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    sample_error: np.ndarray | None = None

    def max_mm(self) -> dict:
        """Largest |error| per level over the final-wall samples [mm] (0 where there are none)."""
        e = np.abs(self.error[self.final]) if np.any(self.final) else np.zeros((1, 3))
        return dict(zip(_LEVELS, map(float, e.max(axis=0))))


#: Feet closer than this [mm] along the drawing are one foot (see _separate_feet).
_SAME_FOOT_MM = 1e-6


def _separate_feet(foot) -> np.ndarray:
    """(n, 2) feet with each run of feet that coincide (within _SAME_FOOT_MM: the written moves along
    the offset where a wall starts or ends, whose points all have the wall's end as foot) spread by
    1e-8 mm a step towards the next distinct foot (or on from the previous one at the end), so that
    every written point is evaluated in order and its tool disc removes the material it cuts: a move
    into the wall along the offset takes a sliver behind the wall's first sample away."""
    foot = np.asarray(foot, dtype=float).copy()
    n = len(foot)
    i = 1
    while i < n:
        if np.hypot(*(foot[i] - foot[i - 1])) >= _SAME_FOOT_MM:
            i += 1
            continue
        a = i - 1
        b = i
        while b < n and np.hypot(*(foot[b] - foot[a])) < _SAME_FOOT_MM:
            b += 1
        if b < n:
            t = foot[b] - foot[a]
        else:
            t = foot[a] - foot[a - 1] if a > 0 else np.array([1.0, 0.0])
        t = t / max(np.hypot(*t), 1e-300)
        foot[a + 1:b] = foot[a] + 1e-8 * np.arange(1, b - a)[:, None] * t
        i = b
    return foot


def check_against_drawing(model, cutter, stock, points, drawing, drawing_final, side, options) -> DrawingCheck:
    """Evaluate the wall of the tool-centre polyline ``points`` (n, 3) against the ``drawing``'s
    polyline (m, 3), whose samples carry the final-wall flags ``drawing_final`` (m); the error is the
    wall the tool's circles leave (:func:`wall_envelope`)."""
    points = np.asarray(points, dtype=float)
    drawing = np.asarray(drawing, dtype=float)
    d = _comp.drawing_offsets(points, drawing, side)
    C = np.asarray(d.offsets, dtype=float)
    n = np.asarray(d.normals, dtype=float)
    # evaluated as foot + C·n, so that the cutting frame is the drawing's tangent as in the
    # compensation (each point is where the program puts it either way)
    foot = points.copy()
    foot[:, :2] -= C[:, None] * n
    foot[:, :2] = _separate_feet(foot[:, :2])
    r = _comp.path_wall_errors(model, cutter, stock, foot, n, C, options)
    err = np.asarray(r.error, dtype=float)
    prof = np.asarray(r.profile, dtype=float)
    engaged = np.asarray(r.engaged, dtype=bool)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(drawing[:, 0]), np.diff(drawing[:, 1])))])
    s = np.asarray(d.s, dtype=float)
    # a point is on a final wall when the drawing's segment its foot lies on joins two final-wall
    # samples; a foot at either end of the drawing is beyond its wall (a join back to the nominal end)
    seg = np.clip(np.searchsorted(arc, s, side="left"), 1, len(drawing) - 1)
    df = np.asarray(drawing_final, dtype=bool)
    final = df[seg] & df[seg - 1] & (s > 1e-9) & (s < arc[-1] - 1e-9)
    if prof.size:
        prof = wall_envelope(foot, n, prof, cutter.radius)
    return DrawingCheck(points=points, error=wall_envelope(foot, n, err, cutter.radius), offsets=C, s=s,
                        final=final, engaged=engaged, profile=prof, sample_error=err)
