"""The wall-error workflow names hidden effects and recovers their parameters.

Bundles from generators.py: a 6 mm, 3-flute, 30° carbide end mill with 30 mm stick-out, three steady
cuts (down ae 0.5 mm c 0.15 mm, down 1.0/0.2, up 0.5/0.25; ap 4 mm), the wall measured over 2 mm of
feed every 10 µm at z = 0.5, 1.5, 2.5, 3.5 mm (x_mm,z_mm,error_mm) or at z = 2 mm (x_mm,error_mm),
Gaussian noise σ = 1 µm. The model's wall error is netshape.deflection's; the hidden holder spring is
written out in the generator (rigid translation F/k of the force at the generating instant) and the
hidden runout as exact circles of radius R + ρ·cos(λ − j·2π/N) placed by the flute angles, the wall
their envelope (an independent evaluation of the workflow's parabolic-arc model).
"""

from __future__ import annotations

import json

import pytest

import netshape.discrepancy as nd
from netshape.cli import main

from generators import WALL_TOOL, replace_once, wall_bundle

NOISE = 1e-3  # mm
K_TRUE = 10.0  # N/µm
RUNOUT_TRUE = (0.004, 40.0)  # mm, deg


def _check(d, expected):
    for name, params in expected.items():
        got = next(e["parameters"] for e in d.effects if e["effect"] == name)
        for k, (v, tol) in params.items():
            assert abs(got[k] - v) < tol, (name, k, got[k], v)


@pytest.mark.parametrize("form", ["xz", "x"])
@pytest.mark.parametrize(
    "hidden, effect, expected",
    [
        ({"holder_stiffness": K_TRUE}, "holder_compliance", {"stiffness_N_per_um": (K_TRUE, 0.2)}),
        (
            {"runout": RUNOUT_TRUE},
            "runout",
            {"rho_mm": (RUNOUT_TRUE[0], 2.5e-4), "lambda_deg": (RUNOUT_TRUE[1], 3.0)},
        ),
    ],
    ids=["holder_compliance", "runout"],
)
def test_hidden_wall_effect_is_named_and_recovered(tmp_path, hidden, effect, expected, form):
    """Tolerances: stiffness 0.2 N/µm (2 %), ρ 0.25 µm, λ 3°; rms after within 10 % of the noise."""
    d = nd.diagnose(wall_bundle(tmp_path, form=form, **hidden))
    assert d.effect == effect and len(d.effects) == 1
    _check(d, {effect: expected})
    assert d.rms_before > 2 * NOISE
    assert d.rms_after < 1.1 * NOISE
    assert abs(d.noise_estimate - NOISE) < 0.1 * NOISE
    loc = d.localisation
    if effect == "holder_compliance":  # the residual follows (−) the force at the generating instant
        assert loc["correlation"]["error~normal_force_N"] < -0.85
    else:  # runout shows once per revolution along x
        assert max(loc["per_revolution_amplitude_mm"]) > NOISE


def test_holder_and_runout_together(tmp_path):
    """Two hidden effects: both named (the larger, holder, first) and both recovered."""
    d = nd.diagnose(wall_bundle(tmp_path, holder_stiffness=K_TRUE, runout=RUNOUT_TRUE))
    assert [e["effect"] for e in d.effects] == ["holder_compliance", "runout"]
    _check(
        d,
        {
            "holder_compliance": {"stiffness_N_per_um": (K_TRUE, 0.2)},
            "runout": {"rho_mm": (RUNOUT_TRUE[0], 2.5e-4), "lambda_deg": (RUNOUT_TRUE[1], 3.0)},
        },
    )
    assert d.rms_after < 1.1 * NOISE


@pytest.mark.parametrize("form", ["xz", "x"])
def test_control_wall_bundle_finds_nothing(tmp_path, form):
    d = nd.diagnose(wall_bundle(tmp_path, form=form))
    assert d.effect is None and d.effects == []
    assert "no missing effect found" in d.summary()
    assert {c["effect"] for c in d.candidates} == {"holder_compliance", "runout"}


