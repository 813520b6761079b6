// netshape::motion: cubic Bézier blocks (cubic.hpp) in the planner: samples on the curve, cycle time
// against the arc it approximates, curvature-continuous joints under jerk limits, blended corners
// next to a cubic, invalid input.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;

namespace {
using Ctrl = std::array<Vec3, 4>;

toolpath::Block chord(const Vec3& a, const Vec3& b, double feed) {
  toolpath::Block blk;
  blk.kind = toolpath::MotionKind::line;
  blk.start = a;
  blk.end = b;
  blk.feed = feed;
  return blk;
}

// Bézier point and derivative, written out here (not the library's) for an independent check
Vec3 bz(const Ctrl& c, double u) {
  const double v = 1 - u;
  return v * v * v * c[0] + 3 * v * v * u * c[1] + 3 * v * u * u * c[2] + u * u * u * c[3];
}
Vec3 bz1(const Ctrl& c, double u) {
  const double v = 1 - u;
  return 3 * v * v * (c[1] - c[0]) + 6 * v * u * (c[2] - c[1]) + 3 * u * u * (c[3] - c[2]);
}
// distance from p to the Bézier: the nearest of 2001 parameter values, refined by Newton on
// (B(u) − p)·B'(u) = 0 with a numerical second derivative
double distance_to_bezier(const Ctrl& c, const Vec3& p) {
  double ub = 0, db = 1e300;
  for (int i = 0; i <= 2000; ++i) {
    const double u = i / 2000.0, d = (bz(c, u) - p).norm();
    if (d < db) db = d, ub = u;
  }
  double u = ub;
  for (int it = 0; it < 20; ++it) {
    const auto f = [&](double x) { return (bz(c, x) - p).dot(bz1(c, x)); };
    const double h = 1e-7, df = (f(u + h) - f(u - h)) / (2 * h);
    if (!(std::abs(df) > 0)) break;
    u = std::clamp(u - f(u) / df, 0.0, 1.0);
  }
  return std::min(db, (bz(c, u) - p).norm());
}
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

// the Bézier pieces of a uniform cubic B-spline through control points d (its knot spans): consecutive
// pieces meet with equal first and second derivatives (C², so tangent and curvature continuous)
std::vector<Ctrl> bspline_pieces(const std::vector<Vec3>& d) {
  std::vector<Ctrl> out;
  for (std::size_t i = 0; i + 3 < d.size(); ++i) {
    const Vec3 &a = d[i], &b = d[i + 1], &c = d[i + 2], &e = d[i + 3];
    out.push_back({(a + 4 * b + c) / 6, (2 * b + c) / 3, (b + 2 * c) / 3, (b + 4 * c + e) / 6});
  }
  return out;
}

void add_cubic(std::vector<toolpath::Block>& blocks, std::vector<CubicControls>& controls, const Ctrl& c,
               double feed) {
  blocks.push_back(chord(c[0], c[3], feed));
  controls.push_back({true, c[1], c[2]});
}
void add_line(std::vector<toolpath::Block>& blocks, std::vector<CubicControls>& controls, const Vec3& a, const Vec3& b,
              double feed) {
  blocks.push_back(chord(a, b, feed));
  controls.push_back({});
}
}  // namespace

