"""Feed scheduling (issue 41, docs/feeds.md) against the deflection model and in the work frame: the
wall-error and deflection limits use the surface-generation model of `netshape deflection`, the
re-simulation checks them, and a program under G55 is scheduled in the stock's G54 frame."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import netshape as ns
from netshape.cli import main
from netshape.compensation.feeds import feed_limits_from_dict
from netshape.compensation.feeds_run import optimize_program, read_program_text

RPM, AP, N = 6000.0, 3.0, 3
SAMPLING = {"step": 0.5, "samples_per_revolution": 72, "disk_height": 0.1}
COARSE = {"step": 1.0, "samples_per_revolution": 36, "disk_height": 0.25}
#: a straight down-milling cut along +X, a_e = 2 mm on the right (−Y) of the 10 mm tool, the stock's
#: edge at y = 20: its wall (y = 18) is the part's final wall
WALL = f"""(straight wall)
G21 G90 G17 G94
S{RPM:g} M3
G0 X-40 Y23 Z5
G0 Z-{AP:g}
G1 X35 F600
G0 Z5
M30
"""
WALL_LIMIT = 0.02  # [mm]


def _cutter():
    return ns.cutter.cutter_from_dict({"kind": "flat", "diameter_mm": 10.0, "flutes": N, "helix_deg": 30.0,
                                       "flute_length_mm": 20.0, "stick_out_mm": 40.0,
                                       "holder_compliance_um_per_N": 0.05})


def _stock():
    return ns.stock.ZMap(-30, 30, -20, 20, 0.25, 0.0, -10.0)


def _coeffs():
    return ns.force.linear_edge_coefficient_set("leekunhwee_flat_slot").coefficients


def _optimize(text, work_offsets=None, sampling=SAMPLING, **limits):
    lim, split = feed_limits_from_dict({"max_feed_mm_min": 20000.0, "air_feed_mm_min": 5000.0, **limits})
    return optimize_program(text, "t.ngc", _stock(), _cutter(), _coeffs(), lim,
                            axis_limits=ns.motion.AxisLimits.uniform(1000.0, 20000.0, math.inf),
                            plan_options=ns.motion.make_options("vector"), split=split, sampling=sampling,
                            work_offsets=work_offsets)


def _steady_feed(res, line):
    """The feed [mm/min] of the longest piece of the program line."""
    p = res.pieces
    ks = [k for k in range(len(p["feed"])) if res.program.blocks[int(p["block"][k])].line == line]
    k = max(ks, key=lambda k: p["end"][k] - p["start"][k])
    return float(p["feed"][k] * 60.0)


def test_wall_error_limit_meets_the_deflection_prediction():
    """The scheduled feed of a straight wall cut makes the wall error that the deflection command's own
    model predicts there (ns.deflection.predict_path, bottom/middle/top) reach the limit within 2 %; the
    written program, re-simulated, nowhere exceeds it."""
    res = _optimize(WALL, max_wall_error_mm=WALL_LIMIT)
    feed = _steady_feed(res, 6)
    assert feed < 19000.0, feed  # the wall limit binds, not max_feed
    tp = read_program_text(WALL, "wall.ngc")
    setup = ns.deflection.setup_path(tp, _cutter(), _stock(), coefficients=_coeffs(), rpm=RPM, spacing=0.5,
                                     disk_height=0.1, side="right", feed_per_tooth=feed / (RPM * N))
    r = ns.deflection.predict_path(setup)
    steady = np.abs(setup.nominal[:, 0]) < 20.0
    predicted = float(np.abs(np.asarray(r.error)[steady]).max())
    assert predicted == pytest.approx(WALL_LIMIT, rel=0.02), (feed, predicted)
    check = res.summary["check"]["max_wall_error_mm"]
    assert check["limit"] == WALL_LIMIT
    assert 0.98 <= check["ratio"] <= 1.0 + 1e-9, check
    assert res.summary["binding"]["max_wall_error_mm"] >= 1


def test_deflection_limit_is_the_tip_deflection_of_the_model():
    """The tip deflection limit: the re-simulated tip deflection of the model reaches it and stays within."""
    res = _optimize(WALL, max_deflection_mm=0.02)
    check = res.summary["check"]["max_deflection_mm"]
    assert 0.98 <= check["ratio"] <= 1.0 + 1e-9, check


#: a slot then a half-immersion pass under G55 (program coordinates), and the same cut in G54
#: coordinates of the stock: G55 − G54 = (10, −5, 0)
OFFSET_PROGRAM = """G21 G90 G17 G94
{g}
S6000 M3
G0 X{x0:g} Y{y0:g} Z5
G1 Z-3 F600
G1 X{x1:g} F1200
G0 Z5
G0 X{x0:g} Y{y2:g}
G1 Z-3 F600
G1 X{x1:g} F1200
G0 Z5
M30
"""
G54, G55 = np.array([100.0, 50.0, -200.0]), np.array([110.0, 45.0, -200.0])


def _offsets():
    w = np.zeros((9, 3))
    w[0], w[1] = G54, G55
    return w


def test_a_program_under_g55_gets_the_feeds_of_the_shifted_program():
    """The stock is in G54 work coordinates: a program under G55 is cut where G55 − G54 moves it, so it
    gets the feeds of the same program shifted by that amount under G54 (the written G55 program keeps
    its own coordinates)."""
    d = G55 - G54
    g55 = OFFSET_PROGRAM.format(g="G55", x0=-50, y0=5, x1=25, y2=10)
    g54 = OFFSET_PROGRAM.format(g="G54", x0=-50 + d[0], y0=5 + d[1], x1=25 + d[0], y2=10 + d[1])
    a = _optimize(g55, max_force_N=400.0, work_offsets=_offsets(), sampling=COARSE)
    b = _optimize(g54, max_force_N=400.0, work_offsets=_offsets(), sampling=COARSE)
    assert len(a.pieces["feed"]) == len(b.pieces["feed"])
    np.testing.assert_allclose(a.pieces["feed"], b.pieces["feed"], rtol=1e-9)
    assert a.summary["binding"]["max_force_N"] >= 2
    assert "X25 F" in a.text and "G55" in a.text


def test_cli_reads_the_work_offsets_from_var(tmp_path):
    """`netshape feeds --var FILE.var` gives the G55 program the feeds of the shifted G54 program."""
    d = G55 - G54
    (tmp_path / "g55.ngc").write_text(OFFSET_PROGRAM.format(g="G55", x0=-50, y0=5, x1=25, y2=10))
    (tmp_path / "g54.ngc").write_text(OFFSET_PROGRAM.format(g="G54", x0=-50 + d[0], y0=5 + d[1],
                                                            x1=25 + d[0], y2=10 + d[1]))
    var = "".join(f"{5221 + 20 * row + k} {v:g}\n"
                  for row, w in enumerate((G54, G55)) for k, v in enumerate(w))
    (tmp_path / "o.var").write_text(var)
    (tmp_path / "tool.toml").write_text('kind = "flat"\ndiameter_mm = 10.0\nflutes = 3\nhelix_deg = 30.0\n'
                                        'flute_length_mm = 20.0\nstick_out_mm = 40.0\n')
    (tmp_path / "stock.toml").write_text("min_mm = [-30.0, -20.0, -10.0]\nmax_mm = [30.0, 20.0, 0.0]\n"
                                         "spacing_mm = 0.5\n")
    feeds = {}
    for name in ("g55", "g54"):
        code = main(["feeds", str(tmp_path / f"{name}.ngc"), "--tool", str(tmp_path / "tool.toml"),
                     "--stock", str(tmp_path / "stock.toml"), "--coefficients", "leekunhwee_flat_slot",
                     "--max-force", "400", "--max-feed", "20000", "--vmax", "1000", "--amax", "20000",
                     "--var", str(tmp_path / "o.var"), "-o", str(tmp_path / f"{name}_out.ngc"),
                     "--step", "1", "--samples", "36", "--disk-height", "0.25"])
        assert code == 0
        text = (tmp_path / f"{name}_out.ngc").read_text()
        feeds[name] = [float(f) for f in re.findall(r"F(\d+\.?\d*)", text)]
    assert feeds["g55"] == feeds["g54"]
    assert main(["feeds", str(tmp_path / "g55.ngc"), "--tool", str(tmp_path / "tool.toml"), "--stock",
                 str(tmp_path / "stock.toml"), "--coefficients", "leekunhwee_flat_slot", "--max-feed", "2000",
                 "--vmax", "100", "--amax", "1000", "--var", str(tmp_path / "nope.var"),
                 "-o", str(tmp_path / "x.ngc")]) == 2
    assert not (tmp_path / "x.ngc").exists()
