"""The learning loop for a machine (issue 43 item 4): measure a grid, diagnose, update the machine,
compensate a program with the updated machine.

    python examples/volumetric_learning.py [--out DIR]

The "real" machine is examples/demo/machine.toml with three errors its file does not hold: an X
backlash of 8 µm, a ball-screw cyclic error of Y (period 40 mm, 3 µm) and a thermal drift of the
spindle along Z (12 µm, τ = 20 min). A volumetric check measures a serpentine grid on it
(netshape.discrepancy.simulate, σ = 0.5 µm, two tool lengths). The diagnosis against the demo
machine names what is missing and writes DIR/machine_learned.toml (the demo file with the found terms
added under comments naming the diagnosis); the re-diagnosis against it finds nothing; and a pocket
program compensated with the demo machine and with the learned one is run on the real machine: the
tip error at the block ends is printed for both. Writes into DIR (default ./volumetric_learning_out):
bundle/ (manifest.toml + CSV), diagnosis.json, machine_learned.toml, part.ngc, part_comp.ngc,
summary.json.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

import netshape as ns
import netshape.discrepancy as nd
from netshape._atomic import atomic_write
from netshape.discrepancy.simulate import measure_grid, program_tip_errors

HERE = Path(__file__).resolve().parent
DEMO = HERE / "demo" / "machine.toml"
HIDDEN = """
[[axes.Y.cyclic]]
period_mm = 40.0
amplitude_um = 3.0
phase_deg = 60.0

[[thermal]]
axis = "Z"
amplitude_mm = 0.012
time_constant_s = 1200.0
"""
PART = "G21 G90 G17\nG0 X-150 Y-100 Z-60\nG1 F400\n" + "".join(
    f"G1 X{150 if i % 2 == 0 else -150}\nG1 Y{-100 + 25 * (i + 1)}\n" for i in range(8)
) + "G3 X-150 Y140 I0 J20\nG1 X0 Y0\nM30\n"


def real_machine(out: Path) -> Path:
    text = DEMO.read_text().replace("origin_mm = [0.0, 0.0, 80.0]", "origin_mm = [0.0, 0.0, 80.0]\nbacklash_um = 8.0")
    p = out / "machine_real.toml"
    p.write_text(text + HIDDEN)
    return p


def rms_um(e) -> float:
    return 1e3 * float(np.sqrt(np.mean(np.sum(np.asarray(e) ** 2, axis=1))))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="volumetric_learning_out")
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    real = real_machine(out)
    # 1. measure: a 17 × 17 × 3 serpentine grid (the Y levels 18.75 mm apart show a 40 mm period)
    bundle = measure_grid(real, out / "bundle", model=DEMO, lo=(-200.0, -150.0, -200.0), hi=(200.0, 150.0, 0.0),
                          counts=(9, 17, 3), seed=7)
    # 2. diagnose against the demo machine and write the learned machine
    d = nd.diagnose(bundle, machine=DEMO)
    print(d.summary())
    learned = out / "machine_learned.toml"
    with atomic_write(learned) as fh:
        fh.write(d.apply(DEMO))
    with atomic_write(out / "diagnosis.json") as fh:
        json.dump(d.to_dict(), fh, indent=2)
    again = nd.diagnose(bundle, machine=learned)
    print(f"re-diagnosis against {learned.name}: effect {again.effect}")
    # 3. compensate a program with either machine and run it on the real one
    (out / "part.ngc").write_text(PART)
    nominal = ns.toolpath.read_gcode(out / "part.ngc")
    res = {}
    for name, machine in (("uncompensated", None), ("demo machine", DEMO), ("learned machine", learned)):
        cmd = nominal
        if machine is not None:
            cmd, rep = ns.compensation.compensate_program(ns.machine.load_machine(machine), nominal,
                                                         chord_tolerance=5e-4)
            if name == "learned machine":
                ns.toolpath.write_gcode(cmd, out / "part_comp.ngc")
        res[name] = rms_um(program_tip_errors(real, cmd, nominal))
        print(f"tip error at the block ends, {name}: rms {res[name]:.2f} um")
    summary = {"effects": d.to_dict()["effects"], "re_diagnosis_effect": again.effect, "tip_error_rms_um": res}
    with atomic_write(out / "summary.json") as fh:
        json.dump(summary, fh, indent=2)


if __name__ == "__main__":
    main()
