"""Feed scheduling (issue 41, docs/feeds.md): blocks/s of the scheduler on a 10 000-block surfacing
program, and the cycle-time saving on the demo job's program and on ../shared/data/gcode/3D_Chips.ngc
with a 10 mm ball end mill on the stock its roughing left (the part's surface offset by the finishing
allowance), at stated limits.

    PYTHONPATH=python python bench/feeds.py [--quick]
"""

from __future__ import annotations

import argparse
import math
import os
import re
import time
from pathlib import Path
from types import SimpleNamespace

HERE = Path(__file__).resolve().parent
CHIPS = HERE.parent.parent / "shared" / "data" / "gcode" / "3D_Chips.ngc"


def surfacing(blocks: int) -> str:
    """A zig-zag of 0.5 mm G1 moves 1 mm deep over a 50 × 50 mm block, ``blocks`` moves."""
    lines = ["G21 G90 G17 G94", "S8000 M3", "G0 X-30 Y-24 Z5", "G1 Z-1 F600"]
    x, y, d, n = -30.0, -24.0, 1.0, 0
    while n < blocks:
        x += 0.5 * d
        if abs(x) > 30:
            d, y = -d, y + 4.0
            lines.append(f"G1 Y{y:g} F1200")
        else:
            lines.append(f"G1 X{x:g} F1200")
        n += 1
    return "\n".join(lines + ["M30"]) + "\n"


def _stock(box, spacing, pre_cut=()):
    from netshape.job.stages import stage_stock

    st = {"min_mm": box[0], "max_mm": box[1], "spacing_mm": spacing, "heights": None,
          "pre_cut": list(pre_cut)}
    return stage_stock(SimpleNamespace(stock=st))


def finishing_stock(box, spacing, tp, ball, allowance: float):
    """The stock a roughing pass leaves for the ball-end finishing program ``tp`` (first start placed): the
    block less what a ball of radius R − ``allowance`` removes with its centre on the program's ball
    centres (its tip ``allowance`` higher): the envelope R − a from the centres is the part's surface
    offset outwards by ``allowance`` along its normal."""
    import netshape as ns
    import numpy as np
    from netshape.compensation.feeds_gcode import copy_block

    stock = _stock(box, spacing)
    small = ns.cutter.cutter_from_dict({"kind": "ball", "diameter_mm": 2 * (ball.radius - allowance),
                                        "flutes": ball.flutes, "helix_deg": math.degrees(ball.helix),
                                        "flute_length_mm": ball.flute_length, "stick_out_mm": ball.stick_out})
    d = np.array([0.0, 0.0, allowance])
    blocks = []
    for b in tp.blocks:
        nb = copy_block(b)
        nb.start, nb.end = np.asarray(b.start) + d, np.asarray(b.end) + d
        if int(b.kind) == 2:
            nb.center = np.asarray(b.center) + d
        blocks.append(nb)
    ns.stock.sweep(stock, small, tp.with_blocks(blocks, list(range(len(blocks)))))
    return stock


def throughput(blocks: int) -> dict:
    import netshape as ns
    from netshape.compensation.feeds import feed_limits_from_dict, schedule_feeds
    from netshape.compensation.feeds_run import read_program_text, with_start

    stock = _stock(([-35, -30, -10], [35, 30, 0]), 0.25)
    cutter = ns.cutter.cutter_from_dict({"kind": "flat", "diameter_mm": 6.0, "flutes": 3, "helix_deg": 35.0,
                                         "flute_length_mm": 16.0, "stick_out_mm": 30.0})
    coeffs = ns.force.linear_edge_coefficient_set("leekunhwee_flat_slot").coefficients
    tp = with_start(read_program_text(surfacing(blocks), "surfacing"), stock)
    lim, split = feed_limits_from_dict({"max_force_N": 150.0, "max_chip_mm": 0.06, "max_feed_mm_min": 4000.0})
    t0 = time.perf_counter()
    s = schedule_feeds(stock, cutter, tp, coeffs, lim, samples_per_revolution=36, disk_height=0.25, **split)
    dt = time.perf_counter() - t0
    n = len(tp.blocks)
    print(f"scheduler: {n} blocks, {len(s.samples['block'])} samples, {len(s.pieces['feed'])} pieces "
          f"in {dt:.2f} s = {n / dt:.0f} blocks/s")
    return {"blocks": n, "seconds": dt, "blocks_per_s": n / dt}


