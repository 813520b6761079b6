"""Where a final wall starts after a lead-in corner, the engagement ramps up over the first stretch of
the wall and the offset it needs bends within the first sample spacing; the written program follows it
(issue 36 item 7): samples are added there and solved point by point in path order, the corner tied to
the first of them (checked.py, _refine_entries).

A straight wall along +X entered from a diagonal lead-in (a turn of about 120°), 6 mm tool, 1.8 mm of
radial width: the written program's wall, checked at 4× the sample density, is within 1 µm of the
drawing over the first millimetre of the wall at the reference level (main: −12.2 µm just after the
corner, the straight written ramp from the corner's own offset overcutting), and nowhere worse than
the uncompensated program.
"""

from __future__ import annotations

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d
from netshape.deflection.checked import compensate_checked
from pocket_cases import flat_cutter

PROGRAM = """G21 G90 G17
G0 X3 Y6 Z5
G1 Z-3 F300
G1 X0 Y0 F900
G1 X12 Y0
G1 X14 Y5
G0 Z5
"""


@pytest.fixture(scope="module")
def checked():
    prog = ns.toolpath.parse_gcode(PROGRAM)
    stock = ns.stock.ZMap(-8.0, 24.0, -12.0, -1.8, 0.2, 0.0, -10.0)  # material below y = −1.8
    setup = d.setup_path(prog, flat_cutter(6.0), stock, coefficients="leekunhwee_flat_slot", rpm=8000,
                         spacing=0.5, side="right", profile_levels=0)
    return compensate_checked(setup, scheme="accelerated", level="middle", tolerance=5e-4)


def test_the_wall_start_after_the_lead_in_corner_is_within_a_micrometre(checked):
    c = checked.check
    wall = c.s[c.final]
    start = c.final & (c.s <= wall.min() + 1.0)
    assert checked.before.max_mm()["middle"] > 0.010  # there is something to compensate
    assert np.max(np.abs(c.error[start, 1])) <= 1e-3


def test_the_refined_wall_is_nowhere_worse_and_better_than_before(checked):
    assert checked.worse_points == 0
    assert checked.after_mm["middle"] < checked.before_mm["middle"]
