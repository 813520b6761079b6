"""Done-when properties of the motion planner (issue 6).

Feasible-by-construction rules (vector, per-axis, blend): every axis' velocity and acceleration,
measured by finite differences of the samples at ts2, stays within its limit; tolerance: 1e-6
relative on velocity and 0.5 % on acceleration (the second difference of a path sampled across a
corner window or a curvature change differs from the continuous acceleration by O(ts2)). With jerk
limits, jerk is checked too (5 % tolerance on the third difference), on polylines and where a line
meets an arc.
Every rule: samples stay on the programmed path (1e-9 mm; blend: the tolerance ε) and end exactly at
the program's end point.
"""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from netshape import toolpath

LIM = nm.AxisLimits([250.0, 200.0, 120.0], [3000.0, 2500.0, 1500.0])
FEASIBLE = ("vector", "per-axis", "blend")


def _random_polyline(seed, n=40):
    rng = np.random.default_rng(seed)
    steps = rng.normal(size=(n, 3)) * rng.uniform(0.05, 4.0, size=(n, 1))
    steps[:, 2] *= 0.3
    return np.vstack([np.zeros(3), np.cumsum(steps, axis=0)])


def _check(tr, lim, rule, tol=0.01, jerk=False):
    st = tr.stats
    if rule in FEASIBLE:
        assert np.all(np.array(st["axis_velocity_mm_s"]) <= np.asarray(lim.velocity) * (1 + 1e-6))
        assert np.all(np.array(st["axis_accel_mm_s2"]) <= np.asarray(lim.acceleration) * 1.005)
        if jerk:
            assert np.all(np.array(st["axis_jerk_mm_s3"]) <= np.asarray(lim.jerk) * 1.05)
    assert st["max_path_deviation_mm"] <= (tol * (1 + 1e-9) if rule == "blend" else 1e-9)
    assert st["end_error_mm"] == 0.0
    for key in ("cycle_time_s", "max_axis_velocity_mm_s", "max_axis_accel_mm_s2", "max_axis_jerk_mm_s3",
                "max_path_deviation_mm", "blocks"):
        assert key in st


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("rule", nm.RULES)
def test_random_polylines(seed, rule):
    pts = _random_polyline(seed)
    tr = nm.plan(pts, LIM, feed=400.0, rule=rule, ts1=1e-3, ts2=1e-4, lookahead=16)
    _check(tr, LIM, rule)
    np.testing.assert_array_equal(tr.position[-1], pts[-1])


JERK_LIM = nm.AxisLimits([250.0, 200.0, 120.0], [3000.0, 2500.0, 1500.0], [2e6, 2e6, 1e6])


@pytest.mark.parametrize("seed", [3, 4])
@pytest.mark.parametrize("rule", FEASIBLE)
def test_feasible_rules_with_jerk_limit(seed, rule):
    """With jerk limits the velocity-jump rules keep each axis' jump within J_i·ts2² (its third
    difference) and hold the speed for 3·ts2 around it; the blend rule has no jump at all."""
    pts = _random_polyline(seed, n=12) * 3.0
    tr = nm.plan(pts, JERK_LIM, feed=200.0, rule=rule, tolerance=0.05, ts1=1e-3, ts2=1e-4)
    _check(tr, JERK_LIM, rule, tol=0.05, jerk=True)


@pytest.mark.parametrize("rule", FEASIBLE)
def test_jerk_limit_where_the_curvature_jumps(rule):
    """Line → semicircle (r = 5 mm) → line, tangent at both junctions: the centripetal acceleration
    steps there, so the speed is capped to keep that step's third difference within J."""
    r = 5.0
    arr = dict(kind=np.array([1, 2, 1]), start=np.array([[-10, -r, 0.0], [0, -r, 0], [0, r, 0]]),
               end=np.array([[0, -r, 0.0], [0, r, 0], [-10, r, 0]]), center=np.zeros((3, 3)),
               clockwise=np.array([0, 0, 0]), plane=np.zeros(3, int), turns=np.array([1, 1, 1]),
               feed=np.array([200.0, 200.0, 200.0]))
    tr = nm.plan(arr, JERK_LIM, rule=rule, tolerance=0.05)
    _check(tr, JERK_LIM, rule, tol=0.05, jerk=True)
    assert tr.stats["max_axis_jerk_mm_s3"] > 1e5  # the limit is actually worked against