def test_two_flutes_report_rho_cos_lambda(tmp_path):
    """With 2 flutes r₁ = −r₀: only ρ·cos λ is identifiable, reported with λ = 0 or 180°."""
    d = nd.diagnose(wall_bundle(tmp_path, runout=(0.004, 60.0), form="x", tool=dict(WALL_TOOL, flutes=2)))
    assert d.effect == "runout"
    assert d.parameters["lambda_deg"] in (0.0, 180.0)
    assert abs(d.parameters["rho_mm"] - 0.002) < 2.5e-4  # ρ·|cos 60°|


def test_cli_wall_bundle(tmp_path, capsys):
    b = wall_bundle(tmp_path / "b", holder_stiffness=K_TRUE, form="x")
    out = tmp_path / "d.json"
    assert main(["diagnose", str(b), "--json", str(out), "--report", str(tmp_path / "rep")]) == 0
    data = json.loads(out.read_text())
    assert data["kind"] == "wall_error" and data["effect"] == "holder_compliance"
    assert abs(data["parameters"]["stiffness_N_per_um"] - K_TRUE) < 0.2
    assert (tmp_path / "rep" / "holder_compliance.png").stat().st_size > 1000
    assert (tmp_path / "rep" / "index.html").exists()


@pytest.mark.parametrize(
    "edit, words",
    [
        (("manifest.toml", "stick_out_mm = 30.0\n", ""), ["manifest.toml", "[tool]", "stick_out_mm"]),
        (("manifest.toml", "flutes = 3", "flutes = 0"), ["manifest.toml", "[tool]", "flutes"]),
        (("manifest.toml", "[tool]", '[tool]\ntype = "ball"'), ["manifest.toml", "[tool]", "ball"]),
        (("manifest.toml", 'coefficients = "Ktc=900', 'coefficients = "Kxx=900'), ["manifest.toml", "[model]", "Kxx"]),
        (("manifest.toml", 'load = "distributed"', 'load = "spread"'), ["manifest.toml", "[model]", "load"]),
        (("manifest.toml", 'mode = "down"', 'mode = "slot"'), ["manifest.toml", "experiment", "side"]),
        (("manifest.toml", "axial_depth_mm = 4.0", "axial_depth_mm = 40.0"), ["manifest.toml", "experiment", "stick_out"]),
        (("manifest.toml", "radial_depth_mm = 0.5", "radial_depth_mm = 9.0"), ["manifest.toml", "experiment", "ae"]),
        (("manifest.toml", "feed_per_tooth_mm = 0.15\n", ""), ["manifest.toml", "experiment", "feed_per_tooth_mm"]),
        (("manifest.toml", 'mode = "down"', 'mode = "down"\nz_mm = 9.0'), ["manifest.toml", "z_mm", "9.0"]),
        (("wall1.csv", "x_mm,error_mm", "x_mm,err_mm"), ["wall1.csv", "err_mm"]),
        (("wall1.csv", "x_mm,error_mm\n0,", "x_mm,error_mm\nnan,"), ["wall1.csv", "line 2", "x_mm"]),
    ],
)
def test_malformed_wall_bundle(tmp_path, edit, words):
    b = wall_bundle(tmp_path / "b", form="x", length=0.2)
    replace_once(b / edit[0], edit[1], edit[2])
    with pytest.raises(ValueError) as exc:
        nd.load_bundle(b)
    for w in words:
        assert w in str(exc.value), (w, str(exc.value))


def test_wall_csv_z_outside_the_cut(tmp_path):
    b = wall_bundle(tmp_path / "b", form="xz", length=0.2, z_levels=(1.0, 2.0))
    replace_once(b / "wall2.csv", ",2,", ",7.5,")
    with pytest.raises(ValueError, match=r"wall2\.csv: line \d+, column 'z_mm': 7\.5"):
        nd.load_bundle(b)
    replace_once(b / "wall2.csv", ",7.5,", ",2,")
    (b / "wall3.csv").unlink()
    with pytest.raises(FileNotFoundError, match="wall3.csv"):
        nd.load_bundle(b)
