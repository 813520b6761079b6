"""Discrepancy workflow: time per bundle of netshape.discrepancy.diagnose, and the cost of one model
evaluation on the C++ kernel against the NumPy element sum of the test generators (the same model
evaluated directly at the measured angles), measured in the same run.

    PYTHONPATH=python python bench/discrepancy.py [--repeats 3]

Bundles (tests/python/discrepancy/generators.py): a cutting-force bundle of 4 experiments (slot at
0.04 and 0.1 mm, up and down milling; 3 revolutions of 180 samples; hidden runout), the same as time
series (the angle of flute 1 fitted as well), a volumetric bundle of 2 × 105 points (hidden
squareness), a wall-error bundle of 3 steady cuts × 804 points and one of 2 contours (program, tool,
stock) × 2005 points (hidden holder spring and runout; the contour time includes the deflection
prediction along each program). Times are CPU times of this process (time.process_time) and wall clock.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python" / "discrepancy"))

import netshape.discrepancy as nd  # noqa: E402
from generators import CONDITIONS, MODEL, force_bundle, oracle_forces, volumetric_bundle, wall_bundle, wall_contour_bundle  # noqa: E402


def timed(fn, repeats):
    best_cpu, best_wall, out = np.inf, np.inf, None
    for _ in range(repeats):
        c, w = time.process_time(), time.perf_counter()
        out = fn()
        best_cpu, best_wall = min(best_cpu, time.process_time() - c), min(best_wall, time.perf_counter() - w)
    return best_cpu, best_wall, out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    print(f"load average {os.getloadavg()[0]:.1f}")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cases = [
            (
                "force, 4 experiments, angle_deg, hidden runout",
                force_bundle(tmp / "fa", runout=(0.008, 60.0)),
            ),
            (
                "force, 4 experiments, time_s, hidden runout",
                force_bundle(tmp / "ft", runout=(0.008, 60.0), form="time"),
            ),
            (
                "volumetric, 2 x 105 points, hidden squareness",
                volumetric_bundle(tmp / "v", squareness={"EC0Y": 30.0}),
            ),
            (
                "wall error, 3 cuts x 804 points, hidden holder spring + runout",
                wall_bundle(tmp / "w", holder_stiffness=10.0, runout=(0.004, 40.0)),
            ),
            (
                "wall error along 2 contours (program + tool + stock) x 2005 points, hidden holder spring + runout",
                wall_contour_bundle(tmp / "wc", holder_stiffness=10.0, runout=(0.004, 40.0)),
            ),
        ]
        print("| bundle | effect found | CPU s | wall s | rms before → after |")
        print("|---|---|---|---|---|")
        for label, folder in cases:
            b = nd.load_bundle(folder)
            cpu, wall, d = timed(lambda: nd.diagnose(b), args.repeats)
            found = " + ".join(e["effect"] for e in d.effects) or None
            print(f"| {label} | {found} | {cpu:.2f} | {wall:.2f} | {d.rms_before:.4g} → {d.rms_after:.4g} |")
        # one model evaluation with runout: kernel grid + interpolation vs the NumPy element sum
        b = nd.load_bundle(cases[0][1])
        prob = nd.ForceProblem(b)
        import dataclasses
        import math

        spec = dataclasses.replace(prob.initial_spec(), runout=(0.008, math.radians(60.0)))

        def kernel():
            prob._cache.clear()
            return prob.predict(spec)

        def numpy_sum():
            return [
                oracle_forces(
                    e.angles, feed=c, mode=m, ae=ae, coefficients=MODEL, runout=(0.008, 60.0), dz=0.05
                )
                for e, (m, ae, c) in zip(b.experiments, CONDITIONS)
            ]

        ck, _, _ = timed(kernel, 5)
        cn, _, _ = timed(numpy_sum, 5)
        print(
            "\none model evaluation (4 experiments x 540 angles, 60 disks, runout): "
            f"kernel {1e3 * ck:.1f} ms, "
            f"NumPy element sum {1e3 * cn:.1f} ms, ratio {cn / ck:.1f}x"
        )


if __name__ == "__main__":
    main()
