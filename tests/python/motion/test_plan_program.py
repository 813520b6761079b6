"""`plan` and `smooth_path` take a Toolpath or toolpath.BlockArrays as they are (issue 40 item 1): the
core reads its blocks, no per-block Python loop or eight NumPy columns in between, and the result is
bit for bit what the same program's block arrays give."""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from netshape import toolpath


def _program() -> str:
    lines = ["G21 G90 G17", "G0 X20 Y0 Z5", "G1 Z0 F900"]
    lines += [f"X{20 * np.cos(a):.4f} Y{20 * np.sin(a):.4f} Z{-0.002 * k:.4f}"
              for k, a in enumerate(np.radians(np.arange(2, 182, 2)))]
    lines += ["G2 X20 Y0 I20 J0", "G1 X40 F1500", "G0 Z5", "M30"]
    return "\n".join(lines) + "\n"


LIM = nm.AxisLimits.uniform(250.0, 3000.0)


@pytest.fixture
def no_python_columns(monkeypatch):
    """Building the columns in Python (blocks_to_arrays) is an error while the test runs."""
    def refuse(*_a, **_k):
        raise AssertionError("columns built through Python")
    monkeypatch.setattr(nm, "blocks_to_arrays", refuse)


@pytest.mark.parametrize("rule", ["blend", "vector", "smooth"])
def test_plan_takes_a_toolpath_and_block_arrays(rule, monkeypatch):
    tp = toolpath.parse_gcode(_program())
    ref = nm.plan(nm.blocks_to_arrays(tp), LIM, rule=rule, tolerance=0.01)
    monkeypatch.setattr(nm, "blocks_to_arrays", lambda *_a, **_k: pytest.fail("columns built through Python"))
    for program in (tp, toolpath._tp.BlockArrays.from_blocks(tp.blocks)):
        got = nm.plan(program, LIM, rule=rule, tolerance=0.01)
        for key in ("t", "position", "velocity", "feed", "block"):
            assert np.array_equal(getattr(got, key), getattr(ref, key)), key
        assert got.stats == ref.stats


def test_smooth_path_takes_a_toolpath(no_python_columns):
    tp = toolpath.parse_gcode(_program())
    ref = nm.smooth_path(toolpath.parse_gcode_arrays(_program()), 0.01)
    got = nm.smooth_path(tp, 0.01)
    assert got[3] == ref[3] and got[3]["runs_smoothed"] >= 1
    for key in ref[0]:
        assert np.array_equal(got[0][key], ref[0][key]), key
    assert np.array_equal(got[1], ref[1]) and np.array_equal(got[2], ref[2])


def test_a_toolpath_with_dwells_plans_in_pieces(no_python_columns):
    text = _program().replace("G1 X40 F1500", "G4 P0.5\nG1 X40 F1500")
    tp = toolpath.parse_gcode(text)
    ref = nm.plan(toolpath.parse_gcode_arrays(text), LIM, rule="blend", tolerance=0.01)
    got = nm.plan(tp, LIM, rule="blend", tolerance=0.01)
    assert got.stats["dwell_time_s"] == 0.5
    assert np.array_equal(got.t, ref.t) and np.array_equal(got.position, ref.position)
