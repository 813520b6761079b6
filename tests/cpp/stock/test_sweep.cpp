#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "netshape/stock/sweep.hpp"

using netshape::MatrixXdR;
using netshape::Points3;
using netshape::Vec3;
using netshape::cutter::Cutter;
using netshape::stock::SweepOptions;
using netshape::stock::TipProfile;
using netshape::stock::ZMap;
using netshape::toolpath::Block;
using netshape::toolpath::MotionKind;

namespace {
const double inf = std::numeric_limits<double>::infinity();

// Independent reference: lowest reach of the tip surface above (x, y) from n + 1 samples along
// the move, each using the profile g(d) = r_c − sqrt(r_c² − (d − a)²) directly.
template <class PointAt>
double sampled_reach(const Cutter& c, PointAt&& point_at, double x, double y, int n) {
  const double R = c.radius;
  const double rc = c.kind == netshape::cutter::CutterKind::flat ? 0.0 : c.corner_radius;
  const double a = R - rc;
  double best = inf;
  for (int k = 0; k <= n; ++k) {
    const Vec3 p = point_at(static_cast<double>(k) / n);
    const double d = std::hypot(x - p.x(), y - p.y());
    if (d > R) continue;
    const double g = d <= a ? 0.0 : rc - std::sqrt(std::max(0.0, rc * rc - (d - a) * (d - a)));
    best = std::min(best, p.z() + g);
  }
  return best;
}

Block arc_block(Vec3 c, double r, double a0, double a1, double z0, double z1, bool cw) {
  Block b;
  b.kind = MotionKind::arc;
  b.center = Vec3(c.x(), c.y(), z0);
  b.start = Vec3(c.x() + r * std::cos(a0), c.y() + r * std::sin(a0), z0);
  b.end = Vec3(c.x() + r * std::cos(a1), c.y() + r * std::sin(a1), z1);
  b.clockwise = cw;
  b.feed = 10.0;
  return b;
}
}  // namespace

TEST_CASE("sweep: a flat end mill along a line leaves a slot of exact width and depth") {
  ZMap z(0.0, 30.0, 0.0, 20.0, 0.05, 10.0, 0.0);
  const Cutter c = Cutter::flat_end(6.0, 2, 0.5);
  const auto st = netshape::stock::sweep_line(z, c, Vec3(-5.0, 10.0, 8.0), Vec3(35.0, 10.0, 8.0));
  int lowered = 0, bad = 0;
  for (int i = 0; i < z.ny(); ++i)
    for (int j = 0; j < z.nx(); ++j) {
      const double expect = std::abs(z.node_y(i) - 10.0) <= 3.0 ? 8.0 : 10.0;
      lowered += expect < 10.0;
      bad += z.heights()(i, j) != expect;
    }
  CHECK(bad == 0);
  CHECK(st.nodes_lowered == lowered);
  CHECK(st.removed_volume == doctest::Approx(lowered * 2.0 * z.dx() * z.dy()));
  CHECK(z.volume() == doctest::Approx(30.0 * 20.0 * 10.0 - st.removed_volume));
  // a partial slot ends in a half circle around the end point
  ZMap e(0.0, 30.0, 0.0, 20.0, 0.1, 10.0, 0.0);
  bad = 0;
  netshape::stock::sweep_line(e, c, Vec3(-5.0, 10.0, 8.0), Vec3(15.0, 10.0, 8.0));
  for (int i = 0; i < e.ny(); ++i)
    for (int j = 0; j < e.nx(); ++j) {
      const double x = e.node_x(j), y = e.node_y(i);
      const bool in = (x <= 15.0 && std::abs(y - 10.0) <= 3.0) || std::hypot(x - 15.0, y - 10.0) <= 3.0;
      bad += e.heights()(i, j) != (in ? 8.0 : 10.0);
    }
  CHECK(bad == 0);
}

