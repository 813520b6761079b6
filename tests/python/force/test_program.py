"""Force along a program on a Z-map stock (needs the stock and toolpath areas)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.force as nf
from netshape import stock as st
from netshape import toolpath as tp

K = nf.LinearEdgeCoefficients(ktc=958.8, krc=251.1, kac=146.4, kte=15.8, kre=19.4, kae=18.2)


def test_zmap_engagement_equals_analytic_for_straight_slot():
    """A straight slot into a flat-topped block: once the cutter is fully in, the forces computed
    with the Z-map engagement equal those of the analytic slot window (φ 0…π, a_p = block top)."""
    cutter = st.Cutter.flat_end(10.0, 2, math.radians(30))
    block = st.ZMap(0.0, 40.0, -10.0, 10.0, 0.1, 3.0, -5.0)
    rpm, c = 6000.0, 0.1
    feed = c * 2 * rpm / 60.0  # mm/s
    prog = tp.parse_gcode(f"G21 G90 G0 X-8 Y0 Z0\nS{rpm:g} M3\nG1 X25 F{feed * 60:g}\n")
    r = nf.simulate_program(block, cutter, prog, K, step=0.5, samples_per_revolution=180, bins=720,
                            disk_height=0.05)
    steady = r.positions[:, 0] > 12
    assert steady.sum() > 5
    e = nf.AngularEngagement.from_mode(nf.MillingMode.slot, 5.0, 10.0)
    m = nf.FlatEndModel(radius=5, flutes=2, helix=math.radians(30), axial_depth=3.0, feed_per_tooth=c,
                        engagement=e, linear_edge=K, disk_height=0.05)
    F = nf.flat_end_forces(m, nf.rotation_angles(180))
    np.testing.assert_allclose(r.mean[steady], np.tile(F.mean(axis=0), (steady.sum(), 1)), rtol=0.02, atol=1.0)
    np.testing.assert_allclose(r.peak_resultant[steady], np.linalg.norm(F, axis=1).max(), rtol=0.02)
    # entering the block the load grows from zero
    assert r.peak_resultant[0] < 0.5 * r.peak_resultant[steady].mean()
    assert r.removed_volume > 0


def test_second_pass_over_cut_stock_sees_less_material():
    """The stock is updated as the cutter moves: a second identical pass cuts air."""
    cutter = st.Cutter.flat_end(10.0, 2, math.radians(30))
    block = st.ZMap(0.0, 30.0, -10.0, 10.0, 0.2, 2.0, -5.0)
    prog = tp.parse_gcode("G21 G90 G0 X-8 Y0 Z0\nS6000 M3\nG1 X20 F1200\nG1 X-8\n")
    r = nf.simulate_program(block, cutter, prog, K, step=1.0)
    first = r.block == r.block.min()
    second = r.block == r.block.max()
    assert r.peak_resultant[first].max() > 100
    assert r.peak_resultant[second].max() < 0.05 * r.peak_resultant[first].max()
    with pytest.raises(ValueError, match="coefficients"):
        nf.simulate_program(block, cutter, prog, "Ktc=1")
    with pytest.raises(ValueError, match="step"):
        nf.simulate_program(block, cutter, prog, K, step=0.0)
