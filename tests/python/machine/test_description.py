"""Machine TOML and controller tables: good files load, bad ones fail with a clear message."""

from __future__ import annotations

from pathlib import Path

import pytest

import netshape as ns

ROOT = Path(__file__).resolve().parents[3]
MACHINES = ROOT / "examples" / "machines"


def test_example_machines_load():
    hmc = ns.machine.load_machine(MACHINES / "hmc_yang_kweon.toml")
    assert list(hmc.tool_chain) == [0, 1] and list(hmc.workpiece_chain) == [2]
    assert hmc.axes[0].errors[0].kind == ns.machine.ErrorFunction.Kind.polynomial
    vmc = ns.machine.load_machine(MACHINES / "vmc.toml")
    assert list(vmc.tool_chain) == [2] and list(vmc.workpiece_chain) == [1, 0]
    assert vmc.axes[0].errors[0].kind == ns.machine.ErrorFunction.Kind.table
    assert vmc.axes[2].errors[0].out_of_range == ns.machine.OutOfRange.clamp
    tab = ns.machine.read_error_table(MACHINES / "vmc_x_errors.csv")
    assert tab["axis"] == "X" and set(tab["components"]) == set(ns.machine.iso_names("X"))
    assert list(vmc.axes[0].errors[0].positions) == tab["positions"]


BASE = 'tool_chain = ["X", "Y"]\nworkpiece_chain = ["Z"]\n'


@pytest.mark.parametrize(
    "text, message",
    [
        (BASE + '[axes.X.polynomials]\nEXY_mm = [0.0]\n', "'EXY_mm' is not an error component of axis X"),
        (BASE + '[axes.X.polynomials]\nEXX = [0.0]\n', "needs a unit suffix"),
        (BASE + '[axes.X.polynomials]\nEAX_mm = [0.0]\n', "needs a unit suffix"),
        (BASE + '[axes.X.polynomials]\nEXX_mm = [nan]\n', "must be a finite number"),
        (BASE + '[axes.X.polynomials]\nEXX_mm = [inf]\n', "must be a finite number"),
        (BASE + '[axes.X]\ntravel_mm = [10.0, -10.0]\n', "min must be below max"),
        (BASE + '[axes.X]\nout_of_range = "wrap"\n', "out_of_range = 'wrap'"),
        (BASE + '[axes.X]\ntable = { X_mm = [0.0, 2.0, 1.0], EXX_mm = [0.0, 0.0, 0.0] }\n',
         "strictly increasing"),
        (BASE + '[axes.X]\ntable = { X_mm = [0.0, 1.0], EXX_mm = [0.0] }\n', "must be a list of 2 numbers"),
        (BASE + '[axes.X]\ntable = { X_mm = [0.0, 1.0], EXX_mm = [0.0, 1.0] }\n'
                '[axes.X.polynomials]\nEXX_mm = [0.0]\n', "already given"),
        (BASE + '[axes.W]\n', "unknown axis"),
        (BASE + '[axes.X]\ntravle_mm = [0, 1]\n', "unknown key 'travle_mm'"),
        (BASE + 'colour = "red"\n', "unknown key 'colour'"),
        ('tool_chain = ["X", "Y"]\nworkpiece_chain = ["Y", "Z"]\n', "exactly once"),
        ('tool_chain = ["X", "Q"]\nworkpiece_chain = ["Z"]\n', "is not X, Y or Z"),
        ('tool_chain = ["X", "Y"]\n', "missing 'workpiece_chain'"),
        (BASE + '[tool]\ndirection = [0.0, 0.0, 2.0]\n', "must be a unit vector"),
        (BASE + '[tool]\nlength_mm = -5.0\n', "must be ≥ 0"),
        (BASE + '[squareness]\nEC0X_rad = 1e-5\n', "unknown key 'EC0X_rad'"),
        (BASE + 'tool_chain_x = 1\n', "unknown key"),
        ("tool_chain = [\n", "not valid TOML"),
    ],
)
def test_bad_toml_is_refused_with_a_clear_message(tmp_path, text, message):
    f = tmp_path / "m.toml"
    f.write_text(text)
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace("[", r"\[")):
        ns.machine.load_machine(f)


@pytest.mark.parametrize(
    "csv, message",
    [
        ("X_mm,EXX_mm\n0,0\n1,0\n1,0\n", "row 4 X_mm = 1.0: positions must be strictly increasing"),
        ("X_mm,EXX_mm\n0,0\n1,nan\n", "row 3 EXX_mm"),
        ("X_mm,EXX_mm,EQX_mm\n0,0,0\n1,0,0\n", "'EQX_mm' is not an error component"),
        ("Y_mm,EYY_mm\n0,0\n1,0\n", "table is for axis Y, expected axis X"),
        ("pos,EXX_mm\n0,0\n1,0\n", "must be the axis position"),
        ("X_mm,EXX_mm\n0,0\n", "at least 2 rows"),
        ("X_mm,EXX_mm\n0,0\n1\n", "row 3 has 1 values"),
        ("X_mm,EXX_mm,EXX_um\n0,0,0\n1,0,0\n", "appears twice"),
    ],
)
def test_bad_tables_are_refused(tmp_path, csv, message):
    (tmp_path / "x.csv").write_text(csv)
    f = tmp_path / "m.toml"
    f.write_text(BASE + '[axes.X]\ntable = "x.csv"\n')
    with pytest.raises(ValueError, match=message.replace("(", r"\(")):
        ns.machine.load_machine(f)


def test_missing_files(tmp_path):
    with pytest.raises(FileNotFoundError):
        ns.machine.load_machine(tmp_path / "nope.toml")
    f = tmp_path / "m.toml"
    f.write_text(BASE + '[axes.X]\ntable = "nope.csv"\n')
    with pytest.raises(FileNotFoundError):
        ns.machine.load_machine(f)
