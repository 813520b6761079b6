"""`netshape run` on ../shared/data/gcode/3D_Chips.ngc (a 3-D ball-nose finishing program, 4 700 lines)
with every prediction and both compensations asked for (job file tests/python/job/data/chips_job.toml,
coarse Z-map and sample spacings). Skips where the shared data is absent."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from netshape.job import job_from_dict, run_job

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

DATA = Path(__file__).resolve().parent / "data"


def chips_job(shared_data: Path, **cutting):
    program = shared_data / "gcode" / "3D_Chips.ngc"
    if not program.is_file():
        pytest.skip(f"{program} is absent")
    doc = tomllib.loads((DATA / "chips_job.toml").read_text())
    doc["program"] = str(program)
    doc["cutting"].update(cutting)
    return job_from_dict(doc, source=str(DATA / "chips_job.toml"), base_dir=DATA)


@pytest.mark.slow
@pytest.mark.shared_data
def test_3d_chips_all_predictions(shared_data, tmp_path):
    job = chips_job(shared_data)
    s = run_job(job, tmp_path)
    assert s["job"]["predictions"] == ["forces", "deflection", "volumetric", "feed_plan"]
    e = s["errors"]
    assert e["volumetric"]["max_after_mm"] < 0.01 * e["volumetric"]["max_before_mm"]
    assert e["total"]["max_after_mm"] < e["total"]["max_before_mm"]
    # a ball nose: the deflection model (flat end mills) says why it has no figures, it does not report 0
    assert e["deflection"]["max_before_mm"] is None
    assert s["stages"]["deflection"] == "skipped"
    assert "flat end mill" in s["deflection"]["reason"]
    # a ball nose of 10 mm in aluminium-like coefficients: forces of tens to hundreds of newtons
    assert 10 < s["forces"]["max_peak_resultant_N"] < 5000
    assert s["cycle_time_s"]["original"] > 0 and s["cycle_time_s"]["compensated"] > 0
    for f in s["files"].values():
        assert (tmp_path / f).is_file()
    assert (tmp_path / "3D_Chips_compensated.ngc").stat().st_size > 100_000
