#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/cutter/cutter.hpp"
#include "netshape/core/types.hpp"

using netshape::cutter::Cutter;
using netshape::cutter::CutterKind;

TEST_CASE("cutter profile: flat, ball and bull-nose envelopes") {
  const Cutter flat = Cutter::flat_end(10.0, 2, netshape::deg2rad(30));
  CHECK(flat.radius_at(0.0) == doctest::Approx(5.0));
  CHECK(flat.radius_at(3.0) == doctest::Approx(5.0));

  const Cutter ball = Cutter::ball_end(10.0, 2, netshape::deg2rad(30));
  CHECK(ball.radius_at(0.0) == doctest::Approx(0.0));
  // sphere of radius 5 centred at z = 5: r(z) = sqrt(25 - (5 - z)^2)
  for (double z : {0.5, 1.0, 2.5, 4.9}) CHECK(ball.radius_at(z) == doctest::Approx(std::sqrt(25 - (5 - z) * (5 - z))));
  CHECK(ball.radius_at(7.0) == doctest::Approx(5.0));

  const Cutter bull = Cutter::bull_nose(10.0, 1.0, 4, netshape::deg2rad(45));
  CHECK(bull.radius_at(0.0) == doctest::Approx(4.0));
  CHECK(bull.radius_at(1.0) == doctest::Approx(5.0));
  CHECK(bull.radius_at(0.5) == doctest::Approx(4.0 + std::sqrt(1 - 0.25)));
}

TEST_CASE("cutter helix lag constant: Cho & Suh §5, D = 25 mm, 60° helix, z = 1.25 mm gives 9.92°") {
  const Cutter c = Cutter::flat_end(25.0, 2, netshape::deg2rad(60));
  const double lag_deg = netshape::rad2deg(1.25 * c.helix_lag());
  CHECK(lag_deg == doctest::Approx(9.92).epsilon(5e-4));
}

TEST_CASE("cutter validation names the field") {
  Cutter c = Cutter::flat_end(10.0, 2, 0.5);
  c.radius = -1.0;
  CHECK_THROWS_WITH_AS(c.validate(), doctest::Contains("cutter.radius = -1"), std::invalid_argument);
  c = Cutter::flat_end(10.0, 2, 0.5);
  c.radius = std::nan("");
  CHECK_THROWS_AS(c.validate(), std::invalid_argument);
  c = Cutter::flat_end(10.0, 2, 0.5);
  c.kind = CutterKind::bull;
  c.corner_radius = 6.0;
  CHECK_THROWS_WITH_AS(c.validate(), doctest::Contains("cutter.corner_radius"), std::invalid_argument);
  c = Cutter::flat_end(10.0, 2, 0.5);
  c.flutes = 0;
  CHECK_THROWS_WITH_AS(c.validate(), doctest::Contains("cutter.flutes = 0"), std::invalid_argument);
  CHECK_THROWS_AS(netshape::cutter::cutter_kind_from_string("drill"), std::invalid_argument);
}
