"""Ball end mill model after G. M. Kim, P. J. Cho, B. H. Kim & C. N. Chu, "Cutting force prediction in
the ball-end milling process of various cutting area using Z-map" (Kim et al.; docs/references.md):
published coefficient set, eq. 3–8, ramp cuts, and the §4.2 fitting procedure."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.force as nf

PUB = nf.ball_end_coefficient_set("kim_zas_ball12")


def test_published_set_and_polynomials():
    """Kim et al. §4.2: K_T = 321.7 + 803.1ψ − 1165.5ψ² + 550.7ψ³, K_R = 104.1 + 139.1ψ − 213.1ψ² + 69.3ψ³,
    m_T = 0.7053, m_R = 0.4788; D = 12 mm, 2 flutes, 30° helix."""
    k = PUB.coefficients
    assert PUB.diameter == 12.0 and PUB.flutes == 2 and PUB.helix == pytest.approx(math.radians(30))
    assert (k.m_t, k.m_r) == (0.7053, 0.4788)
    psi = np.array([0.0, 0.5, 1.0, math.pi / 2])
    np.testing.assert_allclose(k.kt(psi), 321.7 + 803.1 * psi - 1165.5 * psi**2 + 550.7 * psi**3, rtol=1e-14)
    np.testing.assert_allclose(k.kr(psi), 104.1 + 139.1 * psi - 213.1 * psi**2 + 69.3 * psi**3, rtol=1e-14)
    # hand values: K_T(0) = 321.7, K_T(1) = 510.0, K_R(1) = 99.4, K_T(π/2) ≈ 841.85
    assert k.kt(1.0) == pytest.approx(510.0)
    assert k.kr(1.0) == pytest.approx(99.4)
    assert k.kt(math.pi / 2) == pytest.approx(841.845, abs=0.001)


def _reference(theta, R, N, beta, ap, f, k, xi, dpsi_deg=1.0):
    """Independent NumPy evaluation of Kim et al. eq. 1, 4, 5, 6 (the paper's asin/acos form of the
    rotated-frame angles) with the projection of docs/conventions.md §3; elements over the whole
    hemisphere, engaged where the element is in front of the inclined feed and below a_p in the rotated
    frame."""
    n = int(round(90 / dpsi_deg))
    dpsi = (math.pi / 2) / n
    psi = (np.arange(n) + 0.5) * dpsi          # position angle (0 equator … π/2 tip)
    z = R * (1 - np.sin(psi))
    out = np.zeros((len(theta), 3))
    for a, th in enumerate(theta):
        for j in range(N):
            ph = th + j * 2 * math.pi / N - math.tan(beta) / R * z          # tool-frame immersion
            sphi_p = np.sin(ph) * np.cos(psi) * math.sin(xi) + np.sin(psi) * math.cos(xi)   # eq. 4
            phi_p = np.arcsin(np.clip(sphi_p, -1, 1))
            vphi = np.arccos(np.clip(np.cos(ph) * np.cos(psi) / np.cos(phi_p), -1, 1))      # eq. 4
            ahead = np.sin(ph) * np.cos(psi) * math.cos(xi) - np.sin(psi) * math.sin(xi) > 0  # y' > 0
            below = R * (1 - sphi_p) <= ap * (1 + 1e-12)
            t = f * np.sin(vphi)                                              # eq. 5
            dw = R * np.cos(phi_p) * dpsi                                     # eq. 5
            eng = ahead & below & (t > 0)
            tt = np.where(eng, t, 1.0)
            dft = np.where(eng, k.kt(psi) * tt**k.m_t * dw, 0.0)              # eq. 6
            dfr = np.where(eng, k.kr(psi) * tt**k.m_r * dw, 0.0)
            out[a, 0] += np.sum(-dft * np.cos(ph) - dfr * np.sin(ph))
            out[a, 1] += np.sum(dft * np.sin(ph) - dfr * np.cos(ph))
    return out


@pytest.mark.parametrize("xi_deg", [0.0, 20.0, -30.0])
def test_matches_independent_eq_1_to_8(xi_deg):
    th = np.linspace(0, 2 * math.pi, 73)
    m = nf.BallEndModel(radius=6.0, flutes=2, helix=math.radians(30), axial_depth=3.0, feed_per_tooth=0.05,
                        inclination=math.radians(xi_deg), coefficients=PUB.coefficients,
                        element_angle=math.radians(1.0))
    F = nf.ball_end_forces(m, th)
    ref = _reference(th, 6.0, 2, math.radians(30), 3.0, 0.05, PUB.coefficients, math.radians(xi_deg))
    np.testing.assert_allclose(F, ref, atol=1e-9 * np.abs(ref).max() + 1e-9)


def test_ramp_xi_to_zero_equals_plain_cut():
    """ξ → 0 of the ramp model equals the plain (ξ = 0) slot: eq. 4 gives φ' = φ, ϕ = θ."""
    th = nf.rotation_angles(180)
    base = dict(radius=6.0, flutes=2, helix=math.radians(30), axial_depth=3.0, feed_per_tooth=0.05,
                coefficients=PUB.coefficients, element_angle=math.radians(0.25))
    F0 = nf.ball_end_forces(nf.BallEndModel(**base), th)
    F1 = nf.ball_end_forces(nf.BallEndModel(inclination=1e-9, **base), th)
    assert np.abs(F1 - F0).max() < 0.01 * np.abs(F0).max()
    # a climbing ramp takes the tip out of the cut (it trails) and lowers the load
    Fup = nf.ball_end_forces(nf.BallEndModel(inclination=math.radians(30), **base), th)
    assert np.linalg.norm(Fup, axis=1).mean() != pytest.approx(np.linalg.norm(F0, axis=1).mean(), rel=0.05)


