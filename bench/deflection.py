"""Wall-error prediction and deflection compensation throughput (path points per second, each
scheme) of netshape's C++ core against a plain NumPy implementation of the same model, in one run.

Case: the straight cut across arc-preshaped stock of examples/deflection_seeds000.py (Cho & Suh
1993 §5: D 25 mm, 4 flutes, 60°, stick-out 250 mm, A 2.5 mm, f 0.0127 mm), 0.5 mm point spacing.

The NumPy reference evaluates the same path model: per point the engagement scan (720 angles,
material = the pre-path Z-map's pillars via ZMap.is_material_points minus the discs swept along the
earlier points, largest gap removed, edges bisected 40 times), the element forces of every disk and flute vectorised in NumPy with the same smooth edge weights, the
distributed cantilever influence, the wall error at bottom/middle/top; the integrated and Anderson
schemes iterate it in Python exactly as the C++ does. A rate is path points × path evaluations / CPU
time (time.process_time), best of --repeat runs.

    PYTHONPATH=python python bench/deflection.py [--repeat 2]
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


def _example():
    spec = importlib.util.spec_from_file_location("ex", os.path.join(HERE, "..", "examples", "deflection_seeds000.py"))
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
    """Engaged window of the C++ scan: material of the pre-path Z-map minus the discs swept along the
    earlier points (within reach), an angular scan, the largest gap removed, the edges bisected."""
    yc = np.array([-xc[1], xc[0]])
    reach = 2 * R + 2.0
    if len(earlier):
        far = np.linalg.norm(earlier - tip[None, :2], axis=1) > reach
        k = len(earlier)
        # walk back until two consecutive points are out of reach (as the C++ does)
        stop = 0
        for j in range(k - 1, 0, -1):
            if far[j] and far[j - 1]:
                stop = j - 1
                break
        pts = earlier[stop:]
    else:
        pts = earlier

    def material(phi):
        q = tip[None, :2] + R * (np.sin(phi)[:, None] * xc[None] + np.cos(phi)[:, None] * yc[None])
        p3 = np.column_stack([q, np.full(len(q), tip[2] + 1e-6)])
        m = np.asarray(zmap.is_material_points(p3))
        if len(pts) == 1:
            m &= np.sum((q - pts[0]) ** 2, axis=1) >= R * R
        elif len(pts) > 1:
            m &= np.min(_seg_dist2(q, pts[:-1], pts[1:]), axis=1) >= R * R
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


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="deflection throughput vs NumPy")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
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
    t_c, r = best_of(lambda: d.predict_path(setup), args.repeat)
    t_n, e_np = best_of(lambda: numpy_path(setup, normals, np.zeros(n)), 1)
    diff = np.max(np.abs(np.asarray(r.error) - e_np))
    rows.append(("predict", n / t_c, n / t_n, 1, 1))
    for sc in ("one-d", "integrated", "sectional", "accelerated"):
        t_c, res = best_of(lambda: d.compensate_path(setup, scheme=sc), args.repeat)
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
    return 0


if __name__ == "__main__":
    sys.exit(main())
