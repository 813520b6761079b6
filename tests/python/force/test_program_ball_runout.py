"""Ball end mill runout (flute j's chip f·sin ϕ + (r_j − r_{j+1})·cos ψ, docs/force.md) in the single cut
(netshape forces), the program force simulation and the job's forces stage; the kernel against a direct
element sum: tests/cpp/force/test_ball_runout.cpp."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

import netshape.force as nf
from netshape import stock as st
from netshape import toolpath as tp
from netshape.cli import main

KB = nf.ball_end_coefficient_set("kim_zas_ball12").coefficients
RPM, C, AP = 6000.0, 0.08, 4.0


def _cutter(rho=0.0, lam_deg=0.0):
    c = st.Cutter.ball_end(12.0, 2, math.radians(30))
    c.runout_rho, c.runout_lambda = rho, math.radians(lam_deg)
    return c


def _slot(cutter, **kw):
    block = st.ZMap(0.0, 24.0, -8.0, 8.0, 0.2, AP, -8.0)
    prog = tp.parse_gcode(f"G21 G90 G0 X-8 Y0 Z0\nS{RPM:g} M3\nG1 X16 F{C * 2 * RPM:g}\n")
    r = nf.simulate_program(block, cutter, prog, KB, step=2.0, samples_per_revolution=144, **kw)
    steady = r.positions[:, 0] > 8
    assert steady.sum() >= 3
    return r, steady


def test_the_cutters_runout_reaches_a_ball_end_mills_program_forces():
    """ρ 5 µm at λ 0 on an 80 µm chip (r_0 − r_1 = 10 µm): one flute cuts deeper, the peak grows; the
    mean per revolution stays within 2 % (the chip per revolution is unchanged, t^m and the clamp near
    entry and exit aside). Before, simulate_program refused a ball cutter's runout or left it out."""
    plain, s0 = _slot(_cutter())
    r, s = _slot(_cutter(0.005, 0.0))
    assert r.peak_resultant[s].mean() > 1.05 * plain.peak_resultant[s0].mean()
    np.testing.assert_allclose(r.mean[s, :2].mean(axis=0), plain.mean[s0, :2].mean(axis=0),
                               rtol=0.02, atol=0.02 * plain.mean_resultant[s0].mean())
    # the same as the explicit chip; ρ 0 (any λ) is bit-identical to no runout
    same, _ = _slot(_cutter(), chip=nf.RunoutSizeEffect(runout_rho=0.005))
    np.testing.assert_array_equal(same.peak_resultant, r.peak_resultant)
    zero, _ = _slot(_cutter(0.0, 70.0))
    for f in ("mean", "peak", "peak_resultant", "mean_resultant"):
        np.testing.assert_array_equal(getattr(zero, f), getattr(plain, f))


def test_netshape_forces_takes_a_ball_end_mills_runout(tmp_path):
    """The single cut: flute 1's pass (first half revolution) and flute 2's differ by > 10 % with
    ρ 5 µm; without runout they are equal. --chip-exponent stays a flat end mill's option."""
    base = ["forces", "--tool", "ball", "--diameter", "12", "--flutes", "2", "--rpm", "6000",
            "--feed-per-tooth", "0.08", "--ap", "4", "--mode", "slot", "--coefficient-set", "kim_zas_ball12"]
    peaks = []
    for rho in ("0", "0.005"):
        csv = tmp_path / f"b{rho}.csv"
        assert main(base + ["--runout-rho", rho, "--csv", str(csv)]) == 0
        f = np.linalg.norm(np.loadtxt(csv, delimiter=",", skiprows=1)[:, 1:], axis=1)
        peaks.append((f[:180].max(), f[180:].max()))
    assert peaks[0][0] == pytest.approx(peaks[0][1], rel=1e-9)
    assert peaks[1][0] > 1.1 * peaks[1][1]
    assert main(base + ["--chip-exponent", "0.8", "--csv", str(tmp_path / "x.csv")]) == 2
    assert not (tmp_path / "x.csv").exists()


def test_the_jobs_forces_stage_carries_a_ball_tools_runout():
    """The demo job with a 6 mm ball end mill with runout: the forces stage equals simulate_program with
    the cutter's runout and differs from the runout-free tool; the job no longer has the
    forces_without_chip_extension warning."""
    import netshape.job.stages as stages
    import netshape.job.warnings as jw
    from netshape.job.program import stage_program
    from netshape.job.spec import load_job

    job = load_job(Path(__file__).resolve().parents[3] / "examples" / "demo" / "job.toml")
    ball = dict(job.tool, kind="ball")
    plain_job = dataclasses.replace(job, tool=ball, coefficients="kim_zas_ball12")
    run_job = dataclasses.replace(plain_job, tool=dict(ball, runout_rho_mm=0.004, runout_lambda_deg=30.0))
    prog = stage_program(job)
    stock0 = stages.stage_stock(job)
    plain = stages.stage_forces(plain_job, stock0, prog)
    both = stages.stage_forces(run_job, stock0, prog)
    cutter = stages.make_cutter(run_job.tool)
    assert cutter.runout_rho == 0.004
    direct = nf.simulate_program(stock0, cutter, stages.stock_frame_toolpath(prog), KB,
                                 step=job.cutting["step_mm"],
                                 samples_per_revolution=job.cutting["samples_per_revolution"],
                                 disk_height=job.cutting["disk_height_mm"])
    np.testing.assert_allclose(both.peak_resultant, direct.peak_resultant, rtol=1e-9)
    assert np.max(both.peak_resultant) > 1.03 * np.max(plain.peak_resultant)
    assert not hasattr(jw, "forces_without_chip_extension")
