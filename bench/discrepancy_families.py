"""Scored families of generated bundles for `netshape.discrepancy.diagnose` (issue 37 item 6): per kind,
bundles each hiding one random catalogue effect (or none) with random parameters, and the table of
exact-effect recovery, false naming and parameter error per kind and per effect.

    PYTHONPATH=python python bench/discrepancy_families.py [--quick] [--per-kind 60] [--half check|tune|all]

Seeds 0, 2, 4, … are the tuning half (thresholds may be chosen on them), 1, 3, 5, … the check half
(reported). Bundle s hides effect number (s // 2) mod (effects + 1), so both halves hold every effect;
the CSV form or measuring order (below) alternates with each pass through the effects.

* cutting_force: a 10 mm 3-flute 30° flat end mill, the 4 experiments of the test generators (slots at
  0.04 and 0.1 mm, up 0.07, down 0.13), 3 revolutions of 120 samples, noise 1–3 N, angle_deg or time_s.
  Forces from the NumPy element sum of the generators (not the fitted C++ kernel), a mode
  by simulating the 2nd-order system in time. Hidden: runout ρ 3–10 µm at λ 0–360°; edge forces each
  ×0.4–0.7 or ×1.5–2.5; chip exponent p 0.6–0.85; a mode of 800–2000 Hz, ζ 0.02–0.08.
* volumetric_error: two experiments (tool lengths 100 and 220 mm) of a 21 × 5 × 3 grid, 10 s per point,
  X-fastest serpentine or random order, both with t_s and direction; noise 0.5–1.5 µm;
  the data in a random measuring frame (rotation ≤ 50 µrad, translation ≤ 10 µm per axis). Geometric
  errors from netshape.machine, the rest written out in the generators. Hidden: squareness 15–60 µrad
  on one to three of EC0Y, EB0Z, EA0Z; scale 10–40 µm/m on one to three axes; thermal drift on a random
  axis, 5–15 µm, τ 300–3000 s; spindle tilt a, b 20–60 µrad; backlash on a random axis 4–12 µm; a
  cyclic error on X, 2–6 µm, period 45–150 mm.
* wall_error: three steady cuts (down a_e 0.5 mm at 0.15 mm, down 1.0 at 0.2, up 0.5 at 0.25; a_p 4 mm;
  6 mm 3-flute 30° carbide, 30 mm stick-out), the wall over 2 mm every 10 µm, x_mm,error_mm at z = 2 or
  x_mm,z_mm,error_mm at 5 heights; noise 0.5–1.5 µm. The manifest names steady straight
  cuts; the data come from another model: the Z-map sweep along a straight program
  (netshape.deflection.predict_path), the clamp spring loaded by the element-sum force at each height's
  generating instant, runout as exact circles of the flute passes. Hidden: holder spring 5–30 N/µm;
  runout ρ 2–8 µm at λ 0–360°.

Scores per bundle: `exact` — the effects added are exactly the hidden one (with its axis where it has
one), or none for a control; `false` — an effect other than the hidden one is added (or any, on a
control); `missed` — the hidden effect is not added and nothing else is. `ambiguous` counts false
namings the workflow itself flagged (`ambiguous` lists the named effect); `ambiguous raised` the bundles
with any `ambiguous` entry. The parameter error (exact
recoveries only) is relative to the hidden effect's size: runout |ρ̂e^{iλ̂} − ρe^{iλ}|/ρ; vectors
(squareness, scale, tilt) ‖v̂ − v‖/‖v‖; edge forces the largest |K̂ − K|/|K − K_model|; chip exponent
|p̂ − p|/(1 − p); the others the largest relative error of their parameters.
"""

from __future__ import annotations

import argparse
import cmath
import json
import math
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "python" / "discrepancy"))

import netshape.discrepancy as nd  # noqa: E402
import generators as g  # noqa: E402

FORCE_TOOL = {"type": "flat", "diameter_mm": 10.0, "flutes": 3, "helix_deg": 30.0}
EDGE_KEYS = ("Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm")
EFFECTS = {
    "cutting_force": (None, "runout", "edge_forces", "size_effect", "structural_mode"),
    "volumetric_error": (None, "squareness", "scale_error", "thermal_drift", "spindle_tilt", "backlash",
                         "cyclic_error"),
    "wall_error": (None, "holder_compliance", "runout"),
}


