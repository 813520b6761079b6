"""Every program in ../shared/data/gcode reads, round-trips, and `netshape info` agrees with an
independent pure-Python interpretation (tests/python/toolpath/_independent.py); the NURBS files are
refused naming G5.2 / G6.2 and the line."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import netshape as ns
from netshape.cli import main as cli_main

_spec = importlib.util.spec_from_file_location("_independent", Path(__file__).with_name("_independent.py"))
independent = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(independent)

_FIGURES: dict = {}


def reference(path):
    """Independent figures of a program (cached: the sampling is the slow part)."""
    if path not in _FIGURES:
        _FIGURES[path] = independent.figures(path.read_text())
    return _FIGURES[path]


PROGRAMS = ["3D_Chips.ngc", "cds.ngc", "arcspiral.ngc", "tort.ngc"]
NURBS = {"butterfly-xy_G5.2.ngc": ("G5.2", 12), "Curva_Farfalla_1_G6.2.ngc": ("G6.2", 13)}


def same_blocks(a, b, *, tol=1e-9):
    assert len(a) == len(b)
    for x, y in zip(a, b):
        assert x.kind == y.kind
        assert np.abs(np.asarray(x.start) - y.start).max() <= tol
        assert np.abs(np.asarray(x.end) - y.end).max() <= tol
        assert x.clockwise == y.clockwise and x.plane == y.plane and x.turns == y.turns
        if x.kind == ns.toolpath.MotionKind.arc:
            assert np.abs(np.asarray(x.center) - y.center).max() <= tol
        assert x.feed == pytest.approx(y.feed, rel=1e-12)
        assert x.spindle_rpm == y.spindle_rpm and x.tool == y.tool


@pytest.mark.parametrize("name", PROGRAMS)
def test_reads_and_round_trips(shared_data, tmp_path, name):
    path = shared_data / "gcode" / name
    tp = ns.toolpath.read_gcode(path)
    assert len(tp) > 200
    out = tmp_path / "back.ngc"
    ns.toolpath.write_gcode(tp, out)
    same_blocks(tp, ns.toolpath.read_gcode(out))
    # absolute centres and fixed decimals also read back (the latter to its rounding)
    same_blocks(tp, ns.toolpath.parse_gcode(ns.toolpath.format_gcode(tp, absolute_arc_centers=True)))
    same_blocks(tp, ns.toolpath.parse_gcode(ns.toolpath.format_gcode(tp, decimals=6)), tol=2e-6)
    # coordinates round-trip bit for bit
    again = ns.toolpath.read_gcode(out)
    assert all(np.array_equal(x.end, y.end) for x, y in zip(tp, again))


@pytest.mark.parametrize("name", PROGRAMS)
def test_info_agrees_with_independent_interpretation(shared_data, capsys, name):
    path = shared_data / "gcode" / name
    assert cli_main(["info", str(path), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    ref = reference(path)
    for key in ("rapids", "lines", "arcs"):
        assert got[key] == ref[key], key
    assert got["rapid_length_mm"] == pytest.approx(ref["rapid_length_mm"], rel=1e-9)
    # sampled arc lengths converge as 1/n²: 20001 samples per arc
    assert got["feed_length_mm"] == pytest.approx(ref["feed_length_mm"], rel=1e-6)
    assert got["feed_time_s"] == pytest.approx(ref["feed_time_s"], rel=1e-6)
    # dense sampling misses the true extreme by at most r·(1 − cos(π·sweep/n)) < 1e-5 mm here
    np.testing.assert_allclose(got["bbox_min_mm"], ref["bbox_min_mm"], atol=1e-4)
    np.testing.assert_allclose(got["bbox_max_mm"], ref["bbox_max_mm"], atol=1e-4)
    # the exact box contains every sampled point
    assert np.all(np.array(got["bbox_min_mm"]) <= np.array(ref["bbox_min_mm"]) + 1e-9)
    assert np.all(np.array(got["bbox_max_mm"]) >= np.array(ref["bbox_max_mm"]) - 1e-9)


@pytest.mark.parametrize("name", PROGRAMS)
def test_arrays_match_blocks(shared_data, name):
    path = shared_data / "gcode" / name
    tp = ns.toolpath.read_gcode(path)
    arr = ns.toolpath.read_gcode_arrays(path)
    n = len(tp)
    assert arr["start"].shape == (n, 3) and arr["kind"].dtype == np.uint8
    np.testing.assert_array_equal(arr["end"], np.array([b.end for b in tp]))
    np.testing.assert_array_equal(arr["kind"], [int(b.kind) for b in tp])
    np.testing.assert_array_equal(arr["line"], [b.line for b in tp])
    np.testing.assert_array_equal(arr["feed"], [b.feed for b in tp])
    # blocks are continuous
    np.testing.assert_array_equal(arr["start"][1:], arr["end"][:-1])
    # independent arc lengths from the arrays alone
    ref = reference(path)
    ind = ref["blocks"]
    np.testing.assert_allclose(arr["end"], np.array([b["end"] for b in ind]), atol=1e-12)
    arcs = arr["kind"] == 2
    if arcs.any():
        np.testing.assert_allclose(arr["center"][arcs], np.array([b["center"] for b in ind if b["kind"] == "arc"]),
                                   atol=1e-9)
    split = ns.toolpath.read_gcode_arrays(path, arcs="split", chord_tolerance=0.002)
    assert len(split["kind"]) >= n and not (split["kind"] == 2).any()


def test_inch_programs_are_converted_to_mm(shared_data):
    s = ns.toolpath.summary(shared_data / "gcode" / "cds.ngc")
    # cds.ngc: "Top of stock at Z=2 in", X 0 … 4 in, Y -0.25 … 3.915 in (its header)
    assert s.bbox_max[0] == pytest.approx(4 * 25.4)
    assert s.bbox_min[1] == pytest.approx(-0.25 * 25.4)
    tp = ns.toolpath.read_gcode(shared_data / "gcode" / "arcspiral.ngc")
    assert tp[5].feed == pytest.approx(24 * 25.4 / 60)  # f24 in/min


@pytest.mark.parametrize("name", sorted(NURBS))
def test_nurbs_programs_are_refused(shared_data, name):
    code, line = NURBS[name]
    with pytest.raises(ns.ParseError) as err:
        ns.toolpath.read_gcode(shared_data / "gcode" / name)
    assert code in str(err.value) and "not supported" in str(err.value)
    assert err.value.line == line and err.value.column == 1
    proc = subprocess.run([sys.executable, "-m", "netshape", "info", str(shared_data / "gcode" / name)],
                          capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and f"{name}:{line}:1: " in proc.stderr and code in proc.stderr
