// Error synthesis: exact chain vs an independent 4x4 composition, first order vs exact (O(s²)),
// textbook single-component cases, tables.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <random>

#include "netshape/machine.hpp"

using namespace netshape;
using namespace netshape::machine;

namespace {

Eigen::Matrix4d hom(const Mat3& r, const Vec3& t) {
  Eigen::Matrix4d h = Eigen::Matrix4d::Identity();
  h.topLeftCorner<3, 3>() = r;
  h.topRightCorner<3, 1>() = t;
  return h;
}

Mat3 rzyx(double a, double b, double c) {
  return (Eigen::AngleAxisd(c, Vec3::UnitZ()) * Eigen::AngleAxisd(b, Vec3::UnitY()) *
          Eigen::AngleAxisd(a, Vec3::UnitX()))
      .toRotationMatrix();
}

// Independent reference: compose full 4x4 matrices and invert the workpiece chain numerically.
Vec3 reference_error(const Machine& m, const Vec3& p) {
  std::array<Vec3, 3> u;
  u[0] = Vec3::UnitX();
  u[1] = Eigen::AngleAxisd(m.ec0y, Vec3::UnitZ()) * Vec3::UnitY();
  u[2] = Eigen::AngleAxisd(m.ea0z, Vec3::UnitX()) * (Eigen::AngleAxisd(m.eb0z, Vec3::UnitY()) * Vec3::UnitZ());
  auto M = [&](int k, bool actual) {
    const double q = p[k];
    if (!actual) return hom(Mat3::Identity(), q * Vec3::Unit(k));
    const auto& e = m.axes[k].errors;
    return hom(rzyx(e[3](q), e[4](q), e[5](q)), q * u[k] + Vec3(e[0](q), e[1](q), e[2](q)));
  };
  auto W = [&](bool actual) {
    Eigen::Matrix4d ht = Eigen::Matrix4d::Identity();
    for (int k : m.tool_chain) ht = ht * hom(Mat3::Identity(), m.axes[k].origin) * M(k, actual);
    Eigen::Matrix4d hw = Eigen::Matrix4d::Identity();
    for (int k : m.workpiece_chain) {
      const Eigen::Matrix4d mk = M(k, actual);  // Trans(t) R
      const Mat3 r = mk.topLeftCorner<3, 3>();
      const Vec3 t = mk.topRightCorner<3, 1>();
      hw = hw * hom(Mat3::Identity(), m.axes[k].origin) * hom(r.transpose(), -t);  // table: Trans(-t) R^T
    }
    Vec3 d = m.tool_direction;
    if (actual)
      d = Eigen::AngleAxisd(m.spindle_tilt_a, Vec3::UnitX()) * (Eigen::AngleAxisd(m.spindle_tilt_b, Vec3::UnitY()) * d);
    Eigen::Vector4d tip;
    tip << m.spindle_nose + m.tool_length * d, 1.0;
    return Vec3((hw.inverse() * ht * tip).head<3>());
  };
  return W(true) - W(false);
}

Machine random_machine(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<int> order{0, 1, 2};
  std::shuffle(order.begin(), order.end(), rng);
  const int ntool = std::uniform_int_distribution<int>(0, 3)(rng);
  Machine m;
  m.tool_chain.assign(order.begin(), order.begin() + ntool);
  m.workpiece_chain.assign(order.begin() + ntool, order.end());
  for (int k = 0; k < 3; ++k) {
    auto& a = m.axes[k];
    a.origin = Vec3(U(rng), U(rng), U(rng)) * 100.0;
    for (int c = 0; c < 6; ++c) {
      const double unitv = c < 3 ? 0.05 : 1e-4;  // mm, rad at q = 500 mm
      std::vector<double> coef(4);
      for (int j = 0; j < 4; ++j) coef[j] = scale * unitv * U(rng) / std::pow(500.0, j);
      a.errors[c] = ErrorFunction::polynomial(coef, component_name(static_cast<Component>(c), k));
    }
  }
  m.ec0y = scale * 1e-4 * U(rng);
  m.eb0z = scale * 1e-4 * U(rng);
  m.ea0z = scale * 1e-4 * U(rng);
  m.spindle_tilt_a = scale * 1e-4 * U(rng);
  m.spindle_tilt_b = scale * 1e-4 * U(rng);
  m.spindle_nose = Vec3(U(rng), U(rng), U(rng)) * 50.0;
  m.tool_length = 100.0 + 50 * U(rng);
  m.tool_direction = Vec3(U(rng), U(rng), U(rng)).normalized();
  m.validate();
  return m;
}

}  // namespace

