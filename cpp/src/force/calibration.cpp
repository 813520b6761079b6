#include "netshape/force/calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "netshape/core/error.hpp"

namespace netshape::force {

namespace {
constexpr double two_pi = 2.0 * pi;

void check_vector(const char* name, const Eigen::Ref<const VectorXd>& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) NETSHAPE_CHECK_FINITE(name, v[i]);
}

/// ∫_0^π sin^{m+1} φ dφ = √π Γ(m/2 + 1) / Γ(m/2 + 3/2).
double sine_power_integral(double m) {
  return std::sqrt(pi) * std::exp(std::lgamma(0.5 * m + 1.0) - std::lgamma(0.5 * m + 1.5));
}

/// Golden-section minimum of f on [lo, hi].
template <class F>
double golden_min(F&& f, double lo, double hi, int iters = 60) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = lo, b = hi;
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < iters && b - a > 1e-12; ++k) {
    if (f1 <= f2) {
      b = x2; x2 = x1; f2 = f1; x1 = b - g * (b - a); f1 = f(x1);
    } else {
      a = x1; x1 = x2; f1 = f2; x2 = a + g * (b - a); f2 = f(x2);
    }
  }
  return f1 <= f2 ? x1 : x2;
}
}  // namespace

Matrix36 mean_force_matrix(const AngularEngagement& e, double c, int flutes, double a) {
  e.validate();
  NETSHAPE_CHECK_FINITE("feed_per_tooth", c);
  NETSHAPE_CHECK(c >= 0.0, "feed_per_tooth", c, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(flutes >= 1, "flutes", flutes, "must be at least 1");
  NETSHAPE_CHECK_FINITE("axial_depth", a);
  NETSHAPE_CHECK(a > 0.0, "axial_depth", a, "must be positive [mm]");
  const double p0 = e.phi_st, p1 = e.phi_ex;
  auto S2 = [](double p) { return 0.5 * std::sin(p) * std::sin(p); };  // ∫ sin cos
  auto Q = [](double p) { return 0.5 * p - 0.25 * std::sin(2.0 * p); };  // ∫ sin²
  const double dS2 = S2(p1) - S2(p0), dQ = Q(p1) - Q(p0);
  const double dsin = std::sin(p1) - std::sin(p0), dcos = std::cos(p1) - std::cos(p0);
  Matrix36 M = Matrix36::Zero();
  // columns: ktc, krc, kac, kte, kre, kae
  M(0, 0) = -c * dS2;
  M(0, 1) = -c * dQ;
  M(0, 3) = -dsin;
  M(0, 4) = dcos;
  M(1, 0) = c * dQ;
  M(1, 1) = -c * dS2;
  M(1, 3) = -dcos;
  M(1, 4) = -dsin;
  M(2, 2) = -c * dcos;
  M(2, 5) = p1 - p0;
  return M * (flutes * a / two_pi);
}

Vec3 mean_force(const LinearEdgeCoefficients& k, const AngularEngagement& e, double c, int flutes, double a) {
  k.validate();
  const auto arr = k.as_array();
  Eigen::Matrix<double, 6, 1> kv;
  for (int i = 0; i < 6; ++i) kv[i] = arr[i];
  return mean_force_matrix(e, c, flutes, a) * kv;
}

LinearEdgeFit fit_linear_edge_mean_forces(const AngularEngagement& e, int flutes, double a,
                                          const Eigen::Ref<const VectorXd>& feeds,
                                          const Eigen::Ref<const Points3>& F) {
  const Eigen::Index n = feeds.size();
  NETSHAPE_CHECK(F.rows() == n, "mean_forces.rows", F.rows(), "must equal the number of feeds");
  NETSHAPE_CHECK(n >= 2, "feeds.size", n, "needs at least 2 tests");
  check_vector("feeds", feeds);
  for (Eigen::Index i = 0; i < n; ++i) {
    NETSHAPE_CHECK(feeds[i] > 0.0, "feeds", feeds[i], "must be positive [mm/tooth]");
    for (int j = 0; j < 3; ++j) NETSHAPE_CHECK_FINITE("mean_forces", F(i, j));
  }
  NETSHAPE_CHECK(feeds.maxCoeff() - feeds.minCoeff() > 1e-9 * feeds.maxCoeff(), "feeds", feeds.maxCoeff(),
                 "needs at least 2 distinct feeds per tooth");
  Eigen::MatrixXd A(3 * n, 6);
  Eigen::VectorXd b(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    A.middleRows(3 * i, 3) = mean_force_matrix(e, feeds[i], flutes, a);
    b.segment(3 * i, 3) = F.row(i).transpose();
  }
  // scale columns so that cutting (∝ c) and edge columns are comparable
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (int j = 0; j < 6; ++j) {
    if (scale[j] <= 0) throw Error("mean-force regression: coefficient column " + std::to_string(j) + " is not observable");
    A.col(j) /= scale[j];
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 6) throw Error("mean-force regression: the tests do not determine all six coefficients");
  Eigen::VectorXd k = qr.solve(b);
  k = k.cwiseQuotient(scale);
  LinearEdgeFit fit;
  fit.coefficients = LinearEdgeCoefficients::from_array({k[0], k[1], k[2], k[3], k[4], k[5]});
  fit.residuals.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    fit.residuals.row(i) = F.row(i) - mean_force(fit.coefficients, e, feeds[i], flutes, a).transpose();
  for (int j = 0; j < 3; ++j) {
    const double mu = F.col(j).mean();
    const double tot = (F.col(j).array() - mu).square().sum();
    const double res = fit.residuals.col(j).squaredNorm();
    fit.r2[j] = tot > 0 ? 1.0 - res / tot : (res == 0 ? 1.0 : 0.0);
  }
  return fit;
}

Vec3 ball_end_mean_slot_force(const BallEndModel& model) {
  model.validate();
  NETSHAPE_CHECK(model.inclination == 0.0, "inclination", model.inclination,
                 "must be 0 for the closed-form mean slot force [rad]");
  BallEndWorkspace ws(model);
  const auto& K = model.coefficients;
  const double f = model.feed_per_tooth;
  const double It = sine_power_integral(K.m_t), Ir = sine_power_integral(K.m_r);
  double sy = 0, sx = 0;
  for (int i = 0; i < ws.rows(); ++i) {
    const double psi = ws.position_angles()[i];
    sy += K.kt(psi) * ws.widths()[i];
    sx += K.kr(psi) * ws.widths()[i];
  }
  const double scale = model.flutes / two_pi;
  Vec3 out;
  out[0] = -scale * std::pow(f, K.m_r) * Ir * sx;
  out[1] = scale * std::pow(f, K.m_t) * It * sy;
  out[2] = 0.0;
  return out;
}

BallEndFit fit_ball_end_mean_forces(const BallEndModel& geometry, const Eigen::Ref<const VectorXd>& depths,
                                    const Eigen::Ref<const VectorXd>& feeds, const Eigen::Ref<const VectorXd>& mean_fx,
                                    const Eigen::Ref<const VectorXd>& mean_fy, double m_min, double m_max) {
  const Eigen::Index n = depths.size();
  NETSHAPE_CHECK(feeds.size() == n && mean_fx.size() == n && mean_fy.size() == n, "feeds.size", feeds.size(),
                 "depths, feeds, mean_fx and mean_fy must have the same length");
  NETSHAPE_CHECK(n >= 5, "depths.size", n, "needs at least 5 slot tests");
  check_vector("depths", depths);
  check_vector("feeds", feeds);
  check_vector("mean_fx", mean_fx);
  check_vector("mean_fy", mean_fy);
  NETSHAPE_CHECK(m_min > 0.0 && m_max > m_min && m_max <= 2.0, "m_min", m_min, "need 0 < m_min < m_max ≤ 2");
  std::set<long> distinct_depths, distinct_feeds;
  for (Eigen::Index i = 0; i < n; ++i) {
    NETSHAPE_CHECK(depths[i] > 0.0, "depths", depths[i], "must be positive [mm]");
    NETSHAPE_CHECK(feeds[i] > 0.0, "feeds", feeds[i], "must be positive [mm/tooth]");
    distinct_depths.insert(std::lround(depths[i] * 1e6));
    distinct_feeds.insert(std::lround(feeds[i] * 1e9));
  }
  NETSHAPE_CHECK(distinct_depths.size() >= 4, "depths", static_cast<double>(distinct_depths.size()),
                 "needs at least 4 distinct axial depths (distinct count shown)");
  NETSHAPE_CHECK(distinct_feeds.size() >= 2, "feeds", static_cast<double>(distinct_feeds.size()),
                 "needs at least 2 distinct feeds (distinct count shown)");
  // moments S_p(i) = Σ_rows ψ^p w over the rows of test i's depth
  Eigen::MatrixXd S(n, 4);
  BallEndModel g = geometry;
  g.inclination = 0.0;
  g.engagement = AngularEngagement{0.0, pi};
  g.coefficients = BallEndCoefficients{{1, 0, 0, 0}, {1, 0, 0, 0}, 1.0, 1.0};
  for (Eigen::Index i = 0; i < n; ++i) {
    g.axial_depth = depths[i];
    g.feed_per_tooth = feeds[i];
    for (int p = 0; p < 4; ++p) {
      g.coefficients.a = {0, 0, 0, 0};
      g.coefficients.a[p] = 1.0;
      g.coefficients.m_t = 1.0;
      // F̄y with K_T = ψ^p and m = 1 is (N/2π) f I(1) S_p
      const Vec3 m = ball_end_mean_slot_force(g);
      S(i, p) = m[1] / (g.flutes / two_pi * feeds[i] * sine_power_integral(1.0));
    }
  }
  const double scale = geometry.flutes / two_pi;
  // sign: F̄y = +scale f^m I(m) Σ a_p S_p ; F̄x = −scale f^m I(m) Σ b_p S_p
  auto solve = [&](double m, const Eigen::Ref<const VectorXd>& y, double sign, Eigen::Vector4d* coef) {
    Eigen::MatrixXd A(n, 4);
    for (Eigen::Index i = 0; i < n; ++i)
      A.row(i) = sign * scale * std::pow(feeds[i], m) * sine_power_integral(m) * S.row(i);
    Eigen::VectorXd cs = A.colwise().norm().transpose();
    for (int j = 0; j < 4; ++j) A.col(j) /= cs[j];
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    Eigen::Vector4d c = qr.solve(y).cwiseQuotient(cs);
    if (coef) *coef = c;
    Eigen::VectorXd r = y;
    for (Eigen::Index i = 0; i < n; ++i) r[i] -= sign * scale * std::pow(feeds[i], m) * sine_power_integral(m) * S.row(i).dot(c);
    return r.squaredNorm();
  };
  auto best_exponent = [&](const Eigen::Ref<const VectorXd>& y, double sign) {
    const int steps = 140;
    double best = m_min, fbest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= steps; ++k) {
      const double m = m_min + (m_max - m_min) * k / steps;
      const double v = solve(m, y, sign, nullptr);
      if (v < fbest) fbest = v, best = m;
    }
    const double h = (m_max - m_min) / steps;
    return golden_min([&](double m) { return solve(m, y, sign, nullptr); }, std::max(m_min, best - h),
                      std::min(m_max, best + h), 80);
  };
  BallEndFit fit;
  Eigen::Vector4d a, b;
  const double mt = best_exponent(mean_fy, +1.0);
  const double sst = solve(mt, mean_fy, +1.0, &a);
  const double mr = best_exponent(mean_fx, -1.0);
  const double ssr = solve(mr, mean_fx, -1.0, &b);
  fit.coefficients.a = {a[0], a[1], a[2], a[3]};
  fit.coefficients.b = {b[0], b[1], b[2], b[3]};
  fit.coefficients.m_t = mt;
  fit.coefficients.m_r = mr;
  fit.rms_y = std::sqrt(sst / n);
  fit.rms_x = std::sqrt(ssr / n);
  return fit;
}

