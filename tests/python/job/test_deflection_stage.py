"""The deflection stage: in a build without netshape.deflection's path prediction it says so (figures
null, not zero); with a prediction present (here a stand-in with known values) its figures reach the
summary, the total combines both sources and the compensations are applied deflection first."""

from __future__ import annotations

import math
import shutil
import sys

import numpy as np
import pytest

import netshape
from netshape.job import job_from_dict, run_job
from netshape.job import stages as st

from .conftest import DEMO

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


def _job(tmp_path):
    shutil.copytree(DEMO, tmp_path / "demo")
    doc = tomllib.loads((tmp_path / "demo" / "job.toml").read_text())
    doc["predict"] = {"forces": True, "deflection": True, "volumetric": True, "feed_plan": False}
    doc["cutting"].update(step_mm=2.0, samples_per_revolution=12, disk_height_mm=1.0)
    doc["stock"]["spacing_mm"] = 1.0
    doc["report"] = {"dpi": 30, "zmap_stl": False}
    return job_from_dict(doc, source="job.toml", base_dir=tmp_path / "demo")


def test_missing_prediction_is_reported_not_zero(tmp_path, monkeypatch):
    for name in st.DEFLECTION_PREDICT_NAMES:
        monkeypatch.delattr(netshape.deflection, name, raising=False)
    s = run_job(_job(tmp_path), tmp_path / "out")
    assert all(v is None for v in s["errors"]["deflection"].values())
    assert s["stages"]["deflection"].endswith("not available in this build")
    assert s["errors"]["total"] == s["errors"]["volumetric"]
    assert "not available in this build" in (tmp_path / "out" / "report.html").read_text()


class _Prediction:
    def __init__(self, positions, error):
        self.positions = positions
        self.error = error           # (n, 3): bottom, middle, top [mm]


def test_a_present_prediction_reaches_the_summary(tmp_path, monkeypatch):
    calls = []

    def predict(stock, cutter, program, coefficients, *, spacing, **kw):
        calls.append("predict")
        ends = np.array([b.end for b in program.blocks])
        err = np.column_stack([np.full(len(ends), 0.010), np.full(len(ends), 0.020), np.full(len(ends), 0.030)])
        return _Prediction(ends, err)

    class Comp:
        def __init__(self, program):
            self.toolpath = program
            self.after = {"middle": np.full(len(program.blocks), 0.001)}
            self.iterations = 3

    def compensate(stock, cutter, program, coefficients, *, scheme, level, spacing, **kw):
        calls.append(("compensate", scheme, level))
        return Comp(program)

    monkeypatch.setattr(netshape.deflection, "predict_program", predict, raising=False)
    monkeypatch.setattr(netshape.compensation, "compensate_deflection_program", compensate, raising=False)
    s = run_job(_job(tmp_path), tmp_path / "out")
    assert calls[0] == "predict" and calls[1] == ("compensate", "integrated", "middle")
    d = s["errors"]["deflection"]
    assert d["max_before_mm"] == pytest.approx(0.020) and d["max_after_mm"] == pytest.approx(0.001)
    v = s["errors"]["volumetric"]
    t = s["errors"]["total"]
    # root sum of squares per point: bounded by the sources' maxima
    assert max(0.020, v["max_before_mm"]) <= t["max_before_mm"] <= math.hypot(0.020, v["max_before_mm"]) + 1e-12
    assert t["max_after_mm"] < t["max_before_mm"]
    assert s["job"]["compensations"] == ["deflection", "volumetric"]
    assert s["stages"]["deflection"] == "ok"
