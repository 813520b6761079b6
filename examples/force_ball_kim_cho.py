"""Ball-end milling forces after Kim, Cho, Kim & Chu, "Cutting force prediction in the ball-end milling
process of various cutting area using Z-map": the edge-element model with the paper's published
coefficients (netshape set ``kim_zas_ball12``: D 12 mm, 2 flutes, 30° helix), in three steady cuts over
one revolution (a slot, a down-milling side cut, a slot ramping up at ξ = 20°) and along a program cut
through a Z-map, where each element's engagement is read from the stock as it stands (a pass beside
the wall an earlier cut left).

Prints the mean forces of the steady cuts and, for the side pass of the program, the Z-map's mean force
against the steady side cut of the same width (they agree once the pass is under way); writes
ball_forces.png.

    PYTHONPATH=python python examples/force_ball_kim_cho.py [--out DIR] [--spacing MM]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import netshape as ns  # noqa: E402
from netshape._atomic import atomic_save_figure  # noqa: E402

D, FLUTES, HELIX = 12.0, 2, 30.0  # [mm], -, [deg]
FZ, AP, AE = 0.08, 2.0, 3.0       # feed per tooth [mm], axial depth [mm], side-pass radial depth [mm]

# one straight pass along +X at depth AP beside a wall: the stock has material only at y >= R - AE (a
# step an earlier pass left), so the pass cuts AE of material on its +Y side, which is up milling for a
# tool turning clockwise (M3) and moving along +X (the cutting frame of docs/conventions)
PROGRAM = f"""(ball-end pass beside a wall, D {D:g} mm, depth {AP:g} mm)
G21 G90 G17 G94
S10000 M3
G0 X-15 Y0 Z5
G1 Z{-AP:g} F600
G1 X40 F1200
G0 Z5
M30
"""


def steady(mode: str, ae: float | None = None, xi: float = 0.0):
    ang, f = ns.force.cutter_forces(tool="ball", diameter=D, flutes=FLUTES, helix_deg=HELIX, feed_per_tooth=FZ,
                                    ap=AP, ae=ae, mode=mode, coefficient_set="kim_zas_ball12",
                                    inclination_deg=xi)
    return np.degrees(ang), f


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", type=Path, default=Path("out/force_ball_kim_cho"), help="output folder")
    p.add_argument("--spacing", type=float, default=0.1, help="Z-map node spacing [mm]")
    args = p.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    cuts = {"slot": steady("slot"), f"up milling, ae {AE:g} mm": steady("up", AE),
            "slot ramping up 20°": steady("slot", xi=20.0)}
    result = {"steady_mean_N": {}}
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for name, (deg, f) in cuts.items():
        m = f.mean(axis=0)
        result["steady_mean_N"][name] = m.tolist()
        print(f"{name:<22} mean (Fx, Fy, Fz) = ({m[0]:7.2f}, {m[1]:7.2f}, {m[2]:7.2f}) N")
        axes[0].plot(deg, np.hypot(f[:, 0], f[:, 1]), label=name)
    axes[0].set(xlabel="immersion of flute 1 at the tip [deg]", ylabel="|Fxy| on the cutter [N]",
                title="steady cuts, one revolution")
    axes[0].legend(fontsize=8)

    cutter = ns.cutter.cutter_from_dict({"kind": "ball", "diameter_mm": D, "flutes": FLUTES, "helix_deg": HELIX,
                                         "flute_length_mm": 20.0, "stick_out_mm": 40.0}, source="example")
    nx, ny = int(round(70.0 / args.spacing)), int(round(30.0 / args.spacing))
    y = -15.0 + (np.arange(ny) + 0.5) * 30.0 / ny
    heights = np.where(y[:, None] >= D / 2 - AE, 0.0, -15.0) * np.ones((1, nx))  # rows along Y
    stock = ns.stock.ZMap.from_heights(heights, -20.0, 50.0, -15.0, 15.0, -15.0)
    program = ns.toolpath.parse_gcode(PROGRAM)
    coeffs = ns.force.ball_end_coefficient_set("kim_zas_ball12").coefficients
    r = ns.force.simulate_program(stock, cutter, program, coeffs, step=1.0, samples_per_revolution=72,
                                  feed_per_tooth=FZ, spindle_rpm=10000.0)
    side = (r.positions[:, 0] > 10.0) & (r.positions[:, 0] < 35.0)
    zmap_mean = r.mean[side].mean(axis=0)
    steady_up = np.asarray(result["steady_mean_N"][f"up milling, ae {AE:g} mm"])
    result["side_pass_zmap_mean_N"] = zmap_mean.tolist()
    print(f"pass beside the wall, through the Z-map: mean (Fx, Fy) = ({zmap_mean[0]:.2f}, {zmap_mean[1]:.2f}) N; "
          f"steady up-milling cut: ({steady_up[0]:.2f}, {steady_up[1]:.2f}) N")
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(r.positions, axis=0), axis=1))])
    axes[1].plot(s, r.peak_resultant, label="peak per revolution")
    axes[1].plot(s, r.mean_resultant, label="mean per revolution")
    axes[1].set(xlabel="path length [mm]", ylabel="|F| [N]", title="pass beside a wall, through a Z-map")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    atomic_save_figure(fig, args.out / "ball_forces.png", dpi=100)
    print(f"removed volume {r.removed_volume:.1f} mm³; plot in {args.out / 'ball_forces.png'}")
    return result


if __name__ == "__main__":
    main()
