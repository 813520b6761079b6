"""Job file parsing: the demo job reads as written; unknown keys and bad values give one error naming
the key; work offsets are taken per line from the program's G54–G59 words."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from netshape.job import JobError, job_from_dict, load_job, set_dotted
from netshape.job.program import active_work_offsets

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from .conftest import DEMO


def demo_doc() -> dict:
    return tomllib.loads((DEMO / "job.toml").read_text())


def parse(doc):
    return job_from_dict(doc, source="job.toml", base_dir=DEMO)


def test_demo_job_reads_as_written():
    job = load_job(DEMO / "job.toml")
    assert job.program == DEMO / "part.ngc"
    assert job.tool["diameter_mm"] == 6.0 and job.tool["flutes"] == 3
    assert job.stock["min_mm"] == [-30.0, -25.0, -20.0] and job.stock["spacing_mm"] == 0.25
    assert [pc.program.name for pc in job.stock["pre_cut"]] == ["preshape.ngc"]
    assert job.stock["pre_cut"][0].tool["diameter_mm"] == 10.0
    assert job.offsets["G54"] == [-150.0, 80.0, -300.0] and job.offsets["G55"] == [0.0, 0.0, 0.0]
    assert job.offsets["tool_length_mm"] == 100.0
    assert job.machine == DEMO / "machine.toml"
    assert job.predict == {"forces": True, "deflection": True, "volumetric": True, "feed_plan": True}
    # applied in the fixed order deflection, then volumetric, whatever the file's order
    assert job.compensations == ["deflection", "volumetric"]
    assert job.output == Path.cwd() / "netshape-demo"  # outputs go where the user runs


@pytest.mark.parametrize("edit, key", [
    (lambda d: d.update(colour="red"), "colour"),
    (lambda d: d["stock"].update(spacing=1.0), "stock.spacing"),
    (lambda d: d["stock"].update(spacing_mm=-1.0), "stock.spacing_mm"),
    (lambda d: d["stock"].update(max_mm=[30.0, 25.0]), "stock.max_mm"),
    (lambda d: d["stock"].update(max_mm=[30.0, -26.0, 0.0]), "stock.max_mm[1]"),
    (lambda d: d["stock"]["pre_cut"][0].update(feed=3), "stock.pre_cut[0].feed"),
    (lambda d: d["stock"]["pre_cut"][0].pop("tool"), "stock.pre_cut[0].tool"),
    (lambda d: d["offsets"].update(G54_mm=[0, 0]), "offsets.G54_mm"),
    (lambda d: d["offsets"].update(G53_mm=[0, 0, 0]), "offsets.G53_mm"),
    (lambda d: d["offsets"].update(tool_length_mm=-5.0), "offsets.tool_length_mm"),
    (lambda d: d.update(coefficients="no_such_set"), "coefficients"),
    (lambda d: d.update(coefficients="Ktc=1,Kxx=2"), "coefficients"),
    (lambda d: d["machine"].update(error_scale="big"), "machine.error_scale"),
    (lambda d: d["limits"].update(rule="fast"), "limits.rule"),
    (lambda d: d["limits"].pop("vmax_mm_s"), "limits.vmax_mm_s"),
    (lambda d: d["limits"].update(amax_mm_s2=[1.0, 2.0]), "limits.amax_mm_s2"),
    (lambda d: d["cutting"].update(samples_per_revolution=2), "cutting.samples_per_revolution"),
    (lambda d: d["predict"].update(chips=True), "predict.chips"),
    (lambda d: d["predict"].update(forces="yes"), "predict.forces"),
    (lambda d: d["compensate"].update(deflection_scheme="magic"), "compensate.deflection_scheme"),
    (lambda d: d["compensate"].update(deflection_unconverged="ignore"), "compensate.deflection_unconverged"),
    (lambda d: d.update(program="missing.ngc"), "program"),
    (lambda d: d.update(tool={"file": "tool.toml", "flutes": 0}), "flutes"),
    (lambda d: d.update(tool={"file": "tool.toml", "shank_mm": 6}), "tool.shank_mm"),
    (lambda d: d.update(report={"dpi": 5}), "report.dpi"),
])
def test_bad_key_or_value_names_the_key(edit, key):
    doc = demo_doc()
    edit(doc)
    with pytest.raises(JobError) as exc:
        parse(doc)
    msg = str(exc.value)
    assert msg.startswith("job.toml: ") and key in msg and "\n" not in msg


@pytest.mark.parametrize("edit, key", [
    (lambda d: d.pop("machine"), "machine"),
    (lambda d: d.pop("limits"), "limits"),
    (lambda d: d.pop("coefficients"), "coefficients"),
    (lambda d: d["predict"].update(volumetric=False), "compensate.volumetric"),
    (lambda d: d["predict"].update(forces=False), "predict.deflection"),
])
def test_a_prediction_without_what_it_needs_names_the_key(edit, key):
    doc = demo_doc()
    edit(doc)
    with pytest.raises(JobError, match=key.replace(".", r"\.")):
        parse(doc)


def test_stock_file_with_deflection_keys(tmp_path):
    """A stock TOML with the keys of `netshape deflection` (min_mm, max_mm, spacing_mm, [[pre_cut]])
    is read; its relative paths are relative to the stock file."""
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "STOCK.toml").write_text(
        'min_mm = [-30.0, -25.0, -20.0]\nmax_mm = [30.0, 25.0, 0.0]\nspacing_mm = 0.5\n'
        f'[[pre_cut]]\nprogram = "{(DEMO / "preshape.ngc").as_posix()}"\ntool = "{(DEMO / "rougher.toml").as_posix()}"\n')
    doc = demo_doc()
    doc["stock"] = "sub/STOCK.toml"
    doc["program"] = str(DEMO / "part.ngc")
    doc["tool"] = str(DEMO / "tool.toml")
    doc["machine"]["file"] = str(DEMO / "machine.toml")
    job = job_from_dict(doc, source="job.toml", base_dir=tmp_path)
    assert job.stock["spacing_mm"] == 0.5 and len(job.stock["pre_cut"]) == 1
    (tmp_path / "sub" / "STOCK.toml").write_text("min_mm = [0, 0, 0]\nmax_mm = [1, 1, 1]\nspacing = 1\n")
    with pytest.raises(JobError, match="STOCK.toml: spacing"):
        job_from_dict(doc, source="job.toml", base_dir=tmp_path)


def test_work_offset_per_line(tmp_path):
    p = tmp_path / "p.ngc"
    p.write_text("G21 G90\nG0 X1 (G55 in a comment)\nG55 G0 X2\nG1 X3 F100 ; G56\nG5 9 X4\nG54\nG0 X5\n")
    idx = active_work_offsets(p)
    assert list(idx[1:]) == [0, 0, 1, 1, 5, 0, 0]
    p.write_text("G59.1\nG0 X1\n")
    with pytest.raises(ValueError, match="G59.1"):
        active_work_offsets(p)


def test_set_dotted_turns_a_tool_path_into_a_table():
    doc = demo_doc()
    d = set_dotted(doc, "tool.stick_out_mm", 40.0)
    assert d["tool"] == {"file": "tool.toml", "stick_out_mm": 40.0} and doc["tool"] == "tool.toml"
    job = parse(d)
    assert job.tool["stick_out_mm"] == 40.0 and job.tool["diameter_mm"] == 6.0
    with pytest.raises(ValueError, match="grid key"):
        set_dotted(doc, "tool..x", 1)


def test_cli_bad_job_exits_2_with_one_line(tmp_path, capsys):
    import shutil

    from netshape.cli import main

    shutil.copytree(DEMO, tmp_path / "demo")
    job = tmp_path / "demo" / "job.toml"
    job.write_text(job.read_text().replace("spacing_mm = 0.25", "spacing_mm = 0"))
    assert main(["run", str(job), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "stock.spacing_mm = 0" in err
    assert not (tmp_path / "demo" / "netshape-demo").exists()


def test_bad_machine_file_is_a_job_error(tmp_path):
    import shutil

    shutil.copytree(DEMO, tmp_path / "demo")
    m = tmp_path / "demo" / "machine.toml"
    m.write_text(m.read_text().replace("[axes.X]\n", "[axes.X]\nspeed = 3\n"))
    with pytest.raises(JobError, match=r"machine\.file = 'machine\.toml': .*speed"):
        load_job(tmp_path / "demo" / "job.toml")
