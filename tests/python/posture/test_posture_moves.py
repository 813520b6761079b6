"""Between CC points: the joint-linear motion checked with a certified bound and repaired; program.ngc with
approach and retract along the tool axis and rotary moves subdivided to the chord tolerance. Issue 38 item 2."""

from __future__ import annotations

import math

import numpy as np

from netshape import posture as npost
from netshape.geometry import TriangleMesh


def head(pivot=0.0):
    k = npost.Kinematics()
    k.kind = npost.MachineKind.head_bc
    k.pivot_length = pivot
    return k


def test_swing_through_an_obstacle_collides_though_both_ends_are_free(box_mesh):
    """B from +40° to −40° about a fixed tip (head_bc, pivot 0): the holder passes straight up, through a block
    50 mm above the tip; at both ends it is 30 mm away. The point checks say free, the move check says no."""
    v, f = box_mesh([-2.0, -2.0, 48.0], [2.0, 2.0, 52.0])
    chk = npost.InterferenceChecker(TriangleMesh(v, f), npost.default_assembly(), 0.5)
    k = head()
    j0, j1 = np.array([0, 0, 0, math.radians(40), 0.0]), np.array([0, 0, 0, math.radians(-40), 0.0])
    tips, axes = npost.forward_kinematics(k, np.vstack([j0, j1]))
    assert not np.any(chk.collides(tips, axes))
    m = npost.check_move(chk, k, j0, j1)
    assert m.collides and abs(m.at - 0.5) < 0.2
    # a swing that stops short of it (+40° → +25°) is certified free
    j2 = np.array([0, 0, 0, math.radians(25), 0.0])
    assert not npost.check_move(chk, k, j0, j2).collides


def test_certified_free_moves_are_free_when_sampled_densely():
    """Random short moves near the impeller blades (table_ac) between postures tilted up to 6° off the planned
    final ones: every move reported free is free at 200 evenly spaced poses along it (the bound covers the
    poses in between), and the bound is tight enough that nearly every move free at those 200 poses is
    certified free (at most 2 of the 40 are not)."""
    imp = npost.make_impeller()
    v, f = imp.obstacles()
    a = npost.default_assembly()
    chk = npost.InterferenceChecker(TriangleMesh(v, f), a, 0.5)
    k = npost.Kinematics()
    cc, n = imp.cc_path(60)
    final = npost.plan(chk, cc, n).final
    rng = np.random.default_rng(5)
    certified = dense = 0
    for _ in range(40):
        i = int(rng.integers(0, len(cc) - 1))
        ax = np.array(final.axes)[[i, i + 1]] + rng.normal(0.0, math.radians(6) / 2, (2, 3))
        ax /= np.linalg.norm(ax, axis=1)[:, None]
        tips = np.array([cc[i], cc[i + 1]]) + a.ball_radius * (n[[i, i + 1]] - ax)
        joints = npost.inverse_kinematics(k, tips, ax)
        lam = np.linspace(0, 1, 200)[:, None]
        t2, a2 = npost.forward_kinematics(k, joints[0] + lam * (joints[1] - joints[0]))
        free_dense = not np.any(chk.collides(t2, a2))
        dense += free_dense
        if npost.check_move(chk, k, joints[0], joints[1]).collides:
            continue
        certified += 1
        assert free_dense
    assert certified >= 10 and certified >= dense - 2, (certified, dense)


def test_plan_program_approach_retract_chord_and_no_colliding_move(tmp_path):
    """The default impeller on head_bc: every move of the program is checked free; the program starts with an
    approach 10 mm up the first axis and ends with a retract up the last one; the machine's tip leaves no chord
    by more than the tolerance (sampled)."""
    imp = npost.make_impeller()
    cc, n = imp.cc_path(40)
    v, f = imp.obstacles()
    k = head(150.0)
    run = npost.plan_postures(cc, n, v, f, npost.default_assembly(), clearance=0.5, kinematics=k,
                              approach_mm=10.0, chord_mm=0.01)
    p = run.program
    assert not np.any(p.move_collides)
    tips, axes = np.asarray(p.tips), np.asarray(p.axes)
    final = run.result.final
    np.testing.assert_allclose(tips[0], final.tips[0] + 10.0 * final.axes[0], atol=1e-9)
    np.testing.assert_allclose(tips[-1], final.tips[-1] + 10.0 * final.axes[-1], atol=1e-9)
    assert p.source[0] == -1 and p.source[-1] == len(cc)
    # every final posture is a program point, in order
    idx = [int(np.flatnonzero(np.asarray(p.source) == i)[0]) for i in range(len(cc))]
    assert idx == sorted(idx)
    np.testing.assert_allclose(tips[idx], final.tips, atol=1e-9)
    # chord: the joint-linear tip path between program points stays within 0.01 mm (+ sampling) of the chord
    J = np.asarray(p.joints)
    lam = np.linspace(0, 1, 33)[1:-1, None]
    worst = 0.0
    for s in range(len(J) - 1):
        t2, _ = npost.forward_kinematics(k, J[s] + lam * (J[s + 1] - J[s]))
        d = tips[s + 1] - tips[s]
        u = np.clip((t2 - tips[s]) @ d / max(d @ d, 1e-300), 0, 1)
        worst = max(worst, float(np.linalg.norm(t2 - tips[s] - u[:, None] * d, axis=1).max()))
    assert worst <= 0.0105, worst
    text = npost.machine_gcode(k, p)
    lines = [ln for ln in text.splitlines() if ln.startswith(("G0", "G1"))]
    assert lines[0].startswith("G0") and len(lines) == len(J)
