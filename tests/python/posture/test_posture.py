"""netshape.posture: the default impeller's passage end to end, checked against the exact NumPy solid–triangle
test of conftest.py (not the planner's GJK bounds); impeller construction; bad input.

Method: Park, Jung, Hwang, Jung, "A theoretical consideration for continuity control of cutter posture",
Proc. KSPE Conference (C-space, MC-space §2 steps 1–4, MB-spline eq. 1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netshape import posture as npost

POINTS = 40  # the CLI default; MC-space jitter between neighbours shows at this spacing (≈1.1 mm)


@pytest.fixture(scope="module")
def default_run():
    imp = npost.make_impeller()
    cc, normals = imp.cc_path(POINTS)
    v, f = imp.obstacles()
    run = npost.plan_postures(cc, normals, v, f, npost.default_assembly(), clearance=0.5)
    return imp, run, v[f]


def test_default_impeller_normal_posture_collides_on_the_inner_part(default_run, exact):
    """The normal posture (+z) hits the leaning blade where the passage is narrow relative to the lean; the
    independent exact test agrees point by point (where the gap is not within 0.25 mm of the clearance)."""
    imp, run, tri = default_run
    raw = np.asarray(run.result.raw.collides)
    assert 0 < raw.sum() < POINTS, raw
    # the inner part of the passage (where the lean is large against the gap) and nothing beyond it
    np.testing.assert_array_equal(raw, np.arange(POINTS) < raw.sum())
    tips, axes = run.result.raw.tips, run.result.raw.axes
    surely_hit = exact.hits(run.assembly, tri, tips, axes, inflate=0.25)
    surely_free = ~exact.hits(run.assembly, tri, tips, axes, inflate=0.75, grow_ends=True)
    assert np.all(raw[surely_hit]) and not np.any(raw[surely_free])
    assert surely_hit.sum() >= 8 and surely_free.sum() >= POINTS // 2  # the rest lie within 0.25 mm of it


def test_after_mc_mb_repair_nothing_collides_independent_check(default_run, exact):
    """Final postures keep the clearance (the exact solid with its radii grown by the clearance meets no
    triangle), and the largest posture change between neighbours falls to half or less of the MC-space
    postures' (the smoothing's purpose)."""
    imp, run, tri = default_run
    s = run.summary()
    assert s["collisions"]["final"] == 0
    assert not exact.hits(run.assembly, tri, run.result.final.tips, run.result.final.axes, inflate=0.5).any()
    ch = s["max_posture_change_deg_per_mm"]
    assert ch["final"] <= 0.5 * ch["mc"], ch
    # tips: the ball touches the floor at the CC point: centre at CC + R n, tip = centre − R·axis
    r = run.assembly.ball_radius
    centre = run.result.cc + r * run.result.normals
    np.testing.assert_allclose(run.result.final.tips + r * run.result.final.axes, centre, atol=1e-9)


def test_impeller_blade_to_blade_gap_is_exact():
    """Blade 0's suction face turned by 2π/N − 2δ about z is blade 1's pressure face, so the circumferential
    gap at radius r is r·(2π/N − 2δ)."""
    imp = npost.make_impeller()
    uv = np.array([[u, v] for u in np.linspace(0, 1, 7) for v in np.linspace(0, 1, 4)])
    suction = np.asarray(imp.blade_faces[0][1].evaluate(uv))
    pressure = np.asarray(imp.blade_faces[1][0].evaluate(uv))
    r = np.hypot(suction[:, 0], suction[:, 1])
    np.testing.assert_allclose(np.hypot(pressure[:, 0], pressure[:, 1]), r, rtol=1e-12)
    np.testing.assert_allclose(pressure[:, 2], suction[:, 2], atol=1e-12)
    dang = np.unwrap(np.arctan2(pressure[:, 1], pressure[:, 0]) - np.arctan2(suction[:, 1], suction[:, 0]))
    np.testing.assert_allclose(r * dang, imp.passage_gap(r), rtol=1e-12)
    # the floor's normal points to the tool (+z)
    _, n = imp.cc_path(5)
    np.testing.assert_allclose(n, np.tile([0, 0, 1.0], (5, 1)), atol=1e-12)


def test_cli_writes_the_listed_files_and_keys(tmp_path):
    from netshape.cli import main

    kin = tmp_path / "kin.toml"
    kin.write_text('kind = "head_bc"\npivot_length_mm = 150.0\n')
    out = tmp_path / "run"
    assert main(["posture", "plan", "--impeller", "--out", str(out), "--points", "6", "--machine", str(kin)]) == 0
    for name in ("obstacles.stl", "postures_raw.csv", "postures_mc.csv", "postures_final.csv", "summary.json",
                 "program.ngc"):
        assert (out / name).is_file(), name
    head = (out / "postures_final.csv").read_text().splitlines()[0]
    assert head == "s_mm,tip_x_mm,tip_y_mm,tip_z_mm,axis_i,axis_j,axis_k"
    rows = np.loadtxt(out / "postures_final.csv", delimiter=",", skiprows=1)
    assert rows.shape == (6, 7)
    np.testing.assert_allclose(np.linalg.norm(rows[:, 4:], axis=1), 1.0, atol=1e-8)
    import json

    s = json.loads((out / "summary.json").read_text())
    assert set(s) == {"cutter", "clearance_mm", "points", "collisions", "repaired", "max_posture_change_deg_per_mm",
                      "moves", "rotary", "status"}
    assert s["moves"]["machine"] == "head_bc" and s["moves"]["colliding"] == 0 and s["status"] == "ok"
    assert set(s["cutter"]) == {"ball_radius_mm", "shank_radius_mm", "shank_length_mm", "holder_radius_mm",
                                "holder_length_mm"}
    assert set(s["collisions"]) == {"raw", "mc", "final"} == set(s["max_posture_change_deg_per_mm"])
    prog = (out / "program.ngc").read_text().splitlines()
    assert any(" B" in ln and " C" in ln for ln in prog if ln.startswith("G1"))
    # the G-code's B/C words and XYZ give back the final CL points by forward kinematics (in order, between the
    # approach and the retract 10 mm up the tool axis and the points inserted on the chords)
    k = npost.load_kinematics(kin)
    joints = []
    for ln in prog:
        if ln.startswith(("G0", "G1")):
            w = {t[0]: float(t[1:]) for t in ln.split()[1:] if t[0] in "XYZBC"}
            joints.append([w["X"], w["Y"], w["Z"], math.radians(w["B"]), math.radians(w["C"])])
    tips, axes = npost.forward_kinematics(k, np.array(joints))
    np.testing.assert_allclose(tips[0], rows[0, 1:4] + 10.0 * rows[0, 4:], atol=2e-3)
    np.testing.assert_allclose(tips[-1], rows[-1, 1:4] + 10.0 * rows[-1, 4:], atol=2e-3)
    near = [int(np.argmin(np.linalg.norm(tips - r[1:4], axis=1))) for r in rows]
    assert near == sorted(near)
    np.testing.assert_allclose(tips[near], rows[:, 1:4], atol=2e-3)
    np.testing.assert_allclose(axes[near], rows[:, 4:], atol=1e-5)


def test_cli_plot_and_table_ac(tmp_path):
    from netshape.cli import main

    kin = tmp_path / "kin.toml"
    kin.write_text('kind = "table_ac"\ntable_centre_mm = [0.0, 0.0, -50.0]\n')
    out = tmp_path / "run"
    assert main(["posture", "plan", "--impeller", "--out", str(out), "--points", "5", "--machine", str(kin),
                 "--plot"]) == 0
    assert (out / "cspace.png").stat().st_size > 1000 and (out / "angles.png").stat().st_size > 1000
    assert any(" A" in ln and " C" in ln for ln in (out / "program.ngc").read_text().splitlines())


def _write_tool(path, diameter):
    path.write_text(f'kind = "ball"\ndiameter_mm = {diameter}\nflutes = 2\nhelix_deg = 30.0\nflute_length_mm = 20.0\n'
                    f'stick_out_mm = 40.0\nshank_diameter_mm = {diameter}\nshank_length_mm = 35.0\n'
                    f'holder_diameter_mm = 24.0\nholder_length_mm = 80.0\n')


def test_bad_input_names_the_cc_point_or_field(tmp_path, capsys):
    from netshape.cli import main

    # a ball wider than the passage cannot reach the first CC point at any posture
    tool = tmp_path / "fat.toml"
    _write_tool(tool, 24.0)
    assert main(["posture", "plan", "--impeller", "--tool", str(tool), "--out", str(tmp_path / "o"),
                 "--points", "5"]) == 2
    err = capsys.readouterr().err.strip()
    assert "CC point 0" in err and "cannot reach" in err and len(err.splitlines()) == 1
    # empty obstacle mesh
    from netshape import geometry as ng

    surf = ng.bilinear(np.array([0, 0, 0.0]), np.array([10, 0, 0.0]), np.array([0, 10, 0.0]),
                       np.array([10, 10, 0.0]))
    stl = tmp_path / "empty.stl"
    stl.write_text("solid empty\nendsolid empty\n")
    sj = tmp_path / "s.json"
    ng.save_json(surf, sj)
    _write_tool(tool, 6.0)
    assert main(["posture", "plan", "--surface", str(sj), "--obstacles", str(stl), "--tool", str(tool),
                 "--out", str(tmp_path / "o")]) == 2
    assert "obstacles" in capsys.readouterr().err
    # degenerate surface: every control point the same
    deg = ng.NurbsSurface(1, 1, np.array([0, 0, 1, 1.0]), np.array([0, 0, 1, 1.0]), np.zeros((4, 3)))
    with pytest.raises(ValueError, match="surface"):
        npost.surface_cc_path(deg, 5)
    # bad tool key value
    tool.write_text(tool.read_text().replace("holder_length_mm = 80.0", "holder_length_mm = 20.0"))
    with pytest.raises(ValueError, match="holder_length"):
        npost.load_tool(tool)


def _plate(x, y0, y1):
    v = np.array([[x, y0, -50.0], [x, y1, -50.0], [x, y1, 150.0], [x, y0, 150.0]])
    return v, np.array([[0, 1, 2], [0, 2, 3]])


def test_smoothing_into_an_obstacle_is_repaired(exact):
    """A channel open on the left for y < 40 and tight beyond (walls at x = ±6.6: the Ø12 holder keeps 0.1 mm
    more than the clearance upright): the MC postures tilt to the left before the step and stand upright after
    it, and strong smoothing (30 passes) drags the first postures after the step into the walls; they are
    repaired and the independent NumPy distance confirms the clearance."""
    vr, fr = _plate(6.6, -40.0, 120.0)
    vl, fl = _plate(-6.6, 40.0, 120.0)
    v, f = np.concatenate([vr, vl]), np.concatenate([fr, fl + 4])
    y = np.arange(0.0, 61.0, 2.0)
    cc = np.column_stack([np.zeros_like(y), y, np.zeros_like(y)])
    n = np.tile([0.0, 0.0, 1.0], (len(y), 1))
    a = npost.CutterAssembly(2.0, 2.0, 25.0, 6.0, 60.0)
    o = npost.PlanOptions()
    o.passes = 30
    run = npost.plan_postures(cc, n, v, f, a, clearance=0.5, options=o)
    s = run.summary()
    smoothed_hits = np.asarray(run.result.smoothed.collides)
    assert s["collisions"]["mc"] == 0 and smoothed_hits.sum() > 0, s
    np.testing.assert_array_equal(np.asarray(run.result.repaired), smoothed_hits)
    assert s["repaired"] == smoothed_hits.sum() and s["collisions"]["final"] == 0
    assert not exact.hits(a, v[f], run.result.final.tips, run.result.final.axes, inflate=0.5).any()


def test_cli_surface_and_obstacles_and_impeller_toml(tmp_path, capsys):
    """--surface/--obstacles: a flat floor beside one wall (x = 9); the MC posture leans away from the wall and
    nothing collides. --impeller with a TOML file: keys are read, an unknown key is named."""
    from netshape import geometry as ng
    from netshape.cli import main

    surf = ng.bilinear(np.array([0, 0, 0.0]), np.array([0, 20, 0.0]), np.array([-10, 0, 0.0]),
                       np.array([-10, 20, 0.0]))  # u along +y (feed), normal (+y) × (−x) = +z
    sj = tmp_path / "floor.json"
    ng.save_json(surf, sj)
    vw, fw = _plate(9.0, -20.0, 40.0)
    stl = tmp_path / "wall.stl"
    ng.write_stl(stl, vw, fw)
    tool = tmp_path / "tool.toml"
    _write_tool(tool, 4.0)
    out = tmp_path / "o"
    assert main(["posture", "plan", "--surface", str(sj), "--obstacles", str(stl), "--tool", str(tool),
                 "--out", str(out), "--points", "6"]) == 0
    import json

    s = json.loads((out / "summary.json").read_text())
    assert s["points"] == 6 and s["collisions"]["final"] == 0 and s["cutter"]["holder_radius_mm"] == 12.0
    final = np.loadtxt(out / "postures_final.csv", delimiter=",", skiprows=1)
    assert np.all(final[:, 4] < 0)  # tilted away from the wall at +x
    imp = tmp_path / "imp.toml"
    imp.write_text("blades = 10\ntwist_deg = 0.0\n")
    assert main(["posture", "plan", "--impeller", str(imp), "--out", str(tmp_path / "i"), "--points", "5"]) == 0
    s = json.loads((tmp_path / "i" / "summary.json").read_text())
    assert s["collisions"]["raw"] == 0  # upright blades: the normal posture is free
    imp.write_text("blade_count = 10\n")
    assert main(["posture", "plan", "--impeller", str(imp), "--out", str(tmp_path / "i")]) == 2
    assert "blade_count" in capsys.readouterr().err


def test_blade_path_runs_on_blade_1_pressure_face_with_normals_into_the_passage():
    imp = npost.make_impeller()
    cc, n, v, f = imp.blade_path(12)
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-9)
    np.testing.assert_allclose(cc[:, 2], 0.75 * imp.params.blade_height_mm, atol=1e-9)  # ruled in z
    # on blade 1's pressure face: turned by pitch − δ from blade 0's camber surface at the same (u, v)
    angle = np.arctan2(cc[:, 1], cc[:, 0])
    suction0 = imp.blade_faces[0][1].evaluate_with_normals(np.column_stack([np.linspace(0, 1, 12),
                                                                             np.full(12, 0.75)]))[0]
    gap = angle - np.arctan2(suction0[:, 1], suction0[:, 0])
    np.testing.assert_allclose(gap, imp.pitch - 2 * imp.delta, atol=1e-9)
    assert np.all(np.sum(n * (suction0 - cc), axis=1) > 0)  # towards blade 0, across the passage
    assert len(f) > 0 and f.max() < len(v)


def test_status_says_when_collisions_are_left(default_run):
    """The summary's status is "ok" only when no final posture and no move of the written program comes
    within the clearance. The blade-side path leaves colliding moves (the repair clears the postures, not
    every move between them), and must say so."""
    _, run, _ = default_run
    s = run.summary()
    assert s["moves"]["colliding"] == 0 and s["collisions"]["final"] == 0 and s["status"] == "ok"
    imp = npost.make_impeller()
    bc, bn, bv, bf = imp.blade_path(POINTS)
    blade = npost.plan_postures(bc, bn, bv, bf, npost.default_assembly(), clearance=0.5)
    b = blade.summary()
    left = b["moves"]["colliding"] + b["collisions"]["final"]
    assert left > 0, b  # the case this test is about
    assert b["status"] == "collisions_left"
