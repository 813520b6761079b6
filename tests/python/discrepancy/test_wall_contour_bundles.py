"""Wall-error bundles along a program's contour (program, tool.toml, stock.toml as `netshape deflection
predict` takes them): the workflow names hidden effects and recovers their parameters.

Bundles from generators.py (wall_contour_bundle): a 6 mm, 3-flute, 30° carbide end mill with 30 mm
stick-out, 8000 rpm, cutting 4 mm deep along a stock face — a down-milling cut along +X (ae 1 mm,
c 0.2 mm) and an up-milling cut back along −X (ae 0.5 mm, c 0.15 mm); the wall measured every 10 µm
from 12 to 16 mm along each contour at z = 0.4 … 3.6 mm (x_mm,z_mm,error_mm) or at the middle of the cut
(x_mm,error_mm); Gaussian noise σ = 1 µm. The base model is netshape.deflection.predict_path's; the
hidden holder spring is the rigid translation F·n/k and the hidden runout exact circles of radius
R + ρ·cos(λ − j·2π/N) placed by the flute angles, the wall their envelope (an independent evaluation of
the workflow's parabolic-arc model).
"""

from __future__ import annotations

import json

import pytest

import netshape.discrepancy as nd
from netshape.cli import main

from generators import replace_once, wall_contour_bundle

NOISE = 1e-3  # mm
K_TRUE = 10.0  # N/µm
RUNOUT_TRUE = (0.004, 40.0)  # mm, deg
TOL = {"stiffness_N_per_um": 0.2, "rho_mm": 2.5e-4, "lambda_deg": 3.0}


def _params(d, name):
    return next(e["parameters"] for e in d.effects if e["effect"] == name)


@pytest.mark.parametrize("form", ["xz", "x"])
@pytest.mark.parametrize(
    "hidden, names",
    [
        ({"holder_stiffness": K_TRUE}, ["holder_compliance"]),
        ({"runout": RUNOUT_TRUE}, ["runout"]),
        ({"holder_stiffness": K_TRUE, "runout": RUNOUT_TRUE}, ["holder_compliance", "runout"]),
    ],
    ids=["holder_compliance", "runout", "both"],
)
def test_hidden_effects_along_a_contour(tmp_path, hidden, names, form):
    """Tolerances: stiffness 0.2 N/µm (2 %), ρ 0.25 µm, λ 3°; rms after within 10 % of the noise."""
    d = nd.diagnose(wall_contour_bundle(tmp_path, form=form, **hidden))
    assert [e["effect"] for e in d.effects] == names
    if "holder_compliance" in names:
        assert abs(_params(d, "holder_compliance")["stiffness_N_per_um"] - K_TRUE) < TOL["stiffness_N_per_um"]
    if "runout" in names:
        p = _params(d, "runout")
        assert abs(p["rho_mm"] - RUNOUT_TRUE[0]) < TOL["rho_mm"]
        assert abs(p["lambda_deg"] - RUNOUT_TRUE[1]) < TOL["lambda_deg"]
    assert d.rms_before > 2 * NOISE
    assert d.rms_after < 1.1 * NOISE


@pytest.mark.parametrize("form", ["xz", "x"])
def test_control_contour_bundle_finds_nothing(tmp_path, form):
    d = nd.diagnose(wall_contour_bundle(tmp_path, form=form))
    assert d.effect is None and d.effects == []
    assert abs(d.noise_estimate - NOISE) < 0.1 * NOISE


def test_contour_bundle_loads_as_contour_experiments(tmp_path):
    b = nd.load_bundle(wall_contour_bundle(tmp_path, form="x"))
    assert b.kind == "wall_error" and len(b.experiments) == 2
    e = b.experiments[0]
    assert isinstance(e, nd.WallContourExperiment)
    assert e.program.endswith("contour1.ngc") and e.spindle_rpm == 8000.0 and e.side == "auto"
    assert b.tool["flutes"] == 3 and abs(b.tool["helix_deg"] - 30.0) < 1e-9


def test_cli_contour_bundle(tmp_path):
    b = wall_contour_bundle(tmp_path / "b", holder_stiffness=K_TRUE, form="x")
    out = tmp_path / "d.json"
    assert main(["diagnose", str(b), "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    assert data["kind"] == "wall_error" and data["effect"] == "holder_compliance"
    assert abs(data["parameters"]["stiffness_N_per_um"] - K_TRUE) < TOL["stiffness_N_per_um"]


@pytest.mark.parametrize(
    "edit, words, exc",
    [
        (("manifest.toml", 'program = "contour1.ngc"', 'program = "gone.ngc"'), ["gone.ngc", "program"],
         FileNotFoundError),
        (("manifest.toml", 'stock = "stock.toml"', "stock = 3"), ["manifest.toml", "experiment", "stock"], ValueError),
        (("manifest.toml", "spindle_rpm = 8000.0\n", "spindle_rpm = -1.0\n"), ["manifest.toml", "spindle_rpm"],
         ValueError),
        (("manifest.toml", 'tool = "tool.toml"', 'tool = "tool.toml"\nmode = "down"'), ["manifest.toml", "mode"],
         ValueError),
        (("manifest.toml", 'stock = "stock.toml"', 'stock = "stock.toml"\nside = "inside"'),
         ["manifest.toml", "side", "inside"], ValueError),
        (("tool.toml", 'kind = "flat"', 'kind = "ball"'), ["experiment", "flat end mill"], ValueError),
        (("contour1.csv", "x_mm,error_mm", "s_mm,error_mm"), ["contour1.csv", "s_mm"], ValueError),
    ],
)
def test_malformed_contour_bundle(tmp_path, edit, words, exc):
    b = wall_contour_bundle(tmp_path / "b", form="x", s_range=(12.0, 12.2))
    replace_once(b / edit[0], edit[1], edit[2])
    with pytest.raises(exc) as info:
        nd.load_bundle(b)
    for w in words:
        assert w in str(info.value), (w, str(info.value))


def test_contour_points_where_no_wall_is_cut(tmp_path):
    """A measured position beyond the contour's end, or where the tool is still outside the stock,
    is refused naming the CSV line; a height above the cut likewise."""
    b = wall_contour_bundle(tmp_path / "b", form="xz", s_range=(12.0, 12.2), z_levels=(2.0,))
    csv = b / "contour1.csv"
    good = csv.read_text()
    replace_once(csv, "\n12,", "\n99,")
    with pytest.raises(ValueError, match=r"contour1\.csv: line 2, column 'x_mm': 99.*beyond the contour"):
        nd.diagnose(b)
    csv.write_text(good.replace("\n12,", "\n0.5,", 1))
    with pytest.raises(ValueError, match=r"contour1\.csv: line 2, column 'x_mm': 0\.5.*does not cut"):
        nd.diagnose(b)
    csv.write_text(good.replace(",2,", ",6,", 1))
    with pytest.raises(ValueError, match=r"contour1\.csv: line 2: z_mm = 6.*above the cut"):
        nd.diagnose(b)
