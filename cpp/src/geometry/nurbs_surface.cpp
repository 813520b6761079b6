// NurbsSurface (netshape/geometry/nurbs_surface.hpp): construction, one-point derivatives and normals,
// knot insertion and iso-curves; batch evaluation is in nurbs_surface_evaluate.cpp, projection in
// nurbs_surface_projection.cpp.
#include "netshape/geometry/nurbs_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/geometry/basis.hpp"
#include "geometry/nurbs_surface_internal.hpp"

namespace netshape::geometry {

using detail::kDegenerateRel;

namespace {
// Per span s = p … n − 1: reciprocals of the knot differences the basis recursion divides by.
std::vector<double> detail_inverse_knot_table(const VectorXd& U, int p, int n) {
  const int stride = p * (p + 1) / 2 + 2 * (p + 1);
  std::vector<double> t(static_cast<std::size_t>(n - p) * stride, 0.0);
  auto inv = [](double d) { return d > 0 ? 1.0 / d : 0.0; };
  for (int s = p; s < n; ++s) {
    double* row = t.data() + static_cast<std::size_t>(s - p) * stride;
    int k = 0;
    for (int j = 1; j <= p; ++j)
      for (int r = 0; r < j; ++r) row[k++] = inv(U[s + r + 1] - U[s + 1 - j + r]);
    for (int r = 0; r <= p; ++r) {
      const int i = s - p + r;
      row[k + r] = inv(U[i + p] - U[i]);
      row[k + p + 1 + r] = inv(U[i + p + 1] - U[i + 1]);
    }
  }
  return t;
}
}  // namespace

NurbsSurface::NurbsSurface(int degree_u, int degree_v, VectorXd knots_u, VectorXd knots_v, Points3 control_points,
                           VectorXd weights)
    : degree_u_(degree_u), degree_v_(degree_v), knots_u_(std::move(knots_u)), knots_v_(std::move(knots_v)),
      control_points_(std::move(control_points)), weights_(std::move(weights)) {
  NETSHAPE_CHECK(degree_u_ >= 1, "degree_u", degree_u_, "must be at least 1");
  NETSHAPE_CHECK(degree_v_ >= 1, "degree_v", degree_v_, "must be at least 1");
  NETSHAPE_CHECK(knots_u_.size() >= 2 * degree_u_ + 2, "knots_u.size", knots_u_.size(),
                 "must be at least 2 (degree_u + 1)");
  NETSHAPE_CHECK(knots_v_.size() >= 2 * degree_v_ + 2, "knots_v.size", knots_v_.size(),
                 "must be at least 2 (degree_v + 1)");
  count_u_ = static_cast<int>(knots_u_.size()) - degree_u_ - 1;
  count_v_ = static_cast<int>(knots_v_.size()) - degree_v_ - 1;
  validate_knots(knots_u_, degree_u_, count_u_, "knots_u");
  validate_knots(knots_v_, degree_v_, count_v_, "knots_v");
  const Eigen::Index n = static_cast<Eigen::Index>(count_u_) * count_v_;
  NETSHAPE_CHECK(control_points_.rows() == n, "control_points.rows", control_points_.rows(),
                 "must equal (len(knots_u) - degree_u - 1) * (len(knots_v) - degree_v - 1)");
  pw_ = detail::homogeneous_control_points(control_points_, weights_);
  const Vec3 lo = control_points_.colwise().minCoeff().transpose();
  const Vec3 hi = control_points_.colwise().maxCoeff().transpose();
  size_ = std::max((hi - lo).norm(), 1e-300);
  // first derivatives below these are "vanishing" (collapsed edge / pole) [mm per parameter unit]
  tiny_u_ = 1e-9 * size_ / (knots_u_[count_u_] - knots_u_[degree_u_]);
  tiny_v_ = 1e-9 * size_ / (knots_v_[count_v_] - knots_v_[degree_v_]);
  inv_u_ = detail_inverse_knot_table(knots_u_, degree_u_, count_u_);
  inv_v_ = detail_inverse_knot_table(knots_v_, degree_v_, count_v_);
}

bool NurbsSurface::is_rational() const noexcept { return (weights_.array() != weights_[0]).any(); }
std::pair<double, double> NurbsSurface::domain_u() const noexcept {
  return {knots_u_[degree_u_], knots_u_[count_u_]};
}
std::pair<double, double> NurbsSurface::domain_v() const noexcept {
  return {knots_v_[degree_v_], knots_v_[count_v_]};
}

std::pair<double, double> NurbsSurface::check_parameters(double u, double v) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const double tu = 1e-12 * std::max(1.0, ub - ua), tv = 1e-12 * std::max(1.0, vb - va);
  NETSHAPE_CHECK(std::isfinite(u) && u >= ua - tu && u <= ub + tu, "u", u,
                 "must lie in the surface's u domain");
  NETSHAPE_CHECK(std::isfinite(v) && v >= va - tv && v <= vb + tv, "v", v,
                 "must lie in the surface's v domain");
  return {std::clamp(u, ua, ub), std::clamp(v, va, vb)};
}

