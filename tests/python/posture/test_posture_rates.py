"""netshape.posture.rates: rotary-axis angular velocity and acceleration at a feed, against closed forms —
a constant-rate rotation (known rate, zero acceleration), a sinusoidal tilt (peak A0·ω², RMS A0·ω/√2 and
A0·ω²/√2 over whole periods) — and through the machine's inverse kinematics and the CLI's summary."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from netshape import posture as npost
from netshape.posture.rates import RATE_KEYS, axis_rates, joint_rates


def _line(s):
    return np.column_stack([s, np.zeros_like(s), np.zeros_like(s)])


def test_constant_rate_rotation_has_the_known_rate_and_zero_acceleration():
    rng = np.random.default_rng(3)
    s = np.cumsum(rng.uniform(0.2, 1.5, 60))  # uneven spacing along a straight ball-centre path [mm]
    q = np.radians(0.5) * s  # 0.5 deg/mm
    r = axis_rates(q, _line(s), 600.0)  # 10 mm/s → 5 deg/s
    assert r["peak_velocity_deg_s"] == pytest.approx(5.0, rel=1e-12)
    assert r["rms_velocity_deg_s"] == pytest.approx(5.0, rel=1e-12)
    assert r["peak_acceleration_deg_s2"] < 1e-9 and r["rms_acceleration_deg_s2"] < 1e-9


def test_sinusoidal_tilt_gives_the_closed_form_peak_and_rms():
    feed = 1200.0  # 20 mm/s
    period_mm, amp_deg = 40.0, 15.0
    s = np.linspace(0.0, 3 * period_mm, 1201)  # three whole periods, 0.1 mm steps
    q = np.radians(amp_deg) * np.sin(2 * math.pi * s / period_mm)
    omega = 2 * math.pi * (feed / 60.0) / period_mm  # [rad/s]
    r = axis_rates(q, _line(s), feed)
    assert r["peak_velocity_deg_s"] == pytest.approx(amp_deg * omega, rel=1e-3)
    assert r["rms_velocity_deg_s"] == pytest.approx(amp_deg * omega / math.sqrt(2), rel=1e-3)
    assert r["peak_acceleration_deg_s2"] == pytest.approx(amp_deg * omega ** 2, rel=1e-3)
    assert r["rms_acceleration_deg_s2"] == pytest.approx(amp_deg * omega ** 2 / math.sqrt(2), rel=1e-3)


def test_machine_joints_of_a_steady_tilt_rotate_a_at_the_feed_rate():
    # table_ac: an axis tilting in the YZ plane from 10° to 40° at 1 deg/mm has A = tilt, C = 0
    s = np.linspace(0.0, 30.0, 31)
    tilt = np.radians(10.0 + s)
    axes = np.column_stack([np.zeros_like(s), np.sin(tilt), np.cos(tilt)])
    radius = 3.0
    tips = _line(s) - radius * axes  # ball centres on the x axis
    joints = npost.inverse_kinematics(npost.Kinematics(), tips, axes)
    r = joint_rates(joints, tips + radius * axes, 300.0, "A")  # 5 mm/s → 5 deg/s
    assert r["A"]["peak_velocity_deg_s"] == pytest.approx(5.0, rel=1e-9)
    assert r["A"]["peak_acceleration_deg_s2"] < 1e-6
    assert r["C"]["peak_velocity_deg_s"] < 1e-9


def test_bad_feed_and_lengths_are_refused():
    with pytest.raises(ValueError, match="feed_mm_per_min"):
        axis_rates([0.0, 1.0], np.zeros((2, 3)), 0.0)
    with pytest.raises(ValueError, match="same length"):
        axis_rates([0.0, 1.0, 2.0], np.zeros((2, 3)), 100.0)


def test_cli_summary_and_stdout_report_the_rotary_figures(tmp_path, capsys):
    from netshape.cli import main

    out = tmp_path / "run"
    assert main(["posture", "plan", "--impeller", "--out", str(out), "--points", "6", "--feed", "500"]) == 0
    rot = json.loads((out / "summary.json").read_text())["rotary"]
    assert rot["feed_mm_per_min"] == 500.0 and rot["machine"] == "table_ac"
    for stage in ("raw", "mc", "final", "program"):
        assert set(rot[stage]) == {"A", "C"} and all(set(v) == set(RATE_KEYS) for v in rot[stage].values())
    assert rot["raw"]["A"]["peak_velocity_deg_s"] == 0.0  # the floor's normal is +z all along: A stays 0
    assert rot["mc"]["A"]["peak_velocity_deg_s"] > 0.0
    assert "rotary program" in capsys.readouterr().out
