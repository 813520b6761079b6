"""Bundles with hidden effects for the discrepancy tests (and bench/discrepancy.py).

Forces come from an independent NumPy evaluation of the element sum (the frame and formulas of docs/conventions.md:
φ_j(z) = θ + j·2π/N − k_β·z, h = c·sin φ (+ runout offset R_j − R_{j−1}, clamped at 0), linear edge
forces, dF → (Fx, Fy, Fz)), with disks 5× thinner than the workflow's; a structural mode is applied by
simulating the continuous 2nd-order system in time (scipy.signal.lsim over 8 revolutions, the last
ones kept). Volumetric errors come from netshape.machine (validated against an independent matrix
composition in tests/python/machine) plus thermal drift and backlash written out here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

TOOL = {"type": "flat", "diameter_mm": 10.0, "flutes": 2, "helix_deg": 30.0}
MODEL = {
    "Ktc_N_per_mm2": 900.0,
    "Krc_N_per_mm2": 270.0,
    "Kac_N_per_mm2": 150.0,
    "Kte_N_per_mm": 16.0,
    "Kre_N_per_mm": 20.0,
    "Kae_N_per_mm": 10.0,
}
#: (mode, radial depth [mm], feed per tooth [mm]) of the 4 experiments of a force bundle
CONDITIONS = [("slot", 10.0, 0.04), ("slot", 10.0, 0.1), ("up", 5.0, 0.07), ("down", 3.0, 0.13)]
RPM, AP = 6000.0, 3.0


def oracle_forces(
    angles, *, feed, mode, ae, coefficients, runout=None, exponent=None, h_ref=None, tool=TOOL, ap=AP, dz=0.01
):
    """Forces on the cutter (n, 3) [N] at angles θ (n,) [rad] by a direct element sum."""
    R = tool["diameter_mm"] / 2
    N = tool["flutes"]
    kb = math.tan(math.radians(tool["helix_deg"])) / R
    nd = int(math.ceil(ap / dz - 1e-9))
    z = (np.arange(nd) + 0.5) * (ap / nd)
    w = ap / nd
    if mode == "slot":
        st, ex = 0.0, math.pi
    elif mode == "up":
        st, ex = 0.0, math.acos(1 - ae / R)
    else:
        st, ex = math.pi - math.acos(1 - ae / R), math.pi
    ktc, krc, kac, kte, kre, kae = (coefficients[k] for k in MODEL)
    r = (
        np.zeros(N)
        if runout is None
        else runout[0] * np.cos(math.radians(runout[1]) - 2 * np.pi * np.arange(N) / N)
    )
    F = np.zeros((len(angles), 3))
    for j in range(N):
        phi = np.mod(angles[:, None] + 2 * np.pi * j / N - kb * z[None, :], 2 * np.pi)
        h = feed * np.sin(phi) + (r[j] - r[(j + 1) % len(r)])  # flute j + 1 passed just before j
        on = (phi >= st) & (phi <= ex) & (h > 0)
        h = np.where(on, h, 0.0)
        g = h if exponent is None else h_ref * (h / h_ref) ** exponent
        ft = np.where(on, ktc * g + kte, 0.0) * w
        fr = np.where(on, krc * g + kre, 0.0) * w
        fa = np.where(on, kac * g + kae, 0.0) * w
        F[:, 0] += np.sum(-ft * np.cos(phi) - fr * np.sin(phi), 1)
        F[:, 1] += np.sum(ft * np.sin(phi) - fr * np.cos(phi), 1)
        F[:, 2] += np.sum(fa, 1)
    return F


def _toml_value(v):
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return repr(float(v)) if isinstance(v, float) else str(v)


def write_manifest(folder: Path, kind: str, tables: dict, experiments: list) -> None:
    lines = [f'kind = "{kind}"']
    for name, t in tables.items():
        lines.append(f"[{name}]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in t.items()]
    for e in experiments:
        lines.append("[[experiment]]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in e.items()]
    (folder / "manifest.toml").write_text("\n".join(lines) + "\n")


def replace_once(path: Path, old: str, new: str) -> None:
    """Replace the first ``old`` in the text file ``path`` by ``new`` (``old`` must be there): how the
    malformed-bundle tests break one field of a good bundle."""
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))


def write_csv(path: Path, header: list, data: np.ndarray) -> None:
    np.savetxt(path, data, delimiter=",", header=",".join(header), comments="", fmt="%.10g")


def force_bundle(
    folder,
    *,
    runout=None,
    edges=None,
    exponent=None,
    mode=None,
    noise=2.0,
    form="angle",
    revolutions=3,
    per_rev=180,
    seed=1,
    conditions=CONDITIONS,
    phase0=1.0,
    tool=None,
):
    """Write a cutting_force bundle to ``folder``. Hidden effects: ``runout`` (ρ [mm], λ [deg]),
    ``edges`` (true Kte, Kre, Kae; the manifest's model keeps MODEL's), ``exponent`` (chip exponent p),
    ``mode`` (f_n [Hz], ζ). ``form``: "angle" (angle_deg) or "time" (time_s, flute 1 at θ = phase0
    [rad] when t = 0). Returns the folder."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    tool = tool or TOOL
    rng = np.random.default_rng(seed)
    truth = dict(MODEL)
    if edges is not None:
        truth.update(zip(("Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm"), edges))
    h_ref = float(np.exp(np.mean(np.log([c for _, _, c in conditions]))))
    omega = 2 * np.pi * RPM / 60
    exps = []
    for i, (m, ae, c) in enumerate(conditions):
        settle = 5 if mode is not None else 0
        k = np.arange((revolutions + settle) * per_rev)
        theta = 2 * np.pi * k / per_rev + (phase0 if form == "time" else 0.0)
        F = oracle_forces(
            theta,
            feed=c,
            mode=m,
            ae=ae,
            coefficients=truth,
            runout=runout,
            exponent=exponent,
            h_ref=h_ref,
            tool=tool,
        )
        if mode is not None:
            from scipy.signal import lsim

            wn = 2 * np.pi * mode[0]
            sys = ([wn**2], [1.0, 2 * mode[1] * wn, wn**2])
            t = theta / omega
            F = np.column_stack([lsim(sys, F[:, a], t)[1] for a in range(3)])
            F, theta = F[settle * per_rev :], theta[settle * per_rev :] - 2 * np.pi * settle
        F = F + rng.normal(0.0, noise, F.shape)
        name = f"e{i + 1}.csv"
        if form == "angle":
            write_csv(
                folder / name, ["angle_deg", "fx_N", "fy_N", "fz_N"], np.column_stack([np.degrees(theta), F])
            )
        else:
            t = (theta - phase0) / omega  # θ(t) = phase0 + Ω t, t from 0
            write_csv(folder / name, ["time_s", "fx_N", "fy_N", "fz_N"], np.column_stack([t, F]))
        exps.append(
            {
                "file": name,
                "spindle_rpm": RPM,
                "feed_per_tooth_mm": c,
                "axial_depth_mm": AP,
                "radial_depth_mm": ae,
                "mode": m,
            }
        )
    write_manifest(folder, "cutting_force", {"tool": tool, "model": MODEL}, exps)
    return folder


