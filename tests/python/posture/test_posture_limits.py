"""`netshape posture plan` refuses more CC points than it can plan (docs/posture.md, Limits), while
parsing, with one line naming --points and the limit."""

from __future__ import annotations

import time

from netshape.cli import main


def test_ten_million_points_are_refused_at_once(capsys, tmp_path):
    t0 = time.perf_counter()
    assert main(["posture", "plan", "--impeller", "--out", str(tmp_path / "o"), "--points", "10000000"]) == 2
    assert time.perf_counter() - t0 < 2.0
    cap = capsys.readouterr()
    assert cap.err.strip() == "netshape posture plan: error: --points = 10000000: must be in 4..100000"
    assert not (tmp_path / "o").exists()
