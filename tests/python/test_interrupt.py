"""Ctrl-C and progress reports reach long C++ computations (netshape._progress).

The core reports from its long loops; the extension runs pending signal handlers and the optional
Python callback there, so an exception from either stops the C++ loop instead of waiting for it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from netshape import _core
from netshape.cutter import Cutter
from netshape.stock import ZMap

REPO = Path(__file__).resolve().parents[2]


def _env() -> dict:
    """The environment of a child Python that imports the same netshape as this one (the installed
    package, or the source tree a development run put on the path)."""
    return dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))


def _lines(n: int, seed: int = 1):
    rng = np.random.default_rng(seed)
    a = np.c_[rng.uniform(0, 200, (n, 2)), np.full(n, 5.0)]
    b = np.c_[rng.uniform(0, 200, (n, 2)), np.full(n, 5.0)]
    return a, b


def test_an_exception_from_the_callback_stops_the_loop_and_the_next_call_runs_whole():
    z = ZMap(0, 200, 0, 200, 0.05, 10, 0)
    tool = Cutter.flat_end(10.0, 2, 0.5236)
    a, b = _lines(3000)
    calls = []

    class Stop(Exception):
        pass

    def callback(what, done, total):
        calls.append((what, done, total))
        if len(calls) == 2:
            raise Stop

    _core.set_progress(callback)
    try:
        with pytest.raises(Stop):
            _core.stock.sweep_lines(z, tool, a, b)
    finally:
        _core.set_progress(None)
    assert [c[0] for c in calls] == ["sweep", "sweep"]
    assert calls[0][2] == 3000 and 0 < calls[0][1] < calls[1][1] < 3000  # stopped part way

    # the stop left nothing behind: a fresh sweep with no callback runs to the end
    z2 = ZMap(0, 200, 0, 200, 0.5, 10, 0)
    stats = _core.stock.sweep_lines(z2, tool, a[:50], b[:50])
    assert stats.moves == 50


def test_a_volumetric_compensation_reports_and_stops_when_asked(tmp_path):
    from netshape.compensation.volumetric import compensate_program
    from netshape.machine import load_machine

    def program(n):
        rng = np.random.default_rng(3)
        pts = np.c_[rng.uniform(-240, 240, (n, 2)), rng.uniform(-300, -100, n)]
        ngc = tmp_path / f"long{n}.ngc"
        ngc.write_text("G21 G90 G17 G94\nG54\n" + "".join(f"G1 X{x:.3f} Y{y:.3f} Z{z:.3f} F3000\n"
                                                           for x, y, z in pts) + "M30\n")
        return ngc

    machine = load_machine(REPO / "examples" / "machines" / "vmc.toml")
    calls = []

    class Stop(Exception):
        pass

    def callback(what, done, total):
        calls.append((what, done, total))
        raise Stop

    # the hook is called at most every 50 ms: the halvings here take ~0.4 s of CPU (0.05 s at 0.1 mm)
    _core.set_progress(callback)
    try:
        with pytest.raises(Stop):
            compensate_program(machine, program(20000), chord_tolerance=1e-4)
    finally:
        _core.set_progress(None)
    assert calls and calls[0][0] == "volumetric compensation" and calls[0][2] == 0 and calls[0][1] > 0
    _, report = compensate_program(machine, program(500), chord_tolerance=1e-3)  # nothing left behind
    assert report.blocks_in >= 500


def test_progress_context_shows_a_bar_per_stage_and_removes_the_callback(capsys):
    from netshape._progress import progress

    z = ZMap(0, 200, 0, 200, 0.05, 10, 0)
    tool = Cutter.flat_end(10.0, 2, 0.5236)
    a, b = _lines(1500)
    with progress("test", enabled=True):
        _core.stock.sweep_lines(z, tool, a, b)
    err = capsys.readouterr().err
    assert "test: sweep" in err


def test_ctrl_c_stops_a_long_sweep_in_cpp_promptly():
    # ~10^5 random lines on a 0.05 mm Z-map: minutes of C++ work if not stopped
    script = textwrap.dedent("""
        import sys, time
        import numpy as np
        from netshape import _core
        from netshape.cutter import Cutter
        from netshape.stock import ZMap

        rng = np.random.default_rng(1)
        n = 100000
        a = np.c_[rng.uniform(0, 200, (n, 2)), np.full(n, 5.0)]
        b = np.c_[rng.uniform(0, 200, (n, 2)), np.full(n, 5.0)]
        z = ZMap(0, 200, 0, 200, 0.05, 10, 0)
        tool = Cutter.flat_end(10.0, 2, 0.5236)
        print("go", flush=True)
        try:
            _core.stock.sweep_lines(z, tool, a, b)
        except KeyboardInterrupt:
            print("stopped", flush=True)
            sys.exit(3)
        print("finished", flush=True)
    """)
    env = _env()
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
    try:
        assert proc.stdout.readline().strip() == "go"
        time.sleep(0.5)  # inside the C++ sweep by now
        proc.send_signal(signal.SIGINT)
        out, _ = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 3, out
    assert "stopped" in out and "finished" not in out


def test_ctrl_c_during_a_job_exits_130_and_writes_nothing(tmp_path):
    out_dir = tmp_path / "demo"
    env = _env()
    proc = subprocess.Popen([sys.executable, "-m", "netshape", "demo", "--out", str(out_dir), "--quiet"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        time.sleep(4.0)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        proc.kill()
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert not out_dir.exists() or not any(out_dir.iterdir())  # all or nothing: nothing
