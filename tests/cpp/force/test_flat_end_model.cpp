// Flat end mill force model: published and closed-form numbers.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "netshape/force.hpp"

using namespace netshape;
using namespace netshape::force;

namespace {
FlatEndModel slot_model() {
  FlatEndModel m;
  m.radius = 5.0;
  m.flutes = 2;
  m.helix = deg2rad(30.0);
  m.axial_depth = 3.0;
  m.feed_per_tooth = 0.1;
  m.engagement = AngularEngagement::from_mode(MillingMode::slot, 5.0, 10.0);
  m.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
  m.disk_height = 0.01;
  return m;
}
}  // namespace

TEST_CASE("Cho & Suh §5: helix lag at mid depth of a D=25 mm, 60° cutter is 9.92° (printed 9.915°)") {
  FlatEndModel m;
  m.radius = 12.5;
  m.helix = deg2rad(60.0);
  CHECK(rad2deg(m.k_beta() * 1.25) == doctest::Approx(9.924).epsilon(1e-4));
  CHECK(std::abs(rad2deg(m.k_beta() * 1.25) - 9.915) < 0.01);
}

TEST_CASE("Altintas closed-form mean slot forces equal the simulated mean (docs/conventions.md §2 frame)") {
  const FlatEndModel m = slot_model();
  const VectorXd th = rotation_angles(3600);
  const Points3 F = flat_end_forces(m, th);
  const Vec3 mean = F.colwise().mean().transpose();
  const auto& k = m.linear_edge;
  const double N = 2, a = 3.0, c = 0.1;
  const double fx = -N * a * k.krc * c / 4 - N * a * k.kre / pi;
  const double fy = N * a * k.ktc * c / 4 + N * a * k.kte / pi;
  const double fz = N * a * k.kac * c / pi + N * a * k.kae / 2;
  CHECK(mean[0] == doctest::Approx(fx).epsilon(2e-3));
  CHECK(mean[1] == doctest::Approx(fy).epsilon(2e-3));
  CHECK(mean[2] == doctest::Approx(fz).epsilon(2e-3));
  const Vec3 cf = mean_force(k, m.engagement, c, 2, a);
  CHECK(cf[0] == doctest::Approx(fx).epsilon(1e-12));
  CHECK(cf[1] == doctest::Approx(fy).epsilon(1e-12));
  CHECK(cf[2] == doctest::Approx(fz).epsilon(1e-12));
  // signs (forces ON THE CUTTER): feed force negative, normal force positive
  CHECK(mean[0] < 0);
  CHECK(mean[1] > 0);
}

TEST_CASE("up and down milling mean forces equal the general closed form") {
  for (auto mode : {MillingMode::up, MillingMode::down}) {
    FlatEndModel m = slot_model();
    m.engagement = AngularEngagement::from_mode(mode, 5.0, 2.0);
    const Points3 F = flat_end_forces(m, rotation_angles(7200));
    const Vec3 mean = F.colwise().mean().transpose();
    const Vec3 cf = mean_force(m.linear_edge, m.engagement, m.feed_per_tooth, 2, 3.0);
    for (int j = 0; j < 3; ++j) CHECK(mean[j] == doctest::Approx(cf[j]).epsilon(5e-3));
  }
}

TEST_CASE("Kline-DeVor (Cho & Suh eq. 1-5, α = π − φ) equals the linear edge model with ktc=KT, krc=KR·KT") {
  FlatEndModel a = slot_model();
  a.engagement = AngularEngagement::from_mode(MillingMode::down, 5.0, 3.0);
  FlatEndModel b = a;
  b.coefficient_model = FlatCoefficientModel::kline_devor;
  b.kline_devor = {800.0, 0.3};
  a.linear_edge = b.kline_devor.to_linear_edge();
  const VectorXd th = rotation_angles(360);
  const Points3 Fa = flat_end_forces(a, th), Fb = flat_end_forces(b, th);
  CHECK((Fa - Fb).cwiseAbs().maxCoeff() < 1e-9 * Fa.cwiseAbs().maxCoeff());
}

TEST_CASE("workspace reuse does not change results; geometry change rebuilds") {
  FlatEndModel m = slot_model();
  FlatEndWorkspace ws(m);
  const VectorXd th = rotation_angles(90);
  Points3 a(90, 3), b(90, 3);
  flat_end_forces(m, ws, th, a);
  flat_end_forces(m, ws, th, b);
  CHECK((a - b).cwiseAbs().maxCoeff() == 0.0);
  m.axial_depth = 1.0;
  flat_end_forces(m, ws, th, b);
  CHECK(ws.disks() == m.disks());
}

TEST_CASE("engagement map from the window equals the window") {
  FlatEndModel m = slot_model();
  m.disk_height = 0.05;
  m.engagement = AngularEngagement::from_mode(MillingMode::up, 5.0, 2.5);
  const EngagementMap map = EngagementMap::from_window(m.engagement, m.disks(), 3600);
  const VectorXd th = rotation_angles(720);
  const Points3 a = flat_end_forces(m, th), b = flat_end_forces(m, th, map);
  // bins are 0.1°: differences only where an element sits within a bin of the window edge
  CHECK((a.colwise().mean() - b.colwise().mean()).norm() < 2e-3 * a.colwise().mean().norm());
}

