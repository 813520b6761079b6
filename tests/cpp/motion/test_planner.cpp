// netshape::motion: corner rules, profiles, the streaming planner and the Lee & Lee square test.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;

namespace {
toolpath::Block line(const Vec3& a, const Vec3& b, double feed) {
  toolpath::Block blk;
  blk.kind = toolpath::MotionKind::line;
  blk.start = a;
  blk.end = b;
  blk.feed = feed;
  return blk;
}
// A polyline of n lines from the origin, step(i) the i-th displacement [mm], at feed [mm/s].
template <class Step>
std::vector<toolpath::Block> polyline(int n, double feed, Step step) {
  std::vector<toolpath::Block> out;
  Vec3 p(0, 0, 0);
  for (int i = 0; i < n; ++i) {
    const Vec3 q = p + step(i);
    out.push_back(line(p, q, feed));
    p = q;
  }
  return out;
}
// 60 short lines turning in all directions at 400 mm/s, then a half circle of radius 2 mm and a line:
// corners between lines and corners next to an arc in one program.
std::vector<toolpath::Block> lines_arc_line() {
  auto prog = polyline(60, 400, [](int i) {
    return Vec3(0.4 + 0.3 * std::cos(1.7 * i), 0.5 * std::sin(2.3 * i), 0.02 * ((i % 3) - 1));
  });
  const Vec3 p = prog.back().end;
  toolpath::Block arc;
  arc.kind = toolpath::MotionKind::arc;
  arc.start = p;
  arc.center = p + Vec3(2, 0, 0);
  arc.end = p + Vec3(4, 0, 0);
  arc.clockwise = true;
  arc.feed = 400;
  prog.push_back(arc);
  prog.push_back(line(arc.end, arc.end + Vec3(0, -3, 0), 400));
  return prog;
}
std::vector<toolpath::Block> square(double feed) {
  const Vec3 p[5] = {{0, 0, 0}, {20, 0, 0}, {20, 20, 0}, {0, 20, 0}, {0, 0, 0}};
  std::vector<toolpath::Block> out;
  for (int i = 0; i < 4; ++i) out.push_back(line(p[i], p[i + 1], feed));
  return out;
}
}  // namespace