# --- round trips (issue 43): the model of an updated manifest against the hidden truth ---------


def manifest_force_model(manifest: dict, mode, ae, c):
    """(FlatEndModel, RunoutSizeEffect): the C++ forward model of a parsed cutting-force manifest's tool
    and model at one condition."""
    from netshape import force as _f

    t, k = manifest["tool"], manifest["model"]
    eng = _f.AngularEngagement.from_mode(_f.milling_mode_from_string(mode), t["diameter_mm"] / 2,
                                        ae if mode != "slot" else 0.0)
    lin = _f.LinearEdgeCoefficients(*(k[n] for n in ("Ktc_N_per_mm2", "Krc_N_per_mm2", "Kac_N_per_mm2",
                                                    "Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm")))
    model = _f.FlatEndModel(radius=t["diameter_mm"] / 2, flutes=t["flutes"], helix=np.radians(t["helix_deg"]),
                           axial_depth=AP, feed_per_tooth=c, engagement=eng, linear_edge=lin, disk_height=0.01)
    ext = _f.RunoutSizeEffect(runout_rho=t.get("runout_rho_mm", 0.0),
                             runout_lambda=np.radians(t.get("runout_lambda_deg", 0.0)),
                             chip_exponent=k.get("chip_exponent", 1.0), reference_chip=k.get("reference_chip_mm", 0.0))
    return model, ext


