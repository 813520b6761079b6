"""Motion planner benchmark (issue 6), in one run:

1. planning throughput, blocks/s (streaming Planner: push + look-ahead + profile freeze per block,
   no sampling), on 3D_Chips.ngc repeated, for every rule;
2. cycle time of every rule on 3D_Chips.ngc (vmax 250 mm/s, amax 3000 mm/s², programmed F above vmax)
   and on the arc programs with feeds scaled ×100; then the junction-deviation rule at grbl's
   δ = 0.01 mm with both junction accelerations and look-ahead 16 and 64;
3. blend rule at ε = 0.01 mm against the time-optimal traversal of the same blended path under the
   same per-axis limits computed by toppra (TOPP-RA on a dense grid): ratio of cycle times.

    PYTHONPATH=python python bench/motion_plan.py [--quick] [--only throughput|cycle|toppra]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

import netshape.motion as nm
from netshape import toolpath

# the shared data folder: $NETSHAPE_SHARED_DATA, else ../shared/data next to the repository
DATA = Path(os.environ.get("NETSHAPE_SHARED_DATA", Path(__file__).resolve().parents[1].parent / "shared" / "data")) / "gcode"
LIM = nm.AxisLimits.uniform(250.0, 3000.0)


def load(name, feed_scale=1.0, n=None):
    arr = {k: np.asarray(v) for k, v in toolpath.read_gcode_arrays(DATA / name).items()}
    if n is not None:
        first = int(np.flatnonzero(arr["kind"] != 0)[0])
        arr = {k: v[first:first + n] for k, v in arr.items()}
    arr["feed"] = arr["feed"] * feed_scale
    return arr


def throughput(points, rule, repeat):
    opts = nm.make_options(rule, lookahead=64)
    best = float("inf")
    for _ in range(5):  # CPU time, best of five (the machine is shared: its speed swings by ±20 %)
        t0 = time.process_time()
        segs, _ = nm._m._throughput(points, 1e9, LIM, opts, repeat)
        best = min(best, time.process_time() - t0)
    return (len(points) - 1) * repeat / best, segs


def toppra_time(points, s, vmax, amax, grid):
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    ta.setup_logging("WARNING")
    path = ta.SplineInterpolator(s, points)
    vlim = np.column_stack([-vmax, vmax])
    alim = np.column_stack([-amax, amax])
    pc_v = constraint.JointVelocityConstraint(vlim)
    pc_a = constraint.JointAccelerationConstraint(alim, discretization_scheme=constraint.DiscretizationType.Collocation)
    inst = algo.TOPPRA([pc_v, pc_a], path, gridpoints=grid, parametrizer="ParametrizeConstAccel")
    traj = inst.compute_trajectory(0.0, 0.0)
    if traj is None:
        raise RuntimeError("toppra failed")
    return float(traj.duration)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="smaller sizes")
    ap.add_argument("--only", choices=("throughput", "cycle", "toppra"), help="run one section")
    args = ap.parse_args(argv)
    if args.only in (None, "throughput"):
        section_throughput(3 if args.quick else 20)
    if args.only in (None, "cycle"):
        section_cycle()
    if args.only in (None, "toppra"):
        section_toppra(args.quick)
    return 0


def section_throughput(repeat):
    chips = load("3D_Chips.ngc")
    moving = chips["kind"] != 0
    pts = np.vstack([chips["start"][moving][:1], chips["end"][moving]])
    print(f"## 1. planning throughput (3D_Chips.ngc, {len(pts) - 1} blocks x {repeat}, look-ahead 64)")
    for rule in nm.RULES:
        bps, segs = throughput(pts, rule, repeat)
        print(f"  {rule:20s} {bps / 1e6:6.2f} M blocks/s  ({segs} segments)")


def section_cycle():
    print("\n## 2. cycle time [s] per rule (vmax 250 mm/s, amax 3000 mm/s^2, ts1 1 ms, ts2 0.1 ms, look-ahead 64)")
    progs = [("3D_Chips.ngc", 1.0), ("arcspiral.ngc", 100.0), ("tort.ngc", 100.0), ("cds.ngc", 100.0)]
    header = "  program (feed scale)      " + " ".join(f"{r:>19s}" for r in nm.RULES)
    print(header)
    for name, scale in progs:
        arr = load(name, scale)
        row = []
        for rule in nm.RULES:
            tr = nm.plan(arr, LIM, rule=rule, tolerance=0.01, with_deviation=False)
            st = tr.stats
            row.append(f"{st['cycle_time_s']:8.3f} ({st['max_axis_accel_mm_s2']:7.0f})")
        print(f"  {name:16s} (x{scale:<5g}) " + " ".join(f"{c:>19s}" for c in row))
    print("  (in brackets: largest per-axis acceleration reached [mm/s^2], finite differences at ts2)")

    print("\n## 2b. junction-deviation rule at delta = 0.01 mm (grbl $11), cycle time [s] "
          "(largest axis accel)")
    cols = [(acc, la) for acc in nm.JUNCTION_ACCELS for la in (16, 64)]
    print("  program (feed scale)      " + " ".join(f"{acc + ' la ' + str(la):>27s}" for acc, la in cols))
    for name, scale in progs:
        arr = load(name, scale)
        row = []
        for acc, la in cols:
            tr = nm.plan(arr, LIM, rule="junction-deviation", junction_deviation=0.01,
                         square_corner_velocity=0.0, junction_accel=acc, lookahead=la, with_deviation=False)
            st = tr.stats
            row.append(f"{st['cycle_time_s']:8.3f} ({st['max_axis_accel_mm_s2']:7.0f})")
        print(f"  {name:16s} (x{scale:<5g}) " + " ".join(f"{c:>27s}" for c in row))


def section_toppra(quick):
    print("\n## 3. blend rule (eps = 0.01 mm) vs toppra time-optimal on the same blended path")
    n_blocks = 60 if quick else 200
    for name, scale, n in (("3D_Chips.ngc", 1.0, n_blocks), ("tort.ngc", 100.0, n_blocks // 2)):
        arr = load(name, scale, n)
        arr["feed"][:] = 1e4  # above vmax: both planners are limited by the axes only
        opts = nm.make_options("blend", tolerance=0.01, lookahead=max(64, n + 2))
        ds = 0.002
        p, s, t_ours = nm.path_points(arr, LIM, opts, ds)
        keep = np.concatenate([[True], np.diff(s) > 1e-6])
        p, s = p[keep], s[keep]
        # grid: every path point on a 0.01 mm pitch (blends are 0.03-0.5 mm long), at most 60000
        step = max(1, int(np.ceil(max(0.01 / ds, len(s) / 60000))))
        grid = np.unique(np.concatenate([s[::step], s[-1:]]))
        n_grid = len(grid)
        t0 = time.perf_counter()
        t_opt = toppra_time(p, s, np.asarray(LIM.velocity), np.asarray(LIM.acceleration), grid)
        dt = time.perf_counter() - t0
        print(f"  {name} first {n} blocks (x{scale:g} feed): length {s[-1]:.1f} mm, ours {t_ours:.4f} s, "
              f"toppra {t_opt:.4f} s ({n_grid} grid points, {dt:.1f} s), ratio {t_ours / t_opt:.3f}")


if __name__ == "__main__":
    raise SystemExit(main())
