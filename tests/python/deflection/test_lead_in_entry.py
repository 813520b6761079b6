"""Where a compensated final wall starts after a move written as programmed (a lead-in), the written
program reaches the wall's programmed start and then moves along the wall's offset; where it ends before
such a move (a lead-out), it returns along the offset first (issue 36 item 7).

- Into the wall: no point of the written lead-in lies beyond the drawing's wall line beside the wall
  (the written lead-in used to run straight to the offset corner and cross the line before it, cutting
  into the first millimetre of the wall); the wall's own moves are unchanged.
- Out of the wall: the written lead-out starts at the wall's programmed end.
- Without the compensated flags the moves are written as before (straight between the points).
"""

from __future__ import annotations

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d

# a diagonal lead-in back and down to (0, 0) (a turn of 112°, as in the demo), the wall along +X to
# (10, 0), a lead-out back up; the wall on the right of the feed (−Y)
PROGRAM = """G21 G90 G17
G0 X2 Y5 Z5
G1 Z-2 F300
G1 X0 Y0 F900
G1 X10 Y0
G1 X12 Y5
G0 Z5
"""
OFFSET = 0.05  # [mm] towards the wall (−Y)


def _written(active: bool):
    prog = ns.toolpath.parse_gcode(PROGRAM)
    pts, owner, first, last, _ = d.contour_samples(prog, 0.5)
    setup = d.PathSetup(model=None, cutter=None, stock=None, program=prog, nominal=pts, first=first,
                        last=last, side=d.WallSide.right, options=None, owner=owner, spacing=0.5)
    wall = np.flatnonzero(owner == first + 1)
    on = np.zeros(len(pts), dtype=bool)
    on[np.r_[wall[0] - 1, wall]] = True  # the wall's points and its start (the lead-in's end)
    pos = pts.copy()
    pos[on, 1] -= OFFSET
    blocks, origin = d.compensated_blocks(setup, pos, active=on if active else None)
    return blocks, origin, first


def _beside_the_wall_beyond_its_line(blocks, first):
    """Points of the written moves from the lead-in's (block ``first``) start up to the first point of
    the compensated wall, that lie beyond the wall's line (y < 0) beside the wall (0 < x ≤ 10)."""
    out = []
    for b in blocks[first:]:
        for t in np.linspace(0.0, 1.0, 51):
            p = np.asarray(b.point_at(t))
            if p[1] < -1e-9 and 1e-9 < p[0] <= 10.0:
                out.append(p)
        if np.allclose(np.asarray(b.end)[:2], [0.0, -OFFSET]):
            break
    return out


def test_the_lead_in_reaches_the_wall_at_its_start_then_moves_along_the_offset():
    blocks, origin, first = _written(active=True)
    ends = [np.asarray(b.end)[:2] for b in blocks[first:]]
    k = next(i for i, e in enumerate(ends) if np.allclose(e, [0.0, -OFFSET]))
    np.testing.assert_allclose(ends[k - 1], [0.0, 0.0], atol=1e-12)  # the programmed corner first
    assert _beside_the_wall_beyond_its_line(blocks, first) == []
    # both moves belong to the lead-in; the wall's moves follow at the offset
    assert origin[first + k - 1] == origin[first + k] == first
    wall = [b for b, o in zip(blocks, origin) if o == first + 1]
    assert all(abs(b.start[1] + OFFSET) < 1e-12 and abs(b.end[1] + OFFSET) < 1e-12 for b in wall)


def test_the_lead_in_used_to_cross_the_wall_line_before_its_start():
    blocks, _, first = _written(active=False)
    assert len(_beside_the_wall_beyond_its_line(blocks, first)) > 0


