"""The smoothed program written back as G-code (netshape.motion.smooth_gcode, `netshape plan
--smoothed-gcode OUT --smoothed-format arcs|g1|nurbs`), issue 22.

Every file is parsed back here by a small modal G-code reader of the test's own, and compared with
arcs computed here from centre, radius and angles:

- g1: the chords of an arc are consecutive, start and end where the arc does, lie on its circle, and
  each stays within the chord tolerance of the arc (largest distance of densely sampled arc points
  to the chord); their number is the least that can, ceil(|sweep| / 2·acos(1 − tol/R)).
- nurbs: each G5.2 … G5.3 block is evaluated as LinuxCNC defines it (the position before G5.2 is the
  first control point with weight 1; the knot vector is the clamped uniform one for the number of
  control points and the order L) with a Cox–de Boor evaluation written here, cross-checked against
  netshape.geometry.NurbsCurve; the curve stays on the circle within 1e-6 mm, turns one way only, and
  meets the arc's ends.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import netshape.motion as nm
from netshape import toolpath
from netshape.cli import main
from netshape.motion.gcode_splice import spliced_gcode_lines
from netshape.motion.smooth_gcode import FORMATS, smoothed_gcode_lines, write_smoothed_gcode

_AXES = ((0, 1, 2), (2, 0, 1), (1, 2, 0))  # plane -> (a, b, normal): G17 XY, G18 ZX, G19 YZ
PRINTED = 1e-6  # coordinates are printed to 6 decimals: each is off by <= 5e-7 mm


# ---------------------------------------------------------------- programs of arcs and lines, built here

def _point(plane, center, r, ang, normal):
    """Point(s) of the circle of `plane` at angle(s) `ang` [rad]: (3,) or (m, 3)."""
    a, b, n = _AXES[plane]
    ang = np.asarray(ang, dtype=float)
    p = np.empty(ang.shape + (3,))
    p[..., a] = center[a] + r * np.cos(ang)
    p[..., b] = center[b] + r * np.sin(ang)
    p[..., n] = normal
    return p


class _Program:
    """Block arrays made one block at a time, each starting where the last ended; ``arcs`` keeps
    (row, plane, centre, radius, start angle, signed sweep incl. turns, start and end normal coordinate)."""

    def __init__(self, start):
        self.rows, self.arcs, self.pos = [], [], np.asarray(start, dtype=float)

    def _add(self, kind, end, center=(0, 0, 0), cw=False, plane=0, turns=1, feed=20.0):
        self.rows.append((kind, self.pos.copy(), np.asarray(end, float), np.asarray(center, float), int(cw),
                          plane, turns, feed))
        self.pos = np.asarray(end, float)

    def line(self, end, feed=20.0):
        self._add(1, end, feed=feed)

    def rapid(self, end):
        self._add(0, end)

    def arc(self, plane, center, r, a0, sweep, turns=1, rise=0.0, feed=20.0):
        """An arc of signed `sweep` [rad] (its whole angle, turns included) from angle a0; a line first
        leads to its start."""
        n = _AXES[plane][2]
        z0 = self.pos[n] if plane == 0 else center[n]
        p0 = _point(plane, center, r, a0, z0)
        if np.linalg.norm(p0 - self.pos) > 0:
            self.line(p0)
        p1 = _point(plane, center, r, a0 + sweep, z0 + rise)
        if abs(abs(sweep) - 2 * math.pi * turns) < 1e-12:
            p1 = p0.copy()
            p1[n] = z0 + rise
        c = np.array(center, float)
        c[n] = z0
        self.arcs.append((len(self.rows), plane, c, r, a0, sweep, z0, z0 + rise))
        self._add(2, p1, c, sweep < 0, plane, turns, feed)

    def arrays(self):
        cols = list(zip(*self.rows))
        return {"kind": np.array(cols[0], np.int32), "start": np.array(cols[1]), "end": np.array(cols[2]),
                "center": np.array(cols[3]), "clockwise": np.array(cols[4], np.int32),
                "plane": np.array(cols[5], np.int32), "turns": np.array(cols[6], np.int32),
                "feed": np.array(cols[7], float)}


SWEEPS_DEG = (1e-3, 0.5, 17.0, 90.0, 91.0, 180.0, 269.0, 350.0)


def _program():
    """Arcs in the three planes, both directions, sweeps from 0.001° to 350°, full circles, an arc of
    two turns, helical arcs, radii 0.05 … 300 mm, joined by lines; one rapid."""
    g = _Program([1.0, 2.0, 3.0])
    rng = np.random.default_rng(7)
    for plane in (0, 1, 2):
        for sign in (1, -1):
            for deg, r in zip(SWEEPS_DEG, (300.0, 7.0, 0.05, 12.0, 2.5, 40.0, 0.8, 25.0)):
                c = rng.uniform(-50, 50, 3)
                g.arc(plane, c, r, rng.uniform(-math.pi, math.pi), sign * math.radians(deg))
            g.arc(plane, rng.uniform(-50, 50, 3), 6.0, 0.3, sign * 2 * math.pi)  # full circle
    g.arc(0, (5.0, 5.0, 0.0), 4.0, 1.0, 2 * math.pi + 1.0, turns=2)
    g.arc(0, (-5.0, 5.0, 0.0), 3.0, 0.0, 5.0, rise=-1.5)  # helical, G17
    g.arc(2, (0.0, -5.0, 5.0), 3.0, 0.0, -2.0, rise=0.7)  # helical, G19
    g.rapid(g.pos + np.array([0.0, 0.0, 10.0]))
    g.line(g.pos + np.array([3.0, -4.0, 0.0]), feed=5.0)
    return g


# ---------------------------------------------------------------- a modal G-code reader for these files

_WORD = re.compile(r"([A-Z])([-+]?\d+(?:\.\d*)?)")


def _parse(lines):
    """Moves of a written file: ('G0'|'G1', p0, p1), ('G2'|'G3', p0, p1, centre, plane, turns) and
    ('G5.2', control points (k, 3), weights (k,), order) with the plane in force, and feed words."""
    pos, plane, mode, moves, nurbs = np.zeros(3), 0, None, [], None
    for raw in lines:
        text = re.sub(r"\(.*?\)", "", raw).strip()
        if not text:
            continue
        words = _WORD.findall(text)
        gs = [float(v) for k, v in words if k == "G"]
        vals = {k: float(v) for k, v in words if k != "G"}
        for gv in gs:
            if gv in (17, 18, 19):
                plane = int(gv) - 17
            elif gv in (0, 1, 2, 3, 5.2):
                mode = gv
        if 5.3 in gs:
            assert nurbs is not None, raw
            moves.append(("G5.2", np.array(nurbs[0]), np.array(nurbs[1]), nurbs[2], nurbs[3]))
            pos = np.array(nurbs[0][-1])
            nurbs, mode = None, None
            continue
        if 5.2 in gs:
            assert nurbs is None and "Z" not in vals, raw  # G5.2 moves X and Y only
            nurbs = [[pos.copy()], [1.0], int(vals.get("L", 3)), plane]
        if mode == 5.2:
            assert set(vals) <= {"X", "Y", "P", "L", "F"} and "X" in vals and "Y" in vals, raw
            nurbs[0].append(np.array([vals["X"], vals["Y"], pos[2]]))
            nurbs[1].append(vals["P"])  # every control point after the first carries its weight
            continue
        end = np.array([vals.get(k, pos[i]) for i, k in enumerate("XYZ")])
        if mode in (0, 1) and any(k in vals for k in "XYZ"):
            moves.append((f"G{int(mode)}", pos, end))
        elif mode in (2, 3) and any(k in vals for k in "XYZ"):
            c = pos + np.array([vals.get(k, 0.0) for k in "IJK"])
            moves.append((f"G{int(mode)}", pos, end, c, plane, int(vals.get("P", 1))))
        pos = end
    assert nurbs is None
    return moves


def _angle(plane, center, p):
    a, b, _ = _AXES[plane]
    return math.atan2(p[b] - center[b], p[a] - center[a])


def _walk(arcs_of, moves, prog, arrays):
    """Pair the written moves with the program's blocks: lines and rapids one each; arc i takes the
    moves `arcs_of(i, arc)` says it should (a count)."""
    k, out = 1, {}  # moves[0] is the G0 to the first block's start
    arcs = {a[0]: a for a in prog.arcs}
    for i, kind in enumerate(arrays["kind"]):
        if kind != 2:
            m = moves[k]
            assert m[0] == ("G0" if kind == 0 else "G1")
            assert np.allclose(m[2], arrays["end"][i], atol=PRINTED)
            k += 1
            continue
        n = arcs_of(arcs[i])
        out[i] = moves[k:k + n]
        k += n
    assert k == len(moves)
    return out


# ---------------------------------------------------------------- g1

def _expected_chords(r, sweep, tol):
    return max(1, math.ceil(abs(sweep) / (2 * math.acos(1 - tol / r)) - 1e-9))


@pytest.mark.parametrize("tol", [1e-3, 1e-2, 1e-4])
def test_g1_chords_within_tolerance_and_fewest(tol):
    prog = _program()
    arrays = prog.arrays()
    moves = _parse(smoothed_gcode_lines(arrays, "g1", chord_tolerance=tol))
    assert all(m[0] in ("G0", "G1") for m in moves)
    per_arc = _walk(lambda a: _expected_chords(a[3], a[5], tol), moves, prog, arrays)
    worst = 0.0
    for row, plane, c, r, a0, sweep, z0, z1 in prog.arcs:
        chords = per_arc[row]
        assert all(m[0] == "G1" for m in chords)
        a, b, n = _AXES[plane]
        assert np.allclose(chords[0][1], arrays["start"][row], atol=PRINTED)
        assert np.allclose(chords[-1][2], arrays["end"][row], atol=PRINTED)
        # the chord ends on the circle at increasing angles (unwrapped in the arc's direction) that
        # sum to the sweep; the normal coordinate moves in proportion (helices)
        angs = [a0]
        for m in chords:
            p = m[2]
            assert abs(math.hypot(p[a] - c[a], p[b] - c[b]) - r) <= PRINTED
            d = (_angle(plane, c, p) - angs[-1]) % (2 * math.pi)
            d = d if sweep > 0 else d - 2 * math.pi
            if abs(d) > math.pi and abs(sweep) < 1e-6:  # a chord of a tiny arc: rounding noise
                d = d - math.copysign(2 * math.pi, d)
            angs.append(angs[-1] + d)
            assert abs(p[n] - (z0 + (z1 - z0) * (angs[-1] - a0) / sweep)) <= PRINTED
        assert abs(angs[-1] - (a0 + sweep)) <= 2 * PRINTED / r + 1e-12
        if z1 != z0:
            continue  # the sagitta below is that of plane arcs
        for m, t0, t1 in zip(chords, angs[:-1], angs[1:]):
            ts = np.linspace(t0, t1, 257)
            q = _point(plane, c, r, ts, z0)
            p0, p1 = m[1], m[2]
            u = p1 - p0
            s = np.clip((q - p0) @ u / max(u @ u, 1e-300), 0.0, 1.0)
            dist = np.linalg.norm(q - (p0 + s[:, None] * u), axis=1).max()
            worst = max(worst, dist)
            assert dist <= tol + PRINTED, (row, dist, tol)
    assert worst > 0.5 * tol  # the chords use the tolerance (the count is the least one)


def test_g1_reads_back_with_netshape_reader():
    """netshape's own G-code reader takes the file: lines and rapids only, ending where the program does."""
    prog = _program()
    arrays = prog.arrays()
    back = toolpath.parse_gcode_arrays("\n".join(smoothed_gcode_lines(arrays, "g1")))
    assert set(np.unique(back["kind"])) <= {0, 1}
    assert np.allclose(back["end"][-1], arrays["end"][-1], atol=PRINTED)


