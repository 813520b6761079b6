"""netshape.posture: the default impeller's passage end to end, checked against an independent NumPy
point-to-triangle distance (not the planner's AABB-tree branch and bound); impeller construction; bad input.

Method: Park, Jung, Hwang, Jung, "A theoretical consideration for continuity control of cutter posture",
Proc. KSPE Conference (C-space, MC-space §2 steps 1–4, MB-spline eq. 1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from netshape import posture as npost

POINTS = 40  # the CLI default; MC-space jitter between neighbours shows at this spacing (≈1.1 mm)


def point_triangle_distance(p: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Distances (n,) from points p (n, 3) to the nearest of triangles tri (m, 3, 3): Ericson's closest point
    on a triangle (Real-Time Collision Detection §5.1.5), evaluated for every pair."""
    a, b, c = tri[None, :, 0], tri[None, :, 1], tri[None, :, 2]
    P = p[:, None, :]
    ab, ac, ap = b - a, c - a, P - a
    d1, d2 = np.sum(ab * ap, -1), np.sum(ac * ap, -1)
    bp = P - b
    d3, d4 = np.sum(ab * bp, -1), np.sum(ac * bp, -1)
    cp = P - c
    d5, d6 = np.sum(ab * cp, -1), np.sum(ac * cp, -1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        den = va + vb + vc
        v = vb / den
        w = vc / den
        q = a + ab * v[..., None] + ac * w[..., None]  # inside the face
        t_ab = d1 / (d1 - d3)
        q = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[..., None], a + ab * t_ab[..., None], q)
        t_ac = d2 / (d2 - d6)
        q = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[..., None], a + ac * t_ac[..., None], q)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        q = np.where(((va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0))[..., None], b + (c - b) * t_bc[..., None], q)
        q = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a, q)
        q = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b, q)
        q = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c, q)
    return np.min(np.linalg.norm(P - q, axis=-1), axis=1)


def numpy_gap(assembly, tri: np.ndarray, tip: np.ndarray, axis: np.ndarray, h: float = 0.25) -> float:
    """Lower bound of the assembly–mesh gap [mm]: distances of axis samples every h mm minus the part radius,
    less h/2 (the distance is 1-Lipschitz along the axis). Only triangles near the axis are kept."""
    a = assembly
    parts = ((a.ball_radius, a.ball_radius, a.ball_radius), (a.ball_radius, a.shank_length, a.shank_radius),
             (a.shank_length + a.holder_radius, a.holder_length, a.holder_radius))
    best = math.inf
    for z0, z1, r in parts:
        zs = np.arange(z0, z1 + h, h) if z1 > z0 else np.array([z0])
        pts = tip[None, :] + zs[:, None] * axis[None, :]
        # triangles whose box comes within r + 1 mm of this part's axis samples' box (others are further away)
        lo, hi = pts.min(0) - r - 1.0, pts.max(0) + r + 1.0
        near = tri[np.all((tri.max(1) >= lo) & (tri.min(1) <= hi), axis=1)]
        if len(near) == 0:
            continue
        d = point_triangle_distance(pts, near)
        best = min(best, float(d.min()) - r - (h / 2 if z1 > z0 else 0.0))
    return best


@pytest.fixture(scope="module")
def default_run():
    imp = npost.make_impeller()
    cc, normals = imp.cc_path(POINTS)
    v, f = imp.obstacles()
    run = npost.plan_postures(cc, normals, v, f, npost.default_assembly(), clearance=0.5)
    return imp, run, v[f]


def test_default_impeller_normal_posture_collides_on_the_inner_part(default_run):
    """The normal posture (+z) hits the leaning blade where the passage is narrow relative to the lean; the
    independent NumPy distance agrees point by point (where it is not within 0.1 mm of the clearance)."""
    imp, run, tri = default_run
    raw = np.asarray(run.result.raw.collides)
    assert 0 < raw.sum() < POINTS, raw
    # the inner part of the passage (where the lean is large against the gap) and nothing beyond it
    np.testing.assert_array_equal(raw, np.arange(POINTS) < raw.sum())
    a = run.assembly
    for i in range(POINTS):
        g = numpy_gap(a, tri, run.result.raw.tips[i], run.result.raw.axes[i])
        if abs(g - 0.5) > 0.25:
            assert raw[i] == (g < 0.5), (i, g)


def test_after_mc_mb_repair_nothing_collides_independent_check(default_run):
    """Final postures keep the clearance (checked with the brute-force NumPy distance), and the largest posture
    change between neighbours falls to half or less of the MC-space postures' (the smoothing's purpose)."""
    imp, run, tri = default_run
    s = run.summary()
    assert s["collisions"]["final"] == 0
    for i in range(POINTS):
        g = numpy_gap(run.assembly, tri, run.result.final.tips[i], run.result.final.axes[i])
        assert g >= 0.5 - 0.15, (i, g)
    # the NumPy bound agrees with the planner's own gap (AABB-tree branch and bound) to the sampling step
    from netshape.geometry import TriangleMesh

    chk = npost.InterferenceChecker(TriangleMesh(run.obstacle_vertices, run.obstacle_faces), run.assembly, 0.5)
    for i in range(0, POINTS, 7):
        g = numpy_gap(run.assembly, tri, run.result.final.tips[i], run.result.final.axes[i])
        gc = chk.gap(run.result.final.tips[i], run.result.final.axes[i])
        if math.isfinite(g):
            assert gc - 0.125 - 2e-3 <= g <= gc + 2e-3, (i, g, gc)
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
    assert set(s) == {"cutter", "clearance_mm", "points", "collisions", "repaired", "max_posture_change_deg_per_mm"}
    assert set(s["cutter"]) == {"ball_radius_mm", "shank_radius_mm", "shank_length_mm", "holder_radius_mm",
                                "holder_length_mm"}
    assert set(s["collisions"]) == {"raw", "mc", "final"} == set(s["max_posture_change_deg_per_mm"])
    prog = (out / "program.ngc").read_text().splitlines()
    assert any(" B" in ln and " C" in ln for ln in prog if ln.startswith("G1"))
    # the G-code's B/C words and XYZ give back the final CL points by forward kinematics
    k = npost.load_kinematics(kin)
    joints = []
    for ln in prog:
        if ln.startswith(("G0", "G1")):
            w = {t[0]: float(t[1:]) for t in ln.split()[1:] if t[0] in "XYZBC"}
            joints.append([w["X"], w["Y"], w["Z"], math.radians(w["B"]), math.radians(w["C"])])
    tips, axes = npost.forward_kinematics(k, np.array(joints))
    np.testing.assert_allclose(tips, rows[:, 1:4], atol=2e-3)
    np.testing.assert_allclose(axes, rows[:, 4:], atol=1e-5)


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


def test_smoothing_into_an_obstacle_is_repaired():
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
    tri = v[f]
    for i in range(len(y)):
        assert numpy_gap(a, tri, run.result.final.tips[i], run.result.final.axes[i], h=0.1) >= 0.5 - 0.06, i


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
