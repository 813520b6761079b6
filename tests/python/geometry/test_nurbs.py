"""NURBS evaluation, derivatives and normals against independent values.

Reference numbers marked "geomdl suite" are published in the NURBS-Python (geomdl) test suite,
github.com/orbingol/NURBS-Python, tests/test_surface.py and tests/test_curve.py (tolerance 1e-3 there,
as printed to 3–4 decimals)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape.geometry as g

# geomdl suite, tests/test_surface.py fixture `spline_surf` (6 × 6 bicubic, knots 0, .33, .66, 1)
SURF_CP = [
    [-25.0, -25.0, -10.0], [-25.0, -15.0, -5.0], [-25.0, -5.0, 0.0], [-25.0, 5.0, 0.0], [-25.0, 15.0, -5.0],
    [-25.0, 25.0, -10.0], [-15.0, -25.0, -8.0], [-15.0, -15.0, -4.0], [-15.0, -5.0, -4.0], [-15.0, 5.0, -4.0],
    [-15.0, 15.0, -4.0], [-15.0, 25.0, -8.0], [-5.0, -25.0, -5.0], [-5.0, -15.0, -3.0], [-5.0, -5.0, -8.0],
    [-5.0, 5.0, -8.0], [-5.0, 15.0, -3.0], [-5.0, 25.0, -5.0], [5.0, -25.0, -3.0], [5.0, -15.0, -2.0],
    [5.0, -5.0, -8.0], [5.0, 5.0, -8.0], [5.0, 15.0, -2.0], [5.0, 25.0, -3.0], [15.0, -25.0, -8.0],
    [15.0, -15.0, -4.0], [15.0, -5.0, -4.0], [15.0, 5.0, -4.0], [15.0, 15.0, -4.0], [15.0, 25.0, -8.0],
    [25.0, -25.0, -10.0], [25.0, -15.0, -5.0], [25.0, -5.0, 2.0], [25.0, 5.0, 2.0], [25.0, 15.0, -5.0],
    [25.0, 25.0, -10.0],
]
KV = [0.0, 0.0, 0.0, 0.0, 0.33, 0.66, 1.0, 1.0, 1.0, 1.0]


@pytest.fixture(scope="module")
def surf():
    return g.NurbsSurface(3, 3, np.array(KV), np.array(KV), np.array(SURF_CP))


@pytest.mark.parametrize(
    "uv, expected",
    [
        ((0.0, 0.0), (-25.0, -25.0, -10.0)),
        ((0.0, 0.2), (-25.0, -11.403, -3.385)),
        ((0.3, 0.4), (-7.006, -3.308, -6.265)),
        ((0.6, 0.6), (3.533, 3.533, -6.801)),
        ((1.0, 0.8), (25.0, 11.636, -2.751)),
        ((1.0, 1.0), (25.0, 25.0, -10.0)),
    ],
)
def test_surface_points_geomdl_suite(surf, uv, expected):
    """geomdl suite test_bspline_surface_eval / test_nurbs_surface_eval (3 decimals)."""
    assert np.allclose(surf.point(*uv), expected, atol=1e-3)


def test_surface_derivatives_geomdl_suite(surf):
    """geomdl suite test_nurbs_surface_deriv at (u, v) = (0, 0.25) and (0.95, 0.75); geomdl's
    derivatives[k][l] is ∂^{k+l}S/∂u^k∂v^l like ours."""
    d = surf.derivatives(0.0, 0.25, 1)
    assert np.allclose(d[0, 0], (-25.0, -9.0771, -2.3972), atol=1e-3)
    assert np.allclose(d[0, 1], (0.0, 43.6910, 17.5411), atol=1e-3)
    assert np.allclose(d[1, 0], (90.9090, 0.0, -15.0882), atol=1e-3)
    assert np.allclose(d[1, 1], 0.0)  # ours: total order ≤ 1 (geomdl fills l ≤ order per direction)
    assert np.allclose(surf.derivatives(0.0, 0.25, 2)[1, 1], (0.0, 0.0, -140.0367), atol=1e-3)
    d = surf.derivatives(0.95, 0.75, 2)
    expected = [
        [[20.8948, 9.3097, -2.4845], [0.0, 43.7672, -15.0153], [0.0, 100.1022, -74.1165]],
        [[76.2308, 0.0, 18.0372], [0.0, 0.0, -158.5462], [0.0, 0.0, -284.3037]],
        [[224.5342, 0.0, 93.3843], [0.0, 0.0, -542.6274], [0.0, 0.0, -318.8808]],
    ]
    for k in range(3):
        for l in range(3 - k):
            assert np.allclose(d[k, l], expected[k][l], atol=1e-3), (k, l)


def test_surface_insert_knot_keeps_point_geomdl_suite(surf):
    """geomdl suite test_bspline_surface_insert_knot_eval: S(0.3, 0.4) after inserting u=0.3 twice."""
    s2 = surf.insert_knot_u(0.3, 2).insert_knot_v(0.3, 2)
    assert s2.count_u == 8 and s2.count_v == 8
    assert np.allclose(s2.point(0.3, 0.4), (-7.006, -3.308, -6.265), atol=1e-3)
    assert list(s2.knots_v[4:7]) == [0.3, 0.3, 0.33]


def _curve3d(weights=None):
    cp = np.array([[5.0, 5.0, 0], [10.0, 10.0, 0], [20.0, 15.0, 0], [35.0, 15.0, 0], [45.0, 10.0, 0],
                   [50.0, 5.0, 0]])
    return g.NurbsCurve(3, np.array(KV), cp, None if weights is None else np.array(weights))


@pytest.mark.parametrize("u, expected", [(0.0, (5.0, 5.0)), (0.3, (18.617, 13.377)), (0.5, (27.645, 14.691)),
                                         (0.6, (32.143, 14.328)), (1.0, (50.0, 5.0))])
def test_bspline_curve_geomdl_suite(u, expected):
    """geomdl suite test_bspline_curve2d_eval (the 2-D curve embedded at z = 0)."""
    assert np.allclose(_curve3d().point(u)[:2], expected, atol=1e-3)


def test_rational_curve_derivatives_geomdl_suite():
    """geomdl suite test_nurbs_curve2d_deriv, weights (0.5, 1, 0.75, 1, 0.25, 1)."""
    c = _curve3d([0.5, 1.0, 0.75, 1.0, 0.25, 1.0])
    d = c.derivatives(0.5, 3)[:, :2]
    assert np.allclose(d, [(28.1775, 14.7858), (39.7272, 2.2562), (-116.9254, -49.7367), (125.5276, 196.8865)],
                       atol=1e-3)
    assert np.allclose(c.derivatives(0.2, 2)[:, :2], [(13.8181, 11.5103), (40.0602, 17.3878),
                                                      (104.4062, -29.3672)], atol=1e-3)


def test_unnormalised_knots_geomdl_suite():
    """geomdl suite test_bspline_curve2d_eval_kv_norm2: knots 0…3 used as they are."""
    cp = _curve3d().control_points
    c = g.NurbsCurve(3, np.array([0.0, 0, 0, 0, 1, 2, 3, 3, 3, 3]), cp)
    assert c.domain == (0.0, 3.0)
    assert np.allclose(c.point(1.5)[:2], (27.5, 14.687), atol=1e-3)
    assert np.allclose(c.point(2.0)[:2], (34.9997, 13.75), atol=1e-3)


def hemisphere_half_circle(radius=1.0):
    """Half circle (south pole → (R,0,0) → north pole, in the xz-plane) revolved by π about z."""
    prof = g.circular_arc([0, 0, 0], [0, 0, -1], [1, 0, 0], radius, 0.0, math.pi)
    return g.revolve(prof, [0, 0, 0], [0, 0, 1], math.pi)


def hemisphere_quarter_circle(radius=1.0):
    """The standard rational hemisphere: quarter circle (equator → north pole) revolved by 2π about z."""
    prof = g.circular_arc([0, 0, 0], [1, 0, 0], [0, 0, 1], radius, 0.0, math.pi / 2)
    return g.revolve(prof, [0, 0, 0], [0, 0, 1], 2 * math.pi)


def test_rational_hemisphere_mid_normal_and_poles():
    """Issue 4: the rational hemisphere has a defined normal at the poles and (0, −1, 0) mid-surface.

    Half circle revolved by π: S(0.5, 0.5) = (0, 1, 0), S_u = +z, S_v = −x there, so eq. 15 gives
    n = S_u × S_v = (0, −1, 0) (the inward normal of this parametrisation)."""
    s = hemisphere_half_circle()
    assert s.is_rational
    assert np.allclose(s.point(0.5, 0.5), (0, 1, 0), atol=1e-14)
    assert np.allclose(s.normal(0.5, 0.5), (0, -1, 0), atol=1e-14)
    # every point is on the unit sphere and the normal is radial (inward)
    uv = np.random.default_rng(1).random((500, 2))
    p, n = s.evaluate_with_normals(uv)
    assert np.allclose(np.linalg.norm(p, axis=1), 1.0, atol=1e-14)
    assert np.allclose(n, -p, atol=1e-12)
    # poles: S_v ≡ 0 along u = 0 and u = 1; the normal is the limit from inside, for every v
    for v in np.linspace(0, 1, 7):
        assert np.allclose(s.normal(0.0, v), (0, 0, 1), atol=1e-12)
        assert np.allclose(s.normal(1.0, v), (0, 0, -1), atol=1e-12)
        near = s.normal(1.0 - 1e-7, v)
        assert np.allclose(near, (0, 0, -1), atol=1e-6)
    # the vectorised path gives the same pole normals
    _, n = s.evaluate_with_normals(np.array([[0.0, 0.3], [1.0, 0.7]]))
    assert np.allclose(n, [(0, 0, 1), (0, 0, -1)], atol=1e-12)


def test_quarter_circle_hemisphere_pole_and_equator():
    s = hemisphere_quarter_circle(2.0)
    for v in (0.0, 0.25, 0.5, 0.9, 1.0):
        assert np.allclose(s.point(1.0, v), (0, 0, 2), atol=1e-14)
        assert np.allclose(s.normal(1.0, v), (0, 0, -1), atol=1e-12)  # inward, consistent with neighbours
    # v = 0.25 is azimuth 90°: equator point (0, 2, 0), inward normal (0, −1, 0)
    assert np.allclose(s.point(0.0, 0.25), (0, 2, 0), atol=1e-14)
    assert np.allclose(s.normal(0.0, 0.25), (0, -1, 0), atol=1e-12)
    grid_p, grid_n = s.evaluate_grid(np.linspace(0, 1, 11), np.linspace(0, 1, 13))
    assert np.allclose(grid_n, -grid_p / 2.0, atol=1e-12)


def test_cross_check_geomdl_random_surfaces():
    """Points and first/second derivatives agree with geomdl to 1e-12 on random rational surfaces."""
    rng = np.random.default_rng(42)
    for trial in range(6):
        p, q = 1 + trial % 3, 2 + trial % 2
        ours = g.random_surface(rng, p, q, p + 4, q + 3)
        gs = g.to_geomdl(ours)
        uv = rng.random((40, 2))
        pts = ours.evaluate(uv)
        ref = np.array(gs.evaluate_list([tuple(x) for x in uv]))
        assert np.abs(pts - ref).max() < 1e-12
        for u, v in uv[:8]:
            d = ours.derivatives(u, v, 2)
            dg = gs.derivatives(u, v, order=2)
            for k in range(3):
                for l in range(3 - k):
                    scale = max(1.0, np.abs(dg[k][l]).max())
                    assert np.abs(d[k, l] - dg[k][l]).max() < 1e-12 * scale * 10, (k, l)
        # geomdl's unit normal (operations.normal) agrees too, up to orientation convention
        from geomdl import operations

        for u, v in uv[:5]:
            ng = np.array(operations.normal(gs, (u, v), normalize=True)[1])
            assert np.abs(np.abs(ng @ ours.normal(u, v)) - 1.0) < 1e-12


def test_geomdl_and_dict_round_trip(tmp_path):
    s = hemisphere_quarter_circle(3.0)
    back = g.from_geomdl(g.to_geomdl(s))
    uv = np.random.default_rng(0).random((20, 2))
    assert np.abs(back.evaluate(uv) - s.evaluate(uv)).max() < 1e-13
    g.save_json(s, tmp_path / "s.json")
    g.save_toml(s, tmp_path / "s.toml")
    for loaded in (g.load_json(tmp_path / "s.json"), g.load_toml(tmp_path / "s.toml")):
        assert np.abs(loaded.evaluate(uv) - s.evaluate(uv)).max() < 1e-13
    c = g.circular_arc([0, 0, 0], [1, 0, 0], [0, 1, 0], 2.0, 0.0, 1.0)
    c2 = g.from_dict(g.to_dict(c))
    assert np.allclose(c2.point(0.4), c.point(0.4))
    with pytest.raises(ValueError, match="type"):
        g.from_dict({"type": "blob"})


def test_swap_uv_flips_normals(surf):
    t = surf.swap_uv()
    for u, v in [(0.2, 0.7), (0.5, 0.5), (0.9, 0.1)]:
        assert np.allclose(t.point(v, u), surf.point(u, v), atol=1e-13)
        assert np.allclose(t.normal(v, u), -surf.normal(u, v), atol=1e-12)


def test_grid_and_scattered_agree(surf):
    us, vs = np.linspace(0, 1, 17), np.linspace(0, 1, 9)
    gp, gn = surf.evaluate_grid(us, vs)
    uv = np.stack(np.meshgrid(us, vs, indexing="ij"), -1).reshape(-1, 2)
    sp, sn = surf.evaluate_with_normals(uv)
    assert np.abs(gp - sp).max() < 1e-13 and np.abs(gn - sn).max() < 1e-13
    assert np.abs(surf.evaluate_grid(us, vs, normals=False) - gp).max() == 0.0


def test_closest_point_and_iso_curves(surf):
    q = surf.point(0.41, 0.57) + 0.8 * surf.normal(0.41, 0.57)
    r = surf.closest_point(q)
    assert r.converged and abs(r.distance - 0.8) < 1e-9
    assert abs(r.u - 0.41) < 1e-8 and abs(r.v - 0.57) < 1e-8
    rng = np.random.default_rng(4)
    uv = rng.uniform(0.05, 0.95, (20, 2))
    pts, nrm = surf.evaluate_with_normals(uv)
    batch = surf.closest_points(pts + 0.5 * nrm)
    assert np.allclose(batch["distance"], 0.5, atol=1e-9)
    assert np.allclose(batch["uv"], uv, atol=1e-7)
    assert batch["converged"].all()
    single = surf.closest_point(pts[3] + 0.5 * nrm[3])
    assert np.allclose(batch["point"][3], single.point, atol=1e-12)
    c = surf.iso_curve_u(0.41)
    assert np.allclose(c.point(0.57), surf.point(0.41, 0.57), atol=1e-13)
    rc = c.closest_point(c.point(0.2) + [0, 0, 1e-3])
    assert rc.distance <= 1e-3 + 1e-12


def test_bad_input_is_named(surf):
    with pytest.raises(ValueError, match="knots_u"):
        g.NurbsSurface(3, 3, np.array([0, 0, 0, 0, 0.5, 0.3, 1, 1, 1, 1.0]), np.array(KV), np.array(SURF_CP))
    with pytest.raises(ValueError, match="control_points.rows"):
        g.NurbsSurface(3, 3, np.array(KV), np.array(KV), np.array(SURF_CP[:30]))
    w = np.ones(36)
    w[7] = 0.0
    with pytest.raises(ValueError, match=r"weights\[7\]"):
        g.NurbsSurface(3, 3, np.array(KV), np.array(KV), np.array(SURF_CP), w)
    with pytest.raises(ValueError, match="u = 1.5"):
        surf.point(1.5, 0.2)
    with pytest.raises(ValueError, match="v = nan"):
        surf.evaluate(np.array([[0.2, np.nan]]))
    # coincident control points are accepted (a collapsed edge), normals stay defined
    cp = np.array(SURF_CP)
    cp[:6] = cp[0]
    s = g.NurbsSurface(3, 3, np.array(KV), np.array(KV), cp)
    n = s.normal(0.0, 0.5)
    assert np.isfinite(n).all() and abs(np.linalg.norm(n) - 1) < 1e-12
    assert n @ s.normal(1e-6, 0.5) > 0.99


def test_high_degree_generic_path_matches_reference():
    """Degrees above the specialised kernels (≤ 5) take the generic loop: same answers."""
    rng = np.random.default_rng(8)
    ours = g.random_surface(rng, 6, 2, 9, 5)
    gs = g.to_geomdl(ours)
    uv = rng.random((30, 2))
    p, n = ours.evaluate_with_normals(uv)
    for k in range(len(uv)):
        assert np.allclose(p[k], ours.point(*uv[k]), atol=1e-13)
        assert np.allclose(n[k], ours.normal(*uv[k]), atol=1e-12)
    assert np.abs(p - np.array(gs.evaluate_list([tuple(x) for x in uv]))).max() < 1e-12


def test_random_surface_is_reproducible_and_checks_counts():
    """The same seed gives the same net; too few control points for the degree is refused by name."""
    a, b = g.random_surface(7, 2, 3, 5, 6), g.random_surface(np.random.default_rng(7), 2, 3, 5, 6)
    assert (a.count_u, a.count_v) == (5, 6)
    assert np.array_equal(a.control_points, b.control_points) and np.array_equal(a.weights, b.weights)
    assert not np.array_equal(a.control_points, g.random_surface(8, 2, 3, 5, 6).control_points)
    with pytest.raises(ValueError, match="count_v = 3"):
        g.random_surface(0, 3, 3, 5, 3)
