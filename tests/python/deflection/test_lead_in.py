"""A finish pass entered by a lead-in (issue 36 item 7): the corner where the finish starts, and which
blocks are compensated.

- At a corner of the path (a turn of more than 30° at a point) the wall normal and cutting frame are the
  outgoing move's: the finish wall starts at the corner, so its offset moves the corner along that
  wall's normal, not along the bisector of the lead-in and the wall.
- A lead-in whose wall side runs through the cleared pocket generates no wall: it is not a final wall,
  and its last point (where the finish starts) does not make it one; its moves are written as
  programmed up to that point.

The written program of such a pocket, compensated and checked at four times its sample density, is
bench/deflection_lead_in.py's pocket A (``--check`` asserts its bound): a full compensation takes a
minute or more on the shared machine, too long for the test suite.
"""

from __future__ import annotations

import math

import numpy as np

from netshape import deflection as d
from netshape.deflection import walls

from pocket_cases import lead_in_pocket


def test_corner_takes_the_outgoing_moves_normal():
    # a diagonal lead-in, then a straight wall along +X, then an arc sampled at 10° steps
    angles = np.radians(np.arange(10.0, 91.0, 10.0))
    arc = [(10.0 + 5.0 * math.sin(a), 5.0 - 5.0 * math.cos(a)) for a in angles]
    pts = np.array([(-2.0, 5.0), (-1.0, 2.5), (0.0, 0.0), (5.0, 0.0), (10.0, 0.0), *arc])
    pts = np.c_[pts, np.full(len(pts), -2.0)]
    n = np.asarray(d.wall_normals(pts, d.WallSide.right))
    np.testing.assert_allclose(n[2], [0.0, -1.0], atol=1e-12)  # the corner: the wall along +X
    np.testing.assert_allclose(n[3], [0.0, -1.0], atol=1e-12)
    # on the sampled arc (10° turns) the central difference: the normal of the chord of its neighbours
    t = pts[7, :2] - pts[5, :2]
    t /= np.linalg.norm(t)
    np.testing.assert_allclose(n[6], [t[1], -t[0]], atol=1e-12)


def _lead_in_pocket(pre_cut: bool, grid: float = 0.2, **kw):
    # pre-cut: round roughing down to the contour's Z, a disc of radius 12 mm
    return lead_in_pocket(12.0 if pre_cut else None, grid, **kw)


def test_lead_in_is_not_a_final_wall():
    p, prog, setup = _lead_in_pocket(pre_cut=False, grid=0.25)
    r = d.predict_path(setup)
    normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
    remains = walls.wall_remains_points(prog, setup.owner, setup.nominal, normals, np.asarray(r.depth), 3.0)
    final = walls.final_wall_points(setup.owner, remains, walls.generates_wall(r, setup.side))
    blocks = list(prog.blocks)
    finish_first = max(i for i, b in enumerate(blocks) if int(b.kind) != 0) - 8
    lead = np.flatnonzero(setup.owner == finish_first - 1)
    assert not np.any(final[lead[:-1]])  # the lead-in's own points
    assert final[lead[-1]]               # its end: where the finish starts
    assert np.all(final[setup.owner >= finish_first])

