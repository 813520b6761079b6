"""Flat end mill model: published numbers (J.-H. Cho & S.-H. Suh, "Path compensation toward direct shape
control: dealing with tool deflection problem in 2D contour machining"), closed forms (Y. Altintas,
Manufacturing Automation, ch. 2), convergence, signs. Full references: docs/references.md."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.force as nf

K = dict(ktc=958.8, krc=251.1, kac=146.4, kte=15.8, kre=19.4, kae=18.2)


def model(mode="slot", ae=10.0, dz=0.02, helix=30.0, c=0.1, k=K, R=5.0, ap=3.0, N=2):
    e = nf.AngularEngagement.from_mode(nf.milling_mode_from_string(mode), R, ae)
    return nf.FlatEndModel(radius=R, flutes=N, helix=math.radians(helix), axial_depth=ap, feed_per_tooth=c,
                           engagement=e, linear_edge=nf.LinearEdgeCoefficients(**k), disk_height=dz)


def test_cho_suh_helix_lag():
    """Cho & Suh §5: D = 25 mm, 60° helix, A = 2.5 mm; the lag at mid depth z = 1.25 mm is
    z·tanβ/R = 9.92° (the paper prints 9.915°)."""
    m = nf.FlatEndModel(radius=12.5, helix=math.radians(60), axial_depth=2.5)
    lag = math.degrees(m.k_beta() * 1.25)
    assert lag == pytest.approx(9.924, abs=1e-3)
    assert abs(lag - 9.915) < 0.01


def test_altintas_slot_mean_closed_form():
    """Altintas, Manufacturing Automation ch. 2, slot (φ 0…π), in the cutting frame of
    docs/conventions.md §2 (forces on the cutter, φ clockwise from +Y):
    F̄x = −N a krc c/4 − N a kre/π, F̄y = N a ktc c/4 + N a kte/π,
    F̄z = N a kac c/π + N a kae/2. The simulated mean equals them."""
    m = model()
    F = nf.flat_end_forces(m, nf.rotation_angles(3600))
    N, a, c = 2, 3.0, 0.1
    expect = [-N * a * K["krc"] * c / 4 - N * a * K["kre"] / math.pi,
              N * a * K["ktc"] * c / 4 + N * a * K["kte"] / math.pi,
              N * a * K["kac"] * c / math.pi + N * a * K["kae"] / 2]
    np.testing.assert_allclose(F.mean(axis=0), expect, rtol=2e-3)
    np.testing.assert_allclose(nf.mean_force(m.linear_edge, m.engagement, c, N, a), expect, rtol=1e-12)


@pytest.mark.parametrize("mode", ["up", "down"])
def test_up_down_mean_closed_form(mode):
    """General closed form N a/(2π) ∫ over [φst, φex] (windows of docs/conventions.md §2) equals the
    simulated mean."""
    m = model(mode, ae=2.0)
    F = nf.flat_end_forces(m, nf.rotation_angles(7200))
    cf = nf.mean_force(m.linear_edge, m.engagement, 0.1, 2, 3.0)
    np.testing.assert_allclose(F.mean(axis=0), cf, rtol=5e-3, atol=0.05)


def test_sign_conventions():
    """Slot with positive coefficients, forces ON THE CUTTER: the front half (φ≈90°, at +X) pushes
    the cutter back (F̄x < 0: F̄x = −N a(krc c/4 + kre/π)); the cutting velocity of a clockwise
    cutter at +X points to −Y so the tangential force on the cutter points to +Y (F̄y > 0).
    A single straight flute (β = 0) at φ = 90°: Fx = −Fr, Fy = +Ft exactly."""
    m = model()
    F = nf.flat_end_forces(m, nf.rotation_angles(360)).mean(axis=0)
    assert F[0] < 0 and F[1] > 0 and F[2] > 0
    m1 = model(helix=0.0, N=1, k=dict(ktc=1000.0, krc=300.0))
    f = nf.flat_end_forces(m1, np.array([math.pi / 2]))[0]
    ft, fr = 1000.0 * 0.1 * 3.0, 300.0 * 0.1 * 3.0
    np.testing.assert_allclose(f, [-fr, ft, 0.0], rtol=1e-12, atol=1e-9)
    # down milling (near exit, φ→π) of a straight flute: Fx = −Ft cos φ − Fr sin φ > 0 near π
    g = nf.flat_end_forces(m1, np.array([math.radians(170)]))[0]
    assert g[0] > 0


def _analytic(theta, R, N, beta, ap, c, k, st, ex):
    """Exact helical integral of the linear edge model: φ(z) = θ + j 2π/N − kβ z, dz = −dφ/kβ."""
    kb = math.tan(beta) / R
    S2 = lambda p: 0.5 * np.sin(p) ** 2
    Q = lambda p: 0.5 * p - 0.25 * np.sin(2 * p)

    def G(p):
        return np.array([
            -k["ktc"] * c * S2(p) - k["krc"] * c * Q(p) - k["kte"] * np.sin(p) + k["kre"] * np.cos(p),
            k["ktc"] * c * Q(p) - k["krc"] * c * S2(p) - k["kte"] * np.cos(p) - k["kre"] * np.sin(p),
            -k["kac"] * c * np.cos(p) + k["kae"] * p])

    total = np.zeros(3)
    for j in range(N):
        hi = theta + j * 2 * math.pi / N
        lo = hi - kb * ap
        for m in range(-3, 4):
            a, b = max(lo, st + 2 * math.pi * m), min(hi, ex + 2 * math.pi * m)
            if b > a:
                total += (G(b - 2 * math.pi * m) - G(a - 2 * math.pi * m)) / kb
    return total


def test_matches_exact_helical_integral_and_converges():
    """Independent check: the disk sum tends to the exact helical integral. Cutting terms only in a
    slot (the integrand vanishes at entry and exit, a kink inside a disk) → second order in dz;
    with edge forces (a jump at entry/exit) → first order."""
    thetas = np.linspace(0.1, 2 * math.pi, 37)
    for kk, order in ((dict(ktc=958.8, krc=251.1, kac=146.4, kte=0, kre=0, kae=0), 2.0), (K, 1.0)):
        exact = np.array([_analytic(t, 5.0, 2, math.radians(30), 3.0, 0.1, kk, 0.0, math.pi) for t in thetas])
        errs = []
        for dz in (0.2, 0.1, 0.05, 0.025):
            F = nf.flat_end_forces(model(dz=dz, k=kk), thetas)
            errs.append(np.abs(F - exact).max())
        rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
        assert errs[-1] < 0.02 * np.abs(exact).max()
        assert np.mean(rates) == pytest.approx(order, abs=0.45), (errs, rates)


def test_kline_devor_equals_linear_edge():
    """Cho & Suh eq. 1–5 (α = π − φ inside) equals the linear edge model with ktc = K_T, krc = K_R K_T."""
    a = model("down", ae=3.0)
    kd = nf.KlineDevorCoefficients(800.0, 0.3)
    b = nf.FlatEndModel(radius=5, flutes=2, helix=math.radians(30), axial_depth=3, feed_per_tooth=0.1,
                        engagement=a.engagement, coefficient_model=nf.FlatCoefficientModel.kline_devor,
                        kline_devor=kd, disk_height=0.02)
    a.linear_edge = kd.to_linear_edge()
    th = nf.rotation_angles(180)
    np.testing.assert_allclose(nf.flat_end_forces(a, th), nf.flat_end_forces(b, th), rtol=1e-10, atol=1e-9)


def test_summaries_per_revolution():
    m = model()
    th = nf.rotation_angles(720, 2.0)
    F = nf.flat_end_forces(m, th)
    revs = nf.summarize_revolutions(th, F)
    assert len(revs) == 2
    np.testing.assert_allclose(revs[0]["mean"], F[:360].mean(axis=0))
    assert revs[0]["peak_resultant"] == pytest.approx(np.linalg.norm(F[:360], axis=1).max())


def test_workspace_reuse_no_copy_and_same_result():
    m = model()
    ws = nf.FlatEndWorkspace(m)
    th = nf.rotation_angles(90)
    np.testing.assert_array_equal(nf.flat_end_forces(m, th, ws), nf.flat_end_forces(m, th))


@pytest.mark.parametrize("kw,field", [
    (dict(radius=-1.0), "radius"), (dict(axial_depth=0.0), "axial_depth"), (dict(flutes=0), "flutes"),
    (dict(feed_per_tooth=float("nan")), "feed_per_tooth"), (dict(helix=2.0), "helix"),
    (dict(disk_height=0.0), "disk_height")])
def test_bad_input_names_field(kw, field):
    with pytest.raises(ValueError, match=field):
        nf.FlatEndModel(**kw)


def test_bad_engagement_and_angles():
    with pytest.raises(ValueError, match="ae"):
        nf.AngularEngagement.from_mode(nf.MillingMode.up, 5.0, 12.0)
    with pytest.raises(ValueError, match="phi_ex"):
        nf.AngularEngagement(1.0, 0.5)
    with pytest.raises(ValueError, match="angles"):
        nf.flat_end_forces(model(), np.array([0.0, float("inf")]))
    with pytest.raises(ValueError, match="mode"):
        nf.milling_mode_from_string("climb")