TEST_CASE("sweep: ball end mill leaves the exact profile R - sqrt(R^2 - d^2) across the path") {
  ZMap z(0.0, 30.0, 0.0, 20.0, 0.05, 10.0, 0.0);
  const Cutter c = Cutter::ball_end(8.0, 2, 0.5);
  // diagonal path: the cross profile depends only on the distance from the line
  const Vec3 a(-5.0, -3.0, 7.0), b(35.0, 27.0, 7.0);
  netshape::stock::sweep_line(z, c, a, b);
  const Vec3 u = (b - a).normalized();
  double worst = 0.0;
  for (int i = 0; i < z.ny(); ++i)
    for (int j = 0; j < z.nx(); ++j) {
      const Vec3 q(z.node_x(j), z.node_y(i), 7.0);
      const double d = ((q - a) - (q - a).dot(u) * u).norm();
      const double expect = d <= 4.0 ? std::min(10.0, 7.0 + 4.0 - std::sqrt(16.0 - d * d)) : 10.0;
      worst = std::max(worst, std::abs(z.heights()(i, j) - expect));
    }
  CHECK(worst < 1e-12);
  // scallop between two passes 2 mm apart: cusp height R - sqrt(R^2 - (s/2)^2) mid-way
  ZMap s(0.0, 20.0, -0.025, 20.025, 0.05, 10.0, 0.0);  // a node row at y = 10
  netshape::stock::sweep_line(s, c, Vec3(-5.0, 9.0, 6.0), Vec3(25.0, 9.0, 6.0));
  netshape::stock::sweep_line(s, c, Vec3(25.0, 11.0, 6.0), Vec3(-5.0, 11.0, 6.0));
  CHECK(s.cell_height(10.0, 10.0) == doctest::Approx(6.0 + 4.0 - std::sqrt(16.0 - 1.0)).epsilon(1e-12));
  CHECK(s.height_at(10.0, 10.0) == doctest::Approx(6.0 + 4.0 - std::sqrt(15.0)).epsilon(1e-9));
}

TEST_CASE("sweep: bull-nose profile: flat centre, torus corner") {
  ZMap z(0.0, 30.0, 0.0, 20.0, 0.05, 10.0, 0.0);
  const Cutter c = Cutter::bull_nose(10.0, 2.0, 4, 0.5);  // R = 5, r_c = 2, a = 3
  netshape::stock::sweep_line(z, c, Vec3(-5.0, 10.0, 8.0), Vec3(35.0, 10.0, 8.0));
  for (int i = 0; i < z.ny(); ++i) {
    const double d = std::abs(z.node_y(i) - 10.0);
    double expect = 10.0;
    if (d <= 3.0) expect = 8.0;
    else if (d <= 5.0) expect = std::min(10.0, 8.0 + 2.0 - std::sqrt(4.0 - (d - 3.0) * (d - 3.0)));
    for (int j = 0; j < z.nx(); j += 37) REQUIRE(z.heights()(i, j) == doctest::Approx(expect).epsilon(1e-12));
  }
}

TEST_CASE("sweep: a ramp leaves a linearly varying floor; plunges drill a flat hole") {
  ZMap z(0.0, 40.0, 0.0, 20.0, 0.1, 10.0, 0.0);
  const Cutter c = Cutter::flat_end(6.0, 2, 0.5);
  // descending ramp from z = 10 at x = 0 to z = 4 at x = 30: slope -0.2
  netshape::stock::sweep_line(z, c, Vec3(0.0, 10.0, 10.0), Vec3(30.0, 10.0, 4.0));
  // at distance s from the path the lowest reach is where the cutter's front edge passes the
  // node: x_axis = x + sqrt(R² − s²); the floor falls linearly with x
  int bad = 0;
  for (int i = 0; i < z.ny(); ++i) {
    const double s = std::abs(z.node_y(i) - 10.0);
    if (s > 3.0) continue;
    const double rho = std::sqrt(9.0 - s * s);
    for (int j = 0; j < z.nx(); ++j) {
      const double x = z.node_x(j);
      const double expect = x <= 30.0 + rho ? std::min(10.0, 10.0 - 0.2 * std::min(30.0, x + rho)) : 10.0;
      bad += std::abs(z.heights()(i, j) - expect) > 1e-12;
    }
  }
  CHECK(bad == 0);
  // plunge
  ZMap p(0.0, 20.0, 0.0, 20.0, 0.1, 10.0, 0.0);
  netshape::stock::sweep_line(p, c, Vec3(10.0, 10.0, 12.0), Vec3(10.0, 10.0, 3.0));
  CHECK(p.cell_height(10.05, 10.05) == 3.0);
  CHECK(p.cell_height(12.95, 10.05) == 3.0);
  CHECK(p.cell_height(13.05, 10.05) == 10.0);
  // a cut through the stock stops at the bottom
  netshape::stock::sweep_line(p, c, Vec3(2.0, 2.0, -5.0), Vec3(18.0, 2.0, -5.0));
  CHECK(p.cell_height(10.05, 2.05) == 0.0);
  CHECK(p.min_height() == 0.0);
}

