#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/stock/engagement.hpp"
#include "netshape/stock/sweep.hpp"

using netshape::pi;
using netshape::Vec3;
using netshape::VectorXd;
using netshape::cutter::Cutter;
using netshape::stock::ZMap;

TEST_CASE("engagement: the cutting frame of docs/conventions.md §2") {
  const Cutter c = Cutter::flat_end(10.0, 2, 0.5);
  // feed along +Y of the machine: X_c = +Y, Y_c = Z × X_c = −X
  const Vec3 tip(1.0, 2.0, 3.0), feed(0.0, 2.0, 0.5);
  const Vec3 front = netshape::stock::element_point(c, tip, feed, 0.5 * pi, 0.0);
  CHECK((front - Vec3(1.0, 7.0, 3.0)).norm() < 1e-12);  // φ = π/2 is the feed direction
  const Vec3 left = netshape::stock::element_point(c, tip, feed, 0.0, 2.0);
  CHECK((left - Vec3(-4.0, 2.0, 5.0)).norm() < 1e-12);  // φ = 0 is +Y_c, the left of the feed
  const Vec3 right = netshape::stock::element_point(c, tip, feed, pi, 0.0);
  CHECK((right - Vec3(6.0, 2.0, 3.0)).norm() < 1e-12);
  // clockwise seen from the spindle: from +Y_c (φ = 0) to +X_c (φ = π/2)
  const Vec3 a = netshape::stock::element_point(c, tip, feed, 0.1, 0.0) - tip;
  const Vec3 b = netshape::stock::element_point(c, tip, feed, 0.2, 0.0) - tip;
  CHECK(a.cross(b).z() < 0.0);
  const Cutter ball = Cutter::ball_end(10.0, 2, 0.5);
  CHECK((netshape::stock::element_point(ball, tip, feed, 0.5 * pi, 1.0) - tip).head<2>().norm() ==
        doctest::Approx(ball.radius_at(1.0)));
  CHECK_THROWS_WITH_AS(netshape::stock::element_point(c, tip, Vec3(0, 0, -1), 0.0, 0.0),
                       doctest::Contains("feed_direction"), std::invalid_argument);
}

namespace {
// flat block x ∈ [20, 40], y ∈ [10, 30], top 10; the cutter enters from x < 20 along +X at
// y = y_axis and stops one feed step before x = 30: the state before the move to the query position.
netshape::stock::Immersion straight_cut(double y_axis, double ap, double h) {
  ZMap z(20.0, 40.0, 10.0, 30.0, h, 10.0, 0.0);
  const Cutter c = Cutter::flat_end(10.0, 2, 0.5);
  netshape::stock::sweep_line(z, c, Vec3(-10.0, y_axis, 10.0 - ap), Vec3(29.95, y_axis, 10.0 - ap));
  return netshape::stock::immersion(z, c, Vec3(30.0, y_axis, 10.0 - ap), Vec3(1, 0, 0));
}
}  // namespace

TEST_CASE("engagement: immersion from the Z-map equals the analytic one for a straight cut") {
  const double R = 5.0, ae = 2.0, ap = 3.0, h = 0.02;
  // Tolerances [rad] from the pillar model: a wall is known to ±h/2, which moves an edge angle by
  // (h/2)/(R·sin φ) where the wall crosses the circle, and by up to sqrt(h/R) where it is tangent
  // to it (φ = 0 and π); plus the feed step of the last move L/(2R) at the rear.
  const double tol_tangent = 1.1 * std::sqrt(h / R) + 0.05 / (2 * R);
  const double tol_cross = h / (R * std::sin(std::acos(1 - ae / R))) + 1e-3;
  // up milling: material on the +Y_c side, y ≥ y_axis + R − a_e
  const auto up = straight_cut(10.0 + ae - R, ap, h);
  CHECK(up.engaged);
  CHECK(std::abs(up.phi_st) < tol_tangent);
  CHECK(std::abs(up.phi_ex - std::acos(1 - ae / R)) < tol_cross);
  CHECK(up.axial_depth == doctest::Approx(ap));
  CHECK(up.radial_depth == doctest::Approx(ae).epsilon(0.02));
  // down milling: material on the −Y_c side
  const auto down = straight_cut(30.0 + R - ae, ap, h);
  CHECK(std::abs(down.phi_st - (pi - std::acos(1 - ae / R))) < tol_cross);
  CHECK(std::abs(down.phi_ex - pi) < tol_tangent);
  CHECK(down.axial_depth == doctest::Approx(ap));
  // slot
  const auto slot = straight_cut(20.0, ap, h);
  CHECK(std::abs(slot.phi_st) < tol_tangent);
  CHECK(std::abs(slot.phi_ex - pi) < tol_tangent);
  CHECK(slot.radial_depth == doctest::Approx(2 * R).epsilon(0.01));
  // in the air
  const auto air = straight_cut(-20.0, ap, h);  // beside the block
  CHECK_FALSE(air.engaged);
}

TEST_CASE("engagement: element mask against the Z-map, heights above the flute length never engage") {
  ZMap z(0.0, 60.0, 0.0, 40.0, 0.05, 10.0, 0.0);
  Cutter c = Cutter::flat_end(10.0, 2, 0.5);
  c.flute_length = 20.0;
  netshape::stock::sweep_line(z, c, Vec3(-10.0, 20.0, 7.0), Vec3(29.9, 20.0, 7.0));
  VectorXd phi(4), zz(3);
  phi << 0.5 * pi, 1.5 * pi, 0.25 * pi, 0.75 * pi;
  zz << 1.0, 3.5, 25.0;  // in the 3 mm cut, above the block top, above the flutes
  const auto m = netshape::stock::engaged_elements(z, c, Vec3(30.0, 20.0, 7.0), Vec3(1, 0, 0), phi, zz);
  REQUIRE(m.rows() == 3);
  REQUIRE(m.cols() == 4);
  CHECK(m(0, 0));        // front
  CHECK_FALSE(m(0, 1));  // behind: already cut
  CHECK(m(0, 2));
  CHECK(m(0, 3));
  CHECK_FALSE(m.row(1).any());
  CHECK_FALSE(m.row(2).any());
  zz[0] = -1.0;
  CHECK_THROWS_WITH_AS(netshape::stock::engaged_elements(z, c, Vec3(30, 20, 7), Vec3(1, 0, 0), phi, zz),
                       doctest::Contains("z = -1"), std::invalid_argument);
}