# ---------------------------------------------------------------- nurbs

def _clamped_uniform_knots(count, order):
    """LinuxCNC's knot vector of G5.2 for `count` control points of `order`: `order` zeros, then
    1, 2, …, count − order, then count − order + 1 repeated `order` times."""
    inner = list(range(1, count - order + 1))
    return np.array([0.0] * order + inner + [float(count - order + 1)] * order)


def _nurbs_eval(points, weights, order, knots, us):
    """Rational B-spline points at parameters `us`, Cox–de Boor recursion on homogeneous points."""
    p = order - 1
    hom = np.hstack([points * weights[:, None], weights[:, None]])
    out = []
    for u in us:
        span = int(np.searchsorted(knots, u, side="right") - 1)
        span = min(max(span, p), len(points) - 1)
        d = [hom[j + span - p].copy() for j in range(p + 1)]  # de Boor's algorithm
        for r in range(1, p + 1):
            for j in range(p, r - 1, -1):
                i = j + span - p
                den = knots[i + p - r + 1] - knots[i]
                alpha = 0.0 if den == 0 else (u - knots[i]) / den
                d[j] = (1 - alpha) * d[j - 1] + alpha * d[j]
        out.append(d[p][:3] / d[p][3])
    return np.array(out)


def test_nurbs_pieces_lie_on_the_arcs():
    from netshape.geometry import NurbsCurve

    prog = _program()
    arrays = prog.arrays()
    moves = _parse(smoothed_gcode_lines(arrays, "nurbs"))
    a_xy = {a[0] for a in prog.arcs if a[1] == 0 and a[6] == a[7]}

    def count(arc):
        if arc[0] in a_xy:
            return max(1, math.ceil(abs(arc[5]) / (math.pi / 2) - 1e-9))
        return 1

    per_arc = _walk(count, moves, prog, arrays)
    worst, n_pieces = 0.0, 0
    for row, plane, c, r, a0, sweep, z0, z1 in prog.arcs:
        ms = per_arc[row]
        if row not in a_xy:  # G18/G19 or helical: G2/G3 as programmed, in its plane
            (m,) = ms
            assert m[0] == ("G2" if sweep < 0 else "G3") and m[4] == plane
            assert np.allclose(m[2], arrays["end"][row], atol=PRINTED)
            assert np.allclose(m[3], c, atol=PRINTED) and m[5] == arrays["turns"][row]
            continue
        assert np.allclose(ms[0][1][0], arrays["start"][row], atol=PRINTED)
        angle_done = 0.0
        for m in ms:
            kind, pts, w, order, pl = m
            assert kind == "G5.2" and pl == 0 and np.all(w > 0)
            assert np.all(pts[:, 2] == pts[0, 2])
            knots = _clamped_uniform_knots(len(pts), order)
            us = np.linspace(knots[0], knots[-1], 2001)
            q = _nurbs_eval(pts, w, order, knots, us)
            ref = NurbsCurve(order - 1, knots, pts, w).evaluate(us)
            assert np.abs(q - ref).max() <= 1e-9
            rad = np.hypot(q[:, 0] - c[0], q[:, 1] - c[1])
            worst = max(worst, np.abs(rad - r).max())
            assert np.abs(rad - r).max() <= 1e-6, (row, np.abs(rad - r).max())
            assert np.allclose(q[0], pts[0]) and np.allclose(q[-1], pts[-1])
            ang = np.unwrap(np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0]))
            step = np.diff(ang)
            assert np.all(step * math.copysign(1, sweep) >= -1e-9)  # one way only
            assert abs(ang[-1] - ang[0]) <= math.pi / 2 + 2 * PRINTED / r  # at most a quarter turn
            angle_done += ang[-1] - ang[0]
            n_pieces += 1
        assert np.allclose(ms[-1][1][-1], arrays["end"][row], atol=PRINTED)
        assert abs(angle_done - sweep) <= 4 * PRINTED / r + 1e-12
    assert n_pieces > 2 * len(SWEEPS_DEG)
    assert worst < 1e-6