def model_force_error(manifest: dict, hidden: dict) -> float:
    """rms of (the manifest's model − the hidden truth of force_bundle(**hidden)) forces over CONDITIONS,
    one revolution [N]."""
    from netshape import force as _f

    th = np.linspace(0, 2 * np.pi, 240, endpoint=False)
    h_ref = float(np.exp(np.mean(np.log([c for _, _, c in CONDITIONS]))))
    truth = dict(MODEL)
    if "edges" in hidden:
        truth.update(zip(("Kte_N_per_mm", "Kre_N_per_mm", "Kae_N_per_mm"), hidden["edges"]))
    err = []
    for mode, ae, c in CONDITIONS:
        ref = oracle_forces(th, feed=c, mode=mode, ae=ae, coefficients=truth, runout=hidden.get("runout"),
                            exponent=hidden.get("exponent"), h_ref=h_ref)
        model, ext = manifest_force_model(manifest, mode, ae, c)
        err.append(_f.flat_end_forces_extended(model, ext, th) - ref)
    return float(np.sqrt(np.mean(np.square(err))))


# --- volumetric --------------------------------------------------------------------------------------

MACHINE = {"tool_side": ["Z"], "workpiece_side": ["Y", "X"], "tool_length_mm": 100.0}
VOL_MODEL = {"EXX": [0.0, 5e-6], "EYX": [0.0, 0.0, 2e-9], "EBY": [1e-6, 2e-9]}


def _grid_path(nx=7, ny=5, nz=3):
    """Serpentine grid over x ∈ [−200, 200], y ∈ [−150, 150], z ∈ [−200, 0] mm: X moves along each
    line, alternately + and −. Returns points (n, 3) and the X approach direction (n,)."""
    pts, dirs = [], []
    xs = np.linspace(-200, 200, nx)
    s = 1
    for z in np.linspace(-200, 0, nz):
        for y in np.linspace(-150, 150, ny):
            for x in xs if s > 0 else xs[::-1]:
                pts.append((x, y, z))
                dirs.append(s)
            s = -s
    return np.array(pts, float), np.array(dirs, float)


