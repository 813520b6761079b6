"""Issue 43 item 1: the tool file's runout and a coefficient file's chip-size effect reach the
deflection model's element chips (`deflection wall`, `model_for_cutter` → predict, compensate and the
job's deflection stage); the job's program forces say that they leave them out.

The reference is the model built by hand with `make_model(chip=RunoutSizeEffect(...))` (the C++ chip
model, checked against flat_end_forces_extended in tests/cpp/force)."""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import pytest

import netshape as ns
from netshape import deflection as d
from netshape.cli import main

TOOL = ('kind = "flat"\ndiameter_mm = 6.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0\n'
        'stick_out_mm = 30.0\nyoungs_modulus_MPa = 600000.0\n')
K = dict(Ktc_N_per_mm2=900.0, Krc_N_per_mm2=270.0, Kac_N_per_mm2=150.0, Kte_N_per_mm=16.0,
         Kre_N_per_mm=20.0, Kae_N_per_mm=10.0)
CUT = ["--rpm", "8000", "--feed-per-tooth", "0.05", "--ap", "4", "--ae", "0.5", "--mode", "down"]


def _wall(tmp_path, name, extra):
    out = tmp_path / f"{name}.json"
    assert main(["deflection", "wall", *extra, *CUT, "--json", str(out)]) == 0
    return json.loads(out.read_text())["profile"]["error_mm"]


def _by_hand(chip=None):
    m = d.make_model(diameter=6.0, flutes=3, helix_deg=30.0, stick_out=30.0, youngs_modulus=600000.0,
                     feed_per_tooth=0.05, ap=4.0, ae=0.5, mode="down",
                     coefficients="Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10", chip=chip)
    return d.steady_wall(m, "down")["profile"]["error_mm"]


def test_tool_runout_reaches_the_wall(tmp_path):
    (tmp_path / "plain.toml").write_text(TOOL)
    (tmp_path / "runout.toml").write_text(TOOL + "runout_rho_mm = 0.01\nrunout_lambda_deg = 30.0\n")
    coeff = ["--coefficients", "Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10"]
    plain = _wall(tmp_path, "plain", ["--tool", str(tmp_path / "plain.toml"), *coeff])
    got = _wall(tmp_path, "runout", ["--tool", str(tmp_path / "runout.toml"), *coeff])
    want = _by_hand(ns.force.RunoutSizeEffect(runout_rho=0.01, runout_lambda=math.radians(30.0)))
    assert got == pytest.approx(want, rel=1e-9, abs=1e-12)
    assert max(abs(a - b) for a, b in zip(got, plain)) > 0.05 * max(abs(b) for b in plain)
    # model_for_cutter (the path prediction, compensation and the job) carries it too
    c = ns.cutter.load_cutter(tmp_path / "runout.toml")
    m = d.model_for_cutter(c, feed_per_tooth=0.05, coefficients="cho_suh_example")
    assert (m.chip.runout_rho, m.chip.runout_lambda) == (0.01, pytest.approx(math.radians(30.0)))


def test_coefficient_file_written_by_diagnose_is_read(tmp_path):
    """The coefficient file `netshape diagnose --update` writes for a size effect is what `deflection
    wall --coefficients FILE.toml` reads: the wall of that chip exponent and reference chip."""
    from netshape.discrepancy.update_tool import apply_to_coefficients

    text = "".join(f"{k} = {v}\n" for k, v in K.items()) + "reference_chip_mm = 0.04\n"
    diag = {"kind": "cutting_force",
            "effects": [{"effect": "size_effect", "parameters": {"chip_exponent": 0.7}}]}
    (tmp_path / "new.toml").write_text(apply_to_coefficients(diag, text, source="forces/"))
    (tmp_path / "tool.toml").write_text(TOOL)
    got = _wall(tmp_path, "sized", ["--tool", str(tmp_path / "tool.toml"),
                                    "--coefficients", str(tmp_path / "new.toml")])
    want = _by_hand(ns.force.RunoutSizeEffect(chip_exponent=0.7, reference_chip=0.04))
    assert got == pytest.approx(want, rel=1e-9, abs=1e-12)
    assert max(abs(a - b) for a, b in zip(got, _by_hand())) > 0.05 * max(abs(b) for b in _by_hand())


@pytest.mark.parametrize("bad, field", [
    ("chip_exponent = 3.0\n", "chip_exponent"),
    ("chip_exponent = 0.8\nreference_chip_mm = 0.0\n", "reference_chip_mm"),
    ("chip_size = 0.8\n", "chip_size")])
def test_bad_coefficient_file(tmp_path, capsys, bad, field):
    (tmp_path / "k.toml").write_text("".join(f"{k} = {v}\n" for k, v in K.items()) + bad)
    (tmp_path / "tool.toml").write_text(TOOL)
    rc = main(["deflection", "wall", "--tool", str(tmp_path / "tool.toml"), "--coefficients",
               str(tmp_path / "k.toml"), *CUT])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and field in err and len(err.splitlines()) == 1, err
    (tmp_path / "k.toml").write_text("Ktc_N_per_mm2 = 900.0\n")
    assert main(["deflection", "wall", "--tool", str(tmp_path / "tool.toml"), "--coefficients",
                 str(tmp_path / "k.toml"), *CUT]) == 2
    assert "Krc_N_per_mm2: missing" in capsys.readouterr().err


def test_job_coefficients_with_a_size_effect():
    from netshape.deflection.chip import SizeEffectCoefficients
    from netshape.job.spec import JobError
    from netshape.job.spec import _coefficients
    from netshape.job.stages import coefficients_for

    table = {"Ktc_N_mm2": 900.0, "Kte_N_mm": 16.0, "chip_exponent": 0.8, "reference_chip_mm": 0.05}
    assert _coefficients("job.toml", table) == table
    with pytest.raises(JobError, match=r"coefficients\.chip_exponent = 2\.5"):
        _coefficients("job.toml", dict(table, chip_exponent=2.5))
    cutter = ns.cutter.cutter_from_dict(_tool_dict())
    job = SimpleNamespace(coefficients=table, tool=dict(_tool_dict(), runout_rho_mm=0.01))
    k = coefficients_for(job, cutter)
    assert isinstance(k, SizeEffectCoefficients) and (k.chip_exponent, k.reference_chip) == (0.8, 0.05)
    assert k.coefficients.ktc == 900.0 and k.coefficients.krc == 0.0


def _tool_dict():
    return {"kind": "flat", "diameter_mm": 6.0, "flutes": 3, "helix_deg": 30.0, "flute_length_mm": 20.0,
            "stick_out_mm": 30.0}