def test_nurbs_weights_are_needed():
    """The evaluation above can fail: the same control points with weight 1 (a parabola) leave the
    circle of a quarter turn by far more than the tolerance."""
    g = _Program([10.0, 0.0, 0.0])
    g.arc(0, (0.0, 0.0, 0.0), 10.0, 0.0, math.pi / 2)
    (m,) = [m for m in _parse(smoothed_gcode_lines(g.arrays(), "nurbs")) if m[0] == "G5.2"]
    pts, w = m[1], m[2]
    assert w[1] == pytest.approx(math.cos(math.pi / 4), abs=1e-12)
    q = _nurbs_eval(pts, np.ones(3), 3, _clamped_uniform_knots(3, 3), np.linspace(0, 1, 101))
    assert np.abs(np.hypot(q[:, 0], q[:, 1]) - 10.0).max() > 0.1


def test_arcs_form_keeps_turns_and_planes():
    prog = _program()
    arrays = prog.arrays()
    moves = _parse(smoothed_gcode_lines(arrays))
    per_arc = _walk(lambda a: 1, moves, prog, arrays)
    for row, plane, c, r, a0, sweep, z0, z1 in prog.arcs:
        (m,) = per_arc[row]
        assert m[0] == ("G2" if sweep < 0 else "G3") and m[4] == plane
        assert np.allclose(m[3], c, atol=PRINTED) and m[5] == arrays["turns"][row]
    back = toolpath.parse_gcode_arrays("\n".join(smoothed_gcode_lines(arrays)))
    assert np.array_equal(back["turns"][back["kind"] == 2], arrays["turns"][arrays["kind"] == 2])


