"""Issue 37 item 3: the catalogue effect cyclic_error (a ball-screw's periodic positioning error).

The issue's bundle: 57 × 7 × 3 grid, random order, X with a 4 µm periodic error of 20 mm period
(phase 0.7 rad), 1 µm noise. Controls: the same grid with noise only (seeds outside the family of
bench/discrepancy_cyclic.py, where the naming threshold was checked).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import netshape.discrepancy as nd

from generators import structured_volumetric_bundle


def test_ball_screw_cyclic_error_is_named(tmp_path):
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, extra=[("periodic", "ex", "x", 4e-3, 20.0)]))
    out = d.to_dict()
    assert out["effect"] == "cyclic_error", d.summary()
    p = out["parameters"]
    assert p["axis"] == "X"
    assert abs(p["period_mm"] / 20.0 - 1) < 0.02, p
    assert abs(p["amplitude_mm"] / 4e-3 - 1) < 0.10, p
    assert abs((p["phase_deg"] - math.degrees(0.7) + 180) % 360 - 180) < 5.0, p
    assert d.rms_after < 1.1 * d.noise_estimate
    json.dumps(out)


@pytest.mark.parametrize("seed, order", [(31, "random"), (32, "x")])
def test_controls_name_nothing(tmp_path, seed, order):
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, seed=seed, order=order))
    assert d.effects == [], d.summary()
    assert "cyclic_error" in {c["effect"] for c in d.candidates}


def test_bounds():
    """Amplitude above 0.1 mm is implausible; a period at the edge of what the grid shows is rejected."""
    from netshape.discrepancy.catalogue import EffectFit
    from netshape.discrepancy.volumetric_effects import CyclicError

    c = CyclicError()
    big = EffectFit({"axis": "X", "period_mm": 20.0, "amplitude_mm": 0.2, "phase_deg": 0.0}, None, 4, None)
    assert "amplitude_mm = 0.2 is outside" in c.implausible(None, big)
    ok = EffectFit({"axis": "X", "period_mm": 20.0, "amplitude_mm": 0.004, "phase_deg": 0.0}, None, 4, None)
    b = (np.array([-np.inf, -np.inf, 14.3]), np.array([np.inf, np.inf, 200.0]))
    assert c.implausible(None, ok, [1e-3, 1e-3, 20.0], b) is None
    assert "period_mm = 200" in c.implausible(None, ok, [1e-3, 1e-3, 200.0], b)
