"""netshape.deflection: model checks against closed forms, the paper's numbers, the path evaluation and
the compensation schemes, and the CLI (exit codes, JSON keys, atomic output)."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d
from netshape.cli import main

REPO = Path(__file__).resolve().parents[3]

PAPER = dict(diameter=25.0, flutes=4, helix_deg=60.0, stick_out=250.0, youngs_modulus=210e3,
             feed_per_tooth=0.0127, ap=2.5, coefficients="cho_suh_example")


def test_beam_tip_and_point_load_closed_forms():
    """Gere & Goodno, Mechanics of Materials (cantilever, concentrated load at a): tip PL³/3EI,
    deflection at the tip a²(3L − a)/6EI."""
    c = d.Cantilever(length=100.0, youngs_modulus=200e3, inertia=500.0)
    ei = 200e3 * 500.0
    assert c.deflection(10.0, 100.0, 100.0) == pytest.approx(10.0 * 100.0**3 / (3 * ei), rel=1e-14)
    assert c.influence(100.0, 70.0) == pytest.approx(70.0**2 * (300.0 - 70.0) / (6 * ei), rel=1e-14)
    assert d.second_moment(8.0, d.InertiaModel.square) == pytest.approx(8.0**4 / 48)
    assert d.second_moment(8.0, d.InertiaModel.equivalent) == pytest.approx(math.pi * 6.4**4 / 64)


def test_helix_lag_of_the_paper():
    """Cho & Suh 1993 §5: the mid-depth wall point is generated 9.915° (9.92°) after the tip's."""
    m = d.make_model(ae=2.0, mode="down", **PAPER)
    lag = d.generation_angle(m, d.WallSide.right, 1.25) - d.generation_angle(m, d.WallSide.right, 0.0)
    assert math.degrees(lag) == pytest.approx(9.92, abs=0.01)


def test_single_element_distributed_equals_resultant():
    kw = dict(PAPER, ae=2.0, mode="down", disk_height=2.5)
    a = d.steady_wall(d.make_model(load="distributed", **kw), "down")
    b = d.steady_wall(d.make_model(load="resultant", **kw), "down")
    assert a["profile"]["error_mm"] == pytest.approx(b["profile"]["error_mm"], rel=1e-12)


def test_steady_wall_trend_and_slot():
    """The error grows with the width (the trend of the paper's Fig. 4): small while one flute alone
    generates the wall, ~0.1 mm once the next flute cuts its thick chip at the same instant."""
    e = [d.steady_wall(d.make_model(ae=w, mode="down", **PAPER), "down")["wall_error_mm"]["middle"]
         for w in (2.0, 8.0, 11.0, 12.5, 18.0)]
    assert all(b >= a - 1e-9 for a, b in zip(e, e[1:]))
    assert 0 < e[0] < 0.005 and 0.05 < e[-1] < 0.2
    s = d.steady_wall(d.make_model(mode="slot", **PAPER), "slot")
    assert set(s["walls"]) == {"left", "right"}


def test_bad_input():
    with pytest.raises(ValueError, match="stick_out"):
        d.make_model(**dict(PAPER, stick_out=2.0), ae=2.0, mode="down")
    with pytest.raises(ValueError, match="youngs_modulus"):
        d.make_model(**dict(PAPER, youngs_modulus=0.0), ae=2.0, mode="down")
    with pytest.raises(ValueError, match="coefficients"):
        d.parse_coefficients("nonsense_set")