TEST_CASE("sweep: arcs in the XY plane, planar and helical") {
  const Cutter flat = Cutter::flat_end(4.0, 2, 0.5);
  const Cutter ball = Cutter::ball_end(4.0, 2, 0.5);
  // quarter circle r = 8 about (10, 10), counter-clockwise from 0 to 90°, z = 7
  const Block q = arc_block(Vec3(10, 10, 0), 8.0, 0.0, 0.5 * netshape::pi, 7.0, 7.0, false);
  ZMap zf(0.0, 30.0, 0.0, 30.0, 0.1, 10.0, 0.0), zb = zf;
  int bad = 0;
  netshape::stock::sweep_block(zf, flat, q);
  netshape::stock::sweep_block(zb, ball, q);
  for (int i = 0; i < zf.ny(); ++i)
    for (int j = 0; j < zf.nx(); ++j) {
      const double x = zf.node_x(j) - 10.0, y = zf.node_y(i) - 10.0;
      const double rho = std::hypot(x, y), ang = std::atan2(y, x);
      if (ang > 0.05 && ang < 0.5 * netshape::pi - 0.05) {  // inside the angular range, away from the ends
        const double d = std::abs(rho - 8.0);
        bad += zf.heights()(i, j) != (d <= 2.0 ? 7.0 : 10.0);
        const double eb = d <= 2.0 ? std::min(10.0, 7.0 + 2.0 - std::sqrt(4.0 - d * d)) : 10.0;
        bad += std::abs(zb.heights()(i, j) - eb) > 1e-12;
      }
    }
  CHECK(bad == 0);
  // helical arcs (both senses) and full turns against dense sampling
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (const Cutter& c : {flat, ball, Cutter::bull_nose(4.0, 0.8, 2, 0.5)}) {
    for (int t = 0; t < 6; ++t) {
      const double r = 0.5 + 9.0 * U(rng);  // includes r < R (helical hole making)
      const double a0 = 6.28 * U(rng);
      const double sweep = (t == 5 ? 2.6 : 0.3 + 5.5 * U(rng)) * (t % 2 ? -1.0 : 1.0);
      Block b = arc_block(Vec3(15, 15, 0), r, a0, a0 + sweep, 9.0, 9.0 - 3.0 * U(rng) + (t == 3 ? 4.0 : 0.0), sweep < 0);
      if (t == 5) b.turns = 2;
      ZMap z(0.0, 30.0, 0.0, 30.0, 0.25, 12.0, 0.0);
      netshape::stock::sweep_block(z, c, b);
      double worst_above = 0.0, worst_below = 0.0;
      const int n = 4000;
      const double step = b.length() / n;
      std::vector<Vec3> samples(n + 1);
      for (int k = 0; k <= n; ++k) samples[k] = b.point_at(static_cast<double>(k) / n);
      for (int i = 0; i < z.ny(); i += 8)
        for (int j = 0; j < z.nx(); j += 8) {
          const double s = std::min(12.0, sampled_reach(c, [&](double u) { return samples[std::lround(u * n)]; }, z.node_x(j),
                                                        z.node_y(i), n));
          const double e = z.heights()(i, j);
          worst_above = std::max(worst_above, e - s);
          worst_below = std::max(worst_below, s - e);
        }
      CAPTURE(t);
      CHECK(worst_above <= 1e-9);     // exact is never above the sampled envelope
      CHECK(worst_below <= step + std::sqrt(2.0 * c.radius * step));  // and within the sampling error
    }
  }
}

