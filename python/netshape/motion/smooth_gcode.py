"""The smoothed program (block arrays of :func:`netshape.motion.smooth_path`) back out as G-code.

Three forms (``FORMATS``), all absolute mm (G21 G90) with feeds in mm/min:

- ``arcs``: every block as it is, G0 rapids, G1 lines, G2/G3 arcs with I/J/K centre offsets in their
  plane (G17/G18/G19) and a P word for arcs of more than one turn; a cubic Bézier block (kind 3) in
  the XY plane as LinuxCNC's G5 cubic spline, a cubic in any other plane as G1 chords within the
  chord tolerance (:func:`cubic_chord_points`).
- ``g1``: every arc as G1 chords within a chord tolerance [mm]: n = ceil(|sweep| / 2·acos(1 − tol/R))
  chords (netshape.toolpath's one chord count, through :meth:`Toolpath.split_arcs`); every cubic as G1
  chords within the same tolerance (:func:`cubic_chord_points`); lines and rapids as they are.
- ``nurbs``: LinuxCNC's G5.2 … G5.3 NURBS blocks. A block kind listed in ``_TO_NURBS`` is turned into
  :class:`NurbsPiece` s by its converter (arcs: :func:`arc_to_nurbs`, cubics: :func:`cubic_to_nurbs`);
  a block its converter returns ``None`` for, and every other kind, is written as in ``arcs``.
  LinuxCNC's G5.2 moves X and Y only (the control points carry no Z and Z stays where it is), so only
  arcs and cubics in the XY plane (G17) that keep their Z become NURBS; arcs in G18/G19 and helical
  arcs stay G2/G3, cubics in G18/G19 become G1 chords.

Cubic rows (kind 3) carry their inner control points in the array ``ctrl`` (n, 2, 3): the cubic is
start = P0, ctrl[k, 0] = P1, ctrl[k, 1] = P2, end = P3. The key may be absent when no row is a cubic.
The plane of a cubic is read from its four control points (:func:`cubic_plane`), not from ``plane``.

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


PLANAR_TOL = 1e-9  # [mm] a coordinate this close on all four control points is the cubic's normal
MAX_CUBIC_CHORDS = 10_000_000  # the cap of the core's arc chord count, kept for cubics as well


@dataclass(frozen=True)
class CubicBlock:
    """One cubic Bézier block (kind 3): ``points`` (4, 3) control points P0 (start) … P3 (end) [mm],
    ``feed`` [mm/s]."""

    points: np.ndarray
    feed: float


def cubic_plane(points) -> int | None:
    """The coordinate plane (0 G17 XY, 1 G18 ZX, 2 G19 YZ) a cubic lies in: the first of Z, Y, X whose
    value is the same (within PLANAR_TOL) on all four control points (a Bézier stays in the convex hull
    of its control points, so that coordinate is constant along the whole curve); None when no
    coordinate is. XY is tried first, so a cubic that is straight along X (Y and Z constant) is G17."""
    pts = np.asarray(points, dtype=float)
    for plane, axis in ((0, 2), (1, 1), (2, 0)):
        if np.ptp(pts[:, axis]) <= PLANAR_TOL:
            return plane
    return None


def cubic_chord_points(points, tol: float) -> np.ndarray:
    """Points (n + 1, 3) of n G1 chords of the cubic Bézier with control points `points` (4, 3), each
    chord within `tol` [mm] of the curve, P0 first and P3 last (exactly the given end points).

    The chords join B(j/n), j = 0 … n (uniform in the parameter). On a parameter interval of length
    h = 1/n the curve differs from the chord through its ends by at most (h²/8)·max|B''| (the error of
    linear interpolation of a C² function, taken for the vector as a whole), and B''(τ) =
    6·((1 − τ)·D0 + τ·D1) with D0 = P2 − 2P1 + P0, D1 = P3 − 2P2 + P1, so |B''| <= 6·max(|D0|, |D1|).
    n = ceil(sqrt(0.75·max(|D0|, |D1|) / tol)) keeps (h²/8)·6·max(|D0|, |D1|) <= tol: every curve
    point is within tol of its chord, and every chord point within tol of the curve point of the same
    parameter. Raises ValueError when tol is not a positive number or more than MAX_CUBIC_CHORDS chords
    would be needed (messages begin with ``chord_tolerance``, as the core's do).
    """
    tol = float(tol)
    if not (tol > 0.0 and math.isfinite(tol)):
        raise ValueError(f"chord_tolerance = {tol:g}: must be a positive number [mm]")
    p = np.asarray(points, dtype=float)
    d = max(float(np.linalg.norm(p[2] - 2.0 * p[1] + p[0])), float(np.linalg.norm(p[3] - 2.0 * p[2] + p[1])))
    x = math.sqrt(0.75 * d / tol)
    if not x <= MAX_CUBIC_CHORDS:
        raise ValueError(f"chord_tolerance = {tol:g}: too small for this cubic: more than 10 million "
                         "chords would be needed [mm]")
    n = max(1, math.ceil(x))
    t = (np.arange(n + 1, dtype=float) / n)[:, None]
    s = 1.0 - t
    out = (s ** 3) * p[0] + (3.0 * s * s * t) * p[1] + (3.0 * s * t * t) * p[2] + (t ** 3) * p[3]
    out[0], out[-1] = p[0], p[3]  # the ends exactly (no rounding of the Bernstein sums)
    return out


def cubic_to_nurbs(block: CubicBlock) -> list[NurbsPiece] | None:
    """A cubic block as one G5.2 block of order 4 with its four control points and all weights 1, or
    None when it is not in the XY plane (:func:`cubic_plane`). For 4 points of order 4 LinuxCNC's
    clamped uniform knot vector is (0, 0, 0, 0, 1, 1, 1, 1), whose B-spline is the Bézier itself."""
    if cubic_plane(block.points) != 0:
        return None
    return [NurbsPiece(np.array(block.points, dtype=float), np.ones(4), 4)]


# block kind -> its "to NURBS" converter (a block -> list of NurbsPiece, or None to write it as is)
_TO_NURBS = {2: arc_to_nurbs, 3: cubic_to_nurbs}


def _blocks(arrays) -> list:
    """netshape.toolpath.Block objects of block arrays (the core's sweep, point and chord rules); a
    cubic row (kind 3) as a :class:`CubicBlock` (the core's Block has no cubic kind)."""
    from netshape import toolpath as tpm

    kind = np.asarray(arrays["kind"])
    start, end, center = (np.asarray(arrays[k], dtype=float) for k in ("start", "end", "center"))
    cw, plane = np.asarray(arrays["clockwise"]), np.asarray(arrays["plane"])
    turns = np.asarray(arrays["turns"]) if "turns" in arrays else np.ones(len(kind), dtype=int)
    feed = np.asarray(arrays["feed"], dtype=float)
    out = []
    for i in range(len(kind)):
        if int(kind[i]) == 3:
            out.append(CubicBlock(_cubic_points(arrays, i, start, end), float(feed[i])))
            continue
        b = tpm.Block()
        b.kind = tpm.MotionKind(int(kind[i]))
        b.start, b.end, b.center = start[i], end[i], center[i]
        b.clockwise = bool(cw[i])
        b.plane = tpm.Plane(int(plane[i]))
        b.turns = int(turns[i])
        b.feed = float(feed[i])
        out.append(b)
    return out


def _cubic_points(arrays, i, start, end) -> np.ndarray:
    """The four control points (4, 3) of cubic row i: start, ctrl[i, 0], ctrl[i, 1], end."""
    if "ctrl" not in arrays:
        raise ValueError(f"row {i} is a cubic (kind 3) but the block arrays have no 'ctrl'")
    ctrl = np.asarray(arrays["ctrl"], dtype=float)[i]
    return np.array([start[i], ctrl[0], ctrl[1], end[i]], dtype=float)


def _split_arcs(arrays, tol: float) -> dict:
    """The ``g1`` form's block arrays: every arc split into chords by the core
    (:meth:`Toolpath.split_arcs`); cubic rows kept as they are (with their ``ctrl``) for
    :func:`cubic_chord_points`. Without cubic rows the whole program goes through the core at once, as
    before cubics existed; with them each run of rows between cubics does, and the runs and cubics are
    put back together in their order."""
    from netshape import toolpath as tpm
    from netshape._core.toolpath import BlockArrays

    def core(sub):
        tp = tpm.Toolpath()
        tp.blocks = _blocks(sub)
        split = BlockArrays.from_blocks(tp.split_arcs(float(tol)).blocks)
        return {k: np.array(v) for k, v in split.to_dict().items()}

    kind = np.asarray(arrays["kind"])
    cubic = kind == 3
    if not cubic.any():
        return core(arrays)
    n = len(kind)
    base = {k: np.asarray(arrays[k]) for k in ("kind", "start", "end", "center", "clockwise", "plane", "feed")}
    base["turns"] = np.asarray(arrays["turns"]) if "turns" in arrays else np.ones(n, dtype=int)
    base["ctrl"] = np.asarray(arrays["ctrl"], dtype=float)
    parts, i = [], 0
    while i < n:
        j = i + 1
        while j < n and cubic[j] == cubic[i]:
            j += 1
        rows = {k: v[i:j] for k, v in base.items()}
        if not cubic[i]:
            got = core(rows)
            m = len(got["kind"])
            rows = {k: np.asarray(got[k]) for k in base if k != "ctrl"}
            rows["ctrl"] = np.zeros((m, 2, 3))
        parts.append(rows)
        i = j
    return {k: np.concatenate([np.asarray(part[k]) for part in parts]) for k in base}


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

    def cubic(self, pts, f: float, tol: float, g5: bool) -> None:
        """One cubic Bézier block (control points `pts` (4, 3)). With `g5` and the cubic in the XY
        plane: LinuxCNC's G5 cubic spline, ``G5 X Y I J P Q`` (the G17 plane first when another is in
        force). Checked against LinuxCNC's G-code reference (docs/src/gcode/g-code.adoc, "G5 Cubic
        Spline"): X Y are the end point, I J the X/Y offset from the start point to the first control
        point (P1 − P0), P Q the X/Y offset from the END point to the second control point (P2 − P3);
        P and Q are required on every G5 and I J on the first of a series (both are always written
        here, so no G5 depends on the one before); only X and Y may be given (no Z word: the Z of a
        G17 cubic is constant and stays where it is) and G17 must be active. Otherwise, and always
        when not `g5`: G1 chords within `tol` (:func:`cubic_chord_points`), the last one ending at P3."""
        if g5 and cubic_plane(pts) == 0:
            pre = self.plane(0)
            i, j = pts[1, 0] - pts[0, 0], pts[1, 1] - pts[0, 1]
            p, q = pts[2, 0] - pts[3, 0], pts[2, 1] - pts[3, 1]
            self.out.append(f"{pre}G5 X{pts[3, 0]:.6f} Y{pts[3, 1]:.6f} I{i:.6f} J{j:.6f} P{p:.6f} Q{q:.6f}"
                            f"{self.feed(f)}")
            return
        for c in cubic_chord_points(pts, tol)[1:]:
            self.out.append(f"G1 {_xyz(c)}{self.feed(f)}")

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


# extra header comment lines of a program that has cubic blocks (files without cubics are unchanged)
_CUBIC_HEADERS = {
    "arcs": ["(cubic Bezier blocks: in the XY plane as LinuxCNC G5 cubic splines; G5 is XY only, so cubics "
             "in G18 or G19 are written as G1 chords within {tol:g} mm)"],
    "g1": ["(cubic Bezier blocks as G1 chords within {tol:g} mm too)"],
    "nurbs": ["(cubic Bezier blocks: in the XY plane as G5.2 blocks of order 4 (4 control points, weights 1); "
              "cubics in G18 or G19 are written as G1 chords within {tol:g} mm)"],
}


def smoothed_gcode_lines(arrays, fmt: str = "arcs", *, chord_tolerance: float = 0.001) -> list[str]:
    """G-code lines (G21 G90, absolute mm, feeds in mm/min) for block arrays (``kind``, ``start``,
    ``end``, ``center``, ``clockwise``, ``plane``, optional ``turns``, ``feed`` [mm/s], and ``ctrl``
    (n, 2, 3) when a row is a cubic, kind 3) in the form `fmt`, one of ``FORMATS`` (module docstring);
    `chord_tolerance` [mm] is the largest chord error of ``g1`` (> 0), and in every form that of the
    chords of cubics that are not in the XY plane (the 0.001 mm default when not given). Rows of kinds
    0, 1, 2 are written as before cubics existed; only a program with a cubic gets the extra header
    comment."""
    _check_format(fmt)
    has_cubic = bool(np.any(np.asarray(arrays["kind"]) == 3))
    # the cubic comment goes after the form's own comments, before its last line (the G21 G90 … modes)
    header = _HEADERS[fmt][:-1] + (_CUBIC_HEADERS[fmt] if has_cubic else []) + _HEADERS[fmt][-1:]
    w = _Writer([h.format(tol=chord_tolerance) for h in header])
    if fmt == "nurbs":
        w.last_plane = 0
    if len(arrays["kind"]):
        w.out.append(f"G0 {_xyz(np.asarray(arrays['start'], dtype=float)[0])}")
    write_blocks(w, arrays, fmt, chord_tolerance)
    w.out.append("M2")
    return w.out


def _check_format(fmt: str) -> None:
    if fmt not in FORMATS:
        raise ValueError(f"format = {fmt!r}: must be one of {', '.join(FORMATS)}")


def write_blocks(w: "_Writer", arrays, fmt: str, chord_tolerance: float) -> None:
    """Append the moves of the block arrays to `w` in the form `fmt` (no header, no end word)."""
    if fmt == "g1":
        arrays = _split_arcs(arrays, chord_tolerance)
    kind = np.asarray(arrays["kind"])
    start, end, center = (np.asarray(arrays[k], dtype=float) for k in ("start", "end", "center"))
    cw, plane = np.asarray(arrays["clockwise"]), np.asarray(arrays["plane"])
    turns = np.asarray(arrays["turns"]) if "turns" in arrays else np.ones(len(kind), dtype=int)
    feed = np.asarray(arrays["feed"], dtype=float)
    blocks = _blocks(arrays) if fmt == "nurbs" else None
    for i in range(len(kind)):
        k = int(kind[i])
        if blocks is not None and k in _TO_NURBS:
            pieces = _TO_NURBS[k](blocks[i])
            if pieces is not None:
                for piece in pieces:
                    w.nurbs(piece, feed[i])
                continue
        if k == 3:
            w.cubic(_cubic_points(arrays, i, start, end), feed[i], chord_tolerance, g5=fmt != "g1")
            continue
        w.block(k, start[i], end[i], center[i], bool(cw[i]), int(plane[i]), int(turns[i]), feed[i])


def write_smoothed_gcode(arrays, path, fmt: str = "arcs", *, chord_tolerance: float = 0.001) -> None:
    """Write :func:`smoothed_gcode_lines` to `path` atomically (whole or not at all: the lines are
    made before the file is opened)."""
    lines = smoothed_gcode_lines(arrays, fmt, chord_tolerance=chord_tolerance)
    with atomic_write(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
