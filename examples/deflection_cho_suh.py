"""Tool deflection wall error and its path compensation on the cases of J.-H. Cho and S.-H. Suh,
"Path compensation toward direct shape control: dealing with tool deflection problem in 2D contour
machining" (1993), §5 and §2.

Cases (HSS D = 25 mm, 4 flutes, 60° helix, stick-out 250 mm, E = 210 GPa, f = 0.0127 mm/tooth,
600 rpm, A = 2.5 mm, Kline–DeVor K_T = 1000 N/mm², K_R = 0.4 — the "cho_suh_example" set):
  straight  a straight cut along X across stock pre-shaped by an arc (Fig. 12)
  pocket    the north-east corner of a pocket over a roughing residue with a rounded corner (Fig. 13)
  arc       a circular boss finished clockwise over a 1 mm allowance (Fig. 14)
  angled    two angled straight lines over a 1 mm allowance (Fig. 15)
Each case builds its stock from a STOCK.toml with a [[pre_cut]] roughing program, predicts the wall
error, compensates it with every scheme at the middle level (λ = 0.5, tolerance 0.5 µm), and plots nominal/deflected/compensated
paths, the wall error before and after, the cutting width and the forces. The §2 experiment set-up
(D = 7 mm, 4 flutes, 33.7°, 70 mm, A = 2 mm, 600 rpm, 5/7/10 mm/min) gives the trend of the wall
error with the cutting width (Fig. 4).

    python examples/deflection_cho_suh.py OUTDIR [--quick]

Writes OUTDIR/<case>.png, OUTDIR/experiment_trend.png and OUTDIR/summary.json; prints the figures.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import numpy as np

import netshape as ns
from netshape import deflection as d

TOOL = """kind = "flat"
diameter_mm = 25.0
flutes = 4
helix_deg = 60.0
flute_length_mm = 50.0
stick_out_mm = 250.0
youngs_modulus_MPa = 210000.0
"""
FEED = 0.0127 * 4 * 600  # mm/min
R = 12.5
#: discount factor λ of the updates (the paper's steps 8 and 8 of the sectional scheme): 0.5 damps the
#: plain integrated iteration to the paper's ~8 iterations; λ = 1 converges in 3 on these cases.
DISCOUNT = 0.5


def _program(moves: list[str], start, z: float = 0.0) -> str:
    head = ["G21 G90 G17", "T1 M6", "S600 M3", f"G0 X{start[0]:.4f} Y{start[1]:.4f} Z10", f"G1 Z{z:.4f} F{FEED:.4f}"]
    return "\n".join(head + moves + ["G0 Z10", "M30", ""])


def _line(x, y):
    return f"G1 X{x:.4f} Y{y:.4f}"


def _arc(code, x, y, i, j):
    return f"{code} X{x:.4f} Y{y:.4f} I{i:.4f} J{j:.4f}"


def cases():
    """name -> (stock bounds (min, max), roughing program text, finishing program text).

    The allowances are large enough for the wall errors to matter: with the surface generation model
    a down-milling wall is left almost exact while the engagement stays below about 80° for this
    4-flute cutter (the next flute is not yet cutting when one generates the wall), and the error grows
    to ~0.1 mm beyond (see docs/deflection.md)."""
    out = {}
    # straight (Fig. 12): the roughing arc of centre (40, -46), radius 60 + R leaves material below the
    # circle of radius 60 (14 mm above the wall y = 0 at x = 40); the finishing cut runs along y = R
    # towards +X with the wall on its right (down milling).
    c, rho = (40.0, -46.0), 60.0 + R
    a0, a1 = np.radians(150.0), np.radians(30.0)
    s0 = (c[0] + rho * np.cos(a0), c[1] + rho * np.sin(a0))
    s1 = (c[0] + rho * np.cos(a1), c[1] + rho * np.sin(a1))
    rough = _program([_arc("G2", s1[0], s1[1], c[0] - s0[0], c[1] - s0[1])], s0, z=-1.0)
    finish = _program([_line(95.0, R)], (-15.0, R))
    out["straight"] = (([0, -10, -5], [80, 30, 2.5]), rough, finish)
    # pocket (Fig. 13): walls x = 60 and y = 60; roughing leaves 8 mm and a 20 mm corner arc (tool
    # centre path); the finishing pass climbs the east wall and turns west along the north wall.
    xr = 60.0 - R - 8.0
    rough = _program([_line(xr, xr - 20.0), _arc("G3", xr - 20.0, xr, -20.0, 0.0), _line(-15.0, xr)],
                     (xr, -15.0), z=-1.0)
    xf = 60.0 - R
    finish = _program([_line(xf, xf), _line(-15.0, xf)], (xf, -15.0))
    out["pocket"] = (([0, 0, -5], [80, 80, 2.5]), rough, finish)
    # arc (Fig. 14): a circular pocket wall of radius 60 about (70, 70) with 10 mm left, finished
    # counter-clockwise (wall on the right) over half a turn.
    rr, rf = 60.0 - R - 10.0, 60.0 - R
    rough = _program([_arc("G3", 70.0 - rr, 70.0, -rr, 0.0), _arc("G3", 70.0 + rr, 70.0, rr, 0.0)],
                     (70.0 + rr, 70.0), z=-1.0)
    finish = _program([_arc("G3", 70.0, 70.0 + rf, -rf, 0.0), _arc("G3", 70.0 - rf, 70.0, 0.0, -rf)],
                      (70.0 + rf, 70.0))
    out["arc"] = (([0, 0, -5], [140, 140, 2.5]), rough, finish)
    # angled (Fig. 15): walls along 25° then -20° (a convex corner at (50, 40)), 11 mm left, material on
    # the right of the feed.
    def offset_path(off):
        d1 = np.array([np.cos(np.radians(25)), np.sin(np.radians(25))])
        d2 = np.array([np.cos(np.radians(-20)), np.sin(np.radians(-20))])
        p1 = np.array([50.0, 40.0])
        p0, p2 = p1 - 60 * d1, p1 + 60 * d2
        n1, n2 = np.array([-d1[1], d1[0]]), np.array([-d2[1], d2[0]])  # left normals (away from the wall)
        return p0 + off * n1, p1 + off * n1, p1 + off * n2, p2 + off * n2, p1
    a, b, e, f, p1 = offset_path(R + 11.0)
    rough = _program([_line(*b), _arc("G2", *e, *(p1 - b)), _line(*f)], a, z=-1.0)
    a, b, e, f, p1 = offset_path(R)
    finish = _program([_line(*b), _arc("G2", *e, *(p1 - b)), _line(*f)], a)
    out["angled"] = (([0, -10, -5], [100, 50, 2.5]), rough, finish)
    return out


def run_case(name, spec, outdir, schemes, plot=True):
    (lo, hi), rough, finish = spec
    cdir = os.path.join(outdir, name)
    os.makedirs(cdir, exist_ok=True)
    with open(os.path.join(cdir, "tool.toml"), "w") as fh:
        fh.write(TOOL)
    with open(os.path.join(cdir, "rough.nc"), "w") as fh:
        fh.write(rough)
    with open(os.path.join(cdir, "finish.nc"), "w") as fh:
        fh.write(finish)
    with open(os.path.join(cdir, "stock.toml"), "w") as fh:
        fh.write(f"min_mm = {list(map(float, lo))}\nmax_mm = {list(map(float, hi))}\nspacing_mm = 0.1\n\n"
                 "[[pre_cut]]\nprogram = \"rough.nc\"\ntool = \"tool.toml\"\n")
    cutter = ns.cutter.load_cutter(os.path.join(cdir, "tool.toml"))
    stock = d.load_stock(os.path.join(cdir, "stock.toml"))
    program = ns.toolpath.read_gcode(os.path.join(cdir, "finish.nc"))
    setup = d.setup_path(program, cutter, stock, coefficients="cho_suh_example", rpm=600.0, spacing=0.5)
    t0 = time.perf_counter()
    before = d.predict_path(setup)
    t_pred = time.perf_counter() - t0
    rows = {"points": len(setup.nominal), "side": str(setup.side).split(".")[-1],
            "max_wall_error_before_um": {k: v * 1e3 for k, v in d.max_wall_error(before).items()},
            "predict_s": t_pred, "schemes": {}}
    results = {}
    for sc in schemes:
        t0 = time.perf_counter()
        res = d.compensate_path(setup, scheme=sc, level="middle", tolerance=5e-4, discount=DISCOUNT)
        dt = time.perf_counter() - t0
        results[sc] = res
        rows["schemes"][sc] = {
            "converged": bool(res.converged), "iterations": int(res.iterations),
            "path_evaluations": int(res.path_evaluations), "point_evaluations": int(res.point_evaluations),
            "max_wall_error_after_um": float(np.max(np.abs(np.asarray(res.after.error)[:, 1]))) * 1e3,
            "time_s": dt, "message": res.message}
    if "integrated" in results and "sectional" in results:
        rows["integrated_vs_sectional_um"] = float(np.max(np.abs(
            np.asarray(results["integrated"].offsets) - np.asarray(results["sectional"].offsets)))) * 1e3
    if plot:
        from netshape._atomic import atomic_save_figure
        from netshape.deflection.plots import plot_case

        best = results.get("accelerated") or results.get("integrated") or next(iter(results.values()))
        fig = plot_case(setup.nominal, before, best.after, positions=np.asarray(best.positions),
                        normals=np.asarray(best.normals),
                        title=f"{name}: wall error before/after ({str(best.scheme).split('.')[-1]}, middle level)")
        atomic_save_figure(fig, os.path.join(outdir, f"{name}.png"), dpi=90)
    return rows


def experiment_trend(outdir, plot=True):
    """§2 set-up: steady down-milling wall error at mid-depth against the cutting width, 5/7/10 mm/min."""
    widths = np.linspace(0.25, 3.5, 14)
    out = {}
    for feed in (5.0, 7.0, 10.0):
        fz = feed / (600.0 * 4)
        errs = []
        for w in widths:
            m = d.make_model(diameter=7.0, flutes=4, helix_deg=33.7, stick_out=70.0, youngs_modulus=210e3,
                             feed_per_tooth=fz, ap=2.0, ae=float(w), mode="down", coefficients="cho_suh_example")
            errs.append(d.steady_wall(m, "down", levels=3)["wall_error_mm"]["middle"] * 1e3)
        out[f"{feed:g}"] = errs
    if plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from netshape._atomic import atomic_save_figure

        fig, ax = plt.subplots(figsize=(6, 4))
        for k, v in out.items():
            ax.plot(widths, v, "o-", ms=3, label=f"{k} mm/min")
        ax.set_xlabel("cutting width [mm]")
        ax.set_ylabel("wall error at mid-depth [µm]")
        ax.set_title("§2 set-up: D 7, 4 flutes, 33.7°, L 70, A 2, 600 rpm")
        ax.legend()
        fig.tight_layout()
        atomic_save_figure(fig, os.path.join(outdir, "experiment_trend.png"), dpi=90)
    return {"widths_mm": widths.tolist(), "error_um": out}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir")
    ap.add_argument("--quick", action="store_true", help="straight case only, two schemes, no plots of the rest")
    ap.add_argument("--cases", default="straight,pocket,arc,angled")
    args = ap.parse_args(argv)
    os.makedirs(args.outdir, exist_ok=True)
    all_cases = cases()
    names = ["straight"] if args.quick else args.cases.split(",")
    schemes = ("integrated", "accelerated") if args.quick else ("one-d", "integrated", "sectional", "accelerated")
    summary = {"cases": {}}
    for name in names:
        summary["cases"][name] = row = run_case(name, all_cases[name], args.outdir, schemes)
        b = row["max_wall_error_before_um"]
        print(f"{name}: {row['points']} points, {row['side']} wall; before: bottom {b['bottom']:.1f}, "
              f"middle {b['middle']:.1f}, top {b['top']:.1f} um ({row['predict_s']:.2f} s)")
        for sc, r in row["schemes"].items():
            print(f"  {sc:12s} after {r['max_wall_error_after_um']:7.3f} um  iterations {r['iterations']:3d}  "
                  f"path evaluations {r['path_evaluations']:3d}  point evaluations {r['point_evaluations']:6d}  "
                  f"{r['time_s']:.2f} s  {'ok' if r['converged'] else 'NOT CONVERGED: ' + r['message']}")
        if "integrated_vs_sectional_um" in row:
            print(f"  integrated vs sectional offsets: {row['integrated_vs_sectional_um']:.3f} um")
    summary["experiment_trend"] = experiment_trend(args.outdir)
    with open(os.path.join(args.outdir, "summary.json"), "w") as fh:
        json.dump(summary, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
