"""Rule `smooth` against `blend` on runs in space (issue 39 item 2): the seeded helices, conical and
spherical spirals of tests/python/motion/space_programs.py (radius 2–50 mm, pitch 0.01–0.5 mm/rad,
moves 0.1–2 mm, feed 50–250 mm/s, ε 0.003–0.03 mm; odd seeds rounded to 1 µm), vmax 250 mm/s, amax
3000 mm/s². Prints every member where smooth is slower than blend (beyond 10⁻⁹ relative) and the count
per half (even seeds: the half anything is tuned on; odd: held out).

    PYTHONPATH=python python bench/motion_space_family.py [--quick] [--members 240]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import netshape.motion as nm

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python" / "motion"))
from space_programs import space_program  # noqa: E402

LIM = nm.AxisLimits.uniform(250.0, 3000.0)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="24 members of at most 240 points")
    ap.add_argument("--members", type=int, default=240)
    args = ap.parse_args(argv)
    members, points = (24, 240) if args.quick else (args.members, 400)
    slower = {0: 0, 1: 0}
    worst = 0.0
    for seed in range(members):
        arr, eps, desc = space_program(seed, max_points=points)
        tb = nm.plan(arr, LIM, rule="blend", tolerance=eps, with_deviation=False).stats["cycle_time_s"]
        s = nm.plan(arr, LIM, rule="smooth", tolerance=eps).stats
        r = s["cycle_time_s"] / tb
        worst = max(worst, r)
        if r > 1 + 1e-9:
            slower[seed % 2] += 1
            print(f"slower: {desc}: smooth / blend {r:.6f} ({s['runs_smoothed']} pieces)", flush=True)
        if s["max_path_deviation_mm"] > eps * (1 + 1e-9):
            print(f"outside ε: {desc}: {s['max_path_deviation_mm']:.5f} mm", flush=True)
    print(f"\n{members} members: slower than blend {slower[0]} (even seeds), {slower[1]} (odd seeds); "
          f"largest smooth / blend {worst:.4f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
