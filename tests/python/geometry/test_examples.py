"""The geometry example runs (small sizes) so it cannot rot."""

from __future__ import annotations

import importlib.util
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]


def test_dome_raster_example(tmp_path):
    spec = importlib.util.spec_from_file_location("ex_geom", REPO / "examples" / "geometry_dome_raster.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    s = mod.main(["--out", str(tmp_path), "--scallop", "0.05", "--radius", "20"])
    assert s["offset_distance_error_mm"] < 1e-8
    assert s["raster_blocks"] > 50 and s["gcode_blocks_read_back"] >= s["raster_blocks"]
    assert (tmp_path / "cap_raster.ngc").is_file() and (tmp_path / "pocket.ngc").is_file()