TEST_CASE("bad input names the field") {
  FlatEndModel m = slot_model();
  m.axial_depth = -1;
  CHECK_THROWS_WITH_AS(m.validate(), doctest::Contains("axial_depth = -1"), std::invalid_argument);
  m = slot_model();
  m.feed_per_tooth = NAN;
  CHECK_THROWS_WITH_AS(m.validate(), doctest::Contains("feed_per_tooth"), std::invalid_argument);
  CHECK_THROWS_AS(AngularEngagement::from_mode(MillingMode::up, 5.0, 11.0), std::invalid_argument);
  CHECK_THROWS_AS(milling_mode_from_string("climb"), std::invalid_argument);
  CHECK_THROWS_AS(ball_end_coefficient_set("nope"), std::invalid_argument);
}

TEST_CASE("per-revolution summary") {
  FlatEndModel m = slot_model();
  const VectorXd th = rotation_angles(720, 2.0);
  const Points3 F = flat_end_forces(m, th);
  const auto revs = summarize_revolutions(th, F);
  REQUIRE(revs.size() == 2);
  CHECK((revs[0].mean - revs[1].mean).norm() < 1e-9);
  CHECK(revs[0].peak_resultant >= revs[0].mean_resultant);
}

namespace {
// The flat model one element at a time, in the operations of FlatEndWorkspace::reset and the
// element loop (offsets wrapped once, sin/cos by angle addition), so that every element's force is
// the same double as in the vectorised loop and only the order of the sums differs.
Points3 flat_forces_one_by_one(const FlatEndModel& m, const VectorXd& th, const EngagementMap* map) {
  const double tp = 2.0 * pi;
  const auto wrap = [tp](double a) { return a - tp * std::floor(a / tp); };
  const int disks = m.disks(), N = m.flutes;
  const double dz = m.axial_depth / disks, kb = m.k_beta();
  const double st = m.engagement.phi_st, span = m.engagement.phi_ex - m.engagement.phi_st;
  const auto& k = m.linear_edge;
  const bool kd = m.coefficient_model == FlatCoefficientModel::kline_devor;
  Points3 F = Points3::Zero(th.size(), 3);
  for (Eigen::Index a = 0; a < th.size(); ++a) {
    const double s0 = std::sin(th[a]), c0 = std::cos(th[a]);
    for (int i = 0; i < disks; ++i)
      for (int j = 0; j < N; ++j) {
        const double z = (i + 0.5) * dz;
        const double o = j * tp / N - kb * z;
        double ph = wrap(th[a]) + wrap(o);
        if (ph >= tp) ph -= tp;
        const double sp = s0 * std::cos(o) + c0 * std::sin(o), cp = c0 * std::cos(o) - s0 * std::sin(o);
        bool in;
        if (map) {
          const int b = std::min(static_cast<int>(ph * (map->bins() / tp)), map->bins() - 1);
          in = map->mask(i, b) != 0;
        } else {
          double u = ph - st;
          if (u < 0.0) u += tp;
          in = u <= span;
        }
        if (!in) continue;
        if (!kd) {
          const double h = std::max(m.feed_per_tooth * sp, 0.0);
          const double ft = (k.ktc * h + k.kte) * dz, fr = (k.krc * h + k.kre) * dz;
          F(a, 0) += -ft * cp - fr * sp;
          F(a, 1) += ft * sp - fr * cp;
          F(a, 2) += (k.kac * h + k.kae) * dz;
        } else {
          const double tc = std::max(m.feed_per_tooth * sp, 0.0);
          const double dFT = m.kline_devor.kt * tc * dz, dFR = m.kline_devor.kr * dFT;
          F(a, 0) += -dFR * sp - dFT * cp;
          F(a, 1) += -dFR * cp + dFT * sp;
        }
      }
  }
  return F;
}
}  // namespace

TEST_CASE("vectorised element loop equals the model evaluated one element at a time") {
  // element counts 1..13 cover every remainder of the 4-element steps (padded last step);
  // angles beyond ±2π check the wrapping; both coefficient models, window and map engagement
  for (int flutes : {1, 3, 4}) {
    for (int disks : {1, 2, 3, 5, 13}) {
      for (int kd = 0; kd < 2; ++kd) {
        for (int use_map = 0; use_map < 2; ++use_map) {
          FlatEndModel m = slot_model();
          m.flutes = flutes;
          m.axial_depth = 2.0;
          m.disk_height = 2.0 / disks;
          m.engagement = AngularEngagement::from_mode(MillingMode::down, 5.0, 3.0);
          if (kd) {
            m.coefficient_model = FlatCoefficientModel::kline_devor;
            m.kline_devor = {800.0, 0.3};
          }
          REQUIRE(m.disks() == disks);
          VectorXd th = rotation_angles(997, 3.3);
          th.array() -= 7.0;
          const EngagementMap map = EngagementMap::from_window(m.engagement, disks, 720);
          const Points3 got = use_map ? flat_end_forces(m, th, map) : flat_end_forces(m, th);
          const Points3 ref = flat_forces_one_by_one(m, th, use_map ? &map : nullptr);
          CAPTURE(flutes);
          CAPTURE(disks);
          CAPTURE(kd);
          CAPTURE(use_map);
          CHECK((got - ref).cwiseAbs().maxCoeff() <= 1e-13 * ref.cwiseAbs().maxCoeff());
        }
      }
    }
  }
}
