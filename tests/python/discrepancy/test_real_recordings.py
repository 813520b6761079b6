"""The workflow on real dynamometer recordings: ../shared/data/leekunhwee-flat-slot (Kistler DynoWare
exports, 2-flute flat end mill, full slot, a_p 3 mm, 6000 rpm; read by path, never copied).

The bundle's model is what netshape's calibration fits to these recordings (the Altintas mean-force
regression, netshape.force.calibrate_mean_forces); the tool diameter is not given with the data
(10 mm assumed, helix 0°: the helix scan of examples/force_calibration_dynoware.py prefers no lag).
The linear model reproduces the time series with a 48–58 % relative rms residual; the recordings'
README reports alternate tooth peaks differing by up to 27 % (runout) and the force docs a ~1 kHz
ringing. The workflow must name runout first and close part of the gap.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import netshape.discrepancy as nd
import netshape.force as nf

pytestmark = [pytest.mark.shared_data, pytest.mark.slow]


def write_bundle(folder, files, window_s):
    feeds, means = [], []
    for p in files:
        r = nf.read_dynoware(p, to_cutter="leekunhwee")
        feeds.append(int(re.search(r"f(\d+)ap", p.name).group(1)) / (6000 * 2))
        means.append(nf.recording_mean_force(r.times, r.forces, 6000.0))
    k = nf.calibrate_mean_forces(feeds, np.array(means), flutes=2, axial_depth=3.0).coefficients
    names = (
        "Ktc_N_per_mm2",
        "Krc_N_per_mm2",
        "Kac_N_per_mm2",
        "Kte_N_per_mm",
        "Kre_N_per_mm",
        "Kae_N_per_mm",
    )
    lines = [
        'kind = "cutting_force"',
        "[tool]",
        'type = "flat"',
        "diameter_mm = 10.0",
        "flutes = 2",
        "helix_deg = 0.0",
        "[model]",
    ] + [f"{n} = {v!r}" for n, v in zip(names, k.as_array())]
    for p, c in zip(files, feeds):
        lines += [
            "[[experiment]]",
            f'file = "{p}"',
            'format = "dynoware"',
            'to_cutter = "leekunhwee"',
            "spindle_rpm = 6000.0",
            f"feed_per_tooth_mm = {c!r}",
            "axial_depth_mm = 3.0",
            'mode = "slot"',
            f"time_window_s = [0.0, {window_s}]",
        ]
    (folder / "manifest.toml").write_text("\n".join(lines) + "\n")
    return folder


def test_leekunhwee_runout_is_named_and_the_gap_shrinks(shared_data, tmp_path):
    """Three recordings (f_t 0.025, 0.075, 0.125 mm), 6 revolutions each: runout is the first effect
    (ρ·cos λ of order 10 µm), and the effects added cut the rms residual by more than 15 %."""
    folder = shared_data / "leekunhwee-flat-slot"
    files = [folder / f"6-n6000f{f}ap3ae25.csv" for f in (300, 900, 1500)]
    if not all(p.is_file() for p in files):
        pytest.skip(f"{folder}: recordings absent")
    d = nd.diagnose(write_bundle(tmp_path, files, 0.06))
    assert d.effect == "runout"
    assert 0.003 < d.parameters["rho_mm"] < 0.03
    assert d.rms_after < 0.85 * d.rms_before
    assert d.noise_estimate < d.rms_after  # the model still misses something: said in the notes
    assert any("still above the noise" in n for n in d.notes)
