"""The program force simulation with the cutter's runout and the coefficients' chip-size effect,
against the single-cut model (netshape.force.flat_end_forces_extended, tested against a direct element
sum in tests/cpp/force/test_runout_size_effect.cpp) on the steady part of a straight slot."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.force as nf
from netshape import stock as st
from netshape import toolpath as tp
from netshape.deflection.chip import SizeEffectCoefficients

K = nf.LinearEdgeCoefficients(ktc=958.8, krc=251.1, kac=146.4, kte=15.8, kre=19.4, kae=18.2)
RPM, C, AP, SPR = 6000.0, 0.05, 3.0, 180


def _slot(cutter, coefficients, **kw):
    block = st.ZMap(0.0, 30.0, -8.0, 8.0, 0.1, AP, -5.0)
    feed = C * cutter.flutes * RPM  # mm/min
    prog = tp.parse_gcode(f"G21 G90 G0 X-6 Y0 Z0\nS{RPM:g} M3\nG1 X20 F{feed:g}\n")
    r = nf.simulate_program(block, cutter, prog, coefficients, step=1.0, samples_per_revolution=SPR, bins=720,
                            disk_height=0.05, **kw)
    steady = r.positions[:, 0] > 10
    assert steady.sum() >= 5
    return r, steady


def _single(ext):
    slot = nf.AngularEngagement.from_mode(nf.MillingMode.slot, 4.0, 8.0)
    m = nf.FlatEndModel(radius=4, flutes=3, helix=math.radians(30), axial_depth=AP, feed_per_tooth=C,
                        engagement=slot, linear_edge=K, disk_height=0.05)
    return nf.flat_end_forces_extended(m, ext, nf.rotation_angles(SPR))


def _cutter(rho=0.0, lam_deg=0.0):
    c = st.Cutter.flat_end(8.0, 3, math.radians(30))
    c.runout_rho, c.runout_lambda = rho, math.radians(lam_deg)
    return c


def _check(r, steady, F):
    mean = np.tile(F.mean(axis=0), (steady.sum(), 1))
    np.testing.assert_allclose(r.mean[steady, :2], mean[:, :2], rtol=0.02, atol=1.0)
    # Fz: the Z-map's engagement edges at φ = 0 and π, where a flute's chip is its runout step alone
    # and the axial edge term dominates Fz, give 2-4 % more mean Fz than the window [0, π] at every λ
    # (ρ 15 µm, λ 0-315°: +1.9 to +3.6 N on ~95 N; Fx, Fy within 0.2 N, peaks equal)
    np.testing.assert_allclose(r.mean[steady, 2], mean[:, 2], rtol=0.05)
    np.testing.assert_allclose(r.peak_resultant[steady], np.linalg.norm(F, axis=1).max(), rtol=0.02)


def test_the_cutters_runout_loads_one_flute_more_as_the_single_cut_model():
    """ρ 15 µm on a 50 µm chip: the flute that cuts deepest takes up to 0.05 + 0.026 mm, so the
    peak per revolution grows by ~40 % over the runout-free cut (it stayed at the runout-free value
    before the program forces carried the runout)."""
    ext = nf.RunoutSizeEffect(runout_rho=0.015, runout_lambda=math.radians(20))
    r, steady = _slot(_cutter(0.015, 20), K)
    F = _single(ext)
    _check(r, steady, F)
    plain, s0 = _slot(_cutter(), K)
    assert r.peak_resultant[steady].mean() > 1.2 * plain.peak_resultant[s0].mean()
    # runout shifts load between flutes; the mean in-plane force per revolution is nearly unchanged
    # (Fz drops ~10 %: the flute whose chip is clamped at 0 loses its edge force, Kae dominating Fz)
    np.testing.assert_allclose(r.mean[steady, :2].mean(axis=0), plain.mean[s0, :2].mean(axis=0), rtol=0.03)
    # a chip given explicitly replaces the cutter's runout
    r0, _ = _slot(_cutter(0.015, 20), K, chip=nf.RunoutSizeEffect())
    np.testing.assert_array_equal(r0.peak_resultant, plain.peak_resultant)


def test_the_size_effect_of_the_coefficients_reaches_the_program_forces():
    """chip_exponent 0.7 at h_ref 0.1 mm: a 50 µm chip cuts 0.1·0.5^0.7 = 0.062 mm 'equivalent', so the
    cutting forces grow by ~23 %, as the single-cut model with the same size effect."""
    k = SizeEffectCoefficients(K, 0.7, 0.1)
    r, steady = _slot(_cutter(0.01, 0.0), k)
    _check(r, steady, _single(nf.RunoutSizeEffect(runout_rho=0.01, chip_exponent=0.7, reference_chip=0.1)))
    plain, s0 = _slot(_cutter(), K)
    assert r.mean_resultant[steady].mean() > 1.15 * plain.mean_resultant[s0].mean()


def test_no_runout_and_no_size_effect_is_bit_identical_to_the_linear_model():
    plain, _ = _slot(_cutter(), K)
    same, _ = _slot(_cutter(), SizeEffectCoefficients(K, 1.0, 0.0))
    for f in ("mean", "peak", "peak_resultant", "mean_resultant", "engaged_fraction"):
        np.testing.assert_array_equal(getattr(plain, f), getattr(same, f))


def test_a_ball_end_mill_refuses_a_chip_exponent():
    """Its size effect is Feng–Menq's m_T, m_R; its runout: tests/python/force/test_program_ball_runout.py."""
    cutter = st.Cutter.ball_end(8.0, 2, math.radians(30))
    block = st.ZMap(0.0, 10.0, -8.0, 8.0, 0.2, 1.0, -5.0)
    prog = tp.parse_gcode("G21 G90 G0 X-6 Y0 Z0\nS6000 M3\nG1 X5 F600\n")
    kb = nf.ball_end_coefficient_set("kim_zas_ball12").coefficients
    with pytest.raises(ValueError, match="chip_exponent"):
        nf.simulate_program(block, cutter, prog, kb, chip=nf.RunoutSizeEffect(chip_exponent=0.8))


