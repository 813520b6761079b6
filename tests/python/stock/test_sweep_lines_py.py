"""Batch line sweep (`sweep_lines`): the same heights bit for bit as one `sweep_line` call per move,
summed stats; n = 0 and n = 1; bad shapes and non-finite values raise ValueError naming the field."""

from __future__ import annotations

import numpy as np
import pytest

import netshape as ns

Cutter = ns.stock.Cutter


def _moves(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    a = np.column_stack([30 * rng.random(n), 25 * rng.random(n), 4 + 6 * rng.random(n)])
    b = np.column_stack([30 * rng.random(n), 25 * rng.random(n), 4 + 6 * rng.random(n)])
    b[::5, :2] = a[::5, :2]  # plunges
    b[1::5, 2] = a[1::5, 2]  # level lines
    b[2::5, 2] = a[2::5, 2] + 12.0  # ramps climbing out of the stock
    return a, b


@pytest.mark.parametrize("make", [lambda: Cutter.flat_end(6.0, 2, 0.5236), lambda: Cutter.ball_end(6.0, 2, 0.5236),
                                  lambda: Cutter.bull_nose(6.0, 1.0, 2, 0.5236)])
@pytest.mark.parametrize("n", [0, 1, 40])
def test_batch_equals_one_by_one(make, n):
    cutter = make()
    starts, ends = _moves(n, 7)
    one = ns.stock.ZMap(0, 30, 0, 25, 0.1, 10.0, 0.0)
    batch = one.copy()
    total = {"moves": 0, "nodes_visited": 0, "nodes_lowered": 0, "removed_volume": 0.0}
    for a, b in zip(starts, ends):
        d = ns.stock.sweep_line(one, cutter, a, b).to_dict()
        for k in total:
            total[k] += d[k]
    st = ns.stock.sweep_lines(batch, cutter, starts, ends)
    assert np.array_equal(batch.heights, one.heights)  # bit for bit
    assert st.moves == n
    assert st.nodes_visited == total["nodes_visited"]
    assert st.nodes_lowered == total["nodes_lowered"]
    assert st.removed_volume == pytest.approx(total["removed_volume"], rel=1e-12, abs=1e-12)
    if n == 40:
        assert st.nodes_lowered > 0


@pytest.mark.parametrize(
    "starts, ends, field",
    [
        (np.zeros((2, 2)), np.zeros((2, 3)), "starts.shape"),
        (np.zeros((2, 3)), np.zeros((2, 4)), "ends.shape"),
        (np.zeros((2, 3)), np.zeros((3, 3)), "ends.shape"),
        (np.zeros(3), np.zeros(3), "starts.shape"),  # 1-D: taken as (3, 1)
        (np.array([[0.0, 0.0, 1.0], [0.0, np.nan, 1.0]]), np.zeros((2, 3)), r"starts\[1, 1\]"),
        (np.zeros((1, 3)), np.array([[np.inf, 0.0, 0.0]]), r"ends\[0, 0\]"),
    ],
)
def test_bad_input_names_the_field_and_changes_nothing(starts, ends, field):
    z = ns.stock.ZMap(0, 10, 0, 10, 0.1, 5.0, 0.0)
    with pytest.raises(ValueError, match=field):
        ns.stock.sweep_lines(z, Cutter.flat_end(4.0, 2, 0.5236), starts, ends)
    assert np.all(z.heights == 5.0)


@pytest.mark.parametrize("make", [lambda: Cutter.flat_end(6.0, 2, 0.5236), lambda: Cutter.ball_end(6.0, 2, 0.5236)])
def test_flat_and_ball_ramps_and_level_lines_equal_the_reference_bit_for_bit(make):
    """The SIMD kernels (ramps and, since they share them, level lines) against the NumPy reference."""
    from zmap_reference import sweep_line_numpy

    cutter = make()
    starts, ends = _moves(60, 9)
    ends[3::5, 2] = starts[3::5, 2]  # more level lines, some along the axes
    ends[3::10, 1] = starts[3::10, 1]
    ends[8::10, 0] = starts[8::10, 0]
    z = ns.stock.ZMap(0, 30, 0, 25, 0.1, 10.0, 0.0)
    ref = z.heights.copy()
    ns.stock.sweep_lines(z, cutter, starts, ends)
    for a, b in zip(starts, ends):
        sweep_line_numpy(ref, z.x0, z.y0, z.dx, z.dy, z.bottom, cutter, a, b)
    assert np.array_equal(z.heights, ref)
