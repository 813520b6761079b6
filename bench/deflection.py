"""Wall-error prediction and deflection compensation throughput (path points per second, each
scheme) of netshape's C++ core against a plain NumPy implementation of the same model, in one run.

Case: the straight cut across arc-preshaped stock of examples/deflection_cho_suh.py (Cho & Suh
1993 §5: D 25 mm, 4 flutes, 60°, stick-out 250 mm, A 2.5 mm, f 0.0127 mm), 0.5 mm point spacing.

The NumPy reference evaluates the same path model: per point the engagement scan (720 angles,
material = the pre-path Z-map's bilinear surface (ZMap.height_at_points) minus the discs swept along
every earlier move and the move into the point, largest gap removed, edges bisected 40 times), the element forces of every disk and flute vectorised in NumPy with the same smooth edge weights, the
distributed cantilever influence, the wall error at bottom/middle/top; the integrated and Anderson
schemes iterate it in Python exactly as the C++ does. A rate is path points × path evaluations / CPU
time (time.process_time), best of --repeat runs.

Pocket (issue 36): prediction rate along a pocket — clearing rings and a finish contour at one Z as one
run (tests/python/deflection/pocket_cases.py: 8 mm flat end mill, 4 flutes, 2 mm deep, stepover 3 mm,
corner R8, 0.5 mm point spacing, 0.1 mm Z-map) — grown to about 500, 2 000 and 8 000 path points by
scaling the pocket (half-widths 4:3, as many rings as fit), so the density of earlier moves near a point
stays the same and the cost per point should stay flat. Reported: path points/s with exact self-removal,
its cost per point relative to the 500-point pocket, and the Z-map sweep (exact_self_removal = False) for
reference.

    PYTHONPATH=python python bench/deflection.py [--repeat 2] [--only straight|pocket]
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import sys
import tempfile
import time

import numpy as np

import netshape as ns
from netshape import deflection as d

HERE = os.path.dirname(os.path.abspath(__file__))

# the pocket programs live with the tests (tests/python/deflection/pocket_cases.py)
sys.path.insert(0, os.path.join(HERE, "..", "tests", "python", "deflection"))
from pocket_cases import Pocket, pocket_gcode, stock_bounds  # noqa: E402

POCKET_POINTS = (500, 2000, 8000)


def _example():
    spec = importlib.util.spec_from_file_location("ex", os.path.join(HERE, "..", "examples", "deflection_cho_suh.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def numpy_point(model, phi_st, phi_ex, depth, side_angle):
    """Wall error deflections (δx_c, δy_c) at the 3 levels, NumPy, the same model as C++ wall_errors."""
    fm = model.force
    R, N, kb = fm.radius, fm.flutes, math.tan(fm.helix) / fm.radius
    n = max(1, int(math.ceil(depth / fm.disk_height - 1e-9)))
    dz = depth / n
    z = (np.arange(n) + 0.5) * dz
    L, EI = model.beam.length, model.beam.youngs_modulus * model.beam.inertia
    st = phi_st % (2 * math.pi)
    span = min(phi_ex - phi_st, 2 * math.pi)
    hw = 0.5 * kb * dz
    kt, kr = fm.kline_devor.kt, fm.kline_devor.kr
    out = np.empty((3, 2))
    for k, zl in enumerate((0.0, 0.5 * depth, depth)):
        th = side_angle + kb * zl
        phi = th + np.arange(N)[None, :] * 2 * math.pi / N - kb * z[:, None]
        u = np.mod(phi - st, 2 * math.pi)
        ov = np.zeros_like(u)
        for s in (-1, 0, 1):
            a, b = u - hw + s * 2 * math.pi, u + hw + s * 2 * math.pi
            ov += np.maximum(0.0, np.minimum(b, span) - np.maximum(a, 0.0))
        w = np.minimum(1.0, ov / (2 * hw)) * dz
        sa, ca = np.sin(phi), -np.cos(phi)
        ft = kt * np.maximum(fm.feed_per_tooth * sa, 0.0) * w
        fr = kr * ft
        fx = (-fr * sa + ft * ca).sum(1)
        fy = (fr * ca + ft * sa).sum(1)
        x, a = L - zl, L - z
        g = np.where(x <= a, x * x * (3 * a - x), a * a * (3 * x - a)) / (6 * EI)
        out[k] = (fx @ g, fy @ g)
    return out


def _seg_dist2(q, a, b):
    """Squared distances (m, k) from points q (m, 2) to segments a→b (k, 2)."""
    ab = b - a
    l2 = np.maximum(np.sum(ab * ab, axis=1), 1e-300)
    t = np.clip(((q[:, None, :] - a[None]) * ab[None]).sum(-1) / l2[None], 0.0, 1.0)
    c = a[None] + t[..., None] * ab[None]
    return np.sum((c - q[:, None, :]) ** 2, axis=-1)


def numpy_window(zmap, R, tip, xc, earlier, angles=720):
    """Engaged window of the C++ scan: material of the pre-path Z-map's bilinear surface minus the
    discs swept along every earlier move and along the move into the tip (up to, not including, the
    tip's own disc), an angular scan, the largest gap removed, the edges bisected."""
    yc = np.array([-xc[1], xc[0]])
    pts = earlier

    def material(phi):
        q = tip[None, :2] + R * (np.sin(phi)[:, None] * xc[None] + np.cos(phi)[:, None] * yc[None])
        h = np.asarray(zmap.height_at_points(q))
        z = tip[2] + 1e-6
        m = (z >= zmap.bottom) & (z < h)
        if len(pts) == 1:
            m &= np.sum((q - pts[0]) ** 2, axis=1) >= R * R
        elif len(pts) > 1:
            m &= np.min(_seg_dist2(q, pts[:-1], pts[1:]), axis=1) >= R * R
        if len(pts):
            r = R * (1.0 - 1e-9)
            m &= _seg_dist2(q, pts[-1:], tip[None, :2])[:, 0] >= r * r
        return m

    phi = 2 * math.pi * np.arange(angles) / angles
    inm = material(phi)
    if not inm.any():
        return None
    if inm.all():
        st, ex = 0.0, 2 * math.pi
    else:
        empty = ~inm
        starts = np.nonzero(empty & ~np.roll(empty, 1))[0]
        best, bs = 0, 0
        for k0 in starts:
            ln = 0
            while ln < angles and empty[(k0 + ln) % angles]:
                ln += 1
            if ln > best:
                best, bs = ln, k0
        first_in, last_in = (bs + best) % angles, (bs - 1) % angles
        step = 2 * math.pi / angles
        lo = np.array([first_in * step - step, last_in * step + step])
        hi = np.array([first_in * step, last_in * step])
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            m = material(mid)
            hi = np.where(m, mid, hi)
            lo = np.where(m, lo, mid)
        st, ex = hi
        while ex < st:
            ex += 2 * math.pi
    inwin = np.mod(phi - st, 2 * math.pi) <= ex - st + 1e-12
    q = tip[None, :2] + R * (np.sin(phi[inwin])[:, None] * xc[None] + np.cos(phi[inwin])[:, None] * yc[None])
    h = np.asarray(zmap.cell_height_points(q))
    depth = float(np.max(h - tip[2])) if len(h) else 0.0
    if depth <= 1e-9:
        return None
    span = ex - st
    st = st - 2 * math.pi if st > math.pi else st
    return st, st + span, depth


def numpy_path(setup, normals, offsets):
    """Errors (n, 3) along P = R + C n: the C++ path model (exact self removal, nominal-tangent frame)
    with the engagement scan and the deflection written in NumPy."""
    P = setup.nominal.copy()
    P[:, :2] += offsets[:, None] * normals
    n = len(P)
    err = np.empty((n, 3))
    ang = 0.0 if setup.side == d.WallSide.left else math.pi
    nom = setup.nominal
    R = setup.cutter.radius
    for i in range(n):
        a, b = max(i - 1, 0), min(i + 1, n - 1)
        t = nom[b, :2] - nom[a, :2]
        xc = t / np.hypot(t[0], t[1])
        yc = np.array([-xc[1], xc[0]])
        w = numpy_window(setup.stock, R, P[i], xc, P[:i, :2])
        if w is not None:
            dd = numpy_point(setup.model, w[0], w[1], min(w[2], setup.cutter.flute_length), ang)
            dv = dd[:, :1] * xc[None, :] + dd[:, 1:] * yc[None, :]
            err[i] = -offsets[i] - dv @ normals[i]
        else:
            err[i] = -offsets[i]
    return err


def numpy_scheme(setup, anderson, eps=5e-4, limit=50, m=5):
    n = len(setup.nominal)
    normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
    C = np.zeros(n)
    evals = 1
    e = numpy_path(setup, normals, C)[:, 1]
    dF, dG, f_old, g_old = [], [], None, None
    for _ in range(limit):
        worst = np.max(np.abs(e))
        if worst <= eps:
            return evals, worst
        f = e
        g = C + f
        nxt = g
        if anderson:
            if f_old is not None:
                dF.append(f - f_old)
                dG.append(g - g_old)
                dF, dG = dF[-m:], dG[-m:]
            f_old, g_old = f, g
            if dF:
                Fm, Gm = np.column_stack(dF), np.column_stack(dG)
                gamma = np.linalg.lstsq(Fm, f, rcond=None)[0]
                nxt = g - Gm @ gamma
        C = nxt
        e2 = numpy_path(setup, normals, C)[:, 1]
        evals += 1
        if anderson and not np.max(np.abs(e2)) <= 2 * worst:
            dF, dG, f_old = [], [], None
            C = g
            e2 = numpy_path(setup, normals, C)[:, 1]
            evals += 1
        e = e2
    return evals, float(np.max(np.abs(e)))


def best_of(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.process_time()
        out = fn()
        best = min(best, time.process_time() - t0)
    return best, out


def grown_pocket(points: int, spacing: float = 0.5, diameter: float = 8.0, stepover: float = 3.0):
    """The pocket (half-widths 20·k x 15·k mm, corner R8, as many rings at ``stepover`` as leave the
    innermost one narrower than the tool) whose run has about ``points`` path points: (Pocket, Toolpath)."""
    r = 0.5 * diameter

    def make(k):
        hy = 15.0 * k
        rings = max(0, math.ceil((hy - 2 * r) / stepover))
        while rings > 0 and hy - r - rings * stepover <= 1e-6:
            rings -= 1
        return Pocket(half_x=20.0 * k, half_y=hy, tool_diameter=diameter, stepover=stepover, rings=rings)

    def count(k):
        return len(d.contour_of(ns.toolpath.parse_gcode(pocket_gcode(make(k))), spacing)[0])

    lo, hi = 0.5, 8.0
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if count(mid) < points else (lo, mid)
    p = make(hi)
    return p, ns.toolpath.parse_gcode(pocket_gcode(p))


def pocket_table(repeat: int) -> None:
    cutter = ns.cutter.Cutter.flat_end(8.0, 4, math.radians(30.0))
    cutter.flute_length, cutter.stick_out, cutter.youngs_modulus = 20.0, 40.0, 600e3
    rows = []
    for target in POCKET_POINTS:
        p, prog = grown_pocket(target)
        lo, hi = stock_bounds(p)
        stock = ns.stock.ZMap(lo[0], hi[0], lo[1], hi[1], 0.1, hi[2], lo[2])
        setup = d.setup_path(prog, cutter, stock, coefficients="leekunhwee_flat_slot", rpm=8000, spacing=0.5,
                             side="right", profile_levels=0)
        n = len(setup.nominal)
        normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
        zero = np.zeros(n)
        swept_opt = d.PathOptions()
        swept_opt.side, swept_opt.profile_levels, swept_opt.exact_self_removal = setup.side, 0, False
        t_e, _ = best_of(lambda: d.path_wall_errors(setup.model, cutter, stock, setup.nominal, normals, zero,
                                                    setup.options), repeat)
        t_z, _ = best_of(lambda: d.path_wall_errors(setup.model, cutter, stock, setup.nominal, normals, zero,
                                                    swept_opt), repeat)
        rows.append((n, 2 * p.half_x, 2 * p.half_y, p.rings, n / t_e, n / t_z))
    base = rows[0][4]
    print(f"pocket, rings + finish in one run (D8, 4 flutes, 2 mm deep, stepover 3 mm, 0.5 mm points, "
          f"0.1 mm Z-map), load average {os.getloadavg()[0]:.1f}")
    print("| path points | pocket [mm] | rings | exact self-removal: points/s | cost per point ÷ 500-point case "
          "| Z-map sweep: points/s |")
    print("|---|---|---|---|---|---|")
    for n, w, h, rings, r_e, r_z in rows:
        print(f"| {n:,} | {w:.0f} x {h:.0f} | {rings} | {r_e:,.0f} | {base / r_e:.2f} | {r_z:,.0f} |")


def straight_table(repeat: int) -> None:
    ex = _example()
    with tempfile.TemporaryDirectory() as tmp:
        (lo, hi), rough, finish = ex.cases()["straight"]
        for name, text in (("tool.toml", ex.TOOL), ("rough.nc", rough), ("finish.nc", finish)):
            with open(os.path.join(tmp, name), "w") as fh:
                fh.write(text)
        with open(os.path.join(tmp, "stock.toml"), "w") as fh:
            fh.write(f"min_mm = {list(map(float, lo))}\nmax_mm = {list(map(float, hi))}\nspacing_mm = 0.1\n"
                     "[[pre_cut]]\nprogram = \"rough.nc\"\ntool = \"tool.toml\"\n")
        cutter = ns.cutter.load_cutter(os.path.join(tmp, "tool.toml"))
        stock = d.load_stock(os.path.join(tmp, "stock.toml"))
        prog = ns.toolpath.read_gcode(os.path.join(tmp, "finish.nc"))
    setup = d.setup_path(prog, cutter, stock, coefficients="cho_suh_example", rpm=600, spacing=0.5,
                         profile_levels=0)
    n = len(setup.nominal)
    normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
    print(f"straight cut across arc-preshaped stock: {n} path points, load average {os.getloadavg()[0]:.1f}")
    rows = []
    t_c, r = best_of(lambda: d.predict_path(setup), repeat)
    t_n, e_np = best_of(lambda: numpy_path(setup, normals, np.zeros(n)), 1)
    diff = np.max(np.abs(np.asarray(r.error) - e_np))
    rows.append(("predict", n / t_c, n / t_n, 1, 1))
    for sc in ("one-d", "integrated", "sectional", "accelerated"):
        t_c, res = best_of(lambda: d.compensate_path(setup, scheme=sc), repeat)
        pts = n * res.path_evaluations
        if sc in ("integrated", "accelerated"):
            t_n, (ev, _) = best_of(lambda: numpy_scheme(setup, sc == "accelerated"), 1)
            rows.append((sc, pts / t_c, n * ev / t_n, res.path_evaluations, ev))
        else:
            rows.append((sc, pts / t_c, float("nan"), res.path_evaluations, 0))
    print(f"max |C++ - NumPy| of the predicted errors: {diff * 1e3:.2e} um")
    print("| what | C++ path points/s | NumPy path points/s | ratio | path evaluations (C++ / NumPy) |")
    print("|---|---|---|---|---|")
    for name, a, b, ea, eb in rows:
        ratio = f"{a / b:.1f}x" if b == b else "—"
        nb = f"{b:,.0f}" if b == b else "—"
        print(f"| {name} | {a:,.0f} | {nb} | {ratio} | {ea} / {eb if eb else '—'} |")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="deflection throughput vs NumPy; pocket prediction rate by size")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--only", choices=("straight", "pocket"), default=None)
    args = ap.parse_args(argv)
    if args.only in (None, "straight"):
        straight_table(args.repeat)
    if args.only in (None, "pocket"):
        pocket_table(args.repeat)
    return 0


if __name__ == "__main__":
    sys.exit(main())
