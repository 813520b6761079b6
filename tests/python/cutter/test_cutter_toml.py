"""Cutter TOML: round trip, defaults, and bad input naming key and value."""

from __future__ import annotations

import math

import pytest

import netshape as ns

GOOD = """\
kind = "bull"
diameter_mm = 10.0
corner_radius_mm = 1.0
flutes = 3
helix_deg = 30.0
flute_length_mm = 22.0
stick_out_mm = 40.0
youngs_modulus_MPa = 600000.0
"""


def test_load_save_round_trip(tmp_path):
    p = tmp_path / "tool.toml"
    p.write_text(GOOD)
    c = ns.cutter.load_cutter(p)
    assert c.kind == ns.cutter.CutterKind.bull
    assert c.radius == 5.0 and c.corner_radius == 1.0 and c.flutes == 3
    assert c.helix == pytest.approx(math.radians(30))
    # Cho & Suh §5: D = 25 mm, 60° helix, at z = 1.25 mm the lag z·tanβ/R is 9.92°
    d25 = ns.cutter.Cutter.flat_end(25.0, 2, math.radians(60))
    assert math.degrees(1.25 * d25.helix_lag()) == pytest.approx(9.92, abs=0.005)
    out = tmp_path / "out.toml"
    ns.cutter.save_cutter(c, out)
    c2 = ns.cutter.load_cutter(out)
    assert ns.cutter.cutter_to_dict(c2) == ns.cutter.cutter_to_dict(c)
    assert "Cutter(bull, diameter=10 mm" in repr(c2)


def test_defaults_for_flat_and_ball(tmp_path):
    p = tmp_path / "ball.toml"
    p.write_text(GOOD.replace('"bull"', '"ball"').replace("corner_radius_mm = 1.0\n", "")
                 .replace("youngs_modulus_MPa = 600000.0\n", ""))
    c = ns.cutter.load_cutter(p)
    assert c.corner_radius == c.radius == 5.0
    assert c.youngs_modulus == 600e3


@pytest.mark.parametrize(
    "edit, needle",
    [
        (("flutes = 3", "flutes = 3\ncolour = \"red\""), "colour = 'red': unknown key"),
        (("flutes = 3", "flutes = 2.5"), "flutes = 2.5"),
        (("flutes = 3", "flutes = 0"), "flutes = 0"),
        (("diameter_mm = 10.0", "diameter_mm = -10.0"), "cutter.radius = -5"),
        (("diameter_mm = 10.0", "diameter_mm = nan"), "diameter_mm = nan"),
        (("diameter_mm = 10.0", "diameter_mm = \"10\""), "diameter_mm = '10'"),
        (('"bull"', '"drill"'), "drill"),
        (("corner_radius_mm = 1.0", "corner_radius_mm = 6.0"), "cutter.corner_radius = 6"),
        (("stick_out_mm = 40.0", "stick_out_mm = 10.0"), "cutter.stick_out = 10"),
        (("stick_out_mm = 40.0\n", ""), "stick_out_mm: missing"),
        (("helix_deg = 30.0", "helix_deg = 90.0"), "cutter.helix"),
        (("kind", "kind = = "), "not valid TOML"),
    ],
)
def test_bad_values_name_key_and_value(tmp_path, edit, needle):
    p = tmp_path / "bad.toml"
    p.write_text(GOOD.replace(*edit, 1))
    with pytest.raises(ValueError) as err:
        ns.cutter.load_cutter(p)
    assert needle in str(err.value)
    assert str(p) in str(err.value)