def test_the_lead_out_starts_at_the_walls_programmed_end():
    blocks, origin, first = _written(active=True)
    out = [b for b, o in zip(blocks, origin) if o == first + 2]
    np.testing.assert_allclose(np.asarray(out[0].start)[:2], [10.0, -OFFSET], atol=1e-12)
    np.testing.assert_allclose(np.asarray(out[0].end)[:2], [10.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(np.asarray(out[-1].end)[:2], [12.0, 5.0], atol=1e-12)
    # written as programmed from there: one straight line to the lead-out's end after the return
    assert len(out) >= 2
    for b in out[1:]:
        a, e = np.asarray(b.start)[:2], np.asarray(b.end)[:2]
        u = np.array([2.0, 5.0]) / np.hypot(2.0, 5.0)
        for p in (a - [10.0, 0.0], e - [10.0, 0.0]):
            assert abs(u[0] * p[1] - u[1] * p[0]) < 1e-9


def test_the_active_flags_must_match_the_points():
    prog = ns.toolpath.parse_gcode(PROGRAM)
    pts, owner, first, last, _ = d.contour_samples(prog, 0.5)
    setup = d.PathSetup(model=None, cutter=None, stock=None, program=prog, nominal=pts, first=first,
                        last=last, side=d.WallSide.right, options=None, owner=owner, spacing=0.5)
    with pytest.raises(ValueError, match="active"):
        d.compensated_blocks(setup, pts, active=np.ones(3, dtype=bool))


def _straight_wall_setup(grid: float = 0.1):
    """A 6 mm flat end mill's straight wall after a lead-in corner, on stock (Z-map node spacing ``grid``)
    cleared above y = −1.5 by a 10 mm pass: the material is left below that line only."""
    import math

    from pocket_cases import flat_cutter

    stock = ns.stock.ZMap(-6.0, 26.0, -10.0, 10.0, grid, 0.0, -10.0)
    clear = ns.cutter.Cutter.flat_end(10.0, 3, math.radians(30.0))
    clear.flute_length = 20.0
    ns.stock.sweep(stock, clear, ns.toolpath.parse_gcode(
        "G21 G90 G17\nG0 X-12 Y3.5 Z5\nG1 Z-2 F200\nG1 X32 F800\nG0 Z5\n"))
    prog = ns.toolpath.parse_gcode(PROGRAM.replace("G1 X10 Y0", "G1 X20 Y0").replace("G1 X12 Y5", ""))
    return d.setup_path(prog, flat_cutter(6.0), stock, coefficients="leekunhwee_flat_slot", rpm=8000,
                        spacing=0.5, side="right", profile_levels=0)


def test_the_entry_corner_is_solved_for_its_own_error():
    """The scheme ties a corner's offset to the next sample's; where the wall starts after the lead-in,
    compensate_checked solves the corner for its own error instead (the written program reaches it along
    the offset, so that offset is written exactly at the corner)."""
    from netshape.deflection.checked import _entry_offsets

    setup = _straight_wall_setup(0.2)
    wall = np.flatnonzero(setup.owner == setup.first + 1)
    active = np.zeros(len(setup.nominal), dtype=bool)
    active[wall[0] - 1:] = True  # the corner (the lead-in's end) and the wall
    o = d.compensation_options(setup, scheme="accelerated", level="middle", tolerance=5e-4, discount=1.0,
                               max_iterations=50, anderson_depth=5, active=active)
    res = d.compensate_deflection(setup.model, setup.cutter, setup.stock, setup.nominal, o)
    corner = wall[0] - 1
    tied = np.asarray(res.offsets)
    assert tied[corner] == tied[corner + 1] and abs(res.after.error[corner, 1]) > 2e-3
    C = _entry_offsets(setup, res, active, 1, 5e-4)
    r = d.path_wall_errors(setup.model, setup.cutter, setup.stock, setup.nominal, np.asarray(res.normals), C,
                           setup.options)
    assert abs(r.error[corner, 1]) <= 5e-4
    np.testing.assert_array_equal(np.delete(C, corner), np.delete(tied, corner))  # the others held


def test_the_check_counts_what_the_move_along_the_offset_removes():
    """The written move from the programmed corner along the offset into the wall cuts a sliver behind
    the wall's first point (as thick as the offset); the check evaluates every written point in order,
    that move's too, so the wall's first points see the sliver gone and leave the wall the rest of it
    leaves. (The check used to skip the points whose foot is the corner: the sliver stayed, loaded the
    tool and left 12 µm at the first point of the demo's level-2 wall.)"""
    from netshape.deflection.walls import check_against_drawing

    setup = _straight_wall_setup(0.1)
    wall = np.flatnonzero(setup.owner == setup.first + 1)
    on = np.zeros(len(setup.nominal), dtype=bool)
    on[wall[0] - 1:] = True
    pos = np.asarray(setup.nominal).copy()
    pos[on, 1] -= 0.1
    blocks, origin = d.compensated_blocks(setup, pos, active=on)
    w_pts = d.contour_samples(setup.program.with_blocks(blocks, origin), 0.5, 4)[0]
    chk = check_against_drawing(setup.model, setup.cutter, setup.stock, w_pts, setup.nominal, on, setup.side,
                                setup.options)
    e = chk.sample_error[:, 1]
    x = w_pts[:, 0]
    first = np.flatnonzero(chk.final & (x > 1e-6))[0]
    steady = e[np.argmin(np.abs(x - 10.0) + 10 * ~chk.final)]
    assert abs(e[first] - steady) < 1e-3, (e[first], steady)


def test_never_worse_halves_the_sample_nearer_the_worse_points_once_a_round():
    """A wall start whose corner offset overshoots (three times the compensated one) is worse than the
    uncompensated program after the corner: never-worse halves the offset of the sample nearer each
    worse point, once per round however many worse points lie nearer to it, until nothing is worse."""
    from dataclasses import replace

    from netshape.deflection import checked as ck

    setup = _straight_wall_setup()
    chk = ck.compensate_checked(setup, scheme="accelerated", level="middle", tolerance=5e-4, max_rounds=1)
    corner = int(np.flatnonzero(chk.active)[0])
    C = np.asarray(chk.offsets).copy()
    C[corner] *= 3.0
    d_pts = ck.dense_drawing(setup, 4)[0]
    pos = np.asarray(chk.setup.nominal).copy()
    pos[:, :2] += C[:, None] * chk.sample_normals
    blocks, origin, check = ck._write_and_check(chk.setup, pos, d_pts, chk.final, 4, 5e-4, chk.active)
    bad = replace(chk, blocks=blocks, origin=origin, check=check, offsets=C)
    assert bad.worse_points > 1
    fixed = ck._never_worse(bad, d_pts, 4, 5e-4)
    assert fixed.worse_points == 0
    # halved, not zeroed (every worse point used to halve both samples around it, so eight worse points
    # took both to zero in the first round); the samples further on are kept
    assert fixed.offsets[corner] in {C[corner] / 2 ** k for k in range(1, 6)}
    nominal = np.asarray(chk.setup.nominal)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(nominal[:, :2], axis=0).T))])
    after = np.flatnonzero(arc > arc[corner])
    near = after[arc[after] <= arc[corner] + 0.5]  # within one sample spacing of the corner: halved or kept
    assert all(fixed.offsets[k] in {C[k] / 2 ** j for j in range(0, 6)} for k in near)
    far = after[arc[after] > arc[corner] + 1.0]
    np.testing.assert_array_equal(fixed.offsets[far], C[far])
