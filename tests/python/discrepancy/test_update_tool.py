"""netshape.discrepancy.update_tool: a diagnosis written into the tool TOML and the coefficient TOML,
lossless for everything it does not change, with comments naming the diagnosis and the time."""

from __future__ import annotations

import datetime as dt
import tomllib

import pytest

from netshape.cutter import cutter_from_dict
from netshape.discrepancy.update_tool import apply_to_coefficients, apply_to_tool

NOW = dt.datetime(2026, 11, 28, 14, 5, tzinfo=dt.timezone.utc)
TOOL = """\
# finishing end mill
kind = "flat"   # flat end
diameter_mm = 6.0
flutes = 3
helix_deg = 35.0
flute_length_mm = 16.0
stick_out_mm = 30.0

youngs_modulus_MPa = 600000.0
"""
HOLDER = {"kind": "wall_error", "effects": [
    {"effect": "holder_compliance", "parameters": {"stiffness_N_per_um": 20.0, "compliance_um_per_N": 0.05}}]}
RUNOUT = {"kind": "wall_error", "effects": [
    {"effect": "runout", "parameters": {"rho_mm": 0.004, "lambda_deg": 40.0}}]}
FORCE = {"kind": "cutting_force", "effects": [
    {"effect": "edge_forces", "parameters": {"Kte_N_per_mm": 30.0, "Kre_N_per_mm": 25.0, "Kae_N_per_mm": 4.0}},
    {"effect": "size_effect", "parameters": {"chip_exponent": 0.8}},
    {"effect": "runout", "parameters": {"rho_mm": 0.01, "lambda_deg": 0.0}}]}
COEFFS = """\
# steel, calibrated 2026-10
Ktc_N_per_mm2 = 2000.0
Krc_N_per_mm2 = 800.0
Kac_N_per_mm2 = 300.0
Kte_N_per_mm = 40.0
Kre_N_per_mm = 30.0
Kae_N_per_mm = 5.0
reference_chip_mm = 0.02
"""


def _unchanged(before: str, after: str):
    """Every line of ``before`` is in ``after`` verbatim, or changed only after its ``key =``."""
    return [ln for ln in before.splitlines() if ln not in after.splitlines()]


def test_holder_compliance_added_to_a_tool_file_lossless():
    out = apply_to_tool(HOLDER, TOOL, source="walls/", now=NOW)
    assert out.startswith(TOOL.rstrip("\n"))  # every old line kept, in order
    assert "# holder_compliance: added by netshape diagnose of walls/, 2026-11-28 14:05 UTC" in out
    doc = tomllib.loads(out)
    assert doc["holder_compliance_um_per_N"] == pytest.approx(0.05)
    assert cutter_from_dict(doc).holder_compliance == pytest.approx(5e-5)  # [mm/N]


def test_compliance_adds_to_the_files_and_notes_the_old_value():
    """The diagnosis fits what the model (with the file's compliance) still misses: the values add."""
    once = apply_to_tool(HOLDER, TOOL, now=NOW)
    twice = apply_to_tool(HOLDER, once, now=NOW)
    assert tomllib.loads(twice)["holder_compliance_um_per_N"] == pytest.approx(0.1)
    line = next(ln for ln in twice.splitlines() if ln.startswith("holder_compliance_um_per_N"))
    assert "(was 0.05)" in line and "holder_compliance" in line.split("#", 1)[1]
    assert len(twice.splitlines()) == len(once.splitlines())


def test_runout_replaces_and_ignores_effects_of_other_files():
    t = apply_to_tool(RUNOUT, TOOL, now=NOW)
    doc = tomllib.loads(t)
    assert (doc["runout_rho_mm"], doc["runout_lambda_deg"]) == (0.004, 40.0)
    t2 = apply_to_tool(FORCE, t, now=NOW)  # the force diagnosis' runout; edge/size effect are not tool terms
    doc2 = tomllib.loads(t2)
    assert (doc2["runout_rho_mm"], doc2["runout_lambda_deg"]) == (0.01, 0.0)
    assert "Kte_N_per_mm" not in doc2 and not _unchanged(TOOL, t2)


