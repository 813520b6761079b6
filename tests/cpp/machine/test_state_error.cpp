// State-dependent errors (machine/state_error.hpp) and the cyclic term of the synthesis: s(d, t)
// against its formula, approach directions, a cyclic term adding exactly to the positioning component
// with its analytic slope in the Jacobian (central differences), validation.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/machine.hpp"

using namespace netshape;
using namespace netshape::machine;

namespace {
Machine cyclic_machine() {
  Machine m = ideal_machine({2}, {1, 0}, 100.0);
  m.axes[0].errors[0] = ErrorFunction::polynomial({0.0, 1e-5}, "EXX");
  m.axes[0].errors[4] = ErrorFunction::polynomial({2e-6, 1e-9}, "EBX");
  m.axes[0].cyclic = {CyclicTerm{0.003, 25.0, 0.5}};
  m.axes[0].backlash = 0.008;
  m.thermal = {ThermalDrift{2, 0.01, 600.0}};
  m.validate();
  return m;
}
}  // namespace

TEST_CASE("state_error: backlash by approach direction, thermal drift by program time") {
  const Machine m = cyclic_machine();
  CHECK(m.has_state_errors());
  const Vec3 s0 = state_error(m, Vec3(1, -1, 1), 0.0);
  CHECK(s0[0] == doctest::Approx(0.004));
  CHECK(s0[1] == 0.0);
  CHECK(s0[2] == 0.0);
  const Vec3 s1 = state_error(m, Vec3(-1, 1, -1), 600.0);
  CHECK(s1[0] == doctest::Approx(-0.004));
  CHECK(s1[2] == doctest::Approx(0.01 * (1.0 - std::exp(-1.0))).epsilon(1e-14));
  Points3 path(4, 3);
  path << 0, 0, 0, 1, 0, 0, 1, 2, 0, 0, 2, 0;
  const Points3 d = approach_directions(path, Vec3(1, -1, 1));
  CHECK(d(0, 1) == -1.0);
  CHECK(d(2, 1) == 1.0);
  CHECK(d(3, 0) == -1.0);
}

TEST_CASE("a cyclic term adds A sin(2 pi q / P + phi) to the positioning error, with its slope") {
  const Machine m = cyclic_machine();
  Machine plain = m;
  plain.axes[0].cyclic.clear();
  MachineData dm(m), dp(plain);
  for (double x : {-180.0, -3.7, 0.0, 12.5, 199.0}) {
    const Vec3 p(x, 40.0, -60.0);
    const Vec3 diff = tip_error(m, dm, p) - tip_error(plain, dp, p);
    CHECK(diff[0] == doctest::Approx(0.003 * std::sin(2.0 * pi * x / 25.0 + 0.5)).epsilon(1e-12));
    CHECK(std::abs(diff[1]) < 1e-15);
    Mat3 J;
    tip_error_and_jacobian(m, dm, p, J);
    const double h = 1e-4;
    const Vec3 fd = (tip_error(m, dm, p + Vec3(h, 0, 0)) - tip_error(m, dm, p - Vec3(h, 0, 0))) / (2 * h);
    // row 0 holds the cyclic slope (~7.5e-4); the Jacobian is the first-order model's, ~1e-9 off elsewhere
    CHECK(J(0, 0) == doctest::Approx(fd[0]).epsilon(1e-6));
    for (int r = 1; r < 3; ++r) CHECK(std::abs(J(r, 0) - fd[r]) < 1e-8);
  }
}

TEST_CASE("validation names cyclic periods and thermal time constants") {
  Machine m = cyclic_machine();
  m.axes[0].cyclic[0].period = 0.0;
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
  m = cyclic_machine();
  m.thermal[0].time_constant = -1.0;
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
  m = cyclic_machine();
  m.thermal[0].axis = 3;
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
}
