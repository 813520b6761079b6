"""Rule `smooth` on the generated finishing family (issue 39): cycle time of `blend`, `smooth` and
`junction-deviation` (Klipper's square corner velocity 5 mm/s; its velocity jumps are not feasible
for the axis box, shown for reference) against the feed-only bound (every move at its programmed feed
or the axis speed limit, no acceleration), per program of the held-out half of
tests/python/motion/finishing_programs.py and the four shared programs (3D_Chips as written; tort,
cds, arcspiral with feeds ×100). vmax 250 mm/s, amax 3000 mm/s² per axis, ts1 1 ms, look-ahead 64.
Columns: smooth/blend ratio; best/b, a bound on the ratio of any rule that plans the rapids as blend
does (blend's time in the rapids plus the feed-only time of every feed move, over blend's); smooth's largest
deviation from the program (from the samples) and the share of the path in micro-segments (lines ≤ 4 mm).

    PYTHONPATH=python python bench/motion_family.py [--quick] [--half tune|held-out] [--eps 0.01]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

import netshape.motion as nm
from motion_plan import LIM, load  # bench/ is on sys.path when run as a script

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python" / "motion"))
import finishing_programs as fp  # noqa: E402

SHARED = (("3D_Chips.ngc", 1.0), ("tort.ngc", 100.0), ("cds.ngc", 100.0), ("arcspiral.ngc", 100.0))


def path_lengths(arr) -> np.ndarray:
    """Length of each block [mm]: chords, and arcs by sweep·radius (with the helix along the normal)."""
    start, end, center = (np.asarray(arr[k], dtype=float) for k in ("start", "end", "center"))
    length = np.linalg.norm(end - start, axis=1)
    axes = ((0, 1, 2), (2, 0, 1), (1, 2, 0))  # (a, b, normal) of G17, G18, G19
    for i in np.flatnonzero(np.asarray(arr["kind"]) == 2):
        a, b, n = axes[int(arr["plane"][i])]
        v0 = start[i, [a, b]] - center[i, [a, b]]
        v1 = end[i, [a, b]] - center[i, [a, b]]
        ang = np.arctan2(v0[0] * v1[1] - v0[1] * v1[0], v0 @ v1)
        if arr["clockwise"][i]:
            ang = -ang
        ang = ang % (2 * np.pi) or 2 * np.pi
        ang += 2 * np.pi * (int(arr["turns"][i]) - 1)
        length[i] = np.hypot(ang * np.linalg.norm(v0), end[i, n] - start[i, n])
    return length


def block_bounds(arr) -> np.ndarray:
    """Per block, length / speed cap: the programmed feed and the axis speed limits along the chord
    (arcs: the feed only), rapids at the axis limits [s] (0 for empty blocks)."""
    d = np.asarray(arr["end"]) - np.asarray(arr["start"])
    chord = np.linalg.norm(d, axis=1)
    kind = np.asarray(arr["kind"])
    u = np.abs(d) / np.maximum(chord, 1e-12)[:, None]
    vlim = np.asarray(LIM.velocity)[None, :]
    vax = np.min(np.where(u > 1e-12, vlim / np.maximum(u, 1e-12), np.inf), axis=1)
    vax = np.where(kind == 2, np.min(LIM.velocity), vax)
    cap = np.where(kind == 0, vax, np.minimum(np.asarray(arr["feed"]), vax))
    length = path_lengths(arr)
    return np.where(length > 1e-9, length / np.where(length > 1e-9, cap, 1.0), 0.0)


def feed_bound(arr) -> float:
    """Σ block_bounds: the feed-only bound of the whole program [s]."""
    return float(block_bounds(arr).sum())


def best_time(arr, traj) -> float:
    """A bound on the cycle time of any rule that plans the rapids as `traj` (a blend plan) does: its
    time in the rapids plus the feed-only time of every feed move [s] (samples are counted to the block
    they run in)."""
    n = len(arr["kind"])
    t = np.bincount(np.clip(np.asarray(traj.block), 0, n - 1), minlength=n) * traj.stats["ts2_s"]
    rapid = np.asarray(arr["kind"]) == 0
    return float(t[rapid].sum() + block_bounds(arr)[~rapid].sum())


def micro_share(arr) -> float:
    length = np.linalg.norm(np.asarray(arr["end"]) - np.asarray(arr["start"]), axis=1)
    feed = np.asarray(arr["kind"]) != 0
    micro = feed & (np.asarray(arr["kind"]) == 1) & (length <= 4.0)
    return float(length[micro].sum() / max(length[feed].sum(), 1e-12))


def row(name, arr, eps):
    bt = nm.plan(arr, LIM, rule="blend", tolerance=eps, with_deviation=False)
    b = bt.stats
    s = nm.plan(arr, LIM, rule="smooth", tolerance=eps).stats
    j = nm.plan(arr, LIM, rule="junction-deviation", with_deviation=False).stats
    tb, ts = b["cycle_time_s"], s["cycle_time_s"]
    print(f"| {name:28s} | {int(np.count_nonzero(arr['kind'])):6d} | {micro_share(arr):4.2f} | {tb:8.2f} "
          f"| {ts:8.2f} | {ts / tb:5.3f} | {j['cycle_time_s']:8.2f} | {feed_bound(arr):8.2f} "
          f"| {best_time(arr, bt) / tb:5.3f} "
          f"| {s['max_path_deviation_mm']:.4f} | {s['runs_smoothed']:5d} |", flush=True)
    return tb, ts


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", 
                    help="one seed per strategy at a quarter size, no shared programs")
    ap.add_argument("--half", choices=("tune", "held-out"), default="held-out")
    ap.add_argument("--eps", type=float, default=0.01, help="contour tolerance ε [mm]")
    ap.add_argument("--seeds", type=int, default=2, help="programs per strategy")
    args = ap.parse_args(argv)
    seeds, scale = (1, 0.25) if args.quick else (args.seeds, 1.0)
    print(f"ε = {args.eps} mm, {args.half} half, vmax 250 mm/s, amax 3000 mm/s²; times [s]\n")
    print("| program | moves | micro | blend | smooth | s/b | jd | feed-only | best/b | dev_mm | runs |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    worst = 0.0
    for arr, d in fp.family(args.half, seeds, scale):
        name = (f"{d['strategy']} {d['surface']} s{d['seed']} δ{d['chord_tolerance_mm']:.3f} "
                f"F{d['feed_mm_min']}")
        tb, ts = row(name, arr, args.eps)
        worst = max(worst, ts / tb)
    if not args.quick:
        for name, scale_f in SHARED:
            row(f"{name} (F×{scale_f:g})", load(name, scale_f), args.eps)
    print(f"\nlargest smooth/blend over the family: {worst:.4f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
