"""Trouble met while running is reported (issue 42): a rapid through material names its line, a program
whose first move is `G0 Z15` is not swept from an assumed (0, 0, 0) inside the stock, `start_mm` is where
the tool starts."""

from __future__ import annotations

from pathlib import Path

import pytest

from netshape.job import job_from_dict, run_job

TOOL = {"kind": "flat", "diameter_mm": 6.0, "flutes": 3, "helix_deg": 30.0, "flute_length_mm": 16.0,
        "stick_out_mm": 30.0, "youngs_modulus_MPa": 600000.0}


def _job(tmp_path, text, **extra):
    (tmp_path / "p.ngc").write_text(text)
    doc = {"program": "p.ngc", "tool": TOOL, "coefficients": "leekunhwee_flat_slot",
           "stock": {"min_mm": [-20.0, -20.0, -10.0], "max_mm": [20.0, 20.0, 0.0], "spacing_mm": 0.5},
           "predict": {"forces": False, "deflection": False, "volumetric": False, "feed_plan": False},
           "report": {"plots": False, "zmap_stl": False}, **extra}
    return job_from_dict(doc, source=str(tmp_path / "job.toml"), base_dir=tmp_path)


def test_a_first_rapid_up_cuts_nothing(tmp_path):
    s = run_job(_job(tmp_path, "G21 G90\nG0 Z15\nG0 X10 Y10\nM30\n"), tmp_path / "out")
    assert s["removed_volume_mm3"] == pytest.approx(0.0, abs=1e-9)
    assert s["warnings"] == []
    assert "cut" not in s["stages"]


def test_rapid_through_material_is_reported_with_its_line(tmp_path):
    text = "G21 G90\nG0 Z5\nG0 X-15 Y0\nG0 Z-2\nG0 X15\nG0 Z5\nM30\n"
    s = run_job(_job(tmp_path, text), tmp_path / "out")
    kinds = [(w["kind"], w["line"]) for w in s["warnings"]]
    assert ("rapid_through_material", 4) in kinds and ("rapid_through_material", 5) in kinds
    assert s["stages"]["cut"] == "rapid_through_material"
    assert "rapid_through_material" in (tmp_path / "out" / "report.html").read_text()


def test_start_mm_is_where_the_tool_starts(tmp_path):
    # from a start inside the stock, the first move (straight up) cuts; from the default it does not
    s = run_job(_job(tmp_path, "G21 G90\nG1 Z15 F600\nM30\n", start_mm=[0.0, 0.0, -3.0]), tmp_path / "a")
    assert s["removed_volume_mm3"] > 50.0  # a 6 mm hole 3 mm deep: ~85 mm^3 on the 0.5 mm grid
    s = run_job(_job(tmp_path, "G21 G90\nG1 Z15 F600\nM30\n"), tmp_path / "b")
    assert s["removed_volume_mm3"] == pytest.approx(0.0, abs=1e-9)


def test_start_mm_checked(tmp_path):
    with pytest.raises(ValueError, match="start_mm"):
        _job(tmp_path, "G0 Z5\n", start_mm=[0.0, 1.0])
    with pytest.raises(ValueError, match="clearance_mm"):
        _job(tmp_path, "G0 Z5\n", clearance_mm=-1.0)


def test_a_cut_deeper_than_the_stick_out_is_warned(tmp_path):
    text = "G21 G90\nG0 X0 Y0 Z5\nG1 Z-9 F300\nG1 X5\nG0 Z5\nM30\n"
    job = _job(tmp_path, text)
    job.tool = dict(TOOL, stick_out_mm=8.0, flute_length_mm=6.0)
    s = run_job(job, tmp_path / "out")
    deep = [w for w in s["warnings"] if w["kind"] == "tool_shorter_than_cut"]
    assert deep and deep[0]["line"] == 3


def test_a_move_outside_the_machine_travel_is_warned_and_not_compensated(tmp_path):
    # X travel ends at 10 mm (program X zero at machine X zero): the moves on lines 4-6 leave it
    text = (Path(__file__).resolve().parents[3] / "examples" / "demo" / "machine.toml").read_text()
    text = text.replace("travel_mm = [-400.0, 400.0]", "travel_mm = [-400.0, 10.0]", 1)
    (tmp_path / "m.toml").write_text(text)
    program = "G21 G90\nG0 X-15 Y0 Z5\nG1 Z-1 F300\nG1 X15\nG1 Y5\nG0 Z5\nM30\n"
    extra = {"machine": {"file": "m.toml"}, "offsets": {"G54_mm": [0.0, 0.0, -300.0], "tool_length_mm": 100.0},
             "compensate": {"volumetric": True},
             "predict": {"forces": False, "deflection": False, "volumetric": True, "feed_plan": False}}
    s = run_job(_job(tmp_path, program, **extra), tmp_path / "out")
    out = [w for w in s["warnings"] if w["kind"] == "move_outside_travel"]
    assert [w["line"] for w in out] == [4, 5, 6]  # the cut to X15, along Y there, the rapid up there
    assert "axis X reaches 15.0000 mm" in out[0]["message"] and "[-400, 10]" in out[0]["message"]
    assert s["stages"]["volumetric"] == "outside_travel"
    assert s["volumetric_compensation"]["status"] == "skipped"
    assert "volumetric" not in s["job"]["compensations"]
    # the same program inside the travel: no warning, compensated
    (tmp_path / "m.toml").write_text(text.replace("[-400.0, 10.0]", "[-400.0, 400.0]", 1))
    s = run_job(_job(tmp_path, program, **extra), tmp_path / "ok")
    assert not [w for w in s["warnings"] if w["kind"] == "move_outside_travel"]
    assert s["stages"]["volumetric"] == "ok" and "volumetric" in s["job"]["compensations"]
