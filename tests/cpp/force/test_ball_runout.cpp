// Ball end mill with cutter runout: flute j's chip t_j = f·sin ϕ + (r_j − r_{j+1})·cos ψ, clamped at 0
// (ball_end_model.hpp), in the single cut, with an engagement map and along a program.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "netshape/force.hpp"
#include "netshape/stock.hpp"
#include "netshape/toolpath.hpp"

#include "flute_order.hpp"

using namespace netshape;
using namespace netshape::force;

namespace {
BallEndModel slot(double rho, double lambda_deg) {
  BallEndModel m;
  m.radius = 6.0;
  m.flutes = 2;
  m.helix = deg2rad(30.0);
  m.axial_depth = 4.0;
  m.feed_per_tooth = 0.08;
  m.engagement = AngularEngagement::from_mode(MillingMode::slot, m.radius, 12.0);
  m.coefficients = ball_end_coefficient_set("kim_zas_ball12").coefficients;
  m.runout_rho = rho;
  m.runout_lambda = deg2rad(lambda_deg);
  return m;
}

/// Largest |F| over the first and the second half revolution (flute 1's and flute 2's pass).
std::pair<double, double> half_peaks(const Points3& F) {
  const Eigen::Index h = F.rows() / 2;
  const VectorXd r = F.rowwise().norm();
  return {r.head(h).maxCoeff(), r.tail(F.rows() - h).maxCoeff()};
}
}  // namespace

TEST_CASE("ball runout: ρ = 0 is bit-identical whatever λ") {
  const VectorXd th = rotation_angles(144);
  const Points3 F = ball_end_forces(slot(0.0, 0.0), th);
  CHECK((ball_end_forces(slot(0.0, 75.0), th) - F).cwiseAbs().maxCoeff() == 0.0);
  const auto [p1, p2] = half_peaks(F);
  CHECK(std::abs(p1 - p2) <= 1e-9 * p1);  // equal flutes: periodic over a flute pitch
}

TEST_CASE("ball runout: the flutes' peaks differ, the mean per revolution stays") {
  const VectorXd th = rotation_angles(720);
  const Points3 F0 = ball_end_forces(slot(0.0, 0.0), th);
  // ρ 5 µm at λ 0: r_0 − r_1 = 2ρ = 10 µm on an 80 µm chip; flute 1 cuts thicker, flute 2 thinner
  const Points3 F = ball_end_forces(slot(0.005, 0.0), th);
  const auto [p1, p2] = half_peaks(F);
  const auto [q1, q2] = half_peaks(F0);
  CHECK(p1 > 1.05 * q1);
  CHECK(p2 < 0.95 * q2);
  CHECK(p1 > 1.1 * p2);  // a once-per-revolution component
  // the chip removed per revolution is unchanged (Σ_j (r_j − r_{j+1}) = 0); t^m with m < 1 and the
  // clamp near entry and exit (f sin ϕ < 10 µm) leave a small difference
  const double scale = F0.rowwise().norm().mean();
  CHECK((F.colwise().mean() - F0.colwise().mean()).norm() < 0.02 * scale);
  // the flute after flute 1 in the order j takes what flute 1 left: λ 180° swaps the flutes' roles
  const auto [s1, s2] = half_peaks(ball_end_forces(slot(0.005, 180.0), th));
  CHECK(s2 > 1.1 * s1);
}

TEST_CASE("ball runout: a direct element sum at one angle") {
  BallEndModel m = slot(0.004, 40.0);
  m.flutes = 3;
  BallEndWorkspace ws(m);
  const double th = 0.7;
  double fx = 0.0, fy = 0.0;
  const BallEndCoefficients& K = m.coefficients;
  for (int i = 0; i < ws.rows(); ++i)
    for (int j = 0; j < 3; ++j) {
      const double ph = std::fmod(th + j * 2.0 * pi / 3 - m.k_beta() * ws.heights()[i] + 4.0 * pi, 2.0 * pi);
      const double X = ws.radii()[i] * std::sin(ph);
      if (X <= 0.0) continue;
      auto r = [&](int q) { return m.runout_rho * std::cos(m.runout_lambda - q * 2.0 * pi / 3); };
      const double psi = ws.position_angles()[i];
      const double t = m.feed_per_tooth * std::sin(ph) + (r(j) - r(flute_before(j, 3))) * std::cos(psi);
      if (t <= 0.0) continue;
      const double dw = ws.widths()[i];
      const double ft = K.kt(psi) * std::pow(t, K.m_t) * dw;
      const double fr = K.kr(psi) * std::pow(t, K.m_r) * dw;
      fx += -ft * std::cos(ph) - fr * std::sin(ph);
      fy += ft * std::sin(ph) - fr * std::cos(ph);
    }
  VectorXd a(1);
  a << th;
  const Points3 F = ball_end_forces(m, a);
  CHECK(F(0, 0) == doctest::Approx(fx).epsilon(1e-9));
  CHECK(F(0, 1) == doctest::Approx(fy).epsilon(1e-9));
}

TEST_CASE("ball runout: the map model equals the window model on a slot's elements") {
  const VectorXd th = rotation_angles(120);
  for (double lam : {0.0, 130.0}) {
    const BallEndModel m = slot(0.006, lam);
    BallEndWorkspace ws(m);
    const EngagementMap map = EngagementMap::from_window(m.engagement, ws.rows(), 360);
    Points3 F(th.size(), 3), G(th.size(), 3);
    ball_end_forces(m, ws, th, F);
    ball_end_forces(m, ws, th, G, &map);
    CHECK((F - G).cwiseAbs().maxCoeff() <= 1e-9 * F.cwiseAbs().maxCoeff());
  }
  BallEndModel bad = slot(6.0, 0.0);
  CHECK_THROWS_AS(bad.validate(), std::invalid_argument);
}

TEST_CASE("ball runout along a program: ProgramCoefficients::chip carries it, a chip exponent is refused") {
  const toolpath::Toolpath prog = toolpath::parse_gcode("G21 G90 G0 X-8 Y0 Z0\nS6000 M3\nG1 X12 F960\n");
  ProgramCoefficients k;
  k.ball_end = ball_end_coefficient_set("kim_zas_ball12").coefficients;
  ProgramForceOptions opt;
  opt.step = 2.0;
  opt.samples_per_revolution = 72;
  const cutter::Cutter ball = cutter::Cutter::ball_end(12.0, 2, deg2rad(30.0));
  auto run = [&](const ProgramCoefficients& kk) {
    stock::ZMap z(0.0, 12.0, -8.0, 8.0, 0.2, 4.0, -5.0);
    return simulate_program(z, ball, prog, kk, opt);
  };
  const ProgramForces plain = run(k);
  ProgramCoefficients k0 = k;
  k0.chip.runout_lambda = 1.0;  // ρ = 0: the same forces bit for bit
  CHECK((run(k0).peak_resultant - plain.peak_resultant).cwiseAbs().maxCoeff() == 0.0);
  ProgramCoefficients kr = k;
  kr.chip = RunoutSizeEffect{0.005, 0.0, 1.0, 0.0};
  const ProgramForces with = run(kr);
  REQUIRE(with.peak_resultant.size() == plain.peak_resultant.size());
  CHECK(with.peak_resultant.maxCoeff() > 1.05 * plain.peak_resultant.maxCoeff());
  ProgramCoefficients kp = kr;
  kp.chip.chip_exponent = 0.8;
  CHECK_THROWS_AS(run(kp), std::invalid_argument);
}
