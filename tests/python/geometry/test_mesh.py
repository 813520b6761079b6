"""Triangle meshes (CGAL AABB tree) against brute force; STL round trips; 2-D contour offsets."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.geometry as g


def _point_triangle_distance(p, a, b, c):
    """Brute-force distance from p to triangle abc (Ericson, Real-Time Collision Detection §5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return np.linalg.norm(p - a)
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return np.linalg.norm(p - b)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return np.linalg.norm(p - (a + d1 / (d1 - d3) * ab))
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return np.linalg.norm(p - c)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return np.linalg.norm(p - (a + d2 / (d2 - d6) * ac))
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return np.linalg.norm(p - (b + w * (c - b)))
    denom = 1.0 / (va + vb + vc)
    v, w = vb * denom, vc * denom
    return np.linalg.norm(p - (a + ab * v + ac * w))


def _bumpy_mesh():
    n = 12
    x, y = np.meshgrid(np.linspace(0, 10, n), np.linspace(0, 8, n), indexing="ij")
    z = np.sin(x) * np.cos(y)
    prof = np.stack([x, y, z], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    a = (i * n + j).ravel()
    faces = np.concatenate([np.stack([a, a + n, a + n + 1], 1), np.stack([a, a + n + 1, a + 1], 1)])
    return prof, faces.astype(np.int64)


def test_distance_and_closest_point_vs_brute_force():
    v, f = _bumpy_mesh()
    mesh = g.TriangleMesh(v, f)
    q = np.random.default_rng(5).uniform([-2, -2, -3], [12, 10, 3], (60, 3))
    d = mesh.distance(q)
    brute = np.array([min(_point_triangle_distance(p, *v[t]) for t in f) for p in q])
    assert np.abs(d - brute).max() < 1e-12
    pts, dist, faces = mesh.closest_points(q)
    assert np.allclose(dist, brute, atol=1e-12)
    assert np.allclose(np.linalg.norm(pts - q, axis=1), dist, atol=1e-12)
    for k in range(len(q)):  # the reported face holds the closest point
        assert _point_triangle_distance(pts[k], *v[f[faces[k]]]) < 1e-9


def test_rays_and_segments():
    v, f = _bumpy_mesh()
    mesh = g.TriangleMesh(v, f)
    xy = np.random.default_rng(2).uniform([1, 1], [9, 7], (30, 2))
    origins = np.c_[xy, np.full(30, 5.0)]
    dirs = np.tile([0.0, 0.0, -2.0], (30, 1))
    t, pts, faces = mesh.ray_hits(origins, dirs)
    assert np.all(faces >= 0)
    assert np.allclose(pts[:, :2], xy, atol=1e-12)
    assert np.allclose(t, 5.0 - pts[:, 2], atol=1e-12)
    assert mesh.distance(pts).max() < 1e-12
    ts, _, fs = mesh.segment_hits(origins, origins + [0, 0, -10.0])
    assert np.allclose(ts, t / 10.0, atol=1e-12)
    tmiss, pmiss, fmiss = mesh.segment_hits(origins, origins + [0, 0, -1.0])  # stops above the surface
    assert np.all(np.isnan(tmiss)) and np.all(fmiss == -1)
    assert list(mesh.segments_intersect(origins[:2], origins[:2] + [0, 0, -10.0])) == [True, True]
    with pytest.raises(ValueError, match="directions"):
        mesh.ray_hits(origins[:1], np.zeros((1, 3)))


def test_stl_round_trip(tmp_path):
    v, f = _bumpy_mesh()
    mesh = g.TriangleMesh(v, f)
    for binary in (True, False):
        path = tmp_path / f"m{int(binary)}.stl"
        g.write_stl(path, mesh, binary=binary, name="bumpy")
        v2, f2, name = g.read_stl(path)
        assert name == "bumpy"
        assert f2.shape == f.shape and v2.shape == v.shape  # shared vertices merged again
        tol = 1e-6 if binary else 1e-15  # binary STL stores float32
        assert np.abs(np.sort(v2, axis=0) - np.sort(v, axis=0)).max() < tol * 10
        m2 = g.load_stl(path)
        assert m2.area == pytest.approx(mesh.area, rel=1e-6)


def test_stl_bad_input(tmp_path):
    p = tmp_path / "bad.stl"
    p.write_text("solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0\n")
    with pytest.raises(ValueError, match=r"bad.stl:5"):
        g.read_stl(p)
    p.write_bytes(b"\x00" * 90)
    with pytest.raises(ValueError, match="not an STL"):
        g.read_stl(p)
    with pytest.raises(ValueError, match="faces"):
        g.TriangleMesh(np.zeros((3, 3)), np.array([[0, 1, 5]]))


def test_surface_mesh_distance_matches_projection():
    prof = g.circular_arc([0, 0, 0], [1, 0, 0], [0, 0, 1], 10.0, 0.0, math.pi / 2)
    s = g.revolve(prof, [0, 0, 0], [0, 0, 1], 2 * math.pi)
    mesh = g.surface_mesh(s, 60, 120)
    q = np.array([[0.0, 0.0, 15.0], [3.0, 2.0, 12.0]])
    d = mesh.distance(q)
    exact = np.linalg.norm(q, axis=1) - 10.0
    assert np.allclose(d, exact, atol=0.05)  # faceting error of the 60 × 120 triangulation


# ---- 2-D contour offsets ----------------------------------------------------------------------------

SQUARE = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize("d", [0.5, 2.0, 3.7])
def test_outward_square_area_round_corners(d):
    """Offset of an a × a square by d with round corners: area (a + 2d)² − (4 − π) d²."""
    rings = g.offset_region(SQUARE, distance=d)
    assert len(rings) == 1 and not rings[0].hole
    a = 10.0
    assert rings[0].area == pytest.approx((a + 2 * d) ** 2 - (4 - math.pi) * d * d, abs=1e-5)
    arcs = rings[0].kind == 2
    assert arcs.sum() == 4  # one arc per corner, radius d
    r = np.linalg.norm(rings[0].start[arcs] - rings[0].center[arcs], axis=1)
    assert np.allclose(r, d, atol=1e-5)


def test_inward_offset_with_island_and_pocket_rings():
    island = np.array([[4.0, 4.0], [6.0, 4.0], [6.0, 6.0], [4.0, 6.0]])
    rings = g.offset_region(SQUARE, [island], distance=-1.0)
    outer = [r for r in rings if not r.hole]
    holes = [r for r in rings if r.hole]
    assert len(outer) == 1 and len(holes) == 1
    assert outer[0].area == pytest.approx(64.0, abs=1e-5)  # inset of a convex square: mitred = exact
    assert holes[0].area == pytest.approx(-(16.0 - (4 - math.pi)), abs=1e-5)  # island grown, round corners
    levels = g.pocket_rings(SQUARE, [island], tool_radius=1.0, step_over=0.8)
    assert 1 < len(levels) < 10
    areas = [sum(r.area for r in lv) for lv in levels]
    assert all(a1 > a2 for a1, a2 in zip(areas, areas[1:]))  # shrinking
    text = g.rings_gcode(levels, z=-1.0, feed=10.0)
    assert "G2" in text or "G3" in text
    assert "F600.0" in text
    tp = g.pocket_toolpath(SQUARE, [island], tool_radius=1.0, step_over=0.8, z=-1.0, feed=10.0)
    kinds = [int(b.kind) for b in tp.blocks]
    assert 2 in kinds and 1 in kinds
    cut = [b for b in tp.blocks if int(b.kind) == 2]
    assert all(abs(b.start[2] + 1.0) < 1e-12 for b in cut)
    # the same rings read back through the shared G-code writer and reader
    import netshape.toolpath as ntp

    again = ntp.parse_gcode(ntp.format_gcode(tp)) if hasattr(ntp, "parse_gcode") else None
    if again is not None:
        assert sum(int(b.kind) == 2 for b in again.blocks) == len(cut)


def test_concave_corner_gets_arc_when_growing():
    ell = np.array([[0, 0], [10, 0], [10, 4], [4, 4], [4, 10], [0, 10]], float)
    rings = g.offset_region(ell, distance=1.0)
    assert (rings[0].kind == 2).sum() == 5  # five convex corners round, the reflex one stays sharp


def test_self_intersecting_contour_is_refused():
    bow = np.array([[0, 0], [10, 10], [10, 0], [0, 10]], float)
    with pytest.raises(ValueError, match="self-intersecting"):
        g.offset_region(bow, distance=-1.0)
    with pytest.raises(ValueError, match="outer"):
        g.offset_region(np.array([[0, 0], [1, 1]], float), distance=1.0)
