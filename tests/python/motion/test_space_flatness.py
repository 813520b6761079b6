"""`space_flatness` (how far from its own plane a piece of a run in space may lie, as a share of the
fit tolerance) in `smooth_path`, `plan(rule="smooth")` and `netshape plan --space-flatness`
(issue 39): 0 leaves runs in space as programmed, the default 0.5 smooths them, and a value outside
[0, 1) is refused with one line naming it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.motion as nm
from netshape.cli import main

LIM = nm.AxisLimits.uniform(250.0, 3000.0)


def _helix(n=240):
    a = np.linspace(0, 4 * np.pi, n)
    return np.c_[10 * np.cos(a), 10 * np.sin(a), 0.05 * a]


def test_zero_leaves_runs_in_space_as_programmed():
    pts = _helix()
    default = nm.smooth_path(pts, 0.01, feed=100.0)
    flat = nm.smooth_path(pts, 0.01, feed=100.0, space_flatness=0.0)
    assert np.count_nonzero(default[0]["kind"] == 3) > 0
    assert np.count_nonzero(flat[0]["kind"] == 3) == 0
    t0 = nm.plan(pts, LIM, feed=250.0, rule="smooth", tolerance=0.01, space_flatness=0.0).stats
    t5 = nm.plan(pts, LIM, feed=250.0, rule="smooth", tolerance=0.01).stats
    blend = nm.plan(pts, LIM, feed=250.0, rule="blend", tolerance=0.01).stats
    assert t0["cycle_time_s"] == blend["cycle_time_s"]  # nothing smoothed: planned as blend plans it
    assert t5["cycle_time_s"] < 0.8 * t0["cycle_time_s"]


@pytest.mark.parametrize("bad", [-0.1, 1.0, 2.0, math.nan])
def test_bad_values_are_refused(bad):
    with pytest.raises(ValueError, match=r"^space_flatness = .*must be in \[0, 1\)$"):
        nm.smooth_path(_helix(), 0.01, feed=100.0, space_flatness=bad)
    with pytest.raises(ValueError, match="space_flatness"):
        nm.plan(_helix(), LIM, feed=100.0, rule="smooth", space_flatness=bad)


def test_cli_option(tmp_path, capsys):
    pts = _helix()
    text = ["G21 G90", f"G0 X{pts[0, 0]:.4f} Y{pts[0, 1]:.4f} Z{pts[0, 2]:.4f}", "G1 F6000"]
    text += [f"X{x:.4f} Y{y:.4f} Z{z:.4f}" for x, y, z in pts[1:]] + ["M30"]
    (tmp_path / "h.ngc").write_text("\n".join(text) + "\n")
    base = ["plan", str(tmp_path / "h.ngc"), "--vmax", "250", "--amax", "3000", "--rule", "smooth"]
    assert main(base + ["--space-flatness", "0", "--json", str(tmp_path / "a.json")]) == 0
    assert main(base + ["--json", str(tmp_path / "b.json")]) == 0
    import json
    a, b = (json.loads((tmp_path / f).read_text()) for f in ("a.json", "b.json"))
    assert a != b
    capsys.readouterr()
    assert main(base + ["--space-flatness", "1", "--json", str(tmp_path / "c.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--space-flatness" in err[0] and not (tmp_path / "c.json").exists()
