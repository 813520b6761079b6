"""The checked solids contain the real tool: ball, shank cylinder and a flat-faced holder (or a (z, r) holder
profile), checked against the exact NumPy solid–triangle test of conftest.py (not the planner's branch and
bound). Issue 38 item 1."""

from __future__ import annotations

import numpy as np
import pytest

from netshape import posture as npost
from netshape.geometry import TriangleMesh

POSES = 20_000  # bench/posture.py runs 1e5 (the exact test is the slow half)


def test_block_under_the_holder_face_collides(box_mesh):
    """Issue 38's reproduction: a 2 × 2 × 0.8 mm block between radius 6 and 8 mm, 0.2–1.0 mm from the face of
    the Ø20 holder (vertical axis, face at z = 35) must collide at clearance 0.5; its gap is 0.2 mm."""
    a = npost.default_assembly()
    face = a.shank_length
    v, f = box_mesh([6.0, -1.0, face - 1.0], [8.0, 1.0, face - 0.2])
    tip, axis = np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]])
    chk = npost.InterferenceChecker(TriangleMesh(v, f), a, 0.5)
    assert chk.collides(tip, axis)[0]
    assert chk.gap(tip[0], axis[0]) == pytest.approx(0.2, abs=2e-3)
    assert not npost.InterferenceChecker(TriangleMesh(v, f), a, 0.1).collides(tip, axis)[0]


def test_holder_profile_taper_is_checked(box_mesh):
    """A shrink-fit taper (r 5 → 10 mm over z 35 → 45): the block at radius 6–8 just below z = 35 is free of
    it (5 mm at the face) but one beside the taper at z 39–40 (r(z) = 7–7.5) is hit."""
    a = npost.default_assembly()
    a.holder_profile = np.array([[35.0, 5.0], [45.0, 10.0], [80.0, 10.0]])
    a.validate()
    tip, axis = np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]])
    v, f = box_mesh([6.0, -1.0, 34.0], [8.0, 1.0, 34.8])
    assert not npost.InterferenceChecker(TriangleMesh(v, f), a, 0.5).collides(tip, axis)[0]
    v, f = box_mesh([7.2, -1.0, 39.0], [9.0, 1.0, 40.0])
    chk = npost.InterferenceChecker(TriangleMesh(v, f), a, 0.0)
    assert chk.collides(tip, axis)[0]
    # gap of a block beside the taper: its nearest point is the corner (ρ, z) = (8, 37); distance to the cone
    # line ρ = 5 + (z − 35)/2 in the meridian plane
    v, f = box_mesh([8.0, -1.0, 36.0], [9.0, 1.0, 37.0])
    g = npost.InterferenceChecker(TriangleMesh(v, f), a, 0.0).gap(tip[0], axis[0])
    assert g == pytest.approx((8.0 - (5.0 + 0.5 * (37.0 - 35.0))) / np.hypot(1.0, 0.5), abs=2e-3)
    with pytest.raises(ValueError, match="holder_profile"):
        bad = npost.default_assembly()
        bad.holder_profile = np.array([[30.0, 5.0], [80.0, 10.0]])
        bad.validate()


def random_poses(n, seed=0):
    """n poses near the default impeller's blades: the ball on or above the passage floor anywhere across the
    passage, the axis tilted up to 75° in any direction."""
    imp = npost.make_impeller()
    rng = np.random.default_rng(seed)
    cc, normals = imp.cc_path(200)
    i = rng.integers(0, len(cc), n)
    side = np.cross(normals[i], np.gradient(cc, axis=0)[i])
    side /= np.linalg.norm(side, axis=1)[:, None]
    a = npost.default_assembly()
    centre = cc[i] + side * rng.uniform(-4, 4, n)[:, None] + normals[i] * (a.ball_radius + rng.uniform(0, 6, n))[:, None]
    th, ph = rng.uniform(0, np.radians(75), n), rng.uniform(-np.pi, np.pi, n)
    e1 = np.cross(normals[i], side)
    axes = (np.cos(th)[:, None] * normals[i] + np.sin(th)[:, None] * (np.cos(ph)[:, None] * e1
                                                                       + np.sin(ph)[:, None] * side))
    return imp, a, centre - a.ball_radius * axes, axes


@pytest.mark.parametrize("clearance", [0.0, 0.5])
def test_no_pose_reported_free_while_the_exact_solid_hits(clearance, exact):
    """Random poses near the impeller (half at each clearance; bench/posture.py runs 1e5): every pose reported free is free for the
    exact NumPy test (the solid with its radii grown by the clearance, which lies inside solid ⊕ clearance) —
    0 unsafe disagreements. The other way (reported colliding, the grown solid free) is the conservative
    margin; on a sample of 1000 colliding poses it stays under 2 %."""
    imp, a, tips, axes = random_poses(POSES // 2, seed=int(clearance * 10))
    v, f = imp.obstacles()
    tri = v[f]
    got = np.asarray(npost.InterferenceChecker(TriangleMesh(v, f), a, clearance).collides(tips, axes))
    assert 0.2 < got.mean() < 0.9, got.mean()  # near the mesh: both outcomes are common
    free = np.flatnonzero(~got)
    unsafe = free[exact.hits(a, tri, tips[free], axes[free], inflate=clearance)]
    assert len(unsafe) == 0, (len(unsafe), unsafe[:5])
    sample = np.random.default_rng(1).choice(np.flatnonzero(got), 1000, replace=False)
    assert 1 - exact.hits(a, tri, tips[sample], axes[sample], inflate=clearance).mean() < 0.02


def test_cheap_bounds_leave_few_gjk_runs_per_check():
    """Work, not time: the plane and capsule lower bounds skip most triangles before GJK. Planning the default
    impeller at 20 CC points takes ≈ 6.3 frustum–triangle GJK runs per interference check (15.5 with the
    bounding-sphere and plane bounds alone, at 200 points). The postures are the safety tests' business."""
    imp = npost.make_impeller()
    cc, normals = imp.cc_path(20)
    v, f = imp.obstacles()
    chk = npost.InterferenceChecker(TriangleMesh(v, f), npost.default_assembly(), 0.5)
    r = npost.plan(chk, cc, normals)
    assert r.final.collision_count() == 0
    assert chk.gjk_runs / r.checks < 9.0, chk.gjk_runs / r.checks