def test_mean_slot_force_closed_form_equals_simulation():
    m = nf.BallEndModel(radius=6, axial_depth=3, feed_per_tooth=0.05, coefficients=PUB.coefficients)
    sim = nf.ball_end_forces(m, nf.rotation_angles(3600)).mean(axis=0)
    np.testing.assert_allclose(nf.ball_end_mean_slot_force(m), sim, rtol=1e-4, atol=1e-6)
    assert sim[0] < 0 < sim[1]


def test_kim_cho_table1_fit_recovers_published_set():
    """Kim et al. §4.2 (Table 1): slot tests over a_p 0.3–6 mm and f 0.01–0.075 mm/tooth. Mean forces
    synthesised by simulating the published set over a revolution, then fitted: the coefficients and
    exponents come back."""
    depths, feeds, fx, fy = [], [], [], []
    th = nf.rotation_angles(720)
    for ap in (0.3, 0.6, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0):
        for f in (0.01, 0.021, 0.03, 0.045, 0.05, 0.06, 0.075):
            m = nf.BallEndModel(radius=6, flutes=2, helix=math.radians(30), axial_depth=ap, feed_per_tooth=f,
                                coefficients=PUB.coefficients)
            F = nf.ball_end_forces(m, th).mean(axis=0)
            depths.append(ap), feeds.append(f), fx.append(F[0]), fy.append(F[1])
    geom = nf.BallEndModel(radius=6, flutes=2, helix=math.radians(30))
    fit = nf.fit_ball_end_mean_forces(geom, np.array(depths), np.array(feeds), np.array(fx), np.array(fy))
    k = fit.coefficients
    assert k.m_t == pytest.approx(0.7053, abs=2e-3)
    assert k.m_r == pytest.approx(0.4788, abs=2e-3)
    psi = np.linspace(0, math.pi / 2, 7)
    np.testing.assert_allclose(k.kt(psi), PUB.coefficients.kt(psi), rtol=0.01)
    np.testing.assert_allclose(k.kr(psi), PUB.coefficients.kr(psi), rtol=0.01)
    assert fit.rms_y < 1e-2 * np.abs(fy).max()


def test_ball_bad_input():
    with pytest.raises(ValueError, match="inclination"):
        nf.BallEndModel(inclination=math.radians(85))
    with pytest.raises(ValueError, match="m_t"):
        nf.BallEndCoefficients([1, 0, 0, 0], [1, 0, 0, 0], 0.0, 0.5)
    with pytest.raises(ValueError, match="coefficient_set"):
        nf.ball_end_coefficient_set("kim2000")
    with pytest.raises(ValueError, match="depths"):
        nf.fit_ball_end_mean_forces(nf.BallEndModel(), np.ones(6), np.linspace(0.01, 0.06, 6), -np.ones(6), np.ones(6))