TEST_CASE("sweep: random lines, exact envelope against dense sampling") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const Cutter cutters[] = {Cutter::flat_end(6.0, 2, 0.5), Cutter::ball_end(6.0, 2, 0.5),
                            Cutter::bull_nose(6.0, 1.0, 2, 0.5)};
  for (const Cutter& c : cutters) {
    const TipProfile prof = TipProfile::of(c);
    double sum_err = 0.0;
    int count = 0;
    for (int t = 0; t < 24; ++t) {
      Vec3 a(30 * U(rng), 30 * U(rng), 10 * U(rng));
      Vec3 b(30 * U(rng), 30 * U(rng), 10 * U(rng));
      if (t % 8 == 0) b = Vec3(a.x(), a.y(), b.z());                   // plunge
      if (t % 8 == 1) b = Vec3(b.x(), b.y(), a.z());                   // horizontal
      if (t % 8 == 2) b = Vec3(a.x() + 0.3 * U(rng), a.y(), b.z());   // steep ramp
      const int n = 4000;
      std::vector<Vec3> samples(n + 1);
      for (int k = 0; k <= n; ++k) samples[k] = a + (static_cast<double>(k) / n) * (b - a);
      for (int k = 0; k < 40; ++k) {
        const double x = a.x() + (b.x() - a.x()) * U(rng) + 8 * (U(rng) - 0.5);
        const double y = a.y() + (b.y() - a.y()) * U(rng) + 8 * (U(rng) - 0.5);
        const double e = netshape::stock::lowest_reach_line(prof, a, b, x, y);
        const double s = sampled_reach(c, [&](double u) { return samples[std::lround(u * n)]; }, x, y, n);
        if (std::isinf(s)) {
          // never under the cutter at a sample: exact may only reach it between samples, near the edge
          if (!std::isinf(e)) {
            const Vec3 d = b - a;
            const double t0 = std::clamp(((x - a.x()) * d.x() + (y - a.y()) * d.y()) /
                                             std::max(1e-300, d.x() * d.x() + d.y() * d.y()), 0.0, 1.0);
            CHECK(std::hypot(x - a.x() - t0 * d.x(), y - a.y() - t0 * d.y()) <= c.radius + 1e-9);
          }
          continue;
        }
        REQUIRE(e <= s + 1e-9);
        const double step = (b - a).norm() / n;
        CHECK(s - e <= step + std::sqrt(2.0 * c.radius * step) + 1e-12);
        sum_err += s - e;
        ++count;
      }
    }
    CHECK(count > 300);
    CHECK(sum_err / count < 1e-3);
  }
}

