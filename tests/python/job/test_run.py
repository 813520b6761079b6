"""`netshape run` / `netshape demo` end to end on the bundled demo job: the summary's keys, the
compensated errors below the uncompensated ones, the compensated program checked against the machine
model point by point, the report's links, the STL, work offsets, and a failing stage."""

from __future__ import annotations

import json
import re
import shutil
import sys

import numpy as np
import pytest

import netshape as ns
from netshape.job import StageFailed, job_from_dict, load_job, run_job

from .conftest import DEMO

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ERROR_KEYS = {"max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm"}


def test_summary_keys(demo_run):
    _, s, _ = demo_run
    assert set(s["errors"]) == {"deflection", "volumetric", "total"}
    for src in s["errors"].values():
        assert set(src) == ERROR_KEYS
    assert set(s["cycle_time_s"]) == {"original", "compensated"}
    assert {"program", "stock", "cut", "forces", "deflection", "volumetric", "volumetric_compensation",
            "feed_plan", "feed_plan_compensated", "report"} <= set(s["run_time_s"])
    assert all(v >= 0 for v in s["run_time_s"].values())
    assert s["versions"]["netshape"] == ns.__version__
    # the pocket at F900 mm/min: the planned time is at least the time at programmed feed
    info = ns.toolpath.summary(DEMO / "part.ngc")
    assert s["cycle_time_s"]["original"] >= info.feed_time
    assert s["cycle_time_s"]["original"] < 3 * info.feed_time + 10


def test_compensated_errors_below_uncompensated(demo_run):
    _, s, _ = demo_run
    e = s["errors"]
    for src in ("volumetric", "total"):
        assert e[src]["max_after_mm"] < e[src]["max_before_mm"]
        assert e[src]["rms_after_mm"] < e[src]["rms_before_mm"]
    # machine errors of micrometres (docs of examples/demo/machine.toml) ...
    assert 1e-3 < e["volumetric"]["max_before_mm"] < 0.1
    # ... compensated to within the job's chord tolerance (0.001 mm)
    assert e["volumetric"]["max_after_mm"] <= 0.001
    assert e["deflection"]["max_after_mm"] < e["deflection"]["max_before_mm"]


def test_compensated_program_lands_on_the_nominal_points(tmp_path):
    """Independent of the job's own re-prediction: every end point of the original program's feed
    moves is reached, within 1e-6 mm, by the actual tip (machine model) at some end point of the
    compensated program, both placed in the machine by the job's G54 offset. (The demo job with
    volumetric compensation only: deflection compensation moves the contours off the nominal path
    on purpose.)"""
    d = _demo_copy(tmp_path)
    job = job_from_dict(_volumetric_only(tomllib.loads((d / "job.toml").read_text())), source="job.toml",
                        base_dir=d)
    s = run_job(job, tmp_path / "out")
    comp_text = (tmp_path / "out" / s["files"]["compensated_program"]).read_text()
    assert "G54" in comp_text
    comp = ns.toolpath.parse_gcode(comp_text)
    orig = ns.toolpath.read_gcode(DEMO / "part.ngc")
    m = ns.machine.load_machine(DEMO / "machine.toml")
    m.tool_length = job.offsets["tool_length_mm"]
    g54 = np.array(job.offsets["G54"])
    cmd = np.array([b.end for b in comp.blocks]) + g54
    actual = ns.machine.actual_points(m, cmd) - g54
    nominal = np.array([b.end for b in orig.blocks if b.kind != ns.toolpath.MotionKind.rapid])
    d = np.min(np.linalg.norm(nominal[:, None, :] - actual[None, :, :], axis=2), axis=1)
    assert d.max() < 1e-6
    # without compensation the same points are off by the machine's error (micrometres)
    raw = ns.machine.actual_points(m, nominal + g54) - g54
    assert np.linalg.norm(raw - nominal, axis=1).max() > 1e-3


def test_report_references_only_existing_files(demo_run):
    out, s, _ = demo_run
    page = (out / "report.html").read_text()
    refs = re.findall(r'(?:src|href)="([^"]+)"', page)
    assert refs and not any("://" in r or r.startswith("//") for r in refs)
    for r in refs:
        assert (out / r).is_file() and (out / r).stat().st_size > 0, r
    for name in ("force.png", "wall_error.png", "volumetric_error.png", "feed.png", "zmap.png"):
        assert name in refs
    for name in s["files"].values():
        assert (out / name).is_file(), name
    assert not list(out.glob(".*.tmp"))


