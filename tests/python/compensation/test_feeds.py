"""Feed scheduling from the physics (issue 41, docs/feeds.md): limits reached in closed form, air cuts,
the written program re-simulated by netshape.force.simulate_program, monotonicity, bad input."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest
from scipy.optimize import brentq

import netshape as ns
from netshape.cli import main
from netshape.compensation.feeds import feed_limits_from_dict
from netshape.compensation.feeds_run import optimize_program, read_program_text, with_start

TOOL = """kind = "flat"\ndiameter_mm = 10.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0
stick_out_mm = 40.0\nyoungs_modulus_MPa = 600000.0\n"""
STOCK = "min_mm = [-30.0, -20.0, -10.0]\nmax_mm = [30.0, 20.0, 0.0]\nspacing_mm = 0.25\n"
RPM, AP, R, N = 6000.0, 3.0, 5.0, 3
#: a full slot along +X, then a half-immersion (a_e = R, up milling) pass beside it; X-40 → X35 crosses the
#: stock (x in [-30, 30]) with air on both ends; last an air move above the stock
PROGRAM = f"""(slot then half immersion)
G21 G90 G17 G94
S{RPM:g} M3
G0 X-40 Y0 Z5
G1 Z-{AP:g} F600
G1 X35 F1200 (slot)
G0 Z5
G0 X-40 Y5
G1 Z-{AP:g} F600
G1 X35 F1200
G0 Z5
G1 X-40 Y-15 F1200 (air, above the stock)
M30
"""
MAX_FORCE = 400.0


@pytest.fixture(scope="module")
def setup():
    coeffs = ns.force.linear_edge_coefficient_set("leekunhwee_flat_slot").coefficients
    cutter = ns.cutter.cutter_from_dict({"kind": "flat", "diameter_mm": 2 * R, "flutes": N, "helix_deg": 30.0,
                                         "flute_length_mm": 20.0, "stick_out_mm": 40.0})
    stock = ns.stock.ZMap(-30, 30, -20, 20, 0.25, 0.0, -10.0)
    return stock, cutter, coeffs


_RUNS: dict = {}


def _run(setup, **limits):
    """The schedule of PROGRAM under ``limits`` (one run per set of limits in this module)."""
    key = tuple(sorted(limits.items()))
    if key not in _RUNS:
        _RUNS[key] = _schedule(setup, **limits)
    return _RUNS[key]


def _schedule(setup, **limits):
    stock, cutter, coeffs = setup
    lim, split = feed_limits_from_dict({"max_feed_mm_min": 20000.0, "air_feed_mm_min": 5000.0, **limits})
    axis = ns.motion.AxisLimits.uniform(1000.0, 20000.0, math.inf)
    return optimize_program(PROGRAM, "t.ngc", stock, cutter, coeffs, lim, axis_limits=axis,
                            plan_options=ns.motion.make_options("vector"), split=split,
                            sampling={"step": 0.5, "samples_per_revolution": 72, "disk_height": 0.1})


def _window_feed(coeffs, mode, ae, limit):
    """Feed [mm/min] at which the steady-window force model's peak resultant equals ``limit`` (root of
    the force model itself, brentq: independent of the scheduler's closed form)."""
    f = ns.force
    window = f.AngularEngagement.from_mode(getattr(f.MillingMode, mode), R, ae)
    angles = f.rotation_angles(720)

    def peak(c):
        m = f.FlatEndModel(radius=R, flutes=N, helix=math.radians(30), axial_depth=AP, feed_per_tooth=c,
                           engagement=window, linear_edge=coeffs, disk_height=0.1)
        return float(np.linalg.norm(f.flat_end_forces(m, angles), axis=1).max()) - limit

    return brentq(peak, 1e-6, 2.0, xtol=1e-10) * N * RPM