MatrixXdR NurbsSurface::derivatives(double u, double v, int d) const {
  NETSHAPE_CHECK(d >= 0, "order", d, "must be non-negative");
  std::tie(u, v) = check_parameters(u, v);
  const int p = degree_u_, q = degree_v_;
  const int du = std::min(d, p), dv = std::min(d, q);
  const int su = find_span(count_u_, p, u, knots_u_.data());
  const int sv = find_span(count_v_, q, v, knots_v_.data());
  std::vector<double> Nu((du + 1) * (p + 1)), Nv((dv + 1) * (q + 1));
  std::vector<double> scratch(ders_scratch_size(std::max(p, q)));
  basis_function_derivatives(su, u, p, du, knots_u_.data(), Nu.data(), scratch.data());
  basis_function_derivatives(sv, v, q, dv, knots_v_.data(), Nv.data(), scratch.data());
  const int D = d + 1;
  // homogeneous derivatives Aw_{k,l} (A3.6), stored (D·D, 4)
  Points4 aw = Points4::Zero(D * D, 4);
  Points4 temp(q + 1, 4);
  for (int k = 0; k <= du; ++k) {
    for (int s = 0; s <= q; ++s) {
      temp.row(s).setZero();
      for (int r = 0; r <= p; ++r)
        temp.row(s) += Nu[k * (p + 1) + r] * pw_.row((su - p + r) * count_v_ + (sv - q + s));
    }
    const int dd = std::min(d - k, dv);
    for (int l = 0; l <= dd; ++l)
      for (int s = 0; s <= q; ++s) aw.row(k * D + l) += Nv[l * (q + 1) + s] * temp.row(s);
  }
  // rational derivatives (A4.4)
  MatrixXdR skl = MatrixXdR::Zero(D * D, 3);
  const double w00 = aw(0, 3);
  for (int k = 0; k <= d; ++k) {
    for (int l = 0; l <= d - k; ++l) {
      Eigen::RowVector3d v3 = aw.row(k * D + l).head<3>();
      for (int j = 1; j <= l; ++j) v3 -= binomial(l, j) * aw(j, 3) * skl.row(k * D + l - j);
      for (int i = 1; i <= k; ++i) {
        v3 -= binomial(k, i) * aw(i * D, 3) * skl.row((k - i) * D + l);
        Eigen::RowVector3d v2 = Eigen::RowVector3d::Zero();
        for (int j = 1; j <= l; ++j) v2 += binomial(l, j) * aw(i * D + j, 3) * skl.row((k - i) * D + l - j);
        v3 -= binomial(k, i) * v2;
      }
      skl.row(k * D + l) = v3 / w00;
    }
  }
  return skl;
}

Vec3 NurbsSurface::point(double u, double v) const { return derivatives(u, v, 0).row(0).transpose(); }