def _straight_setup(tmp_path, width=12.0, spacing=1.0):
    """A straight down-milling cut along +X over a flat-sided stock of constant width."""
    tool = tmp_path / "tool.toml"
    tool.write_text('kind = "flat"\ndiameter_mm = 25.0\nflutes = 4\nhelix_deg = 60.0\nflute_length_mm = 50.0\n'
                    'stick_out_mm = 250.0\nyoungs_modulus_MPa = 210000.0\n')
    (tmp_path / "stock.toml").write_text(f"min_mm = [0.0, -10.0, -5.0]\nmax_mm = [40.0, {width}, 2.5]\n"
                                         "spacing_mm = 0.1\n")
    (tmp_path / "cut.nc").write_text("G21 G90 G17\nS600 M3\nG0 X-15 Y12.5 Z5\nG1 Z0 F30.48\n"
                                     "G1 X55 Y12.5\nG0 Z10\nM30\n")
    cutter = ns.cutter.load_cutter(tool)
    stock = d.load_stock(tmp_path / "stock.toml")
    prog = ns.toolpath.read_gcode(tmp_path / "cut.nc")
    return d.setup_path(prog, cutter, stock, coefficients="cho_suh_example", rpm=600, spacing=spacing,
                        profile_levels=0)


def test_path_steady_part_matches_the_steady_cut(tmp_path):
    setup = _straight_setup(tmp_path)
    assert setup.side == d.WallSide.right
    r = d.predict_path(setup)
    x = setup.nominal[:, 0]
    mid = (x > 15) & (x < 25)
    steady = d.steady_wall(d.make_model(ae=12.0, mode="down", **PAPER), "down")["wall_error_mm"]
    e = np.asarray(r.error)[mid]
    np.testing.assert_allclose(np.asarray(r.width)[mid], 12.0, atol=0.06)
    np.testing.assert_allclose(e[:, 1], steady["middle"], rtol=0.05)
    assert np.all(np.asarray(r.engaged)[x < -13] == 0)


def test_schemes_converge_to_the_same_path(tmp_path):
    setup = _straight_setup(tmp_path)
    out = {}
    for sc in ("one-d", "integrated", "sectional", "accelerated"):
        res = d.compensate_path(setup, scheme=sc, level="middle", tolerance=5e-4, discount=0.5)
        out[sc] = res
        after = np.max(np.abs(np.asarray(res.after.error)[:, 1]))
        before = np.max(np.abs(np.asarray(res.before.error)[:, 1]))
        assert before > 0.02
        if sc != "one-d":
            assert res.converged, res.message
            assert after <= 1e-3
    ci, cs = np.asarray(out["integrated"].offsets), np.asarray(out["sectional"].offsets)
    assert np.max(np.abs(ci - cs)) < 2e-3
    # with the paper's damped update (λ = 0.5) the plain iteration needs ~8 iterations, Anderson far fewer
    assert out["accelerated"].path_evaluations < out["integrated"].path_evaluations
    assert out["integrated"].iterations >= 6
    # the steady middle section: the 1-D root is the converged offset there
    x = setup.nominal[:, 0]
    mid = (x > 15) & (x < 25)
    np.testing.assert_allclose(np.asarray(out["one-d"].offsets)[mid], ci[mid], atol=2e-3)


def test_non_convergence_is_reported(tmp_path):
    setup = _straight_setup(tmp_path)
    res = d.compensate_path(setup, scheme="integrated", tolerance=1e-9, max_iterations=2)
    assert not res.converged
    assert "point" in res.message and "limit" in res.message


def test_path_that_never_touches_the_stock(tmp_path):
    setup = _straight_setup(tmp_path)
    (tmp_path / "away.nc").write_text("G21 G90 G17\nS600 M3\nG0 X-15 Y60 Z5\nG1 Z0 F30.48\nG1 X55 Y60\nM30\n")
    prog = ns.toolpath.read_gcode(tmp_path / "away.nc")
    with pytest.raises(ValueError, match="never touches"):
        d.setup_path(prog, setup.cutter, setup.stock, coefficients="cho_suh_example", rpm=600)