def test_slot_then_half_immersion_reach_the_force_limit(setup):
    """Each steady cut runs at the feed that puts the force model's peak on the limit (within 2 %), and the
    written program, re-simulated, reaches the limit there without exceeding it."""
    res = _run(setup, max_force_N=MAX_FORCE)
    coeffs = setup[2]
    p = res.pieces
    lines = np.array([res.program.blocks[int(b)].line for b in p["block"]])
    for line, mode, ae in ((6, "slot", 2 * R), (10, "up", R)):
        expected = _window_feed(coeffs, mode, ae, MAX_FORCE)
        mid = [k for k in np.flatnonzero(lines == line)
               if (p["end"][k] - p["start"][k]) * 75 > 20]  # the long steady piece of the 75 mm move
        assert mid, (line, p)
        got = max(p["feed"][k] * 60 for k in mid)
        assert got == pytest.approx(expected, rel=0.02), (line, got, expected)
        assert res.rows[[r["line"] for r in res.rows].index(line)]["force_after_N"] <= MAX_FORCE * 1.005
    assert res.summary["check"]["max_force_N"]["ratio"] <= 1.005
    assert res.summary["check"]["max_force_N"]["ratio"] >= 0.98


def test_air_cuts_run_at_the_air_feed(setup):
    res = _run(setup, max_force_N=MAX_FORCE)
    p = res.pieces
    air = [k for k in range(len(p["feed"])) if res.program.blocks[int(p["block"][k])].line == 12]
    assert air and all(abs(p["feed"][k] * 60 - 5000.0) < 0.2 for k in air)
    # the slot's entry from outside the stock is air too
    first = np.flatnonzero([res.program.blocks[int(b)].line == 6 for b in p["block"]])[0]
    assert abs(p["feed"][first] * 60 - 5000.0) < 0.2


def test_no_sample_exceeds_a_limit_when_resimulated(setup):
    """The written text read back and cut again: force and chip stay within their limits everywhere."""
    stock, cutter, coeffs = setup
    res = _run(setup, max_force_N=MAX_FORCE, max_chip_mm=0.12)
    written = with_start(read_program_text(res.text, "out.ngc"), stock)
    again = ns.force.simulate_program(stock, cutter, written, coeffs, step=0.5, disk_height=0.1)
    assert np.max(again.peak_resultant) <= MAX_FORCE * 1.005
    chip = [r["chip_after_mm"] for r in res.rows]
    assert max(chip) <= 0.12 * (1 + 1e-9)
    assert res.summary["cycle_time_s"]["optimized"] < res.summary["cycle_time_s"]["original"]


def test_raising_a_limit_never_slows_a_sample(setup):
    a = _run(setup, max_force_N=300.0, max_chip_mm=0.1)
    b = _run(setup, max_force_N=450.0, max_chip_mm=0.1)
    from netshape.compensation.feeds_report import piece_of_samples

    fa = a.pieces["feed"][piece_of_samples(a.schedule.samples, a.pieces)]
    fb = b.pieces["feed"][piece_of_samples(b.schedule.samples, b.pieces)]
    assert np.all(fb >= fa - 1e-9)
    assert np.any(fb > fa * 1.05)


def test_lossless_only_f_words_and_splits_added(setup):
    res = _run(setup, max_force_N=MAX_FORCE)
    out = res.text.splitlines()
    assert out[0].startswith("(netshape feeds:") and "max_force_N 400" in out[0]
    strip = lambda s: re.sub(r"\s*F[\d.]+", "", s).strip()  # noqa: E731
    kept = [ln for ln in out[1:] if not re.fullmatch(r"G1 X[-\d.]+ Y[-\d.]+ Z[-\d.]+ F[\d.]+", ln)]
    assert [strip(x) for x in kept] == [strip(x) for x in PROGRAM.splitlines()]


def _files(tmp_path):
    (tmp_path / "t.ngc").write_text(PROGRAM)
    (tmp_path / "tool.toml").write_text(TOOL)
    (tmp_path / "stock.toml").write_text(STOCK)
    return ["feeds", str(tmp_path / "t.ngc"), "--tool", str(tmp_path / "tool.toml"), "--stock",
            str(tmp_path / "stock.toml"), "--coefficients", "leekunhwee_flat_slot", "--vmax", "500",
            "--amax", "5000", "-o", str(tmp_path / "out.ngc"), "--json", str(tmp_path / "s.json")]