TEST_CASE("sweep: programs, collinear merging and chorded arcs give the same heights") {
  const Cutter c = Cutter::ball_end(6.0, 2, 0.5);
  netshape::toolpath::Toolpath prog;
  // 1 mm blocks along two rows, a rapid above the stock, and an arc in the ZX plane
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 20; ++k) {
      Block b;
      b.kind = MotionKind::line;
      const double y = 5.0 + 4.0 * row;
      b.start = Vec3(k, y, 8.0);
      b.end = Vec3(k + 1.0, y, 8.0);
      b.feed = 10;
      prog.blocks.push_back(b);
    }
  Block r;
  r.kind = MotionKind::rapid;
  r.start = Vec3(20, 9, 8);
  r.end = Vec3(20, 9, 20);
  prog.blocks.push_back(r);
  Block zx;
  zx.kind = MotionKind::arc;
  zx.plane = netshape::toolpath::Plane::zx;
  zx.start = Vec3(5, 14, 9.5);
  zx.end = Vec3(15, 14, 9.5);
  zx.center = Vec3(10, 14, 9.5);  // half circle dipping to z = 4.5 in the ZX plane
  zx.clockwise = true;  // through angle π of the (Z, X) plane: the bottom
  prog.blocks.push_back(zx);

  ZMap merged(0.0, 20.0, 0.0, 20.0, 0.1, 10.0, 0.0), single = merged;
  SweepOptions o;
  const auto sm = netshape::stock::sweep(merged, c, prog, o);
  o.merge_collinear = false;
  const auto ss = netshape::stock::sweep(single, c, prog, o);
  CHECK(sm.moves < ss.moves);
  CHECK(sm.nodes_visited < ss.nodes_visited);
  CHECK((merged.heights() - single.heights()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(sm.removed_volume == doctest::Approx(ss.removed_volume));
  CHECK(sm.rapids_cutting == 0);
  // the ZX half circle: lowest point z = 9.5 - 5 = 4.5 at x = 10, within the chord tolerance
  CHECK(merged.cell_height(10.05, 14.05) == doctest::Approx(4.5 + 3.0 - std::sqrt(9.0 - 0.05 * 0.05 * 2)).epsilon(2e-3));

  // polyline fast path equals per-block sweeps
  Points3 pts(21, 3);
  for (int k = 0; k <= 20; ++k) pts.row(k) << k, 5.0, 8.0;
  ZMap p(0.0, 20.0, 0.0, 20.0, 0.1, 10.0, 0.0), b = p;
  netshape::stock::sweep_polyline(p, c, pts);
  for (int k = 0; k < 20; ++k) netshape::stock::sweep_block(b, c, prog.blocks[k]);
  CHECK((p.heights() - b.heights()).cwiseAbs().maxCoeff() < 1e-12);

  // a rapid through material is reported
  ZMap crash(0.0, 20.0, 0.0, 20.0, 0.5, 10.0, 0.0);
  Block g0 = r;
  g0.start = Vec3(0, 10, 5);
  g0.end = Vec3(20, 10, 5);
  CHECK(netshape::stock::sweep_block(crash, c, g0).rapids_cutting == 1);
  o.include_rapids = false;
  ZMap safe(0.0, 20.0, 0.0, 20.0, 0.5, 10.0, 0.0);
  CHECK(netshape::stock::sweep_block(safe, c, g0, o).nodes_lowered == 0);
}

TEST_CASE("sweep: moves outside the footprint touch nothing; bad input is rejected") {
  ZMap z(0.0, 10.0, 0.0, 10.0, 0.1, 10.0, 0.0);
  const Cutter c = Cutter::flat_end(6.0, 2, 0.5);
  const auto st = netshape::stock::sweep_line(z, c, Vec3(50, 50, 0), Vec3(80, -40, 0));
  CHECK(st.nodes_visited == 0);
  CHECK(netshape::stock::sweep_line(z, c, Vec3(1e12, 0, 0), Vec3(-1e12, 1e12, 0)).nodes_lowered >= 0);
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_line(z, c, Vec3(std::nan(""), 0, 0), Vec3(1, 1, 1)),
                       doctest::Contains("line.start"), std::invalid_argument);
  Cutter bad = c;
  bad.radius = 0.0;
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_line(z, bad, Vec3(0, 0, 0), Vec3(1, 1, 1)),
                       doctest::Contains("cutter.radius"), std::invalid_argument);
  Points3 none(0, 3);
  CHECK_THROWS_AS(netshape::stock::sweep_polyline(z, c, none), std::invalid_argument);
  SweepOptions o;
  o.chord_tolerance = 0.0;
  Block b;
  b.end = Vec3(1, 0, 0);
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_block(z, c, b, o), doctest::Contains("sweep.chord_tolerance"),
                       std::invalid_argument);
  CHECK((z.heights().array() == 10.0).all());
}

