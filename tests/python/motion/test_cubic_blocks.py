"""Cubic Bézier blocks in block arrays (kind 3, with ``ctrl`` = P1, P2 per row) through
netshape.motion.plan.

The curve is evaluated here in NumPy, independently of the planner: samples must lie within the
blend rule's tolerance of the program (lines and Béziers; distances to a dense sampling refined by
Newton steps), and the second finite differences of the samples must stay within the axis limits.
"""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm

LIM = nm.AxisLimits.uniform(250, 3000)


def _bezier(c, u):
    u = np.asarray(u, float)[:, None]
    v = 1.0 - u
    return v**3 * c[0] + 3 * v * v * u * c[1] + 3 * v * u * u * c[2] + u**3 * c[3]


def _bezier_d1(c, u):
    u = np.asarray(u, float)[:, None]
    v = 1.0 - u
    return 3 * v * v * (c[1] - c[0]) + 6 * v * u * (c[2] - c[1]) + 3 * u * u * (c[3] - c[2])


def _distance_to_bezier(c, pts):
    """Distance of each point to the Bézier c (4, 3): nearest of 4001 parameters, then Newton on
    (B(u) - p)·B'(u) = 0."""
    grid = np.linspace(0.0, 1.0, 4001)
    curve = _bezier(c, grid)
    d = np.linalg.norm(pts[:, None, :] - curve[None, :, :], axis=2)
    u = grid[np.argmin(d, axis=1)]
    h = 1e-7
    for _ in range(8):
        f = np.einsum("ij,ij->i", _bezier(c, u) - pts, _bezier_d1(c, u))
        fp = np.einsum("ij,ij->i", _bezier(c, u + h) - pts, _bezier_d1(c, u + h))
        fm = np.einsum("ij,ij->i", _bezier(c, u - h) - pts, _bezier_d1(c, u - h))
        df = (fp - fm) / (2 * h)
        u = np.clip(u - np.where(df != 0, f / np.where(df != 0, df, 1.0), 0.0), 0.0, 1.0)
    return np.minimum(d.min(axis=1), np.linalg.norm(_bezier(c, u) - pts, axis=1))


def _distance_to_segment(a, b, pts):
    d = b - a
    t = np.clip((pts - a) @ d / (d @ d), 0.0, 1.0)
    return np.linalg.norm(a + t[:, None] * d - pts, axis=1)


def _program():
    """A line, two cubics meeting tangentially, and a line at a 90° corner after the second cubic."""
    c1 = np.array([[0, 0, 0], [4, 2, 0], [8, 3, 0.5], [12, 3, 1.0]], float)
    # the second cubic leaves along the first one's end tangent
    t = c1[3] - c1[2]
    c2 = np.array([c1[3], c1[3] + 1.2 * t, [20, 0, 1.0], [24, 0, 1.0]], float)
    line0 = np.array([[-10, 0, 0], [0, 0, 0]], float)  # along +x, the first cubic leaves at (4, 2): a corner
    line3 = np.array([c2[3], c2[3] + [0, 10, 0]])      # the second cubic ends along +x: a 90° corner
    n = 4
    arr = dict(kind=np.array([1, 3, 3, 1], np.int32),
               start=np.array([line0[0], c1[0], c2[0], line3[0]]), end=np.array([line0[1], c1[3], c2[3], line3[1]]),
               center=np.zeros((n, 3)), clockwise=np.zeros(n, np.int32), plane=np.zeros(n, np.int32),
               turns=np.ones(n, np.int32), feed=np.full(n, 200.0), ctrl=np.zeros((n, 2, 3)))
    arr["ctrl"][1] = c1[1:3]
    arr["ctrl"][2] = c2[1:3]
    return arr, (line0, c1, c2, line3)


@pytest.mark.parametrize("tolerance", [0.01, 0.05])
def test_cubic_rows_are_planned_on_the_curve_within_tolerance(tolerance):
    arr, (line0, c1, c2, line3) = _program()
    tr = nm.plan(arr, LIM, rule="blend", tolerance=tolerance)
    pos = np.asarray(tr.position)
    d = np.min(np.stack([_distance_to_segment(*line0, pos), _distance_to_bezier(c1, pos),
                         _distance_to_bezier(c2, pos), _distance_to_segment(*line3, pos)]), axis=0)
    assert d.max() <= tolerance * (1 + 1e-3)
    # the cubics are followed, not their chords: samples near the middle of the first cubic are far
    # from its chord
    mid = _bezier(c1, [0.5])[0]
    near = np.linalg.norm(pos - mid, axis=1) < 0.05
    assert near.any()
    assert _distance_to_segment(c1[0], c1[3], pos[near]).min() > 0.5
    # feasible: second differences of the samples within the axis acceleration (and the speed limit)
    ts = tr.stats["ts2_s"]
    acc = np.abs(np.diff(pos, 2, axis=0)) / ts**2
    assert acc.max() <= 3000 * 1.005
    assert (np.abs(np.diff(pos, axis=0)) / ts).max() <= 250 * (1 + 1e-6)
    assert np.linalg.norm(pos[-1] - line3[1]) < 1e-9
    assert set(np.unique(tr.block)) == {0, 1, 2, 3}
    assert tr.stats["max_path_deviation_mm"] <= tolerance * (1 + 1e-3)


def test_without_ctrl_key_kind3_rows_are_straight_and_bad_ctrl_is_refused():
    arr, _ = _program()
    no_ctrl = {k: v for k, v in arr.items() if k != "ctrl"}
    # zeros as P1 = P2 = origin: still a valid cubic, but not the chord; just check that it plans
    tr = nm.plan(no_ctrl, LIM, rule="vector")
    assert np.linalg.norm(np.asarray(tr.position)[-1] - arr["end"][-1]) < 1e-9
    bad = dict(arr, ctrl=np.zeros((4, 3)))
    with pytest.raises(ValueError, match="ctrl"):
        nm.plan(bad, LIM, rule="blend")
    nan = dict(arr, ctrl=arr["ctrl"].copy())
    nan["ctrl"][2, 0, 1] = np.nan
    with pytest.raises(ValueError, match=r"ctrl\[2\]"):
        nm.plan(nan, LIM, rule="blend")


def test_smoothing_refuses_cubic_rows_naming_kind_and_row():
    arr, _ = _program()
    with pytest.raises(ValueError, match=r"kind\[1\] = 3"):
        nm.smooth_path(arr, 0.01)
