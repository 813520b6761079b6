"""§4 tests of C.-S. Lee & J.-P. Lee, "The implement of 2-step motion control loop and look ahead algorithm
for a high speed machining" (Lee & Lee; docs/references.md): the right-angle blocks (Fig. 12) and the
three semicircles (Fig. 13–15)."""

from __future__ import annotations

import numpy as np
import pytest

import netshape.motion as nm
from netshape.motion import lookahead_lee as s


def _plan(points, feed_mm_min, rule="paper", **kw):
    lim = nm.AxisLimits.uniform(1e4, s.ACC)
    return nm.plan(points, lim, feed=feed_mm_min / 60.0, rule=rule, ts1=s.TS1, ts2=s.TS2,
                   allowable_speed_difference=s.ALLOWABLE, lookahead=100, **kw)


def _feed_at(traj, point):
    k = np.argmin(np.linalg.norm(traj.position - point, axis=1))
    return traj.feed[k] * 60.0


def test_right_angle_blocks_corner_speed_is_allowable_difference():
    """Lee & Lee §4.1, Fig. 12: 4 × 20 mm single-axis blocks at 90°, F5000, allowable difference
    100 mm/min: eq. 4 gives less than 100 mm/min at 90°, so each corner runs at 100 mm/min, and
    every block reaches F5000 in between."""
    pts = s.square_program()
    tr = _plan(pts, 5000.0)
    for c in pts[1:-1]:
        assert _feed_at(tr, c) == pytest.approx(100.0, rel=0.01)
    assert tr.feed.max() * 60 == pytest.approx(5000.0, rel=1e-9)
    assert np.all(tr.position[-1] == pts[-1])
    # eq. 4 alone at 90° is Acc·Ts1 = 0.18 mm/s = 10.8 mm/min (< 100): the floor is what acts
    assert nm.paper_corner_speed(s.ACC, s.TS1, np.pi / 2) * 60 == pytest.approx(10.8)


def test_semicircle_feeds_fall_with_radius():
    """Lee & Lee §4.2, Fig. 14(f): F4000, three semicircles of 77 micro-blocks; the paper reads the
    arc feeds as ~3000–3200, ~1100 and ~550 mm/min. With our reconstruction (radii 30/10/5 mm, 39/22/16
    chords, Acc·Ts1 = 0.18 mm/s) the junction feeds on the arcs are about 3330, 1060 and 560 mm/min; we
    require the paper's figures within 12 %."""
    pts = s.semicircle_program()
    assert len(pts) - 1 == 80
    tr = _plan(pts, 4000.0)
    start = 3 + 0  # index of the first arc vertex in pts (pts[2] is the end of the second long block)
    expect = (3200.0, 1100.0, 550.0)
    i = 3
    for n, want in zip(s.CHORDS, expect):
        inner = pts[i + 1: i + n - 1]  # vertices between chords of this semicircle
        feeds = np.array([_feed_at(tr, p) for p in inner])
        assert np.median(feeds) == pytest.approx(want, rel=0.12)
        i += n
    assert start == 3
    # long blocks reach the programmed feed (Fig. 14 b)
    assert tr.feed.max() * 60 == pytest.approx(4000.0, rel=1e-9)


def test_eq4_tangent_speed_numbers():
    """eq. 4 numbers behind the reconstruction: Acc·Ts/(1 − cos(π/n))."""
    v = [nm.paper_corner_speed(s.ACC, s.TS1, np.pi / n) * 60 for n in s.CHORDS]
    assert v == pytest.approx([3331.0, 1061.0, 562.0], rel=1e-3)


@pytest.mark.parametrize("rule", nm.RULES)
def test_every_rule_runs_the_semicircles(rule):
    tr = _plan(s.semicircle_program(), 4000.0, rule=rule)
    assert tr.stats["end_error_mm"] == 0.0
    tol = 0.01 if rule == "blend" else 1e-9
    assert tr.stats["max_path_deviation_mm"] <= tol


def test_old_module_name_is_a_deprecated_alias():
    """`netshape.motion.seeds002` still imports for one release, warns, and names the new module."""
    import importlib
    import sys

    sys.modules.pop("netshape.motion.seeds002", None)
    with pytest.warns(DeprecationWarning, match="netshape.motion.lookahead_lee"):
        old = importlib.import_module("netshape.motion.seeds002")
    assert old.semicircle_program is s.semicircle_program
    assert old.ACC == s.ACC and old.CHORDS == s.CHORDS