def test_cli_wall_json(tmp_path, capsys):
    out = tmp_path / "w.json"
    rc = main(["deflection", "wall", "--diameter", "25", "--flutes", "4", "--helix", "60", "--stick-out", "250",
               "--youngs-modulus", "210000", "--inertia", "square", "--load", "distributed", "--rpm", "600",
               "--feed-per-tooth", "0.0127", "--ap", "2.5", "--ae", "2", "--mode", "down",
               "--coefficients", "KT=1000,KR=0.4", "--json", str(out)])
    assert rc == 0
    data = json.loads(out.read_text())
    assert set(data["wall_error_mm"]) == {"bottom", "middle", "top"}
    assert len(data["profile"]["z_mm"]) >= 21 and len(data["profile"]["error_mm"]) == len(data["profile"]["z_mm"])
    assert data["max_force_N"] > 0
    rc = main(["deflection", "wall", "--diameter", "25", "--flutes", "4", "--helix", "60", "--stick-out", "2",
               "--youngs-modulus", "210000", "--rpm", "600", "--feed-per-tooth", "0.0127", "--ap", "2.5",
               "--ae", "2", "--mode", "down", "--coefficients", "cho_suh_example"])
    assert rc == 2
    assert "--stick-out" in capsys.readouterr().err
    rc = main(["deflection", "wall", "--diameter", "25", "--flutes", "4", "--helix", "60", "--stick-out", "250",
               "--youngs-modulus", "0", "--rpm", "600", "--feed-per-tooth", "0.0127", "--ap", "2.5",
               "--ae", "2", "--mode", "down", "--coefficients", "cho_suh_example"])
    assert rc == 2
    assert "--youngs-modulus" in capsys.readouterr().err


def test_cli_predict_and_compensate(tmp_path, capsys):
    _straight_setup(tmp_path)
    common = ["--tool", str(tmp_path / "tool.toml"), "--stock", str(tmp_path / "stock.toml"),
              "--coefficients", "cho_suh_example", "--rpm", "600", "--spacing", "1.0"]
    pj = tmp_path / "p.json"
    assert main(["deflection", "predict", str(tmp_path / "cut.nc"), *common, "--json", str(pj)]) == 0
    data = json.loads(pj.read_text())
    assert set(data["max_wall_error_mm"]) == {"bottom", "middle", "top"}
    assert len(data["points"]["x_mm"]) == len(data["points"]["error_middle_mm"])
    nc = tmp_path / "comp.nc"
    assert main(["deflection", "compensate", str(tmp_path / "cut.nc"), *common, "--scheme", "accelerated",
                 "--level", "middle", "-o", str(nc)]) == 0
    assert "before" in capsys.readouterr().out
    prog = ns.toolpath.read_gcode(nc)
    ys = [b.end[1] for b in prog.blocks if int(b.kind) == 1 and abs(b.end[2]) < 1e-9]
    assert min(ys) < 12.5 - 0.02  # moved towards the wall (−Y) where it cuts
    # a scheme that cannot converge writes nothing
    bad = tmp_path / "bad.nc"
    assert main(["deflection", "compensate", str(tmp_path / "cut.nc"), *common, "--scheme", "integrated",
                 "--tolerance", "1e-9", "--max-iterations", "2", "-o", str(bad)]) == 2
    assert not bad.exists()
    assert "not written" in capsys.readouterr().err
    (tmp_path / "away.nc").write_text("G21 G90 G17\nS600 M3\nG0 X-15 Y60 Z5\nG1 Z0 F30.48\nG1 X55 Y60\nM30\n")
    assert main(["deflection", "predict", str(tmp_path / "away.nc"), *common]) == 2
    assert "never touches" in capsys.readouterr().err


@pytest.mark.slow
def test_example_runs(tmp_path):
    """examples/deflection_cho_suh.py --quick runs, writes its plot and meets the done-when figures."""
    proc = subprocess.run([sys.executable, str(REPO / "examples" / "deflection_cho_suh.py"), str(tmp_path),
                           "--quick"], capture_output=True, text=True, timeout=600,
                          env=dict(os.environ, MPLBACKEND="Agg"))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "straight.png").stat().st_size > 1000
    s = json.loads((tmp_path / "summary.json").read_text())["cases"]["straight"]
    assert s["max_wall_error_before_um"]["middle"] > 10
    for r in s["schemes"].values():
        assert r["converged"] and r["max_wall_error_after_um"] <= 1.0
    assert s["schemes"]["accelerated"]["path_evaluations"] < s["schemes"]["integrated"]["path_evaluations"]