def test_bad_format():
    with pytest.raises(ValueError, match="format = 'svg': must be one of arcs, g1, nurbs"):
        smoothed_gcode_lines(_program().arrays(), "svg")
    with pytest.raises(ValueError, match="chord_tolerance"):
        smoothed_gcode_lines(_program().arrays(), "g1", chord_tolerance=0.0)


def test_write_is_atomic(tmp_path):
    """A failing write leaves an existing file as it was."""
    out = tmp_path / "s.ngc"
    out.write_text("old\n")
    with pytest.raises(ValueError):
        write_smoothed_gcode(_program().arrays(), out, "g1", chord_tolerance=1e-300)
    assert out.read_text() == "old\n" and sorted(p.name for p in tmp_path.iterdir()) == ["s.ngc"]


# ---------------------------------------------------------------- the CLI

def _micro_segment_program() -> str:
    """An XY curve and a YZ half circle in 2° micro-segments: `--rule smooth` makes arcs of both planes."""
    lines = ["G21 G90 G17", "G0 X20 Y0 Z1", "G1 Z0 F600"]
    for a in np.radians(np.arange(2, 272, 2)):
        lines.append(f"G1 X{20 * np.cos(a):.4f} Y{20 * np.sin(a) + 0.3 * np.sin(5 * a):.4f}")
    lines += ["G1 X0 Y-40", "G0 Z5", "G0 X30 Y0 Z0"]
    for a in np.radians(np.arange(2, 182, 2)):
        lines.append(f"G1 Y{15 * np.sin(a):.4f} Z{-15 + 15 * np.cos(a):.4f}")
    return "\n".join(lines + ["M2"]) + "\n"


PLAN = ["plan", "p.ngc", "--vmax", "250", "--amax", "3000", "--rule", "smooth", "--tolerance", "0.01",
        "--json", "o.json"]


@pytest.fixture
def program(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "p.ngc").write_text(_micro_segment_program())
    return tmp_path


@pytest.mark.parametrize("fmt, extra", [(None, []), ("arcs", []), ("g1", []),
                                        ("g1", ["--chord-tolerance", "0.0002"]), ("nurbs", [])])
def test_cli_writes_each_format(program, fmt, extra):
    argv = PLAN + ["--smoothed-gcode", "s.ngc"] + (["--smoothed-format", fmt] if fmt else []) + extra
    assert main(argv) == 0
    arrays = toolpath.read_gcode_arrays("p.ngc")
    new, first, _, _ = nm.smooth_path(arrays, 0.01)
    kw = {"chord_tolerance": float(extra[1])} if extra else {}
    # the program's text with the new moves in place (gcode_splice; test_smooth_splice.py)
    want = spliced_gcode_lines(_micro_segment_program(), arrays, np.zeros((len(arrays["kind"]), 3)), new, first,
                               fmt or "arcs", **kw)
    assert (program / "s.ngc").read_text() == "\n".join(want) + "\n"
    moves = _parse(want)
    kinds = {m[0] for m in moves}
    if fmt == "g1":
        assert kinds <= {"G0", "G1"}
    if fmt == "nurbs":
        # XY curves as NURBS; the YZ runs' cubics as G1 chords, YZ corner arcs as G2 / G3
        assert "G5.2" in kinds and {"G1"} <= kinds
        assert all(m[4] == 0 for m in moves if m[0] == "G5.2")
        assert all(m[4] == 2 for m in moves if m[0] in ("G2", "G3"))


def test_cli_accepts_every_library_format(program):
    for fmt in FORMATS:
        assert main(PLAN + ["--smoothed-gcode", f"{fmt}.ngc", "--smoothed-format", fmt]) == 0


def _one_line(capsys, argv) -> str:
    assert main(argv) == 2
    cap = capsys.readouterr()
    lines = cap.err.splitlines()
    assert cap.out == "" and len(lines) == 1, cap.err
    assert lines[0].startswith("netshape plan: error: "), lines[0]
    return lines[0]


