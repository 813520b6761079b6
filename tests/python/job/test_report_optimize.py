"""The job's report shows its ``[optimize]`` results (issue 41, docs/feeds.md): cycle time before and
after, the saving, pieces per binding limit, the largest force, the re-simulated checks, and the
feed/force plot."""

from __future__ import annotations

import re

from netshape.job.report import optimize_rows
from netshape.job.run import run_job
from netshape.job.spec import job_from_dict

PROGRAM = """G21 G90 G17 G94
S6000 M3
G0 X-40 Y0 Z5
G1 Z-3 F600
G1 X35 F1200
G0 Z5
M30
"""
TOOL = ('kind = "flat"\ndiameter_mm = 10.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0\n'
        'stick_out_mm = 40.0\n')


def test_report_html_shows_the_optimize_results(tmp_path):
    (tmp_path / "t.ngc").write_text(PROGRAM)
    (tmp_path / "tool.toml").write_text(TOOL)
    doc = {"program": "t.ngc", "tool": "tool.toml", "coefficients": "leekunhwee_flat_slot",
           "stock": {"min_mm": [-30.0, -20.0, -10.0], "max_mm": [30.0, 20.0, 0.0], "spacing_mm": 0.5},
           "predict": ["feed_plan"],
           "limits": {"vmax_mm_s": 500.0, "amax_mm_s2": 5000.0},
           "cutting": {"samples_per_revolution": 36, "disk_height_mm": 0.25, "step_mm": 1.0},
           "report": {"plots": True, "zmap_stl": False},
           "optimize": {"max_force_N": 400.0, "max_feed_mm_min": 20000.0}}
    job = job_from_dict(doc, source=str(tmp_path / "job.toml"), base_dir=tmp_path)
    summary = run_job(job, tmp_path / "out")
    page = (tmp_path / "out" / "report.html").read_text()
    assert 'id="optimize"' in page
    cells = dict(re.findall(r'data-key="(optimize\.[^"]+)">([^<]*)<', page))
    o = summary["optimize"]
    for key in ("optimize.cycle_time_s.original", "optimize.cycle_time_s.optimized", "optimize.saving_percent",
                "optimize.binding.max_force_N", "optimize.max_force_N.optimized",
                "optimize.check.max_force_N.ratio"):
        assert key in cells, (key, sorted(cells))
    optimized = float(f"{o['cycle_time_s']['optimized']:.6g}")
    assert float(cells["optimize.cycle_time_s.optimized"]) == optimized
    assert int(cells["optimize.binding.max_force_N"]) == o["binding"]["max_force_N"] >= 1
    assert len(cells) == len(optimize_rows(summary))
    assert (tmp_path / "out" / "feeds.png").stat().st_size > 1000
    assert 'src="feeds.png"' in page
    assert summary["files"]["plot_optimize"] == "feeds.png"
