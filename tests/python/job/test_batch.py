"""`netshape batch`: a parameter grid run on a Dask LocalCluster with 2 workers gives the same rows
as the same runs one by one in this process."""

from __future__ import annotations

import csv
import sys
import shutil

import pytest

from netshape.job.batch import ERROR_COLUMNS, expand, run_batch, run_specs

from .conftest import DEMO

GRID = """
[grid]
"cutting.feed_scale" = [0.5, 1.0]
"machine.error_scale" = [0.5, 2.0]
"""


def _study(tmp_path):
    d = tmp_path / "demo"
    shutil.copytree(DEMO, d)
    text = (d / "job.toml").read_text()
    text = text.replace("spacing_mm = 0.25", "spacing_mm = 1.0").replace("deflection = true", "deflection = false")
    text = text.replace("forces = true", "forces = false")
    text = text.replace("[cutting]", "[report]\nplots = false\nzmap_stl = false\n\n[cutting]")
    (d / "study.toml").write_text(text + GRID)
    return d / "study.toml"


def test_grid_expands_in_file_order(tmp_path):
    specs = expand([_study(tmp_path)])
    assert [s["run"] for s in specs] == [f"study-{i:03d}" for i in range(4)]
    assert [tuple(s["params"].values()) for s in specs] == [(0.5, 0.5), (0.5, 2.0), (1.0, 0.5), (1.0, 2.0)]
    assert all("grid" not in s["doc"] for s in specs)


def test_bad_grid_value_fails_before_running(tmp_path):
    study = _study(tmp_path)
    study.write_text(study.read_text().replace('"machine.error_scale" = [0.5, 2.0]',
                                               '"machine.error_scale" = [0.5, -1.0]'))
    with pytest.raises(ValueError, match=r"study-001\]: machine.error_scale = -1.0"):
        expand([study])


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore")  # dask's own start-up and shut-down warnings
def test_local_cluster_equals_one_by_one(tmp_path):
    pytest.importorskip("dask.distributed", reason="dask[distributed] is not installed (the batch extra)")
    study = _study(tmp_path)
    rows = run_batch([study], tmp_path / "dask", workers=2)
    alone = run_specs(expand([study]), tmp_path / "alone", scheduler="none")
    assert [r["status"] for r in rows] == ["ok"] * 4
    keep = ["run", "cutting.feed_scale", "machine.error_scale", *ERROR_COLUMNS, "cycle_time_original_s",
            "cycle_time_compensated_s"]
    assert [{k: r[k] for k in keep} for r in rows] == [{k: r[k] for k in keep} for r in alone]
    # the grid changes what it should: errors scale with the machine, cycle time with the feed
    by = {(r["cutting.feed_scale"], r["machine.error_scale"]): r for r in rows}
    assert by[(1.0, 2.0)]["volumetric_max_before_mm"] > 3 * by[(1.0, 0.5)]["volumetric_max_before_mm"]
    assert by[(0.5, 0.5)]["cycle_time_original_s"] > 1.5 * by[(1.0, 0.5)]["cycle_time_original_s"]
    with open(tmp_path / "dask" / "batch.csv", newline="") as fh:
        table = list(csv.DictReader(fh))
    assert [t["run"] for t in table] == [r["run"] for r in rows]
    assert float(table[3]["volumetric_max_before_mm"]) == rows[3]["volumetric_max_before_mm"]
    page = (tmp_path / "dask" / "batch.html").read_text()
    assert "batch.png" in page and (tmp_path / "dask" / "batch.png").stat().st_size > 0
    for r in rows:
        assert (tmp_path / "dask" / r["run"] / "report.html").is_file()


def test_bundled_study_expands_to_twelve_runs():
    specs = expand([DEMO / "study.toml"])
    assert len(specs) == 12
    assert specs[-1]["params"] == {"cutting.feed_scale": 1.5, "tool.stick_out_mm": 40.0, "machine.error_scale": 3.0}
    assert specs[-1]["doc"]["tool"] == {"file": "tool.toml", "stick_out_mm": 40.0}


def test_cli_batch_here_and_missing_dask(tmp_path, monkeypatch, capsys):
    from netshape.cli import main

    study = _study(tmp_path)
    study.write_text(study.read_text().replace('"cutting.feed_scale" = [0.5, 1.0]', '"cutting.feed_scale" = [1.0]')
                     .replace('"machine.error_scale" = [0.5, 2.0]', '"machine.error_scale" = [1.0]'))
    assert main(["batch", str(study), "--scheduler", "none", "--out", str(tmp_path / "b"), "--quiet"]) == 0
    assert "1 runs, 0 failed" in capsys.readouterr().out
    with open(tmp_path / "b" / "batch.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert rows[0]["status"] == "ok" and float(rows[0]["volumetric_max_after_mm"]) < 1e-3
    # without dask.distributed: one line naming what to install, exit 2
    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    assert main(["batch", str(study), "--out", str(tmp_path / "c"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "netshape[batch]" in err