Vec3 NurbsSurface::normal(double u, double v) const {
  std::tie(u, v) = check_parameters(u, v);
  const MatrixXdR d = derivatives(u, v, 1);
  const Vec3 su = d.row(2).transpose(), sv = d.row(1).transpose();  // D = 2: row k·2 + l
  const Vec3 n = su.cross(sv);
  const double nn = n.norm();
  if (su.norm() > tiny_u_ && sv.norm() > tiny_v_ && nn > kDegenerateRel * su.norm() * sv.norm()) return n / nn;
  return degenerate_normal(u, v);
}

Vec3 NurbsSurface::degenerate_normal(double u, double v) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const int K = std::max(degree_u_, degree_v_) + 1;
  const int D = K + 1;
  const MatrixXdR d = derivatives(u, v, K);
  auto S = [&](int k, int l) -> Vec3 { return d.row(k * D + l).transpose(); };
  const double tiny_u = tiny_u_, tiny_v = tiny_v_;
  const Vec3 su = S(1, 0), sv = S(0, 1);
  // S_v vanishes on an edge u = u0: S_v(u0 + δ, v) ≈ δ^k/k! ∂^k_u S_v, normal → sgn(δ)^k unit(S_u × ∂^k_u S_v).
  if (sv.norm() <= tiny_v && su.norm() > tiny_u) {
    const double dir = (u < ub) ? 1.0 : -1.0;
    for (int k = 1; k + 1 <= K; ++k) {
      const Vec3 c = su.cross(S(k, 1));
      if (c.norm() > kDegenerateRel * su.norm() * S(k, 1).norm() && c.norm() > 1e-300)
        return ((k % 2 == 1) ? dir : 1.0) * c.normalized();
    }
  }
  if (su.norm() <= tiny_u && sv.norm() > tiny_v) {
    const double dir = (v < vb) ? 1.0 : -1.0;
    for (int k = 1; k + 1 <= K; ++k) {
      const Vec3 c = S(1, k).cross(sv);
      if (c.norm() > kDegenerateRel * sv.norm() * S(1, k).norm() && c.norm() > 1e-300)
        return ((k % 2 == 1) ? dir : 1.0) * c.normalized();
    }
  }
  // General fallback: mean of the normals on a ring of neighbouring parameters inside the domain.
  for (double eps : {1e-6, 1e-4, 1e-2}) {
    Vec3 sum = Vec3::Zero();
    for (int a = 0; a < 8; ++a) {
      const double t = 2.0 * pi * a / 8.0;
      const double uu = std::clamp(u + eps * (ub - ua) * std::cos(t), ua, ub);
      const double vv = std::clamp(v + eps * (vb - va) * std::sin(t), va, vb);
      const MatrixXdR e = derivatives(uu, vv, 1);
      const Vec3 n = Vec3(e.row(2).transpose()).cross(Vec3(e.row(1).transpose()));
      const double nn = n.norm();
      if (e.row(2).norm() > tiny_u_ && e.row(1).norm() > tiny_v_ &&
          nn > kDegenerateRel * e.row(2).norm() * e.row(1).norm())
        sum += n / nn;
    }
    if (sum.norm() > 1e-6) return sum.normalized();
  }
  throw Error("NurbsSurface::normal: the surface is degenerate around (u, v) = (" + std::to_string(u) + ", " +
              std::to_string(v) + "); no normal can be defined");
}

SurfaceWorkspace NurbsSurface::make_workspace() const {
  SurfaceWorkspace ws;
  ws.degree_u = degree_u_;
  ws.degree_v = degree_v_;
  ws.count_v = count_v_;
  ws.nu.resize(2 * (degree_u_ + 1));
  ws.nv.resize(2 * (degree_v_ + 1));
  ws.scratch_u.resize(ders_scratch_size(degree_u_));
  ws.scratch_v.resize(ders_scratch_size(degree_v_));
  ws.row0.resize(4 * count_v_);
  ws.row1.resize(4 * count_v_);
  return ws;
}