TEST_CASE("sweep: the SIMD row kernels over the stadium rows equal the per-node kernel over the bounding box") {
  // Every node of the grid (the whole bounding box and beyond) is compared with the scalar per-node
  // kernel; moves of every kind (ramps up and down, level, plunges, steep, along the axes) and on
  // stock that earlier moves have already cut, so that skipped blocks (height already below the
  // cutter's lower bound) are exercised too.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (const Cutter& c : {Cutter::flat_end(6.0, 2, 0.5), Cutter::ball_end(6.0, 2, 0.5),
                          Cutter::bull_nose(6.0, 1.0, 2, 0.5)}) {
    const TipProfile prof = TipProfile::of(c);
    ZMap z(0.0, 25.0, 0.0, 25.0, 0.15, 12.0, 0.0);
    MatrixXdR expect = z.heights();
    std::int64_t lowered = 0;
    for (int t = 0; t < 16; ++t) {
      const Vec3 a(25 * U(rng), 25 * U(rng), 5 + 5 * U(rng));
      Vec3 b(25 * U(rng), 25 * U(rng), 5 + 5 * U(rng));
      if (t % 8 == 0) b.z() = a.z();                      // level
      if (t % 8 == 1) b = Vec3(a.x(), a.y(), b.z());      // plunge
      if (t % 8 == 2) b = Vec3(a.x() + 0.2, a.y(), b.z()); // steep ramp
      if (t % 8 == 3) b.y() = a.y();                      // along X
      if (t % 8 == 4) b.x() = a.x();                      // along Y
      const auto st = netshape::stock::sweep_line(z, c, a, b);
      std::int64_t low = 0;
      double worst = 0.0;
      for (int i = 0; i < z.ny(); ++i)
        for (int j = 0; j < z.nx(); ++j) {
          const double e = netshape::stock::lowest_reach_line(prof, a, b, z.node_x(j), z.node_y(i));
          const double nh = std::min(expect(i, j), std::max(0.0, e));
          low += nh < expect(i, j);
          expect(i, j) = nh;
          worst = std::max(worst, std::abs(z.heights()(i, j) - nh));
        }
      CHECK(worst <= 1e-12);
      CHECK(st.nodes_lowered == low);
      lowered += low;
    }
    CHECK(lowered > 1000);
  }
}

TEST_CASE("sweep: sweep_lines equals one sweep_line per move, bit for bit; bad shapes are rejected") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (const Cutter& c : {Cutter::flat_end(6.0, 2, 0.5), Cutter::ball_end(6.0, 2, 0.5),
                          Cutter::bull_nose(6.0, 1.0, 2, 0.5)}) {
    for (int n : {0, 1, 30}) {
      MatrixXdR a(n, 3), b(n, 3);
      for (int k = 0; k < n; ++k) {
        a.row(k) << 25 * U(rng), 25 * U(rng), 5 + 5 * U(rng);
        b.row(k) << 25 * U(rng), 25 * U(rng), 5 + 5 * U(rng);
        if (k % 4 == 1) b(k, 2) = a(k, 2);
      }
      ZMap one(0.0, 25.0, 0.0, 25.0, 0.15, 12.0, 0.0);
      ZMap batch = one;
      std::int64_t visited = 0, lowered = 0;
      for (int k = 0; k < n; ++k) {
        const auto st = netshape::stock::sweep_line(one, c, a.row(k).transpose(), b.row(k).transpose());
        visited += st.nodes_visited;
        lowered += st.nodes_lowered;
      }
      const auto st = netshape::stock::sweep_lines(batch, c, a, b);
      CHECK(st.moves == n);
      CHECK(st.nodes_visited == visited);
      CHECK(st.nodes_lowered == lowered);
      CHECK((batch.heights().array() == one.heights().array()).all());
    }
  }
  ZMap z(0.0, 10.0, 0.0, 10.0, 0.1, 10.0, 0.0);
  const Cutter c = Cutter::flat_end(6.0, 2, 0.5);
  MatrixXdR two(2, 2), three(2, 3), four(3, 3);
  two.setZero();
  three.setZero();
  four.setZero();
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_lines(z, c, two, three), doctest::Contains("starts.shape[1]"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_lines(z, c, three, four), doctest::Contains("ends.shape[0]"),
                       std::invalid_argument);
  three(1, 2) = std::nan("");
  CHECK_THROWS_WITH_AS(netshape::stock::sweep_lines(z, c, three, three), doctest::Contains("starts[1, 2]"),
                       std::invalid_argument);
  CHECK((z.heights().array() == 10.0).all());
}

