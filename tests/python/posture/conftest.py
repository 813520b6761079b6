"""Exact, independent solid–triangle test for the posture tests: the assembly (ball + frustums with flat ends,
radii grown by `inflate`) against triangles, in NumPy, by minimising a convex function over the triangle — not
the planner's GJK bounds.

For a frustum z ∈ [z0, z1], radius r(z) (linear), a point x with z = (x − tip)·a, ρ = |(x − tip) − z a| is inside
iff z0 ≤ z ≤ z1 and h(x) = ρ − r(z) ≤ 0. ρ is convex in x and r affine, so h is convex on the polygon
triangle ∩ slab; its minimum lies at the point where the axis pierces the triangle's plane (the only interior
stationary point of |y| − g·y) or on the polygon's boundary: the edges clipped to the slab (closed-form minimum
of √(quadratic) − linear) and the chords cut by the end planes (point–segment distance). The ball is the
point–triangle distance (Ericson, Real-Time Collision Detection §5.1.5)."""

from __future__ import annotations

import numpy as np
import pytest


def _dot(u, v):
    return np.einsum("ij,ij->i", u, v)


def closest_on_triangles(p, a, b, c):
    """Closest points (n, 3) on triangles (a, b, c) (n, 3 each) to points p (n, 3), pairwise (Ericson §5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    bp, cp = p - b, p - c
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        den = va + vb + vc
        q = a + ab * (vb / den)[:, None] + ac * (vc / den)[:, None]
        m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        q = np.where(m[:, None], a + ab * (d1 / (d1 - d3))[:, None], q)
        m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        q = np.where(m[:, None], a + ac * (d2 / (d2 - d6))[:, None], q)
        m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
        q = np.where(m[:, None], b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))[:, None], q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, q)
    q = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, q)
    return q


def _segment_point_distance(x0, x1, p):
    d = x1 - x0
    den = _dot(d, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.clip(np.where(den > 0, _dot(p - x0, d) / den, 0.0), 0.0, 1.0)
    return np.linalg.norm(p - x0 - t[:, None] * d, axis=1)


def frustum_hits(tip, ax, tri, z0, z1, r0, r1):
    """(n,) bool: triangle k (tri (n, 3, 3)) meets the frustum z ∈ [z0, z1], radius r0 → r1 on axis tip + z·ax."""
    beta = (r1 - r0) / (z1 - z0)

    def radius(z):
        return r0 + beta * (z - z0)

    V = tri - tip[:, None, :]
    zv = np.einsum("nvk,nk->nv", V, ax)
    pv = V - zv[..., None] * ax[:, None, :]
    best = np.full(len(tip), np.inf)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        zu, dz = zv[:, i], zv[:, j] - zv[:, i]
        P, D = pv[:, i], pv[:, j] - pv[:, i]
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (z0 - zu) / dz, (z1 - zu) / dz
        flat = dz == 0
        lo = np.where(flat, np.where((zu >= z0) & (zu <= z1), 0.0, np.inf), np.maximum(np.minimum(ta, tb), 0.0))
        hi = np.where(flat, np.where((zu >= z0) & (zu <= z1), 1.0, -np.inf), np.minimum(np.maximum(ta, tb), 1.0))
        ok = lo <= hi
        lo, hi = np.where(ok, lo, 0.0), np.where(ok, hi, 0.0)
        a2, b, c = _dot(D, D), _dot(P, D), _dot(P, P)
        k1 = beta * dz
        with np.errstate(divide="ignore", invalid="ignore"):
            e = np.maximum(c - b * b / a2, 0.0)
            s = np.sign(k1) * np.abs(k1) * np.sqrt(e / (a2 * (a2 - k1 * k1)))
            ts = np.where((a2 > k1 * k1) & (a2 > 0), s - b / a2, lo)
        ts = np.clip(np.nan_to_num(ts, nan=0.0), lo, hi)
        for t in (lo, hi, ts):
            h = np.linalg.norm(P + t[:, None] * D, axis=1) - radius(zu + t * dz)
            best = np.minimum(best, np.where(ok, h, np.inf))
    for zc in (z0, z1):  # chords of the triangle in the end planes
        pts, valid = [], []
        for i, j in ((0, 1), (1, 2), (2, 0)):
            dz = zv[:, j] - zv[:, i]
            with np.errstate(divide="ignore", invalid="ignore"):
                t = (zc - zv[:, i]) / dz
            ok = (dz != 0) & (t >= 0) & (t <= 1)
            valid.append(ok)
            pts.append(V[:, i] + np.where(ok, t, 0.0)[:, None] * (V[:, j] - V[:, i]))
        centre = zc * ax
        for i, j in ((0, 1), (1, 2), (0, 2)):
            h = _segment_point_distance(pts[i], pts[j], centre) - radius(zc)
            best = np.minimum(best, np.where(valid[i] & valid[j], h, np.inf))
    n = np.cross(V[:, 1] - V[:, 0], V[:, 2] - V[:, 0])
    den = _dot(ax, n)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = _dot(V[:, 0], n) / den
    X = s[:, None] * ax
    inside = (den != 0) & (s >= z0) & (s <= z1)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        inside &= _dot(np.cross(V[:, j] - V[:, i], X - V[:, i]), n) >= 0
    return (best <= 0) | inside


def _near(tree, cen, rad, tips, axes, z0, z1, reach):
    """Candidate (pose, triangle) pairs: the triangle's bounding sphere (centroid cen, radius rad) comes within
    `reach` of the axis segment z ∈ [z0, z1] (every triangle touching a solid within `reach` of that segment is
    kept). A k-d tree of the centroids gives the pairs within the segment's bounding sphere first."""
    mid = tips + 0.5 * (z0 + z1) * axes
    lists = tree.query_ball_point(mid, np.hypot(0.5 * (z1 - z0), reach) + rad.max(), return_sorted=False)
    k = np.repeat(np.arange(len(tips)), [len(x) for x in lists])
    m = np.concatenate([np.asarray(x, dtype=np.int64) for x in lists]) if len(k) else np.zeros(0, np.int64)
    d = cen[m] - tips[k]
    z = _dot(d, axes[k])
    zc = np.clip(z, z0, z1)
    keep = _dot(d, d) - 2 * z * zc + zc * zc < (reach + rad[m]) ** 2
    return k[keep], m[keep]


