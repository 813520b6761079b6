"""Rule `smooth` on the seeded finishing family (finishing_programs.py, issue 39 item 2): on every
program `smooth` is never slower than `blend` at the same ε, stays within ε of the program (from its
samples) and within the axis box; a program in which nothing is smoothed is planned exactly as
`blend` plans it (the whole ε at every vertex between programmed pieces, not a share of it).
Small programs (a fifth of the bench's size) so that the file runs in seconds."""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from finishing_programs import STRATEGIES, program

LIM = nm.AxisLimits.uniform(250.0, 3000.0)
CASES = [(s, seed, eps) for s in STRATEGIES for seed, eps in ((0, 0.01), (1, 0.03), (2, 0.01))]


@pytest.mark.parametrize("strategy, seed, eps", CASES)
def test_smooth_never_slower_than_blend(strategy, seed, eps):
    arr, desc = program(strategy, seed, scale=0.2)
    b = nm.plan(arr, LIM, rule="blend", tolerance=eps, with_deviation=False)
    s = nm.plan(arr, LIM, rule="smooth", tolerance=eps)
    tb, ts = b.stats["cycle_time_s"], s.stats["cycle_time_s"]
    assert ts <= tb * (1 + 1e-12), (desc, tb, ts)
    assert s.stats["max_path_deviation_mm"] <= eps * (1 + 1e-9), desc
    acc = np.abs(np.diff(s.position, 2, axis=0)).max() / s.stats["ts2_s"] ** 2
    assert acc <= 3000.0 * 1.005, desc


def test_nothing_smoothed_is_planned_as_blend():
    """A 3-D micro-segment helix-like path that lies in no coordinate plane: no run, no corner arc,
    so `smooth` gives the `blend` plan sample for sample."""
    t = np.linspace(0.0, 6 * np.pi, 400)
    pts = np.column_stack([20 * np.cos(t), 20 * np.sin(t), 0.5 * t + 0.2 * np.sin(5 * t)])
    arr = nm.polyline_arrays(pts, 200.0)
    b = nm.plan(arr, LIM, rule="blend", tolerance=0.01, with_deviation=False)
    s = nm.plan(arr, LIM, rule="smooth", tolerance=0.01)
    assert s.stats["runs_smoothed"] == 0 and s.stats["corners_rounded"] == 0
    assert s.stats["cycle_time_s"] == b.stats["cycle_time_s"]
    assert np.array_equal(s.position, b.position)
