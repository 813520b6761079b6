"""Calibrate the linear edge-force model on real dynamometer recordings and show how well it
reproduces them over time.

Data: the leekunhwee-flat-slot recordings (Kistler DynoWare CSV, 10 kHz; 2-flute flat end mill,
full slot, a_p = 3 mm, 6000 rpm, f_t = 0.025 … 0.125 mm/tooth), not shipped with netshape: download the
CSV files of github.com/leekunhwee/ForceCalculation (Jianhui Li) into a folder and pass it as --data.
Read by path, never copied.

Steps
1. read each recording and map the dynamometer channels to forces ON THE CUTTER in the cutting
   frame of docs/conventions.md §2 (C = (dyn Fy, dyn Fx, dyn Fz), see netshape.force.dynoware);
2. mean force over whole revolutions → Altintas mean-force regression → Ktc … Kae;
3. per recording: the model with those coefficients, its angle offset found by a phase fit and the
   helix lag scanned (diameter and helix are not given: only the lag over the depth, a_p·tanβ/R,
   shapes the waveform; D = 10 mm is assumed and the helix fitted), plotted against the measurement
   over a few revolutions (PNG per recording).

Run: python examples/force_calibration_dynoware.py [--data DIR] [--out DIR] [--revolutions N]
"""

from __future__ import annotations

import argparse
import json
import math
import re
from pathlib import Path

import numpy as np

import netshape.force as nf
from netshape._atomic import atomic_save_figure, atomic_write
from netshape.force.plots import plot_measured_vs_simulated

HERE = Path(__file__).resolve().parent
DEFAULT_DATA = HERE.parent.parent / "shared" / "data" / "leekunhwee-flat-slot"
FLUTES, AP, RPM = 2, 3.0, 6000.0
ASSUMED_DIAMETER = 10.0


def conditions(path: Path) -> tuple[float, float]:
    """(rpm, feed per tooth [mm]) from a name like 6-n6000f300ap3ae25.csv (F in mm/min)."""
    m = re.search(r"n(\d+)f(\d+)ap", path.name)
    if not m:
        raise ValueError(f"file name = {path.name!r}: expected n<rpm>f<feed mm/min>ap…")
    rpm, feed = float(m.group(1)), float(m.group(2))
    return rpm, feed / (rpm * FLUTES)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", type=Path, default=DEFAULT_DATA,
                    help="folder of the leekunhwee-flat-slot DynoWare CSV files "
                         "(github.com/leekunhwee/ForceCalculation)")
    ap.add_argument("--out", type=Path, default=Path("force_calibration_out"))
    ap.add_argument("--revolutions", type=int, default=4, help="revolutions plotted and phase-fitted")
    args = ap.parse_args(argv)
    files = sorted(args.data.glob("*.csv"), key=lambda p: conditions(p)[1])
    if not files:
        raise SystemExit(f"--data = {args.data}: no CSV files (download the leekunhwee-flat-slot recordings "
                         "of github.com/leekunhwee/ForceCalculation and pass their folder)")
    args.out.mkdir(parents=True, exist_ok=True)
    recs, feeds, means = [], [], []
    for p in files:
        rpm, c = conditions(p)
        r = nf.read_dynoware(p, to_cutter="leekunhwee")
        recs.append((p, rpm, c, r))
        feeds.append(c)
        means.append(nf.recording_mean_force(r.times, r.forces, rpm))
    fit = nf.calibrate_mean_forces(feeds, np.array(means), flutes=FLUTES, axial_depth=AP)
    k = fit.coefficients
    print("mean-force regression (N = 2, a_p = 3 mm):")
    print("  Ktc = %.1f  Krc = %.1f  Kac = %.1f N/mm^2   Kte = %.2f  Kre = %.2f  Kae = %.2f N/mm"
          % (k.ktc, k.krc, k.kac, k.kte, k.kre, k.kae))
    print("  r^2 (x, y, z) = %.3f %.3f %.3f" % tuple(fit.r2))
    result = {"coefficients": k.to_dict(), "r2": list(map(float, fit.r2)), "recordings": []}
    helix_grid = [math.radians(h) for h in range(0, 61, 5)]
    for p, rpm, c, r in recs:
        n = int(round(args.revolutions * 60.0 / rpm * r.sampling_rate))
        t, F = r.times[:n], r.forces[:n]
        rf = nf.fit_recording(t, F, rpm=rpm, feed_per_tooth=c, flutes=FLUTES, axial_depth=AP,
                              radius=ASSUMED_DIAMETER / 2, helix_grid=helix_grid, fixed=k, phase_steps=36)
        peak_meas = np.abs(F).max(axis=0)
        peak_sim = np.abs(rf.simulated).max(axis=0)
        rel = float(np.sqrt(np.mean((F - rf.simulated) ** 2)) / np.sqrt(np.mean(F**2)))
        print(f"  {p.name}: f_t = {c:.3f} mm, helix (D {ASSUMED_DIAMETER:g} assumed) = "
              f"{math.degrees(rf.helix):.0f} deg, phase = {math.degrees(rf.phase):.1f} deg, rms (x, y, z) = "
              f"{rf.rms[0]:.1f} {rf.rms[1]:.1f} {rf.rms[2]:.1f} N, relative rms {100 * rel:.0f} %")
        fig = plot_measured_vs_simulated(
            t, F, rf.simulated,
            title=f"{p.name}: f_t {c:.3f} mm, slot a_p 3 mm, {rpm:.0f} rpm - measured vs linear edge model "
                  f"(mean-force coefficients, phase fitted)")
        png = args.out / (p.stem + "_measured_vs_model.png")
        atomic_save_figure(fig, png, dpi=90)
        result["recordings"].append({
            "file": p.name, "feed_per_tooth": c, "mean_measured": means[feeds.index(c)].tolist(),
            "mean_model": list(map(float, nf.mean_force(k, nf.AngularEngagement(0, math.pi), c, FLUTES, AP))),
            "helix_deg": math.degrees(rf.helix), "phase_deg": math.degrees(rf.phase),
            "rms_N": rf.rms.tolist(), "relative_rms": rel, "peak_measured": peak_meas.tolist(),
            "peak_model": peak_sim.tolist(), "plot": png.name})
    with atomic_write(args.out / "calibration.json", "w") as fh:
        json.dump(result, fh, indent=2)
    return result


if __name__ == "__main__":
    main()
