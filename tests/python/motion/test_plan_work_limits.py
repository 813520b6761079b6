"""`netshape plan` sizes its work before it starts (docs/motion.md, Limits): a program whose fine samples
(at least its cycle time / --ts2) exceed --max-samples is refused with one line naming the input that
makes it long, fast and before anything is written; a look-ahead deeper than the program costs nothing."""

from __future__ import annotations

import json
import resource
import time

import pytest

from netshape.cli import main

SQUARE = "G21 G90\nG1 X10 F600\nG1 Y10\nG1 X0\nG1 Y0\nG1 X5\n"


def _refused(capsys, tmp_path, program: str, *extra: str, limits=("--vmax", "200", "--amax", "2000")) -> str:
    p = tmp_path / "p.ngc"
    p.write_text(program)
    out = tmp_path / "o.json"
    t0 = time.perf_counter()
    code = main(["plan", str(p), *limits, "--rule", "vector", "--json", str(out), *extra])
    elapsed = time.perf_counter() - t0
    cap = capsys.readouterr()
    assert code == 2, cap
    lines = cap.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("netshape plan: error: "), cap.err
    assert "over the limit of 50000000" in lines[0] or "--max-samples" in " ".join(extra), lines[0]
    assert not out.exists()
    assert elapsed < 2.0, elapsed  # refused before planning (planning these takes minutes and GBs)
    return lines[0]


def test_a_very_long_move_is_refused_naming_its_line(capsys, tmp_path):
    line = _refused(capsys, tmp_path, "G21 G90\nG1 X100000000 F6000\n")
    assert ":2: a move of 1e+08 mm at F6000 mm/min" in line and "fine samples" in line


def test_a_tiny_feed_is_refused_naming_its_line(capsys, tmp_path):
    line = _refused(capsys, tmp_path, "G21 G90\nG1 X10 F0.000001\n")
    assert ":2: a move of 10 mm at F1e-06 mm/min" in line


@pytest.mark.parametrize("extra, needle", [
    (("--vmax", "1e-9", "--amax", "2000"), "--vmax = 1e-09 [mm/s]"),
    (("--vmax", "200", "--amax", "1e-9"), "--amax = 1e-09 [mm/s^2]"),
    (("--vmax", "200", "--amax", "2000", "--jmax", "1e-9"), "--jmax = 1e-09 [mm/s^3]"),
    (("--vmax", "200", "--amax", "2000", "--ts1", "1e-9", "--ts2", "1e-9"), "--ts2 = 1e-09 [s]"),
])
def test_limits_and_periods_that_ask_for_too_many_samples(capsys, tmp_path, extra, needle):
    line = _refused(capsys, tmp_path, SQUARE, *extra, limits=())
    assert line.startswith(f"netshape plan: error: {needle}"), line
    assert "raise --max-samples" in line


def test_max_samples_lowers_the_budget(capsys, tmp_path):
    line = _refused(capsys, tmp_path, SQUARE, "--max-samples", "1000")
    assert "over the limit of 1000" in line


def test_a_program_within_the_budget_runs(capsys, tmp_path):
    p = tmp_path / "p.ngc"
    p.write_text(SQUARE)
    assert main(["plan", str(p), "--vmax", "200", "--amax", "2000", "--rule", "vector", "--json",
                 str(tmp_path / "o.json"), "--max-samples", "100000"]) == 0
    assert json.loads((tmp_path / "o.json").read_text())["samples"] < 100000


def test_a_deep_lookahead_on_a_short_program_costs_no_memory(capsys, tmp_path):
    """--lookahead 100000 on a 5-block program once sized the planner's ring for 100000 blocks (3 GB);
    the ring now holds what the program can use, with the same trajectory."""
    p = tmp_path / "p.ngc"
    p.write_text(SQUARE)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    results = []
    for la in ("64", "100000"):
        out = tmp_path / f"o{la}.json"
        assert main(["plan", str(p), "--vmax", "200", "--amax", "2000", "--rule", "blend", "--json", str(out),
                     "--lookahead", la]) == 0
        results.append(json.loads(out.read_text()))
    grown_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown_kb < 500_000, grown_kb
    assert results[1]["lookahead"] == 100000
    for k in ("cycle_time_s", "samples", "max_axis_velocity_mm_s", "max_axis_accel_mm_s2"):
        assert results[0][k] == results[1][k], k


def test_the_planner_stops_at_max_samples_where_the_estimate_is_low(capsys, tmp_path):
    """The estimate is a lower bound (corners slow the tool further); the planner itself stops at the bound
    with a ValueError, so the memory stays bounded (the CLI names --max-samples)."""
    from netshape import motion, toolpath

    p = tmp_path / "p.ngc"
    p.write_text(SQUARE)
    a = toolpath.read_gcode_arrays(p)
    limits = motion.AxisLimits.uniform(200.0, 2000.0, float("inf"))
    assert len(motion.plan(a, limits, rule="vector", max_samples=100000).t) == 45262
    with pytest.raises(ValueError, match=r"^max_samples = 45100: the plan needs more fine samples"):
        motion.plan(a, limits, rule="vector", max_samples=45100)
    assert main(["plan", str(p), "--vmax", "200", "--amax", "2000", "--rule", "vector", "--json",
                 str(tmp_path / "o.json"), "--max-samples", "45100"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("netshape plan: error: --max-samples = 45100: the plan needs more fine samples"), err
    assert not (tmp_path / "o.json").exists()


def test_a_tiny_jerk_limit_is_refused_before_the_samples_are_made(tmp_path):
    """The planned time of the first segments already implies more samples than allowed: the planner
    refuses then, instead of filling ~70 B per sample up to the limit (3.4 GB for 5e7) first."""
    import subprocess
    import sys
    import textwrap
    from pathlib import Path

    p = tmp_path / "p.ngc"
    p.write_text(SQUARE)
    if not Path("/proc/self/status").exists():
        pytest.skip("needs /proc/self/status (VmHWM) to read the peak memory")
    # VmHWM: the peak resident memory of this process image (ru_maxrss would keep the forking
    # parent's peak across exec)
    script = textwrap.dedent(f"""
        import re
        from pathlib import Path
        from netshape import motion, toolpath
        a = toolpath.read_gcode_arrays({str(p)!r})
        limits = motion.AxisLimits.uniform(200.0, 2000.0, 1e-7)
        try:
            motion.plan(a, limits, rule="blend", ts2=1e-3, max_samples=50_000_000)
        except ValueError as exc:
            print(str(exc).split(";")[0])
        print(re.search(r"VmHWM:\\s*(\\d+) kB", Path("/proc/self/status").read_text()).group(1))
    """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True).stdout
    message, rss_kb = out.strip().splitlines()
    assert message.startswith("max_samples = 50000000: the plan needs more fine samples")
    assert int(rss_kb) < 1_000_000  # well below the 3.4 GB the samples up to the limit would take