std::vector<Points3> linear_edge_basis(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles) {
  FlatEndWorkspace ws(model);
  MatrixXdR M(angles.size(), 6);
  flat_end_moments(model, ws, angles, M);
  std::vector<Points3> B(6, Points3::Zero(angles.size(), 3));
  // Fx = −ktc M0 − krc M1 − kte M3 − kre M4, Fy = ktc M1 − krc M0 + kte M4 − kre M3, Fz = kac M2 + kae M5
  B[0].col(0) = -M.col(0);
  B[0].col(1) = M.col(1);
  B[1].col(0) = -M.col(1);
  B[1].col(1) = -M.col(0);
  B[2].col(2) = M.col(2);
  B[3].col(0) = -M.col(3);
  B[3].col(1) = M.col(4);
  B[4].col(0) = -M.col(4);
  B[4].col(1) = -M.col(3);
  B[5].col(2) = M.col(5);
  return B;
}

TimeSeriesFit fit_linear_edge_time_series(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                                          const Eigen::Ref<const Points3>& forces, int phase_steps) {
  const Eigen::Index n = angles.size();
  NETSHAPE_CHECK(forces.rows() == n, "forces.rows", forces.rows(), "must equal the number of angles");
  NETSHAPE_CHECK(n >= 12, "angles.size", n, "needs at least 12 samples");
  NETSHAPE_CHECK(phase_steps >= 4 && phase_steps <= 100000, "phase_steps", phase_steps, "must be in [4, 1e5]");
  check_vector("angles", angles);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int j = 0; j < 3; ++j) NETSHAPE_CHECK_FINITE("forces", forces(i, j));
  FlatEndModel m = model;
  m.coefficient_model = FlatCoefficientModel::linear_edge;
  m.linear_edge = LinearEdgeCoefficients{};
  FlatEndWorkspace ws(m);
  MatrixXdR M(n, 6);
  VectorXd shifted(n);
  Eigen::Matrix<double, 6, 1> best_k;
  // y stacked per axis
  auto evaluate = [&](double phase, Eigen::Matrix<double, 6, 1>* kout) {
    shifted = angles.array() + phase;
    flat_end_moments(m, ws, shifted, M);
    // design matrix rows: x then y then z, columns ktc krc kac kte kre kae
    Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> Atb = Eigen::Matrix<double, 6, 1>::Zero();
    double btb = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Matrix<double, 6, 1> ax, ay, az;
      ax << -M(i, 0), -M(i, 1), 0, -M(i, 3), -M(i, 4), 0;
      ay << M(i, 1), -M(i, 0), 0, M(i, 4), -M(i, 3), 0;
      az << 0, 0, M(i, 2), 0, 0, M(i, 5);
      AtA.noalias() += ax * ax.transpose() + ay * ay.transpose() + az * az.transpose();
      Atb.noalias() += ax * forces(i, 0) + ay * forces(i, 1) + az * forces(i, 2);
      btb += forces.row(i).squaredNorm();
    }
    Eigen::Matrix<double, 6, 1> d = AtA.diagonal().cwiseMax(1e-300).cwiseSqrt();
    Eigen::Matrix<double, 6, 6> As = d.cwiseInverse().asDiagonal() * AtA * d.cwiseInverse().asDiagonal();
    Eigen::Matrix<double, 6, 1> k = As.ldlt().solve(d.cwiseInverse().asDiagonal() * Atb);
    k = k.cwiseQuotient(d);
    if (kout) *kout = k;
    return btb - 2.0 * k.dot(Atb) + k.dot(AtA * k);  // residual sum of squares
  };
  const double period = two_pi / model.flutes;
  double best = 0.0, fbest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < phase_steps; ++s) {
    const double p = period * s / phase_steps;
    const double v = evaluate(p, nullptr);
    if (v < fbest) fbest = v, best = p;
  }
  const double h = period / phase_steps;
  const double phase = golden_min([&](double p) { return evaluate(p, nullptr); }, best - h, best + h, 40);
  evaluate(phase, &best_k);
  TimeSeriesFit fit;
  fit.coefficients = LinearEdgeCoefficients::from_array({best_k[0], best_k[1], best_k[2], best_k[3], best_k[4], best_k[5]});
  fit.phase = phase - two_pi * std::floor(phase / two_pi);
  m.linear_edge = fit.coefficients;
  shifted = angles.array() + fit.phase;
  Points3 sim(n, 3);
  flat_end_forces(m, ws, shifted, sim);
  const Points3 r = forces - sim;
  for (int j = 0; j < 3; ++j) fit.rms[j] = std::sqrt(r.col(j).squaredNorm() / n);
  fit.rms_total = std::sqrt(r.squaredNorm() / (3.0 * n));
  return fit;
}

}  // namespace netshape::force
