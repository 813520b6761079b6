"""Lee & Lee §4 reproduced: feed profiles of the right-angle blocks (Fig. 12) and of the three
semicircles (Fig. 14 f) and the per-axis profiles (Fig. 15), as PNG, with every corner rule compared.

    python examples/lookahead_lee.py [--out DIR]

The paper gives no coordinates, radii, acceleration or periods; the reconstruction is in
netshape/motion/lookahead_lee.py and docs/motion.md (radii 30/10/5 mm, 39/22/16 chords, Acc = 450 mm/s²,
Ts1 = 0.4 ms, Ts2 = 0.1 ms, allowable speed difference 100 mm/min).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

import netshape.motion as nm
from netshape._atomic import atomic_save_figure, atomic_write
from netshape.motion import lookahead_lee as s
from netshape.motion.plots import plot_profiles


def run(out: Path) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    out.mkdir(parents=True, exist_ok=True)
    lim = nm.AxisLimits.uniform(1e4, s.ACC)
    common = dict(ts1=s.TS1, ts2=s.TS2, allowable_speed_difference=s.ALLOWABLE, lookahead=100)
    summary = {}

    # Fig. 12: four 20 mm blocks at right angles, F5000
    sq = nm.plan(s.square_program(), lim, feed=5000 / 60, rule="paper", **common)
    atomic_save_figure(plot_profiles(sq, title="Lee & Lee Fig. 12: 4 × 20 mm at 90°, F5000, paper rule"),
                       out / "fig12_right_angle.png")
    corners = [float(sq.feed[np.argmin(np.linalg.norm(sq.position - c, axis=1))] * 60)
               for c in s.square_program()[1:-1]]
    summary["fig12"] = {"cycle_time_s": sq.stats["cycle_time_s"], "corner_feed_mm_min": corners}

    # Fig. 14 (f) and 15: semicircles, every rule
    pts = s.semicircle_program()
    fig = Figure(figsize=(9, 7), constrained_layout=True)
    axes = fig.subplots(len(nm.RULES), 1, sharex=True)
    summary["fig14"] = {}
    for ax, rule in zip(axes, nm.RULES):
        tr = nm.plan(pts, lim, feed=4000 / 60, rule=rule, **common)
        ax.plot(tr.t, tr.feed * 60, lw=0.8, color="k")
        ax.set_ylabel("feed\n[mm/min]")
        ax.set_title(f"{rule}: cycle {tr.stats['cycle_time_s']:.3f} s, max axis accel "
                     f"{tr.stats['max_axis_accel_mm_s2']:.0f} mm/s²", fontsize=9)
        ax.grid(alpha=0.3)
        summary["fig14"][rule] = {k: tr.stats[k] for k in ("cycle_time_s", "max_axis_accel_mm_s2",
                                                           "max_path_deviation_mm")}
        if rule == "paper":
            atomic_save_figure(plot_profiles(tr, title="Lee & Lee Fig. 14 (f) / 15: F4000, 3 semicircles, paper rule"),
                               out / "fig15_axis_profiles.png")
            i = 3
            arc = []
            for n in s.CHORDS:
                vert = pts[i + 1: i + n - 1]
                arc.append(float(np.median([tr.feed[np.argmin(np.linalg.norm(tr.position - p, axis=1))] * 60
                                            for p in vert])))
                i += n
            summary["fig14"]["paper"]["arc_junction_feed_mm_min"] = arc
    axes[-1].set_xlabel("time [s]")
    atomic_save_figure(fig, out / "fig14_feed_rules.png")
    with atomic_write(out / "summary.json", "w") as fh:
        json.dump(summary, fh, indent=2)
    return summary


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="out/lookahead_lee", help="output folder (PNG + summary.json)")
    args = p.parse_args(argv)
    summary = run(Path(args.out))
    print(json.dumps(summary, indent=2))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
