"""The stock example runs (small grid) and gives the slot engagement it promises."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "stock_zmap.py"


def test_example_runs(tmp_path):
    spec = importlib.util.spec_from_file_location("stock_zmap_example", EXAMPLE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    r = mod.main(["--out", str(tmp_path), "--spacing", "0.25"])
    assert (tmp_path / "stock_zmap.stl").stat().st_size > 84
    assert (tmp_path / "stock_zmap.png").stat().st_size > 0
    assert r["slot_axial_depth_mm"] == pytest.approx(4.0)
    assert abs(r["slot_phi_st_deg"]) < 15 and abs(r["slot_phi_ex_deg"] - 180) < 15
    assert r["volume_mm3"] == pytest.approx(80 * 70 * 20 - r["removed_mm3"], rel=1e-9)
