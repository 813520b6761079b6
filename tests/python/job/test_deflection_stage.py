"""The deflection stage: with the prediction replaced by a stand-in with known values its figures reach
the summary, the total combines both sources and the compensations are applied deflection first; a
tool the model cannot take is reported (figures null, not zero)."""

from __future__ import annotations

import shutil
import sys

import numpy as np
import pytest

import netshape
from netshape.job import job_from_dict, run_job
from netshape.job import stage_deflection as sd
from netshape.job import stages as st
from netshape.job.program import stage_program

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


class _Errors:
    def __init__(self, n, middle):
        self.error = np.column_stack([np.full(n, middle / 2), np.full(n, middle), np.full(n, 2 * middle)])
        self.depth = np.full(n, 3.0)
        self.engaged = np.ones(n, dtype=np.int32)
        self.wall_flags = np.full(n, 3, dtype=np.int32)  # both wall angles in the window


def _fake_api(monkeypatch, calls):
    """Stand-ins for the deflection area's contour API with known answers: 20 µm wall error at the
    middle level before, 1 µm after (the written program's check); the compensated contour is the
    nominal one. The final-wall rule itself runs for real on the stand-in's points."""
    from types import SimpleNamespace

    import netshape.deflection.checked as checked

    def setup_path(program, cutter, stock, *, coefficients, rpm, spacing, feed_per_tooth=None):
        calls.append(("setup", len(program.blocks), rpm))
        pts, owner = [np.asarray(program.blocks[0].start)], [0]
        for i, b in enumerate(program.blocks):
            k = max(1, int(np.ceil(b.length() / spacing)))
            pts += [np.asarray(b.point_at(j / k)) for j in range(1, k + 1)]
            owner += [i] * k
        if stock.max_height() < -5.5 and program.blocks[0].start[2] > -4:
            raise ValueError("program: the contour never touches the stock")
        return SimpleNamespace(nominal=np.array(pts), program=program, owner=np.array(owner),
                               side=netshape.deflection.WallSide.right)

    def predict_path(setup):
        return _Errors(len(setup.nominal), 0.020)

    def check(setup, middle):
        n = len(setup.nominal)
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(setup.nominal[:, :2], axis=0).T))])
        return SimpleNamespace(s=arc, error=_Errors(n, middle).error, final=np.ones(n, dtype=bool),
                               engaged=np.ones(n, dtype=bool), points=setup.nominal)

    def compensate_checked(setup, *, scheme, level, tolerance, later_program, block_offset):
        calls.append(("compensate", scheme, level))
        blocks = list(setup.program.blocks)
        return SimpleNamespace(result=SimpleNamespace(converged=True, message="", iterations=4), converged=True,
                               blocks=blocks, origin=list(range(len(blocks))), before=check(setup, 0.020),
                               check=check(setup, 0.001), before_mm={"bottom": 0.01, "middle": 0.02, "top": 0.04},
                               after_mm={"bottom": 0.0005, "middle": 0.001, "top": 0.002})

    monkeypatch.setattr(netshape.deflection, "setup_path", setup_path)
    monkeypatch.setattr(netshape.deflection, "predict_path", predict_path)
    monkeypatch.setattr(checked, "compensate_checked", compensate_checked)


def test_contour_runs_of_the_demo_pocket():
    """The pocket: at each of the two levels the clearing rings and the finishing contour form one run
    of XY moves at one Z (the plunge, rapids and the ramped lead-out are not contours)."""
    import netshape.toolpath as tpm

    tp = tpm.read_gcode(DEMO / "part.ngc")
    runs = sd.contour_runs(tp)
    assert len(runs) == 2
    for first, last in runs:
        zs = {round(float(b.start[2]), 9) for b in tp.blocks[first:last + 1]}
        assert len(zs) == 1 and tp.blocks[first - 1].kind == tpm.MotionKind.line  # after the plunge
    assert [round(float(tp.blocks[f].start[2]), 6) for f, _ in runs] == [-3.0, -6.0]


def test_a_present_prediction_reaches_the_summary(tmp_path, monkeypatch):
    calls = []
    _fake_api(monkeypatch, calls)
    s = run_job(_job(tmp_path), tmp_path / "out")
    assert [c for c in calls if c[0] == "setup"] == [("setup", 25, 8000.0), ("setup", 25, 8000.0)]
    assert ("compensate", "accelerated", "middle") in calls  # the demo job's scheme
    d = s["errors"]["deflection"]
    assert d["max_before_mm"] == pytest.approx(0.020) and d["max_after_mm"] == pytest.approx(0.001)
    v = s["errors"]["volumetric"]
    t = s["errors"]["total"]
    # on the final walls the errors add along the wall normal: within the machine's error of the wall
    # error before; after, the volumetric residual is added in the adverse direction
    assert 0.020 - v["max_before_mm"] <= t["max_before_mm"] <= 0.020 + v["max_before_mm"] + 1e-12
    assert 0.001 <= t["max_after_mm"] <= 0.001 + v["max_after_mm"] + 1e-12
    assert t["max_after_mm"] < t["max_before_mm"]
    # the per-contour block: the rings are not final walls, the finishing passes are
    contours = s["deflection"]["contours"]
    assert [c["final_wall"] for c in contours].count(True) >= 1
    assert all(c["converged"] for c in contours if c["final_wall"])
    assert s["job"]["compensations"] == ["deflection", "volumetric"]
    assert s["stages"]["deflection"] == "ok"


def test_ball_end_mill_is_reported_not_available(tmp_path, monkeypatch):
    _fake_api(monkeypatch, [])
    job = _job(tmp_path)
    job.tool = dict(job.tool, kind="ball", corner_radius_mm=3.0)
    job.coefficients = "kim_zas_ball12"
    res = sd.stage_deflection(job, st.stage_stock(job), stage_program(job), compensate=True)
    assert not res.available and "flat end mill" in res.reason


def test_unconverged_points_carry_their_contour_pieces_line_and_count_the_rest():
    # one run of two pieces: blocks 0–1 (line 18, not a final wall) and blocks 2–3 (line 36, final); the
    # samples 0.5 mm apart, sample k ending block owner[k]; the final piece's first point (the corner,
    # the end of block 1) counts as final, so the check misses the tolerance from x = 1.5 mm on
    from types import SimpleNamespace

    arc = 0.5 * np.arange(10)
    owner = np.array([0, 0, 1, 1, 2, 2, 2, 3, 3, 3])
    pieces = [{"line": 18, "final_wall": False, "first_block": 0, "last_block": 1, "points": slice(0, 4)},
              {"line": 36, "final_wall": True, "first_block": 2, "last_block": 3, "points": slice(4, 10)}]
    s = np.linspace(0.0, 4.5, 37)
    err = np.zeros((37, 3))
    err[:, 1] = np.where(s > 1.5, 1e-3 * (6.0 - s), 0.0)  # the largest just after the corner
    check = SimpleNamespace(s=s, error=err, final=s > 1.5, points=np.c_[s, np.zeros(37), np.zeros(37)])
    pts, left_out = sd.unconverged_points(check, 1, 5e-4, pieces, arc, owner, limit=5)
    assert {p["line"] for p in pts} == {36}  # the stretch from the corner is block 2's: line 36
    assert [p["x_mm"] for p in pts] == pytest.approx([1.625, 1.75, 1.875, 2.0, 2.125])  # the largest first
    assert left_out == int(np.sum(s > 1.5)) - 5