def test_zmap_stl_is_the_cut_stock(demo_run):
    out, _, _ = demo_run
    _, tris = ns.stock.read_stl(out / "zmap.stl")
    z = tris[..., 2]
    assert len(tris) > 1000
    assert z.min() == pytest.approx(-20.0) and z.max() == pytest.approx(0.0)
    # the pocket floor, 6 mm deep, is in the solid
    assert np.any(np.isclose(z, -6.0, atol=1e-4))


def _demo_copy(tmp_path):
    shutil.copytree(DEMO, tmp_path / "demo")
    return tmp_path / "demo"


def _volumetric_only(doc):
    doc["predict"] = {"forces": False, "deflection": False, "volumetric": True, "feed_plan": False}
    doc["compensate"] = {"volumetric": True, "chord_tolerance_mm": 0.001}
    doc["report"] = {"dpi": 40, "zmap_stl": False}
    doc["stock"]["spacing_mm"] = 1.0
    return doc


def test_work_offset_g55_places_the_program_like_g54(tmp_path, demo_run):
    """The same program under G55 with G55_mm = the demo's G54 gives the demo's volumetric errors; with
    the offset left at zero (identity) it does not."""
    _, s, _ = demo_run
    d = _demo_copy(tmp_path)
    (d / "part.ngc").write_text((d / "part.ngc").read_text().replace("G40 G49 G54", "G40 G49 G55"))
    doc = _volumetric_only(tomllib.loads((d / "job.toml").read_text()))
    doc["offsets"] = {"G55_mm": [-150.0, 80.0, -300.0], "tool_length_mm": 100.0}
    r = run_job(job_from_dict(doc, source="job.toml", base_dir=d), tmp_path / "g55")
    assert r["errors"]["volumetric"]["max_before_mm"] == pytest.approx(s["errors"]["volumetric"]["max_before_mm"],
                                                                       rel=1e-9)
    assert "G55" in (tmp_path / "g55" / "part_compensated.ngc").read_text()
    doc["offsets"] = {"G55_mm": [-150.0, 80.0, -290.0], "tool_length_mm": 100.0}
    r2 = run_job(job_from_dict(doc, source="job.toml", base_dir=d), tmp_path / "g55b")
    assert r2["errors"]["volumetric"]["max_before_mm"] != pytest.approx(s["errors"]["volumetric"]["max_before_mm"],
                                                                        rel=1e-6)