TEST_CASE("rotation_zyx equals Rz*Ry*Rx") {
  for (double a : {1e-5, -0.02, 0.3}) {
    const Mat3 r = rotation_zyx(a, -0.7 * a, 1.3 * a);
    CHECK((r - rzyx(a, -0.7 * a, 1.3 * a)).cwiseAbs().maxCoeff() < 1e-15);
  }
}

TEST_CASE("exact synthesis equals a direct 4x4 composition on random machines") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-400.0, 400.0);
  for (int trial = 0; trial < 40; ++trial) {
    // include big errors (scale 100: 5 mm, 0.01 rad) where second-order terms matter
    const double scale = trial % 2 ? 1.0 : 100.0;
    const Machine m = random_machine(rng, scale);
    MachineData data(m);
    for (int i = 0; i < 20; ++i) {
      const Vec3 p(U(rng), U(rng), U(rng));
      const Vec3 e = tip_error(m, data, p);
      const Vec3 r = reference_error(m, p);
      CHECK((e - r).norm() < 1e-10 * (1.0 + r.norm()) + 1e-11);
    }
  }
}

TEST_CASE("first order equals exact to second order in the error size") {
  std::mt19937 rng(11);
  const Machine base = random_machine(rng, 1.0);
  const Vec3 p(120.0, -250.0, 310.0);
  auto scaled = [&](double s) {
    Machine m = base;
    for (auto& a : m.axes)
      for (auto& f : a.errors)
        for (double& c : f.coefficients) c *= s;
    m.ec0y *= s, m.eb0z *= s, m.ea0z *= s, m.spindle_tilt_a *= s, m.spindle_tilt_b *= s;
    MachineData d(m);
    return (tip_error(m, d, p, Order::exact) - tip_error(m, d, p, Order::first)).norm();
  };
  const double d1 = scaled(10.0), d2 = scaled(20.0), d4 = scaled(40.0);
  CHECK(d1 > 0);
  CHECK(d2 / d1 == doctest::Approx(4.0).epsilon(0.05));
  CHECK(d4 / d2 == doctest::Approx(4.0).epsilon(0.05));
}

TEST_CASE("a positioning error moves only its own axis, either side") {
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < 3; ++k) {
      Machine m = side == 0 ? ideal_machine({0, 1, 2}, {}, 100.0) : ideal_machine({}, {0, 1, 2}, 100.0);
      m.axes[k].errors[k] = ErrorFunction::polynomial({0.0, 1e-5});  // 10 µm/m scale error
      MachineData data(m);
      const Vec3 p(200.0, -150.0, 300.0);
      const Vec3 e = tip_error(m, data, p);
      Vec3 expected = Vec3::Zero();
      expected[k] = 1e-5 * p[k];
      CHECK((e - expected).norm() < 1e-15);
    }
  }
}

TEST_CASE("pitch error gives an Abbe error proportional to the offset") {
  // X axis on the tool side with pitch EBX (rotation about Y); the tip sits L below the carriage.
  for (double L : {50.0, 100.0, 200.0}) {
    Machine m = ideal_machine({0}, {1, 2}, L);
    const double eps = 2e-5;
    m.axes[0].errors[4] = ErrorFunction::polynomial({eps});
    MachineData data(m);
    const Vec3 e1 = tip_error(m, data, Vec3(100, 0, 0), Order::first);
    // ε_y × (0, 0, -L) = (-ε L, 0, 0)
    CHECK(e1.x() == doctest::Approx(-eps * L).epsilon(1e-12));
    CHECK(std::abs(e1.y()) < 1e-18);
    CHECK(std::abs(e1.z()) < 1e-18);
    const Vec3 e = tip_error(m, data, Vec3(100, 0, 0));
    CHECK(e.x() == doctest::Approx(-std::sin(eps) * L).epsilon(1e-12));
    CHECK(e.z() == doctest::Approx(L * (1 - std::cos(eps))).epsilon(1e-9));
  }
}

TEST_CASE("table interpolation and range policy") {
  const auto f = ErrorFunction::table({0.0, 100.0, 300.0}, {0.0, 0.01, -0.01}, OutOfRange::error, "EXX");
  CHECK(f(50.0) == doctest::Approx(0.005));
  CHECK(f(200.0) == doctest::Approx(0.0));
  CHECK(f(300.0) == doctest::Approx(-0.01));
  CHECK_THROWS_AS(f(300.5), std::invalid_argument);
  auto g = f;
  g.out_of_range = OutOfRange::clamp;
  CHECK(g(400.0) == doctest::Approx(-0.01));
  g.out_of_range = OutOfRange::extrapolate;
  CHECK(g(400.0) == doctest::Approx(-0.02));
  CHECK(g(-100.0) == doctest::Approx(-0.01));
  CHECK_THROWS_AS(ErrorFunction::table({0.0, 0.0}, {0.0, 1.0}), std::invalid_argument);
  CHECK_THROWS_AS(ErrorFunction::table({0.0, 1.0}, {0.0, NAN}), std::invalid_argument);
  CHECK_THROWS_AS(ErrorFunction::polynomial({INFINITY}), std::invalid_argument);
}