def volumetric_bundle(
    folder,
    *,
    squareness=None,
    scale=None,
    thermal=None,
    tilt=None,
    backlash=None,
    noise=5e-4,
    seed=2,
    experiments=2,
    lengths=(100.0, 220.0),
    grid=(7, 5, 3),
    order="serpentine",
    seconds_per_point=20.0,
    cyclic=None,
    frame=None,
    drift=None,
):
    """Write a volumetric_error bundle. Hidden: ``squareness`` {EC0Y, EB0Z, EA0Z: µrad}, ``scale``
    {EXX/EYY/EZZ: µm/m}, ``thermal`` (axis, amplitude [mm], τ [s]), ``drift`` (axis, rate [mm/s]: a
    drift linear in time), ``tilt`` (a, b) [µrad],
    ``backlash`` (axis, reversal [µm]), ``cyclic`` (axis, amplitude [mm], period [mm], phase [deg]: that
    axis' error A·sin(2π·pos/period + phase)), ``frame`` (rotation ω [µrad] (3,), translation T [mm] (3,):
    the data in a measuring frame, e + ω × p + T); noise [mm]. Experiments use the tool lengths
    ``lengths``; each measures the serpentine ``grid`` (``order`` "serpentine", X fastest) or its points
    in random order ("random", each with a random approach direction), ``seconds_per_point`` apart."""
    from netshape.machine import machine_from_dict, tip_error

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    exps = []
    t_next = 0.0
    for i in range(experiments):
        L = lengths[i % len(lengths)]
        doc = {
            "tool_chain": ["Z"],
            "workpiece_chain": ["Y", "X"],
            "tool": {"length_mm": L},
            "squareness": {},
            "spindle": {},
            "axes": {"X": {"polynomials": {}}, "Y": {"polynomials": {}}, "Z": {"polynomials": {}}},
        }
        for k, v in VOL_MODEL.items():
            doc["axes"][k[2]]["polynomials"][k + ("_mm" if k[1] in "XYZ" else "_rad")] = list(v)
        for k, v in (squareness or {}).items():
            doc["squareness"][k + "_rad"] = v * 1e-6
        for k, v in (scale or {}).items():
            p = doc["axes"][k[2]]["polynomials"].setdefault(k + "_mm", [0.0, 0.0])
            p[1] = p[1] + v * 1e-6
        if tilt is not None:
            doc["spindle"] = {"tilt_a_rad": tilt[0] * 1e-6, "tilt_b_rad": tilt[1] * 1e-6}
        m = machine_from_dict(doc)
        pts, dirs = _grid_path(*grid)
        if order == "random":
            pts, dirs = pts[rng.permutation(len(pts))], rng.choice([-1.0, 1.0], len(pts))
        t = t_next + seconds_per_point * np.arange(len(pts))
        t_next = t[-1] + seconds_per_point
        e = np.array(tip_error(m, pts))
        if cyclic is not None:
            a = "XYZ".index(cyclic[0])
            e[:, a] += cyclic[1] * np.sin(2 * np.pi * pts[:, a] / cyclic[2] + math.radians(cyclic[3]))
        if frame is not None:
            e += np.cross(np.asarray(frame[0], float) * 1e-6, pts) + np.asarray(frame[1], float)
        if thermal is not None:
            e[:, "XYZ".index(thermal[0])] += thermal[1] * (1 - np.exp(-t / thermal[2]))
        if drift is not None:
            e[:, "XYZ".index(drift[0])] += drift[1] * t
        if backlash is not None:
            e[:, "XYZ".index(backlash[0])] += 0.5 * backlash[1] * 1e-3 * dirs
        e += rng.normal(0, noise, e.shape)
        name = f"v{i + 1}.csv"
        write_csv(
            folder / name,
            ["x_mm", "y_mm", "z_mm", "ex_mm", "ey_mm", "ez_mm", "t_s", "direction"],
            np.column_stack([pts, e, t, dirs]),
        )
        exps.append({"file": name, "tool_length_mm": L})
    write_manifest(folder, "volumetric_error", {"machine": MACHINE, "model": VOL_MODEL}, exps)
    return folder


# --- wall error ----------------------------------------------------------------------------------

WALL_TOOL = {"diameter_mm": 6.0, "flutes": 3, "helix_deg": 30.0, "stick_out_mm": 30.0, "youngs_modulus_MPa": 600e3}
WALL_MODEL = {"coefficients": "Ktc=900,Krc=270,Kac=150,Kte=16,Kre=20,Kae=10", "inertia": "square", "load": "distributed"}
#: (mode, radial depth [mm], feed per tooth [mm]) of the 3 steady cuts of a wall bundle
WALL_CONDITIONS = [("down", 0.5, 0.15), ("down", 1.0, 0.2), ("up", 0.5, 0.25)]
WALL_AP = 4.0


def runout_reach(X, Z, *, R, flutes, kb, feed, runout):
    """How far [mm] beyond the nominal radius R the wall at (x, z) was cut with a runout (ρ [mm], λ [deg]):
    flute j cuts an exact circle of radius R + ρ·cos(λ − j·2π/N) at every pass, the passes placed by the
    flute angles (flute j at height z reaches the wall angle at θ = φ_w + k_β·z + j·2π/N + 2πm, the tool
    centre then at x = N·c·(θ − φ_w)/2π); the wall is the deepest of all circles. X, Z: same shape."""
    rho, lam, N = runout[0], math.radians(runout[1]), flutes
    reach = np.full(np.shape(X), -np.inf)
    for j in range(N):
        Rj = R + rho * math.cos(lam - 2 * math.pi * j / N)
        for mrev in range(int(np.min(X) / (N * feed)) - 3, int(np.max(X) / (N * feed)) + 3):
            xp = N * feed * (kb * Z + 2 * math.pi * j / N + 2 * math.pi * mrev) / (2 * math.pi)
            dd = np.minimum(np.abs(X - xp), Rj)
            reach = np.maximum(reach, np.sqrt(Rj**2 - dd**2) - R)
    return reach