def saving(name, text, stock, cutter, coeffs, table) -> dict:
    import netshape as ns
    from netshape.compensation.feeds import feed_limits_from_dict
    from netshape.compensation.feeds_run import optimize_program

    lim, split = feed_limits_from_dict(table)
    axis = ns.motion.AxisLimits.uniform(200.0, 2000.0, math.inf)
    t0 = time.perf_counter()
    r = optimize_program(text, name, stock, cutter, coeffs, lim, axis_limits=axis,
                         plan_options=ns.motion.make_options("blend", ts1=2e-3, ts2=1e-3), split=split,
                         sampling={"step": 0.5, "samples_per_revolution": 36, "disk_height": 0.25})
    c = r.summary["cycle_time_s"]
    print(f"{name}: limits {r.summary['limits']}")
    f = r.summary["max_force_N"]
    print(f"  cycle time {c['original']:.1f} s -> {c['optimized']:.1f} s "
          f"({r.summary['saving_percent']:.1f} % saved); "
          f"max force {f['original']:.0f} -> {f['optimized']:.0f} N; "
          f"binding {r.summary['binding']}; {time.perf_counter() - t0:.1f} s")
    return r.summary


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="1000 blocks, the demo program only")
    p.add_argument("--chips-only", action="store_true", help="only the 3D_Chips saving")
    p.add_argument("--allowance", type=float, default=0.5,
                   help="3D_Chips: finishing allowance the roughing left, normal to the part [mm] (0.5)")
    p.add_argument("--max-force", type=float, default=1500.0,
                   help="3D_Chips: force limit [N] (1500: the program's own peak on the finishing stock)")
    p.add_argument("--max-chip", type=float, default=0.3,
                   help="3D_Chips: chip limit [mm] (0.3: its F900 moves at 1600 rev/min are 0.28 mm)")
    a = p.parse_args(argv)
    import netshape as ns
    from netshape.job.spec import PreCut

    if not a.chips_only:
        throughput(1000 if a.quick else 10000)
    demo = HERE.parent / "examples" / "demo"
    import tomllib

    rough = PreCut(program=demo / "preshape.ngc", tool=tomllib.loads((demo / "rougher.toml").read_text()))
    stock = _stock(([-30, -25, -20], [30, 25, 0]), 0.25, [rough])
    cutter = ns.cutter.load_cutter(demo / "tool.toml")
    coeffs = ns.force.linear_edge_coefficient_set("leekunhwee_flat_slot").coefficients
    if not a.chips_only:
        saving("demo part.ngc", (demo / "part.ngc").read_text(), stock, cutter, coeffs,
               {"max_force_N": 300.0, "max_chip_mm": 0.05, "max_feed_mm_min": 3000.0,
                "air_feed_mm_min": 5000.0})
    if not a.quick and CHIPS.is_file():
        ball = ns.cutter.cutter_from_dict({"kind": "ball", "diameter_mm": 10.0, "flutes": 2,
                                           "helix_deg": 30.0, "flute_length_mm": 30.0, "stick_out_mm": 50.0})
        kim = ns.force.ball_end_coefficient_set("kim_zas_ball12").coefficients
        # the file sets #<fscale> = 10000 (F up to 4.5e6 mm/min); its header states 450 mm/min: fscale 2
        # (F450 and, for most of its moves, F900)
        text = re.sub(r"#<fscale>\s*=\s*[\d.]+", "#<fscale> = 2.0", CHIPS.read_text())
        from netshape.compensation.feeds_run import read_program_text, with_start

        box = ([-50, -50, -50], [50, 50, 0])
        # a finishing program runs on what roughing left: the part's surface offset by the allowance
        tp = with_start(read_program_text(text, "3D_Chips"), _stock(box, 0.5))
        stock = finishing_stock(box, 0.5, tp, ball, a.allowance)
        saving(f"3D_Chips.ngc (ball D10, #<fscale> = 2, {a.allowance:g} mm allowance)", text, stock, ball,
               kim,
               {"max_force_N": a.max_force, "max_chip_mm": a.max_chip, "max_feed_mm_min": 3000.0,
                "air_feed_mm_min": 5000.0})
    print(f"(load average {os.getloadavg()[0]:.1f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