@pytest.mark.parametrize("value, rule", [("0", "must be positive [mm]"), ("-0.001", "must be positive [mm]"),
                                         ("nan", "must be finite [mm]"), ("inf", "must be finite [mm]"),
                                         ("abc", "must be a number [mm]")])
def test_cli_bad_chord_tolerance(program, capsys, value, rule):
    line = _one_line(capsys, PLAN + ["--smoothed-gcode", "s.ngc", "--smoothed-format", "g1",
                                     "--chord-tolerance", value])
    assert line.endswith(f"--chord-tolerance = {value}: {rule}")
    assert sorted(p.name for p in program.iterdir()) == ["p.ngc"]


@pytest.mark.parametrize("argv, message", [
    (["--smoothed-format", "g1"], "--smoothed-format = g1: needs --smoothed-gcode OUT.ngc"),
    (["--smoothed-gcode", "s.ngc", "--chord-tolerance", "0.01"],
     "--chord-tolerance = 0.01: only used with --smoothed-format g1"),
    (["--smoothed-gcode", "s.ngc", "--smoothed-format", "nurbs", "--chord-tolerance", "0.01"],
     "--chord-tolerance = 0.01: only used with --smoothed-format g1"),
    (["--smoothed-gcode", "s.ngc", "--smoothed-format", "svg"],
     "--smoothed-format = svg: must be one of arcs, g1, nurbs"),
])
def test_cli_option_errors(program, capsys, argv, message):
    assert _one_line(capsys, PLAN + argv).endswith(message)
    assert sorted(p.name for p in program.iterdir()) == ["p.ngc"]


def test_cli_no_half_written_file(program, capsys):
    """A chord tolerance too small for an arc or a cubic fails while the chords are made (whichever block
    comes first): no smoothed file, no temporary file, no JSON summary."""
    line = _one_line(capsys, PLAN + ["--smoothed-gcode", "s.ngc", "--smoothed-format", "g1",
                                     "--chord-tolerance", "1e-300"])
    assert re.search(r"--chord-tolerance = 1e-300: too small for this (arc|cubic)", line), line
    assert sorted(p.name for p in program.iterdir()) == ["p.ngc"]


# ---------------------------------------------------------------- cubic Bézier blocks (kind 3)
#
# Programs of lines, arcs and cubic Bézier rows (start = P0, ctrl[k] = (P1, P2), end = P3) in the
# three coordinate planes; the written files are parsed back by the reader above (extended by G5) and
# compared with the Bézier evaluated here in Bernstein form.

def _bezier(pts, ts):
    """Points (m, 3) of the cubic Bézier with control points `pts` (4, 3) at parameters `ts`."""
    t = np.asarray(ts, dtype=float)[:, None]
    s = 1.0 - t
    return s ** 3 * pts[0] + 3 * s * s * t * pts[1] + 3 * s * t * t * pts[2] + t ** 3 * pts[3]


def _in_plane(plane, normal, ab):
    """Points (m, 3) with in-plane coordinates `ab` (m, 2) of `plane` and its normal coordinate fixed."""
    a, b, n = _AXES[plane]
    ab = np.asarray(ab, dtype=float)
    p = np.empty((len(ab), 3))
    p[:, a], p[:, b], p[:, n] = ab[:, 0], ab[:, 1], normal
    return p


class _CubicProgram(_Program):
    """_Program with cubic rows; ``cubics`` keeps (row, control points (4, 3), plane or None)."""

    def __init__(self, start):
        super().__init__(start)
        self.ctrl, self.cubics = {}, []

    def cubic(self, p1, p2, p3, plane, feed=20.0, plane_column=None):
        pts = np.array([self.pos, p1, p2, p3], dtype=float)
        self.ctrl[len(self.rows)] = pts[1:3]
        self.cubics.append((len(self.rows), pts, plane))
        self._add(3, p3, plane=plane if plane_column is None else plane_column, feed=feed)

    def arrays(self):
        out = super().arrays()
        ctrl = np.zeros((len(self.rows), 2, 3))
        for row, c in self.ctrl.items():
            ctrl[row] = c
        out["ctrl"] = ctrl
        return out