def wall_bundle(folder, *, holder_stiffness=None, runout=None, noise=1e-3, seed=3, form="xz",
                length=2.0, dx=0.01, z_levels=(0.5, 1.5, 2.5, 3.5), conditions=WALL_CONDITIONS, tool=None):
    """Write a wall_error bundle of steady straight cuts. The model's wall error e₀(z) and the force at
    the generating instant come from netshape.deflection (the bundle's own model); hidden:
    ``holder_stiffness`` [N/µm] (the tool translates rigidly by F/k) and ``runout`` (ρ [mm], λ [deg]):
    flute j cuts an exact circle of radius R + ρ·cos(λ − j·2π/N) at every pass, the passes placed by
    the flute angles (flute j at height z reaches the wall angle at θ = φ_w + k_β·z + j·2π/N + 2πm,
    the tool centre then at x = N·c·(θ − φ_w)/2π), the wall the deepest of all circles. ``form``:
    "xz" (x_mm,z_mm,error_mm over ``z_levels``) or "x" (x_mm,error_mm at z = ap/2). Noise [mm];
    ``tool``: a [tool] table (default WALL_TOOL)."""
    from netshape import deflection as d

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    t = WALL_TOOL if tool is None else tool
    R, N = t["diameter_mm"] / 2, t["flutes"]
    kb = math.tan(math.radians(t["helix_deg"])) / R
    x = np.arange(0.0, length + 1e-9, dx)
    zs = np.asarray(z_levels if form == "xz" else [WALL_AP / 2], float)
    exps = []
    for i, (mode, ae, c) in enumerate(conditions):
        side = "left" if mode == "up" else "right"
        m = d.make_model(diameter=t["diameter_mm"], flutes=N, helix_deg=t["helix_deg"], stick_out=t["stick_out_mm"],
                         youngs_modulus=t["youngs_modulus_MPa"], feed_per_tooth=c, ap=WALL_AP, ae=ae, mode=mode,
                         coefficients=WALL_MODEL["coefficients"])
        w = d.wall_errors(m, d.DeflectionWorkspace(m), getattr(d.WallSide, side), zs)
        ny = 1.0 if side == "left" else -1.0
        X, Z = np.meshgrid(x, zs)
        E = np.repeat(np.asarray(w.error)[:, None], len(x), axis=1)
        if holder_stiffness is not None:
            E -= (np.asarray(w.force)[:, 1] * ny)[:, None] / (holder_stiffness * 1e3)
        if runout is not None:
            E -= runout_reach(X, Z, R=R, flutes=N, kb=kb, feed=c, runout=runout)
        E += rng.normal(0.0, noise, E.shape)
        name = f"wall{i + 1}.csv"
        if form == "xz":
            write_csv(folder / name, ["x_mm", "z_mm", "error_mm"], np.column_stack([X.ravel(), Z.ravel(), E.ravel()]))
        else:
            write_csv(folder / name, ["x_mm", "error_mm"], np.column_stack([x, E[0]]))
        exps.append({"file": name, "feed_per_tooth_mm": c, "axial_depth_mm": WALL_AP, "radial_depth_mm": ae,
                     "mode": mode, "spindle_rpm": 8000.0})
    write_manifest(folder, "wall_error", {"tool": t, "model": WALL_MODEL}, exps)
    return folder


# --- wall error along a program's contour ------------------------------------------------------

CONTOUR_TOOL_TOML = ('kind = "flat"\ndiameter_mm = 6.0\nflutes = 3\nhelix_deg = 30.0\nflute_length_mm = 20.0\n'
                     'stick_out_mm = 30.0\nyoungs_modulus_MPa = 600000.0\n')
#: a block of stock below Y = 0, 4 mm deep under the cut at Z = −4
CONTOUR_STOCK_TOML = "min_mm = [0.0, -10.0, -8.0]\nmax_mm = [40.0, 0.0, 0.0]\nspacing_mm = 0.1\n"
CONTOUR_RPM = 8000.0
#: (program, feed per tooth [mm]) of the contour experiments: a straight down-milling cut along +X
#: (ae 1 mm, right wall at Y = −1) and an up-milling cut back along −X (ae 0.5 mm, left wall at Y = −0.5)
CONTOUR_CUTS = [
    ("G21 G90 G17\nS8000 M3\nG0 X-5 Y2 Z5\nG1 Z-4 F600\nG1 X30 Y2 F4800\nG0 Z10\nM30\n", 0.2),
    ("G21 G90 G17\nS8000 M3\nG0 X35 Y2.5 Z5\nG1 Z-4 F600\nG1 X5 Y2.5 F3600\nG0 Z10\nM30\n", 0.15),
]