def hidden(kind: str, seed: int):
    """The effect hidden in bundle ``seed`` of ``kind`` and its random parameters (the truth)."""
    effects = EFFECTS[kind]
    effect = effects[(seed // 2) % len(effects)]
    rng = np.random.default_rng([37, list(EFFECTS).index(kind), seed])
    u = rng.uniform
    if effect is None:
        return None, {}
    if effect == "runout":
        rho = u(3e-3, 10e-3) if kind == "cutting_force" else u(2e-3, 8e-3)
        return effect, {"rho_mm": rho, "lambda_deg": u(0.0, 360.0)}
    if effect == "edge_forces":
        f = [u(0.4, 0.7) if rng.random() < 0.5 else u(1.5, 2.5) for _ in EDGE_KEYS]
        return effect, {k: g.MODEL[k] * fk for k, fk in zip(EDGE_KEYS, f)}
    if effect == "size_effect":
        return effect, {"chip_exponent": u(0.6, 0.85)}
    if effect == "structural_mode":
        return effect, {"frequency_hz": u(800.0, 2000.0), "damping_ratio": u(0.02, 0.08)}
    signs = rng.choice([-1.0, 1.0], 3)
    on = np.zeros(3, bool)
    on[rng.permutation(3)[: rng.integers(1, 4)]] = True
    if effect == "squareness":
        v = np.where(on, signs * u(15.0, 60.0, 3), 0.0)
        return effect, dict(zip(("EC0Y_urad", "EB0Z_urad", "EA0Z_urad"), v))
    if effect == "scale_error":
        v = np.where(on, signs * u(10.0, 40.0, 3), 0.0)  # hidden, on top of the model's EXX, EYY, EZZ
        return effect, dict(zip(("EXX_um_per_m", "EYY_um_per_m", "EZZ_um_per_m"), v))
    if effect == "thermal_drift":
        return effect, {"axis": "XYZ"[rng.integers(3)], "amplitude_mm": signs[0] * u(5e-3, 15e-3),
                        "time_constant_s": u(300.0, 3000.0)}
    if effect == "spindle_tilt":
        return effect, {"tilt_a_urad": signs[0] * u(20.0, 60.0), "tilt_b_urad": signs[1] * u(20.0, 60.0)}
    if effect == "backlash":
        return effect, {"axis": "XYZ"[rng.integers(3)], "reversal_um": u(4.0, 12.0)}
    if effect == "cyclic_error":
        return effect, {"axis": "X", "period_mm": u(45.0, 150.0), "amplitude_mm": u(2e-3, 6e-3),
                        "phase_deg": u(0.0, 360.0)}
    if effect == "holder_compliance":
        return effect, {"stiffness_N_per_um": u(5.0, 30.0)}
    raise AssertionError(effect)


def variant_index(kind: str, seed: int) -> int:
    """0 or 1: the CSV form or measuring order of bundle ``seed``, alternating with each pass through
    the kind's effects, so every effect meets both in each half."""
    return (seed // 2 // len(EFFECTS[kind])) % 2


def force_case(folder, seed, effect, p):
    rng = np.random.default_rng([370, seed])
    kw = {}
    if effect == "runout":
        kw["runout"] = (p["rho_mm"], p["lambda_deg"])
    elif effect == "edge_forces":
        kw["edges"] = tuple(p[k] for k in EDGE_KEYS)
    elif effect == "size_effect":
        kw["exponent"] = p["chip_exponent"]
    elif effect == "structural_mode":
        kw["mode"] = (p["frequency_hz"], p["damping_ratio"])
    form = ("angle", "time")[variant_index("cutting_force", seed)]
    return g.force_bundle(folder, noise=float(rng.uniform(1.0, 3.0)), form=form, per_rev=120, seed=seed,
                          phase0=float(rng.uniform(0, 2 * math.pi)), tool=FORCE_TOOL, **kw), form


def volumetric_case(folder, seed, effect, p):
    rng = np.random.default_rng([371, seed])
    kw = {}
    if effect == "squareness":
        kw["squareness"] = {k[:4]: v for k, v in p.items() if v}
    elif effect == "scale_error":
        kw["scale"] = {k[:3]: v for k, v in p.items() if v}
    elif effect == "thermal_drift":
        kw["thermal"] = (p["axis"], p["amplitude_mm"], p["time_constant_s"])
    elif effect == "spindle_tilt":
        kw["tilt"] = (p["tilt_a_urad"], p["tilt_b_urad"])
    elif effect == "backlash":
        kw["backlash"] = (p["axis"], p["reversal_um"])
    elif effect == "cyclic_error":
        kw["cyclic"] = (p["axis"], p["amplitude_mm"], p["period_mm"], p["phase_deg"])
    order = ("serpentine", "random")[variant_index("volumetric_error", seed)]
    frame = (rng.uniform(-50, 50, 3), rng.uniform(-0.01, 0.01, 3))
    return g.volumetric_bundle(folder, noise=float(rng.uniform(5e-4, 1.5e-3)), seed=seed, grid=(21, 5, 3),
                               order=order, seconds_per_point=10.0, frame=frame, **kw), order


#: (mode, radial depth [mm], feed per tooth [mm]) of the wall family's three steady cuts
WALL_CUTS = g.WALL_CONDITIONS
WALL_Z = (0.4, 1.2, 2.0, 2.8, 3.6)  # profile levels of predict_path (0.2 mm apart over a_p 4 mm)


def wall_zmap(folder: Path, mode: str, ae: float, c: float):
    """The wall error (21 profile levels, (21,)) of a steady straight cut from the Z-map sweep along a
    straight program: the middle of a 35 mm pass along ±X over a 4 mm deep block, the wall at Y = 0."""
    import netshape as ns
    from netshape import deflection as d

    R, N, rpm = 3.0, 3, 8000.0
    (folder / "zmap_tool.toml").write_text(g.CONTOUR_TOOL_TOML)
    (folder / "zmap_stock.toml").write_text("min_mm = [-10.0, -10.0, -8.0]\nmax_mm = [40.0, 0.0, 0.0]\n"
                                            "spacing_mm = 0.1\n")
    y = R - ae
    xs = ("X-5", "X30") if mode == "down" else ("X35", "X0")
    (folder / "zmap.ngc").write_text(f"G21 G90 G17\nS8000 M3\nG0 {xs[0]} Y{y} Z5\nG1 Z-4 F600\n"
                                     f"G1 {xs[1]} F{c * N * rpm}\nG0 Z10\nM30\n")
    setup = d.setup_path(ns.toolpath.read_gcode(folder / "zmap.ngc"),
                         ns.cutter.load_cutter(folder / "zmap_tool.toml"),
                         d.load_stock(folder / "zmap_stock.toml"),
                         coefficients=g.WALL_MODEL["coefficients"], rpm=rpm, spacing=0.5, profile_levels=21)
    r = d.predict_path(setup)
    nominal = np.asarray(setup.nominal)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(nominal[:, :2], axis=0).T))])
    k = int(np.argmin(np.abs(s - 17.5)))
    assert abs(float(np.asarray(r.depth)[k]) - 4.0) < 1e-9 and str(setup.side).endswith(
        "left" if mode == "up" else "right")
    return np.asarray(r.profile)[k]


