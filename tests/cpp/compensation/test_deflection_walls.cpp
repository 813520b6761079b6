// Final walls and drawing offsets (netshape/compensation/deflection_compensation.hpp): which walls a
// later pass takes away, and a program's offsets from a drawing, checked against closed-form geometry.
#include <doctest/doctest.h>

#include <cmath>

#include "netshape/compensation.hpp"

using namespace netshape;
using namespace netshape::compensation;

namespace {
// a pass along +X at y, z from x0 to x1 as (m, 3) rows
Points3 pass(double y, double z, double x0, double x1, int m) {
  Points3 p(m, 3);
  for (int i = 0; i < m; ++i) p.row(i) << x0 + (x1 - x0) * i / (m - 1), y, z;
  return p;
}
}  // namespace

TEST_CASE("wall_remains: a later pass closer than the radius takes the wall, one at the radius does not") {
  const double R = 3.0;
  // wall points of a pass at y = 0 (right wall at y = -R), z = 0, 3 mm high
  Points3 wall = pass(-R, 0.0, 1.0, 9.0, 9);
  const VectorXd top = VectorXd::Constant(9, 3.0);
  const Eigen::VectorXi after = Eigen::VectorXi::Constant(9, 1);
  for (double y_later : {-0.5, -1.0, -2.9, 0.0, 1.0}) {
    const Points3 later = pass(y_later, 0.0, 0.0, 10.0, 2);
    Eigen::VectorXi cut(2);
    cut << 0, 1;
    const Eigen::VectorXi keep = wall_remains(wall, top, after, later, cut, R, 0.005);
    // distance from the wall points to the later pass: |y_later + R|
    const bool expect_kept = std::abs(y_later + R) >= R - 0.005;
    for (int k = 0; k < 9; ++k) CHECK(keep[k] == (expect_kept ? 1 : 0));
  }
  SUBCASE("a rapid, a pass above the wall's top and a pass before first_later leave it") {
    const Points3 later = pass(-1.0, 0.0, 0.0, 10.0, 2);
    Eigen::VectorXi rapid(2);
    rapid << 0, 0;
    CHECK(wall_remains(wall, top, after, later, rapid, R, 0.005).minCoeff() == 1);
    const Points3 above = pass(-1.0, 3.5, 0.0, 10.0, 2);
    Eigen::VectorXi cut(2);
    cut << 0, 1;
    CHECK(wall_remains(wall, top, after, above, cut, R, 0.005).minCoeff() == 1);
    const Eigen::VectorXi none_later = Eigen::VectorXi::Constant(9, 2);
    CHECK(wall_remains(wall, top, none_later, later, cut, R, 0.005).minCoeff() == 1);
  }
  SUBCASE("a later pass over part of the wall takes only that part") {
    const Points3 later = pass(-1.0, 0.0, 0.0, 4.0, 2);
    Eigen::VectorXi cut(2);
    cut << 0, 1;
    const Eigen::VectorXi keep = wall_remains(wall, top, after, later, cut, R, 0.005);
    for (int k = 0; k < 9; ++k) {
      // wall point at x = 1 + k; within R − clearance of the segment ending at x = 4 when
      // (x − 4)² + 2² < (R − 0.005)²
      const double x = 1.0 + k;
      const double d = x <= 4.0 ? 2.0 : std::hypot(x - 4.0, 2.0);
      CHECK(keep[k] == (d < R - 0.005 ? 0 : 1));
    }
  }
}

TEST_CASE("wall_remains: many later moves, only the near ones visited, same answer as brute force") {
  // a spiral of later moves; compare with a brute-force distance test
  const int m = 4000;
  Points3 later(m, 3);
  for (int j = 0; j < m; ++j) {
    const double t = 0.01 * j, r = 1.0 + 0.05 * j;
    later.row(j) << r * std::cos(t), r * std::sin(t), 0.0;
  }
  Eigen::VectorXi cut = Eigen::VectorXi::Ones(m);
  Points3 wall(200, 3);
  for (int k = 0; k < 200; ++k) wall.row(k) << -100.0 + k, 0.37 * k - 40.0, 0.0;
  const VectorXd top = VectorXd::Constant(200, 1.0);
  const Eigen::VectorXi after = Eigen::VectorXi::Constant(200, 1);
  const double R = 4.0, clear = 0.005;
  const Eigen::VectorXi keep = wall_remains(wall, top, after, later, cut, R, clear);
  for (int k = 0; k < 200; ++k) {
    bool near = false;
    for (int j = 1; j < m && !near; ++j) {
      const Vec2 a = later.row(j - 1).head<2>().transpose(), b = later.row(j).head<2>().transpose();
      const Vec2 q = wall.row(k).head<2>().transpose();
      const double t = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      near = (a + t * (b - a) - q).norm() < R - clear;
    }
    CHECK(keep[k] == (near ? 0 : 1));
  }
}

TEST_CASE("drawing_offsets: signed offsets along the drawing's normal, followed pass by pass") {
  // drawing: two side-by-side passes joined by a step over (a pocket's rings in miniature)
  Points3 drawing(5, 3);
  drawing << 0, 0, 0, 10, 0, 0, 10, 2, 0, 0, 2, 0, 0, 4, 0;
  // program: the drawing moved by +0.05 towards the right wall (−Y on the first pass, +Y on the
  // second, which runs along −X)
  Points3 points(6, 3);
  points << 1, -0.05, 0, 5, -0.05, 0, 9, -0.05, 0, 9, 2.05, 0, 5, 2.05, 0, 1, 2.05, 0;
  const DrawingOffsets d = drawing_offsets(points, drawing, deflection::WallSide::right, 2.0);
  for (int i = 0; i < 6; ++i) CHECK(d.offsets[i] == doctest::Approx(0.05).epsilon(1e-9));
  CHECK(d.s[0] == doctest::Approx(1.0));
  CHECK(d.s[2] == doctest::Approx(9.0));
  CHECK(d.s[3] == doctest::Approx(13.0));  // 10 + 2 + 1 along the second pass
  CHECK(d.normals(0, 1) == doctest::Approx(-1.0));
  CHECK(d.normals(3, 1) == doctest::Approx(1.0));
  // the foot plus C·n is the point
  for (int i = 0; i < 6; ++i) CHECK(d.foot_distance[i] == doctest::Approx(0.05));
}