TEST_CASE("cubic block: a circle quadrant as one cubic runs like the arc, every sample on the Bézier") {
  const double R = 10, k = 0.5523;
  const Ctrl c = {Vec3(R, 0, 0), Vec3(R, k * R, 0), Vec3(k * R, R, 0), Vec3(0, R, 0)};
  toolpath::Block arc;
  arc.kind = toolpath::MotionKind::arc;
  arc.start = c[0];
  arc.end = c[3];
  arc.center = Vec3::Zero();
  arc.clockwise = false;
  arc.feed = 150;
  for (const bool jerk : {false, true}) {
    CAPTURE(jerk);
    const AxisLimits lim = jerk ? AxisLimits::uniform(200, 2000, 1e5) : AxisLimits::uniform(200, 2000);
    PlanOptions o;
    const Trajectory ta = plan({arc}, lim, o);
    const Trajectory tc = plan({chord(c[0], c[3], 150)}, {{true, c[1], c[2]}}, lim, o);
    std::printf("quadrant R = 10 mm (%s): arc %.6f s, cubic %.6f s\n", jerk ? "jerk 1e5" : "no jerk",
                ta.stats.cycle_time, tc.stats.cycle_time);
    // without jerk limits both are cut into pieces with per-axis bounds: the same time within 2 %; with
    // them the arc's 16 pieces each run their own S-curve, the cubic's 4 fewer: not slower than the arc
    if (!jerk) CHECK(std::abs(tc.stats.cycle_time / ta.stats.cycle_time - 1) < 0.02);
    else CHECK(tc.stats.cycle_time <= 1.02 * ta.stats.cycle_time);
    double dmax = 0;
    for (Eigen::Index i = 0; i < tc.position.rows(); ++i)
      dmax = std::max(dmax, distance_to_bezier(c, tc.position.row(i).transpose()));
    CHECK(dmax <= 1e-6);
    // (the batch figure measures against a fine polyline of the curve: a few 1e-6 mm of chord error)
    CHECK(tc.stats.max_path_deviation <= 1e-5);
    CHECK(tc.stats.end_error < 1e-12);
    CHECK((tc.block.array() == 0).all());
    for (int i = 0; i < 3; ++i) CHECK(tc.stats.axis_acceleration[i] <= 2000 * 1.005);
  }
}

namespace {
// the segments the planner hands out for one cubic block from rest to rest (its pieces)
long planned_pieces(const Ctrl& c, const AxisLimits& lim, double feed) {
  Planner p(lim, PlanOptions{});
  REQUIRE(p.push(chord(c[0], c[3], feed), CubicControls{true, c[1], c[2]}) == Status::ok);
  p.finish();
  PlannedSegment seg;
  long n = 0;
  while (p.next_segment(seg) == Status::ok) ++n;
  return n;
}
}  // namespace

TEST_CASE("cubic block: pieces of two table intervals where the curve turns little and its curvature is even") {
  // Without jerk limits a strongly curved cubic is cut into 16 pieces, or into 8 where every pair of
  // table intervals turns by at most 0.05 rad and either its curvature varies by at most 3 % over each
  // pair or the centripetal part takes at most twice the axis budget. Arcs of radius R and sweep phi
  // as one cubic (handles 4/3·tan(phi/4)·R; curvature within ~1e-5 of 1/R for phi <= 0.3; a pair turns
  // by phi/8: 0.031, 0.038, 0.075 and 0.196 rad, so the last two keep 16 pieces); the same
  // curve split in two halves (de Casteljau at u = 1/2: twice as many pieces over it, joined with
  // equal tangent and curvature) is faster by at most 0.5 % with 8 pieces (1 % with 16: a quarter
  // circle's 16 pieces against 32); and the arc block itself takes the same time within 2 %.
  const AxisLimits lim = AxisLimits::uniform(250, 3000);
  struct Case {
    double R, phi;
    long pieces;
  };
  for (const Case k : {Case{2.0, 0.25, 8}, Case{1.0, 0.3, 8}, Case{0.5, 0.6, 16}, Case{10.0, M_PI / 2, 16}}) {
    CAPTURE(k.R);
    CAPTURE(k.phi);
    const double h = 4.0 / 3.0 * std::tan(k.phi / 4) * k.R;
    const Vec3 a(k.R, 0, 0), b(k.R * std::cos(k.phi), k.R * std::sin(k.phi), 0);
    const Ctrl c = {a, a + Vec3(0, h, 0), b - h * Vec3(-std::sin(k.phi), std::cos(k.phi), 0), b};
    CHECK(planned_pieces(c, lim, 250) == k.pieces);
    const Vec3 m01 = (c[0] + c[1]) / 2, m12 = (c[1] + c[2]) / 2, m23 = (c[2] + c[3]) / 2;
    const Vec3 q1 = (m01 + m12) / 2, q2 = (m12 + m23) / 2, mid = (q1 + q2) / 2;
    std::vector<toolpath::Block> halves;
    std::vector<CubicControls> controls;
    add_cubic(halves, controls, {c[0], m01, q1, mid}, 250);
    add_cubic(halves, controls, {mid, q2, m23, c[3]}, 250);
    toolpath::Block arc = chord(a, b, 250);
    arc.kind = toolpath::MotionKind::arc;
    arc.center = Vec3::Zero();
    const Trajectory tc = plan({chord(a, b, 250)}, {{true, c[1], c[2]}}, lim, PlanOptions{});
    const Trajectory th = plan(halves, controls, lim, PlanOptions{});
    const Trajectory ta = plan({arc}, lim, PlanOptions{});
    std::printf("arc R %.1f mm, %.2f rad: %ld pieces, cubic %.6f s, halves %.6f s, arc %.6f s\n", k.R, k.phi,
                k.pieces, tc.stats.cycle_time, th.stats.cycle_time, ta.stats.cycle_time);
    CHECK(tc.stats.cycle_time <= (k.pieces == 8 ? 1.005 : 1.01) * th.stats.cycle_time);
    CHECK(std::abs(tc.stats.cycle_time / ta.stats.cycle_time - 1) < 0.02);
  }
  // a 0.5 mm cubic whose curvature grows from 0.28 to 0.56 /mm (~9 % per pair, at most 0.035 rad per
  // pair): the centripetal part at 250 mm/s is ~12 times the budget
  const Ctrl uneven = {Vec3(0, 0, 0), Vec3(0.17, 0, 0), Vec3(0.34, 0.012, 0), Vec3(0.5, 0.045, 0)};
  CHECK(planned_pieces(uneven, lim, 250) == 16);
}