def wall_case(folder, seed, effect, p):
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng([372, seed])
    form = ("x", "xz")[variant_index("wall_error", seed)]
    t = g.WALL_TOOL
    R, N = t["diameter_mm"] / 2, t["flutes"]
    kb = math.tan(math.radians(t["helix_deg"])) / R
    coef = dict(zip(g.MODEL, (900.0, 270.0, 150.0, 16.0, 20.0, 10.0)))
    zs = np.asarray(WALL_Z if form == "xz" else (2.0,))
    x = np.arange(0.0, 2.0 + 1e-9, 0.01)
    X, Z = np.meshgrid(x, zs)
    noise = float(rng.uniform(5e-4, 1.5e-3))
    exps = []
    for i, (mode, ae, c) in enumerate(WALL_CUTS):
        profile = wall_zmap(folder, mode, ae, c)
        E = np.repeat(profile[np.rint(zs / 0.2).astype(int)][:, None], len(x), axis=1)
        if effect == "holder_compliance":
            right = mode == "down"
            phi_w = math.pi if right else 0.0  # the wall's immersion angle (down: exit, up: entry)
            F = g.oracle_forces(phi_w + kb * zs, feed=c, mode=mode, ae=ae, coefficients=coef, tool=t,
                                ap=g.WALL_AP, dz=0.002)
            E -= (F[:, 1] * (-1.0 if right else 1.0))[:, None] / (p["stiffness_N_per_um"] * 1e3)
        elif effect == "runout":
            E -= g.runout_reach(X, Z, R=R, flutes=N, kb=kb, feed=c, runout=(p["rho_mm"], p["lambda_deg"]))
        E += rng.normal(0.0, noise, E.shape)
        name = f"wall{i + 1}.csv"
        if form == "xz":
            g.write_csv(folder / name, ["x_mm", "z_mm", "error_mm"],
                        np.column_stack([X.ravel(), Z.ravel(), E.ravel()]))
        else:
            g.write_csv(folder / name, ["x_mm", "error_mm"], np.column_stack([x, E[0]]))
        exps.append({"file": name, "feed_per_tooth_mm": c, "axial_depth_mm": g.WALL_AP, "radial_depth_mm": ae,
                     "mode": mode, "spindle_rpm": 8000.0})
    g.write_manifest(folder, "wall_error", {"tool": t, "model": g.WALL_MODEL}, exps)
    return folder, form


