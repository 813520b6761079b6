#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;
using toolpath::Block;

namespace {

Block arc(const Vec3& a, const Vec3& b, const Vec3& c, bool cw) {
  Block k;
  k.kind = toolpath::MotionKind::arc;
  k.start = a;
  k.end = b;
  k.center = c;
  k.clockwise = cw;
  k.feed = 1000;
  return k;
}

// smallest distance from p to the block sampled at 200 001 points (an independent estimate: above the
// true distance by at most half a sample spacing, 1.2e-4 mm on these arcs, where p is on the arc)
double sampled(const Block& b, const Vec3& p) {
  double best = 1e300;
  for (int i = 0; i <= 200000; ++i) best = std::min(best, (b.point_at(i / 200000.0) - p).norm());
  return best;
}

double one(const Block& b, const Vec3& p) {
  Points3 pts(1, 3);
  pts.row(0) = p.transpose();
  return deviation_to_program({b}, pts, {0}, {0});
}

}  // namespace

TEST_CASE("deviation_to_program: distance to circular and helical arcs equals a dense sampling") {
  const Block ccw = arc({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, false);  // quarter circle, G17
  const double c45 = std::cos(pi / 4), s45 = std::sin(pi / 4);
  const std::vector<Vec3> pts = {{10.3 * c45, 10.3 * s45, 0.0}, {9.8 * c45, 9.8 * s45, 0.1},
                                 {10 * std::cos(-0.5), 10 * std::sin(-0.5), 0.0},  // before the start
                                 {-3, -4, 2}, {0, 0, 0}, {0.0, 10.5, -0.2}};
  CHECK(one(ccw, pts[0]) == doctest::Approx(0.3).epsilon(1e-12));
  CHECK(one(ccw, pts[1]) == doctest::Approx(std::hypot(0.2, 0.1)).epsilon(1e-12));
  auto agrees = [](double exact, double sample) {
    return exact <= sample + 1e-12 && sample - exact < 1.5e-4;
  };
  for (const Vec3& p : pts) CHECK(agrees(one(ccw, p), sampled(ccw, p)));
  // the same quarter clockwise is the other three quarters
  const Block cw = arc({10, 0, 0}, {0, 10, 0}, {0, 0, 0}, true);
  CHECK(one(cw, pts[0]) > 1.0);
  for (const Vec3& p : pts) CHECK(agrees(one(cw, p), sampled(cw, p)));
  // a full circle (start = end) and a helix (measured along a polyline: its refinement resolves ~1 µm)
  const Block full = arc({10, 0, 0}, {10, 0, 0}, {0, 0, 0}, false);
  CHECK(one(full, {0, -12, 1}) == doctest::Approx(std::hypot(2.0, 1.0)).epsilon(1e-12));
  const Block helix = arc({10, 0, 0}, {0, 10, 3}, {0, 0, 0}, false);
  for (const Vec3& p : pts) CHECK(std::abs(one(helix, p) - sampled(helix, p)) < 2e-3);
}
