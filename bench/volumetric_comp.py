"""Volumetric compensation throughput: compensated points per second of the C++ core
(netshape.compensation.compensate_points, one core) and its ratio to a NumPy reference
implementation of the same exact synthesis and fixed-point iteration, measured in the same run.

    PYTHONPATH=python python bench/volumetric_comp.py [--n 1000000]

Times are CPU times of this process (time.process_time), so other load on the machine inflates
them less than wall-clock would; both are printed.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

import netshape as ns

ROOT = Path(__file__).resolve().parents[1]
Kind = ns.machine.ErrorFunction.Kind


def _eval(f, q):
    if f.kind == Kind.zero:
        return np.zeros_like(q)
    if f.kind == Kind.polynomial:
        return np.polyval(np.asarray(f.coefficients)[::-1], q)
    x, v = np.asarray(f.positions), np.asarray(f.values)
    if f.out_of_range == ns.machine.OutOfRange.extrapolate:
        i = np.clip(np.searchsorted(x, q) - 1, 0, len(x) - 2)
        return v[i] + (q - x[i]) * (v[i + 1] - v[i]) / (x[i + 1] - x[i])
    return np.interp(q, x, v)  # clamp (error policy: points are inside)


def _rot(a, b, c):
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    r = np.empty(a.shape + (3, 3))
    r[..., 0, 0] = cb * cc
    r[..., 0, 1] = sa * sb * cc - ca * sc
    r[..., 0, 2] = ca * sb * cc + sa * sc
    r[..., 1, 0] = cb * sc
    r[..., 1, 1] = sa * sb * sc + ca * cc
    r[..., 1, 2] = ca * sb * sc - sa * cc
    r[..., 2, 0] = -sb
    r[..., 2, 1] = sa * cb
    r[..., 2, 2] = ca * cb
    return r


def numpy_tip_error(m, p):
    """Exact synthesis in NumPy (same conventions as the C++ core: docs/machine.md)."""
    u = [np.array([1.0, 0, 0]),
         np.array([-np.sin(m.ec0y), np.cos(m.ec0y), 0.0]),
         _rot(np.array(m.ea0z), np.array(0.0), np.array(0.0)) @ _rot(np.array(0.0), np.array(m.eb0z), np.array(0.0)) @ [0, 0, 1.0]]
    axes = m.axes
    err = []
    for k in range(3):
        q = p[:, k]
        e = [_eval(f, q) for f in axes[k].errors]
        err.append((np.column_stack(e[:3]), _rot(e[3], e[4], e[5])))
    tilt = _rot(np.array(m.spindle_tilt_a), np.array(0.0), np.array(0.0)) @ _rot(np.array(0.0), np.array(m.spindle_tilt_b), np.array(0.0))
    tip = np.asarray(m.spindle_nose) + m.tool_length * (tilt @ np.asarray(m.tool_direction))
    v = np.broadcast_to(tip, p.shape).copy()
    vn = np.broadcast_to(m.nominal_tip(), p.shape).copy()
    for k in reversed(list(m.tool_chain)):
        dlt, r = err[k]
        o = np.asarray(axes[k].origin)
        v = o + np.einsum("nij,nj->ni", r, v) + p[:, k:k + 1] * u[k] + dlt
        vn = o + vn + p[:, k:k + 1] * np.eye(3)[k]
    for k in m.workpiece_chain:
        dlt, r = err[k]
        o = np.asarray(axes[k].origin)
        v = np.einsum("nij,nj->ni", r, v - o + p[:, k:k + 1] * u[k] + dlt)
        vn = vn - o + p[:, k:k + 1] * np.eye(3)[k]
    return v - vn


def numpy_compensate(m, nominal, tol=1e-9, max_iter=50):
    p = nominal.copy()
    for _ in range(max_iter):
        r = p + numpy_tip_error(m, p) - nominal
        if np.linalg.norm(r, axis=1).max() <= tol:
            return p
        p -= r
    raise RuntimeError("NumPy reference did not converge")


def _time(f, *a):
    t0, w0 = time.process_time(), time.perf_counter()
    out = f(*a)
    return out, time.process_time() - t0, time.perf_counter() - w0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--n", type=int, default=1_000_000, help="points per case")
    rng = np.random.default_rng(0)
    ap.add_argument("--repeat", type=int, default=3, help="timings: best (least CPU time) of this many runs")
    a = ap.parse_args(argv)
    print(f"load average {os.getloadavg()[0]:.2f} (1 min)")
    print(f"{'machine':<26} {'points':<8} {'C++ M pts/s (cpu)':>18} {'(wall)':>8} {'NumPy M pts/s':>14} "
          f"{'ratio':>7} {'evals/pt':>9} {'max |C++ − NumPy| mm':>21} {'max residual mm':>16}")
    for name in ("hmc_yang_kweon.toml", "vmc.toml"):
        m = ns.machine.load_machine(ROOT / "examples" / "machines" / name)
        lo = np.array([ax.travel_min for ax in m.axes])
        hi = np.array([ax.travel_max for ax in m.axes])
        cases = {
            "random": rng.uniform(lo + 1, hi - 1, (a.n, 3)),
            # along a raster path: 0.05 mm steps (CL points of a finishing pass)
            "path": np.column_stack([lo[0] + 1 + (np.arange(a.n) * 0.05) % (hi[0] - lo[0] - 2),
                                     lo[1] + 1 + (np.arange(a.n) * 0.05 // (hi[0] - lo[0] - 2)) * 0.5 % (hi[1] - lo[1] - 2),
                                     np.full(a.n, 0.5 * (lo[2] + hi[2])) + 5 * np.sin(np.arange(a.n) * 1e-3)]),
        }
        for case, pts in cases.items():
            ns.compensation.compensate_points(m, pts[:1000])  # warm up
            best = None
            for _ in range(max(1, a.repeat)):
                run = _time(ns.compensation.compensate_points, m, pts)
                if best is None or run[1] < best[1]:
                    best = run
            cmd, cpu, wall = best
            evals = float(np.mean(ns.compensation.compensate_points_status(m, pts).iterations))
            nref = min(len(pts), 200_000)
            ref, rcpu, _ = min((_time(numpy_compensate, m, pts[:nref]) for _ in range(max(1, a.repeat))),
                               key=lambda run: run[1])
            res = np.linalg.norm(ns.machine.actual_points(m, cmd) - pts, axis=1).max()
            cpp_rate = len(pts) / cpu / 1e6
            np_rate = nref / rcpu / 1e6
            print(f"{m.name[:18] + ' ' + case:<26} {len(pts):<8d} {cpp_rate:>18.2f} {len(pts) / wall / 1e6:>8.2f} "
                  f"{np_rate:>14.3f} {cpp_rate / np_rate:>7.1f} {evals:>9.3f} {np.abs(cmd[:nref] - ref).max():>21.2e} {res:>16.2e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