CASES = {"cutting_force": force_case, "volumetric_error": volumetric_case, "wall_error": wall_case}


def _rel(a, b):
    return abs(a - b) / abs(b)


def parameter_error(effect, got: dict, truth: dict, variant: str) -> float:
    """The relative parameter error of a recovered effect (see the module docstring). A time series
    does not say which flute is "1": its runout angle counts modulo the flute pitch."""
    if effect == "runout":
        z = cmath.rect(truth["rho_mm"], math.radians(truth["lambda_deg"]))
        shifts = range(FORCE_TOOL["flutes"]) if variant == "time" else (0,)
        pitch = 360.0 / FORCE_TOOL["flutes"]
        return min(abs(cmath.rect(got["rho_mm"], math.radians(got["lambda_deg"] + k * pitch)) - z)
                   for k in shifts) / abs(z)
    if effect in ("squareness", "scale_error", "spindle_tilt"):
        v, w = np.array([got[k] for k in truth]), np.array(list(truth.values()))
        if effect == "scale_error":  # reported: the axis' whole linear term, the model's included
            v = v - [1e6 * (g.VOL_MODEL.get(k[:3], [0.0, 0.0]) + [0.0])[1] for k in truth]
        return float(np.linalg.norm(v - w) / np.linalg.norm(w))
    if effect == "edge_forces":
        return max(abs(got[k] - truth[k]) / abs(truth[k] - g.MODEL[k]) for k in EDGE_KEYS)
    if effect == "size_effect":
        return abs(got["chip_exponent"] - truth["chip_exponent"]) / (1 - truth["chip_exponent"])
    keys = {"structural_mode": ("frequency_hz", "damping_ratio"),
            "thermal_drift": ("amplitude_mm", "time_constant_s"), "backlash": ("reversal_um",),
            "cyclic_error": ("period_mm", "amplitude_mm"),
            "holder_compliance": ("stiffness_N_per_um",)}[effect]
    return max(_rel(got[k], truth[k]) for k in keys)


def classify(effect, truth: dict, named: list) -> tuple[bool, bool]:
    """(exact, false naming) of the effects added, ``named`` [(effect, parameters)], when ``effect``
    (None: a control) with parameters ``truth`` was hidden; an effect on another axis is another effect."""
    names = [n for n, _ in named]
    axis_ok = all(pp.get("axis", truth.get("axis")) == truth.get("axis") for n, pp in named if n == effect)
    exact = names == ([effect] if effect else []) and axis_ok
    return exact, any(n != effect for n in names) or (effect in names and not axis_ok)


