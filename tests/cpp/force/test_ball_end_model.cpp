// Ball end mill model: steady side cuts meet the wall at each element's own radius (docs/conventions.md §2).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "netshape/force.hpp"

using namespace netshape;
using namespace netshape::force;

namespace {
BallEndModel side_cut(MillingMode mode, double ae, double ap) {
  BallEndModel m;
  m.radius = 6.0;
  m.flutes = 2;
  m.helix = deg2rad(30.0);
  m.axial_depth = ap;
  m.feed_per_tooth = 0.08;
  m.engagement = AngularEngagement::from_mode(mode, m.radius, ae);
  m.coefficients = ball_end_coefficient_set("kim_zas_ball12").coefficients;
  return m;
}

/// Per-row map of the window each row should get from the wall at R − a_e: up [0, acos((R − a_e)/r)],
/// down [π − acos((R − a_e)/r), π], nothing where r ≤ R − a_e; bins marked by their centre.
EngagementMap wall_map(const BallEndModel& m, const BallEndWorkspace& ws, MillingMode mode, double ae, int bins) {
  EngagementMap map;
  map.mask.setZero(ws.rows(), bins);
  const double wall = m.radius - ae;
  for (int i = 0; i < ws.rows(); ++i) {
    const double r = ws.radii()[i];
    if (r <= wall) continue;
    const double w = std::acos(std::max(-1.0, wall / r));
    for (int b = 0; b < bins; ++b) {
      const double phi = (b + 0.5) * 2.0 * pi / bins;
      const bool in = mode == MillingMode::up ? phi <= w : (phi >= pi - w && phi <= pi);
      map.mask(i, b) = in ? 1 : 0;
    }
  }
  return map;
}
}  // namespace

TEST_CASE("ball side cut: each row's window comes from its radius and the wall at R − a_e") {
  const VectorXd th = rotation_angles(180);
  for (MillingMode mode : {MillingMode::up, MillingMode::down})
    for (double ae : {0.5, 3.0, 6.0})
      for (double ap : {4.0, 8.0}) {  // below and above R; r(4) = 5.66 mm > R − 0.5
        const BallEndModel m = side_cut(mode, ae, ap);
        BallEndWorkspace ws(m);
        Points3 F(th.size(), 3), G(th.size(), 3);
        ball_end_forces(m, ws, th, F);
        const EngagementMap map = wall_map(m, ws, mode, ae, 14400);
        ball_end_forces(m, ws, th, G, &map);
        const double scale = F.leftCols(2).rowwise().norm().mean();
        CAPTURE(ae);
        CAPTURE(ap);
        CHECK(scale > 0.1);
        // bins of 0.025°: an edge moves by at most half a bin
        CHECK((F.colwise().mean() - G.colwise().mean()).cwiseAbs().maxCoeff() < 2e-3 * scale);
      }
}

TEST_CASE("ball side cut: no element reaches a wall beyond its radius; a_e = D is the slot") {
  const VectorXd th = rotation_angles(90);
  // a_p 2: largest row radius √(36 − 16) = 4.47 mm < R − a_e = 5 mm
  CHECK(ball_end_forces(side_cut(MillingMode::down, 1.0, 2.0), th).cwiseAbs().maxCoeff() == 0.0);
  const Points3 slot = ball_end_forces(side_cut(MillingMode::slot, 0.0, 3.0), th);
  const Points3 full = ball_end_forces(side_cut(MillingMode::up, 12.0, 3.0), th);
  CHECK((slot - full).cwiseAbs().maxCoeff() <= 1e-9 * slot.cwiseAbs().maxCoeff());
}