def test_manifest_tables_are_edited_in_place():
    manifest = ('kind = "wall_error"\n[tool]\ndiameter_mm = 6.0\nflutes = 3\n\n[model]\n'
                'coefficients = "leekunhwee_flat_slot"\n\n[[experiment]]\nfile = "a.csv"\n')
    out = apply_to_tool(HOLDER, manifest, now=NOW)
    doc = tomllib.loads(out)
    assert doc["tool"]["holder_compliance_um_per_N"] == pytest.approx(0.05)
    assert doc["experiment"] == [{"file": "a.csv"}] and "holder_compliance_um_per_N" not in doc
    fm = ('kind = "cutting_force"\n[tool]\nflutes = 2\n[model]\nKte_N_per_mm = 16.0\nreference_chip_mm = 0.05\n'
          '[[experiment]]\nfile = "a.csv"\n')
    doc = tomllib.loads(apply_to_coefficients(FORCE, fm, now=NOW, source="b"))
    assert doc["model"]["Kte_N_per_mm"] == 30.0 and doc["model"]["chip_exponent"] == 0.8
    assert doc["tool"] == {"flutes": 2} and doc["experiment"] == [{"file": "a.csv"}]


def test_coefficients_edge_forces_and_size_effect():
    out = apply_to_coefficients(FORCE, COEFFS, source="slots/", now=NOW)
    doc = tomllib.loads(out)
    assert (doc["Kte_N_per_mm"], doc["Kre_N_per_mm"], doc["Kae_N_per_mm"]) == (30.0, 25.0, 4.0)
    assert doc["chip_exponent"] == 0.8 and doc["reference_chip_mm"] == 0.02  # the file's reference kept
    assert doc["Ktc_N_per_mm2"] == 2000.0 and out.splitlines()[0] == "# steel, calibrated 2026-10"
    kte = next(ln for ln in out.splitlines() if ln.startswith("Kte_N_per_mm"))
    assert "edge_forces: netshape diagnose of slots/, 2026-11-28 14:05 UTC (was 40.0)" in kte


def test_crlf_and_no_final_newline_survive():
    crlf = TOOL.replace("\n", "\r\n")
    out = apply_to_tool(HOLDER, crlf, now=NOW)
    assert out.startswith(crlf) and "\r\nholder_compliance_um_per_N = 0.05\r\n" in out
    out = apply_to_tool(HOLDER, TOOL.rstrip("\n"), now=NOW)
    assert tomllib.loads(out)["youngs_modulus_MPa"] == 600000.0


@pytest.mark.parametrize(
    "call, diagnosis, text, words",
    [
        (apply_to_tool, {"effects": []}, TOOL, "effect = no effect: nothing to write into the tool file"),
        (apply_to_tool, FORCE | {"effects": FORCE["effects"][:2]}, TOOL, "edge_forces, size_effect"),
        (apply_to_coefficients, RUNOUT, COEFFS, "effect = runout: nothing to write into the coefficients"),
        (apply_to_tool, HOLDER, "kind = \n", "tool TOML: not valid TOML"),
        (apply_to_tool, object(), TOOL, "has no 'effects'"),
        (apply_to_coefficients, FORCE, "Ktc_N_per_mm2 = 900.0\n", "reference_chip_mm unknown"),
        (apply_to_tool, {"effects": [{"effect": "runout", "parameters": {"rho_mm": float("nan"),
                                                                          "lambda_deg": 0.0}}]}, TOOL, "rho_mm = nan"),
    ],
)
def test_refusals_name_the_problem(call, diagnosis, text, words):
    with pytest.raises(ValueError) as exc:
        call(diagnosis, text, now=NOW)
    assert words in str(exc.value)


def test_holder_keys_of_the_cutter_toml_are_validated():
    base = tomllib.loads(TOOL)
    with pytest.raises(ValueError, match="holder_compliance_um_per_N = -1.0"):
        cutter_from_dict(base | {"holder_compliance_um_per_N": -1.0})
    with pytest.raises(ValueError, match="runout_rho"):
        cutter_from_dict(base | {"runout_rho_mm": 5.0})
    c = cutter_from_dict(base | {"runout_rho_mm": 0.01, "runout_lambda_deg": 90.0})
    assert c.runout_rho == 0.01 and c.runout_lambda == pytest.approx(1.5707963267948966)