def score(kind, seed, tmp):
    """Generate and diagnose bundle ``seed`` of ``kind``; returns a row dict."""
    effect, truth = hidden(kind, seed)
    folder, variant = CASES[kind](Path(tmp) / f"{kind}-{seed}", seed, effect, truth)
    d = nd.diagnose(nd.load_bundle(folder))
    named = [(e["effect"], e["parameters"]) for e in d.effects]
    names = [n for n, _ in named]
    exact, false = classify(effect, truth, named)
    amb = d.to_dict().get("ambiguous") or []
    flagged = false and any(set(names) & set(a["effects"]) for a in amb)
    perr = parameter_error(effect, named[0][1], truth, variant) if exact and effect else None
    return {"kind": kind, "seed": seed, "effect": effect or "none", "variant": variant, "named": names,
            "exact": exact, "false": false, "missed": not exact and not false, "ambiguous": flagged,
            "any_ambiguous": bool(amb),
            "perr": perr, "params": named[0][1] if named else None, "truth": truth}


def table(rows) -> str:
    """The markdown table of the rows: per kind, per effect and a total line per kind."""
    out = ["| kind | hidden effect | bundles | exact | false naming | missed | params within 10 % | "
           "param error median / max | `ambiguous` raised |", "|---|---|---|---|---|---|---|---|---|"]
    groups = defaultdict(list)
    for r in rows:
        groups[(r["kind"], r["effect"])].append(r)
        groups[(r["kind"], "all")].append(r)
    for kind in EFFECTS:
        for eff in [e or "none" for e in EFFECTS[kind]] + ["all"]:
            rs = groups.get((kind, eff))
            if not rs:
                continue
            n = len(rs)
            ex, fa = sum(r["exact"] for r in rs), sum(r["false"] for r in rs)
            amb = sum(r["ambiguous"] for r in rs)
            pe = [r["perr"] for r in rs if r["perr"] is not None]
            within = f"{sum(e <= 0.1 for e in pe)}/{len(pe)}" if pe else "–"
            errs = f"{100 * np.median(pe):.1f} / {100 * max(pe):.1f} %" if pe else "–"
            label = f"**{eff}**" if eff == "all" else eff
            fal = f"{fa} ({100 * fa / n:.0f} %)" + (f", {amb} flagged ambiguous" if amb else "")
            out.append(f"| {kind} | {label} | {n} | {ex} ({100 * ex / n:.0f} %) | {fal} | "
                       f"{sum(r['missed'] for r in rs)} | {within} | {errs} | "
                       f"{sum(r.get('any_ambiguous', False) for r in rs)} |")
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="3 bundles per kind (seeds 1, 3, 5), < 60 s")
    ap.add_argument("--per-kind", type=int, default=100,
                    help="seeds --first … this − 1 per kind, both halves (default 100)")
    ap.add_argument("--half", choices=("check", "tune", "all"), default="check")
    ap.add_argument("--kinds", default=",".join(EFFECTS), help="comma-separated kinds")
    ap.add_argument("--verbose", action="store_true", help="one line per bundle")
    ap.add_argument("--first", type=int, default=0, help="start at this seed (to split a run)")
    ap.add_argument("--rows-out", help="also write the rows to this JSON file")
    ap.add_argument("--merge", nargs="+", help="print the table of these --rows-out files, run nothing")
    args = ap.parse_args(argv)
    if args.merge:
        rows = [r for f in args.merge for r in json.loads(Path(f).read_text())]
        print(table(rows))
        return rows
    if args.quick:
        seeds = [1, 3, 5]
    else:
        seeds = [s for s in range(args.first, args.per_kind)
                 if args.half == "all" or s % 2 == (args.half == "check")]
    rows, t0, c0 = [], time.perf_counter(), time.process_time()
    with tempfile.TemporaryDirectory() as tmp:
        for kind in args.kinds.split(","):
            for seed in seeds:
                r = score(kind, seed, tmp)
                rows.append(r)
                if args.verbose or (not r["exact"]):
                    print(f"  {kind} seed {seed} ({r['variant']}): hidden {r['effect']} {r['truth']} -> "
                          f"{r['named']} {r['params']}", flush=True)
    half = "quick" if args.quick else args.half
    print(f"\n{half} half, seeds {seeds[0]}…{seeds[-1]} ({len(seeds)} per kind), "
          f"{time.perf_counter() - t0:.0f} s wall, {time.process_time() - c0:.0f} s CPU\n")
    print(table(rows))
    if args.rows_out:
        Path(args.rows_out).write_text(json.dumps(rows, default=float))
    return rows


if __name__ == "__main__":
    main()