NurbsSurface NurbsSurface::insert_knot_u(double u, int times) const {
  u = check_parameters(u, domain_v().first).first;
  // rows = u index, columns = all v control points (homogeneous)
  const MatrixXdR rows = Eigen::Map<const MatrixXdR>(pw_.data(), count_u_, 4 * count_v_);
  VectorXd UQ;
  MatrixXdR Q;
  detail::insert_knot_rows(degree_u_, knots_u_, rows, u, times, UQ, Q);
  const Eigen::Index n = Q.rows() * count_v_;
  Points3 cp(n, 3);
  VectorXd w(n);
  const Eigen::Map<const Points4> q4(Q.data(), n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    w[i] = q4(i, 3);
    cp.row(i) = q4.row(i).head<3>() / w[i];
  }
  return NurbsSurface(degree_u_, degree_v_, std::move(UQ), knots_v_, std::move(cp), std::move(w));
}

NurbsSurface NurbsSurface::insert_knot_v(double v, int times) const {
  v = check_parameters(domain_u().first, v).second;
  MatrixXdR rows(count_v_, 4 * count_u_);  // rows = v index
  for (int i = 0; i < count_u_; ++i)
    for (int j = 0; j < count_v_; ++j) rows.block<1, 4>(j, 4 * i) = pw_.row(i * count_v_ + j);
  VectorXd VQ;
  MatrixXdR Q;
  detail::insert_knot_rows(degree_v_, knots_v_, rows, v, times, VQ, Q);
  const int nv = static_cast<int>(Q.rows());
  Points3 cp(static_cast<Eigen::Index>(count_u_) * nv, 3);
  VectorXd w(cp.rows());
  for (int i = 0; i < count_u_; ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::RowVector4d h = Q.block<1, 4>(j, 4 * i);
      w[i * nv + j] = h[3];
      cp.row(i * nv + j) = h.head<3>() / h[3];
    }
  return NurbsSurface(degree_u_, degree_v_, knots_u_, std::move(VQ), std::move(cp), std::move(w));
}

NurbsSurface NurbsSurface::swap_uv() const {
  Points3 cp(control_points_.rows(), 3);
  VectorXd w(weights_.size());
  for (int i = 0; i < count_u_; ++i)
    for (int j = 0; j < count_v_; ++j) {
      cp.row(j * count_u_ + i) = control_points_.row(i * count_v_ + j);
      w[j * count_u_ + i] = weights_[i * count_v_ + j];
    }
  return NurbsSurface(degree_v_, degree_u_, knots_v_, knots_u_, std::move(cp), std::move(w));
}

NurbsCurve NurbsSurface::iso_curve_u(double u0) const {
  u0 = check_parameters(u0, domain_v().first).first;
  const int p = degree_u_;
  const int su = find_span(count_u_, p, u0, knots_u_.data());
  std::vector<double> N(p + 1), scratch(2 * (p + 1));
  basis_functions(su, u0, p, knots_u_.data(), N.data(), scratch.data());
  Points3 cp(count_v_, 3);
  VectorXd w(count_v_);
  for (int j = 0; j < count_v_; ++j) {
    Eigen::RowVector4d h = Eigen::RowVector4d::Zero();
    for (int r = 0; r <= p; ++r) h += N[r] * pw_.row((su - p + r) * count_v_ + j);
    w[j] = h[3];
    cp.row(j) = h.head<3>() / h[3];
  }
  return NurbsCurve(degree_v_, knots_v_, std::move(cp), std::move(w));
}

NurbsCurve NurbsSurface::iso_curve_v(double v0) const {
  v0 = check_parameters(domain_u().first, v0).second;
  const int q = degree_v_;
  const int sv = find_span(count_v_, q, v0, knots_v_.data());
  std::vector<double> N(q + 1), scratch(2 * (q + 1));
  basis_functions(sv, v0, q, knots_v_.data(), N.data(), scratch.data());
  Points3 cp(count_u_, 3);
  VectorXd w(count_u_);
  for (int i = 0; i < count_u_; ++i) {
    Eigen::RowVector4d h = Eigen::RowVector4d::Zero();
    for (int s = 0; s <= q; ++s) h += N[s] * pw_.row(i * count_v_ + sv - q + s);
    w[i] = h[3];
    cp.row(i) = h.head<3>() / h[3];
  }
  return NurbsCurve(degree_u_, knots_u_, std::move(cp), std::move(w));
}

}  // namespace netshape::geometry
