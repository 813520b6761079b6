"""The wall a program leaves is the envelope of the deflected tool's circles (issue 36 item 7): where a
sample's offset drops faster than the tool's curvature follows, the circle of its neighbour cuts deeper
there and that cut is the wall; material left counts wherever no circle removes it; circles of another
wall (a lead-in across a corner) do not enter.

Geometry only: samples on a drawing with their wall normals (towards the material) and their own
errors (+ material left) [mm], tool radius 3 mm."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netshape.deflection.walls import wall_envelope

R = 3.0


def _straight(n=41, step=0.05):
    x = step * np.arange(n)
    foot = np.c_[x, np.zeros(n)]
    normals = np.tile([0.0, -1.0], (n, 1))  # the wall at y = −R, material below
    return x, foot, normals


def test_a_neighbours_deeper_circle_is_the_wall():
    x, foot, normals = _straight()
    e = np.zeros(len(x))
    e[20] = -0.010   # 10 µm overcut at x = 1.0
    e[21] = +0.030   # the next sample 50 µm on: its own circle leaves 30 µm
    env = wall_envelope(foot, normals, e, R)
    sag = R - math.sqrt(R * R - 0.05 ** 2)  # the overcut circle's rise 50 µm from its deepest point
    assert env[21] == pytest.approx(-0.010 + sag, abs=1e-12)
    assert env[20] == pytest.approx(-0.010, abs=1e-12)
    assert env[19] == pytest.approx(-0.010 + sag, abs=1e-12)  # cut behind it as well
    assert np.all(env <= e + 1e-15)


def test_material_left_everywhere_still_counts():
    x, foot, normals = _straight()
    e = np.full(len(x), 0.020)
    e[10] = 0.035
    env = wall_envelope(foot, normals, e, R)
    np.testing.assert_allclose(np.delete(env, 10), 0.020, atol=1e-12)
    # the neighbours' circles, 50 µm on either side
    assert env[10] == pytest.approx(0.020 + R - math.sqrt(R * R - 0.05 ** 2), abs=1e-12)


def test_every_level_on_its_own_and_a_concave_arc_keeps_a_uniform_error():
    # tool centres on a circle of radius 5 about the origin, the wall outside at radius 8 (a corner arc)
    a = np.radians(np.arange(0.0, 91.0, 0.5))
    foot = 5.0 * np.c_[np.cos(a), np.sin(a)]
    normals = np.c_[np.cos(a), np.sin(a)]
    e = np.tile([0.004, -0.002, 0.011], (len(a), 1))
    np.testing.assert_allclose(wall_envelope(foot, normals, e, R), e, atol=1e-12)


def test_another_walls_circles_are_left_out():
    # a diagonal lead-in (45°, its wall normal 45° from the wall's) ends where the wall along +X starts;
    # 50 µm deep along its own normal, its circles would reach 35 µm past the wall's line if they counted
    x, foot, normals = _straight(11)
    k = np.arange(4, 0, -1)
    u = math.sqrt(0.5)
    foot = np.vstack([np.c_[-0.05 * k * u, 0.05 * k * u], foot])
    normals = np.vstack([np.tile([-u, -u], (4, 1)), normals])
    e = np.r_[np.full(4, -0.050), np.full(11, 0.001)]
    env = wall_envelope(foot, normals, e, R)
    np.testing.assert_allclose(env[4:], 0.001, atol=1e-12)
    # the same lead-in along the wall's own normal does count
    env_same = wall_envelope(foot, np.tile([0.0, -1.0], (15, 1)), e, R)
    assert env_same[4] < -0.014
