"""Engagement from the Z-map equals the analytic engagement for a straight cut into a flat-topped
block (issue 3, Done-when). Analytic immersion (docs/conventions.md §2; Altintas, Manufacturing Automation
ch. 2): up milling φ_st = 0, φ_ex = acos(1 − a_e/R); down milling φ_st = π − acos(1 − a_e/R), φ_ex = π;
slotting 0 … π; axial depth a_p."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape as ns

Cutter = ns.stock.Cutter
R, AE, AP, H, TOP = 5.0, 2.0, 3.0, 0.02, 10.0
STEP = 0.05  # the last move before the query position [mm]


def analytic(mode: str) -> tuple[float, float]:
    if mode == "up":
        return 0.0, math.acos(1 - AE / R)
    if mode == "down":
        return math.pi - math.acos(1 - AE / R), math.pi
    return 0.0, math.pi


@pytest.mark.parametrize("mode", ["up", "down", "slot"])
@pytest.mark.parametrize("feed", [(1.0, 0.0), (0.6, -0.8)])
def test_immersion_from_zmap_equals_analytic(mode, feed):
    z, tool, tip, f = cut_band(mode, feed)
    im = ns.stock.immersion(z, tool, tip, f)
    st, ex = analytic(mode)
    # pillar model: walls are known to +-h/2 (and one cell more along a slanted feed): an edge angle
    # moves by (h/2)/(R sin phi) where the wall crosses the circle and by up to sqrt(h/R) where it is
    # tangent (phi = 0, pi), plus L/(2R) of the last move at the rear
    h = H * (1.0 if feed[1] == 0.0 else math.sqrt(2.0))
    tol_tangent = 1.1 * math.sqrt(h / R) + STEP / (2 * R)
    tol_cross = h / (R * math.sin(math.acos(1 - AE / R))) + 1e-3
    tol_st = tol_tangent if mode in ("up", "slot") else tol_cross
    tol_ex = tol_tangent if mode in ("down", "slot") else tol_cross
    assert im.engaged
    assert abs(im.phi_st - st) < tol_st
    assert abs(im.phi_ex - ex) < tol_ex
    assert im.axial_depth == pytest.approx(AP, abs=1e-9)
    assert im.radial_depth == pytest.approx(2 * R if mode == "slot" else AE, rel=0.02)


def cut_band(mode: str, feed, step: float = STEP):
    """A flat end mill enters a flat-topped block (top z = 10) along `feed` and stops one step short
    of the query point `tip`: the Z-map as it is before the move that ends there. For up milling the
    material is y_c >= R - a_e (Y_c = Z x X_c, the left of the feed), for down milling
    y_c <= -(R - a_e): earlier, deeper passes clear the other side."""
    f = np.array([feed[0], feed[1], 0.0]) / math.hypot(*feed)
    left = np.array([-f[1], f[0], 0.0])
    tool = Cutter.flat_end(2 * R, 2, 0.5236)
    z = ns.stock.ZMap(0.0, 60.0, 0.0, 60.0, H, TOP, 0.0)
    tip = np.array([30.0, 30.0, TOP - AP])
    if mode != "slot":
        # free side: -Y_c for up milling, +Y_c for down milling. A pass at y_c = o clears
        # [o - R, o + R]: o = -a_e leaves the wall at R - a_e (up), o = +a_e at -(R - a_e) (down)
        side = -1.0 if mode == "up" else 1.0
        o = side * AE
        ns.stock.sweep_line(z, tool, tip - 45 * f + o * left + [0, 0, -1.0], tip + 45 * f + o * left + [0, 0, -1.0])
        # and everything beyond it on that side
        for k in range(1, 6):
            oo = o + side * 1.5 * R * k
            ns.stock.sweep_line(z, tool, tip - 45 * f + oo * left + [0, 0, -1.0],
                                tip + 45 * f + oo * left + [0, 0, -1.0])
    ns.stock.sweep_line(z, tool, tip - 45 * f, tip - step * f)
    return z, tool, tip, f


def test_engaged_elements_mask_matches_analytic_band():
    # the Z-map before a 0.5 mm move (a block): the crescent of material between the previous and
    # the current cutter circle is L·sin(phi) thick, which the grid resolves away from phi = 0 and pi
    step = 0.5
    z, tool, tip, f = cut_band("up", (1.0, 0.0), step)
    phi = np.linspace(0.0, 2 * math.pi, 360, endpoint=False) + 0.5 * math.pi / 180
    zs = np.array([0.25, 1.0, 2.0, 2.9, 3.1, 5.0])
    mask = ns.stock.engaged_elements(z, tool, tip, f, phi, zs)
    assert mask.shape == (6, 360) and mask.dtype == np.bool_
    st, ex = analytic("up")
    expect = (zs[:, None] < AP) & (phi[None, :] >= st) & (phi[None, :] <= ex)
    # away from the edge angles the mask is exact: at the tangent edge (phi_st = 0) the rear margin
    # L/(2R) of the move plus the wall blur sqrt(h/R); at the crossing edge (h/2)/(R sin phi_ex)
    band_st = step / (2 * R) + 1.1 * math.sqrt(H / R)
    band_ex = H / (R * math.sin(ex)) + 2 * math.pi / 360
    away = (np.abs(phi - st) > band_st) & (np.abs(phi - 2 * math.pi - st) > band_st) & (np.abs(phi - ex) > band_ex)
    assert away.sum() > 300
    np.testing.assert_array_equal(mask[:, away], expect[:, away])
    assert not mask[zs > AP].any()


def test_cutting_frame_and_element_point_follow_design_section_2():
    tool = Cutter.flat_end(10.0, 2, 0.5236)
    xc, yc = ns.stock.cutting_frame((0.0, 3.0, 0.0))
    np.testing.assert_allclose(xc, [0, 1, 0])
    np.testing.assert_allclose(yc, [-1, 0, 0])  # Z x X
    # phi = pi/2 points along the feed, phi = 0 to the left (+Y_c), clockwise seen from the spindle
    np.testing.assert_allclose(ns.stock.element_point(tool, (0, 0, 0), (0, 1, 0), math.pi / 2, 0.0), [0, 5, 0],
                               atol=1e-12)
    np.testing.assert_allclose(ns.stock.element_point(tool, (0, 0, 0), (0, 1, 0), 0.0, 1.0), [-5, 0, 1], atol=1e-12)