def test_compensated_program_keeps_arcs_within_tolerance(tmp_path):
    """A uniformly offset arc stays one G2/G3 block (same centre); a wavy offset is written sample by sample
    through every point: an arc between two samples whose radii agree (no chord inside the arc), a line
    where they do not."""
    (tmp_path / "a.nc").write_text("G21 G90 G17\nS600 M3\nG0 X60 Y50 Z5\nG1 Z0 F30\nG3 X40 Y50 I-10 J0\nM30\n")
    prog = ns.toolpath.read_gcode(tmp_path / "a.nc")
    pts, first, last, _ = d.contour_of(prog, 0.5)
    normals = np.asarray(d.wall_normals(pts, d.WallSide.left))
    setup = d.PathSetup(None, None, None, prog, pts, first, last, d.WallSide.left, None)
    out = d.compensated_program(setup, pts + np.column_stack([0.01 * normals, np.zeros(len(pts))]))
    arcs = [b for b in out.blocks if int(b.kind) == 2]
    assert len(arcs) == 1 and np.allclose(arcs[0].center, (50, 50, 0))
    assert arcs[0].radius() == pytest.approx(10.0 - 0.01, abs=1e-5)  # left of a CCW arc: towards the centre
    wavy = 0.01 * np.sin(np.arange(len(pts)))
    wpts = pts + np.column_stack([wavy[:, None] * normals, np.zeros(len(pts))])
    out = d.compensated_program(setup, wpts)
    moves = [b for b in out.blocks if int(b.kind) != 0 and np.hypot(*(np.asarray(b.end) - b.start)[:2]) > 1e-9]
    moves = moves[:len(pts) - 1]  # then the join back to the nominal end
    np.testing.assert_allclose([b.end for b in moves], wpts[1:], atol=1e-9)
    for b, a, e in zip(moves, wpts[:-1], wpts[1:]):
        ra, re = np.hypot(*(a[:2] - (50, 50))), np.hypot(*(e[:2] - (50, 50)))
        assert (int(b.kind) == 2) == (abs(ra - re) <= 5e-4 * ra)


def test_exact_self_removal_agrees_with_the_zmap_sweep(tmp_path):
    """The contour's own removal as exact swept discs and as a Z-map swept move by move (stock.sweep_line,
    read with stock.immersion) give the same engagement up to the 0.1 mm grid."""
    setup = _straight_setup(tmp_path)
    n = len(setup.nominal)
    normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
    exact = d.path_wall_errors(setup.model, setup.cutter, setup.stock, setup.nominal, normals, np.zeros(n),
                               setup.options)
    opt = d.PathOptions()
    opt.side = setup.side
    opt.exact_self_removal = False
    swept = d.path_wall_errors(setup.model, setup.cutter, setup.stock, setup.nominal, normals, np.zeros(n), opt)
    x = setup.nominal[:, 0]
    mid = (x > 5) & (x < 35)
    np.testing.assert_allclose(np.asarray(swept.width)[mid], np.asarray(exact.width)[mid], atol=0.1)
    np.testing.assert_allclose(np.asarray(swept.error)[mid], np.asarray(exact.error)[mid], atol=3e-3)


def test_cli_predict_plot(tmp_path):
    _straight_setup(tmp_path)
    out = tmp_path / "plots"
    assert main(["deflection", "predict", str(tmp_path / "cut.nc"), "--tool", str(tmp_path / "tool.toml"),
                 "--stock", str(tmp_path / "stock.toml"), "--coefficients", "cho_suh_example", "--rpm", "600",
                 "--spacing", "2", "--plot", str(out)]) == 0
    assert (out / "wall_error.png").stat().st_size > 1000 and (out / "profile.png").exists()