def test_cli_writes_program_and_summary(tmp_path, capsys):
    argv = _files(tmp_path) + ["--max-force", "400", "--max-feed", "20000", "--csv", str(tmp_path / "b.csv")]
    assert main(argv) == 0
    s = json.loads((tmp_path / "s.json").read_text())
    assert set(s["cycle_time_s"]) == {"original", "optimized"}
    assert set(s["max_force_N"]) == {"original", "optimized"}
    assert s["binding"]["max_force_N"] >= 2
    assert (tmp_path / "b.csv").read_text().startswith("line,binding,")


def test_cli_refuses_a_limit_no_feed_keeps(tmp_path, capsys):
    """5 N is below the edge force alone: no feed keeps it; the block's line and the limit are named and
    nothing is written."""
    argv = _files(tmp_path) + ["--max-force", "5", "--max-feed", "3000", "--min-feed", "100"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "max_force_N = 5" in err and "line 6" in err, err
    assert not (tmp_path / "out.ngc").exists() and not (tmp_path / "s.json").exists()


def test_cli_takes_the_spindle_limits_of_the_tool_file_unless_an_option_overrides(tmp_path, capsys):
    base = _files(tmp_path) + ["--max-feed", "20000"]
    assert main(base) == 0
    free = json.loads((tmp_path / "s.json").read_text())
    # a torque limit in the tool file binds and slows the program
    (tmp_path / "tool.toml").write_text(TOOL + "max_torque_Nm = 1.0\n")
    assert main(base) == 0
    held = json.loads((tmp_path / "s.json").read_text())
    assert held["binding"].get("max_torque_Nm", 0) > 0
    assert held["cycle_time_s"]["optimized"] > 1.05 * free["cycle_time_s"]["optimized"]
    # the option wins over the file
    assert main(base + ["--max-torque", "1000"]) == 0
    loose = json.loads((tmp_path / "s.json").read_text())
    assert loose["binding"].get("max_torque_Nm", 0) == 0
    # a bad value in the file is a one-line error naming the key
    (tmp_path / "tool.toml").write_text(TOOL + "max_power_W = -5\n")
    capsys.readouterr()
    assert main(base) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "max_power_W = -5" in err, err


@pytest.mark.parametrize("extra, field", [(["--max-force", "-3"], "--max-force"),
                                          (["--min-feed", "5000"], "--min-feed"),
                                          (["--min-chip", "0.2", "--max-chip", "0.1"], "--min-chip")])
def test_cli_bad_limits_name_the_option(tmp_path, capsys, extra, field):
    argv = _files(tmp_path) + ["--max-feed", "3000"] + extra
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert field in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "out.ngc").exists()


def _job_doc(tmp_path, optimize):
    (tmp_path / "t.ngc").write_text(PROGRAM)
    (tmp_path / "tool.toml").write_text(TOOL)
    return {"program": "t.ngc", "tool": "tool.toml", "coefficients": "leekunhwee_flat_slot",
            "stock": {"min_mm": [-30.0, -20.0, -10.0], "max_mm": [30.0, 20.0, 0.0], "spacing_mm": 0.25},
            "predict": ["forces", "feed_plan"], "limits": {"vmax_mm_s": 500.0, "amax_mm_s2": 5000.0},
            "cutting": {"samples_per_revolution": 72, "disk_height_mm": 0.1}, "optimize": optimize}