TEST_CASE("eq. 3 and 5: reach speed is sqrt(v^2 + 2 a L) for trapezoids") {
  CHECK(reach_speed(0.0, 20.0, 450.0, INFINITY) == doctest::Approx(std::sqrt(2 * 450.0 * 20.0)));
  CHECK(reach_speed(10.0, 1.0, 100.0, INFINITY) == doctest::Approx(std::sqrt(100.0 + 200.0)));
  // S-curves need more room: slower than the trapezoid, faster than the start
  const double s = reach_speed(0.0, 1.0, 1000.0, 1e5);
  CHECK(s < std::sqrt(2000.0));
  CHECK(s > 0.0);
  CHECK(ramp_distance(0.0, s, 1000.0, 1e5) == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("S-curve backward reach: every end speed from w up is reached, monotone in w, tight") {
  // Independent check by a scan of end speeds: from u = reach_back_speed(w, L, a, j) a single ramp
  // reaches every end speed in [w, u] within L, from a slightly higher start some end speed in that
  // range is out of reach, and u does not fall when w rises. Over both regimes (jerk- and
  // acceleration-bound ramps) and end speeds from rest to near the start speed.
  const double a_s[] = {500.0, 3000.0, 20000.0};
  const double j_s[] = {1e4, 1e5, 1e6, 1e7};
  const double L_s[] = {1e-3, 0.05, 1.0, 7.0, 50.0};
  const auto worst_ramp = [](double u, double w, double a, double j) {  // longest ramp to [w, u], by scan
    double d = 0;
    for (int k = 0; k <= 2000; ++k) d = std::max(d, ramp_distance(u, w + (u - w) * k / 2000.0, a, j));
    return d;
  };
  long cases = 0, non_monotone_ramps = 0;
  for (const double a : a_s)
    for (const double j : j_s)
      for (const double L : L_s) {
        double u_prev = 0;
        for (int q = 0; q <= 40; ++q) {
          const double w = 300.0 * q * q / 1600.0;  // 0 ... 300 mm/s, dense near rest
          const double u = reach_back_speed(w, L, a, j);
          CAPTURE(a);
          CAPTURE(j);
          CAPTURE(L);
          CAPTURE(w);
          CHECK(u >= w);
          CHECK(u >= u_prev * (1 - 1e-12));
          CHECK(worst_ramp(u, w, a, j) <= L * (1 + 1e-6));
          const double up = u * (1 + 1e-6) + 1e-9;
          CHECK(worst_ramp(up, w, a, j) > L);
          if (ramp_distance(u, w, a, j) < worst_ramp(u, w, a, j) * (1 - 1e-3)) ++non_monotone_ramps;
          u_prev = u;
          ++cases;
        }
      }
  CHECK(cases == 3 * 4 * 5 * 41);
  CHECK(non_monotone_ramps > 50);  // the case the bound exists for: a lower end speed, a shorter ramp
  // without a jerk limit it is Lee & Lee eq. 3 read backwards
  CHECK(reach_back_speed(10.0, 2.0, 1000.0, INFINITY) == doctest::Approx(std::sqrt(100.0 + 4000.0)));
}

TEST_CASE("jerk limits, short look-ahead: every profile covers exactly its segment, axes within limits") {
  // Long lines, each followed by a run of 0.05 mm lines: with a buffer of a few blocks the stop at its
  // end keeps the long line's end speed low (a slow-down by more than 2/3 of the speed, where a
  // jerk-bound S-curve ramp's distance grows again as its end speed rises), and each block pushed
  // raises it a little. The start speed promised to the long line must stay reachable.
  std::vector<toolpath::Block> prog;
  Vec3 p(0, 0, 0);
  double heading = 0;
  for (int r = 0; r < 12; ++r) {
    for (int i = 0; i < 61; ++i) {
      heading += i == 0 ? 0.4 + 0.1 * r : 0.01 * std::sin(0.3 * i);
      const double len = i == 0 ? 4.0 + 2.0 * r : 0.05;
      const Vec3 q = p + len * Vec3(std::cos(heading), std::sin(heading), 0.0);
      prog.push_back(line(p, q, 250.0));
      p = q;
    }
  }
  for (const double jerk : {3e4, 1e5, 1e6})
    for (const int la : {2, 4, 16})
      for (const CornerRule r : {CornerRule::vector, CornerRule::blend}) {
        PlanOptions o;
        o.rule = r;
        o.lookahead = la;
        o.tolerance = 0.01;
        AxisLimits lim = AxisLimits::uniform(250, 3000);
        lim.jerk = Vec3::Constant(jerk);
        Planner pl(lim, o);
        PlannedSegment seg;
        std::size_t i = 0;
        long segments = 0, bad = 0;
        for (Status st; (st = pl.next_segment(seg)) != Status::finished;) {
          if (st == Status::ok) {
            ++segments;
            double d = 0;
            for (const double x : seg.profile.d) d += x;
            if (std::abs(d - seg.segment.length()) > 1e-9 * std::max(1.0, seg.segment.length())) ++bad;
          } else if (i < prog.size()) {
            REQUIRE(pl.push(prog[i++]) == Status::ok);
          } else {
            pl.finish();
          }
        }
        CAPTURE(jerk);
        CAPTURE(la);
        CAPTURE(static_cast<int>(r));
        CHECK(segments >= static_cast<long>(prog.size()));
        CHECK(bad == 0);
        const auto tr = plan(prog, lim, o);
        for (int k = 0; k < 3; ++k) CHECK(tr.stats.axis_acceleration[k] <= lim.acceleration[k] * (1 + 1e-3));
      }
}

TEST_CASE("corner rules: eq. 4 against the velocity-jump bound (issue's 23x at 5 degrees)") {
  const double th = deg2rad(5.0);
  const Vec3 u1(1, 0, 0), u2(std::cos(th), std::sin(th), 0);
  CHECK(turn_angle(u1, u2) == doctest::Approx(th));
  const double paper = paper_corner_speed(1000.0, 1e-3, th);
  const double vec = vector_corner_speed(u1, u2, 1000.0, 1e-3);
  CHECK(paper / vec == doctest::Approx(2 * std::sin(th / 2) / (1 - std::cos(th))).epsilon(1e-9));
  CHECK(paper / vec == doctest::Approx(22.9).epsilon(0.01));
  // per-axis is never below the vector rule with equal limits
  CHECK(per_axis_corner_speed(u1, u2, Vec3::Constant(1000.0), 1e-3) >= vec);
  // Klipper: a 90° corner runs at the square corner velocity
  const double d = klipper_junction_deviation(5.0, 3000.0);
  CHECK(junction_deviation_speed(3000.0, d, pi / 2) == doctest::Approx(5.0));
}

TEST_CASE("junction deviation: corner speed from the turn angle (grbl's formula with θ = π − φ)") {
  // grbl (planner.c): cos θ = −u1·u2 is the angle between the two moves at the vertex and
  // v² = a·δ·sin(θ/2)/(1 − sin(θ/2)); written here from that form, at the turns φ
  const double a = 3000.0, dev = 0.01;
  auto grbl = [&](double phi) {
    const double s = std::sqrt(0.5 * (1.0 + std::cos(phi)));  // sin(θ/2), cos θ = −cos φ
    return std::sqrt(a * dev * s / (1.0 - s));
  };
  for (const double deg : {0.5, 5.7, 45.0, 84.3, 90.0, 135.0, 174.3, 179.5})
    CHECK(junction_deviation_speed(a, dev, deg2rad(deg)) == doctest::Approx(grbl(deg2rad(deg))).epsilon(1e-12));
  // gentle turns run fast, near-reversals crawl
  CHECK(junction_deviation_speed(a, dev, deg2rad(5.7)) > 150.0);
  CHECK(junction_deviation_speed(a, dev, deg2rad(174.3)) < 1.3);
  CHECK(std::isinf(junction_deviation_speed(a, dev, 0.0)));
  CHECK(junction_deviation_speed(a, dev, pi) == 0.0);
  // tiny turns: 1 − cos(φ/2) ≈ φ²/8, so v² ≈ 8·a·δ/φ²
  CHECK(junction_deviation_speed(a, dev, 1e-7) == doctest::Approx(std::sqrt(8 * a * dev) / 1e-7).epsilon(1e-6));
  // acceleration: grbl's along unit(u2 − u1) against the smallest moving-axis limit
  const Vec3 acc(3000, 1000, 500), u1(1, 0, 0), u2(0, 1, 0);
  CHECK(junction_acceleration(acc, u1, u2, JunctionAccel::min_moving_axis) == doctest::Approx(1000.0));
  CHECK(junction_acceleration(acc, u1, u2, JunctionAccel::along_change) == doctest::Approx(1000.0 * std::sqrt(2.0)));
  CHECK(junction_acceleration(Vec3::Constant(3000), u1, u2, JunctionAccel::along_change) ==
        doctest::Approx(3000.0 * std::sqrt(2.0)));
  CHECK(junction_deviation_corner_speed(u1, u2, acc, dev, JunctionAccel::along_change) ==
        doctest::Approx(std::sqrt(1000.0 * std::sqrt(2.0) * dev * std::sqrt(0.5) / (1 - std::sqrt(0.5)))));
  CHECK(parse_junction_accel("along_change") == JunctionAccel::along_change);
  CHECK_THROWS_AS(parse_junction_accel("grbl"), std::invalid_argument);
}

TEST_CASE("junction deviation: the issue's four-line program runs its corners at grbl's speeds") {
  // G1 X10 Y0 F60000, X20 Y1, X20 Y11, X19 Y1; vmax 250, amax 3000, δ = 0.01 mm: turns of 5.7°, 84.3°
  // and 174.3°, at 155.4, 9.3 and 1.25 mm/s by grbl's formula (issue 21)
  std::vector<toolpath::Block> prog;
  const Vec3 p[5] = {{0, 0, 0}, {10, 0, 0}, {20, 1, 0}, {20, 11, 0}, {19, 1, 0}};
  for (int i = 0; i < 4; ++i) prog.push_back(line(p[i], p[i + 1], 1000.0));
  const double want[3] = {155.4, 9.3, 1.25}, tol[3] = {0.05, 0.05, 0.005};
  for (const bool klipper : {false, true}) {
    PlanOptions o;
    o.rule = CornerRule::junction_deviation;
    o.junction_deviation = 0.01;
    // Klipper's mapping: scv = √(δ·a/(√2 − 1)) gives the same δ (the issue's --scv 8.51)
    o.square_corner_velocity = klipper ? std::sqrt(0.01 * 3000.0 / (std::sqrt(2.0) - 1.0)) : 0.0;
    Planner pl(AxisLimits::uniform(250, 3000), o);
    PlannedSegment ps;
    std::size_t i = 0;
    std::vector<double> ve(4, -1.0);
    for (;;) {
      const Status st = pl.next_segment(ps);
      if (st == Status::finished) break;
      if (st == Status::need_blocks) {
        while (i < prog.size() && pl.push(prog[i]) == Status::ok) ++i;
        if (i == prog.size()) pl.finish();
        continue;
      }
      ve[static_cast<std::size_t>(ps.segment.source)] = ps.profile.ve;  // the last piece of the block
    }
    for (int k = 0; k < 3; ++k) CHECK(ve[k] == doctest::Approx(want[k]).epsilon(tol[k] / want[k]));
    CHECK(ve[3] == 0.0);
  }
}

TEST_CASE("junction deviation: the corner speed is capped by both blocks' nominal speeds") {
  // a 1° turn allows ~3 m/s; the entry of the second block is capped by the slower of the two feeds
  for (const double f2 : {40.0, 200.0}) {
    PlanOptions o;
    o.rule = CornerRule::junction_deviation;
    o.junction_deviation = 0.01;
    o.square_corner_velocity = 0.0;
    const std::vector<toolpath::Block> prog = {
        line(Vec3(0, 0, 0), Vec3(50, 0, 0), 100.0),
        line(Vec3(50, 0, 0), Vec3(50 + 50 * std::cos(deg2rad(1.0)), 50 * std::sin(deg2rad(1.0)), 0), f2)};
    Planner pl(AxisLimits::uniform(250, 3000), o);
    PlannedSegment ps;
    std::size_t i = 0;
    double v_vertex = -1;
    for (;;) {
      const Status st = pl.next_segment(ps);
      if (st == Status::finished) break;
      if (st == Status::need_blocks) {
        while (i < prog.size() && pl.push(prog[i]) == Status::ok) ++i;
        if (i == prog.size()) pl.finish();
        continue;
      }
      if (ps.segment.source == 0) v_vertex = ps.profile.ve;
    }
    CHECK(v_vertex == doctest::Approx(std::min(100.0, f2)));
  }
}

TEST_CASE("Lee & Lee Fig. 12: four 20 mm blocks at right angles, corner feed = allowable difference") {
  PlanOptions o;
  o.rule = CornerRule::paper;
  o.ts1 = 4e-4;
  o.ts2 = 1e-4;
  o.allowable_speed_difference = 100.0 / 60.0;
  const auto tr = plan(square(5000.0 / 60.0), AxisLimits::uniform(5000.0 / 60.0, 450.0), o);
  // at each corner the feed falls to 100 mm/min
  for (const Vec3 c : {Vec3(20, 0, 0), Vec3(20, 20, 0), Vec3(0, 20, 0)}) {
    Eigen::Index k;
    (tr.position.rowwise() - c.transpose()).rowwise().norm().minCoeff(&k);
    CHECK(tr.feed[k] * 60.0 == doctest::Approx(100.0).epsilon(0.01));
  }
  CHECK(tr.feed.maxCoeff() == doctest::Approx(5000.0 / 60.0));
  CHECK(tr.stats.end_error == doctest::Approx(0.0));
}

TEST_CASE("streaming: push/next never throws, reports buffer_full and need_blocks, ends at the end point") {
  PlanOptions o;
  o.rule = CornerRule::vector;
  o.lookahead = 2;
  Planner p(AxisLimits::uniform(100, 1000), o);
  std::vector<toolpath::Block> blocks;
  for (int r = 0; r < 3; ++r)
    for (const auto& b : square(50.0)) blocks.push_back(b);  // 12 blocks through a buffer of ~5
  std::size_t i = 0;
  Sample s;
  int full = 0, need = 0;
  long n = 0;
  for (;;) {
    const Status st = p.next(s);
    if (st == Status::ok) {
      ++n;
      continue;
    }
    if (st == Status::finished) break;
    REQUIRE(st == Status::need_blocks);
    ++need;
    for (;;) {
      if (i == blocks.size()) {
        p.finish();
        break;
      }
      const Status ps = p.push(blocks[i]);
      if (ps == Status::buffer_full) {
        ++full;
        break;
      }
      REQUIRE(ps == Status::ok);
      ++i;
    }
  }
  CHECK(full > 0);
  CHECK(need > 0);
  CHECK((s.position - Vec3::Zero()).norm() < 1e-12);
  CHECK(p.end_time() > 0);
  toolpath::Block bad = line(Vec3(0, 0, 0), Vec3(NAN, 0, 0), 10);
  Planner q(AxisLimits::uniform(100, 1000), o);
  CHECK(q.push(bad) == Status::invalid_input);
}

TEST_CASE("vector, per-axis and blend rules respect axis limits by finite differences") {
  for (CornerRule r : {CornerRule::vector, CornerRule::per_axis, CornerRule::blend}) {
    PlanOptions o;
    o.rule = r;
    AxisLimits lim;
    lim.velocity = Vec3(100, 80, 50);
    lim.acceleration = Vec3(2000, 1500, 1000);
    const auto b = polyline(30, 200, [](int i) {
      return Vec3(std::cos(1.3 * i) * (0.3 + 0.1 * (i % 7)), std::sin(2.1 * i) * 0.5, 0.05 * ((i % 3) - 1));
    });
    const auto tr = plan(b, lim, o);
    for (int i = 0; i < 3; ++i) {
      CHECK(tr.stats.axis_velocity[i] <= lim.velocity[i] * (1 + 1e-6));
      CHECK(tr.stats.axis_acceleration[i] <= lim.acceleration[i] * (1 + 1e-3));
    }
    CHECK(tr.stats.end_error < 1e-12);
    CHECK(tr.stats.max_path_deviation <= o.tolerance * (1 + 1e-6));
  }
}

TEST_CASE("bad options and limits throw invalid_argument naming the field") {
  PlanOptions o;
  o.ts1 = 1.5e-4;  // not a multiple of ts2 = 1e-4
  CHECK_THROWS_AS(o.validate(), std::invalid_argument);
  AxisLimits l = AxisLimits::uniform(-1, 100);
  CHECK_THROWS_WITH_AS(l.validate(), doctest::Contains("limits.velocity.x"), std::invalid_argument);
  CHECK_THROWS_AS(parse_rule("fast"), std::invalid_argument);
  CHECK(parse_rule("per_axis") == CornerRule::per_axis);
  // a blend below 1 nm is numerically a sharp corner (crossed with a velocity jump): refused
  PlanOptions t;
  t.tolerance = 1e-20;
  CHECK_THROWS_WITH_AS(t.validate(), doctest::Contains("tolerance"), std::invalid_argument);
  t.tolerance = min_tolerance;
  t.corner_tolerance = 1e-9;
  CHECK_THROWS_WITH_AS(t.validate(), doctest::Contains("corner_tolerance"), std::invalid_argument);
  t.corner_tolerance = 0;
  CHECK_NOTHROW(t.validate());
}

TEST_CASE("blend rule: the segments next_segment hands out chain up and agree with next() sampling") {
  // corners between lines (one ring node whose pieces are handed out one by one) and corners next to
  // an arc (pieces as separate nodes) in one program
  PlanOptions o;
  o.rule = CornerRule::blend;
  o.lookahead = 8;
  o.tolerance = 0.01;
  const AxisLimits lim = AxisLimits::uniform(250, 3000);
  const auto prog = lines_arc_line();

  auto drive = [&](Planner& pl, auto&& take) {
    std::size_t i = 0;
    for (;;) {
      const Status st = take();
      if (st == Status::finished) break;
      if (st == Status::need_blocks) {
        while (i < prog.size() && pl.push(prog[i]) == Status::ok) ++i;
        if (i == prog.size()) pl.finish();
      }
    }
  };
  Planner a(lim, o);
  std::vector<PlannedSegment> segs;
  PlannedSegment ps;
  drive(a, [&] {
    const Status st = a.next_segment(ps);
    if (st == Status::ok) segs.push_back(ps);
    return st;
  });
  REQUIRE(segs.size() > 2 * prog.size());  // the blends are cut into pieces
  int blend_pieces = 0;
  for (std::size_t k = 0; k + 1 < segs.size(); ++k) {
    const PlannedSegment& s = segs[k];
    const PlannedSegment& n = segs[k + 1];
    if (s.segment.kind == SegmentKind::blend) ++blend_pieces;
    CHECK(std::abs(s.t0 + s.profile.duration - n.t0) <= 1e-12 * (1 + n.t0));
    CHECK(std::abs(s.profile.ve - n.profile.vs) <= 1e-9 * (1 + n.profile.vs));
    CHECK((s.segment.point_at(s.segment.length()) - n.segment.point_at(0.0)).norm() <= 1e-9);
  }
  CHECK(blend_pieces > 3 * 60);
  CHECK((segs.back().segment.point_at(segs.back().segment.length()) - prog.back().end).norm() <= 1e-9);

  // sampling: every fine sample lies where the handed-out segment running at that time puts it
  Planner b(lim, o);
  Sample smp;
  std::size_t k = 0;
  double worst = 0;
  long samples = 0;
  drive(b, [&] {
    const Status st = b.next(smp);
    if (st != Status::ok) return st;
    while (k + 1 < segs.size() && segs[k].t0 + segs[k].profile.duration <= smp.t) ++k;
    double s, v, acc;
    segs[k].profile.eval(smp.t - segs[k].t0, s, v, acc);
    worst = std::max(worst, (segs[k].segment.point_at(s) - smp.position).norm());
    ++samples;
    return st;
  });
  CHECK(samples > 1000);
  CHECK(worst <= 1e-9);
}

TEST_CASE("blend rule: every blend piece's peak speed keeps each axis within its limits along the piece") {
  // The pieces of a blend between two lines get per-axis bounds of |u_c| and |κ n_c| from their end
  // nodes only (the `bounds` of kernels/line_blend.cpp). Sample every handed-out piece densely and check that
  // at its peak speed vp the axis velocity |u_c|·vp and centripetal acceleration |κ n_c|·vp² stay
  // within V_c and A_c: a bound that missed an interior maximum would show here. Corners turn in
  // all three axes, and the limits differ per axis.
  PlanOptions o;
  o.rule = CornerRule::blend;
  o.lookahead = 16;
  o.tolerance = 0.02;
  AxisLimits lim;
  lim.velocity = Vec3(120, 80, 50);
  lim.acceleration = Vec3(2500, 1500, 700);
  const auto prog = polyline(80, 1e6, [](int i) {
    return Vec3(2.0 * std::cos(2.1 * i), 2.0 * std::sin(1.3 * i), 1.2 * std::sin(0.7 * i + 1.0));
  });
  Planner pl(lim, o);
  PlannedSegment ps;
  std::size_t i = 0;
  int pieces = 0;
  double worst_v = 0, worst_a = 0;  // largest |u_c|·vp/V_c and |κ n_c|·vp²/A_c
  for (;;) {
    const Status st = pl.next_segment(ps);
    if (st == Status::finished) break;
    if (st == Status::need_blocks) {
      while (i < prog.size() && pl.push(prog[i]) == Status::ok) ++i;
      if (i == prog.size()) pl.finish();
      continue;
    }
    if (ps.segment.kind != SegmentKind::blend) continue;
    ++pieces;
    const Segment& s = ps.segment;
    const double L = s.length(), vp = ps.profile.vp, h = 1e-4 * L;
    for (int k = 0; k <= 400; ++k) {
      const double at = L * k / 400.0;
      const Vec3 u = s.tangent_at(at);
      // curvature vector du/ds by central differences inside the whole blend (the ends of a piece
      // are interior points of the blend, except at the blend's own ends)
      const double a0 = std::max(-s.trim_start, at - h), a1 = std::min(L + s.trim_end, at + h);
      const Vec3 kv = (s.tangent_at(a1) - s.tangent_at(a0)) / (a1 - a0);
      for (int c = 0; c < 3; ++c) {
        worst_v = std::max(worst_v, std::abs(u[c]) * vp / lim.velocity[c]);
        worst_a = std::max(worst_a, std::abs(kv[c]) * vp * vp / lim.acceleration[c]);
      }
    }
  }
  REQUIRE(pieces > 100);
  CHECK(worst_v <= 1.0 + 1e-9);
  CHECK(worst_a <= 1.0 + 1e-3);  // finite differences of the tangent
  CHECK(worst_a > 0.5);          // the check bites: some piece runs near its centripetal limit
}

TEST_CASE("Planner copies and moves: a copy taken mid-stream continues with the same bits as the original") {
  static_assert(std::is_copy_constructible_v<Planner> && std::is_copy_assignable_v<Planner>);
  static_assert(std::is_nothrow_move_constructible_v<Planner> && std::is_nothrow_move_assignable_v<Planner>);
  // line-line blends (one ring node each), a blend next to an arc (separate nodes) and the arc's pieces
  PlanOptions o;
  o.rule = CornerRule::blend;
  o.lookahead = 8;
  const auto prog = lines_arc_line();

  // samples of `pl` from now to the end, pushing prog[i...] when it asks for blocks
  auto run = [&](Planner& pl, std::size_t i, std::vector<Sample>& out) {
    Sample s;
    for (;;) {
      const Status st = pl.next(s);
      if (st == Status::finished) break;
      if (st == Status::ok) {
        out.push_back(s);
        continue;
      }
      REQUIRE(st == Status::need_blocks);
      while (i < prog.size() && pl.push(prog[i]) == Status::ok) ++i;
      if (i == prog.size()) pl.finish();
    }
  };
  auto same = [](const std::vector<Sample>& a, const std::vector<Sample>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k)
      if (a[k].t != b[k].t || a[k].position != b[k].position || a[k].velocity != b[k].velocity ||
          a[k].feed != b[k].feed || a[k].block != b[k].block)
        return false;
    return true;
  };
  const AxisLimits lim = AxisLimits::uniform(250, 3000);
  std::vector<Sample> whole;
  {
    Planner ref(lim, o);
    run(ref, 0, whole);
  }
  REQUIRE(whole.size() > 1000);

  // the original up to half of the samples, then copies of it
  Planner a(lim, o);
  std::size_t i = 0;
  std::vector<Sample> head;
  Sample s;
  while (head.size() < whole.size() / 2) {
    const Status st = a.next(s);
    if (st == Status::ok) {
      head.push_back(s);
    } else {
      while (i < prog.size() && a.push(prog[i]) == Status::ok) ++i;
      if (i == prog.size()) a.finish();
    }
  }
  Planner b(a);                // copy construction
  Planner c(lim, PlanOptions{});
  c = a;                       // copy assignment over a planner with other options
  CHECK(c.options().rule == CornerRule::blend);
  std::vector<Sample> rest_a, rest_b, rest_c, rest_d;
  run(a, i, rest_a);           // the original first: the copies must not share its state
  run(b, i, rest_b);
  Planner d(std::move(c));     // moving hands the state over
  run(d, i, rest_d);
  head.insert(head.end(), rest_a.begin(), rest_a.end());
  CHECK(same(head, whole));
  CHECK(same(rest_b, rest_a));
  CHECK(same(rest_d, rest_a));
  Planner e(lim, o);
  e = std::move(d);            // move assignment of a finished planner
  CHECK(e.next(s) == Status::finished);
  CHECK(e.blocks_pushed() == static_cast<long>(prog.size()));
}