def test_jerk_limited_profile_on_a_line_is_smooth():
    lim = nm.AxisLimits.uniform(100.0, 1000.0, 2e4)
    tr = nm.plan(np.array([[0, 0, 0], [30, 0, 0]], float), lim, feed=100.0, rule="vector")
    assert tr.stats["max_axis_jerk_mm_s3"] <= 2e4 * 1.01
    assert tr.stats["max_axis_accel_mm_s2"] <= 1000.0 * 1.001
    trap = nm.plan(np.array([[0, 0, 0], [30, 0, 0]], float), nm.AxisLimits.uniform(100.0, 1000.0),
                   feed=100.0, rule="vector")
    assert tr.stats["cycle_time_s"] > trap.stats["cycle_time_s"]


def test_arcs_planned_as_arcs_centripetal_limit():
    """Two full turns r = 5 mm at F far above the limit, planned against the per-axis box: at constant
    speed some axis sees the whole centripetal v²/r, so the arc runs near √(A·r) (a little above on
    the diagonals, where the load splits over two axes; never above √(√2·A·r)), faster than the vector
    split of the jerk-limited mode (√(0.8·A·r)), and every axis stays within A (checked in _check)."""
    r, a = 5.0, 1000.0
    arr = dict(kind=np.array([2]), start=np.array([[r, 0, 0.0]]), end=np.array([[r, 0, 0.0]]),
               center=np.zeros((1, 3)), clockwise=np.array([0]), plane=np.array([0]), turns=np.array([2]),
               feed=np.array([500.0]))
    lim = nm.AxisLimits.uniform(500.0, a)
    for rule in nm.RULES:
        tr = nm.plan(arr, lim, rule=rule)
        assert np.sqrt(a * r) * 0.98 <= tr.feed.max() <= np.sqrt(np.sqrt(2.0) * a * r)
        _check(tr, lim, rule)


def _shared_program(shared_data, name, n, feed_scale=1.0):
    path = shared_data / "gcode" / name
    if not path.exists():
        pytest.skip(f"{path} is absent")
    arr = {k: np.asarray(v) for k, v in toolpath.read_gcode_arrays(path).items()}
    moving = np.flatnonzero(arr["kind"] != 0)
    first = moving[0]
    sl = slice(first, first + n)
    out = {k: v[sl] for k, v in arr.items()}
    out["feed"] = out["feed"] * feed_scale
    return out


@pytest.mark.parametrize("rule", nm.RULES)
@pytest.mark.parametrize("name,n,scale", [("3D_Chips.ngc", 400, 1.0), ("arcspiral.ngc", 60, 100.0),
                                          ("tort.ngc", 80, 100.0)])
def test_shared_programs(shared_data, rule, name, n, scale):
    arr = _shared_program(shared_data, name, n, scale)
    tr = nm.plan(arr, LIM, rule=rule, ts1=1e-3, ts2=1e-4, lookahead=32)
    _check(tr, LIM, rule)
    np.testing.assert_allclose(tr.position[-1], arr["end"][-1], rtol=0, atol=0)


@pytest.mark.shared_data
@pytest.mark.parametrize("rule", FEASIBLE)
def test_shared_arc_program_with_jerk_limit(shared_data, rule):
    """arcspiral.ngc (arcs meeting lines and blends, feeds ×100) with jerk limits: velocity,
    acceleration and jerk of every axis stay within the limits."""
    arr = _shared_program(shared_data, "arcspiral.ngc", 60, 100.0)
    lim = nm.AxisLimits.uniform(250.0, 3000.0, 1e6)
    tr = nm.plan(arr, lim, rule=rule, tolerance=0.01, ts1=1e-3, ts2=1e-4, lookahead=32)
    _check(tr, lim, rule, tol=0.01, jerk=True)
