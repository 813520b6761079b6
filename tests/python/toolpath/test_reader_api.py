"""Python surface of netshape.toolpath: errors with positions, bad input, writer atomicity, reprs."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest

import netshape as ns
from netshape.cli import main as cli_main

tp_mod = ns.toolpath


def _child_env():
    """Environment for a child `python -m netshape` that imports this same netshape."""
    from pathlib import Path as _P

    root = str(_P(ns.__file__).parent.parent)
    return dict(os.environ, PYTHONPATH=os.pathsep.join([root, os.environ.get("PYTHONPATH", "")]))


def test_parse_error_has_position_and_reason():
    with pytest.raises(ns.ParseError) as err:
        tp_mod.parse_gcode("G0 X1\nG1 X2 G7 F100\n", source="prog.ngc")
    e = err.value
    assert isinstance(e, ValueError)
    assert (e.source, e.line, e.column, e.reason) == ("prog.ngc", 2, 7, "unknown G-code G7")
    assert str(e) == "prog.ngc:2:7: unknown G-code G7"


@pytest.mark.parametrize(
    "text, needle",
    [
        ("G0 X[SQRT[-1]]", "SQRT of a negative"),
        ("G0 X[0/0]", "division by zero"),
        ("G0 X[" + "[" * 5000 + "1", "nested deeper"),
        ("G0 X5\nG2 X0 Y5.2 I-5 F60", "arc radius mismatch: start radius 5.000 mm, end radius 5.200 mm"),
        ("G0 X5\nG2 X5 R3 F60", "R arc with coincident end points"),
        ("G41 D1", "cutter radius compensation G41"),
        ("G83 X1 Y1 Z-1 R1 Q1", "canned cycle G83"),
        ("G92 X0", "G92"),
        ("G93", "inverse-time"),
        ("O100 while [1 LT 2]", "o-word control flow .while."),
        ("O100 sub", "o100 sub is not closed by o100 endsub"),
        ("G0 B10", "axis word B"),
    ],
)
def test_refusals(text, needle):
    with pytest.raises(ns.ParseError, match=needle.replace("[", r"\[").replace("(", r"\(")):
        tp_mod.parse_gcode(text)


def test_read_options_are_checked(tmp_path):
    with pytest.raises(ValueError, match="arcs"):
        tp_mod.parse_gcode("G0 X1", arcs="chords")
    with pytest.raises(ValueError, match="chord_tolerance"):
        tp_mod.parse_gcode("G0 X1", arcs="split", chord_tolerance=0)
    with pytest.raises(FileNotFoundError):
        tp_mod.read_gcode(tmp_path / "missing.ngc")
    with pytest.raises(IsADirectoryError):
        tp_mod.read_gcode(tmp_path)


def test_split_arcs_and_arrays():
    text = "G0 X10\nG3 X-10 Y0 I-10 F600\n"
    keep = tp_mod.parse_gcode_arrays(text)
    assert keep["kind"].tolist() == [0, 2]
    assert keep["feed"][1] == pytest.approx(10.0)
    np.testing.assert_allclose(keep["center"][1], [0, 0, 0], atol=1e-12)
    split = tp_mod.parse_gcode_arrays(text, arcs="split", chord_tolerance=0.01)
    n = tp_mod.chord_count(10.0, np.pi, 0.01)
    assert len(split["kind"]) == 1 + n
    mid = 0.5 * (split["start"][1:] + split["end"][1:])
    dev = 10.0 - np.hypot(mid[:, 0], mid[:, 1])
    assert dev.max() <= 0.01 + 1e-12
    assert tp_mod.parse_gcode(text, arcs="split", chord_tolerance=0.01)[-1].end[0] == -10.0


def test_write_is_atomic(tmp_path):
    tp = tp_mod.parse_gcode("G0 X1\nG1 Y2 F100\n")
    target = tmp_path / "out.ngc"
    target.write_text("old")
    bad = tp_mod.Toolpath()
    b = tp_mod.Block()
    b.end = np.array([np.nan, 0.0, 0.0])
    bad.blocks = [b]
    with pytest.raises(ValueError, match="block.end"):
        tp_mod.write_gcode(bad, target)
    assert target.read_text() == "old"
    assert list(tmp_path.iterdir()) == [target]
    tp_mod.write_gcode(tp, target, header_comment="made (by) test")
    text = target.read_text()
    assert text.startswith("(made  by  test)\nG21 G90 G17 G94 G91.1\n") and text.endswith("M2\n")


def test_reprs_and_summary_dict():
    tp = tp_mod.parse_gcode("G0 X1\nG2 X3 Y0 R1 F60\nG4 P2\n", source="r.ngc")
    assert repr(tp) == "Toolpath(2 blocks, source='r.ngc')"
    assert repr(tp[1]).startswith("Block(arc, start=(1, 0, 0), end=(3, 0, 0), center=(2, 0, 0), G2 G17")
    s = tp.summary()
    assert "feed_length=3.14159 mm" in repr(s)
    d = s.to_dict()
    assert d["arcs"] == 1 and d["dwell_time_s"] == 2.0
    assert d["bbox_max_mm"][1] == pytest.approx(1.0)  # top of the clockwise half circle
    assert list(iter(tp_mod.GcodeReader.from_string("G0 X1\nG0 X2")))[1].end[0] == 2.0


def test_cli_bad_input_is_one_line_exit_2(tmp_path):
    bad = tmp_path / "bad.ngc"
    bad.write_text("G21\nG0 X1\nG1 X2 Y[1+] F100\n")
    proc = subprocess.run([sys.executable, "-m", "netshape", "info", str(bad)], capture_output=True, text=True, env=_child_env())
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1
    assert f"{bad}:3:11: expected a value, found ']'" in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "netshape", "info", str(tmp_path / "none.ngc")],
                          capture_output=True, text=True, env=_child_env())
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1 and "no such file" in proc.stderr
    binary = tmp_path / "bin.ngc"
    binary.write_bytes(b"G0 X1\n\x00\x01\x02garbage\n")
    assert cli_main(["info", str(binary)]) == 2


def test_cli_info_table(capsys, repo_root):
    assert cli_main(["info", str(repo_root / "examples" / "demo" / "part.ngc")]) == 0
    out = capsys.readouterr().out
    assert "blocks" in out and "feed time" in out and "bounding box X  -17.000 … 17.000 mm" in out
    assert "arc 25" in out
