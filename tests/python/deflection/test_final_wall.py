"""The part's wall (issue 36): which passes leave it, the written program judged against the drawing,
never worse than the program as written.

- Final walls: in a pocket (clearing rings, then the finish contour, one run at one Z) only the finish
  contour's blocks are final-wall blocks; the test checks it against plain geometry (a wall point is cut
  away when a later pass comes within R of it), independently of the C++ grid.
- Against the drawing: `deflection predict --drawing` of the program `deflection compensate` wrote gives
  the errors `compensate` reported (`after_mm`), and the uncompensated program against itself gives
  `predict`'s own errors.
- Never worse: over random arc-preshaped stocks the written program's error at the reference level,
  checked at four times its sample density, is nowhere above the uncompensated program's.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import netshape as ns
from netshape import deflection as d
from netshape.cli import main
from netshape.deflection import walls
from netshape.deflection.checked import compensate_checked

from pocket_cases import flat_cutter, Pocket, pocket_gcode, stock_bounds

CUT = dict(coefficients="leekunhwee_flat_slot", rpm=8000, spacing=0.5, side="right", profile_levels=0)


def _cutter(diameter: float):
    return flat_cutter(diameter)


@pytest.mark.parametrize("rotation", [0.0, 30.0])
def test_only_the_finish_pass_is_a_final_wall(rotation):
    p = Pocket(tool_diameter=8, rings=3, stepover=3.0, rotation_deg=rotation)
    lo, hi = stock_bounds(p)
    prog = ns.toolpath.parse_gcode(pocket_gcode(p))
    stock = ns.stock.ZMap(lo[0], hi[0], lo[1], hi[1], 0.1, hi[2], lo[2])
    setup = d.setup_path(prog, _cutter(8), stock, **CUT)
    r = d.predict_path(setup)
    normals = np.asarray(d.wall_normals(setup.nominal, setup.side))
    remains = walls.wall_remains_points(prog, setup.owner, setup.nominal, normals, np.asarray(r.depth), 4.0)
    final = walls.final_wall_points(setup.owner, remains, np.asarray(r.engaged))
    # independent: the finish loop is the last 9 cutting blocks (from the middle of its -Y side: 5 lines,
    # 4 corner arcs), after the one-stepover joining move from the last ring
    blocks = list(prog.blocks)
    finish_first = max(i for i, b in enumerate(blocks) if int(b.kind) != 0) - 8
    on_finish = setup.owner >= finish_first
    # every finish-pass point (but the start, shared with the joining move) is final, no ring point is
    assert np.all(final[on_finish])
    assert not np.any(final[~on_finish][:-1])
    # geometry: a ring point's wall lies within R of some later pass point (brute force over the path);
    # the last one is the finish's start, whose wall (the outgoing move's, at the corner) is the finish's
    W = setup.nominal[:, :2] + 4.0 * normals
    for i in np.flatnonzero(~on_finish & np.asarray(r.engaged, dtype=bool))[:-1][::7]:
        later = setup.nominal[setup.owner > setup.owner[i], :2]
        assert np.min(np.hypot(*(later - W[i]).T)) < 4.0, i


def test_predict_reports_only_the_final_wall(tmp_path):
    p = Pocket(tool_diameter=8, rings=3, stepover=3.0)
    lo, hi = stock_bounds(p)
    (tmp_path / "pocket.ngc").write_text(pocket_gcode(p))
    (tmp_path / "tool.toml").write_text('kind = "flat"\ndiameter_mm = 8.0\nflutes = 4\nhelix_deg = 30.0\n'
                                        'flute_length_mm = 20.0\nstick_out_mm = 40.0\nyoungs_modulus_MPa = 600000.0\n')
    (tmp_path / "stock.toml").write_text(f"min_mm = {list(lo)}\nmax_mm = {list(hi)}\nspacing_mm = 0.1\n")
    out = tmp_path / "p.json"
    assert main(["deflection", "predict", str(tmp_path / "pocket.ngc"), "--tool", str(tmp_path / "tool.toml"),
                 "--stock", str(tmp_path / "stock.toml"), "--coefficients", "leekunhwee_flat_slot", "--rpm", "8000",
                 "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    pieces = data["contours"]
    assert [c["final_wall"] for c in pieces] == [False, True]
    final = np.asarray(data["points"]["final_wall"])
    err = np.abs(np.asarray(data["points"]["error_middle_mm"]))
    # the reported maximum is the finish pass's, not the rings' (which cut full slots, so larger)
    assert data["max_wall_error_mm"]["middle"] == pytest.approx(err[final].max())
    assert err[~final].max() > err[final].max()


def _straight(tmp_path, seed=None):
    """A straight down-milling finishing cut across stock pre-shaped by arcs (random ones for a seed)."""
    rng = np.random.default_rng(seed)
    (tmp_path / "tool.toml").write_text('kind = "flat"\ndiameter_mm = 10.0\nflutes = 4\nhelix_deg = 30.0\n'
                                        'flute_length_mm = 30.0\nstick_out_mm = 45.0\n'
                                        'youngs_modulus_MPa = 600000.0\n')
    (tmp_path / "rough.toml").write_text('kind = "flat"\ndiameter_mm = 16.0\nflutes = 3\nhelix_deg = 30.0\n'
                                         'flute_length_mm = 30.0\nstick_out_mm = 60.0\n'
                                         'youngs_modulus_MPa = 600000.0\n')
    # roughing: arcs bulging into the wall region leave a width that varies along the cut
    r = [rng.uniform(14, 35) if seed is not None else 20.0 for _ in range(2)]
    y = [rng.uniform(10.5, 12.5) if seed is not None else 11.5 for _ in range(2)]
    lines = ["G21 G90 G17", "S3000 M3", f"G0 X-5 Y{y[0] + 8:.3f} Z5", "G1 Z-3 F300",
             f"G1 X0 Y{y[0] + 8:.3f} F600", f"G2 X20 Y{y[1] + 8:.3f} R{r[0]:.3f}", f"G2 X45 Y{y[0] + 8:.3f} R{r[1]:.3f}",
             "G0 Z10", "M30"]
    (tmp_path / "rough.nc").write_text("\n".join(lines) + "\n")
    (tmp_path / "stock.toml").write_text("min_mm = [-10.0, -10.0, -8.0]\nmax_mm = [50.0, 30.0, 0.0]\n"
                                         'spacing_mm = 0.1\n[[pre_cut]]\nprogram = "rough.nc"\ntool = "rough.toml"\n')
    (tmp_path / "cut.nc").write_text("G21 G90 G17\nS3000 M3\nG0 X-8 Y14 Z5\nG1 Z-3 F300\nG1 X48 Y14 F600\n"
                                     "G0 Z10\nM30\n")
    return ["--tool", str(tmp_path / "tool.toml"), "--stock", str(tmp_path / "stock.toml"),
            "--coefficients", "leekunhwee_flat_slot", "--rpm", "3000", "--spacing", "0.5"]


def test_compensate_reports_the_written_program_and_predict_drawing_agrees(tmp_path, capsys):
    common = _straight(tmp_path)
    cj, nc = tmp_path / "c.json", tmp_path / "comp.nc"
    assert main(["deflection", "compensate", str(tmp_path / "cut.nc"), *common, "-o", str(nc),
                 "--json", str(cj)]) == 0
    comp = json.loads(cj.read_text())
    assert set(comp["after_mm"]) == {"bottom", "middle", "top"}
    assert comp["after_mm"]["middle"] < 0.25 * comp["before_mm"]["middle"]
    assert "after:" in capsys.readouterr().out
    # the taper: bottom and top keep errors the 2-D offset cannot remove (stated in the output)
    assert max(comp["after_mm"]["bottom"], comp["after_mm"]["top"]) > comp["after_mm"]["middle"]
    # the same tool measures the written program against the drawing
    pj = tmp_path / "p.json"
    assert main(["deflection", "predict", str(nc), *common, "--drawing", str(tmp_path / "cut.nc"),
                 "--json", str(pj)]) == 0
    pred = json.loads(pj.read_text())
    # at the written program's own samples (a subset of compensate's denser check): no larger
    for k in ("bottom", "middle", "top"):
        assert pred["max_wall_error_mm"][k] <= comp["after_mm"][k] + 1e-6
    assert pred["offset_mm"]["max"] > 0.005  # the written program really is offset from the drawing
    # the uncompensated program against itself as drawing: its own prediction
    pj2 = tmp_path / "p2.json"
    pj3 = tmp_path / "p3.json"
    assert main(["deflection", "predict", str(tmp_path / "cut.nc"), *common, "--drawing", str(tmp_path / "cut.nc"),
                 "--json", str(pj2)]) == 0
    assert main(["deflection", "predict", str(tmp_path / "cut.nc"), *common, "--json", str(pj3)]) == 0
    a, b = json.loads(pj2.read_text()), json.loads(pj3.read_text())
    for k in ("bottom", "middle", "top"):
        assert a["max_wall_error_mm"][k] == pytest.approx(b["max_wall_error_mm"][k], abs=2e-4)


@pytest.mark.parametrize("seed", range(6))
def test_never_worse_than_the_program_as_written(tmp_path, seed):
    common = _straight(tmp_path, seed)
    cutter = ns.cutter.load_cutter(tmp_path / "tool.toml")
    stock = d.load_stock(tmp_path / "stock.toml")
    setup = d.setup_path(ns.toolpath.read_gcode(tmp_path / "cut.nc"), cutter, stock,
                         coefficients="leekunhwee_flat_slot", rpm=3000, spacing=0.5)
    chk = compensate_checked(setup, scheme="accelerated", level="middle", tolerance=5e-4)
    # the written program at 4x its density against the uncompensated one at the same drawing places
    before = np.interp(chk.check.s, chk.before.s, np.abs(chk.before.error[:, 1]))
    after = np.abs(chk.check.error[:, 1])
    on = chk.check.final
    assert np.all(after[on] <= before[on] + 0.01 * 5e-4 + 1e-9), float(np.max(after[on] - before[on]))
    assert chk.worse_points == 0
    assert common  # the CLI options were built for the same files
