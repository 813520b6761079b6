"""5-axis tool posture in a narrow impeller passage, after Park, Jung, Hwang & Jung, "A theoretical
consideration for continuity control of cutter posture" (C-space of tilt and rotation per cutter-contact
point, MC-space midpoints between the two C-obstacles, MB-spline smoothing of the posture vectors).

The default impeller's passage is narrow and deep: a ball-end mill held along the floor normal hits the
blades at the inner points. The planner moves every posture into the middle of the free C-space, smooths
the postures along the path, re-checks them against the blades and repairs any the smoothing pushed into
a blade. Prints the collision counts and the largest posture change per stage; writes the postures as
CSV, a B/C machine program, and PNGs of one point's C-space and of the angles along the path.

    PYTHONPATH=python python examples/posture_park.py [--out DIR] [--points N]
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from netshape import posture as npost


def main(argv: list[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", type=Path, default=Path("out/posture_park"), help="output folder")
    p.add_argument("--points", type=int, default=40, help="cutter-contact points along the passage")
    args = p.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    impeller = npost.make_impeller()                    # the default passage (docs/posture.md)
    cc, normals = impeller.cc_path(args.points)         # middle of the passage floor, normals up
    vertices, faces = impeller.obstacles()              # the two blades that bound the passage
    run = npost.plan_postures(cc, normals, vertices, faces, npost.default_assembly(), clearance=0.5)
    machine = npost.kinematics_from_dict({"kind": "head_bc", "pivot_length_mm": 150.0}, source="example")
    run.write(args.out, plot=True, kinematics=machine)

    s = run.summary()
    print(f"{s['points']} CC points, clearance {s['clearance_mm']} mm")
    for stage in ("raw", "mc", "final"):
        print(f"  {stage:>5}: {s['collisions'][stage]:3d} colliding postures, largest change "
              f"{s['max_posture_change_deg_per_mm'][stage]:.2f} deg/mm")
    print(f"  repaired after smoothing: {s['repaired']}")
    print(f"written to {args.out}: {', '.join(sorted(f.name for f in args.out.iterdir()))}")
    (args.out / "example_summary.json").write_text(json.dumps(s, indent=2) + "\n")
    return s


if __name__ == "__main__":
    main()
