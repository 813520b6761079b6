#include "netshape/geometry/nurbs_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/geometry/basis.hpp"

namespace netshape::geometry {

NurbsCurve::NurbsCurve(int degree, VectorXd knots, Points3 control_points, VectorXd weights)
    : degree_(degree), knots_(std::move(knots)), control_points_(std::move(control_points)),
      weights_(std::move(weights)) {
  NETSHAPE_CHECK(degree_ >= 1, "degree", degree_, "must be at least 1");
  const int n = static_cast<int>(control_points_.rows());
  NETSHAPE_CHECK(n >= degree_ + 1, "control_points.rows", n, "need at least degree + 1 control points");
  validate_knots(knots_, degree_, n, "knots");
  pw_ = detail::homogeneous_control_points(control_points_, weights_);
}

bool NurbsCurve::is_rational() const noexcept {
  return weights_.size() > 0 && (weights_.array() != weights_[0]).any();
}

std::pair<double, double> NurbsCurve::domain() const noexcept {
  return {knots_[degree_], knots_[count()]};
}

double NurbsCurve::check_parameter(double u, const char* field) const {
  const auto [a, b] = domain();
  const double tol = 1e-12 * std::max(1.0, b - a);
  NETSHAPE_CHECK(std::isfinite(u) && u >= a - tol && u <= b + tol, field, u,
                 "must lie in the curve's parameter domain");
  return std::clamp(u, a, b);
}

Points3 NurbsCurve::derivatives(double u, int order) const {
  NETSHAPE_CHECK(order >= 0, "order", order, "must be non-negative");
  u = check_parameter(u);
  const int p = degree_;
  const int du = std::min(order, p);
  const int span = find_span(count(), p, u, knots_.data());
  std::vector<double> nd((du + 1) * (p + 1)), scratch(ders_scratch_size(p));
  basis_function_derivatives(span, u, p, du, knots_.data(), nd.data(), scratch.data());
  // homogeneous derivatives Aw^(k) (A3.2)
  Points4 ck = Points4::Zero(order + 1, 4);
  for (int k = 0; k <= du; ++k)
    for (int j = 0; j <= p; ++j) ck.row(k) += nd[k * (p + 1) + j] * pw_.row(span - p + j);
  // rational derivatives (A4.2)
  Points3 out(order + 1, 3);
  for (int k = 0; k <= order; ++k) {
    Eigen::RowVector3d v = ck.row(k).head<3>();
    for (int i = 1; i <= k; ++i) v -= binomial(k, i) * ck(i, 3) * out.row(k - i);
    out.row(k) = v / ck(0, 3);
  }
  return out;
}

Vec3 NurbsCurve::point(double u) const { return derivatives(u, 0).row(0).transpose(); }

Vec3 NurbsCurve::tangent(double u) const {
  const Points3 d = derivatives(u, degree_ + 1);
  const double scale = std::max(1.0, control_points_.cwiseAbs().maxCoeff());
  for (int k = 1; k <= degree_; ++k) {
    const Vec3 t = d.row(k).transpose();
    if (t.norm() > 1e-12 * scale) return t.normalized();
  }
  throw Error("NurbsCurve::tangent: all derivatives vanish at u = " + std::to_string(u) +
              " (curve collapsed to a point)");
}

Points3 NurbsCurve::evaluate(const Eigen::Ref<const VectorXd>& us) const {
  const int p = degree_;
  Points3 out(us.size(), 3);
  std::vector<double> N(p + 1), scratch(2 * (p + 1));
  for (Eigen::Index m = 0; m < us.size(); ++m) {
    const double u = check_parameter(us[m], "us");
    const int span = find_span(count(), p, u, knots_.data());
    basis_functions(span, u, p, knots_.data(), N.data(), scratch.data());
    Eigen::RowVector4d a = Eigen::RowVector4d::Zero();
    for (int j = 0; j <= p; ++j) a += N[j] * pw_.row(span - p + j);
    out.row(m) = a.head<3>() / a[3];
  }
  return out;
}

Points3 NurbsCurve::sample(int n) const {
  NETSHAPE_CHECK(n >= 2, "count", n, "must be at least 2");
  const auto [a, b] = domain();
  return evaluate(VectorXd::LinSpaced(n, a, b));
}

int NurbsCurve::knot_multiplicity(double u) const noexcept {
  return static_cast<int>((knots_.array() == u).count());
}

namespace detail {
void insert_knot_rows(int p, const VectorXd& UP, const MatrixXdR& Pw, double u, int r, VectorXd& UQ,
                      MatrixXdR& Qw) {
  const int np = static_cast<int>(Pw.rows()) - 1;
  const int mp = np + p + 1;
  const int k = find_span(np + 1, p, u, UP.data());
  int s = 0;
  for (int i = 0; i <= mp; ++i)
    if (UP[i] == u) ++s;
  NETSHAPE_CHECK(r >= 1, "times", r, "must be at least 1");
  NETSHAPE_CHECK(r + s <= p, "times", r, "multiplicity after insertion must not exceed the degree");
  const Eigen::Index cols = Pw.cols();
  UQ.resize(mp + r + 1);
  Qw.resize(np + r + 1, cols);
  for (int i = 0; i <= k; ++i) UQ[i] = UP[i];
  for (int i = 1; i <= r; ++i) UQ[k + i] = u;
  for (int i = k + 1; i <= mp; ++i) UQ[i + r] = UP[i];
  for (int i = 0; i <= k - p; ++i) Qw.row(i) = Pw.row(i);
  for (int i = k - s; i <= np; ++i) Qw.row(i + r) = Pw.row(i);
  MatrixXdR Rw(p - s + 1, cols);
  for (int i = 0; i <= p - s; ++i) Rw.row(i) = Pw.row(k - p + i);
  int L = k - p;
  for (int j = 1; j <= r; ++j) {
    L = k - p + j;
    for (int i = 0; i <= p - j - s; ++i) {
      const double alpha = (u - UP[L + i]) / (UP[i + k + 1] - UP[L + i]);
      Rw.row(i) = alpha * Rw.row(i + 1) + (1.0 - alpha) * Rw.row(i);
    }
    Qw.row(L) = Rw.row(0);
    Qw.row(k + r - j - s) = Rw.row(p - j - s);
  }
  for (int i = L + 1; i < k - s; ++i) Qw.row(i) = Rw.row(i - L);
}
}  // namespace detail

NurbsCurve NurbsCurve::insert_knot(double u, int times) const {
  u = check_parameter(u);
  VectorXd UQ;
  MatrixXdR Qw;
  detail::insert_knot_rows(degree_, knots_, MatrixXdR(pw_), u, times, UQ, Qw);
  Points3 cp(Qw.rows(), 3);
  VectorXd w(Qw.rows());
  for (Eigen::Index i = 0; i < Qw.rows(); ++i) {
    w[i] = Qw(i, 3);
    cp.row(i) = Qw.row(i).head<3>() / w[i];
  }
  return NurbsCurve(degree_, std::move(UQ), std::move(cp), std::move(w));
}

CurveProjection NurbsCurve::closest_point(const Vec3& p, double tolerance, int max_iterations) const {
  for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("point", p[c]);
  NETSHAPE_CHECK(tolerance > 0.0, "tolerance", tolerance, "must be positive [mm]");
  const auto [a, b] = domain();
  const int samples = std::max(16, 4 * count() * degree_);
  const VectorXd us = VectorXd::LinSpaced(samples, a, b);
  const Points3 pts = evaluate(us);
  // Newton from the best few samples (local minima of the sampled distance), keep the best result.
  std::vector<std::pair<double, int>> order;
  for (int i = 0; i < samples; ++i) order.emplace_back((pts.row(i).transpose() - p).squaredNorm(), i);
  std::partial_sort(order.begin(), order.begin() + std::min<int>(3, samples), order.end());
  CurveProjection best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int start = 0; start < std::min(3, samples); ++start) {
    double u = us[order[start].second];
    CurveProjection r;
    for (int it = 0; it < max_iterations; ++it) {
      r.iterations = it + 1;
      const Points3 d = derivatives(u, 2);
      const Vec3 diff = d.row(0).transpose() - p;
      const Vec3 c1 = d.row(1).transpose(), c2 = d.row(2).transpose();
      const double f = c1.dot(diff);
      if (diff.norm() <= tolerance || std::abs(f) <= 1e-14 * std::max(1e-300, c1.norm() * diff.norm())) {
        r.converged = true;
        break;
      }
      const double df = c2.dot(diff) + c1.squaredNorm();
      double un = (df > 0.0) ? u - f / df : u - f / std::max(c1.squaredNorm(), 1e-300);
      un = std::clamp(un, a, b);
      if (std::abs((un - u) * c1.norm()) <= tolerance) {
        u = un;
        r.converged = true;
        break;
      }
      u = un;
    }
    r.u = u;
    r.point = point(u);
    r.distance = (r.point - p).norm();
    if (r.distance < best.distance) best = r;
  }
  return best;
}


namespace detail {

Points4 homogeneous_control_points(const Points3& control_points, VectorXd& weights) {
  const Eigen::Index n = control_points.rows();
  if (weights.size() == 0) weights = VectorXd::Ones(n);
  NETSHAPE_CHECK(weights.size() == n, "weights.size", weights.size(), "must equal the number of control points");
  Points4 pw(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = weights[i];
    NETSHAPE_CHECK(std::isfinite(w) && w > 0.0, ("weights[" + std::to_string(i) + "]").c_str(), w,
                   "must be positive and finite");
    for (int c = 0; c < 3; ++c) {
      const double x = control_points(i, c);
      NETSHAPE_CHECK(std::isfinite(x), ("control_points[" + std::to_string(i) + "]").c_str(), x,
                     "must be finite [mm]");
      pw(i, c) = x * w;
    }
    pw(i, 3) = w;
  }
  return pw;
}

}  // namespace detail

}  // namespace netshape::geometry
