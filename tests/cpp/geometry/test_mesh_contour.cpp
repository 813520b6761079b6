#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/geometry.hpp"

using namespace netshape;
using namespace netshape::geometry;

TEST_CASE("AABB mesh: distance, closest point and ray hits on a unit cube's top face") {
  Points3 v(4, 3);
  v << 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Faces f(2, 3);
  f << 0, 1, 2, 0, 2, 3;
  const TriangleMesh mesh(v, f);
  CHECK(mesh.area() == doctest::Approx(1.0));
  Points3 q(3, 3);
  q << 0.5, 0.5, 3.0, 2.0, 0.5, 1.0, -1.0, -1.0, 0.0;
  const VectorXd d = mesh.distance(q);
  CHECK(d[0] == doctest::Approx(2.0));
  CHECK(d[1] == doctest::Approx(1.0));
  CHECK(d[2] == doctest::Approx(std::sqrt(3.0)));
  const ClosestPoints cp = mesh.closest_points(q);
  CHECK((cp.points.row(1) - Eigen::RowVector3d(1.0, 0.5, 1.0)).norm() < 1e-12);
  Points3 dir(3, 3);
  dir << 0, 0, -1, 0, 0, -1, 0, 0, 1;
  const RayHits h = mesh.ray_hits(q, dir);
  CHECK(h.t[0] == doctest::Approx(2.0));
  CHECK(std::isnan(h.t[1]));
  CHECK(h.faces[1] == -1);
  CHECK(std::isnan(h.t[2]));  // (−1, −1) lies outside the face
  CHECK_THROWS_AS(TriangleMesh(v, Faces::Constant(1, 3, 7)), std::invalid_argument);
}

TEST_CASE("contour offset: outward square area with round corners, self-intersection refused") {
  Region r;
  r.outer.resize(4, 2);
  r.outer << 0, 0, 4, 0, 4, 4, 0, 4;
  const auto rings = offset_region(r, 1.0);
  REQUIRE(rings.size() == 1);
  CHECK(rings[0].area() == doctest::Approx(36.0 - (4.0 - pi)).epsilon(1e-6));
  Region bow;
  bow.outer.resize(4, 2);
  bow.outer << 0, 0, 4, 4, 4, 0, 0, 4;
  CHECK_THROWS_WITH_AS(offset_region(bow, -0.5), doctest::Contains("self-intersecting"), std::invalid_argument);
}

TEST_CASE("CC to CL: ball, flat and bull formulas with a tilted axis") {
  cutter::Cutter ball = cutter::Cutter::ball_end(10.0, 2, 0.5);
  cutter::Cutter flat = cutter::Cutter::flat_end(10.0, 2, 0.5);
  cutter::Cutter bull = cutter::Cutter::bull_nose(10.0, 1.0, 2, 0.5);
  const Vec3 cc(1, 2, 3), n = Vec3(0.3, 0.0, 1.0).normalized(), a = Vec3::UnitZ();
  CHECK((cc_to_cl(ball, cc, n, a) - (cc + 5.0 * n - 5.0 * a)).norm() < 1e-14);
  CHECK((cc_to_cl(flat, cc, n, a) - (cc + 5.0 * Vec3::UnitX())).norm() < 1e-14);
  CHECK((cc_to_cl(bull, cc, n, a) - (cc + 1.0 * n + 4.0 * Vec3::UnitX() - a)).norm() < 1e-14);
  CHECK((cc_to_cl(flat, cc, a, a) - cc).norm() == 0.0);  // end face on a level surface
  Points3 one(1, 3);
  one.row(0) = cc.transpose();
  for (const auto& c : {ball, flat, bull})
    CHECK(std::abs(cutter_signed_distance(c, cc_to_cl(c, cc, n, a), a, one)[0]) < 1e-12);
  CHECK_THROWS_AS(cc_to_cl(ball, cc, -a, a), std::invalid_argument);
}
