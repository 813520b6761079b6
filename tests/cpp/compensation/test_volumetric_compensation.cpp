// Volumetric compensation: residual, travel refusal, non-convergence reported.
#include <doctest/doctest.h>

#include <random>

#include "netshape/compensation.hpp"
#include "netshape/machine.hpp"

using namespace netshape;
using namespace netshape::machine;
using namespace netshape::compensation;

namespace {
Machine test_machine() {
  Machine m = ideal_machine({0, 1}, {2}, 150.0);
  m.tool_direction = Vec3(0, 0, 1);
  for (int k = 0; k < 3; ++k) {
    m.axes[k].travel_min = -500;
    m.axes[k].travel_max = 500;
    m.axes[k].origin = Vec3(10.0 * k, -20.0, 30.0);
    for (int c = 0; c < 6; ++c) {
      const double s = c < 3 ? 1e-4 : 2e-7;
      m.axes[k].errors[c] = ErrorFunction::polynomial({s * (c - 2.5), s * 0.3 * (k + 1), -1e-4 * s * c});
    }
  }
  m.ec0y = 3e-5, m.eb0z = -2e-5, m.ea0z = 1e-5;
  m.spindle_tilt_a = 1e-5, m.spindle_tilt_b = -2e-5;
  m.validate();
  return m;
}
}  // namespace

TEST_CASE("compensated points land on the nominal ones") {
  const Machine m = test_machine();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-400.0, 400.0);
  Points3 nominal(500, 3);
  for (int i = 0; i < 500; ++i) nominal.row(i) << U(rng), U(rng), U(rng);
  const Points3 cmd = compensate_points(m, nominal);
  const Points3 actual = actual_points(m, cmd);
  CHECK((actual - nominal).rowwise().norm().maxCoeff() <= 1e-9);
  CHECK((cmd - nominal).rowwise().norm().maxCoeff() > 1e-3);  // the compensation did something
}

TEST_CASE("points pushed outside travel are refused, naming the axis") {
  Machine m = test_machine();
  m.axes[0].errors[0] = ErrorFunction::polynomial({0.5});  // X reads 0.5 mm long everywhere
  Points3 nominal(2, 3);
  nominal << 0, 0, 0, -499.8, 0, 0;  // needs X = -500.3
  auto res = compensate_points_status(m, nominal);
  CHECK(res.status[0] == VolumetricStatus::ok);
  CHECK(res.status[1] == VolumetricStatus::outside_travel);
  CHECK(res.axis[1] == 0);
  try {
    compensate_points(m, nominal);
    FAIL("no throw");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("axis X") != std::string::npos);
  }
}

TEST_CASE("a machine the iteration cannot invert is reported, not returned") {
  Machine m = ideal_machine({0, 1, 2}, {}, 0.0);
  // e(x) = -x: p + e(p) = 0 everywhere, no commanded point reaches x = 1
  m.axes[0].errors[0] = ErrorFunction::polynomial({0.0, -1.0});
  Points3 nominal(1, 3);
  nominal << 1.0, 0.0, 0.0;
  VolumetricOptions o;
  o.check_travel = false;
  auto res = compensate_points_status(m, nominal, o);
  CHECK(res.status[0] == VolumetricStatus::not_converged);
  CHECK_THROWS_AS(compensate_points(m, nominal, o), netshape::Error);
  o.tolerance = -1;
  CHECK_THROWS_AS(compensate_points(m, nominal, o), std::invalid_argument);
}

TEST_CASE("along a path the step matrix is reused: two evaluations per point, residual still verified") {
  const Machine m = test_machine();
  // a zig-zag raster with 0.05 mm steps and jumps of 30 mm between rows (step matrix recomputed there)
  const int n = 4000;
  Points3 nominal(n, 3);
  for (int i = 0; i < n; ++i) {
    const int row = i / 1000, j = i % 1000;
    nominal.row(i) << -300.0 + 0.05 * (row % 2 ? 999 - j : j) + 30.0 * row, -200.0 + 30.0 * row, 100.0 + 5 * std::sin(0.01 * i);
  }
  const VolumetricResult res = compensate_points_status(m, nominal);
  REQUIRE(res.all_ok());
  const Points3 actual = actual_points(m, res.commanded);
  CHECK((actual - nominal).rowwise().norm().maxCoeff() <= 1e-9);
  CHECK(res.residual.maxCoeff() <= 1e-9);
  CHECK(res.iterations.cast<double>().mean() < 2.01);
  // the same points one by one (a fresh Jacobian each) give the same commanded points to the tolerance
  MachineData data(m);
  for (int i = 0; i < n; i += 97) {
    Vec3 cmd;
    double r;
    int it, ax;
    REQUIRE(compensate_point(m, data, nominal.row(i).transpose(), VolumetricOptions{}, cmd, r, it, ax) ==
            VolumetricStatus::ok);
    CHECK((cmd - res.commanded.row(i).transpose()).norm() < 1e-8);
  }
}

