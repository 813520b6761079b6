"""Streaming smoothing (C++ netshape::motion::Smoother through netshape.motion.smooth_path_streamed):
the streamed blocks equal smooth_path's, and Smoother -> Planner plans the same cycle time as
smooth() + Planner (issue 22)."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

import netshape.motion as nm
from netshape import toolpath

# smooth_path's default share of the tolerance given to the fitted curves
FIT_SHARE = inspect.signature(nm.smooth_path).parameters["fit_share"].default

LIM = nm.AxisLimits.uniform(250.0, 3000.0)


@pytest.fixture(scope="module")
def chips(shared_data):
    arr = {k: np.asarray(v) for k, v in toolpath.read_gcode_arrays(shared_data / "gcode" / "3D_Chips.ngc").items()}
    return arr


def _same(a, b):
    (na, fa, la, sa), (nb, fb, lb, sb) = a, b
    assert np.array_equal(na["kind"], nb["kind"])
    assert np.array_equal(fa, fb) and np.array_equal(la, lb)
    for k in ("start", "end", "center", "ctrl"):
        assert np.array_equal(na[k], nb[k]), k  # bit for bit
    for k in ("runs_smoothed", "runs_kept", "corners_kept", "corners_rounded", "max_fit_deviation_mm"):
        assert sa[k] == sb[k], k


@pytest.mark.parametrize("chunk", [1, 7, 500])
def test_streamed_equals_batch_on_3d_chips(chips, chunk):
    batch = nm.smooth_path(chips, 0.01, window=200)
    streamed = nm.smooth_path_streamed(chips, 0.01, window=200, chunk=chunk)
    assert streamed[3]["chunks"] > 5 and streamed[3]["forced_cuts"] == 0
    _same(streamed, batch)


@pytest.mark.parametrize("min_chunk", [1, 64])
def test_default_window_streams_from_the_first_long_line(chips, min_chunk):
    # the default buffer (8 194 blocks) holds all of 3D_Chips; the smoother still hands out blocks as soon
    # as a long line (> max_segment) follows min_chunk blocks, so output starts after a few hundred blocks
    batch = nm.smooth_path(chips, 0.01)
    streamed = nm.smooth_path_streamed(chips, 0.01, chunk=1, min_chunk=min_chunk)
    stats = streamed[3]
    assert stats["forced_cuts"] == 0 and stats["chunks"] > 20
    length = np.linalg.norm(chips["end"] - chips["start"], axis=1)
    long_blocks = np.flatnonzero((length > 4.0) | (chips["kind"] != int(toolpath.MotionKind.line)))
    first_cut = long_blocks[long_blocks >= min_chunk][0]
    # pushed up to and including a cut block (the first one past min_chunk unless its cut was refused)
    assert stats["first_output_after_blocks"] - 1 in set(long_blocks.tolist())
    assert first_cut + 1 <= stats["first_output_after_blocks"] <= first_cut + 200
    _same(streamed, batch)


def test_tiny_window_is_cut_and_stays_in_tolerance(chips):
    new, first, last, stats = nm.smooth_path_streamed(chips, 0.01, window=8, chunk=3)
    assert stats["forced_cuts"] > 0
    pts = np.vstack([new["start"], new["end"]])
    dev = nm._m._deviation_to_program(*nm._program_args(nm._arrays(chips, None)), pts,
                                      np.concatenate([first, first]).tolist(), np.concatenate([last, last]).tolist())
    assert dev <= FIT_SHARE * 0.01 + 1e-9


def test_smoother_to_planner_cycle_time(chips):
    opts = nm.make_options("blend", tolerance=0.1 * 0.01, lookahead=64)
    args = nm._program_args(nm._arrays(chips, None))
    seg_b, t_b = nm._m._smooth_plan(*args, 0.01, 200, LIM, opts, False)
    seg_s, t_s = nm._m._smooth_plan(*args, 0.01, 200, LIM, opts, True)
    assert t_b > 30.0
    assert abs(t_s - t_b) <= 1e-9 and seg_s == seg_b
    # the Smoother in a thread of its own, blocks handed over through a ring: the same plan
    seg_t, t_t = nm._m._smooth_plan(*args, 0.01, 200, LIM, opts, True, 2, 2)
    assert abs(t_t - t_b) <= 1e-9 and seg_t == seg_b
    # the default window, streamed in chunks from the first long line on, in one and in two threads
    seg_b, t_b = nm._m._smooth_plan(*args, 0.01, 4096, LIM, opts, False)
    for threads in (1, 2):
        seg_t, t_t = nm._m._smooth_plan(*args, 0.01, 4096, LIM, opts, True, 1, threads)
        assert t_t == t_b and seg_t == seg_b
    with pytest.raises(ValueError, match="threads"):
        nm._m._smooth_plan(*args, 0.01, 200, LIM, opts, True, 1, 3)


def test_bad_block_names_the_field():
    pts = np.array([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0], [3, 1, 0]], float)
    with pytest.raises(ValueError, match="block 1: block.end"):
        nm.smooth_path_streamed(nm.polyline_arrays(pts, 100.0), 0.01)
    with pytest.raises(ValueError, match="chunk"):
        nm.smooth_path_streamed(nm.polyline_arrays(pts[:2], 100.0), 0.01, chunk=0)
    with pytest.raises(ValueError, match="min_chunk"):
        nm.smooth_path_streamed(nm.polyline_arrays(pts[:2], 100.0), 0.01, min_chunk=0)