def wall_contour_bundle(folder, *, holder_stiffness=None, runout=None, noise=1e-3, seed=5, form="xz",
                        s_range=(12.0, 16.0), ds=0.01, z_levels=(0.4, 1.2, 2.0, 2.8, 3.6)):
    """Write a wall_error bundle of contour experiments (program, tool.toml, stock.toml as
    ``netshape deflection predict`` takes them; CSV x_mm along the contour from its start). The base
    wall error and the force at the generating instant are netshape.deflection.predict_path's, read at
    the measured heights (on its profile levels) and linearly between its points along the contour;
    hidden: ``holder_stiffness`` [N/µm] (rigid translation F·n/k) and ``runout`` (ρ [mm], λ [deg]) as
    exact circles of radius R + ρ·cos(λ − j·2π/N) placed by the flute angles along the straight cut.
    ``form``: "xz" (x_mm,z_mm,error_mm over ``z_levels``) or "x" (x_mm,error_mm at the middle of
    the 4 mm cut, z = 2)."""
    import netshape as ns
    from netshape import deflection as d

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "tool.toml").write_text(CONTOUR_TOOL_TOML)
    (folder / "stock.toml").write_text(CONTOUR_STOCK_TOML)
    rng = np.random.default_rng(seed)
    cutter = ns.cutter.load_cutter(folder / "tool.toml")
    stock = d.load_stock(folder / "stock.toml")
    R, N = 3.0, 3
    kb = math.tan(math.radians(30.0)) / R
    s_meas = np.arange(s_range[0], s_range[1] + 1e-9, ds)
    zs = np.asarray(z_levels if form == "xz" else [2.0], float)
    exps = []
    for i, (text, c) in enumerate(CONTOUR_CUTS):
        name = f"contour{i + 1}"
        (folder / f"{name}.ngc").write_text(text)
        prog = ns.toolpath.read_gcode(folder / f"{name}.ngc")
        setup = d.setup_path(prog, cutter, stock, coefficients=WALL_MODEL["coefficients"], rpm=CONTOUR_RPM,
                             spacing=0.5, profile_levels=21)
        r = d.predict_path(setup)
        nominal = np.asarray(setup.nominal)
        s_pts = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(nominal[:, :2], axis=0).T))])
        depth = np.asarray(r.depth)
        assert np.allclose(depth[(s_pts > 10) & (s_pts < 18)], 4.0)
        profile = np.asarray(r.profile)
        fn = np.sum(np.asarray(r.force) * np.asarray(d.wall_normals(nominal, setup.side)), axis=1)
        S, Z = np.meshgrid(s_meas, zs)
        levels = np.rint(Z / 4.0 * 20).astype(int)  # the measured heights are profile levels z_k = 0.2·k
        E = np.empty(S.shape)
        for row in range(len(zs)):
            E[row] = np.interp(s_meas, s_pts, profile[:, levels[row, 0]])
        if holder_stiffness is not None:
            E -= np.interp(S, s_pts, fn) / (holder_stiffness * 1e3)
        if runout is not None:
            E -= runout_reach(S, Z, R=R, flutes=N, kb=kb, feed=c, runout=runout)
        E += rng.normal(0.0, noise, E.shape)
        if form == "xz":
            write_csv(folder / f"{name}.csv", ["x_mm", "z_mm", "error_mm"],
                      np.column_stack([S.ravel(), Z.ravel(), E.ravel()]))
        else:
            write_csv(folder / f"{name}.csv", ["x_mm", "error_mm"], np.column_stack([s_meas, E[0]]))
        exps.append({"file": f"{name}.csv", "program": f"{name}.ngc", "tool": "tool.toml", "stock": "stock.toml",
                     "spindle_rpm": CONTOUR_RPM, "spacing_mm": 0.5})
    write_manifest(folder, "wall_error", {"model": WALL_MODEL}, exps)
    return folder


