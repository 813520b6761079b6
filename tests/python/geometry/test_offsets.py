"""Offset surfaces (S.-H. Yang & S.-H. Kweon, "Volumetric error compensation of a 3-axis horizontal
machining center in the post-processor", eq. 12; docs/references.md), CC→CL for flat, ball and bull-nose
cutters, raster paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.geometry as g


def dome(radius=30.0):
    """Convex spherical cap seen from +z (outward normals after flipping the revolve's inward ones)."""
    prof = g.circular_arc([0, 0, 0], [0, 0, 1], [1, 0, 0], radius, 0.0, math.radians(60))
    # profile from the pole down to 60° colatitude, revolved by 2π: u = colatitude, v = azimuth;
    # S_u × S_v points outward here
    return g.revolve(prof, [0, 0, 0], [0, 0, 1], 2 * math.pi)


def wavy():
    """A bicubic B-spline with gentle convex and concave regions."""
    n = 7
    x, y = np.meshgrid(np.linspace(0, 60, n), np.linspace(0, 50, n), indexing="ij")
    z = 4.0 * np.sin(x / 20.0) * np.cos(y / 25.0)
    cp = np.stack([x, y, z], -1).reshape(-1, 3)
    kv = np.r_[np.zeros(4), np.linspace(0, 1, n - 2)[1:-1], np.ones(4)]
    return g.NurbsSurface(3, 3, kv, kv, cp)


def test_offset_points_lie_at_distance_d():
    """O = Q + d n: the closest point of O on Q is Q itself, at distance |d| (eq. 12)."""
    s = wavy()
    rng = np.random.default_rng(3)
    uv = rng.uniform(0.1, 0.9, (25, 2))
    for d in (2.0, -1.5):
        off = g.offset_points(s, uv, d)
        for k in range(len(uv)):
            r = s.closest_point(off[k])
            assert abs(r.distance - abs(d)) < 1e-7
    grid = g.offset_grid(s, np.linspace(0, 1, 5), np.linspace(0, 1, 4), 1.0)
    p, n = s.evaluate_grid(np.linspace(0, 1, 5), np.linspace(0, 1, 4))
    assert np.allclose(grid, p + n)


def test_dome_normals_point_out():
    s = dome()
    p, n = s.evaluate_with_normals(np.array([[0.5, 0.3], [0.0, 0.5], [1.0, 0.9]]))
    assert np.allclose(n, p / 30.0, atol=1e-12)


AXES = [(0, 0, 1), (0.3, -0.2, 1.0), (1.0, 0.0, 1.0)]
CUTTERS = [("ball", 5.0, 5.0), ("flat", 4.0, 0.0), ("bull", 6.0, 1.5)]


@pytest.mark.parametrize("cutter", CUTTERS)
@pytest.mark.parametrize("axis", AXES)
def test_cl_touches_at_cc_and_nowhere_deeper(cutter, axis):
    """The cutter placed at CL touches the (convex) surface at CC and does not cut into it nearby:
    signed distance of surface samples to the cutter solid ≥ 0, = 0 at CC."""
    s = dome()
    a = np.array(axis, float) / np.linalg.norm(axis)
    rng = np.random.default_rng(7)
    us = np.linspace(0, 1, 80)
    vs = np.linspace(0, 1, 160)
    pts, _ = s.evaluate_grid(us, vs)
    checked = 0
    for _ in range(12):
        u, v = rng.uniform(0.05, 0.95), rng.uniform(0, 1)
        cc = s.point(u, v)
        n = s.normal(u, v)
        if n @ a < 0.05:  # the tool cannot reach from this axis
            continue
        cl = g.cc_to_cl(cutter, cc, n, a)[0]
        d_cc = g.cutter_signed_distance(cutter, cl, a, cc)[0]
        assert abs(d_cc) < 1e-9
        near = pts[np.linalg.norm(pts - cc, axis=1) < 3 * cutter[1]]
        sd = g.cutter_signed_distance(cutter, cl, a, near)
        assert sd.min() > -1e-9, (cutter, axis, sd.min())
        # and the contact is tight: a slightly lower tool would cut
        sd2 = g.cutter_signed_distance(cutter, cl - 0.01 * n, a, cc)
        assert sd2[0] < 0
        checked += 1
    assert checked >= 6


def test_ball_cl_formula():
    """Ball: tip = CC + R n − R a (the centre lies on the offset surface at d = R)."""
    s = wavy()
    uv = np.random.default_rng(0).random((50, 2))
    p, n = s.evaluate_with_normals(uv)
    cl = g.cc_to_cl(("ball", 3.0), p, n)
    assert np.allclose(cl, g.offset_points(s, uv, 3.0) - [0, 0, 3.0])


def test_cc_to_cl_refuses_back_facing_normal():
    with pytest.raises(ValueError, match="normal . axis"):
        g.cc_to_cl(("ball", 3.0), [[0, 0, 0]], [[0, 0, -1]])
    with pytest.raises(ValueError, match="cutter.kind"):
        g.cc_to_cl(("drill", 3.0), [[0, 0, 0]], [[0, 0, 1]])


def test_scallop_step():
    """Flat surface: step = 2 sqrt(h (2R − h)); on a convex surface the tool centres sit on a larger
    circle than the surface, so the step (on the surface) is smaller; concave allows a larger one."""
    R, h = 5.0, 0.01
    flat = g.scallop_step(R, h, 0.0)
    assert flat == pytest.approx(2 * math.sqrt(h * (2 * R - h)))
    assert g.scallop_step(R, h, 1 / 50.0) < flat < g.scallop_step(R, h, -1 / 50.0)
    # convex: check the defining geometry: cusp at radius ρ + h is R from both tool centres
    rho = 50.0
    theta = g.scallop_step(R, h, 1 / rho) / rho
    c1 = (rho + R) * np.array([1.0, 0.0])
    cusp = (rho + h) * np.array([math.cos(theta / 2), math.sin(theta / 2)])
    assert np.linalg.norm(cusp - c1) == pytest.approx(R, rel=1e-12)
    # concave (centre of curvature on the tool side): centres on ρ − R, cusp at ρ − h
    theta = g.scallop_step(R, h, -1 / rho) / rho
    c1 = (rho - R) * np.array([1.0, 0.0])
    cusp = (rho - h) * np.array([math.cos(theta / 2), math.sin(theta / 2)])
    assert np.linalg.norm(cusp - c1) == pytest.approx(R, rel=1e-12)


def test_raster_toolpath_and_gcode(tmp_path):
    s = wavy()
    path = g.raster_toolpath(s, ("ball", 3.0), scallop_height=0.05, chord_tolerance=0.01, feed=25.0)
    assert len(path) > 100
    feed_blocks = path.kind == 1
    assert np.all(path.feed[feed_blocks] == 25.0)
    # every CL point along the passes keeps the ball on the surface: distance of the ball centre to
    # the surface is the radius R (within the chord tolerance, the centre being on the offset surface)
    centres = path.end[feed_blocks][::7] + [0, 0, 3.0]
    dist = np.array([s.closest_point(c).distance for c in centres])
    assert np.all(np.abs(dist - 3.0) < 1e-6)
    text = path.to_gcode()
    assert "G1" in text and "F1500" in text  # 25 mm/s written as mm/min
    out = tmp_path / "raster.ngc"
    path.write_gcode(out)
    assert out.read_text() == text
    # the toolpath reader gives the same blocks back (end points exact, feeds in mm/s)
    import netshape.toolpath as ntp

    back = ntp.read_gcode(out)
    ends = np.array([b.end for b in back.blocks])
    assert len(back.blocks) >= len(path)
    assert np.abs(ends[-len(path):] - path.end).max() < 1e-9
    with pytest.raises(ValueError, match="step_over"):
        g.raster_toolpath(s, ("flat", 3.0))
