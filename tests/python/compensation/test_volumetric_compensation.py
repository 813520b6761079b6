"""Volumetric compensation of points and of G-code programs (S.-H. Yang & S.-H. Kweon, "Volumetric error
compensation of a 3-axis horizontal machining center in the post-processor", §4.2; docs/references.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import netshape as ns

ROOT = Path(__file__).resolve().parents[3]
HMC = ROOT / "examples" / "machines" / "hmc_yang_kweon.toml"
VMC = ROOT / "examples" / "machines" / "vmc.toml"


@pytest.mark.parametrize("path", [HMC, VMC])
def test_compensated_points_land_on_the_nominal_ones(path):
    m = ns.machine.load_machine(path)
    lo = np.array([a.travel_min for a in m.axes]) + 5
    hi = np.array([a.travel_max for a in m.axes]) - 5
    nominal = np.random.default_rng(1).uniform(lo, hi, (20000, 3))
    cmd = ns.compensation.compensate_points(m, nominal)
    actual = ns.machine.actual_points(m, cmd)
    assert np.linalg.norm(actual - nominal, axis=1).max() <= 1e-9
    before = ns.machine.volumetric_error(m, nominal)
    assert before.min() > 1e-3  # there was something to compensate


def _random_program(rng, lo, hi, n=30):
    """Random lines and XY arcs (R form) inside [lo, hi]."""
    cur = rng.uniform(lo, hi)
    lines = ["G21 G90 G17", "T3 M6", "S9000 M3", "G0 X%.4f Y%.4f Z%.4f" % tuple(cur), "F900"]
    for _ in range(n):
        if rng.random() < 0.6:
            cur = rng.uniform(lo, hi)
            lines.append("G1 X%.4f Y%.4f Z%.4f F%d" % (*cur, rng.integers(300, 2000)))
        else:
            r = rng.uniform(20, 60)
            for _ in range(100):
                ang = rng.uniform(0, 2 * np.pi)
                end = cur[:2] + rng.uniform(0.2, 1.9) * r * np.array([np.cos(ang), np.sin(ang)])
                if np.all(end >= lo[:2] + r) and np.all(end <= hi[:2] - r):
                    break
            else:
                continue
            lines.append("G%d X%.4f Y%.4f R%.4f" % (rng.choice([2, 3]), *end, r))
            cur = np.array([*end, cur[2]])
    lines.append("M30")
    return "\n".join(lines) + "\n"


def _nominal_path(tp):
    """Blocks of the nominal program as (kind, data) for an exact distance: lines as segments, XY arcs
    (constant Z in these programs) as centre, radius, start angle, signed sweep."""
    out = []
    for b in tp.blocks:
        s, e = np.asarray(b.start), np.asarray(b.end)
        if b.kind == ns.toolpath.MotionKind.arc:
            c = np.asarray(b.center)
            a0 = np.arctan2(s[1] - c[1], s[0] - c[0])
            out.append(("arc", (c, b.radius(), a0, b.sweep(), s[2])))
        else:
            out.append(("line", (s, e)))
    return out


def _distance_to_path(p, path):
    best = np.full(len(p), np.inf)
    for kind, d in path:
        if kind == "line":
            a, b = d
            ab = b - a
            L2 = max(float(ab @ ab), 1e-300)
            t = np.clip((p - a) @ ab / L2, 0, 1)
            dist = np.linalg.norm(p - (a + t[:, None] * ab), axis=1)
        else:
            c, r, a0, sw, z = d
            ang = np.arctan2(p[:, 1] - c[1], p[:, 0] - c[0])
            rel = np.mod((ang - a0) * np.sign(sw), 2 * np.pi)
            inside = rel <= abs(sw) + 1e-12
            radial = np.hypot(np.hypot(p[:, 0] - c[0], p[:, 1] - c[1]) - r, p[:, 2] - z)
            ends = np.array([[c[0] + r * np.cos(a0), c[1] + r * np.sin(a0), z],
                             [c[0] + r * np.cos(a0 + sw), c[1] + r * np.sin(a0 + sw), z]])
            de = np.min(np.linalg.norm(p[:, None, :] - ends[None], axis=2), axis=1)
            dist = np.where(inside, radial, de)
        best = np.minimum(best, dist)
    return best


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_post_processed_program_lands_on_the_nominal_path(tmp_path, seed):
    rng = np.random.default_rng(seed)
    m = ns.machine.load_machine(HMC)
    src = tmp_path / "in.ngc"
    src.write_text(_random_program(rng, np.array([150.0, 150.0, 100.0]), np.array([650.0, 450.0, 400.0])))
    out = tmp_path / "out.ngc"
    tol = 0.002
    rep = ns.compensation.compensate_gcode(m, src, out, chord_tolerance=tol)
    assert rep.max_residual_mm <= 1e-9
    nominal = ns.toolpath.read_gcode(src)
    comp = ns.toolpath.read_gcode(out)  # re-read with the toolpath reader
    # modal state kept: feeds, spindle and tool of every output block come from the source
    feeds_in = {round(b.feed, 9) for b in nominal.blocks if b.kind != ns.toolpath.MotionKind.rapid}
    feeds_out = {round(b.feed, 9) for b in comp.blocks if b.kind != ns.toolpath.MotionKind.rapid}
    assert feeds_out <= feeds_in and len(feeds_out) > 1
    assert {b.tool for b in comp.blocks} == {3} and {b.spindle_rpm for b in comp.blocks} == {9000.0}
    # end points: actual tip on the nominal end points to 1e-9 mm (the writer round-trips exactly)
    ends = np.array([b.end for b in comp.blocks])
    act = ns.machine.actual_points(m, ends)
    nominal_ends = np.array([b.end for b in nominal.blocks])
    d_end = np.array([np.linalg.norm(nominal_ends - a, axis=1).min() for a in act])
    poly = _nominal_path(nominal)
    # every output point lands on the nominal path; most are block ends exactly
    assert _distance_to_path(act, poly).max() <= 1e-8
    assert np.sum(d_end <= 1e-9) >= len(nominal.blocks)
    # along the blocks: actual path within the chord tolerance of the nominal one
    samples = np.array([b.point_at(s) for b in comp.blocks if b.kind != ns.toolpath.MotionKind.rapid
                        for s in (0.25, 0.5, 0.75)])
    dev = _distance_to_path(ns.machine.actual_points(m, samples), poly)
    assert dev.max() <= tol + 1e-6
    # without compensation the same check fails (the test can fail)
    samples0 = np.array([b.point_at(s) for b in nominal.blocks if b.kind != ns.toolpath.MotionKind.rapid
                         for s in (0.25, 0.5, 0.75)])
    assert _distance_to_path(ns.machine.actual_points(m, samples0), poly).max() > 10 * tol


def test_a_first_feed_move_from_the_initial_position_is_followed_from_where_the_tip_stands(tmp_path):
    # the program's first move is a G1 from the reader's initial position (0, 0, 0), which is not a
    # programmed point and stays uncompensated: the move is followed from the tip's actual position there
    m = ns.machine.load_machine(VMC)
    src = tmp_path / "in.ngc"
    src.write_text("G21 G90 G17 G94\nG1 X100 Y50 Z-200 F3000\nG1 X-100 Y-50 Z-150\nM30\n")
    out = tmp_path / "out.ngc"
    tol = 0.001
    ns.compensation.compensate_gcode(m, src, out, chord_tolerance=tol)
    comp = ns.toolpath.read_gcode(out)
    start = ns.machine.actual_points(m, np.zeros((1, 3)))[0]
    corners = np.array([start, [100.0, 50.0, -200.0], [-100.0, -50.0, -150.0]])
    poly = [("line", (corners[0], corners[1])), ("line", (corners[1], corners[2]))]
    pts = np.array([b.point_at(s) for b in comp.blocks for s in np.linspace(0.0, 1.0, 9)])
    assert _distance_to_path(ns.machine.actual_points(m, pts), poly).max() <= tol + 1e-6
    assert np.linalg.norm(start) > 10 * tol  # the uncompensated start is off the nominal origin


def test_small_error_arcs_are_kept_as_arcs(tmp_path):
    doc = {"tool_chain": ["X", "Y"], "workpiece_chain": ["Z"], "tool": {"length_mm": 100.0},
           "axes": {"X": {"polynomials": {"EXX_mm": [0.0, 2e-6]}}}}
    m = ns.machine.machine_from_dict(doc)
    src = tmp_path / "a.ngc"
    src.write_text("G0 X10 Y0 Z5\nG1 Z0 F500\nG2 X-10 Y0 I-10 J0\nG1 X-20\nM30\n")
    tp, rep = ns.compensation.compensate_program(m, src, chord_tolerance=0.01)
    assert rep.arcs_kept == 1 and rep.arcs_split == 0
    tp, rep = ns.compensation.compensate_program(m, src, chord_tolerance=1e-6)
    assert rep.arcs_kept == 0 and rep.arcs_split == 1


def test_points_pushed_outside_travel_are_refused_naming_line_and_axis(tmp_path):
    doc = {"tool_chain": ["X", "Y"], "workpiece_chain": ["Z"], "tool": {"length_mm": 100.0},
           "axes": {"X": {"travel_mm": [-100.0, 100.0], "polynomials": {"EXX_mm": [0.5]}},
                    "Y": {"travel_mm": [-100.0, 100.0]}, "Z": {"travel_mm": [-100.0, 100.0]}}}
    m = ns.machine.machine_from_dict(doc)
    src = tmp_path / "edge.ngc"
    # X reads 0.5 mm long everywhere: nominal X = -99.8 needs the command X = -100.3
    src.write_text("G0 X0 Y0 Z10\nG1 Z0 F500\n(edge)\nG1 X-99.8\nM30\n")
    out = tmp_path / "out.ngc"
    with pytest.raises(ValueError, match=r"edge.ngc:4: compensated axis X = -100.300000 mm is outside its travel"):
        ns.compensation.compensate_gcode(m, src, out)
    assert not out.exists()  # atomic: nothing written
    src.write_text("G0 X0 Y0 Z10\nG1 Z0 F500\nG1 X-99.0\nM30\n")
    ns.compensation.compensate_gcode(m, src, out)
    assert out.exists()


def test_non_convergence_is_reported():
    doc = {"tool_chain": ["X", "Y", "Z"], "workpiece_chain": [],
           "axes": {"X": {"polynomials": {"EXX_mm": [0.0, -1.0]}}}}
    m = ns.machine.machine_from_dict(doc)
    with pytest.raises(ns.Error, match="did not converge"):
        ns.compensation.compensate_points(m, [[1.0, 0.0, 0.0]], check_travel=False)
    res = ns.compensation.compensate_points_status(m, [[1.0, 0.0, 0.0]], check_travel=False)
    assert res.status[0] == int(ns.compensation.VolumetricStatus.not_converged)
    with pytest.raises(ValueError, match="tolerance"):
        ns.compensation.compensate_points(m, [[1.0, 0.0, 0.0]], tolerance=0.0)


@pytest.mark.parametrize("plane, arc", [("G18", "G2 X20 Z0 I10 K0"), ("G19", "G3 Y20 Z0 J10 K0")])
def test_arcs_in_other_planes(tmp_path, plane, arc):
    m = ns.machine.load_machine(HMC)
    src = tmp_path / "p.ngc"
    src.write_text(f"G0 X300 Y200 Z100\nG1 X300 Y200 Z100 F500\n{plane} G91 G1 X0\nG90\n"
                   f"G0 X300 Y200 Z100\n{arc.replace('X20', 'X320').replace('Y20', 'Y220').replace('Z0', 'Z100')}\nM30\n")
    out = tmp_path / "o.ngc"
    ns.compensation.compensate_gcode(m, src, out, chord_tolerance=0.001)
    nominal = ns.toolpath.read_gcode(src)
    comp = ns.toolpath.read_gcode(out)
    a = ns.machine.actual_points(m, np.array([comp.blocks[-1].end]))[0]
    np.testing.assert_allclose(a, nominal.blocks[-1].end, atol=1e-9)
    mid = np.array([b.point_at(0.5) for b in comp.blocks[-3:]])
    act = ns.machine.actual_points(m, mid)
    arcb = nominal.blocks[-1]
    r = arcb.radius()
    c = np.asarray(arcb.center)
    n_ax = (2, 1, 0)[int(arcb.plane)]
    inplane = [i for i in range(3) if i != n_ax]
    d = np.abs(np.linalg.norm((act - c)[:, inplane], axis=1) - r)
    assert d.max() <= 0.001 + 1e-9
