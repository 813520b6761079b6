"""`netshape volumetric` sizes its work before it starts (docs/machine.md, Limits) and never writes NaN or
Infinity: a map of more than --max-points points, a compensation of more than --max-chords moves, and a
machine whose error model is not finite are refused with one line, before anything is written."""

from __future__ import annotations

import json
import time
from pathlib import Path

import pytest

from netshape.cli import main

DEMO = Path(__file__).resolve().parents[3] / "examples" / "demo"


def _refused(capsys, argv, *needles) -> str:
    t0 = time.perf_counter()
    code = main(argv)
    elapsed = time.perf_counter() - t0
    cap = capsys.readouterr()
    assert code == 2, cap
    lines = [ln for ln in cap.err.strip().splitlines() if ": warning: " not in ln]  # the reader's, once each
    assert len(lines) == 1 and "Traceback" not in cap.err, cap.err
    assert cap.out == ""
    for n in needles:
        assert n in lines[0], (n, lines[0])
    assert elapsed < 2.0, elapsed
    return lines[0]


def test_a_grid_over_max_points_is_refused_before_the_map(capsys, tmp_path):
    out = tmp_path / "m.json"
    _refused(capsys, ["volumetric", "map", str(DEMO / "machine.toml"), "--grid", "300,300,300", "--json", str(out)],
             "netshape volumetric map: error: --grid = 300,300,300: gives 27000000 map points, over the limit of "
             "2000000; raise --max-points")
    assert not out.exists()


def test_max_points_sets_the_limit(capsys, tmp_path):
    _refused(capsys, ["volumetric", "map", str(DEMO / "machine.toml"), "--grid", "9,9,5", "--max-points", "100"],
             "--grid = 9,9,5: gives 405 map points, over the limit of 100")
    _refused(capsys, ["volumetric", "map", str(DEMO / "machine.toml"), "--program", str(DEMO / "part.ngc"),
                      "--max-points", "10"], f"--program = {DEMO / 'part.ngc'}: gives")


def test_a_tiny_chord_tolerance_is_refused_before_the_compensation(capsys, tmp_path):
    out = tmp_path / "c.ngc"
    _refused(capsys, ["volumetric", "compensate", str(DEMO / "part.ngc"), "--machine", str(DEMO / "machine.toml"),
                      "-o", str(out), "--chord-tolerance", "1e-12"],
             "--chord-tolerance = 1e-12: gives", "compensated moves", "over the limit of 20000000")
    assert not out.exists()


def test_the_chord_estimate_is_near_the_real_count(tmp_path):
    from netshape import compensation as nc
    from netshape import machine as nm
    from netshape import toolpath

    m = nm.load_machine(DEMO / "machine.toml")
    off = {"work_offsets": {"G54": [-150, 80, -300]}}
    for tol in (0.002, 0.0002):
        a = toolpath.read_gcode_arrays(DEMO / "part.ngc", arcs="keep", **off)
        est = nc.estimate_chords(m, a, tol)
        rep = nc.compensate_gcode(m, DEMO / "part.ngc", tmp_path / "c.ngc", chord_tolerance=tol, **off)
        assert rep.blocks_out / 4 <= est <= 4 * rep.blocks_out + 10, (tol, est, rep.blocks_out)


@pytest.mark.parametrize("edit, needle", [
    (("EXX_mm = [0.002, 2.5e-5]", "EXX_mm = [0.002, 2.5e-5, 0, 0, 1e300]"), "its error model gives a non-finite"),
    (("length_mm = 100.0", "length_mm = 1e300"), "tool.length_mm = 1e+300"),
])
def test_a_non_finite_map_is_an_error_naming_the_machine(capsys, tmp_path, edit, needle):
    m = tmp_path / "m.toml"
    m.write_text((DEMO / "machine.toml").read_text().replace(*edit))
    out = tmp_path / "m.json"
    _refused(capsys, ["volumetric", "map", str(m), "--json", str(out)], f"{m}: ", needle)
    assert not out.exists()


def test_map_json_is_strict(tmp_path):
    out = tmp_path / "m.json"
    assert main(["volumetric", "map", str(DEMO / "machine.toml"), "--grid", "3,3,2", "--json", str(out)]) == 0
    json.loads(out.read_text(), parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
