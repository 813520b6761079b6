"""The learning loop for a machine over a family (issue 43 item 3, the wide version of
tests/python/discrepancy/test_update_machine.py): per volumetric catalogue effect, per size and seed,
a virtual machine (examples/demo/machine.toml with the effect hidden) is measured on a serpentine
grid, diagnosed against the demo machine, updated (Diagnosis.apply), re-diagnosed, and a zig-zag
program compensated with either machine is run on the truth.

    PYTHONPATH=python python bench/volumetric_learning.py [--quick]

Prints per case: the effect named, the effect the re-diagnosis names (should be none), and the rms
tip error at the program's block ends left by the original and by the updated machine [µm].
--quick: one size and one seed per effect (the CI size); --sizes 0.5,2 --seeds 1 a part of the family.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEMO = ROOT / "examples" / "demo" / "machine.toml"

from netshape import toolpath  # noqa: E402
from netshape.discrepancy.simulate import closed_loop  # noqa: E402

PROGRAM = "G21 G90 G17\nG0 X-180 Y-120 Z-100\nG1 F300\n" + "".join(
    f"G1 X{180 if i % 2 == 0 else -180}\nG1 Y{-80 + 40 * i}\n" for i in range(6)
) + "G2 X-100 Y120 I40 J0\nG1 X0 Y0 Z-150\nM30\n"


def hidden(effect: str, s: float) -> tuple[list, str]:
    """(replacements in the demo text, appended text) for ``effect`` at size factor ``s``."""
    if effect == "squareness":
        return [("EC0Y_rad = 1.5e-5", f"EC0Y_rad = {1.5e-5 + 25e-6 * s!r}")], ""
    if effect == "scale_error":
        return [("EYY_mm = [-0.001, 3.0e-5]", f"EYY_mm = [-0.001, {3.0e-5 + 20e-6 * s!r}]")], ""
    if effect == "spindle_tilt":
        return [("tilt_a_rad = 5.0e-6", f"tilt_a_rad = {5e-6 + 30e-6 * s!r}")], ""
    if effect == "backlash":
        return [("origin_mm = [0.0, 0.0, 80.0]", f"origin_mm = [0.0, 0.0, 80.0]\nbacklash_um = {6.0 * s!r}")], ""
    if effect == "cyclic_error":
        return [], f"[[axes.X.cyclic]]\nperiod_mm = {60.0 + 20 * s!r}\namplitude_um = {3.0 * s!r}\nphase_deg = 40.0\n"
    return [], f'[[thermal]]\naxis = "Z"\namplitude_mm = {0.01 * s!r}\ntime_constant_s = 900.0\n'


EFFECTS = ("squareness", "scale_error", "spindle_tilt", "backlash", "cyclic_error", "thermal_drift")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--sizes", type=lambda v: [float(x) for x in v.split(",")], default=[0.5, 1.0, 2.0],
                    help="size factors of the hidden effects (default 0.5,1,2)")
    ap.add_argument("--seeds", type=lambda v: [int(x) for x in v.split(",")], default=[0, 1, 2])
    args = ap.parse_args()
    sizes, seeds = ((1.0,), (0,)) if args.quick else (args.sizes, args.seeds)
    nominal = toolpath.parse_gcode(PROGRAM, source="zigzag.ngc")
    base = DEMO.read_text()
    print(f"{'effect':14s} {'size':>5s} {'seed':>4s}  {'named':14s} {'after':8s} {'orig um':>8s} {'upd um':>8s} "
          f"{'left':>6s} {'s':>5s}")
    worst = 0.0
    for effect in EFFECTS:
        for s in sizes:
            for seed in seeds:
                with tempfile.TemporaryDirectory() as tmp:
                    tmp = Path(tmp)
                    repl, extra = hidden(effect, s)
                    text = base
                    for a, b in repl:
                        text = text.replace(a, b)
                    (tmp / "truth.toml").write_text(text + ("\n" + extra if extra else ""))
                    t0 = time.perf_counter()
                    r = closed_loop(tmp / "truth.toml", DEMO, tmp, nominal, seed=seed)
                    dt = time.perf_counter() - t0
                eo, eu = 1e3 * r["error_original_mm"], 1e3 * r["error_updated_mm"]
                worst = max(worst, eu / eo)
                print(f"{effect:14s} {s:5.2f} {seed:4d}  {str(r['diagnosis'].effect):14s} "
                      f"{str(r['again'].effect):8s} {eo:8.3f} {eu:8.3f} {100 * eu / eo:5.1f}% {dt:5.1f}")
    print(f"largest share of the original error left: {100 * worst:.1f} %")


if __name__ == "__main__":
    main()