TEST_CASE("many points at once give the one-by-one points and statuses, failures included") {
  Machine m = test_machine();
  m.axes[0].errors[0] = ErrorFunction::polynomial({0.5, 1e-4});  // X reads 0.5 mm long: needs X − 0.5
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-450.0, 450.0);
  for (const int n : {0, 1, 3, 8, 37, 203}) {
    Points3 nominal(n, 3);
    for (int i = 0; i < n; ++i) nominal.row(i) << U(rng), U(rng), U(rng);
    if (n > 20) {
      nominal.row(5) << -499.8, 0, 0;  // pushed outside X's travel
      // a short path inside the random points (warm starts within a lane's run)
      for (int i = 10; i < 20; ++i) nominal.row(i) << 100.0 + 0.05 * i, 20.0, -30.0;
    }
    const VolumetricResult res = compensate_points_status(m, nominal);
    REQUIRE(res.commanded.rows() == n);
    MachineData data(m);
    for (int i = 0; i < n; ++i) {
      Vec3 cmd;
      double r;
      int it, ax;
      const VolumetricStatus st = compensate_point(m, data, nominal.row(i).transpose(), VolumetricOptions{}, cmd, r, it, ax);
      CHECK(st == res.status[i]);
      CHECK(ax == res.axis[i]);
      CHECK((cmd - res.commanded.row(i).transpose()).norm() < 1e-8);
      if (st == VolumetricStatus::ok) {
        // the residual was evaluated at the returned point
        const Vec3 c = res.commanded.row(i).transpose();
        const double verified = (c + tip_error(m, data, c) - nominal.row(i).transpose()).norm();
        CHECK(verified <= 1e-9);
        CHECK(res.residual[i] == doctest::Approx(verified).epsilon(1e-6));
      }
    }
    if (n > 20) CHECK(res.status[5] == VolumetricStatus::outside_travel);
  }
}

TEST_CASE("many points at once: a table left during the iteration and a machine that cannot be inverted") {
  // X error table with policy error: the first point is pushed below its start
  Machine m = test_machine();
  for (int c = 0; c < 6; ++c) m.axes[0].errors[c] = ErrorFunction::zero_function();
  m.axes[0].errors[0] = ErrorFunction::table({-100.0, 0.0, 100.0}, {0.2, 0.1, 0.3}, OutOfRange::error, "EXX");
  Points3 nominal(20, 3);
  for (int i = 0; i < 20; ++i) nominal.row(i) << -99.95 + 10.0 * i, 5.0, 5.0;
  const VolumetricResult res = compensate_points_status(m, nominal);
  MachineData data(m);
  int outside = 0;
  for (int i = 0; i < 20; ++i) {
    Vec3 cmd;
    double r;
    int it, ax;
    const VolumetricStatus st = compensate_point(m, data, nominal.row(i).transpose(), VolumetricOptions{}, cmd, r, it, ax);
    CHECK(st == res.status[i]);
    outside += st == VolumetricStatus::outside_table;
  }
  CHECK(outside > 0);
  CHECK(res.status[0] == VolumetricStatus::outside_table);
  CHECK(res.status[1] == VolumetricStatus::ok);
  // e(x) = −x on X: not invertible, reported for every point
  Machine bad = ideal_machine({0, 1, 2}, {}, 0.0);
  bad.axes[0].errors[0] = ErrorFunction::polynomial({0.0, -1.0});
  VolumetricOptions o;
  o.check_travel = false;
  const VolumetricResult rb = compensate_points_status(bad, nominal, o);
  for (int i = 0; i < 20; ++i) CHECK(rb.status[i] == VolumetricStatus::not_converged);
}
