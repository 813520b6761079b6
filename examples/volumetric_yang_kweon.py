"""Yang & Kweon's flow (Fig. 4; docs/references.md): NURBS design surface → CL points on its offset surface →
volumetric error before compensation → compensated CL data → volumetric error after.

    python examples/volumetric_yang_kweon.py [--out DIR] [--n 41] [--machine examples/machines/hmc_yang_kweon.toml]

Writes into DIR (default ./volumetric_yang_kweon_out): fig6_error_map.png, fig7_offset_before_x1.png,
fig7_offset_before_x10.png, fig8_error_after.png, fig10_before_after_x10.png, nominal.ngc,
compensated.ngc and summary.json; prints the before/after ranges next to the paper's
(241.176–885.645 µm before, 6e-9–12.4e-9 µm after). The machine's error values are ours (the paper
prints none), so only the order of magnitude of "before" is comparable; "after" is the convergence
of the compensation and is comparable directly.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

import netshape as ns
from netshape._atomic import atomic_save_figure, atomic_write

HERE = Path(__file__).resolve().parent
PAPER_BEFORE_UM = (241.176, 885.645)
PAPER_AFTER_UM = (6e-9, 12.4e-9)


def design_surface() -> ns.geometry.NurbsSurface:
    """A free-form bicubic NURBS patch (5 × 5 control points, one raised weight) facing the HMC's
    spindle (+Z), 300 × 250 mm in X, Y, heights 60–140 mm above the table reference."""
    xs = np.linspace(250.0, 550.0, 5)
    ys = np.linspace(150.0, 400.0, 5)
    h = np.array([[60, 80, 90, 80, 60],
                  [80, 120, 130, 110, 70],
                  [90, 130, 140, 120, 80],
                  [80, 110, 120, 100, 70],
                  [60, 70, 80, 70, 60]], dtype=float)
    cps = np.array([[xs[i], ys[j], h[i, j]] for i in range(5) for j in range(5)])
    w = np.ones(25)
    w[12] = 1.5
    knots = np.array([0, 0, 0, 0, 0.5, 1, 1, 1, 1], dtype=float)
    return ns.geometry.NurbsSurface(3, 3, knots, knots, cps, w)


def run(out: Path, n: int = 41, machine_path: Path = HERE / "machines" / "hmc_yang_kweon.toml",
        offset: float = 5.0, chord_tolerance: float = 0.001, tolerance: float = 1e-11) -> dict:
    """Run the flow; ``tolerance`` is the compensation residual for the CL points [mm] (1e-11 mm, the
    order of the paper's 6e-9–12.4e-9 µm; the library default is 1e-9 mm)."""
    out.mkdir(parents=True, exist_ok=True)
    machine = ns.machine.load_machine(machine_path)
    surf = design_surface()
    us = np.linspace(0.0, 1.0, n)
    vs = np.linspace(0.0, 1.0, n)
    # eq. (12): O(u, v) = Q(u, v) + f(d)·n(u, v), f(d) = 5 mm (ball radius; Yang & Kweon Fig. 5)
    uv = np.array([[u, v] for u in us for v in vs])
    cl = ns.geometry.offset_points(surf, uv, offset)
    q = surf.evaluate(uv)

    # before compensation: where the tool centre actually goes for the nominal CL points
    before = ns.machine.error_map(machine, cl, shape=(n, n), label="CL before compensation")
    cmp_orders = ns.machine.compare_orders(machine, cl)
    # compensation in the post-processor (Yang & Kweon §4.2)
    cmd = ns.compensation.compensate_points(machine, cl, tolerance=tolerance)
    after_err = ns.machine.actual_points(machine, cmd) - cl
    after_ve = np.linalg.norm(after_err, axis=1)

    # plots (Yang & Kweon Fig. 6, 7(a), 7(b), 8, 10)
    atomic_save_figure(ns.machine.plot_error_map(before, title="Volumetric error map on the CL points "
                                                 f"(before): {before.volumetric.min() * 1e3:.1f} – "
                                                 f"{before.volumetric.max() * 1e3:.1f} µm"),
                       out / "fig6_error_map.png", dpi=110)
    grid = cl.reshape(n, n, 3)
    errs = before.errors.reshape(n, n, 3)
    atomic_save_figure(ns.machine.plot_surface_error(grid, errs, scale=1.0), out / "fig7_offset_before_x1.png", dpi=110)
    atomic_save_figure(ns.machine.plot_surface_error(grid, errs, scale=10.0), out / "fig7_offset_before_x10.png", dpi=110)
    emap_after = ns.machine.ErrorMap(cl, after_err, after_ve, np.zeros(len(cl)), (n, n), "after")
    atomic_save_figure(ns.machine.plot_error_map(emap_after, title="Volumetric error after compensation: "
                                                 f"{after_ve.min() * 1e3:.2e} – {after_ve.max() * 1e3:.2e} µm"),
                       out / "fig8_error_after.png", dpi=110)
    atomic_save_figure(ns.machine.plot_surface_error(grid, errs, scale=10.0, compensated=after_err.reshape(n, n, 3),
                                                     title="Offset surface before (dashed) and after (red) "
                                                     "compensation, errors ×10"),
                       out / "fig10_before_after_x10.png", dpi=110)

    # the same as G-code: a zig-zag of G1 moves through the CL grid, compensated by the post-processor
    rows = [grid[i] if i % 2 == 0 else grid[i][::-1] for i in range(n)]
    pts = np.vstack(rows)
    lines = ["G21 G90 G17", "T1 M6", "S6000 M3",
             "G0 X%.6f Y%.6f Z%.6f" % (pts[0][0], pts[0][1], pts[0][2] + 20), "G1 Z%.6f F600" % pts[0][2]]
    lines += ["G1 X%.6f Y%.6f Z%.6f%s" % (*p, " F1500" if i == 0 else "") for i, p in enumerate(pts[1:])]
    lines.append("M30")
    with atomic_write(out / "nominal.ngc", "w") as fh:
        fh.write("\n".join(lines) + "\n")
    report = ns.compensation.compensate_gcode(machine, out / "nominal.ngc", out / "compensated.ngc",
                                              chord_tolerance=chord_tolerance)

    summary = {
        "machine": machine.name,
        "cl_points": int(len(cl)),
        "design_surface_z_mm": [float(q[:, 2].min()), float(q[:, 2].max())],
        "before_um": [float(before.volumetric.min() * 1e3), float(before.volumetric.max() * 1e3)],
        "paper_before_um": list(PAPER_BEFORE_UM),
        "tolerance_mm": tolerance,
        "after_um": [float(after_ve.min() * 1e3), float(after_ve.max() * 1e3)],
        "paper_after_um": list(PAPER_AFTER_UM),
        "exact_minus_first_order_max_um": cmp_orders["max_difference_mm"] * 1e3,
        "largest_correction_um": float(np.linalg.norm(cmd - cl, axis=1).max() * 1e3),
        "gcode": report.to_dict(),
    }
    with atomic_write(out / "summary.json", "w") as fh:
        json.dump(summary, fh, indent=1)
    return summary


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=Path("volumetric_yang_kweon_out"))
    ap.add_argument("--n", type=int, default=41, help="CL grid points per parameter direction")
    ap.add_argument("--machine", type=Path, default=HERE / "machines" / "hmc_yang_kweon.toml")
    a = ap.parse_args(argv)
    s = run(a.out, a.n, a.machine)
    print(f"{s['machine']}: {s['cl_points']} CL points")
    print(f"  before compensation: {s['before_um'][0]:.1f} – {s['before_um'][1]:.1f} µm "
          f"(paper: {PAPER_BEFORE_UM[0]} – {PAPER_BEFORE_UM[1]} µm, on its own machine values)")
    print(f"  after compensation:  {s['after_um'][0]:.2e} – {s['after_um'][1]:.2e} µm "
          f"(paper: {PAPER_AFTER_UM[0]:.1e} – {PAPER_AFTER_UM[1]:.1e} µm)")
    print(f"  exact − first-order synthesis ≤ {s['exact_minus_first_order_max_um']:.3g} µm")
    g = s["gcode"]
    print(f"  G-code: {g['blocks_in']} blocks → {g['blocks_out']}, path within {g['max_path_deviation_mm'] * 1e3:.3f} µm")
    print(f"  written to {a.out}/")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
