"""`netshape deflection` never writes NaN/Infinity and sizes path work before it starts (docs/deflection.md,
Limits): a non-finite wall error is one line naming the tool's numbers; a --spacing that puts more than
--max-points points on the program is refused before the stock is built."""

from __future__ import annotations

import time
from pathlib import Path

from netshape.cli import main

DEMO = Path(__file__).resolve().parents[3] / "examples" / "demo"
WALL = ["deflection", "wall", "--diameter", "25", "--flutes", "4", "--helix", "60", "--youngs-modulus", "210000",
        "--rpm", "600", "--feed-per-tooth", "0.0127", "--ap", "2.5", "--ae", "2", "--mode", "down",
        "--coefficients", "cho_suh_example"]


def _one_line(capsys, argv) -> str:
    t0 = time.perf_counter()
    assert main(argv) == 2
    assert time.perf_counter() - t0 < 2.0
    cap = capsys.readouterr()
    lines = cap.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in cap.err, cap.err
    assert cap.out == ""
    return lines[0]


def test_wall_with_a_huge_stick_out_names_it_and_writes_nothing(capsys, tmp_path):
    out = tmp_path / "w.json"
    line = _one_line(capsys, WALL + ["--stick-out", "1e300", "--json", str(out)])
    assert line.startswith("netshape deflection wall: error: --stick-out = 1e+300 "), line
    assert "gives a non-finite result (wall_error_mm." in line and line.endswith("nothing written")
    assert not out.exists()


def test_wall_json_is_strict_for_a_normal_tool(tmp_path):
    import json

    out = tmp_path / "w.json"
    assert main(WALL + ["--stick-out", "250", "--json", str(out)]) == 0
    json.loads(out.read_text(), parse_constant=lambda c: (_ for _ in ()).throw(AssertionError(c)))


def test_predict_spacing_over_the_point_budget_is_refused_first(capsys, tmp_path):
    tool, stock = tmp_path / "t.toml", tmp_path / "s.toml"
    tool.write_text((DEMO / "tool.toml").read_text())
    stock.write_text("min_mm = [-30, -25, -20]\nmax_mm = [30, 25, 0]\nspacing_mm = 0.25\n")
    for action, extra in (("predict", []), ("compensate", ["-o", str(tmp_path / "c.nc")])):
        line = _one_line(capsys, ["deflection", action, str(DEMO / "part.ngc"), "--tool", str(tool), "--stock",
                                  str(stock), "--coefficients", "cho_suh_example", "--rpm", "8000",
                                  "--spacing", "1e-6", *extra])
        assert line.startswith(f"netshape deflection {action}: error: --spacing = 1e-06: gives "), line
        assert "path points along" in line and "over the limit of 2000000" in line
    assert not (tmp_path / "c.nc").exists()