def _cubic_program():
    """Cubic chains in G17, G18 and G19 (random control points in the plane, S-shaped ones, tight ones
    with a loop or a cusp, tangent-continuous chains end to start), mixed with lines and arcs, a G19 arc
    right before an XY cubic (the G5 needs G17 back), a straight cubic along X (Y and Z constant: XY),
    one whose normal coordinate wobbles by 4e-10 mm (still planar), one whose plane column is wrong
    (the writer reads the plane from the points) and a non-planar one."""
    g = _CubicProgram([0.0, 0.0, 1.0])
    rng = np.random.default_rng(11)
    for plane in (0, 1, 2):
        a, b, n = _AXES[plane]
        normal = float(rng.uniform(-5, 5))
        here = g.pos.copy()
        here[n] = normal
        g.line(here)
        for _ in range(4):  # random control points
            ab = g.pos[[a, b]] + rng.uniform(-20, 20, (3, 2))
            p = _in_plane(plane, normal, ab)
            g.cubic(p[0], p[1], p[2], plane)
        o = g.pos[[a, b]]
        # S-shaped: the inner points on both sides of the chord
        p = _in_plane(plane, normal, o + np.array([[6.0, 8.0], [12.0, -8.0], [18.0, 0.0]]))
        g.cubic(p[0], p[1], p[2], plane)
        o = g.pos[[a, b]]
        # tight: a loop (inner points crossed over), then a cusp (B' = 0 inside)
        p = _in_plane(plane, normal, o + np.array([[10.0, 6.0], [-7.0, 6.0], [3.0, 0.0]]))
        g.cubic(p[0], p[1], p[2], plane)
        o = g.pos[[a, b]]
        p = _in_plane(plane, normal, o + np.array([[4.0, 3.0], [0.0, 3.0], [4.0, 0.0]]))
        g.cubic(p[0], p[1], p[2], plane)
        for _ in range(3):  # a tangent-continuous chain: P1 mirrors the last P2 about the joint
            last = g.cubics[-1][1]
            p1 = last[3] + 0.7 * (last[3] - last[2])
            ab = g.pos[[a, b]] + rng.uniform(-10, 10, (2, 2))
            p = _in_plane(plane, normal, ab)
            g.cubic(p1, p[0], p[1], plane)
        tiny = _in_plane(plane, normal, g.pos[[a, b]] + np.array([[1e-3, 2e-3], [3e-3, -1e-3], [4e-3, 0.0]]))
        g.cubic(tiny[0], tiny[1], tiny[2], plane)
        g.arc(plane, _point(plane, g.pos, -5.0, 0.0, normal), 5.0, 0.0, 1.2)
    g.arc(2, (g.pos[0], g.pos[1] + 4.0, g.pos[2]), 4.0, math.pi, -1.0)  # a G19 arc, then XY cubics
    z = g.pos[2]
    x0, y0 = g.pos[0], g.pos[1]
    g.cubic((x0 + 3, y0 + 5, z), (x0 + 9, y0 - 5, z + 4e-10), (x0 + 12, y0, z), 0)  # planar within 1e-9
    g.cubic((x0 + 13, y0, z), (x0 + 20, y0, z), (x0 + 26, y0, z), 0)  # straight along X
    x0, y0 = g.pos[0], g.pos[1]
    g.cubic((x0 + 2, y0 + 4, z), (x0 + 5, y0 + 4, z), (x0 + 7, y0, z), 0, plane_column=2)  # wrong column
    g.rapid(g.pos + np.array([0.0, 0.0, 3.0]))
    x0, y0, z0 = g.pos
    g.cubic((x0 + 3, y0, z0 + 2), (x0 + 5, y0 + 4, z0 - 1), (x0 + 2, y0 + 6, z0 + 1), None, plane_column=0)
    g.line(g.pos + np.array([1.0, 1.0, 0.0]), feed=5.0)
    return g


def _parse_cubic(lines):
    """_parse, plus G5 moves ('G5', p0, p1, p2, p3, plane) rebuilt from I J (offset of P1 from the
    start) and P Q (offset of P2 from the end); a G5 names X and Y only."""
    pos, plane, out, rest = np.zeros(3), 0, [], []
    for raw in lines:
        text = re.sub(r"\(.*?\)", "", raw).strip()
        words = _WORD.findall(text)
        gs = [float(v) for k, v in words if k == "G"]
        if 5.0 not in gs:
            rest.append(raw)
            continue
        # flush what came before (a fresh _parse from the G0 that puts the tool at `pos`)
        for m in _parse([f"G0 X{pos[0]:.6f} Y{pos[1]:.6f} Z{pos[2]:.6f}", *rest])[1:]:
            out.append(m)
            pos = np.array(m[2] if m[0] != "G5.2" else m[1][-1])
        for gv in gs:
            if gv in (17, 18, 19):
                plane = int(gv) - 17
        # keep the plane in force for the lines after the G5 as well
        rest = [("G17", "G18", "G19")[plane]]
        vals = {k: float(v) for k, v in words if k != "G"}
        assert set(vals) <= {"X", "Y", "I", "J", "P", "Q", "F"}, raw
        assert {"X", "Y", "I", "J", "P", "Q"} <= set(vals), raw
        end = np.array([vals["X"], vals["Y"], pos[2]])
        p1 = pos + np.array([vals["I"], vals["J"], 0.0])
        p2 = end + np.array([vals["P"], vals["Q"], 0.0])
        out.append(("G5", pos.copy(), p1, p2, end, plane))
        pos = end
    out += _parse([f"G0 X{pos[0]:.6f} Y{pos[1]:.6f} Z{pos[2]:.6f}", *rest])[1:]
    return out


def _end_of(m):
    return m[1][-1] if m[0] == "G5.2" else (m[4] if m[0] == "G5" else m[2])


def _walk_cubic(moves, arrays):
    """Moves of each row: one for a rapid or line; an arc or a cubic takes the moves up to and including
    the first that ends at its end point (chords), where the row after starts."""
    out, k = [], 1  # moves[0] is the G0 to the first block's start
    for i, kind in enumerate(arrays["kind"]):
        j = k
        if kind in (2, 3):
            while np.abs(_end_of(moves[j]) - arrays["end"][i]).max() > PRINTED:
                j += 1
        out.append(moves[k:j + 1])
        k = j + 1
    assert k == len(moves)
    return out