def test_failed_stage_is_named_and_writes_nothing_half(tmp_path, capsys, monkeypatch):
    """A stage that fails (here the volumetric compensation, made to raise) stops the run naming that
    stage and leaves no report, summary or temporary file; the CLI prints one line. (A program outside
    the machine's travel is a warning, not a failure: test_run_warnings.py.)"""
    from netshape.job import stages

    def refuse(*args, **kwargs):
        raise ValueError("compensated axis Z = 5.0 mm is outside its travel [-450, 0] mm")

    monkeypatch.setattr(stages, "stage_volumetric_compensation", refuse)
    d = _demo_copy(tmp_path)
    doc = _volumetric_only(tomllib.loads((d / "job.toml").read_text()))
    job = job_from_dict(doc, source="job.toml", base_dir=d)
    with pytest.raises(StageFailed) as exc:
        run_job(job, tmp_path / "out")
    assert exc.value.stage == "volumetric_compensation" and "travel" in str(exc.value)
    assert not (tmp_path / "out").exists()  # the folder is made only when the outputs are written
    from netshape.cli import main

    assert main(["run", str(d / "job.toml"), "--out", str(tmp_path / "cli"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "stage volumetric_compensation failed" in err
    assert not (tmp_path / "cli").exists()


def test_machine_error_scale_scales_the_error(tmp_path, demo_run):
    """machine.error_scale multiplies every error: 0 leaves an exact machine (2 doubles the deviation:
    test_example_job_api_runs)."""
    _, s, _ = demo_run
    d = _demo_copy(tmp_path)
    doc = _volumetric_only(tomllib.loads((d / "job.toml").read_text()))
    doc["machine"]["error_scale"] = 0.0
    r = run_job(job_from_dict(doc, source="job.toml", base_dir=d), tmp_path / "zero")
    assert r["errors"]["volumetric"]["max_before_mm"] < 1e-12
    summary = json.loads((tmp_path / "zero" / "summary.json").read_text())
    assert summary["errors"] == r["errors"]


def test_example_job_api_runs(tmp_path, capsys):
    import runpy

    from .conftest import REPO

    mod = runpy.run_path(str(REPO / "examples" / "job_api.py"))
    res = mod["main"]([str(tmp_path), "--quick"])
    a, b = res["as written"]["errors"]["volumetric"], res["errors x2"]["errors"]["volumetric"]
    # machine.error_scale = 2 doubles the deviation (micrometre errors: the synthesis is linear to ~1e-3)
    assert b["max_before_mm"] == pytest.approx(2 * a["max_before_mm"], rel=5e-3)
    assert "volumetric error" in capsys.readouterr().out


def test_program_switching_work_offsets_is_compensated_in_each_frame(tmp_path):
    """A program that cuts under G54, then under G55: the compensated program switches offsets at the
    same place, and read back with the job's offsets every nominal point is reached in the machine."""
    from netshape.job.stages import active_work_offsets

    d = _demo_copy(tmp_path)
    (d / "two.ngc").write_text(
        "G21 G90 G17 G94\nG54\nG0 Z5\nG0 X-10 Y-5\nG1 Z-1 F300\nG1 X10 F900\nG2 X10 Y5 I0 J5\nG1 X-10\nG0 Z5\n"
        "G55\nG0 X-10 Y-5\nG1 Z-1 F300\nG1 X10 F900\nG3 X10 Y5 I0 J5\nG0 Z5\nM30\n")
    doc = _volumetric_only(tomllib.loads((d / "job.toml").read_text()))
    doc["program"] = "two.ngc"
    doc["stock"].pop("pre_cut")
    doc["offsets"] = {"G54_mm": [-150.0, 80.0, -300.0], "G55_mm": [120.0, -60.0, -280.0], "tool_length_mm": 100.0}
    job = job_from_dict(doc, source="job.toml", base_dir=d)
    s = run_job(job, tmp_path / "out")
    assert s["errors"]["volumetric"]["max_after_mm"] < 1e-3 < s["errors"]["volumetric"]["max_before_mm"]
    comp_path = tmp_path / "out" / "two_compensated.ngc"
    text = comp_path.read_text()
    assert text.index("G54") < text.index("G55")
    offsets = np.array([job.offsets[g] for g in ("G54", "G55", "G56", "G57", "G58", "G59")])
    m = ns.machine.load_machine(d / "machine.toml")
    m.tool_length = 100.0

    def machine_ends(path):
        tp = ns.toolpath.read_gcode(path)
        idx = active_work_offsets(path)[[b.line for b in tp.blocks]]
        return np.array([b.end for b in tp.blocks]) + offsets[idx], [b.kind for b in tp.blocks]

    cmd, _ = machine_ends(comp_path)
    actual = ns.machine.actual_points(m, cmd)
    nominal, kinds = machine_ends(d / "two.ngc")
    nominal = nominal[[k != ns.toolpath.MotionKind.rapid for k in kinds]]
    dist = np.min(np.linalg.norm(nominal[:, None, :] - actual[None, :, :], axis=2), axis=1)
    assert dist.max() < 1e-6


def test_demo_program_clears_the_drawn_pocket():
    """The bundled pocket (drawing: 40 x 30 mm, 8 mm corner radii, 6 mm deep, centred at the origin)
    cut from the pre-shaped stock: every Z-map node 0.3 mm inside the drawn outline is at the floor,
    every node 0.3 mm outside it is untouched stock (no island left, no gouge)."""
    from netshape.job import stages as st

    job = load_job(DEMO / "job.toml")
    prog = st.stage_program(job)
    z, removed = st.stage_cut(job, st.stage_stock(job), prog)
    xs, ys = ns.stock.node_coordinates(z)
    X, Y = np.meshgrid(xs, ys)
    # signed distance to the drawn rounded rectangle (negative inside)
    qx, qy = np.abs(X) - (20.0 - 8.0), np.abs(Y) - (15.0 - 8.0)
    sd = np.hypot(np.maximum(qx, 0), np.maximum(qy, 0)) + np.minimum(np.maximum(qx, qy), 0) - 8.0
    h = np.asarray(z.heights)
    assert np.all(np.abs(h[sd < -0.3] + 6.0) < 1e-9)
    assert np.all(np.abs(h[sd > 0.3]) < 1e-9)
    assert removed > 0


def test_force_stage_in_chunks_cuts_the_same_stock(monkeypatch):
    """The force stage simulates the program a chunk of blocks at a time (for its progress bar), the
    Z-map carried over: the material it removes equals the plain sweep's, and the forces match those of
    one call to within the sampling restart at chunk starts."""
    from netshape.job import stages as st

    job = load_job(DEMO / "job.toml")
    prog = st.stage_program(job)
    stock0 = st.stage_stock(job)
    _, removed = st.stage_cut(job, stock0, prog)
    whole = st.stage_forces(job, stock0, prog)
    monkeypatch.setattr(st, "FORCE_CHUNK_BLOCKS", 7)
    done = []
    parts = st.stage_forces(job, stock0, prog, progress=done.append)
    assert done[-1] == len(prog.toolpath.blocks) and len(done) == -(-len(prog.toolpath.blocks) // 7)
    assert whole.removed_volume == pytest.approx(removed, rel=1e-9)
    assert parts.removed_volume == pytest.approx(removed, rel=1e-9)
    assert np.max(parts.peak_resultant) == pytest.approx(np.max(whole.peak_resultant), rel=0.03)
    assert np.all(np.diff(parts.block) >= 0)


def test_compensated_program_keeps_the_programs_words(demo_run):
    """Deflection then volumetric compensation change coordinates only: the compensated program carries
    the original's comments, tool/spindle words, work offset and program end in the same order."""
    import warnings

    out, s, _ = demo_run
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ns.toolpath.GcodeWarning)
        orig = ns.toolpath.read_gcode(DEMO / "part.ngc")
        comp = ns.toolpath.parse_gcode((out / s["files"]["compensated_program"]).read_text())
    words = [c.text for c in orig.commands]
    assert {"M5", "M30", "G54"} <= set(words)
    assert s["job"]["compensations"] == ["deflection", "volumetric"]
    assert [c.text for c in comp.commands if not c.text.startswith("(netshape compensated")] == words


@pytest.mark.slow
def test_unconverged_deflection_contour_reported_or_fatal(tmp_path):
    """The demo pocket's finishing pass meets a step in the stock where no offset makes the wall error
    vanish at the step itself: with compensate.deflection_unconverged = "report" (default) the run
    sets stages.deflection to "unconverged" and names the contours and points in the deflection block;
    with "fail" the run stops at the deflection stage and writes nothing."""
    d = _demo_copy(tmp_path)
    doc = tomllib.loads((d / "job.toml").read_text())
    doc["predict"] = {"forces": True, "deflection": True, "volumetric": False, "feed_plan": False}
    doc["cutting"].update(step_mm=2.0, samples_per_revolution=12, disk_height_mm=1.0, error_spacing_mm=0.5)
    doc["compensate"] = {"deflection": True, "deflection_scheme": "accelerated"}
    doc["report"] = {"plots": False, "zmap_stl": False}
    s = run_job(job_from_dict(doc, source="job.toml", base_dir=d), tmp_path / "report")
    assert s["stages"]["deflection"] == "unconverged"
    block = s["deflection"]
    assert "did not reach the tolerance" in block["reason"] and "lines " in block["reason"]
    bad = [c for c in block["contours"] if c["final_wall"] and not c["converged"]]
    assert bad and all(c["max_residual_mm"] > 5e-4 for c in bad)
    assert block["unconverged_points"] and {"line", "x_mm", "y_mm", "error_mm"} <= set(block["unconverged_points"][0])
    e = s["errors"]["deflection"]
    assert e["max_after_mm"] < e["max_before_mm"] and e["rms_after_mm"] < 0.5 * e["rms_before_mm"]
    doc["compensate"]["deflection_unconverged"] = "fail"
    with pytest.raises(StageFailed) as exc:
        run_job(job_from_dict(doc, source="job.toml", base_dir=d), tmp_path / "fail")
    assert exc.value.stage == "deflection" and "deflection compensation of the contour from line" in str(exc.value)
    assert not (tmp_path / "fail").exists() or not any((tmp_path / "fail").iterdir())
