"""A job's numbers are sized before any stage runs (docs/job.md, Limits): feeds after feed_scale within
the writer's F ≤ 1e8 mm/min, a finite feed per tooth, force/error/feed-plan samples, heights files and
the Z-map STL within their budgets, a batch grid within --max-runs; results are never written with
NaN or Infinity. Each refusal is one line naming the job file, the key and the value, before any output."""

from __future__ import annotations

import re
import shutil
import time
from pathlib import Path

import numpy as np
import pytest

from netshape.cli import main

from .conftest import DEMO


def _job(tmp_path, table: str = "", sets: dict | None = None, extra: str = "") -> Path:
    d = tmp_path / "demo"
    shutil.copytree(DEMO, d)
    text = (d / "job.toml").read_text()
    text = re.sub(r'^output = .*$', f'output = "{d / "out"}"', text, flags=re.M)
    for key, value in (sets or {}).items():
        text = re.sub(rf"^{re.escape(key)} = .*$", "", text, flags=re.M)
        text = re.sub(rf"^\[{table}\].*$", lambda m: f"{m.group(0)}\n{key} = {value}", text, count=1, flags=re.M)
    (d / "job.toml").write_text(text + extra)
    return d / "job.toml"


def _refused(capsys, argv, *needles, max_s: float = 2.0, first: str = "") -> str:
    t0 = time.perf_counter()
    code = main(argv)
    elapsed = time.perf_counter() - t0
    cap = capsys.readouterr()
    assert code == 2, cap
    lines = cap.err.strip().splitlines()
    if first:  # a line that comes before the refusal (batch states its size)
        assert lines[0] == first, cap.err
        lines = lines[1:]
    assert len(lines) == 1, cap.err
    assert "Traceback" not in cap.err
    for n in needles:
        assert n in lines[0], (n, lines[0])
    assert elapsed < max_s, elapsed  # refused before the work
    return lines[0]


def _no_outputs(job):
    assert not (job.parent / "out").exists()


@pytest.mark.parametrize("key, value, needle", [
    ("feed_scale", "1e60", "cutting.feed_scale = 1e+60: gives F "),
    ("spindle_rpm", "1e-300", "cutting.spindle_rpm = 1e-300: gives a feed per tooth of 1.67e+300 mm"),
    ("step_mm", "1e-6", "cutting.step_mm = 1e-06: gives"),
    ("error_spacing_mm", "1e-7", "cutting.error_spacing_mm = 1e-07: gives"),
])
def test_cutting_numbers_that_break_or_explode_the_run(capsys, tmp_path, key, value, needle):
    job = _job(tmp_path, "cutting", {key: value})
    line = _refused(capsys, ["run", str(job), "--quiet"], needle)
    assert line.startswith(f"netshape run: error: {job}: ")
    _no_outputs(job)


def test_feed_plan_period_is_sized(capsys, tmp_path):
    job = _job(tmp_path, "limits", {"ts1_s": "1e-9", "ts2_s": "1e-9"})
    _refused(capsys, ["run", str(job), "--quiet"], "limits.ts2_s = 1e-09: gives", "feed-plan samples")


def test_feed_plan_jerk_is_sized(capsys, tmp_path):
    """1e-12 is refused by the estimate before the run; a jerk limit whose corners, not its length, make
    the plan long (1e-9 on the demo) reaches the planner's own bound (test_plan_work_limits)."""
    job = _job(tmp_path, "limits", {"jmax_mm_s3": "1e-12"})
    _refused(capsys, ["run", str(job), "--quiet"], "limits.jmax_mm_s3 = ", "feed-plan samples")


def test_a_huge_heights_file_is_refused_before_it_is_loaded(capsys, tmp_path):
    job = _job(tmp_path)
    h = tmp_path / "demo" / "h.npy"
    # a 20000 x 20000 header over a few bytes: np.load would need 3.2 GB, the check reads the header
    with open(h, "wb") as fh:
        np.lib.format.write_array_header_1_0(fh, {"descr": "<f8", "fortran_order": False, "shape": (20000, 20000)})
        fh.write(b"\0" * 64)
    job.write_text(re.sub(r"^spacing_mm = 0.25", 'heights = "h.npy"', job.read_text(), flags=re.M))
    _refused(capsys, ["run", str(job), "--quiet"], "stock.heights = 'h.npy': holds 20000 x 20000 = 4e+08 Z-map nodes")


