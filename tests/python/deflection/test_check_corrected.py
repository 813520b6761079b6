"""The offsets corrected by the written program's own check (checked.py, _check_corrected; issue 36 item 7).

A sample's own error is −C − δ·n; the check judges the wall as the deepest cut of the deflected circles,
which on a curved wall also moves with the tangential deflection. On a circular pocket's finish pass
(6 mm tool, 1.2 mm of radial width) the compensated program's wall sits about 1.7 µm inside the drawing
along the whole circle though every sample meets its own target; moving the offsets by the checked
error at the samples brings the mean |error| on the wall from above 1 µm to below 0.5 µm, while the
largest moves by less than the tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d
from netshape.deflection import checked as ck
from pocket_cases import flat_cutter

# in from the centre, once round the circle of centre radius 5 mm (wall radius 8 mm), back to the centre
PROGRAM = """G21 G90 G17
G0 X0 Y0 Z5
G1 Z-3 F300
G1 X5 Y0 F900
G3 X-5 Y0 I-5 J0
G3 X5 Y0 I5 J0
G1 X0 Y0
G0 Z5
"""
TOL = 5e-4


@pytest.fixture(scope="module")
def compensated():
    stock = ns.stock.ZMap(-12.0, 12.0, -12.0, 12.0, 0.2, 0.0, -10.0)
    clear = ns.cutter.Cutter.flat_end(10.0, 3, math.radians(30.0))
    clear.flute_length = 20.0
    ns.stock.sweep(stock, clear, ns.toolpath.parse_gcode(  # cleared to radius 6.8 mm
        "G21 G90 G17\nG0 X1.8 Y0 Z5\nG1 Z-4 F200\nG3 X1.8 Y0 I-1.8 J0 F800\nG0 Z5\n"))
    setup = d.setup_path(ns.toolpath.parse_gcode(PROGRAM), flat_cutter(6.0), stock,
                         coefficients="leekunhwee_flat_slot", rpm=8000, spacing=0.5, side="right",
                         profile_levels=0)
    return setup, ck.compensate_checked(setup, scheme="accelerated", level="middle", tolerance=TOL,
                                       max_rounds=1)


def _abs_errors(out):
    return np.abs(out.check.error[out.check.final, out.level])


def test_the_check_correction_brings_the_curved_wall_to_the_drawing(compensated):
    setup, chk = compensated
    d_pts = ck.dense_drawing(setup, 4)[0]
    corrected = ck._check_corrected(chk, d_pts, 4, TOL)
    assert np.mean(_abs_errors(chk)) > 1e-3
    assert np.mean(_abs_errors(corrected)) < 0.5e-3
    assert _abs_errors(corrected).max() <= _abs_errors(chk).max() + TOL


def test_compensate_checked_keeps_the_best_written_program_and_never_worse(compensated):
    _, chk = compensated
    assert chk.worse_points == 0
    assert chk.after_mm["middle"] < chk.before_mm["middle"]