TEST_CASE("sweep: quick reject of moves above the stock; a move over one high cell still cuts it") {
  for (const Cutter& c : {Cutter::flat_end(6.0, 2, 0.5), Cutter::ball_end(6.0, 2, 0.5),
                          Cutter::bull_nose(6.0, 1.0, 2, 0.5)}) {
    // a block at 5 mm with one pillar at 10 mm
    MatrixXdR h = MatrixXdR::Constant(100, 100, 5.0);
    h(80, 20) = 10.0;
    ZMap z = ZMap::from_heights(h, 0.0, 20.0, 0.0, 20.0, 0.0);
    CHECK(z.height_bound(0, 99) == 10.0);
    CHECK(z.height_bound(0, 50) == 5.0);
    // 5 mm above everything, ramps, level lines, plunges, arcs: nothing visited, nothing changed
    for (const auto& ab : {std::pair<Vec3, Vec3>{Vec3(-5, 3, 15), Vec3(25, 17, 16)},
                           std::pair<Vec3, Vec3>{Vec3(2, 2, 15), Vec3(18, 18, 15)},
                           std::pair<Vec3, Vec3>{Vec3(10, 10, 20), Vec3(10, 10, 15)}}) {
      const auto st = netshape::stock::sweep_line(z, c, ab.first, ab.second);
      CHECK(st.moves == 1);
      CHECK(st.nodes_visited == 0);
      CHECK(st.nodes_lowered == 0);
    }
    CHECK(netshape::stock::sweep_block(z, c, arc_block(Vec3(10, 10, 0), 5.0, 0.0, 3.0, 15.0, 16.0, false))
              .nodes_visited == 0);
    // above the 5 mm floor but far from the pillar's rows: rejected too
    CHECK(netshape::stock::sweep_line(z, c, Vec3(0, 3, 6), Vec3(20, 4, 6)).nodes_visited == 0);
    CHECK((z.heights().array() == h.array()).all());
    // at 8 mm over the pillar: it is cut (and only it)
    const auto st = netshape::stock::sweep_line(z, c, Vec3(0, 16.25, 8), Vec3(20, 16.25, 8));
    CHECK(st.nodes_visited > 0);
    CHECK(st.nodes_lowered == 1);
    CHECK(z.heights()(80, 20) < 10.0);
    CHECK(z.heights()(80, 20) >= 8.0);
  }
  // lazily tightened: after the top has been surfaced from 10 to 5 mm, a move at 6 mm is rejected
  const Cutter c = Cutter::flat_end(4.0, 2, 0.5);
  ZMap z(0.0, 20.0, 0.0, 20.0, 0.25, 10.0, 0.0);
  for (double y = -1.0; y <= 21.0; y += 0.5)  // stepover 0.5 mm: each row band is swept about 8 times
    netshape::stock::sweep_line(z, c, Vec3(-3, y, 5), Vec3(23, y, 5));
  CHECK(z.max_height() == 5.0);
  CHECK(netshape::stock::sweep_line(z, c, Vec3(-3, 10, 6), Vec3(23, 12, 6.5)).nodes_visited == 0);
  CHECK(z.height_bound(40, 50) == 5.0);  // the bands that move consulted were recomputed
  // raising a height through heights_mut() marks the bounds stale: the next move cuts it
  z.heights_mut()(40, 40) = 9.0;
  CHECK(z.height_bound(0, z.ny() - 1) == std::numeric_limits<double>::infinity());
  const auto st = netshape::stock::sweep_line(z, c, Vec3(-3, 10.1, 6), Vec3(23, 10.1, 6));
  CHECK(st.nodes_lowered == 1);
  CHECK(z.heights()(40, 40) == 6.0);
}
