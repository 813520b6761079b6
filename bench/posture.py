"""Benchmark: 5-axis posture planning — CC points per second through C-space + MC-space + MB-spline + repair
on the default impeller passage, interference checks per second, the between-point program (move check,
repair, rotary subdivision), the rotary axes' peak and RMS angular velocity and acceleration at a feed on
the impeller floor and on a blade-side path (Impeller.blade_path), and the disagreement count of the C++ check
against the exact NumPy solid–triangle test of tests/python/posture/conftest.py on the same mesh and poses.

    PYTHONPATH=python python bench/posture.py [--points 200] [--poses 100000] [--quick] [--baseline DIR]

Times are CPU time (time.process_time); the extension is single-threaded. With --baseline DIR (a directory
whose `netshape` package is another build, e.g. main's installed one), the planning rate of this build and of
the baseline are measured in alternating child processes, `--rounds` times each, under the same load; the
ratio of the medians is printed.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from netshape import posture as npost
from netshape.geometry import TriangleMesh

HERE = Path(__file__).resolve().parent


def _load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


# One planning run in a child process: the C-space + MC + MB + repair of the impeller at `points` CC points;
# prints "<CC points/s> <checks/s> <GJK runs per check>" (−1: the build does not count them). Runs against whichever `netshape` is first on the child's sys.path.
_CHILD = """
import sys, time
from netshape import posture as npost
from netshape.geometry import TriangleMesh
n = int(sys.argv[1])
imp = npost.make_impeller()
cc, normals = imp.cc_path(n)
v, f = imp.obstacles()
chk = npost.InterferenceChecker(TriangleMesh(v, f), npost.default_assembly(), 0.5)
t = time.process_time()
r = npost.plan(chk, cc, normals)
dt = time.process_time() - t
print(n / dt, r.checks / dt, getattr(chk, "gjk_runs", -1) / r.checks)
"""


def _child_rate(path, points):
    env = dict(os.environ, PYTHONPATH=str(path))
    out = subprocess.run([sys.executable, "-c", _CHILD, str(points)], env=env, capture_output=True, text=True,
                         check=True).stdout.split()
    return float(out[0]), float(out[1]), float(out[2])


def compare(baseline, points, rounds):
    """Planning rate of this build and of `baseline`, alternating, `rounds` each: medians and their ratio."""
    ours, base = [], []
    for _ in range(rounds):
        base.append(_child_rate(baseline, points))
        ours.append(_child_rate(HERE.parent / "python", points))
    mo, mb = statistics.median(r[0] for r in ours), statistics.median(r[0] for r in base)
    print(f"interleaved x{rounds}, {points} CC points: this build {mo:.1f} CC points/s "
          f"({statistics.median(r[1] for r in ours):.0f} checks/s, {ours[0][2]:.2f} GJK runs/check), baseline "
          f"{mb:.1f} CC points/s ({statistics.median(r[1] for r in base):.0f} checks/s); ratio {mo / mb:.2f}x")


def _print_rotary(name, rot):
    for stage in ("raw", "mc", "final", "program"):
        print(f"  {name:14s} {stage:7s} " + "; ".join(
            f"{ax} {r['peak_velocity_deg_s']:7.2f}/{r['rms_velocity_deg_s']:6.2f} deg/s "
            f"{r['peak_acceleration_deg_s2']:8.1f}/{r['rms_acceleration_deg_s2']:7.1f} deg/s^2"
            for ax, r in rot[stage].items()))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--poses", type=int, default=100_000)
    ap.add_argument("--quick", action="store_true", help="CI size: 20 points, 4000 poses")
    ap.add_argument("--baseline", type=Path, help="directory holding the baseline build's netshape package")
    ap.add_argument("--feed", type=float, default=1000.0, help="feed of the rotary-axis figures [mm/min]")
    ap.add_argument("--rounds", type=int, default=3, help="alternating runs per build with --baseline")
    args = ap.parse_args(argv)
    if args.quick:
        args.points, args.poses = 20, 4000
    if args.baseline:
        compare(args.baseline, args.points, args.rounds)
    imp = npost.make_impeller()
    cc, normals = imp.cc_path(args.points)
    v, f = imp.obstacles()
    asm = npost.default_assembly()
    print(f"load average {os.getloadavg()[0]:.1f}; obstacles {len(f)} triangles; {args.points} CC points")

    t = time.process_time()
    run = npost.plan_postures(cc, normals, v, f, asm, clearance=0.5, approach_mm=10.0, chord_mm=0.01,
                              feed_mm_per_min=args.feed)
    dt = time.process_time() - t
    r, p, s = run.result, run.program, run.summary()
    t = time.process_time()
    npost.plan(npost.InterferenceChecker(TriangleMesh(v, f), asm, 0.5), cc, normals)
    dt_plan = time.process_time() - t
    print(f"plan (C-space + MC + MB + repair): {args.points / dt_plan:.1f} CC points/s, {r.checks / dt_plan:.0f} "
          f"checks/s ({r.checks} interference checks, {r.checks / args.points:.0f} per point)")
    print(f"  with the program (move check + repair + chord + approach): {args.points / dt:.1f} CC points/s; "
          f"{p.checks} move checks; moves colliding {p.colliding_before} -> {int(np.sum(p.move_collides))}, "
          f"{p.inserted} CL points inserted, {len(p.tips)} program points")
    print(f"  collisions raw/mc/final {s['collisions']}, repaired {s['repaired']}, "
          f"max change deg/mm {s['max_posture_change_deg_per_mm']}")

    print(f"rotary axes at {args.feed:g} mm/min (peak/RMS velocity deg/s, acceleration deg/s^2):")
    _print_rotary("impeller floor", run.rotary_rates())
    bc, bn, bv, bf = imp.blade_path(args.points)
    t = time.process_time()
    blade = npost.plan_postures(bc, bn, bv, bf, asm, clearance=0.5, approach_mm=10.0, chord_mm=0.01,
                                feed_mm_per_min=args.feed)
    dt = time.process_time() - t
    bs = blade.summary()
    print(f"blade-side path (blade 1 pressure face at 3/4 height, {args.points} CC points, {dt:.1f} s): collisions "
          f"raw/mc/final {bs['collisions']}, moves colliding {bs['moves']['colliding']}, "
          f"max change deg/mm {bs['max_posture_change_deg_per_mm']}")
    _print_rotary("blade side", blade.rotary_rates())

    exact = _load("posture_exact", HERE.parent / "tests/python/posture/conftest.py")
    solids = _load("posture_solids", HERE.parent / "tests/python/posture/test_posture_solids.py")
    _, _, tips, axes = solids.random_poses(args.poses, seed=0)
    tri = v[f]
    for clearance in (0.0, 0.5):
        chk = npost.InterferenceChecker(TriangleMesh(v, f), asm, clearance)
        t = time.process_time()
        got = np.asarray(chk.collides(tips, axes))
        rate_cpp = len(tips) / (time.process_time() - t)
        free = np.flatnonzero(~got)  # unsafe = reported free while the exact solid hits: every free pose
        sample = np.random.default_rng(1).choice(np.flatnonzero(got), min(4000, int(got.sum())), replace=False)
        t = time.process_time()
        unsafe = int(exact.exact_hits(asm, tri, tips[free], axes[free], inflate=clearance).sum())
        rate_np = len(free) / (time.process_time() - t)
        spare = 1 - exact.exact_hits(asm, tri, tips[sample], axes[sample], inflate=clearance).mean()
        print(f"clearance {clearance}: {len(tips)} poses, C++ {rate_cpp:.0f} checks/s, exact NumPy {rate_np:.0f}/s; "
              f"unsafe (free but the exact solid hits) {unsafe} of {len(free)} free; conservative (colliding, the "
              f"exact solid free) {100 * spare:.1f} % of {len(sample)} colliding; colliding {got.mean():.2f}")


if __name__ == "__main__":
    main()
