"""Whether cyclic_error (netshape/discrepancy/volumetric_catalogue.py) is named when a ball-screw
cyclic error is there, and only then (issue 37 item 3).

    PYTHONPATH=python python bench/discrepancy_cyclic.py

Family: per seed, a volumetric bundle on a 57 × 7 × 3 grid (random order for odd seeds, X fastest
for even ones), noise σ 0.5–2 µm, and either nothing (control) or a cyclic error on X (amplitude
2–6 µm, period 10–60 mm, random phase). The only threshold the naming uses is the workflow's
BIC_MARGIN; seeds 0–9 (tuning half) give the largest BIC drop cyclic_error reaches on the controls
(its null distribution), which must stay below BIC_MARGIN; seeds 10–19 (check half) report false
namings on the controls, and naming, period and amplitude errors on the cyclic bundles.
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python" / "discrepancy"))

import netshape.discrepancy as nd  # noqa: E402
from netshape.discrepancy import workflow  # noqa: E402
from generators import structured_volumetric_bundle  # noqa: E402


def family_case(seed: int, cyclic: bool):
    rng = np.random.default_rng(2000 + seed)
    noise = float(rng.uniform(0.5e-3, 2e-3))
    amp, period = float(rng.uniform(2e-3, 6e-3)), float(rng.uniform(10.0, 60.0))
    extra = [("periodic", "ex", "x", amp, period)] if cyclic else []
    kw = dict(extra=extra, noise=noise, seed=seed, order="random" if seed % 2 else "x")
    return kw, (amp, period) if cyclic else None


def run(tmp, seed, cyclic):
    kw, truth = family_case(seed, cyclic)
    return nd.diagnose(structured_volumetric_bundle(Path(tmp) / f"{seed}{cyclic}", **kw)), truth


def main():
    with tempfile.TemporaryDirectory() as tmp:
        drops = []
        for seed in range(10):
            d, _ = run(tmp, seed, False)
            bic0 = d.problem.bic(d.spec_before, len(d.problem.nuisance_experiments()))
            c = next(c for c in d.candidates if c["effect"] == "cyclic_error")
            drops.append(bic0 - c["bic"])
        print(f"tuning half (seeds 0-9): cyclic_error's BIC drop on controls {np.round(drops, 1).tolist()}, "
              f"max {max(drops):.1f} (BIC_MARGIN {workflow.BIC_MARGIN})")
        false, named, perr, aerr = 0, 0, [], []
        for seed in range(10, 20):
            d, _ = run(tmp, seed, False)
            false += bool(d.effects)
            d, (amp, period) = run(tmp, seed, True)
            if d.effect == "cyclic_error" and d.parameters["axis"] == "X":
                named += 1
                perr.append(abs(d.parameters["period_mm"] / period - 1))
                aerr.append(abs(d.parameters["amplitude_mm"] / amp - 1))
            print(f"  seed {seed}: truth {amp * 1e3:.2f} µm, {period:.2f} mm; named {d.effect} {d.parameters}")
        print(f"check half (seeds 10-19): false namings on controls {false}/10, cyclic_error named {named}/10, "
              f"max period error {100 * max(perr, default=math.nan):.2f} %, "
              f"max amplitude error {100 * max(aerr, default=math.nan):.1f} %")


if __name__ == "__main__":
    main()
