"""Z-map example: cut a pocket with a flat end mill and finish a ramp with a ball end mill, report the
removed volume and the engagement at one position, write the heights as STL and a PNG.

    PYTHONPATH=python python examples/stock_zmap.py [--out DIR] [--spacing MM]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import netshape as ns
from netshape._atomic import atomic_save_figure

PROGRAM = """(pocket and ramp)
G21 G90 G17
G0 X-8 Y15 Z25
G1 Z16 F800
G1 X35
G2 X45 Y25 I0 J10
G1 Y45
G3 X35 Y55 I-10 J0
G1 X-8
G0 Z25
"""


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", type=Path, default=Path("."), help="output folder (default: here)")
    p.add_argument("--spacing", type=float, default=0.1, help="grid spacing [mm]")
    args = p.parse_args(argv)

    z = ns.stock.ZMap(0.0, 80.0, 0.0, 70.0, args.spacing, 20.0, 0.0)
    flat = ns.stock.Cutter.flat_end(10.0)
    ball = ns.stock.Cutter.ball_end(8.0)
    prog = ns.toolpath.parse_gcode(PROGRAM, source="example")
    s1 = ns.stock.sweep(z, flat, prog)
    # a ball-end ramp from z = 20 down to z = 14 across the block
    s2 = ns.stock.sweep_line(z, ball, (60.0, -5.0, 20.0), (60.0, 75.0, 14.0))

    # engagement of the flat end mill half-way along the first G1, before that move's last step
    tip = np.array([20.0, 15.0, 16.0])
    z2 = ns.stock.ZMap(0.0, 80.0, 0.0, 70.0, args.spacing, 20.0, 0.0)
    ns.stock.sweep_line(z2, flat, (-8.0, 15.0, 16.0), tip - [0.05, 0.0, 0.0])
    im = ns.stock.immersion(z2, flat, tip, (1.0, 0.0, 0.0))

    args.out.mkdir(parents=True, exist_ok=True)
    z.to_stl(args.out / "stock_zmap.stl")
    atomic_save_figure(z.plot(title="pocket + ball ramp"), args.out / "stock_zmap.png", dpi=100)
    result = {
        "grid": (z.ny, z.nx),
        "removed_mm3": s1.removed_volume + s2.removed_volume,
        "volume_mm3": z.volume(),
        "slot_phi_st_deg": math.degrees(im.phi_st),
        "slot_phi_ex_deg": math.degrees(im.phi_ex),
        "slot_axial_depth_mm": im.axial_depth,
    }
    for k, v in result.items():
        print(f"{k:22s} {v}")
    return result


if __name__ == "__main__":
    main()