def exact_hits(assembly, tri, tips, axes, inflate=0.0, grow_ends=False):
    """(P,) bool: the solid at pose k (tips, axes (P, 3)) meets a triangle of tri (m, 3, 3). The solid's radii
    (ball, shank, holder) are grown by `inflate` [mm], its frustums' ends too with grow_ends. Radii only: the
    grown solid lies inside solid ⊕ inflate (a hit means gap ≤ inflate); with the ends it holds solid ⊕ inflate
    (no hit means gap ≥ inflate)."""
    from scipy.spatial import cKDTree

    R = assembly.ball_radius
    cen = tri.mean(1)
    rad = np.linalg.norm(tri - cen[:, None, :], axis=2).max(1)
    tree = cKDTree(cen)
    k, m = _near(tree, cen, rad, tips, axes, R, R, R + inflate)
    c = tips[k] + R * axes[k]
    q = closest_on_triangles(c, tri[m, 0], tri[m, 1], tri[m, 2])
    hit = np.zeros(len(tips), bool)
    np.logical_or.at(hit, k, np.linalg.norm(q - c, axis=1) < R + inflate)
    for z0, z1, r0, r1 in np.asarray(assembly.sections):
        z0, z1 = (z0 - inflate, z1 + inflate) if grow_ends else (z0, z1)
        todo = np.flatnonzero(~hit)  # a pose already hit needs no more
        k, m = _near(tree, cen, rad, tips[todo], axes[todo], z0, z1, max(r0, r1) + inflate)
        k = todo[k]
        h = frustum_hits(tips[k], axes[k], tri[m], z0, z1, r0 + inflate, r1 + inflate)
        np.logical_or.at(hit, k, h)
    return hit


def box(lo, hi):
    """Vertices (8, 3) and faces (12, 3) of the axis-aligned box [lo, hi] [mm]."""
    x = np.array([[lo[0], lo[1], lo[2]], [hi[0], lo[1], lo[2]], [hi[0], hi[1], lo[2]], [lo[0], hi[1], lo[2]],
                  [lo[0], lo[1], hi[2]], [hi[0], lo[1], hi[2]], [hi[0], hi[1], hi[2]], [lo[0], hi[1], hi[2]]])
    f = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5],
                  [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])
    return x, f


@pytest.fixture(scope="session")
def box_mesh():
    """box(lo, hi) → vertices (8, 3), faces (12, 3) of an axis-aligned box [mm]."""
    return box


@pytest.fixture(scope="session")
def exact():
    """The exact NumPy test as a namespace: exact.hits(assembly, tri, tips, axes, inflate)."""
    class _Exact:
        hits = staticmethod(exact_hits)
        closest = staticmethod(closest_on_triangles)
    return _Exact
