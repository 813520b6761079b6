"""Steady side cuts of a ball end mill: each element's window comes from its own radius r(z) and the
wall at R − a_e from the axis (docs/conventions.md §2), checked against the engagement that a Z-map of a box
pre-cut to that wall gives (netshape.stock.engaged_elements, the Kim et al. §3.2 reading), against an
independent NumPy evaluation of Kim et al. eq. 1, 4–6 with the wall, and flat end mills unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.force as nf
from netshape import stock as st

PUB = nf.ball_end_coefficient_set("kim_zas_ball12")  # Kim et al. §4.2: D 12 mm, 2 flutes, 30°
R = 6.0
HELIX = math.radians(30.0)
SPACING = 0.01   # Z-map node spacing [mm]: the wall lands within SPACING/2 of R − a_e
BINS = 2880      # angular bins of the map (0.125°)


def _walled_box(mode, ae, ap, spacing=SPACING):
    """A box with its top at a_p above the tool tip (z = 0) and a straight wall parallel to the feed
    (+X) at y = R − a_e (up milling, material on +Y) or y = −(R − a_e) (down milling, material on −Y);
    the other side is pre-cut below the tip. The grid is offset so that the wall does not fall on a
    cell edge: the pillar model puts it on the nearest edge. Returns (Z-map, the a_e of that edge)."""
    x0, x1, y0, y1 = -R - 1.0, R + 1.0, -R - 0.5 + 0.0037, R + 0.5 + 0.0037
    nx, ny = int(round((x1 - x0) / spacing)), int(round((y1 - y0) / spacing))
    dy = (y1 - y0) / ny
    y = y0 + (np.arange(ny) + 0.5) * dy
    wall = R - ae
    keep = y >= wall if mode == "up" else y <= -wall
    heights = np.where(keep[:, None], ap, -5.0) * np.ones((1, nx))
    edge = y[keep].min() - 0.5 * dy if mode == "up" else -(y[keep].max() + 0.5 * dy)
    return st.ZMap.from_heights(heights, x0, x1, y0, y1, -5.0), R - edge


def _zmap_map(cutter, mode, ae, ap, heights, step=0.5):
    """Engagement map of the rows `heights` with the cutter at the origin moving along +X, read as
    netshape.force.simulate_program does: after the straight cut has been swept up to `step` [mm]
    behind (steady state; the material in front of the edges is still there). Returns (map, a_e of
    the Z-map's wall)."""
    z, ae_grid = _walled_box(mode, ae, ap)
    st.sweep_line(z, cutter, np.array([-R - 3.0, 0, 0]), np.array([-step, 0, 0]))
    phi = (np.arange(BINS) + 0.5) * 2 * math.pi / BINS
    mask = st.engaged_elements(z, cutter, np.zeros(3), np.array([1.0, 0, 0]), phi, np.asarray(heights))
    return nf.EngagementMap(mask.astype(np.uint8)), ae_grid


def _ball(mode, ae, ap, c=0.08, xi=0.0):
    e = nf.AngularEngagement.from_mode(nf.milling_mode_from_string(mode), R, ae)
    return nf.BallEndModel(radius=R, flutes=2, helix=HELIX, axial_depth=ap, feed_per_tooth=c, inclination=xi,
                           engagement=e, coefficients=PUB.coefficients, element_angle=math.radians(0.5),
                           disk_height=0.05)


@pytest.mark.parametrize("ap", [4.0, 8.0])
@pytest.mark.parametrize("ae", [0.5, 1.5, 3.0, 6.0])
@pytest.mark.parametrize("mode", ["up", "down"])
def test_ball_steady_cut_equals_zmap_wall(mode, ae, ap):
    """Steady mode = the elements a Z-map of the walled box engages (same chip, same coefficients),
    for a_p below and above R. The Z-map's wall lies on a cell edge within SPACING/2 = 0.005 mm of
    R − a_e: at that edge's a_e the steady mode agrees within 0.3 % of the mean in-plane resultant
    + 0.005 N in the mean and 0.5 % (L1) in the waveform (bins of 0.125°, element points read per
    cell); at the nominal a_e within 1 % + 0.03 N (the 0.005 mm wall shift itself)."""
    cutter = st.Cutter.ball_end(2 * R, 2, HELIX)
    cutter.flute_length = 20.0
    m = _ball(mode, ae, ap)
    ws = nf.BallEndWorkspace(m)
    th = nf.rotation_angles(360)
    zmap, ae_grid = _zmap_map(cutter, mode, ae, ap, ws.heights())
    assert abs(ae_grid - ae) <= 0.5 * SPACING + 1e-12
    G = nf.ball_end_forces(m, th, ws, zmap)
    F = nf.ball_end_forces(_ball(mode, ae_grid, ap), th)
    scale = np.linalg.norm(F[:, :2], axis=1).mean()
    assert scale > 0.1
    np.testing.assert_allclose(G.mean(axis=0)[:2], F.mean(axis=0)[:2], atol=0.003 * scale + 0.005)
    assert np.abs(F[:, :2] - G[:, :2]).mean() < 0.005 * np.abs(F[:, :2]).mean() + 0.005
    nominal = nf.ball_end_forces(m, th, ws)
    np.testing.assert_allclose(G.mean(axis=0)[:2], nominal.mean(axis=0)[:2], atol=0.01 * scale + 0.03)


def test_issue_cut_against_zmap_and_old_full_radius_window():
    """Kim et al. set, down milling, a_e 3, a_p 2, c 0.08 (issue 24): the mean force follows the
    Z-map, and the old reading (every element with the window of the full radius R, which the map
    `from_window` reproduces) is 3–4× larger."""
    cutter = st.Cutter.ball_end(2 * R, 2, HELIX)
    m = _ball("down", 3.0, 2.0)
    ws = nf.BallEndWorkspace(m)
    th = nf.rotation_angles(360)
    F = nf.ball_end_forces(m, th, ws).mean(axis=0)
    G = nf.ball_end_forces(m, th, ws, _zmap_map(cutter, "down", 3.0, 2.0, ws.heights())[0]).mean(axis=0)
    old = nf.ball_end_forces(m, th, ws, nf.EngagementMap.from_window(m.engagement, ws.rows(), BINS)).mean(axis=0)
    np.testing.assert_allclose(F[:2], G[:2], rtol=0.01, atol=0.05)
    assert 2.5 < old[0] / F[0] < 4.5 and 2.5 < old[1] / F[1] < 4.5


def test_elements_inside_the_wall_do_not_cut():
    """a_p 2 < R: the largest element radius is √(R² − (R − a_p)²) = 4.47 mm < R − a_e = 5 mm for
    a_e = 1, so no element reaches the wall: zero force; a_e = 2 (wall at 4 mm) cuts."""
    th = nf.rotation_angles(90)
    for mode in ("up", "down"):
        assert np.abs(nf.ball_end_forces(_ball(mode, 1.0, 2.0), th)).max() == 0.0
        assert np.abs(nf.ball_end_forces(_ball(mode, 2.0, 2.0), th)).max() > 1.0


def test_full_width_side_cut_equals_slot():
    """a_e = D puts the wall at −R: every element cuts its whole front half, as in a slot (window [0, π])."""
    th = nf.rotation_angles(120)
    slot = nf.ball_end_forces(_ball("slot", 0.0, 3.0), th)
    for mode in ("up", "down"):
        np.testing.assert_allclose(nf.ball_end_forces(_ball(mode, 2 * R, 3.0), th), slot,
                                   atol=1e-9 * np.abs(slot).max())


def _reference_wall(theta, ap, f, k, xi, wall_y, up, dpsi_deg=0.5):
    """Independent NumPy evaluation of Kim et al. eq. 1, 4, 5, 6 (asin/acos form, ball part only,
    a_p ≤ R) with a straight wall parallel to the feed: an element cuts where it is ahead of the
    inclined feed, below a_p in the rotated frame, and on the material side of y = wall_y."""
    n = int(round(90 / dpsi_deg))
    dpsi = (math.pi / 2) / n
    psi = (np.arange(n) + 0.5) * dpsi
    z = R * (1 - np.sin(psi))
    out = np.zeros((len(theta), 2))
    for a, th in enumerate(theta):
        for j in range(2):
            ph = th + j * math.pi - math.tan(HELIX) / R * z
            sphi_p = np.sin(ph) * np.cos(psi) * math.sin(xi) + np.sin(psi) * math.cos(xi)
            phi_p = np.arcsin(np.clip(sphi_p, -1, 1))
            vphi = np.arccos(np.clip(np.cos(ph) * np.cos(psi) / np.cos(phi_p), -1, 1))
            ahead = np.sin(ph) * np.cos(psi) * math.cos(xi) - np.sin(psi) * math.sin(xi) > 0
            below = R * (1 - sphi_p) <= ap * (1 + 1e-12)
            y = R * np.cos(psi) * np.cos(ph)
            side = y >= wall_y if up else y <= wall_y
            t = f * np.sin(vphi)
            dw = R * np.cos(phi_p) * dpsi
            eng = ahead & below & side & (t > 0)
            tt = np.where(eng, t, 1.0)
            dft = np.where(eng, k.kt(psi) * tt**k.m_t * dw, 0.0)
            dfr = np.where(eng, k.kr(psi) * tt**k.m_r * dw, 0.0)
            out[a, 0] += np.sum(-dft * np.cos(ph) - dfr * np.sin(ph))
            out[a, 1] += np.sum(dft * np.sin(ph) - dfr * np.cos(ph))
    return out


@pytest.mark.parametrize(("mode", "ae", "xi_deg"), [("up", 2.0, 0.0), ("down", 3.0, 0.0), ("up", 2.5, 20.0),
                                                    ("down", 1.5, -25.0)])
def test_wall_matches_independent_eq_1_to_6(mode, ae, xi_deg):
    """The per-element wall, also on a ramp (the wall y = ±(R − a_e) is a vertical plane containing
    the inclined feed), equals the NumPy reference element by element (same Δψ grid)."""
    th = np.linspace(0, 2 * math.pi, 61)
    m = _ball(mode, ae, 3.0, c=0.05, xi=math.radians(xi_deg))
    F = nf.ball_end_forces(m, th)
    up = mode == "up"
    ref = _reference_wall(th, 3.0, 0.05, PUB.coefficients, math.radians(xi_deg), (R - ae) if up else -(R - ae), up)
    np.testing.assert_allclose(F[:, :2], ref, atol=1e-9 * np.abs(ref).max() + 1e-9)


@pytest.mark.parametrize("mode", ["up", "down"])
def test_flat_end_mill_window_equals_zmap_wall(mode):
    """A flat end mill's elements all sit at R: its window [0, acos(1 − a_e/R)] (up) or
    [π − acos(1 − a_e/R), π] (down) is the wall, and the Z-map of the walled box agrees with it
    (same tolerance as the ball; the flat model itself is unchanged, its closed forms are tested in
    test_flat_model.py)."""
    ae, ap = 1.5, 3.0
    cutter = st.Cutter.flat_end(2 * R, 2, HELIX)
    # cutting terms only: the edge terms also count elements with h = 0, and the Z-map read `step`
    # behind the cutter keeps a sliver of material just behind the side (X in (−step/2, 0))
    K = nf.LinearEdgeCoefficients(ktc=958.8, krc=251.1, kac=146.4)
    e = nf.AngularEngagement.from_mode(nf.milling_mode_from_string(mode), R, ae)
    m = nf.FlatEndModel(radius=R, flutes=2, helix=HELIX, axial_depth=ap, feed_per_tooth=0.08, engagement=e,
                        linear_edge=K, disk_height=0.05)
    ws = nf.FlatEndWorkspace(m)
    th = nf.rotation_angles(360)
    zmap, ae_grid = _zmap_map(cutter, mode, ae, ap, ws.heights())
    G = nf.flat_end_forces(m, th, ws, zmap)
    m.engagement = nf.AngularEngagement.from_mode(nf.milling_mode_from_string(mode), R, ae_grid)
    F = nf.flat_end_forces(m, th, ws)
    scale = np.linalg.norm(F[:, :2], axis=1).mean()
    np.testing.assert_allclose(G.mean(axis=0), F.mean(axis=0), atol=0.003 * scale + 0.005)


def test_slot_radial_depth_is_the_diameter():
    """A slot is cut by the whole tool: cutter_forces takes ae = D or None for it and names ae otherwise."""
    kw = dict(tool="ball", diameter=12.0, flutes=2, helix_deg=30.0, feed_per_tooth=0.05, ap=3.0, mode="slot",
              samples_per_revolution=36)
    _, a = nf.cutter_forces(**kw)
    _, b = nf.cutter_forces(ae=12.0, **kw)
    np.testing.assert_array_equal(a, b)
    with pytest.raises(ValueError, match="ae = 6"):
        nf.cutter_forces(ae=6.0, **kw)
