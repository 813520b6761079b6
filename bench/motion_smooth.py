"""Tolerance-band smoothing benchmark (issue 22), in one run:

1. cycle time of rule "smooth" against "blend" on 3D_Chips.ngc (vmax 250 mm/s, amax 3000 mm/s²) at
   ε = 0.01, 0.03, 0.1 mm, with the default max_turn 30° and with 92° (90° vertices inside runs are
   then fitted by the spline instead of kept as corners), and on tort / cds / arcspiral with feeds ×100 (as bench/motion_plan.py), with
   the largest axis acceleration by finite differences, the deviation from the original program, the
   runs smoothed and corners kept;
2. the ratio to TOPP-RA (toppra, per-axis box on a dense grid) on the smoothed path, first 200 blocks of
   3D_Chips at ε = 0.01 mm;
3. throughput of smoothing + planning (blocks of the original program per second; planning without
   sampling, in C++: smooth() + Planner less smooth_path(); best of three CPU times);
4. the same through the streaming Smoother -> Planner against smooth() + Planner (C++ loops, one block
   at a time, best of three wall-clock and CPU times), in one thread and with the Smoother in a second
   thread (the pipeline of a controller), with the buffer of the default window and of window 200, and
   the blocks pushed before the first smoothed block comes out;
5. with a jerk limit (10^5 mm/s³ per axis) on 3D_Chips at ε = 0.01 mm: "blend" against "smooth", with the
   largest third finite difference of the samples.

    PYTHONPATH=python python bench/motion_smooth.py [--quick]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import netshape.motion as nm
from motion_plan import LIM, load, toppra_time  # bench/ is on sys.path when run as a script

FIT_SHARE = 0.98  # netshape.motion.smooth_path default: the planner blends within (1 - FIT_SHARE)·ε


def cycle(arr, rule, eps, **kw):
    tr = nm.plan(arr, LIM, rule=rule, tolerance=eps, **kw)
    return tr.stats


def section_cycle(quick):
    print("## 1. cycle time [s] (vmax 250 mm/s, amax 3000 mm/s^2, ts1 1 ms, ts2 0.1 ms, look-ahead 64)")
    print("  program (feed scale) max_turn  eps    blend (accel)        smooth (accel)   dev_mm  runs  corners  blocks->new")
    progs = [("3D_Chips.ngc", 1.0, (0.01, 0.03, 0.1), 30.0), ("3D_Chips.ngc", 1.0, (0.01, 0.03, 0.1), 92.0)]
    if not quick:
        progs += [("tort.ngc", 100.0, (0.01, 0.03), 30.0), ("cds.ngc", 100.0, (0.01, 0.03), 30.0),
                  ("arcspiral.ngc", 100.0, (0.01, 0.03), 30.0)]
    for name, scale, epss, turn in progs:
        arr = load(name, scale)
        for eps in epss:
            b = cycle(arr, "blend", eps)
            s = cycle(arr, "smooth", eps, max_turn=np.radians(turn))
            print(f"  {name:14s} (x{scale:<5g}) turn {turn:3.0f} {eps:5.2f} {b['cycle_time_s']:8.3f} ({b['max_axis_accel_mm_s2']:6.0f})"
                  f"   {s['cycle_time_s']:8.3f} ({s['max_axis_accel_mm_s2']:6.0f})  {s['max_path_deviation_mm']:.4f}"
                  f"  {s['runs_smoothed']:4d}  {s['corners_kept']:6d}   {s['blocks']}->{s['smoothed_blocks']}")


def section_toppra(quick):

    n = 60 if quick else 200
    arr = load("3D_Chips.ngc", 1.0, n)
    arr["feed"][:] = 1e4
    eps = 0.01
    new = nm.smooth_path(arr, eps)[0]
    opts = nm.make_options("blend", tolerance=(1.0 - FIT_SHARE) * eps, lookahead=max(64, n + 2))
    ds = 0.002
    p, s, t_ours = nm.path_points(new, LIM, opts, ds)
    keep = np.concatenate([[True], np.diff(s) > 1e-6])
    p, s = p[keep], s[keep]
    step = max(1, int(np.ceil(max(0.01 / ds, len(s) / 60000))))
    grid = np.unique(np.concatenate([s[::step], s[-1:]]))
    t_opt = toppra_time(p, s, np.asarray(LIM.velocity), np.asarray(LIM.acceleration), grid)
    print(f"\n## 2. smooth (eps {eps}) vs toppra on the smoothed path, 3D_Chips first {n} blocks: "
          f"ours {t_ours:.4f} s, toppra {t_opt:.4f} s, ratio {t_ours / t_opt:.3f}")


def section_throughput(repeat):
    arr = load("3D_Chips.ngc", 1.0)
    n = int(np.count_nonzero(arr["kind"] != 0))
    opts = nm.make_options("blend", tolerance=(1.0 - FIT_SHARE) * 0.01, lookahead=64)
    args = nm._program_args(arr)
    best_s = best_b = float("inf")
    for _ in range(3):
        t0 = time.process_time()
        for _ in range(repeat):
            nm.smooth_path(arr, 0.01)
        t1 = time.process_time()
        nm._m._smooth_plan(*args, 0.01, 4096, LIM, opts, False, repeat)
        t2 = time.process_time()
        best_s, best_b = min(best_s, (t1 - t0) / repeat), min(best_b, (t2 - t1) / repeat)
    best_p = best_b - best_s  # smooth() + Planner in C++, less the smoothing
    print(f"\n## 3. throughput on 3D_Chips ({n} moves, eps 0.01): smoothing {n / best_s:.0f} blocks/s, "
          f"planning the smoothed blocks {n / best_p:.0f} blocks/s, together {n / best_b:.0f} blocks/s")


def section_stream(repeat):
    arr = load("3D_Chips.ngc", 1.0)
    n = len(arr["kind"])
    opts = nm.make_options("blend", tolerance=(1.0 - FIT_SHARE) * 0.01, lookahead=64)
    args = nm._program_args(arr)
    print(f"\n## 4. streaming on 3D_Chips ({n} blocks, eps 0.01): Smoother -> Planner vs smooth() + Planner"
          "\n  (blocks/s by wall clock and by CPU time, best of three; 2 threads: the Smoother in a thread of its own)")
    for window in (4096, 200):
        for streamed, threads in ((False, 1), (True, 1), (True, 2)):
            wall = cpu = float("inf")
            for _ in range(3):
                t0, c0 = time.perf_counter(), time.process_time()
                _, t_cycle = nm._m._smooth_plan(*args, 0.01, window, LIM, opts, streamed, repeat, threads)
                wall = min(wall, (time.perf_counter() - t0) / repeat)
                cpu = min(cpu, (time.process_time() - c0) / repeat)
            label = f"streamed, {threads} thread{'s' if threads > 1 else ' '}" if streamed else "batch            "
            print(f"  window {window:5d} {label}: {n / wall:8.0f} blocks/s wall, {n / cpu:8.0f} CPU"
                  f"  (cycle {t_cycle:.6f} s)")
    # start-up latency: program blocks pushed before the first smoothed block comes out
    firsts = {mc: nm.smooth_path_streamed(arr, 0.01, min_chunk=mc)[3]["first_output_after_blocks"]
              for mc in (1, 64, 2 * 4096 + 1)}
    print(f"  first smoothed block after {firsts[64]} blocks pushed (min_chunk 64; {firsts[1]} with 1, "
          f"{firsts[2 * 4096 + 1]} cutting only a full buffer)")


def section_jerk():
    arr = load("3D_Chips.ngc", 1.0)
    lim = nm.AxisLimits(velocity=[250.0] * 3, acceleration=[3000.0] * 3, jerk=[1e5] * 3)
    print("\n## 5. jerk 1e5 mm/s^3 per axis, 3D_Chips, eps 0.01: cycle time [s] (largest axis jerk by third differences)")
    for rule in ("blend", "smooth"):
        tr = nm.plan(arr, lim, rule=rule, tolerance=0.01)
        jerk = np.abs(np.diff(tr.position, 3, axis=0)).max() / tr.stats["ts2_s"] ** 3
        print(f"  {rule:6s} {tr.stats['cycle_time_s']:8.3f} ({jerk:.0f})")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3D_Chips only, smaller sizes")
    ap.add_argument("--only", choices=("cycle", "toppra", "throughput", "stream", "jerk"))
    args = ap.parse_args(argv)
    if args.only in (None, "cycle"):
        section_cycle(args.quick)
    if args.only in (None, "toppra"):
        section_toppra(args.quick)
    if args.only in (None, "throughput"):
        section_throughput(2 if args.quick else 5)
    if args.only in (None, "stream"):
        section_stream(2 if args.quick else 5)
    if args.only in (None, "jerk") and not args.quick:
        section_jerk()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
