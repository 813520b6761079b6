"""Rule `smooth` on runs in space (space_programs.py, issue 39 item 2): on every member of a seeded
family of helices and 3-D spirals `smooth` is never slower than `blend` at the same ε (floating-point
noise only), and stays within ε of the program. The bench's larger sweep is
bench/motion_space_family.py."""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from space_programs import space_program

LIM = nm.AxisLimits.uniform(250.0, 3000.0)


def _times(arr, eps):
    b = nm.plan(arr, LIM, rule="blend", tolerance=eps, with_deviation=False)
    s = nm.plan(arr, LIM, rule="smooth", tolerance=eps)
    return b.stats["cycle_time_s"], s


# Known misses (issue 39, open): 4, 15, 21 are feed-limited and their fitted curves are 3–7 µm longer than
# blend's path, which cuts every corner (1–4·10⁻⁵ slower); on 7 and 17 a piece meets a block left as
# programmed (or a planar stretch's curve, 17: coordinates rounded to 1 µm) at a turn, which the planner
# blends within the 2 % of ε left next to a cubic (0.4 % and 5 % slower).
KNOWN_SLOWER = {4, 7, 15, 17, 21}
SEEDS = [pytest.param(s, marks=pytest.mark.xfail(strict=True, reason="known slower")) if s in KNOWN_SLOWER
         else s for s in range(24)]


@pytest.mark.parametrize("seed", SEEDS)
def test_space_runs_never_slower_than_blend(seed):
    arr, eps, desc = space_program(seed, max_points=240)
    tb, s = _times(arr, eps)
    assert s.stats["cycle_time_s"] <= tb * (1 + 1e-9), (desc, tb, s.stats["cycle_time_s"])
    assert s.stats["max_path_deviation_mm"] <= eps * (1 + 1e-9), desc


@pytest.mark.parametrize("turns", [2.0, 3.0])
def test_helix_pieces_join_without_curvature_peaks(turns):
    """A 240-point helix (r 10 mm, 0.05 mm per radian) at 100 mm/s, ε 0.01 mm: the pieces of its run in
    space join with the polyline's direction at their joint, so no cubic curves much more than the
    helix (κ 0.1 /mm) and the plan is not slower than blend's (it was 1.290323 s against 1.289978 s
    at two turns, 1.938861 s against 1.917644 s at three, with peaks of κ 0.37 /mm)."""
    t = np.linspace(0.0, 2 * np.pi * turns, 240)
    arr = nm.polyline_arrays(np.column_stack([10 * np.cos(t), 10 * np.sin(t), 0.05 * t]), 100.0)
    tb, s = _times(arr, 0.01)
    assert s.stats["runs_smoothed"] > 1
    assert s.stats["cycle_time_s"] <= tb * (1 + 1e-9), (tb, s.stats["cycle_time_s"])
    blocks, _, _, _ = nm.smooth_path(arr, 0.01)
    p0, p3 = np.asarray(blocks["start"]), np.asarray(blocks["end"])
    cubic = np.asarray(blocks["kind"]) == 3
    p0, p3 = p0[cubic], p3[cubic]
    c = np.asarray(blocks["ctrl"])[cubic]
    p1, p2 = c[:, 0], c[:, 1]
    u = np.linspace(0.0, 1.0, 17)[:, None, None]
    d1 = 3 * ((1 - u) ** 2 * (p1 - p0) + 2 * (1 - u) * u * (p2 - p1) + u**2 * (p3 - p2))
    d2 = 6 * ((1 - u) * (p2 - 2 * p1 + p0) + u * (p3 - 2 * p2 + p1))
    kappa = np.linalg.norm(np.cross(d1, d2), axis=2) / np.linalg.norm(d1, axis=2) ** 3
    # the largest curvature of blend's corner blends there: Bézier P0, vertex, vertex, P3 with P0, P3 at
    # 0.45 of a move from the vertex (planner/blend.cpp), at its middle (8/3)·sin(θ/2) / (d·cos²(θ/2))
    e = np.diff(np.column_stack([10 * np.cos(t), 10 * np.sin(t), 0.05 * t]), axis=0)
    chord = np.linalg.norm(e[0])
    half = 0.5 * np.arccos(e[0] @ e[1] / chord**2)
    kb = 8 / 3 * np.sin(half) / (0.45 * chord * np.cos(half) ** 2)
    assert kappa.max() <= kb, (kappa.max(), kb)
