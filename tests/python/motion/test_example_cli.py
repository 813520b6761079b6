"""The example script and the `netshape plan` command run end to end (so they cannot rot)."""

from __future__ import annotations

import importlib.util
import json

import numpy as np
import pytest

from netshape.cli import main


def _load_example(repo_root):
    spec = importlib.util.spec_from_file_location("lookahead_lee", repo_root / "examples" / "lookahead_lee.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_example_writes_figures(repo_root, tmp_path):
    summary = _load_example(repo_root).run(tmp_path)
    for name in ("fig12_right_angle.png", "fig14_feed_rules.png", "fig15_axis_profiles.png", "summary.json"):
        assert (tmp_path / name).stat().st_size > 1000 or name.endswith(".json")
    assert summary["fig12"]["corner_feed_mm_min"] == pytest.approx([100.0] * 3, rel=0.01)


PROGRAM = """G21 G90 G17
G0 X0 Y0 Z0
G1 X20 F3000
G1 Y20
G2 X30 Y30 I10 J0
G1 X0
M30
"""


@pytest.mark.parametrize("rule", ["paper", "vector", "per-axis", "junction-deviation", "blend"])
def test_cli_plan(tmp_path, rule):
    prog = tmp_path / "p.ngc"
    prog.write_text(PROGRAM)
    out, csv, png = tmp_path / "o.json", tmp_path / "s.csv", tmp_path / "p.png"
    rc = main(["plan", str(prog), "--vmax", "100", "--amax", "1000", "--rule", rule, "--json", str(out),
               "--samples", str(csv), "--plot", str(png), "--ts1", "0.001", "--ts2", "0.0005"])
    assert rc == 0
    d = json.loads(out.read_text())
    for key in ("blocks", "cycle_time_s", "max_axis_velocity_mm_s", "max_axis_accel_mm_s2", "max_axis_jerk_mm_s3",
                "max_path_deviation_mm"):
        assert key in d
    assert d["blocks"] == 4  # the rapid from the origin to the origin has no length
    data = np.loadtxt(csv, delimiter=",", skiprows=1)
    np.testing.assert_allclose(data[-1, 1:4], [0, 30, 0], atol=1e-6)
    assert png.stat().st_size > 1000


def test_cli_limits_toml(tmp_path):
    prog = tmp_path / "p.ngc"
    prog.write_text(PROGRAM)
    lim = tmp_path / "m.toml"
    lim.write_text("[axes.x]\nvmax_mm_s = 50\namax_mm_s2 = 500\n[axes.y]\nvmax_mm_s = 40\namax_mm_s2 = 400\n"
                   "[limits]\nvmax_mm_s = 30\namax_mm_s2 = 300\n")
    out = tmp_path / "o.json"
    assert main(["plan", str(prog), "--limits", str(lim), "--rule", "per-axis", "--json", str(out)]) == 0
    d = json.loads(out.read_text())
    assert d["limits"]["vmax_mm_s"] == [50, 40, 30]
    assert d["max_axis_velocity_mm_s"] <= 50 * (1 + 1e-6)


def test_cli_bad_input(tmp_path, capsys):
    prog = tmp_path / "p.ngc"
    prog.write_text(PROGRAM)
    out = tmp_path / "o.json"
    assert main(["plan", str(prog), "--vmax", "-1", "--amax", "10", "--rule", "vector", "--json", str(out)]) == 2
    assert "--vmax" in capsys.readouterr().err
    assert main(["plan", str(prog), "--rule", "vector", "--json", str(out)]) == 2
    assert main(["plan", str(prog), "--vmax", "1", "--amax", "10", "--rule", "vector", "--ts1", "0.00015",
                 "--json", str(out)]) == 2
    assert "ts1" in capsys.readouterr().err
    assert main(["plan", str(tmp_path / "nope.ngc"), "--vmax", "1", "--amax", "10", "--rule", "vector",
                 "--json", str(out)]) == 2
    assert not out.exists()
    bad = tmp_path / "bad.toml"
    bad.write_text("[axes.x]\nvmax_mm_s = 'fast'\n")
    assert main(["plan", str(prog), "--limits", str(bad), "--rule", "vector", "--json", str(out)]) == 2
    assert "axes.x.vmax_mm_s" in capsys.readouterr().err


def test_bad_input_python():
    import netshape.motion as nm

    with pytest.raises(ValueError, match="rule"):
        nm.make_options("fastest")
    with pytest.raises(ValueError, match="tolerance"):
        nm.make_options("blend", tolerance=0.0)
    with pytest.raises(ValueError, match="points.shape"):
        nm.plan(np.zeros((1, 3)), nm.AxisLimits.uniform(1, 1), feed=1.0)
    with pytest.raises(ValueError, match="blocks"):
        nm.plan(np.zeros((3, 3)), nm.AxisLimits.uniform(1, 1), feed=1.0)
    with pytest.raises(ValueError, match="limits.acceleration.y"):
        nm.AxisLimits([1, 1, 1], [1, float("nan"), 1])
    with pytest.raises(ValueError, match="feed"):
        nm.plan(np.array([[0, 0, 0], [1, 0, 0.0]]), nm.AxisLimits.uniform(1, 1), feed=float("nan"))


def test_streaming_python():
    import netshape.motion as nm

    p = nm.Planner(nm.AxisLimits.uniform(100, 1000), nm.make_options("vector", lookahead=2))
    pts = [(0, 0, 0), (10, 0, 0), (10, 10, 0), (0, 10, 0)]
    i, samples = 1, 0
    while True:
        st, s = p.next()
        if st == nm.Status.ok:
            samples += 1
            last = s
            continue
        if st == nm.Status.finished:
            break
        assert st == nm.Status.need_blocks
        while i < len(pts):
            if p.push_arrays(1, pts[i - 1], pts[i], feed=50.0) == nm.Status.buffer_full:
                break
            i += 1
        if i == len(pts):
            p.finish()
    assert samples > 100
    np.testing.assert_allclose(last.position, pts[-1])
    assert p.push_arrays(1, (0, 0, 0), (float("nan"), 0, 0)) == nm.Status.invalid_input
