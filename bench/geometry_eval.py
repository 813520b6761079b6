"""Benchmark: NURBS surface points + unit normals per second, netshape vs geomdl in the same run, and
CGAL AABB-tree distance queries per second vs a NumPy brute force.

    PYTHONPATH=python python bench/geometry_eval.py [--points 1000000] [--geomdl-points 2000]

Times are CPU time of this process (time.process_time), so other jobs on a shared machine inflate
them less than wall-clock time would; the extension is single-threaded.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import netshape.geometry as g


def best_rate(fn, n, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t = time.process_time()
        fn()
        best = min(best, time.process_time() - t)
    return n / max(best, 1e-9)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--geomdl-points", type=int, default=2000)
    ap.add_argument("--queries", type=int, default=200_000)
    args = ap.parse_args(argv)

    from geomdl import operations

    rng = np.random.default_rng(0)
    s = g.random_surface(rng)
    gs = g.to_geomdl(s)
    n = args.points
    uv = rng.random((n, 2))
    side = int(round(np.sqrt(n)))
    us = np.linspace(0, 1, side)

    rate_scattered = best_rate(lambda: s.evaluate_with_normals(uv), n)
    rate_grid = best_rate(lambda: s.evaluate_grid(us, us), side * side)
    rate_points = best_rate(lambda: s.evaluate(uv), n)

    m = args.geomdl_points
    uvg = [tuple(x) for x in uv[:m]]

    def geomdl_points_normals():
        for u, v in uvg:
            gs.evaluate_single((u, v))
            operations.normal(gs, (u, v))

    rate_geomdl = best_rate(geomdl_points_normals, m, repeat=1)
    # agreement in the same run
    ours_p, ours_n = s.evaluate_with_normals(uv[:50])
    ref_p = np.array(gs.evaluate_list([tuple(x) for x in uv[:50]]))
    ref_n = np.array([operations.normal(gs, tuple(x))[1] for x in uv[:50]])
    err_p = np.abs(ours_p - ref_p).max()
    err_n = np.abs(np.abs(np.sum(ours_n * ref_n, axis=1)) - 1).max()

    print(f"surface: degree 3x3, 12x12 rational control net")
    print(f"  netshape scattered points+normals : {rate_scattered / 1e6:8.2f} M points/s")
    print(f"  netshape grid points+normals      : {rate_grid / 1e6:8.2f} M points/s")
    print(f"  netshape scattered points only    : {rate_points / 1e6:8.2f} M points/s")
    print(f"  geomdl points+normals             : {rate_geomdl / 1e3:8.2f} k points/s")
    print(f"  ratio scattered / geomdl          : {rate_scattered / rate_geomdl:8.0f} x")
    print(f"  ratio grid / geomdl               : {rate_grid / rate_geomdl:8.0f} x")
    print(f"  max |point - geomdl| = {err_p:.1e} mm, max normal misalignment = {err_n:.1e}")

    # AABB distance queries
    mesh = g.surface_mesh(s, 200, 200)
    q = rng.uniform(mesh.bbox_min - 1, mesh.bbox_max + 1, (args.queries, 3))
    rate_aabb = best_rate(lambda: mesh.distance(q), args.queries)
    V, F = mesh.vertices, mesh.faces
    tri = V[F]  # brute-force reference: distance to all triangle vertices (lower bound work, NumPy)
    sub = q[:200]

    def brute():
        for p in sub:
            np.min(np.linalg.norm(tri.reshape(-1, 3) - p, axis=1))

    rate_brute = best_rate(brute, len(sub), repeat=1)
    print(f"mesh: {mesh.face_count} triangles")
    print(f"  AABB distance queries             : {rate_aabb / 1e6:8.3f} M queries/s")
    print(f"  NumPy brute force (vertex dist.)  : {rate_brute / 1e3:8.3f} k queries/s")
    print(f"  ratio                             : {rate_aabb / rate_brute:8.0f} x")


if __name__ == "__main__":
    main()
