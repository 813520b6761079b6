"""The smoothed program (block arrays of :func:`netshape.motion.smooth_path`) back out as G-code.

Three forms (``FORMATS``), all absolute mm (G21 G90) with feeds in mm/min:

- ``arcs``: every block as it is, G0 rapids, G1 lines, G2/G3 arcs with I/J/K centre offsets in their
  plane (G17/G18/G19) and a P word for arcs of more than one turn.
- ``g1``: every arc as G1 chords within a chord tolerance [mm]: n = ceil(|sweep| / 2·acos(1 − tol/R))
  chords (netshape.toolpath's one chord count, through :meth:`Toolpath.split_arcs`); lines and rapids
  as they are.
- ``nurbs``: LinuxCNC's G5.2 … G5.3 NURBS blocks. A block kind listed in ``_TO_NURBS`` is turned into
  :class:`NurbsPiece` s by its converter (arcs: :func:`arc_to_nurbs`); a block its converter returns
  ``None`` for, and every other kind, is written as in ``arcs``. LinuxCNC's G5.2 moves X and Y only
  (the control points carry no Z and Z stays where it is), so only arcs in the XY plane (G17) that keep
  their Z become NURBS; arcs in G18/G19 and helical arcs stay G2/G3.

LinuxCNC's G5.2 takes no knots: from k control points and the order L it builds the clamped uniform
knot vector (L zeros, 1 … k − L, then k − L + 1 repeated L times). An exact circle needs a double
knot between its quadratic pieces, which that vector cannot have, so every arc piece is a block of its
own: three control points, order 3, knots (0, 0, 0, 1, 1, 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from netshape._atomic import atomic_write

FORMATS = ("arcs", "g1", "nurbs")
_PLANE = ("G17", "G18", "G19")
_IJK = ((0, "I"), (1, "J"), (2, "K"))
_AXES = ((0, 1), (2, 0), (1, 2))  # in-plane axes (a, b) of G17, G18, G19
_NORMAL = (2, 1, 0)  # the axis each plane's arcs turn about


@dataclass(frozen=True)
class NurbsPiece:
    """One G5.2 block: ``points`` (k, 3) control points [mm], the first where the tool already is;
    ``weights`` (k,) positive; ``order`` = degree + 1 (k >= order). The knot vector is LinuxCNC's
    clamped uniform one for k points of this order (module docstring)."""

    points: np.ndarray
    weights: np.ndarray
    order: int


def arc_to_nurbs(block) -> list[NurbsPiece] | None:
    """An arc block (netshape.toolpath.Block, kind arc) as exact rational quadratic pieces of at most
    a quarter turn each, or None when LinuxCNC's G5.2 cannot carry it (not in the XY plane, or its Z
    changes).

    A piece from P0 to P2 over the angle 2h (h <= 45°) about the centre C has its middle control point
    where the tangents at P0 and P2 meet, P1 = C + (M − C)/cos²h with M the chord midpoint
    (|M − C| = R·cos h, |P1 − C| = R/cos h), and weights (1, cos h, 1): the rational quadratic Bézier
    with these weights is the circle arc exactly. The piece ends are ``block.point_at`` (the end of the
    last piece is the block's end).
    """
    if int(block.plane) != 0:
        return None
    start, end, center = (np.asarray(v, dtype=float) for v in (block.start, block.end, block.center))
    if end[2] != start[2]:
        return None
    sweep = abs(block.sweep())
    m = max(1, math.ceil(sweep / (0.5 * math.pi) * (1.0 - 1e-12)))
    h = 0.5 * sweep / m
    w = math.cos(h)
    ends = [start] + [np.asarray(block.point_at(j / m), dtype=float) for j in range(1, m)] + [end]
    pieces = []
    for p0, p2 in pairwise(ends):
        p1 = center + (0.5 * (p0 + p2) - center) / (w * w)
        p1[2] = start[2]
        pieces.append(NurbsPiece(np.array([p0, p1, p2]), np.array([1.0, w, 1.0]), 3))
    return pieces


# block kind -> its "to NURBS" converter (a block -> list of NurbsPiece, or None to write it as is)
_TO_NURBS = {2: arc_to_nurbs}


def _blocks(arrays) -> list:
    """netshape.toolpath.Block objects of block arrays (the core's sweep, point and chord rules)."""
    from netshape import toolpath as tpm

    kind = np.asarray(arrays["kind"])
    start, end, center = (np.asarray(arrays[k], dtype=float) for k in ("start", "end", "center"))
    cw, plane = np.asarray(arrays["clockwise"]), np.asarray(arrays["plane"])
    turns = np.asarray(arrays["turns"]) if "turns" in arrays else np.ones(len(kind), dtype=int)
    feed = np.asarray(arrays["feed"], dtype=float)
    out = []
    for i in range(len(kind)):
        b = tpm.Block()
        b.kind = tpm.MotionKind(int(kind[i]))
        b.start, b.end, b.center = start[i], end[i], center[i]
        b.clockwise = bool(cw[i])
        b.plane = tpm.Plane(int(plane[i]))
        b.turns = int(turns[i])
        b.feed = float(feed[i])
        out.append(b)
    return out


def _xyz(p) -> str:
    return f"X{p[0]:.6f} Y{p[1]:.6f} Z{p[2]:.6f}"


class _Writer:
    """G-code lines with the modal feed and plane written only where they change."""

    def __init__(self, header: list[str]):
        self.out = list(header)
        self.last_f = None
        self.last_plane = None

    def feed(self, f: float) -> str:
        if self.last_f is None or f != self.last_f:
            self.last_f = f
            return f" F{f * 60.0:.4f}"
        return ""

    def plane(self, pl: int) -> str:
        if pl != self.last_plane:
            self.last_plane = pl
            return _PLANE[pl] + " "
        return ""

    def block(self, kind, start, end, center, cw, pl, turns, f) -> None:
        """One block as G0, G1 or G2/G3 (I J K centre offsets in its plane, P turns when more than one)."""
        if kind == 0:
            self.out.append(f"G0 {_xyz(end)}")
            return
        fw = self.feed(f)
        if kind == 1:
            self.out.append(f"G1 {_xyz(end)}{fw}")
            return
        pre = self.plane(pl)
        off = center - start
        ijk = " ".join(f"{_IJK[a][1]}{off[a]:.6f}" for a in sorted(_AXES[pl]))
        p = f" P{turns}" if turns > 1 else ""
        self.out.append(f"{pre}{'G2' if cw else 'G3'} {_xyz(end)} {ijk}{p}{fw}")

    def nurbs(self, piece: NurbsPiece, f: float) -> None:
        """One G5.2 … G5.3 block in the XY plane: X Y and weight P of every control point after the
        first (LinuxCNC takes the current position as the first, with weight 1), order L."""
        if piece.weights[0] != 1.0:
            raise ValueError(f"weights[0] = {piece.weights[0]}: the first control point of a G5.2 block "
                             "has weight 1")
        pre = self.plane(0)
        pts, w = piece.points, piece.weights
        self.out.append(f"{pre}G5.2 X{pts[1, 0]:.6f} Y{pts[1, 1]:.6f} P{w[1]:.12f} L{piece.order}"
                        f"{self.feed(f)}")
        for p, wi in zip(pts[2:], w[2:]):
            self.out.append(f"X{p[0]:.6f} Y{p[1]:.6f} P{wi:.12f}")
        self.out.append("G5.3")


_HEADERS = {
    "arcs": ["(netshape smooth: smoothed program)", "G21 G90"],
    "g1": ["(netshape smooth: smoothed program, arcs as G1 chords within {tol:g} mm)", "G21 G90"],
    "nurbs": ["(netshape smooth: smoothed program, XY arcs as LinuxCNC G5.2 NURBS blocks of order 3)",
              "(G5.2 moves X and Y only: arcs in G18 or G19 and helical arcs are written as G2 or G3)",
              "G21 G90 G17"],
}


def smoothed_gcode_lines(arrays, fmt: str = "arcs", *, chord_tolerance: float = 0.001) -> list[str]:
    """G-code lines (G21 G90, absolute mm, feeds in mm/min) for block arrays (``kind``, ``start``,
    ``end``, ``center``, ``clockwise``, ``plane``, optional ``turns``, ``feed`` [mm/s]) in the form
    `fmt`, one of ``FORMATS`` (module docstring); `chord_tolerance` [mm] is the largest chord error of
    ``g1`` (> 0)."""
    if fmt not in FORMATS:
        raise ValueError(f"format = {fmt!r}: must be one of {', '.join(FORMATS)}")
    if fmt == "g1":
        from netshape import toolpath as tpm
        from netshape._core.toolpath import BlockArrays

        tp = tpm.Toolpath()
        tp.blocks = _blocks(arrays)
        split = BlockArrays.from_blocks(tp.split_arcs(float(chord_tolerance)).blocks)
        arrays = {k: np.array(v) for k, v in split.to_dict().items()}
    kind = np.asarray(arrays["kind"])
    start, end, center = (np.asarray(arrays[k], dtype=float) for k in ("start", "end", "center"))
    cw, plane = np.asarray(arrays["clockwise"]), np.asarray(arrays["plane"])
    turns = np.asarray(arrays["turns"]) if "turns" in arrays else np.ones(len(kind), dtype=int)
    feed = np.asarray(arrays["feed"], dtype=float)
    w = _Writer([h.format(tol=chord_tolerance) for h in _HEADERS[fmt]])
    if fmt == "nurbs":
        w.last_plane = 0
    if len(kind):
        w.out.append(f"G0 {_xyz(start[0])}")
    blocks = _blocks(arrays) if fmt == "nurbs" else None
    for i in range(len(kind)):
        k = int(kind[i])
        if blocks is not None and k in _TO_NURBS:
            pieces = _TO_NURBS[k](blocks[i])
            if pieces is not None:
                for piece in pieces:
                    w.nurbs(piece, feed[i])
                continue
        w.block(k, start[i], end[i], center[i], bool(cw[i]), int(plane[i]), int(turns[i]), feed[i])
    w.out.append("M2")
    return w.out


def write_smoothed_gcode(arrays, path, fmt: str = "arcs", *, chord_tolerance: float = 0.001) -> None:
    """Write :func:`smoothed_gcode_lines` to `path` atomically (whole or not at all: the lines are
    made before the file is opened)."""
    lines = smoothed_gcode_lines(arrays, fmt, chord_tolerance=chord_tolerance)
    with atomic_write(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
