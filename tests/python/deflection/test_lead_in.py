"""A finish pass entered by a lead-in (issue 36 item 7): the corner where the finish starts, and which
blocks are compensated.

- At a corner of the path (a turn of more than 30° at a point) the wall normal and cutting frame are the
  outgoing move's: the finish wall starts at the corner, so its offset moves the corner along that
  wall's normal, not along the bisector of the lead-in and the wall.
- A lead-in whose wall side runs through the cleared pocket generates no wall: it is not a final wall,
  and its last point (where the finish starts) does not make it one; its moves are written as
  programmed up to that point.
- The written program of a pocket with a diagonal lead-in and a round pre-cut whose floor is the
  contour's Z (generated here, not the demo) meets a bound at the middle level, checked at four times
  its sample density.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d
from netshape.deflection import walls
from netshape.deflection.checked import compensate_checked

from pocket_cases import flat_cutter, Pocket, pocket_gcode, stock_bounds


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
    p = Pocket(**{**dict(half_x=18, half_y=13, corner_radius=6, tool_diameter=6, stepover=2.5, rings=3,
                         lead_in=-4.0, z=-3.0), **kw})
    lo, hi = stock_bounds(p)
    stock = ns.stock.ZMap(lo[0], hi[0], lo[1], hi[1], grid, hi[2], lo[2])
    if pre_cut:  # round roughing with a 10 mm tool down to the contour's Z: a disc of radius 12 mm
        rough = ns.cutter.Cutter.flat_end(10.0, 3, math.radians(30.0))
        rough.flute_length = 20.0
        ns.stock.sweep(stock, rough, ns.toolpath.parse_gcode(
            f"G21 G90 G17\nG0 X7 Y0 Z5\nG1 Z{p.z:g} F200\nG2 X7 Y0 I-7 J0 F800\nG0 Z5\n"))
    prog = ns.toolpath.parse_gcode(pocket_gcode(p))
    setup = d.setup_path(prog, flat_cutter(p.tool_diameter), stock, coefficients="leekunhwee_flat_slot",
                         rpm=8000, spacing=0.5, side="right", profile_levels=0)
    return p, prog, setup


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


def test_lead_in_pocket_written_program_meets_the_bound():
    p, prog, setup = _lead_in_pocket(pre_cut=True)
    chk = compensate_checked(setup, scheme="accelerated", level="middle", tolerance=5e-4)
    # the lead-in is written as programmed up to its last point
    blocks = list(prog.blocks)
    finish_first = max(i for i, b in enumerate(blocks) if int(b.kind) != 0) - 8
    lead_blocks = [b for b, o in zip(chk.blocks, chk.origin) if o == finish_first - 1]
    start = np.asarray(blocks[finish_first - 1].start)
    assert np.linalg.norm(np.asarray(lead_blocks[0].start) - start) < 1e-9
    u = np.asarray(blocks[finish_first - 1].end[:2]) - start[:2]
    u /= np.linalg.norm(u)
    off = [abs(u[0] * (b.end[1] - start[1]) - u[1] * (b.end[0] - start[0])) for b in lead_blocks[:-1]]
    assert max(off, default=0.0) < 1e-6  # on the programmed line
    assert chk.before_mm["middle"] > 0.07
    assert chk.after_mm["middle"] <= 0.010, chk.after_mm
