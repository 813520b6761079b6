"""Benchmark: 5-axis posture planning — CC points per second through C-space + MC-space + MB-spline + repair
on the default impeller passage, and assembly interference checks per second (C++ branch and bound on the
CGAL AABB tree) against a NumPy brute force (axis sampled every 0.1 mm, every triangle) in the same run.

    PYTHONPATH=python python bench/posture.py [--points 40] [--checks 2000] [--numpy-checks 20]

Times are CPU time of this process (time.process_time); the extension is single-threaded.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

try:
    from netshape import posture as npost
except ImportError:  # pragma: no cover
    npost = None


def numpy_collides(assembly, tri, tip, axis, clearance, h=0.1):
    """Reference: min over axis samples (every h mm) and all triangles of point–triangle distance − radius."""
    a = assembly
    parts = ((a.ball_radius, a.ball_radius, a.ball_radius), (a.ball_radius, a.shank_length, a.shank_radius),
             (a.shank_length + a.holder_radius, a.holder_length, a.holder_radius))
    A, B, C = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(B - A, C - A)
    for z0, z1, r in parts:
        zs = np.arange(z0, z1 + h, h) if z1 > z0 else np.array([z0])
        p = tip + zs[:, None] * axis
        # distance to each triangle's plane where the projection falls inside, else to its three edges
        d = _point_triangle(p, A, B, C, n)
        if d.min() - r < clearance:
            return True
    return False


def _seg(p, a, b):
    ab = b - a
    t = np.clip(np.einsum("pmk,mk->pm", p[:, None, :] - a, ab) / np.einsum("mk,mk->m", ab, ab), 0, 1)
    return np.linalg.norm(p[:, None, :] - (a + t[..., None] * ab), axis=-1)


def _point_triangle(p, A, B, C, n):
    nn = n / np.linalg.norm(n, axis=1)[:, None]
    d_plane = np.einsum("pmk,mk->pm", p[:, None, :] - A, nn)
    q = p[:, None, :] - d_plane[..., None] * nn
    inside = np.ones(d_plane.shape, bool)
    for a, b in ((A, B), (B, C), (C, A)):
        inside &= np.einsum("pmk,mk->pm", np.cross(b - a, q - a), nn) >= 0
    edges = np.minimum(np.minimum(_seg(p, A, B), _seg(p, B, C)), _seg(p, C, A))
    return np.where(inside, np.abs(d_plane), edges)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=40)
    ap.add_argument("--checks", type=int, default=2000)
    ap.add_argument("--numpy-checks", type=int, default=20)
    args = ap.parse_args(argv)
    imp = npost.make_impeller()
    cc, normals = imp.cc_path(args.points)
    v, f = imp.obstacles()
    asm = npost.default_assembly()
    print(f"load average {os.getloadavg()[0]:.1f}; obstacles {len(f)} triangles; {args.points} CC points")

    t = time.process_time()
    run = npost.plan_postures(cc, normals, v, f, asm, clearance=0.5)
    dt = time.process_time() - t
    s = run.summary()
    print(f"plan (C-space + MC + MB + repair): {args.points / dt:.1f} CC points/s "
          f"({run.result.checks} interference checks, {run.result.checks / args.points:.0f} per point)")
    print(f"  collisions raw/mc/final {s['collisions']}, repaired {s['repaired']}, "
          f"max change deg/mm {s['max_posture_change_deg_per_mm']}")

    rng = np.random.default_rng(0)
    idx = rng.integers(0, args.points, args.checks)
    th = rng.uniform(0, np.radians(60), args.checks)
    ph = rng.uniform(-np.pi, np.pi, args.checks)
    axes = np.empty((args.checks, 3))
    tips = np.empty((args.checks, 3))
    for k, (i, a, b) in enumerate(zip(idx, th, ph)):
        fr = run.result.cspaces[i].frame
        axes[k] = fr.axis(a, b)
        tips[k] = cc[i] + asm.ball_radius * normals[i] - asm.ball_radius * axes[k]
    from netshape.geometry import TriangleMesh

    chk = npost.InterferenceChecker(TriangleMesh(v, f), asm, 0.5)
    t = time.process_time()
    flags = chk.collides(tips, axes)
    rate_cpp = args.checks / (time.process_time() - t)
    tri = v[f]
    m = args.numpy_checks
    t = time.process_time()
    ref = [numpy_collides(asm, tri, tips[k], axes[k], 0.5) for k in range(m)]
    rate_np = m / (time.process_time() - t)
    agree = int(np.sum(np.asarray(ref) == flags[:m]))
    print(f"interference checks: C++ {rate_cpp:.0f}/s, NumPy brute force {rate_np:.1f}/s, "
          f"ratio {rate_cpp / rate_np:.0f}x; agreement {agree}/{m}")


if __name__ == "__main__":
    main()