TEST_CASE("machine validation") {
  CHECK_THROWS_AS(ideal_machine({0, 1}, {1, 2}), std::invalid_argument);
  CHECK_THROWS_AS(ideal_machine({0}, {1}), std::invalid_argument);
  Machine m = ideal_machine({2}, {1, 0});
  m.tool_direction = Vec3(0, 0, 2);
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
  m.tool_direction = Vec3(0, 0, -1);
  m.axes[1].travel_min = 10;
  m.axes[1].travel_max = 0;
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
}

TEST_CASE("first-order Jacobian matches finite differences of the error") {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const Machine m = random_machine(rng, 1.0);
    MachineData data(m);
    const Vec3 p(123.0, -211.0, 305.0);
    Mat3 jac;
    const Vec3 e = tip_error_and_jacobian(m, data, p, jac);
    CHECK((e - tip_error(m, data, p)).norm() < 1e-15);
    const double h = 1e-3;
    for (int k = 0; k < 3; ++k) {
      Vec3 a = p, b = p;
      a[k] += h;
      b[k] -= h;
      const Vec3 fd = (tip_error(m, data, a) - tip_error(m, data, b)) / (2 * h);
      // exact vs first-order Jacobian differ by O(error²) ~ 1e-8 here
      CHECK((fd - jac.col(k)).norm() < 1e-6);
      CHECK(fd.norm() > 1e-5);
    }
  }
}

TEST_CASE("tables and mixed axes (one-pass kernels and the generic path) equal the 4x4 composition") {
  // Axis k of each random machine becomes: 0 all six components tables on shared uniform positions,
  // 1 shared non-uniform positions with two zero components, 2 tables on different positions (generic),
  // 3 one table among polynomials (generic). Policies clamp / extrapolate, points partly outside the tables.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 24; ++trial) {
    Machine m = random_machine(rng, trial % 3 ? 1.0 : 100.0);
    for (int k = 0; k < 3; ++k) {
      const int mode = (trial + k) % 4;
      const OutOfRange policy = (trial + k) % 2 ? OutOfRange::clamp : OutOfRange::extrapolate;
      std::vector<double> x;
      for (int i = 0; i <= 12; ++i) x.push_back(-300.0 + 50.0 * i + (mode == 1 ? 10.0 * std::sin(1.7 * i) : 0.0));
      for (int c = 0; c < 6; ++c) {
        if (mode == 3 && c != 4) continue;  // keep the polynomials
        if (mode == 1 && (c == 1 || c == 5)) {
          m.axes[k].errors[c] = ErrorFunction::zero_function();
          continue;
        }
        std::vector<double> xc = x;
        if (mode == 2)
          for (double& xi : xc) xi += 3.0 * c;
        std::vector<double> v;
        for (double xi : xc) v.push_back(m.axes[k].errors[c](xi) + (c < 3 ? 1e-3 : 1e-6) * U(rng));
        m.axes[k].errors[c] = ErrorFunction::table(xc, v, policy, component_name(static_cast<Component>(c), k));
      }
    }
    m.validate();
    MachineData data(m);
    for (int i = 0; i < 20; ++i) {
      const Vec3 p(400.0 * U(rng), 400.0 * U(rng), 400.0 * U(rng));
      const Vec3 e = tip_error(m, data, p);
      const Vec3 r = reference_error(m, p);
      CHECK((e - r).norm() < 1e-10 * (1.0 + r.norm()) + 1e-11);
      Mat3 jac;
      // same value with slopes (tables: interpolation written through the slope, rounding-level differences)
      CHECK((tip_error_and_jacobian(m, data, p, jac) - e).norm() < 1e-14 * (1.0 + e.norm()));
    }
  }
}