def _dist_to_curve(pts, q):
    """Distance of points `q` (m, 3) to the cubic with control points `pts`. The curve is sampled at
    4001 parameters in 100 windows of 40 steps; the nearest sample of each window is refined by a
    ternary search on the parameter within one step either side, and the least distance over the
    windows is taken (so a branch of a loop passing close by does not hide the nearest one)."""
    ts = np.linspace(0.0, 1.0, 4001)
    c = _bezier(pts, ts)
    out = []
    for qc in np.array_split(q, max(1, len(q) // 64)):
        d = ((qc[:, None, :] - c[None, :4000, :]) ** 2).sum(-1).reshape(len(qc), 100, 40)
        k = d.argmin(-1) + 40 * np.arange(100)[None, :]  # (mc, 100) sample index per window
        lo, hi = np.clip(ts[k] - 1 / 4000, 0, 1).ravel(), np.clip(ts[k] + 1 / 4000, 0, 1).ravel()
        qq = np.repeat(qc, 100, axis=0)

        def d2(t):
            return ((_bezier(pts, t) - qq) ** 2).sum(1)

        for _ in range(36):  # the bracket shrinks to (2/3)^36 of 2/4000: < 1e-9 in the parameter
            m1, m2 = lo + (hi - lo) / 3, hi - (hi - lo) / 3
            left = d2(m1) < d2(m2)
            hi = np.where(left, m2, hi)
            lo = np.where(left, lo, m1)
        best = np.minimum(d2(0.5 * (lo + hi)), d2(np.ones_like(lo)))  # the end P3 is its own candidate
        out.append(np.sqrt(best.reshape(len(qc), 100).min(1)))
    return np.concatenate(out)


def _dist_to_polyline(q, verts):
    """Distance of points `q` (m, 3) to the polyline through `verts` (k, 3)."""
    p0, u = verts[:-1], np.diff(verts, axis=0)
    uu = np.maximum((u * u).sum(1), 1e-300)
    s = np.clip(((q[:, None, :] - p0[None]) * u[None]).sum(-1) / uu, 0.0, 1.0)
    return np.linalg.norm(q[:, None, :] - (p0[None] + s[..., None] * u[None]), axis=-1).min(axis=1)


def _check_chords(pts, verts, tol):
    """Largest of: distance of 2000 curve points to the polyline `verts`, and of points along every chord
    (ends and 7 inside) to the curve; asserts the polyline starts and ends where the curve does."""
    assert np.abs(verts[0] - pts[0]).max() <= PRINTED
    assert np.abs(verts[-1] - pts[3]).max() <= PRINTED
    curve_to_poly = _dist_to_polyline(_bezier(pts, np.linspace(0, 1, 2000)), verts).max()
    s = np.linspace(0.0, 1.0, 9)[:, None, None]
    along = (verts[:-1][None] + s * np.diff(verts, axis=0)[None]).reshape(-1, 3)
    poly_to_curve = _dist_to_curve(pts, along).max()
    return max(curve_to_poly, poly_to_curve)


def _chords_of(ms, start):
    assert all(m[0] == "G1" for m in ms), [m[0] for m in ms]
    assert np.abs(ms[0][1] - start).max() <= PRINTED
    for m0, m1 in zip(ms[:-1], ms[1:]):
        assert np.array_equal(m0[2], m1[1])
    return np.array([ms[0][1]] + [m[2] for m in ms])


def _printed(v):
    return np.array([float(f"{x:.6f}") for x in v])


@pytest.mark.parametrize("tol", [1e-3, 1e-2])
def test_g1_cubics_as_chords_within_tolerance(tol):
    prog = _cubic_program()
    arrays = prog.arrays()
    lines = smoothed_gcode_lines(arrays, "g1", chord_tolerance=tol)
    assert lines[1] == f"(cubic Bezier blocks as G1 chords within {tol:g} mm too)"
    moves = _parse(lines)
    assert {m[0] for m in moves} <= {"G0", "G1"}
    per_row = _walk_cubic(moves, arrays)
    worst = 0.0
    for row, pts, plane in prog.cubics:
        verts = _chords_of(per_row[row], arrays["start"][row])
        assert np.array_equal(verts[-1], _printed(pts[3]))  # the end point exactly, as printed
        err = _check_chords(pts, verts, tol)
        assert err <= tol + PRINTED, (row, err, tol)
        worst = max(worst, err)
    assert worst > 0.25 * tol  # the chords use the tolerance (no needless chords everywhere)
    for row, *_ in prog.arcs:  # arcs as before: chords ending at the arc's end
        assert np.abs(per_row[row][-1][2] - arrays["end"][row]).max() <= PRINTED
    back = toolpath.parse_gcode_arrays("\n".join(lines))
    assert set(np.unique(back["kind"])) <= {0, 1}
    assert np.allclose(back["end"][-1], arrays["end"][-1], atol=PRINTED)


def test_chord_check_can_fail():
    """The check above catches a polyline that leaves the curve: the written chords of a tight cubic
    with every other inner vertex dropped are farther from the curve than the tolerance."""
    prog = _cubic_program()
    arrays = prog.arrays()
    tol = 1e-3
    per_row = _walk_cubic(_parse(smoothed_gcode_lines(arrays, "g1", chord_tolerance=tol)), arrays)
    row, pts, _ = prog.cubics[5]  # the loop of G17
    verts = _chords_of(per_row[row], arrays["start"][row])
    assert len(verts) > 10
    coarse = np.vstack([verts[:-1:2], verts[-1:]])
    assert _check_chords(pts, coarse, tol) > 1.5 * tol


def test_arcs_form_writes_xy_cubics_as_g5():
    prog = _cubic_program()
    arrays = prog.arrays()
    tol = 1e-3
    lines = smoothed_gcode_lines(arrays)  # the default form and chord tolerance (0.001 mm)
    assert lines[1].startswith("(cubic Bezier blocks: in the XY plane as LinuxCNC G5 cubic splines")
    assert "G18 or G19 are written as G1 chords within 0.001 mm" in lines[1]
    moves = _parse_cubic(lines)
    per_row = _walk_cubic(moves, arrays)
    n_g5 = n_chorded = 0
    for row, pts, plane in prog.cubics:
        ms = per_row[row]
        if plane == 0:  # G5: P1 and P2 rebuilt from I J and P Q, to the printed precision
            (m,) = ms
            assert m[0] == "G5" and m[5] == 0
            got = np.array(m[1:5])
            assert np.abs(got[:, :2] - pts[:, :2]).max() <= 2 * PRINTED, (row, got - pts)
            assert abs(m[1][2] - pts[0][2]) <= PRINTED  # Z stays where it is (G5 carries no Z)
            n_g5 += 1
        else:  # G18 / G19 (and the non-planar one): G1 chords within the default tolerance
            verts = _chords_of(ms, arrays["start"][row])
            assert _check_chords(pts, verts, tol) <= tol + PRINTED
            n_chorded += 1
    assert n_g5 == 14 and n_chorded == 23
    for row, plane, c, *_ in prog.arcs:  # arcs still G2 / G3 in their plane
        (m,) = per_row[row]
        assert m[0] in ("G2", "G3") and m[4] == plane and np.abs(m[3] - c).max() <= PRINTED


def test_arcs_form_cubic_chord_tolerance_is_the_argument():
    """Out-of-XY cubics follow `chord_tolerance` in the arcs form too (the CLI passes none: 0.001 mm)."""
    prog = _cubic_program()
    arrays = prog.arrays()
    tol = 0.02
    per_row = _walk_cubic(_parse_cubic(smoothed_gcode_lines(arrays, chord_tolerance=tol)), arrays)
    worst = 0.0
    for row, pts, plane in prog.cubics:
        if plane != 0:
            worst = max(worst, _check_chords(pts, _chords_of(per_row[row], arrays["start"][row]), tol))
    assert 0.25 * tol < worst <= tol + PRINTED


def test_nurbs_form_writes_xy_cubics_as_order_4_blocks():
    prog = _cubic_program()
    arrays = prog.arrays()
    tol = 1e-3
    lines = smoothed_gcode_lines(arrays, "nurbs")
    assert lines[2].startswith("(cubic Bezier blocks: in the XY plane as G5.2 blocks of order 4")
    moves = _parse(lines)
    per_row = _walk_cubic(moves, arrays)
    n_nurbs = 0
    for row, pts, plane in prog.cubics:
        ms = per_row[row]
        if plane != 0:
            verts = _chords_of(ms, arrays["start"][row])
            assert _check_chords(pts, verts, tol) <= tol + PRINTED
            continue
        (m,) = ms
        kind, cp, w, order, pl = m
        assert kind == "G5.2" and order == 4 and pl == 0 and len(cp) == 4 and np.all(w == 1.0)
        knots = _clamped_uniform_knots(4, 4)
        assert np.array_equal(knots, [0, 0, 0, 0, 1, 1, 1, 1])
        us = np.linspace(0.0, 1.0, 2001)
        q = _nurbs_eval(cp, w, order, knots, us)
        ref = _bezier(pts, us)
        assert np.abs(q[:, :2] - ref[:, :2]).max() <= 1e-6, row
        assert np.abs(q[:, 2] - pts[0][2]).max() <= PRINTED
        n_nurbs += 1
    assert n_nurbs == 14
    # the XY arcs are still G5.2 of order 3, the others G2 / G3
    assert {m[3] for m in moves if m[0] == "G5.2"} == {3, 4}


def test_cubic_rows_need_ctrl_and_no_ctrl_key_is_fine():
    prog = _program()
    arrays = prog.arrays()
    assert "ctrl" not in arrays
    with_ctrl = dict(arrays, ctrl=np.zeros((len(arrays["kind"]), 2, 3)))
    for fmt in FORMATS:  # a zero "ctrl" without cubic rows changes nothing
        assert smoothed_gcode_lines(with_ctrl, fmt) == smoothed_gcode_lines(arrays, fmt)
    bad = dict(prog.arrays())
    bad["kind"] = bad["kind"].copy()
    bad["kind"][-1] = 3
    with pytest.raises(ValueError, match="kind 3.*no 'ctrl'"):
        smoothed_gcode_lines(bad)


def test_cubic_chord_tolerance_errors():
    prog = _CubicProgram([0.0, 0.0, 0.0])
    prog.cubic((0.0, 10.0, 0.0), (10.0, 10.0, 0.0), (10.0, 0.0, 0.0), 0)
    arrays = prog.arrays()
    with pytest.raises(ValueError, match="chord_tolerance = 0: must be a positive number"):
        smoothed_gcode_lines(arrays, "g1", chord_tolerance=0.0)
    with pytest.raises(ValueError, match="chord_tolerance = 1e-300: too small for this cubic"):
        smoothed_gcode_lines(arrays, "g1", chord_tolerance=1e-300)
    assert smoothed_gcode_lines(arrays, "arcs", chord_tolerance=1e-300)[-2].startswith("G17 G5 X")  # no chords
