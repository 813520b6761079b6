// Calibration: the regressions recover the coefficients they were fed.
#include <doctest/doctest.h>

#include <cmath>

#include "netshape/force.hpp"

using namespace netshape;
using namespace netshape::force;

TEST_CASE("mean-force regression recovers the linear edge coefficients from simulated slot means") {
  FlatEndModel m;
  m.radius = 5;
  m.flutes = 2;
  m.axial_depth = 3;
  m.disk_height = 0.02;
  m.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
  const VectorXd feeds = (VectorXd(5) << 0.025, 0.05, 0.075, 0.1, 0.125).finished();
  Points3 means(5, 3);
  const VectorXd th = rotation_angles(3600);
  for (int i = 0; i < 5; ++i) {
    m.feed_per_tooth = feeds[i];
    means.row(i) = flat_end_forces(m, th).colwise().mean();
  }
  const LinearEdgeFit fit = fit_linear_edge_mean_forces(m.engagement, 2, 3.0, feeds, means);
  const auto k = fit.coefficients.as_array(), k0 = m.linear_edge.as_array();
  for (int j = 0; j < 6; ++j) CHECK(k[j] == doctest::Approx(k0[j]).epsilon(5e-3));
  CHECK(fit.r2.minCoeff() > 0.9999);
}

TEST_CASE("time-series fit recovers coefficients and phase") {
  FlatEndModel m;
  m.radius = 5;
  m.flutes = 2;
  m.axial_depth = 3;
  m.feed_per_tooth = 0.1;
  m.disk_height = 0.05;
  m.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
  const VectorXd th = rotation_angles(600, 3.0);
  const double phase = 0.7;
  const Points3 F = flat_end_forces(m, (th.array() + phase).matrix());
  const TimeSeriesFit fit = fit_linear_edge_time_series(m, th, F, 60);
  CHECK(std::fmod(fit.phase, pi) == doctest::Approx(phase).epsilon(1e-4));
  const auto k = fit.coefficients.as_array(), k0 = m.linear_edge.as_array();
  for (int j = 0; j < 6; ++j) CHECK(k[j] == doctest::Approx(k0[j]).epsilon(1e-3));
  CHECK(fit.rms_total < 1e-4);
}