TEST_CASE("cubic blocks: a C2 B-spline chain under jerk limits is not slowed at its joints") {
  std::vector<Vec3> d;
  for (int j = 0; j <= 22; ++j) d.emplace_back(3.0 * j, 2.5 * std::sin(0.8 * j), 0.4 * std::cos(0.5 * j));
  const auto pieces = bspline_pieces(d);
  // the same chain with the curvature changed at every joint: the left piece's P2 moved along the
  // joint tangent (still tangent-continuous, no longer curvature-continuous)
  auto g1 = pieces;
  for (std::size_t i = 0; i + 1 < g1.size(); ++i) g1[i][2] = g1[i][3] - 1.4 * (g1[i][3] - g1[i][2]);
  // and with the curvature off by ~1e-8 relative at every joint, as a fitted spline's rounded pieces:
  // still a curvature-continuous chain to the planner
  auto g2r = pieces;
  for (std::size_t i = 0; i + 1 < g2r.size(); ++i) g2r[i][2] = g2r[i][3] - (1 + 1e-8) * (g2r[i][3] - g2r[i][2]);
  const double J = 2e5;
  const AxisLimits lim = AxisLimits::uniform(300, 3000, J);
  for (CornerRule r : {CornerRule::vector, CornerRule::blend}) {
    CAPTURE(static_cast<int>(r));
    PlanOptions o;
    o.rule = r;
    double t[3];
    for (int which = 0; which < 3; ++which) {
      std::vector<toolpath::Block> blocks;
      std::vector<CubicControls> controls;
      for (const Ctrl& c : which == 0 ? pieces : which == 1 ? g1 : g2r) add_cubic(blocks, controls, c, 300);
      const Trajectory tr = plan(blocks, controls, lim, o, which == 0);
      t[which] = tr.stats.cycle_time;
      for (int i = 0; i < 3; ++i) {
        CHECK(tr.stats.axis_jerk[i] <= J * 1.02);
        CHECK(tr.stats.axis_acceleration[i] <= 3000 * 1.005);
      }
      if (which == 0) CHECK(tr.stats.max_path_deviation <= 1e-5);
    }
    std::printf("B-spline chain, jerk %.0e (rule %d): G2 %.6f s, G1 %.6f s\n", J, static_cast<int>(r), t[0], t[1]);
    CHECK(t[0] < 0.9 * t[1]);
    CHECK(std::abs(t[2] / t[0] - 1) < 1e-3);
  }
}