def test_job_optimize_table(tmp_path):
    """The job's [optimize] table: validated at load (naming the key), scheduled as `netshape feeds` does."""
    from netshape.job.optimize import stage_optimize
    from netshape.job.spec import job_from_dict
    from netshape.job.stages import stage_stock

    job = job_from_dict(_job_doc(tmp_path, {"max_force_N": 400.0, "max_feed_mm_min": 20000.0}),
                        source=str(tmp_path / "job.toml"), base_dir=tmp_path)
    summary, text, _ = stage_optimize(job, stage_stock(job))
    assert summary["binding"]["max_force_N"] >= 2
    assert summary["check"]["max_force_N"]["ratio"] <= 1.005
    assert text.startswith("(netshape feeds:")
    with pytest.raises(ValueError, match=r"optimize\.max_force = 400"):
        job_from_dict(_job_doc(tmp_path, {"max_force": 400.0, "max_feed_mm_min": 2000.0}),
                      source=str(tmp_path / "job.toml"), base_dir=tmp_path)


def test_a_wall_error_no_feed_keeps_is_refused(setup):
    """With no min_feed the smallest written feed (0.1 mm/min) is the floor: a wall-error limit the edge
    forces alone exceed is refused, naming the limit and the line, never written as F0."""
    with pytest.raises(ValueError, match=r"max_wall_error_mm = 0.01: the block on line 6 keeps it only"):
        _schedule(setup, max_wall_error_mm=0.01)


def test_ball_end_mill_reaches_the_force_limit():
    """A ball end mill (Feng–Menq, chip exponents: the feed found by bisection): the written program,
    re-simulated, reaches the force limit in the steady slot within 2 % and nowhere exceeds it."""
    kim = ns.force.ball_end_coefficient_set("kim_zas_ball12").coefficients
    ball = ns.cutter.cutter_from_dict({"kind": "ball", "diameter_mm": 2 * R, "flutes": 2, "helix_deg": 30.0,
                                       "flute_length_mm": 20.0, "stick_out_mm": 40.0})
    stock = ns.stock.ZMap(-30, 30, -20, 20, 0.25, 0.0, -10.0)
    lim, split = feed_limits_from_dict({"max_force_N": 150.0, "max_feed_mm_min": 20000.0})
    res = optimize_program(PROGRAM, "t.ngc", stock, ball, kim, lim,
                           axis_limits=ns.motion.AxisLimits.uniform(1000.0, 20000.0, math.inf),
                           plan_options=ns.motion.make_options("vector", ts1=2e-3, ts2=1e-3), split=split,
                           sampling={"step": 0.5, "samples_per_revolution": 72, "disk_height": 0.1})
    ratio = res.summary["check"]["max_force_N"]["ratio"]
    assert 0.98 <= ratio <= 1.005, ratio
    assert res.summary["binding"]["max_force_N"] >= 2


def test_the_tool_file_is_read_once(tmp_path, monkeypatch):
    """`netshape feeds` reads the tool TOML once: the cutter and its spindle limits come from one dict."""
    import netshape._config as config
    import netshape.cutter as cutter_module

    real, reads = config.load_toml, []

    def counting(path, *args, **kwargs):
        if str(path).endswith("tool.toml"):
            reads.append(str(path))
        return real(path, *args, **kwargs)

    monkeypatch.setattr(config, "load_toml", counting)
    monkeypatch.setattr(cutter_module, "load_toml", counting)
    (tmp_path / "t.ngc").write_text(PROGRAM)
    (tmp_path / "tool.toml").write_text(TOOL + "max_torque_Nm = 50.0\n")
    (tmp_path / "stock.toml").write_text(STOCK)
    code = main(["feeds", str(tmp_path / "t.ngc"), "--tool", str(tmp_path / "tool.toml"), "--stock",
                 str(tmp_path / "stock.toml"), "--coefficients", "leekunhwee_flat_slot", "--max-feed", "3000",
                 "--vmax", "200", "--amax", "2000", "--step", "1", "--samples", "36", "--disk-height", "0.25",
                 "-o", str(tmp_path / "out.ngc"), "--json", str(tmp_path / "s.json")])
    assert code == 0
    assert reads == [str(tmp_path / "tool.toml")]
    assert json.loads((tmp_path / "s.json").read_text())["limits"]["max_torque_Nm"] == 50.0