def test_the_feed_schedule_takes_size_effect_coefficients_as_their_linear_part():
    """netshape feeds solves the linear chip in closed form (docs/feeds.md): coefficients with a size
    effect (the job's [coefficients] table) are scheduled with their linear part, not refused."""
    from netshape.compensation.feeds import FeedLimits, schedule_feeds

    block = st.ZMap(0.0, 12.0, -8.0, 8.0, 0.2, AP, -5.0)
    prog = tp.parse_gcode(f"G21 G90 G0 X-6 Y0 Z0\nS{RPM:g} M3\nG1 X10 F900\n")
    lim = FeedLimits()
    lim.max_force, lim.max_feed = 300.0, 200.0
    kw = dict(step=1.0, samples_per_revolution=36)
    plain = schedule_feeds(block, _cutter(), prog, K, lim, **kw)
    sized = schedule_feeds(block, _cutter(), prog, SizeEffectCoefficients(K, 0.7, 0.1), lim, **kw)
    np.testing.assert_array_equal(plain.samples["allowed"], sized.samples["allowed"])
    assert np.isfinite(plain.samples["allowed"][:, 0]).any()


def test_the_jobs_forces_stage_carries_the_tools_runout_and_the_size_effect():
    """The demo job with runout in its tool and a chip exponent in its coefficient table: the forces
    stage changes and equals the program force simulation with both."""
    import dataclasses
    from pathlib import Path

    import netshape.job.stages as stages
    from netshape.job.program import stage_program
    from netshape.job.spec import load_job

    job = load_job(Path(__file__).resolve().parents[3] / "examples" / "demo" / "job.toml")
    k = nf.linear_edge_coefficient_set(job.coefficients).coefficients
    table = {"Ktc_N_mm2": k.ktc, "Krc_N_mm2": k.krc, "Kac_N_mm2": k.kac, "Kte_N_mm": k.kte, "Kre_N_mm": k.kre,
             "Kae_N_mm": k.kae, "chip_exponent": 0.8, "reference_chip_mm": 0.05}
    ext = dataclasses.replace(job, tool=dict(job.tool, runout_rho_mm=0.01, runout_lambda_deg=30.0),
                              coefficients=table)
    prog = stage_program(job)
    stock0 = stages.stage_stock(job)
    plain = stages.stage_forces(job, stock0, prog)
    both = stages.stage_forces(ext, stock0, prog)
    assert np.max(both.peak_resultant) > 1.1 * np.max(plain.peak_resultant)
    cutter = stages.make_cutter(ext.tool)
    assert cutter.runout_rho == 0.01
    direct = nf.simulate_program(stock0, cutter, stages.stock_frame_toolpath(prog),
                                 SizeEffectCoefficients(k, 0.8, 0.05), step=ext.cutting["step_mm"],
                                 samples_per_revolution=ext.cutting["samples_per_revolution"],
                                 disk_height=ext.cutting["disk_height_mm"])
    np.testing.assert_allclose(both.peak_resultant, direct.peak_resultant, rtol=1e-9)
