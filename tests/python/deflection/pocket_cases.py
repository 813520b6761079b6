"""Pocket programs for the deflection tests and bench/deflection.py: clearing rings and a finish contour at
one Z as one contiguous run of XY cutting moves (no rapid, no Z move between them), as G-code text.

The finish contour is the tool-centre path of a rounded-rectangle wall (half-widths ``half_x``, ``half_y``
[mm], corner radius ``corner_radius`` [mm]): half-widths minus the tool radius R, corner arcs of radius
``corner_radius − R`` (sharp corners where that is ≤ 0). Ring k of ``rings`` (k = 1 innermost) is the
finish path offset inwards by (rings + 1 − k)·``stepover`` (the corner radius shrinks by the same amount,
down to a sharp corner); the innermost ring clears the middle (its smaller half-width is below R). Every
loop runs counter-clockwise — the outer wall on the right of the feed, down milling — from and back to
the middle of its −Y side (the finish loop from ``lead_in`` [mm] along +X from it); a straight move
joins a loop to the next (one stepover long; diagonal into the finish loop when ``lead_in`` ≠ 0). The
whole figure is rotated by ``rotation_deg`` about ``centre``. Arcs are G3 with I J.

    p = Pocket(half_x=20, half_y=15, corner_radius=8, tool_diameter=8, stepover=3, rings=3)
    text = pocket_gcode(p)                 # plunge, rings, finish
    rings, finish = pocket_gcode(p, "rings"), pocket_gcode(p, "finish")

A test helper, not part of the package.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

@dataclass(frozen=True)
class Pocket:
    """A rounded-rectangle pocket cleared by rings, then finished; lengths [mm], angles [deg]."""
    half_x: float = 20.0
    half_y: float = 15.0
    corner_radius: float = 8.0
    tool_diameter: float = 8.0
    stepover: float = 3.0
    rings: int = 3
    z: float = -2.0
    rotation_deg: float = 0.0
    centre: tuple[float, float] = (0.0, 0.0)
    feed: float = 900.0          # [mm/min]
    lead_in: float = 0.0         # [mm] the finish loop's start along +X from its −Y side's middle

    def validate(self) -> None:
        r = 0.5 * self.tool_diameter
        inner_x = self.half_x - r - self.rings * self.stepover
        inner_y = self.half_y - r - self.rings * self.stepover
        if not 0 < self.stepover < self.tool_diameter:
            raise ValueError(f"stepover = {self.stepover}: must lie in (0, the tool diameter "
                             f"{self.tool_diameter}) [mm]")
        if not 0 < min(inner_x, inner_y) < r:
            raise ValueError(f"rings = {self.rings}, stepover = {self.stepover}: the innermost ring's "
                             f"smaller half-width {min(inner_x, inner_y):g} mm must lie in (0, R = {r:g}) so "
                             "that it clears the middle (no island)")
        a, rc = self.half_x - r, max(self.corner_radius - r, 0.0)
        if not abs(self.lead_in) < a - rc:
            raise ValueError(f"lead_in = {self.lead_in}: must lie within the finish loop's straight −Y side "
                             f"(|lead_in| < {a - rc:g} mm)")

    def loops(self) -> list[tuple[float, float, float]]:
        """(half-width x, half-width y, corner radius) of each loop's tool-centre path, innermost first,
        the finish last [mm]."""
        self.validate()
        r = 0.5 * self.tool_diameter
        out = []
        for k in range(self.rings, -1, -1):
            o = k * self.stepover
            out.append((self.half_x - r - o, self.half_y - r - o, max(self.corner_radius - r - o, 0.0)))
        return out


def _loop_moves(a: float, b: float, rc: float, x_start: float = 0.0) -> list[tuple]:
    """Counter-clockwise rounded rectangle about the origin from (x_start, −b) back to it:
    ("line", end) and ("arc", end, centre) items (arcs counter-clockwise)."""
    rc = min(rc, a, b)
    moves: list[tuple] = []
    at = (x_start, -b)

    def line(q):
        nonlocal at
        if math.hypot(q[0] - at[0], q[1] - at[1]) > 1e-9:  # no zero-length moves where the arcs meet
            moves.append(("line", q))
        at = q

    # the four corners, counter-clockwise from the −Y side: (corner, direction into it, direction out)
    corners = [((a, -b), (1, 0), (0, 1)), ((a, b), (0, 1), (-1, 0)),
               ((-a, b), (-1, 0), (0, -1)), ((-a, -b), (0, -1), (1, 0))]
    for (cx, cy), (ix, iy), (ox, oy) in corners:
        if rc > 0:
            p = (cx - ix * rc, cy - iy * rc)
            line(p)
            at = (cx + ox * rc, cy + oy * rc)
            moves.append(("arc", at, (p[0] + ox * rc, p[1] + oy * rc)))
        else:
            line((cx, cy))
    line((x_start, -b))
    return moves


def pocket_moves(p: Pocket) -> tuple[tuple[float, float], list[tuple], int]:
    """(start point, moves, index of the finish loop's first move), before rotation, about the origin."""
    loops = p.loops()
    start = (0.0, -loops[0][1])
    moves: list[tuple] = []
    finish_first = 0
    for k, (a, b, rc) in enumerate(loops):
        x_start = p.lead_in if k == len(loops) - 1 else 0.0
        if k > 0:
            moves.append(("line", (x_start, -b)))
        if k == len(loops) - 1:
            finish_first = len(moves)
        moves.extend(_loop_moves(a, b, rc, x_start))
    return start, moves, finish_first


def _place(p: Pocket, xy) -> tuple[float, float]:
    c, s = math.cos(math.radians(p.rotation_deg)), math.sin(math.radians(p.rotation_deg))
    return (p.centre[0] + c * xy[0] - s * xy[1], p.centre[1] + s * xy[0] + c * xy[1])


def pocket_gcode(p: Pocket, part: str = "all") -> str:
    """G-code text: ``all`` (rings and finish as one run), ``rings`` (up to the finish loop's start, the
    joining move included) or ``finish`` (the finish loop alone); each plunges at its first point."""
    if part not in ("all", "rings", "finish"):
        raise ValueError(f"part = {part!r}: must be all, rings or finish")
    start, moves, fin = pocket_moves(p)
    if part == "rings":
        moves = moves[:fin]
    elif part == "finish":
        start = moves[fin - 1][1] if fin > 0 else start
        moves = moves[fin:]
    x0, y0 = _place(p, start)
    lines = [f"(pocket: {part}; half-widths {p.half_x:g} x {p.half_y:g} mm, corner R{p.corner_radius:g}, "
             f"tool D{p.tool_diameter:g}, {p.rings} rings at stepover {p.stepover:g}, "
             f"{p.rotation_deg:g} deg)",
             "G21 G90 G17 G94", "S8000 M3", f"G0 X{x0:.6f} Y{y0:.6f} Z5", f"G1 Z{p.z:g} F300"]
    cur = start
    feed = f" F{p.feed:g}"
    for m in moves:
        x, y = _place(p, m[1])
        if m[0] == "line":
            lines.append(f"G1 X{x:.6f} Y{y:.6f}{feed}")
        else:
            cx, cy = _place(p, m[2])
            sx, sy = _place(p, cur)
            lines.append(f"G3 X{x:.6f} Y{y:.6f} I{cx - sx:.6f} J{cy - sy:.6f}{feed}")
        feed = ""
        cur = m[1]
    lines += ["G0 Z10", "M30", ""]
    return "\n".join(lines)


def stock_bounds(p: Pocket, margin: float = 6.0, top: float = 0.0, bottom: float = -10.0):
    """(min [x, y, z], max [x, y, z]) [mm] of a block holding the rotated pocket with ``margin`` around it."""
    c, s = abs(math.cos(math.radians(p.rotation_deg))), abs(math.sin(math.radians(p.rotation_deg)))
    ex, ey = c * p.half_x + s * p.half_y + margin, s * p.half_x + c * p.half_y + margin
    return ([p.centre[0] - ex, p.centre[1] - ey, bottom], [p.centre[0] + ex, p.centre[1] + ey, top])


def square_gcode(half: float, overlap: float, recut: float = 0.0, z: float = -2.0, rotation_deg: float = 0.0,
                 clockwise: bool = False, feed: float = 900.0) -> str:
    """A closed square tool-centre path of half-side ``half`` [mm] about the origin: from the middle of its
    −Y side round the square and on past the start for ``overlap`` [mm] along the first side, so that the
    tool returns over its own first cut; the last move ends ``recut`` [mm] inside the first side (0: along
    it). Counter-clockwise (inside on the left of the feed) or ``clockwise`` (inside on the right: down
    milling round a boss); plunged at the start; rotated by ``rotation_deg``."""
    if not 0 < overlap <= half:
        raise ValueError(f"overlap = {overlap}: must lie in (0, half = {half}] [mm]")
    p = Pocket(rotation_deg=rotation_deg)
    s = -1.0 if clockwise else 1.0
    pts = [(0.0, -half), (s * half, -half), (s * half, half), (-s * half, half), (-s * half, -half),
           (s * overlap, -half + recut)]
    x0, y0 = _place(p, pts[0])
    lines = [f"(closed square: half-side {half:g} mm, overlap {overlap:g} mm, recut {recut:g} mm, "
             f"{rotation_deg:g} deg, {'clockwise' if clockwise else 'counter-clockwise'})",
             "G21 G90 G17 G94", "S8000 M3", f"G0 X{x0:.6f} Y{y0:.6f} Z5", f"G1 Z{z:g} F300"]
    feed_word = f" F{feed:g}"
    for q in pts[1:]:
        x, y = _place(p, q)
        lines.append(f"G1 X{x:.6f} Y{y:.6f}{feed_word}")
        feed_word = ""
    lines += ["G0 Z10", "M30", ""]
    return "\n".join(lines)


def flat_cutter(diameter: float):
    """The flat end mill of these cases: 4 flutes, 30° helix, 20 mm flutes, stick-out 5 D, carbide."""
    import netshape as ns

    c = ns.cutter.Cutter.flat_end(diameter, 4, math.radians(30.0))
    c.flute_length = 20.0
    c.stick_out = 5.0 * diameter
    c.youngs_modulus = 600e3
    return c
