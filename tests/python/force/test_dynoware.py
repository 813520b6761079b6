"""DynoWare reader and calibration on the real leekunhwee-flat-slot recordings (skip without data)."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import netshape.force as nf
from netshape.errors import ParseError

REF = dict(ktc=958.8, krc=251.1, kac=146.4, kte=15.8, kre=19.4, kae=18.2)


@pytest.fixture(scope="module")
def slot_data(shared_data):
    d = shared_data / "leekunhwee-flat-slot"
    if not d.is_dir():
        pytest.skip(f"{d} is absent (the leekunhwee-flat-slot recordings)")
    out = []
    for p in sorted(d.glob("*.csv")):
        m = re.search(r"n(\d+)f(\d+)ap", p.name)
        rpm, feed = float(m.group(1)), float(m.group(2))
        r = nf.read_dynoware(p, to_cutter="leekunhwee")
        out.append((feed / (2 * rpm), rpm, r))
    out.sort(key=lambda t: t[0])
    return out


def test_reader_format(slot_data):
    c, rpm, r = slot_data[0]
    assert r.sampling_rate == 10000.0
    assert r.times.shape == (10001,) and r.forces.shape == (10001, 3)
    assert r.channels == ("Time", "Fx", "Fy", "Fz") and r.units == ("s", "N", "N", "N")
    assert r.metadata["Filename"].endswith(".dwd")
    # README reference means (dynamometer frame) for f_t = 0.025: 63.02, −39.78, 55.72 N
    np.testing.assert_allclose(r.raw.mean(axis=0), [63.02, -39.78, 55.72], atol=0.02)
    # cutting frame: C = (dyn Fy, dyn Fx, dyn Fz)
    np.testing.assert_array_equal(r.forces[:, 0], r.raw[:, 1])
    np.testing.assert_array_equal(r.forces[:, 1], r.raw[:, 0])


def test_mean_force_regression_matches_reference(slot_data):
    """README reference (independent regression): Ktc 958.8, Krc 251.1, Kac 146.4 N/mm²,
    Kte 15.8, Kre 19.4, Kae 18.2 N/mm (N = 2, a = 3 mm)."""
    feeds = [c for c, _, _ in slot_data]
    means = np.array([nf.recording_mean_force(r.times, r.forces, rpm) for _, rpm, r in slot_data])
    # physics of the mapping: on the cutter, F̄x (feed) < 0 and F̄y > 0 in slotting
    assert np.all(means[:, 0] < 0) and np.all(means[:, 1] > 0)
    fit = nf.calibrate_mean_forces(feeds, means, flutes=2, axial_depth=3.0)
    k = fit.coefficients.to_dict()
    for name, ref in REF.items():
        assert k[name] == pytest.approx(ref, rel=0.01), name
    assert fit.r2[1] > 0.99


def test_fit_is_stable_leave_one_feed_out(slot_data):
    """Leaving any one of the five feeds out changes Ktc by less than 5 %."""
    feeds = np.array([c for c, _, _ in slot_data])
    means = np.array([nf.recording_mean_force(r.times, r.forces, rpm) for _, rpm, r in slot_data])
    full = nf.calibrate_mean_forces(feeds, means, flutes=2, axial_depth=3.0).coefficients.ktc
    for i in range(len(feeds)):
        keep = np.arange(len(feeds)) != i
        k = nf.calibrate_mean_forces(feeds[keep], means[keep], flutes=2, axial_depth=3.0).coefficients.ktc
        assert abs(k - full) / full < 0.05, (i, k, full)


def test_time_series_phase_fit_reproduces_the_waveform(slot_data):
    """Over 4 revolutions the mean-force model, with its angle offset fitted, explains the measured
    Fy better than its mean alone, and the fitted phase makes the mirrored frame mapping worse."""
    c, rpm, r = slot_data[2]
    n = 400
    k = nf.LinearEdgeCoefficients(**REF)
    fit = nf.fit_recording(r.times[:n], r.forces[:n], rpm=rpm, feed_per_tooth=c, flutes=2, axial_depth=3.0,
                           radius=5.0, helix=math.radians(30), fixed=k, phase_steps=24)
    F = r.forces[:n]
    assert fit.rms[1] < 0.8 * F[:, 1].std()
    mirrored = r.raw[:n] @ np.array([[0, 1.0, 0], [-1.0, 0, 0], [0, 0, 1.0]]).T
    fit_m = nf.fit_recording(r.times[:n], mirrored, rpm=rpm, feed_per_tooth=c, flutes=2, axial_depth=3.0,
                             radius=5.0, helix=math.radians(30), fixed=k, phase_steps=24)
    assert fit.rms_total < fit_m.rms_total


def test_example_runs(slot_data, tmp_path, repo_root):
    """examples/force_calibration_dynoware.py runs and writes its plots and JSON."""
    d = Path(slot_data[0][2].path).parent
    proc = subprocess.run([sys.executable, str(repo_root / "examples" / "force_calibration_dynoware.py"),
                           "--data", str(d), "--out", str(tmp_path), "--revolutions", "2"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "Ktc = 958.8" in proc.stdout
    assert len(list(tmp_path.glob("*.png"))) == 5
    assert (tmp_path / "calibration.json").is_file()


def test_reader_bad_files(tmp_path):
    p = tmp_path / "bad.csv"
    p.write_text("DynoWare,Version 2\nSampling rate [Hz]:,10000\nTime,Fx,Fy,Fz\ns,N,N,N\n0,1,2,3\n0.1,1,x,3\n")
    with pytest.raises(ParseError, match=":6"):
        nf.read_dynoware(p)
    p.write_text("hello\n")
    with pytest.raises(ParseError, match="DynoWare"):
        nf.read_dynoware(p)
    p.write_text("Time,Fx,Fy,Fz\ns,N,N,kN\n0,1,2,3\n1,1,2,3\n")
    with pytest.raises(ParseError, match="Fz"):
        nf.read_dynoware(p)
    p.write_text("Time,Fx,Fy,Fz\ns,N,N,N\n0,1,2,3\n0.5,1,2,3\n")
    r = nf.read_dynoware(p, to_cutter=np.eye(3))
    assert r.sampling_rate == pytest.approx(2.0)
    with pytest.raises(ValueError, match="to_cutter"):
        nf.read_dynoware(p, to_cutter="kistler")