TEST_CASE("cubic block between two lines at corners: the blend rule blends both corners within the tolerance") {
  // a line along +y, a cubic leaving at (4, 1) and ending along +x, a line along +y again (90°)
  const Ctrl c = {Vec3(0, 0, 0), Vec3(4, 1, 0), Vec3(8, 0, 0), Vec3(12, 0, 0)};
  std::vector<toolpath::Block> blocks;
  std::vector<CubicControls> controls;
  add_line(blocks, controls, Vec3(0, -10, 0), c[0], 200);
  add_cubic(blocks, controls, c, 200);
  add_line(blocks, controls, c[3], c[3] + Vec3(0, 10, 0), 200);
  for (const bool jerk : {false, true}) {
    CAPTURE(jerk);
    const Vec3 A(2000, 1500, 1000);
    AxisLimits lim;
    lim.velocity = Vec3(200, 150, 100);
    lim.acceleration = A;
    if (jerk) lim.jerk = Vec3::Constant(1e5);
    PlanOptions o;
    o.rule = CornerRule::blend;
    o.tolerance = 0.02;
    const Trajectory tr = plan(blocks, controls, lim, o);
    double dmax = 0;
    bool rounded_first = false, rounded_second = false;
    for (Eigen::Index i = 0; i < tr.position.rows(); ++i) {
      const Vec3 p = tr.position.row(i).transpose();
      const double d = std::min({distance_to_segment(p, blocks[0].start, blocks[0].end), distance_to_bezier(c, p),
                                 distance_to_segment(p, blocks[2].start, blocks[2].end)});
      dmax = std::max(dmax, d);
      // a sample off both pieces next to a corner: the corner was blended
      if ((p - c[0]).norm() < 1 && d > 1e-4) rounded_first = true;
      if ((p - c[3]).norm() < 1 && d > 1e-4) rounded_second = true;
    }
    CHECK(dmax <= o.tolerance * (1 + 1e-3));
    CHECK(rounded_first);
    CHECK(rounded_second);
    CHECK(tr.stats.max_path_deviation <= o.tolerance * (1 + 1e-3));
    for (int i = 0; i < 3; ++i) CHECK(tr.stats.axis_acceleration[i] <= A[i] * 1.005);
    CHECK(tr.stats.end_error < 1e-12);
    // every block shows up in the samples' block index, in order
    CHECK(tr.block[0] == 0);
    CHECK(tr.block[tr.block.size() - 1] == 2);
    CHECK(std::is_sorted(tr.block.data(), tr.block.data() + tr.block.size()));
    CHECK((tr.block.array() == 1).any());
  }
}

TEST_CASE("two cubic blocks at a corner: the blend trims both curves and stays within the tolerance") {
  // the first ends along (3, -2), the second starts along (2, 3); then a line tangent to the second
  const Ctrl c1 = {Vec3(0, 0, 0), Vec3(3, 2, 0), Vec3(6, 2, 0), Vec3(9, 0, 0)};
  const Ctrl c2 = {Vec3(9, 0, 0), Vec3(11, 3, 0), Vec3(14, 4, 0.5), Vec3(18, 4, 0.5)};
  std::vector<toolpath::Block> blocks;
  std::vector<CubicControls> controls;
  add_cubic(blocks, controls, c1, 200);
  add_cubic(blocks, controls, c2, 200);
  add_line(blocks, controls, c2[3], c2[3] + Vec3(10, 0, 0), 200);
  for (const bool jerk : {false, true}) {
    CAPTURE(jerk);
    const AxisLimits lim = jerk ? AxisLimits::uniform(250, 3000, 1e5) : AxisLimits::uniform(250, 3000);
    PlanOptions o;
    o.rule = CornerRule::blend;
    const Trajectory tr = plan(blocks, controls, lim, o, false);
    double dmax = 0, at_corner = 0;
    for (Eigen::Index i = 0; i < tr.position.rows(); ++i) {
      const Vec3 p = tr.position.row(i).transpose();
      const double d = std::min({distance_to_bezier(c1, p), distance_to_bezier(c2, p),
                                 distance_to_segment(p, blocks[2].start, blocks[2].end)});
      dmax = std::max(dmax, d);
      if ((p - c1[3]).norm() < 0.5) at_corner = std::max(at_corner, d);
    }
    CHECK(dmax <= o.tolerance * (1 + 1e-3));
    CHECK(at_corner > 0.2 * o.tolerance);  // the corner was rounded, not run through
    for (int i = 0; i < 3; ++i) CHECK(tr.stats.axis_acceleration[i] <= 3000 * 1.005);
    CHECK(tr.stats.end_error < 1e-12);
  }
}

