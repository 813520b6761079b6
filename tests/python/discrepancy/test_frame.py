"""Issue 37 item 3: the registered measurement frame (ISO 230-1: X primary, Y secondary reference).

Bundles from generators.structured_volumetric_bundle (57 × 7 × 3 grid, 1 µm noise, random order):
the known model plus linear cross terms. The frame is fitted with the base model every time; its
rotation is the one that makes X's straightness slopes (ey, ez against x) and Y's slope in z (ez
against y) zero, so the other three cross slopes are squareness.
"""

from __future__ import annotations

import json

import pytest

import netshape.discrepancy as nd

from generators import structured_volumetric_bundle


def test_squareness_in_a_frame_aligned_to_y(tmp_path):
    """ey = 3·10⁻⁵·x: X and Y 30 µrad out of square, measured in a frame aligned to Y. Before: named
    thermal_drift. Now: the frame turns 30 µrad about Z and the squareness is EC0Y = −30 µrad."""
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, extra=[("trend", "ey", "x", 3e-5)]))
    out = d.to_dict()
    assert out["effect"] == "squareness", d.summary()
    assert abs(out["parameters"]["EC0Y_urad"] + 30.0) < 1.5
    assert abs(out["parameters"]["EB0Z_urad"]) < 1.5 and abs(out["parameters"]["EA0Z_urad"]) < 1.5
    assert [e["effect"] for e in out["effects"]] == ["squareness"]
    f = out["frame"]
    assert set(f) == {"rotation_urad", "translation_mm"} and len(f["rotation_urad"]) == len(f["translation_mm"]) == 3
    assert abs(f["rotation_urad"][2] - 30.0) < 1.5
    assert "frame (ISO 230-1" in d.summary()
    json.dumps(out)


def test_rigidly_rotated_measurement_names_nothing(tmp_path):
    """The data seen in a frame turned 50 µrad about Z and −20 µrad about X (e += ω × p): the frame
    takes all of it, no effect is named, the rotation is recovered within 1 µrad."""
    wz, wx = 5e-5, -2e-5
    extra = [("trend", "ey", "x", wz), ("trend", "ex", "y", -wz), ("trend", "ez", "y", wx), ("trend", "ey", "z", -wx)]
    d = nd.diagnose(structured_volumetric_bundle(tmp_path, extra=extra, seed=4))
    assert d.effects == [], d.summary()
    r = d.frame["rotation_urad"]
    assert abs(r[2] - 50.0) < 1.0 and abs(r[0] + 20.0) < 1.0 and abs(r[1]) < 1.0, r
    assert abs(d.rms_after - 1e-3) < 0.1e-3


@pytest.mark.parametrize("kind", ["force"])
def test_other_kinds_have_no_frame(tmp_path, kind):
    from generators import force_bundle

    assert nd.diagnose(force_bundle(tmp_path)).to_dict()["frame"] is None
