"""Issue 37 item 5: identifiability. Before choosing, the workflow checks whether the bundle can tell
the candidates apart and reports `ambiguous` (the effects, the reason, the measurement that would
separate them): covariates that move together (|corr| > 0.95) or candidates whose BICs differ by < 2.
"""

from __future__ import annotations

import json

import numpy as np

import netshape.discrepancy as nd
from netshape.discrepancy.workflow import identifiability

from generators import structured_volumetric_bundle


def test_time_following_position_is_ambiguous(tmp_path):
    """The issue's case: time ∝ x (X slowest), ez drifting in time: a time effect and a position
    effect cannot be told apart; the report says so and what to do."""
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, extra=[("trend", "ez", "t", 1e-6)], order="x-slowest"))
    out = d.to_dict()
    amb = [a for a in out["ambiguous"] if "thermal_drift" in a["effects"]]
    assert amb, out["ambiguous"]
    assert {"squareness", "scale_error"} & {e for a in amb for e in a["effects"]}
    assert all("corr" in a["reason"] and "random order" in a["measure"] for a in amb)
    assert len({tuple(a["effects"]) for a in out["ambiguous"]}) == len(out["ambiguous"])
    assert "ambiguous" in d.summary()
    json.dumps(out)


def test_random_order_is_not_ambiguous(tmp_path):
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, extra=[("periodic", "ex", "x", 4e-3, 20.0)]))
    assert d.effect == "cyclic_error" and d.ambiguous == []
    d = nd.diagnose(structured_volumetric_bundle(tmp_path / "c", seed=31))
    assert d.effects == [] and d.ambiguous == []


def test_equal_bic_is_ambiguous():
    """Two qualifying candidates within ΔBIC 2 of each other: named together, with the measurement
    that varies their covariates independently."""

    class E:
        def __init__(self, cov):
            self.covariate = cov

    class P:
        pass

    cat = {"a": E("time"), "b": E("tool_length")}
    round_ = [{"effect": "a", "bic": -100.0}, {"effect": "b", "bic": -99.0}]
    (amb,) = identifiability(P(), cat, round_, 0.0)
    assert amb["effects"] == ["a", "b"] and "ΔBIC = 1.00" in amb["reason"] and "random order" in amb["measure"]
    assert identifiability(P(), cat, [{"effect": "a", "bic": -100.0}, {"effect": "b", "bic": -90.0}], 0.0) == []
    assert np.isfinite(round_[0]["bic"])