TEST_CASE("a table with out_of_range = error refuses a point outside it in every kernel") {
  Machine m = ideal_machine({0, 1}, {2}, 100.0);
  m.axes[0].errors[0] = ErrorFunction::table({0.0, 100.0}, {0.0, 0.01}, OutOfRange::error, "EXX");  // packed
  m.axes[1].errors[0] = ErrorFunction::table({0.0, 100.0}, {0.0, 0.01}, OutOfRange::error, "EXY");  // mixed
  m.axes[1].errors[4] = ErrorFunction::polynomial({1e-5});
  MachineData data(m);
  CHECK_NOTHROW(tip_error(m, data, Vec3(50.0, 50.0, 0.0)));
  CHECK_THROWS_WITH_AS(tip_error(m, data, Vec3(150.0, 50.0, 0.0)), doctest::Contains("EXX"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(tip_error(m, data, Vec3(50.0, -5.0, 0.0)), doctest::Contains("EXY"), std::invalid_argument);
  CHECK_THROWS_AS(tip_error(m, data, Vec3(NAN, 50.0, 0.0)), std::invalid_argument);
}

namespace {
// tip_error_lanes against the one-point functions on `batch_lanes` points; `bad` lanes are skipped.
void check_lanes(const Machine& m, MachineData& data, const std::array<Vec3, batch_lanes>& pts, unsigned expect_bad) {
  double p[3][batch_lanes], e[3][batch_lanes], jac[9][batch_lanes], e2[3][batch_lanes];
  for (int l = 0; l < batch_lanes; ++l)
    for (int c = 0; c < 3; ++c) p[c][l] = pts[l][c];
  CHECK(tip_error_lanes(data, p, e) == expect_bad);
  CHECK(tip_error_lanes(data, p, e2, &jac) == expect_bad);
  // every vector width this CPU runs gives the same numbers to rounding
  int widths = 0;
  for (int w : {1, 2, 4, 8}) {
    if (!detail::lanes_width_supported(w)) continue;
    ++widths;
    double ew[3][batch_lanes], jw[9][batch_lanes];
    CHECK(detail::tip_error_lanes_width(w, data, p, ew, &jw) == expect_bad);
    for (int l = 0; l < batch_lanes; ++l) {
      if ((expect_bad >> l) & 1u) continue;
      // the same operations; the AVX-512 variant may fuse multiply-adds (rounding-level differences)
      for (int c = 0; c < 3; ++c) CHECK(std::abs(ew[c][l] - e2[c][l]) <= 1e-15 * (1.0 + std::abs(e2[c][l])));
      for (int j = 0; j < 9; ++j) CHECK(std::abs(jw[j][l] - jac[j][l]) <= 1e-15 * (1.0 + std::abs(jac[j][l])));
    }
  }
  CHECK(widths >= 1);
  for (int l = 0; l < batch_lanes; ++l) {
    if ((expect_bad >> l) & 1u) continue;
    Mat3 j1;
    const Vec3 ref = tip_error_and_jacobian(m, data, pts[l], j1);
    const Vec3 ref0 = tip_error(m, data, pts[l]);
    const double scale = 1e-15 * (1.0 + ref.norm());
    for (int c = 0; c < 3; ++c) {
      CHECK(std::abs(e[c][l] - ref0[c]) <= scale);
      CHECK(std::abs(e2[c][l] - ref0[c]) <= scale);
      for (int col = 0; col < 3; ++col) CHECK(std::abs(jac[3 * col + c][l] - j1(c, col)) <= 1e-15 * (1.0 + j1.norm()));
    }
  }
}
}  // namespace

TEST_CASE("many points at once (vectorised) equal the one-point synthesis and Jacobian") {
  // polynomial machines, table machines (uniform: vector lookup; non-uniform, mixed: per lane), angles
  // above 1e-3 rad (per-lane fallback), lanes outside a table with policy clamp / extrapolate
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 24; ++trial) {
    Machine m = random_machine(rng, trial % 3 ? 1.0 : 100.0);
    if (trial % 4 >= 2) {
      for (int k = 0; k < 3; ++k) {
        const bool uniform = (trial + k) % 3 != 0;
        std::vector<double> x;
        for (int i = 0; i <= 12; ++i) x.push_back(-300.0 + 50.0 * i + (uniform ? 0.0 : 10.0 * std::sin(1.7 * i)));
        const OutOfRange policy = (trial + k) % 2 ? OutOfRange::clamp : OutOfRange::extrapolate;
        for (int c = 0; c < 6; ++c) {
          if ((trial + k) % 5 == 0 && c == 2) continue;  // a polynomial among tables: generic per-function path
          std::vector<double> v;
          for (double xi : x) v.push_back(m.axes[k].errors[c](xi));
          m.axes[k].errors[c] = ErrorFunction::table(x, v, policy);
        }
      }
      m.validate();
    }
    MachineData data(m);
    for (int rep = 0; rep < 4; ++rep) {
      std::array<Vec3, batch_lanes> pts;
      // rep 0: all inside ±280 mm (tables: vector lookup), others: some lanes outside the tables
      const double r = rep == 0 ? 280.0 : 400.0;
      for (auto& q : pts) q = Vec3(r * U(rng), r * U(rng), r * U(rng));
      check_lanes(m, data, pts, 0u);
    }
  }
}

TEST_CASE("many points at once: points outside a table with policy error are flagged, not thrown") {
  Machine m = ideal_machine({0, 1}, {2}, 100.0);
  for (int c = 0; c < 6; ++c)
    m.axes[0].errors[c] = ErrorFunction::table({0.0, 50.0, 100.0}, {0.0, 1e-3, 0.01}, OutOfRange::error, "EXX");
  m.axes[1].errors[0] = ErrorFunction::table({0.0, 100.0}, {0.0, 0.01}, OutOfRange::error, "EXY");  // mixed
  m.axes[1].errors[4] = ErrorFunction::polynomial({1e-5});
  MachineData data(m);
  std::array<Vec3, batch_lanes> pts;
  for (int l = 0; l < batch_lanes; ++l) pts[l] = Vec3(10.0 * l, 5.0 * l, 0.0);
  pts[2].x() = 150.0;   // outside X's table
  pts[5].y() = -5.0;    // outside Y's table
  pts[7].z() = NAN;     // not finite (polynomial Z)
  check_lanes(m, data, pts, (1u << 2) | (1u << 5) | (1u << 7));
}

TEST_CASE("many points at once: exact Jacobian and second-order terms match finite differences") {
  // lane_jacobian is ∂e/∂p of the exact synthesis (forward differentiation along the chain);
  // lane_curvature gives the second derivative of e along d (exact minus it is O(error · slope))
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double worst_j = 0.0, worst_h = 0.0;
  for (int trial = 0; trial < 12; ++trial) {
    const Machine m = random_machine(rng, 1.0);
    MachineData data(m);
    for (int w : {1, 2, 4, 8}) {
      if (!detail::lanes_width_supported(w)) continue;
      double p[3][batch_lanes], e[3][batch_lanes], jac[9][batch_lanes];
      for (int c = 0; c < 3; ++c)
        for (int l = 0; l < batch_lanes; ++l) p[c][l] = 300.0 * U(rng);
      REQUIRE(detail::tip_error_lanes_width(w, data, p, e, &jac) == 0u);
      for (int l = 0; l < batch_lanes; ++l) {
        const Vec3 q(p[0][l], p[1][l], p[2][l]);
        for (int k = 0; k < 3; ++k) {
          const double h = 1e-2;
          Vec3 a = q, b = q;
          a[k] += h;
          b[k] -= h;
          const Vec3 fd = (tip_error(m, data, a) - tip_error(m, data, b)) / (2 * h);
          const Vec3 jk(data.lane_jacobian[3 * k][l], data.lane_jacobian[3 * k + 1][l],
                        data.lane_jacobian[3 * k + 2][l]);
          worst_j = std::max(worst_j, (fd - jk).norm());
        }
        // second derivative along d (|d| ≈ 0.5 mm)
        const Vec3 d(0.3 * U(rng), 0.3 * U(rng), 0.3 * U(rng));
        const Vec3 fd2 = tip_error(m, data, q + d) + tip_error(m, data, q - d) - 2.0 * tip_error(m, data, q);
        Vec3 hd = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
          Vec3 wk = Vec3::Zero();
          for (int j = 0; j < 3; ++j)
            if (data.compiled().arm_grows[j][k]) wk[j] = d[j];
          const Vec3 g(data.lane_curvature[3 * k][l], data.lane_curvature[3 * k + 1][l],
                       data.lane_curvature[3 * k + 2][l]);
          const Vec3 es(data.lane_curvature[9 + 3 * k][l], data.lane_curvature[10 + 3 * k][l],
                        data.lane_curvature[11 + 3 * k][l]);
          hd += d[k] * d[k] * g + 2.0 * d[k] * es.cross(wk);
        }
        worst_h = std::max(worst_h, (fd2 - hd).norm() / std::max(fd2.norm(), 1e-12));
      }
    }
  }
  MESSAGE("exact Jacobian vs finite differences: " << worst_j << ", H[d,d] relative: " << worst_h);
  CHECK(worst_j < 1e-9);   // the first-order Jacobian is off by ~1e-8 here
  CHECK(worst_h < 1e-2);
}
