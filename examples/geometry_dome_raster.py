"""Design surface → offset → CL points → raster G-code, and a pocket with an island (Yang & Kweon §3).

    PYTHONPATH=python python examples/geometry_dome_raster.py [--out DIR] [--scallop 0.01]

Builds an exact rational spherical cap (NURBS surface of revolution), checks the offset surface
(eq. 12) against closest-point distances, makes a ball-end-mill raster at a scallop-height target,
writes it as G-code through the toolpath writer, and writes a pocket with round-corner rings.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import netshape.geometry as g
import netshape.toolpath as tp


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("out_geometry"))
    ap.add_argument("--scallop", type=float, default=0.01, help="scallop height [mm]")
    ap.add_argument("--radius", type=float, default=40.0, help="cap radius [mm]")
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    # design surface Q(u, v): arc from the pole down to 35° colatitude, revolved about z
    prof = g.circular_arc([0, 0, 0], [0, 0, 1], [1, 0, 0], args.radius, 0.0, math.radians(35))
    cap = g.revolve(prof, [0, 0, 0], [0, 0, 1], 2 * math.pi)
    g.save_json(cap, args.out / "cap.json")

    # offset surface O = Q + d n (eq. 12), d = ball radius: the ball centres
    R = 3.0
    uv = np.random.default_rng(0).random((200, 2))
    centres = g.offset_points(cap, uv, R)
    err = max(abs(cap.closest_point(c).distance - R) for c in centres[:40])

    path = g.raster_toolpath(cap, ("ball", R), scallop_height=args.scallop, chord_tolerance=0.005, feed=30.0)
    path.write_gcode(args.out / "cap_raster.ngc")
    back = tp.read_gcode(args.out / "cap_raster.ngc")

    square = np.array([[0, 0], [60, 0], [60, 40], [0, 40]], float)
    island = np.array([[25, 15], [35, 15], [35, 25], [25, 25]], float)
    pocket = g.pocket_toolpath(square, [island], tool_radius=4.0, step_over=3.0, z=-2.0, feed=15.0)
    tp.write_gcode(pocket, args.out / "pocket.ngc")

    summary = {
        "offset_distance_error_mm": float(err),
        "raster_blocks": len(path),
        "raster_feed_length_mm": path.feed_length(),
        "gcode_blocks_read_back": len(back.blocks),
        "pocket_blocks": len(pocket.blocks),
    }
    for k, v in summary.items():
        print(f"{k:28s} {v}")
    return summary


if __name__ == "__main__":
    main()