TEST_CASE("cubic block: invalid input is refused naming the field") {
  PlanOptions o;
  Planner p(AxisLimits::uniform(100, 1000), o);
  toolpath::Block arc;
  arc.kind = toolpath::MotionKind::arc;
  arc.start = Vec3(1, 0, 0);
  arc.end = Vec3(0, 1, 0);
  arc.center = Vec3::Zero();
  arc.feed = 50;
  CHECK(p.push(arc, {true, Vec3(1, 0.5, 0), Vec3(0.5, 1, 0)}) == Status::invalid_input);
  CHECK(std::string(p.last_error()).find("kind") != std::string::npos);
  const toolpath::Block l = chord(Vec3(0, 0, 0), Vec3(3, 0, 0), 50);
  CHECK(p.push(l, {true, Vec3(1, std::nan(""), 0), Vec3(2, 1, 0)}) == Status::invalid_input);
  CHECK(std::string(p.last_error()).find("c1") != std::string::npos);
  CHECK(p.push(l, {true, Vec3(1, 1, 0), Vec3(2, INFINITY, 0)}) == Status::invalid_input);
  CHECK(std::string(p.last_error()).find("c2") != std::string::npos);
  CHECK(p.blocks_pushed() == 0);
  // controls.cubic false: the block as it is (an arc stays an arc)
  CHECK(p.push(arc, CubicControls{}) == Status::ok);
  CHECK(p.blocks_pushed() == 1);
  // the batch API names the block
  try {
    plan({l}, {{true, Vec3(1, 1, 0), Vec3(std::nan(""), 0, 0)}}, AxisLimits::uniform(100, 1000), o);
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("controls[0]: c2") != std::string::npos);
  }
  CHECK_THROWS_AS(plan({l, l}, {CubicControls{}}, AxisLimits::uniform(100, 1000), o), std::invalid_argument);
}

TEST_CASE("blend rule: corner_tolerance between programmed pieces, tolerance next to cubic blocks") {
  // two lines at 90°, then a cubic leaving the second line at an angle, then a line at 90° again
  const Ctrl c = {Vec3(10, 10, 0), Vec3(14, 11, 0), Vec3(18, 10, 0), Vec3(22, 10, 0)};
  std::vector<toolpath::Block> blocks;
  std::vector<CubicControls> controls;
  add_line(blocks, controls, Vec3(0, 0, 0), Vec3(10, 0, 0), 200);
  add_line(blocks, controls, Vec3(10, 0, 0), c[0], 200);
  add_cubic(blocks, controls, c, 200);
  add_line(blocks, controls, c[3], c[3] + Vec3(0, 10, 0), 200);
  const AxisLimits lim = AxisLimits::uniform(200, 2000);
  PlanOptions o;
  o.rule = CornerRule::blend;
  o.tolerance = 0.002;
  o.corner_tolerance = 0.02;
  // lines only: the plan at corner_tolerance is the plan at that tolerance, sample for sample
  PlanOptions whole = o;
  whole.tolerance = 0.02;
  whole.corner_tolerance = 0;
  const std::vector<toolpath::Block> lines(blocks.begin(), blocks.begin() + 2);
  const Trajectory ta = plan(lines, lim, o), tb = plan(lines, lim, whole);
  CHECK(ta.stats.cycle_time == tb.stats.cycle_time);
  CHECK(ta.position == tb.position);
  // with the cubic: the line-line corner uses more than the tolerance, the corners at the cubic not
  const Trajectory tr = plan(blocks, controls, lim, o);
  double d_lines = 0, d_cubic = 0;
  for (Eigen::Index i = 0; i < tr.position.rows(); ++i) {
    const Vec3 p = tr.position.row(i).transpose();
    const double d = std::min({distance_to_segment(p, blocks[0].start, blocks[0].end),
                               distance_to_segment(p, blocks[1].start, blocks[1].end), distance_to_bezier(c, p),
                               distance_to_segment(p, blocks[3].start, blocks[3].end)});
    if ((p - Vec3(10, 0, 0)).norm() < 2) d_lines = std::max(d_lines, d);
    if ((p - c[0]).norm() < 2 || (p - c[3]).norm() < 2) d_cubic = std::max(d_cubic, d);
  }
  CHECK(d_lines > 0.002 * 2);
  CHECK(d_lines <= 0.02 * (1 + 1e-3));
  CHECK(d_cubic <= 0.002 * (1 + 1e-3));
}
