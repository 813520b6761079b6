"""`netshape volumetric` and examples/volumetric_yang_kweon.py run end to end (small sizes)."""

from __future__ import annotations

import json
import runpy
from pathlib import Path

import numpy as np
import pytest

import netshape as ns
from netshape.cli import main

ROOT = Path(__file__).resolve().parents[3]
HMC = ROOT / "examples" / "machines" / "hmc_yang_kweon.toml"
VMC = ROOT / "examples" / "machines" / "vmc.toml"


def test_cli_map(tmp_path, capsys):
    rc = main(["volumetric", "map", str(VMC), "--grid", "3,3,2", "--plot", str(tmp_path / "m.png"),
               "--json", str(tmp_path / "m.json")])
    assert rc == 0
    assert (tmp_path / "m.png").stat().st_size > 1000
    d = json.loads((tmp_path / "m.json").read_text())
    assert d["summary"]["points"] == 18 and len(d["errors_mm"]) == 18
    assert "volumetric error" in capsys.readouterr().out


def test_cli_map_along_program(tmp_path):
    src = tmp_path / "p.ngc"
    src.write_text("G0 X-100 Y-100 Z-50\nG1 X100 F600\nG2 X100 Y100 I0 J100\nM30\n")
    assert main(["volumetric", "map", str(VMC), "--program", str(src), "--json", str(tmp_path / "m.json")]) == 0
    d = json.loads((tmp_path / "m.json").read_text())
    assert d["summary"]["points"] > 10
    m = ns.machine.load_machine(VMC)
    np.testing.assert_allclose(d["errors_mm"][1], ns.machine.tip_error(m, [[-100.0, -100.0, -50.0]])[0], atol=1e-15)


def test_cli_compensate(tmp_path):
    src = tmp_path / "p.ngc"
    src.write_text("G21 G90\nG0 X-100 Y-100 Z-50\nG1 Z-100 F600\nG1 X200 Y100\nG2 X200 Y-100 I0 J-100\nM30\n")
    out = tmp_path / "o.nc"
    rc = main(["volumetric", "compensate", str(src), "--machine", str(VMC), "-o", str(out),
               "--chord-tolerance", "0.001", "--json", str(tmp_path / "r.json")])
    assert rc == 0
    tp = ns.toolpath.read_gcode(out)
    m = ns.machine.load_machine(VMC)
    act = ns.machine.actual_points(m, np.array([tp.blocks[-1].end]))
    np.testing.assert_allclose(act[0], [200.0, -100.0, -100.0], atol=1e-9)


@pytest.mark.parametrize(
    "argv, message",
    [
        (["volumetric", "map", "nope.toml"], "no such file"),
        (["volumetric", "compensate", "p.ngc", "--machine", str(VMC), "-o", "o.nc", "--chord-tolerance", "-1"],
         "chord-tolerance"),
        (["volumetric", "map", "bad.toml"], "unknown key"),
    ],
)
def test_cli_bad_input_exits_2(tmp_path, monkeypatch, capsys, argv, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "p.ngc").write_text("G1 X1 F100\n")
    (tmp_path / "bad.toml").write_text('tool_chain = ["X"]\nworkpiece_chain = ["Y", "Z"]\nfoo = 1\n')
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_cli_grid_syntax(capsys):
    assert main(["volumetric", "map", str(VMC), "--grid", "3,3"]) == 2
    assert "--grid = 3,3" in capsys.readouterr().err


def test_example_volumetric_yang_kweon(tmp_path):
    mod = runpy.run_path(str(ROOT / "examples" / "volumetric_yang_kweon.py"))
    s = mod["run"](tmp_path, n=9)
    assert s["after_um"][1] <= 1e-6  # ≤ 1e-9 mm
    assert 10.0 < s["before_um"][0] < s["before_um"][1] < 2000.0
    for f in ("fig6_error_map.png", "fig7_offset_before_x10.png", "fig8_error_after.png",
              "fig10_before_after_x10.png", "compensated.ngc", "summary.json"):
        assert (tmp_path / f).exists()
    m = ns.machine.load_machine(HMC)
    nominal = ns.toolpath.read_gcode(tmp_path / "nominal.ngc")
    comp = ns.toolpath.read_gcode(tmp_path / "compensated.ngc")
    a = ns.machine.actual_points(m, np.array([comp.blocks[-1].end]))[0]
    np.testing.assert_allclose(a, nominal.blocks[-1].end, atol=1e-9)