def test_a_huge_csv_heights_file_is_counted_before_it_is_loaded(capsys, tmp_path):
    # a long first row: an estimate from the file size over the first row's would say ~700 rows
    job = _job(tmp_path)
    first = ",".join(["-1.00000000000000"] * 8000) + "\n"
    row = ",".join(["-1"] * 8000) + "\n"
    (tmp_path / "demo" / "h.csv").write_text(first + row * 5999)  # 4.8e7 nodes
    job.write_text(re.sub(r"^spacing_mm = 0.25", 'heights = "h.csv"', job.read_text(), flags=re.M))
    _refused(capsys, ["run", str(job), "--quiet"], "stock.heights = 'h.csv': holds at least 50")


def test_heights_csv_rows_are_counted_exactly(tmp_path):
    from netshape.stock.config import heights_shape as _heights_shape

    p = tmp_path / "h.csv"
    p.write_text("1.000000,2,3\n4,5,6\n7,8,9")  # no newline after the last row
    assert _heights_shape(p) == (3.0, 3, False)
    p.write_text("1,2\n" * 7)
    assert _heights_shape(p) == (7.0, 2, False)
    assert _heights_shape(p, max_nodes=5) == (7.0, 2, True)  # stopped counting: at least


def test_a_zmap_stl_of_too_many_triangles_is_refused(capsys, tmp_path):
    job = _job(tmp_path)
    job.write_text(re.sub(r"^spacing_mm = 0.25", "spacing_mm = 0.01", job.read_text(), flags=re.M))  # 6000 x 5000
    _refused(capsys, ["run", str(job), "--quiet"], "report.zmap_stl = True: the Z-map STL would hold 6e+07 triangles")


def test_a_batch_grid_states_its_size_and_refuses_over_max_runs(capsys, tmp_path):
    values = "[" + ", ".join(str(1 + i / 1000) for i in range(100)) + "]"
    grid = f'\n[grid]\n"cutting.feed_scale" = {values}\n"machine.error_scale" = {values}\n' \
           f'"tool.stick_out_mm" = {values}\n"cutting.step_mm" = [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4]\n'
    job = _job(tmp_path, extra=grid)
    _refused(capsys, ["batch", str(job), "--scheduler", "none", "--out", str(tmp_path / "b")],
             f"{job}: grid: gives 10000000 runs", "over the limit of 10000", "--max-runs",
             first="netshape batch: 10000000 runs")
    _refused(capsys, ["batch", str(job), "--scheduler", "none", "--max-runs", "5", "--quiet",
                      "--out", str(tmp_path / "b")], "over the limit of 5")
    assert not (tmp_path / "b").exists()


def test_a_non_finite_result_is_an_error_not_a_file(tmp_path, monkeypatch):
    """Whatever the cause, a run whose summary holds NaN/inf writes nothing and names the job."""
    from netshape.job import load_job, run_job
    from netshape.job import run as jr

    job = load_job(_job(tmp_path, "predict", {"deflection": "false", "volumetric": "false", "feed_plan": "false"}))
    monkeypatch.setattr(jr, "versions", lambda: {"netshape": float("nan")})
    with pytest.raises(ValueError, match=r"job.toml: gives a non-finite result \(versions.netshape = nan\); nothing"):
        run_job(job, tmp_path / "o", quiet=True)
    assert not (tmp_path / "o" / "summary.json").exists()


def test_a_batch_run_with_a_non_finite_feed_per_tooth_is_refused_before_any_runs(capsys, tmp_path):
    """spindle_rpm = 1e-300 once gave a batch row with status ok and inf cells."""
    job = _job(tmp_path, extra='\n[grid]\n"cutting.spindle_rpm" = [8000.0, 1e-300]\n')
    _refused(capsys, ["batch", str(job), "--scheduler", "none", "--quiet", "--out", str(tmp_path / "b")],
             f"{job} [job-001]: cutting.spindle_rpm = 1e-300: gives a feed per tooth of")
    assert not (tmp_path / "b").exists()


def test_a_non_finite_machine_error_names_the_machine(capsys, tmp_path):
    """A 1e300 polynomial once stopped the run with scipy's "'x' must be finite"."""
    job = _job(tmp_path, "predict", {"deflection": "false", "forces": "false"})
    m = job.parent / "machine.toml"
    m.write_text(m.read_text().replace("EXX_mm = [0.002, 2.5e-5]", "EXX_mm = [0.002, 2.5e-5, 0, 0, 1e300]"))
    _refused(capsys, ["run", str(job), "--quiet"], f"machine.file = '{m}': gives a volumetric error of nan mm at "
             "machine point", max_s=30.0)
