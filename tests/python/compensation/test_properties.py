"""Property-based check of the program compensation (hypothesis, derandomized, bounded examples):
for a random machine (polynomial ISO 230-1 error components, squareness, either chain layout) and a
random program of lines and XY arcs inside the travel, the compensated program run through the
machine model (p + e(p), netshape.machine.actual_points, a separate function from the compensation)
lands on the nominal end points within the point tolerance and follows the nominal path within the
chord tolerance at ¼, ½, ¾ of every output block (S.-H. Yang & S.-H. Kweon, volumetric error
compensation in the post-processor, §4.2; docs/references.md)."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import netshape as ns

TRAVEL = 300.0  # every axis [-300, 300] mm; programs stay within ±150 mm


@st.composite
def machines(draw):
    comp = st.floats(-2e-4, 2e-4)  # slope of a translation component [mm/mm]
    rot = st.floats(-2e-7, 2e-7)   # slope of a rotation component [rad/mm]
    axes = {}
    for a in "XYZ":
        poly = {f"E{d}{a}_mm": [draw(st.floats(-0.02, 0.02)), draw(comp), draw(st.floats(-1e-7, 1e-7))] for d in "XYZ"}
        poly |= {f"E{d}{a}_rad": [0.0, draw(rot)] for d in "ABC"}
        axes[a] = {"travel_mm": [-TRAVEL, TRAVEL], "polynomials": poly}
    tool, work = draw(st.sampled_from([(["X", "Y", "Z"], []), (["X", "Y"], ["Z"]), (["Z"], ["Y", "X"])]))
    doc = {"tool_chain": tool, "workpiece_chain": work, "tool": {"length_mm": draw(st.floats(0.0, 150.0))},
           "squareness": {k: draw(st.floats(-3e-5, 3e-5)) for k in ("EC0Y_rad", "EB0Z_rad", "EA0Z_rad")},
           "axes": axes}
    return ns.machine.machine_from_dict(doc)


_c = st.integers(-150000, 150000).map(lambda v: v / 1000.0)


@st.composite
def programs(draw):
    x, y, z = 0.0, 0.0, 0.0
    lines = ["G21 G90 G17 F800", "G0 X0 Y0 Z0"]
    for _ in range(draw(st.integers(1, 8))):
        if draw(st.booleans()):
            x, y, z = draw(_c), draw(_c), draw(st.integers(-50000, 50000)) / 1000.0
            lines.append(f"G1 X{x} Y{y} Z{z}")
        else:  # a circular XY arc at constant Z, centre within ±100 mm so it stays inside ±150
            i, j = draw(st.integers(-40000, 40000)) / 1000.0, draw(st.integers(-40000, 40000)) / 1000.0
            if abs(x + i) > 100 or abs(y + j) > 100 or np.hypot(i, j) < 1.0:
                continue
            r = np.hypot(i, j)
            ang = draw(st.floats(0.0, 2 * np.pi))
            x, y = round(float(x + i + r * np.cos(ang)), 9), round(float(y + j + r * np.sin(ang)), 9)
            lines.append(f"{draw(st.sampled_from(['G2', 'G3']))} X{x!r} Y{y!r} I{i} J{j}")
    lines.append("M30")
    return "\n".join(lines) + "\n"


def _distance(p, b):
    """Distance [mm] of points p (n, 3) from the nominal block b (line, or XY arc at constant Z)."""
    s, e = np.asarray(b.start), np.asarray(b.end)
    if b.kind != ns.toolpath.MotionKind.arc:
        ab = e - s
        t = np.clip((p - s) @ ab / max(float(ab @ ab), 1e-300), 0.0, 1.0)
        return np.linalg.norm(p - (s + t[:, None] * ab), axis=1)
    c = np.asarray(b.center)
    return np.hypot(np.hypot(p[:, 0] - c[0], p[:, 1] - c[1]) - b.radius(), p[:, 2] - s[2])


@settings(derandomize=True, max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(machines(), programs(), st.sampled_from([0.002, 0.0005]))
def test_compensated_program_lands_on_the_nominal_one(machine, text, tol):
    nominal = ns.toolpath.parse_gcode(text, source="p.ngc")
    out, rep = ns.compensation.compensate_program(machine, nominal, chord_tolerance=tol)
    assert rep.max_residual_mm <= 1e-9 and rep.max_path_deviation_mm <= tol
    src = {b.line: b for b in nominal.blocks}
    ends = np.array([b.end for b in out.blocks])
    actual_ends = ns.machine.actual_points(machine, ends)
    last = {}
    for i, b in enumerate(out.blocks):
        last[b.line] = i
    for line, i in last.items():  # the last output block of each source block ends on its nominal end
        np.testing.assert_allclose(actual_ends[i], src[line].end, rtol=0, atol=2e-9)
    for b in out.blocks:
        nb = src[b.line]
        if nb.kind == ns.toolpath.MotionKind.rapid:
            continue
        samples = np.array([b.point_at(s) for s in (0.25, 0.5, 0.75)])
        assert _distance(ns.machine.actual_points(machine, samples), nb).max() <= tol + 1e-6
