"""The geometry functions take a netshape Cutter whole (C++ receives the caller's object, not a cutter
rebuilt from its kind and radii); the (kind, radius[, corner]) tuple is a shorthand for the same shape."""

from __future__ import annotations

import numpy as np
import pytest

import netshape as ns

g = ns.geometry


def test_cutter_object_and_tuple_give_the_same_cl():
    """Bull nose: tip = CC + r n + (R − r) e − r a (docs/geometry.md), e the unit in-plane part of n."""
    c = ns.cutter.Cutter.bull_nose(10.0, 1.5, 3, 0.5)
    c.flute_length, c.stick_out = 12.0, 30.0  # lengths of the caller's tool: not replaced
    n = np.array([[0.6, 0.0, 0.8]])
    cc = np.array([[1.0, 2.0, 3.0]])
    cl = g.cc_to_cl(c, cc, n)
    e = np.array([1.0, 0.0, 0.0])
    expected = cc[0] + 1.5 * n[0] + (5.0 - 1.5) * e - 1.5 * np.array([0.0, 0.0, 1.0])
    np.testing.assert_allclose(cl[0], expected, atol=1e-12)
    np.testing.assert_array_equal(cl, g.cc_to_cl(("bull", 5.0, 1.5), cc, n))
    assert g.cutter_signed_distance(c, cl[0], (0, 0, 1), cc)[0] == pytest.approx(0.0, abs=1e-12)


def test_an_inconsistent_cutter_is_refused_naming_the_field():
    c = ns.cutter.Cutter.bull_nose(10.0, 1.5, 3, 0.5)
    c.corner_radius = 6.0  # larger than the radius
    with pytest.raises(ValueError, match="corner_radius"):
        g.cc_to_cl(c, [[0, 0, 0]], [[0, 0, 1]])
    with pytest.raises(ValueError, match="cutter = 'drill'"):
        g.cc_to_cl("drill", [[0, 0, 0]], [[0, 0, 1]])