# --- structured residuals (issue 37): a big grid, random or ordered measuring, extra errors -------


def structured_volumetric_bundle(
    folder,
    *,
    extra=None,
    noise=1e-3,
    seed=0,
    order="random",
    grid=(57, 7, 3),
    seconds_per_point=6.0,
    repeats=0,
    stated=None,
    squareness=None,
    thermal=None,
):
    """One experiment on a ``grid`` over x ∈ [−200, 200], y ∈ [−150, 150], z ∈ [−200, 0] mm, measured in
    ``order`` ("random", "x": X fastest, then Y, Z, "y": Y fastest, or "x-slowest": Z fastest, X
    slowest, so x grows with time), tool length 100 mm, the
    known model VOL_MODEL plus: ``extra`` a list of
    ("periodic", component, covariate, amplitude [mm], period) | ("step", component, covariate, height,
    at) | ("trend", component, covariate, slope [mm per unit]), covariates x, y, z [mm] or t [s];
    ``squareness`` {EC0Y…: µrad}; ``thermal`` (axis, amplitude, τ). ``repeats``: that many more
    passes over every point (ISO 230-2 style, same order, both approach directions alternate by pass).
    ``stated``: write [noise] sigma_mm. Noise Gaussian σ = ``noise`` [mm]."""
    from netshape.machine import machine_from_dict, tip_error

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    nx, ny, nz = grid
    X, Y, Z = np.meshgrid(np.linspace(-200, 200, nx), np.linspace(-150, 150, ny), np.linspace(-200, 0, nz),
                          indexing="ij")
    if order == "y":
        pts = np.column_stack([a.transpose(2, 0, 1).ravel() for a in (X, Y, Z)])
    elif order == "x-slowest":  # X steps once per line: position along x grows with time
        pts = np.column_stack([a.ravel() for a in (X, Y, Z)])
    else:
        pts = np.column_stack([a.transpose(2, 1, 0).ravel() for a in (X, Y, Z)])
    if order == "random":
        pts = pts[rng.permutation(len(pts))]
    dirs = np.ones(len(pts))
    if repeats:
        pts = np.concatenate([pts] * (repeats + 1))
        dirs = np.concatenate([np.full(len(dirs), 1.0 if k % 2 == 0 else -1.0) for k in range(repeats + 1)])
    t = seconds_per_point * np.arange(len(pts))
    doc = {"tool_chain": ["Z"], "workpiece_chain": ["Y", "X"], "tool": {"length_mm": 100.0},
           "squareness": {k + "_rad": v * 1e-6 for k, v in (squareness or {}).items()}, "spindle": {},
           "axes": {"X": {"polynomials": {}}, "Y": {"polynomials": {}}, "Z": {"polynomials": {}}}}
    for k, v in VOL_MODEL.items():
        doc["axes"][k[2]]["polynomials"][k + ("_mm" if k[1] in "XYZ" else "_rad")] = list(v)
    e = np.array(tip_error(machine_from_dict(doc), pts))
    cov = {"x": pts[:, 0], "y": pts[:, 1], "z": pts[:, 2], "t": t}
    for term in extra or ():
        form, comp, c = term[:3]
        j = "xyz".index(comp[-1])
        v = cov[c]
        if form == "periodic":
            e[:, j] += term[3] * np.sin(2 * np.pi * v / term[4] + 0.7)
        elif form == "step":
            e[:, j] += term[3] * (v > term[4])
        elif form == "trend":
            e[:, j] += term[3] * (v - v.mean())
    if thermal is not None:
        e[:, "XYZ".index(thermal[0])] += thermal[1] * (1 - np.exp(-t / thermal[2]))
    e += rng.normal(0, noise, e.shape)
    write_csv(folder / "grid.csv", ["x_mm", "y_mm", "z_mm", "ex_mm", "ey_mm", "ez_mm", "t_s", "direction"],
              np.column_stack([pts, e, t, dirs]))
    tables = {"machine": MACHINE, "model": VOL_MODEL}
    if stated is not None:
        tables["noise"] = {"sigma_mm": stated}
    write_manifest(folder, "volumetric_error", tables, [{"file": "grid.csv", "tool_length_mm": 100.0}])
    return folder
