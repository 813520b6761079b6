"""The learning cut (issue 43 item 4): cut a test wall, measure it, diagnose the wall bundle, update
the tool, compensate the part program with the updated tool — the offline counterpart of torque-based
online deflection compensation.

The "machine" here is netshape itself with a holder compliance the user's tool file does not know
(HIDDEN_UM_PER_N): it cuts the test wall and the part, so the result can be checked against the truth.

    python examples/deflection_learning_cut.py --out OUTDIR [--quick]

Steps (files in OUTDIR):
  1. tool.toml, stock.toml, test_cut.ngc (a straight down-milling wall, ae 1 mm, 4 mm deep), part.ngc
     (a rounded-rectangle pocket: two clearing rings, then a 0.5 mm finish pass);
  2. "cut and measure" the test wall: wall.csv (x_mm,error_mm at mid depth, every 20 µm, σ 1 µm);
  3. bundle/manifest.toml (kind wall_error, one contour experiment) → netshape diagnose;
  4. tool_updated.toml = the diagnosis written into tool.toml (netshape.discrepancy.update_tool);
  5. netshape deflection compensate part.ngc with tool.toml and with tool_updated.toml;
  6. the compensated programs cut by the "machine" (netshape deflection predict --drawing part.ngc with
     the true tool): the part's wall error with each, and with a compensation that knew the machine.
Prints one line per step and writes summary.json.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np

import netshape as ns
import netshape.discrepancy as nd
from netshape import deflection as d
from netshape.discrepancy.update_tool import apply_to_tool

HIDDEN_UM_PER_N = 0.12  # the machine's holder/spindle compliance [µm/N] (8.3 N/µm), unknown to tool.toml
COEFFICIENTS = "Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10"
RPM = 8000.0
TOOL = """# 6 mm carbide finishing end mill as catalogued (no holder term yet)
kind = "flat"
diameter_mm = 6.0
flutes = 3
helix_deg = 30.0
flute_length_mm = 20.0
stick_out_mm = 30.0
youngs_modulus_MPa = 600000.0
"""
STOCK = "min_mm = [-20.0, -16.0, -8.0]\nmax_mm = [40.0, 16.0, 0.0]\nspacing_mm = 0.1\n"
TEST_CUT = "G21 G90 G17\nS8000 M3\nG0 X25 Y-17 Z5\nG1 Z-4 F600\nG1 X38 Y-17 F4800\nG0 Z10\nM30\n"


def _pocket() -> str:
    """Two clearing rings (the outer 0.5 mm inside the wall) then the finish pass of a 24 x 16 mm pocket
    with 5 mm corners at Z −3, all counter-clockwise (down milling, the wall on the right)."""
    def loop(hx, hy, r):
        """A counter-clockwise loop from the middle of the −Y side; corner arcs of radius r (none if r ≤ 0)."""
        c = max(r, 0.0)
        pts = [(hx - c, -hy), (hx, -hy + c), (hx, hy - c), (hx - c, hy), (-hx + c, hy), (-hx, hy - c),
               (-hx, -hy + c), (-hx + c, -hy), (0.0, -hy)]
        centres = [(hx - c, -hy + c), (hx - c, hy - c), (-hx + c, hy - c), (-hx + c, -hy + c)]
        lines, prev = [f"G1 X0 Y{-hy:.3f}"], (0.0, -hy)
        for k, (x, y) in enumerate(pts):
            if k % 2 == 1 and c > 0:  # the corner arc into this point
                cx, cy = centres[k // 2]
                lines.append(f"G3 X{x:.3f} Y{y:.3f} I{cx - prev[0]:.3f} J{cy - prev[1]:.3f}")
            elif k % 2 == 0 or c > 0:
                lines.append(f"G1 X{x:.3f} Y{y:.3f}")
            prev = (x, y)
        return lines
    R = 3.0
    head = ["G21 G90 G17", "S8000 M3", "G0 X0 Y0 Z5", "G1 Z-3 F600", "G1 X0 Y0 F3600"]
    rings = [loop(12 - R - off, 8 - R - off, 5 - R - off) for off in (3.5, 0.5)]  # 0.5 mm left to finish
    finish = loop(12 - R, 8 - R, 5 - R)
    return "\n".join(head + rings[0] + rings[1] + finish + ["G0 Z10", "M30", ""])


def _cli(*args: str) -> str:
    proc = subprocess.run([sys.executable, "-m", "netshape", *args], capture_output=True, text=True)
    if proc.returncode:
        raise SystemExit(proc.stderr)
    return proc.stdout


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--quick", action="store_true", help="coarser stock grid (0.2 mm) and path spacing (1 mm)")
    args = ap.parse_args()
    out = Path(args.out)
    stock_text = STOCK.replace("spacing_mm = 0.1", "spacing_mm = 0.2") if args.quick else STOCK
    spacing = "1.0" if args.quick else "0.5"
    (out / "bundle").mkdir(parents=True, exist_ok=True)
    truth_text = TOOL + f"holder_compliance_um_per_N = {HIDDEN_UM_PER_N}\n"
    for name, text in (("tool.toml", TOOL), ("stock.toml", stock_text), ("test_cut.ngc", TEST_CUT),
                       ("part.ngc", _pocket()), ("machine_tool.toml", truth_text)):
        (out / name).write_text(text)
        if name != "part.ngc":
            (out / "bundle" / name).write_text(text)

    # 2. the machine cuts the test wall; a probe measures it at mid depth (x along the contour)
    truth = ns.cutter.load_cutter(out / "machine_tool.toml")
    setup = d.setup_path(ns.toolpath.read_gcode(out / "test_cut.ngc"), truth, d.load_stock(out / "stock.toml"),
                         coefficients=COEFFICIENTS, rpm=RPM, spacing=0.5, profile_levels=21)
    r = d.predict_path(setup)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(np.asarray(setup.nominal)[:, :2], axis=0).T))])
    x = np.arange(4.0, 10.0 + 1e-9, 0.02)
    err = np.interp(x, s, np.asarray(r.error)[:, 1]) + np.random.default_rng(7).normal(0.0, 1e-3, x.size)
    np.savetxt(out / "bundle" / "wall.csv", np.column_stack([x, err]), delimiter=",", header="x_mm,error_mm",
               comments="", fmt="%.6f")
    print(f"1-2. test wall cut and measured: {x.size} points, mean error {1e3 * err.mean():.1f} µm")

    # 3. the bundle, diagnosed
    (out / "bundle" / "manifest.toml").write_text(
        'kind = "wall_error"\n[model]\ncoefficients = "' + COEFFICIENTS + '"\n[noise]\nsigma_mm = 0.001\n'
        '[[experiment]]\nfile = "wall.csv"\nprogram = "test_cut.ngc"\ntool = "tool.toml"\nstock = "stock.toml"\n'
        f"spindle_rpm = {RPM}\nspacing_mm = 0.5\n")
    diag = nd.diagnose(nd.load_bundle(out / "bundle"))
    found = diag.parameters.get("compliance_um_per_N", float("nan"))
    print(f"3. diagnose: effect {diag.effect}, compliance {found:.4f} µm/N (hidden {HIDDEN_UM_PER_N}), "
          f"rms {1e3 * diag.rms_before:.2f} → {1e3 * diag.rms_after:.2f} µm")

    # 4. the tool updated
    (out / "tool_updated.toml").write_text(apply_to_tool(diag, (out / "tool.toml").read_text()))
    print("4. tool_updated.toml written")

    # 5-6. the part compensated with each tool, then cut by the machine
    common = ["--stock", str(out / "stock.toml"), "--rpm", str(RPM), "--coefficients", COEFFICIENTS,
              "--spacing", spacing]
    result = {"hidden_compliance_um_per_N": HIDDEN_UM_PER_N, "found_compliance_um_per_N": found,
              "effect": diag.effect}
    runs = (("uncompensated", None), ("original tool", "tool.toml"), ("updated tool", "tool_updated.toml"),
            ("machine's own tool (the best possible)", "machine_tool.toml"))
    for label, tool in runs:
        prog = out / "part.ngc"
        if tool is not None:
            prog = out / f"part_{tool.split('.')[0]}.nc"
            _cli("deflection", "compensate", str(out / "part.ngc"), "--tool", str(out / tool), "-o", str(prog),
                 "--scheme", "accelerated", *common)
        stem = label.split(" (")[0].replace(" ", "_").replace("'", "")
        js = out / f"check_{stem}.json"
        _cli("deflection", "predict", str(prog), "--drawing", str(out / "part.ngc"), "--tool",
             str(out / "machine_tool.toml"), "--json", str(js), *common)
        data = json.loads(js.read_text())
        pts = data["points"]
        mid = 1e3 * np.asarray(pts["error_middle_mm"])[np.asarray(pts["final_wall"], bool)]
        result[label] = {"max_wall_error_mm": data["max_wall_error_mm"], "middle_rms_um": float(np.sqrt(np.mean(mid**2))),
                         "middle_p95_um": float(np.percentile(np.abs(mid), 95))}
        print(f"5-6. part cut by the machine, {label}: wall error at mid depth (the compensation's level) rms "
              f"{result[label]['middle_rms_um']:.2f} µm, 95 % within {result[label]['middle_p95_um']:.2f} µm; "
              "largest bottom/middle/top " + " / ".join(f"{1e3 * v:.1f}" for v in data["max_wall_error_mm"].values())
              + " µm")
    (out / "summary.json").write_text(json.dumps(result, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
