"""The one CLI convention for bad input (netshape.cli._args): every subcommand refuses a bad value with
exactly one stderr line `netshape COMMAND: error: --opt = value: rule [unit]`, nothing on stdout, and exit
code 2; argparse's own errors (not a number, a missing option, a bad choice, an unknown option, a missing
action) are one line too."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

import pytest

from netshape.cli import _args, main

FORCES = ["forces", "--diameter", "10", "--flutes", "2", "--rpm", "6000", "--feed-per-tooth", "0.1",
          "--ap", "3", "--coefficient-set", "leekunhwee_flat_slot", "--csv", "f.csv"]
WALL = ["deflection", "wall", "--diameter", "25", "--flutes", "4", "--helix", "60", "--stick-out", "250",
        "--youngs-modulus", "210000", "--rpm", "600", "--feed-per-tooth", "0.0127", "--ap", "2.5",
        "--ae", "2", "--coefficients", "cho_suh_example"]
PATH_COMMON = ["--tool", "t.toml", "--stock", "s.toml", "--coefficients", "cho_suh_example", "--rpm", "600"]
PLAN = ["plan", "p.ngc", "--vmax", "250", "--amax", "3000", "--rule", "vector", "--json", "o.json"]
POSTURE = ["posture", "plan", "--impeller", "--out", "o"]


def _one_line(capsys, argv: list[str], prefix: str, *needles: str) -> str:
    assert main(argv) == 2
    cap = capsys.readouterr()
    assert cap.out == ""
    lines = cap.err.splitlines()
    assert len(lines) == 1 and cap.err.endswith("\n"), cap.err
    prog = f"netshape {prefix}" if prefix else "netshape"
    assert lines[0].startswith(f"{prog}: error: "), lines[0]
    for n in needles:
        assert n in lines[0], (n, lines[0])
    return lines[0]


# one bad value per subcommand, refused while parsing: option, value and rule with its unit
@pytest.mark.parametrize("argv, prefix, line", [
    (FORCES + ["--diameter", "-3"], "forces", "--diameter = -3: must be positive [mm]"),
    (FORCES + ["--helix", "90"], "forces", "--helix = 90: must be in [0, 85) [deg]"),
    (FORCES + ["--samples", "4"], "forces", "--samples = 4: must be in 8..1000000"),
    (FORCES + ["--flutes", "0"], "forces", "--flutes = 0: must be between 1 and 64"),
    (WALL + ["--youngs-modulus", "0"], "deflection wall", "--youngs-modulus = 0: must be positive [MPa]"),
    (WALL + ["--levels", "2"], "deflection wall", "--levels = 2: must be in 3..10001"),
    (["deflection", "predict", "p.nc", *PATH_COMMON, "--spacing", "0"], "deflection predict",
     "--spacing = 0: must be positive [mm]"),
    (["deflection", "compensate", "p.nc", *PATH_COMMON, "-o", "o.nc", "--discount", "1.5"],
     "deflection compensate", "--discount = 1.5: must be in (0, 1]"),
    (["volumetric", "map", "m.toml", "--grid", "3,0,3"], "volumetric map", "--grid = 3,0,3: must be 3"),
    (["volumetric", "compensate", "p.ngc", "--machine", "m.toml", "-o", "o.nc", "--chord-tolerance", "inf"],
     "volumetric compensate", "--chord-tolerance = inf: must be finite [mm]"),
    (PLAN + ["--vmax", "-3"], "plan", "--vmax = -3: must be positive [mm/s]"),
    (PLAN + ["--lookahead", "1"], "plan", "--lookahead = 1: must be in 2..1000000 [blocks]"),
    (PLAN + ["--ts2", "0"], "plan", "--ts2 = 0: must be in (0, 1] [s]"),
    (PLAN + ["--allowable", "-1"], "plan", "--allowable = -1: must be >= 0 [mm/min]"),
    (PLAN + ["--tolerance", "1e-20"], "plan", "--tolerance = 1e-20: must be >= 1e-06 [mm]"),
    (POSTURE + ["--tilt-max", "95"], "posture plan", "--tilt-max = 95: must be in (0, 90) [deg]"),
    (POSTURE + ["--clearance", "-0.5"], "posture plan", "--clearance = -0.5: must be >= 0 [mm]"),
    (["batch", "study.toml", "--workers", "0"], "batch", "--workers = 0: must be >= 1"),
])
def test_bad_value_is_one_line(tmp_path, monkeypatch, capsys, argv, prefix, line):
    monkeypatch.chdir(tmp_path)
    assert _one_line(capsys, argv, prefix).startswith(f"netshape {prefix}: error: {line}")
    assert not any(tmp_path.iterdir())  # nothing written


# argparse's own errors, and the commands that take no values (info, run, demo, diagnose)
@pytest.mark.parametrize("argv, prefix, needles", [
    (PLAN + ["--vmax", "abc"], "plan", ["--vmax = abc: must be a number [mm/s]"]),
    (FORCES + ["--flutes", "2.5"], "forces", ["--flutes = 2.5: must be an integer"]),
    (PLAN[:-4] + ["--rule", "fast", "--json", "o.json"], "plan",
     ["--rule = fast: must be one of paper, vector"]),
    (FORCES + ["--mode", "climb"], "forces", ["--mode = climb: must be one of up, down, slot"]),
    (["plan", "p.ngc", "--vmax", "1", "--amax", "1"], "plan", ["required", "--rule", "--json"]),
    (PLAN + ["--vmax"], "plan", ["--vmax", "expected one argument"]),
    (["info", "p.ngc", "--jsn"], "info", ["unrecognized arguments: --jsn"]),
    (["run"], "run", ["required", "JOB.toml"]),
    (["demo", "--out"], "demo", ["--out", "expected one argument"]),
    (["diagnose", "bundle/"], "diagnose", ["required", "--json"]),
    (["volumetric"], "volumetric", ["required", "ACTION"]),
    (["volumetric", "draw"], "volumetric", ["ACTION = draw: must be one of map, compensate"]),
    (["nope"], "", ["COMMAND = nope: must be one of info, forces,"]),
    (["posture"], "posture", ["required", "ACTION"]),
    (["deflection", "wall", "--rpm", "600"], "deflection wall", ["required", "--feed-per-tooth"]),
    (POSTURE + ["--surface", "s.json"], "posture plan", ["--surface", "not allowed with", "--impeller"]),
])
def test_argparse_error_is_one_line(tmp_path, monkeypatch, capsys, argv, prefix, needles):
    monkeypatch.chdir(tmp_path)
    _one_line(capsys, argv, prefix, *needles)


# options checked against each other: after parsing, same shape, same prefix
@pytest.mark.parametrize("argv, prefix, line", [
    (FORCES + ["--ae", "12", "--mode", "down"], "forces", "--ae = 12: must not exceed --diameter (10) [mm]"),
    (FORCES + ["--mode", "up"], "forces", "--mode = up: needs --ae"),
    (WALL + ["--stick-out", "2"], "deflection wall",
     "--stick-out = 2: shorter than the axial depth --ap = 2.5"),
    (PLAN + ["--ts1", "0.00015"], "plan", "--ts1 = 0.00015: must be a whole multiple of --ts2 = 0.0001 [s]"),
    (PLAN + ["--smoothed-gcode", "s.ngc"], "plan", "--smoothed-gcode = s.ngc: needs --rule smooth"),
    (POSTURE + ["--obstacles", "w.stl"], "posture plan", "--obstacles = w.stl: not used with --impeller"),
])
def test_cross_option_error_is_one_line(tmp_path, monkeypatch, capsys, argv, prefix, line):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "p.ngc").write_text("G21 G90\nG1 X10 F600\nM30\n")
    assert line in _one_line(capsys, argv, prefix)


def test_help_and_version_return_0(capsys):
    assert main(["plan", "--help"]) == 0
    assert "--vmax" in capsys.readouterr().out
    assert main(["--version"]) == 0


def test_exit_status_of_the_command(tmp_path):
    """The process itself: exit status 2 and one line, no usage block."""
    import netshape

    env = {**os.environ, "PYTHONPATH": str(Path(netshape.__file__).resolve().parents[1])}
    proc = subprocess.run([sys.executable, "-m", "netshape", *PLAN, "--vmax", "abc"], cwd=tmp_path,
                          capture_output=True, text=True, env=env)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr == "netshape plan: error: --vmax = abc: must be a number [mm/s]\n"


def test_validators():
    assert _args.positive("--x", "mm")("2.5") == 2.5
    assert _args.non_negative("--x")("0") == 0.0
    assert _args.real("--x", "deg", gt=-80, lt=80)("-79.5") == -79.5
    assert _args.integer("--n", ge=8, le=10)("10") == 10
    assert _args.counts("--grid", 3, example="9,9,5")("9,9,5") == (9, 9, 5)
    for conv, text, msg in [
        (_args.positive("--x", "mm"), "0", "--x = 0: must be positive [mm]"),
        (_args.positive("--x", "mm"), "nan", "--x = nan: must be finite [mm]"),
        (_args.non_negative("--x", "s"), "-1e-9", "--x = -1e-9: must be >= 0 [s]"),
        (_args.finite("--x"), "-inf", "--x = -inf: must be finite"),
        (_args.real("--x", ge=1), "0.5", "--x = 0.5: must be >= 1"),
        (_args.integer("--n", ge=4), "3", "--n = 3: must be >= 4"),
        (_args.integer("--n"), "", "--n = '': must be an integer"),
        (_args.counts("--grid", 3), "1,2", "--grid = 1,2: must be 3 comma-separated integers >= 1"),
    ]:
        with pytest.raises(argparse.ArgumentTypeError) as exc:
            conv(text)
        assert str(exc.value) == msg
