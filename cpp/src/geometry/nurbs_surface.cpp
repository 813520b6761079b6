#include "netshape/geometry/nurbs_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/geometry/basis.hpp"

namespace netshape::geometry {

namespace {
// Relative size below which a cross product S_u × S_v counts as degenerate.
constexpr double kDegenerateRel = 1e-10;
}  // namespace

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

namespace {
void check_workspace(const SurfaceWorkspace& ws, int p, int q, int nv) {
  NETSHAPE_CHECK(ws.degree_u == p && ws.degree_v == q && ws.count_v == nv &&
                     ws.row0.size() == static_cast<std::size_t>(4 * nv),
                 "workspace.degree_u", ws.degree_u, "workspace was not made by this surface's make_workspace()");
}

// Point and unit normal from homogeneous A, A_u, A_v; returns false if S_u × S_v is degenerate.
inline bool finish_point_normal(const double* A, const double* Au, const double* Av, double* P, double* N,
                                double tiny_u2, double tiny_v2) {
  const double iw = 1.0 / A[3];
  double S[3], Su[3], Sv[3];
  for (int c = 0; c < 3; ++c) S[c] = A[c] * iw;
  for (int c = 0; c < 3; ++c) {
    Su[c] = (Au[c] - Au[3] * S[c]) * iw;
    Sv[c] = (Av[c] - Av[3] * S[c]) * iw;
  }
  P[0] = S[0];
  P[1] = S[1];
  P[2] = S[2];
  if (!N) return true;
  const double n0 = Su[1] * Sv[2] - Su[2] * Sv[1];
  const double n1 = Su[2] * Sv[0] - Su[0] * Sv[2];
  const double n2 = Su[0] * Sv[1] - Su[1] * Sv[0];
  const double nn2 = n0 * n0 + n1 * n1 + n2 * n2;
  const double su2 = Su[0] * Su[0] + Su[1] * Su[1] + Su[2] * Su[2];
  const double sv2 = Sv[0] * Sv[0] + Sv[1] * Sv[1] + Sv[2] * Sv[2];
  if (!(su2 > tiny_u2) || !(sv2 > tiny_v2) || !(nn2 > kDegenerateRel * kDegenerateRel * su2 * sv2)) return false;
  const double inv = 1.0 / std::sqrt(nn2);
  N[0] = n0 * inv;
  N[1] = n1 * inv;
  N[2] = n2 * inv;
  return true;
}

// Degree-specialised kernel of the scattered evaluation (P, Q known at compile time: loops unroll,
// arrays live in registers). Returns false where the normal is degenerate (caller falls back).
// Basis functions and first derivatives (as basis_functions_d1) for a compile-time degree, with the
// knot-difference reciprocals read from a per-span table (no divisions):
// inv[0 .. P(P+1)/2) for the A2.2 steps, then 1/(U_{i+P} − U_i) and 1/(U_{i+P+1} − U_{i+1}) per r.
template <int P>
inline void basis_d1_table(int span, double u, const double* U, const double* inv, double* N, double* dN) noexcept {
  double left[P + 1], right[P + 1], low[P + 1] = {};
  N[0] = 1.0;
  int t = 0;
  for (int j = 1; j <= P; ++j) {
    if (j == P)
      for (int r = 0; r < P; ++r) low[r] = N[r];
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] * inv[t++];
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  const double* a = inv + P * (P + 1) / 2;
  const double* b = a + (P + 1);
  for (int r = 0; r <= P; ++r) {
    double d = 0.0;
    if (r >= 1) d += low[r - 1] * a[r];
    if (r <= P - 1) d -= low[r] * b[r];
    dN[r] = P * d;
  }
}

template <int P, int Q>
inline void homogeneous_d1_fixed(const double* pw, int nv, int count_u, int count_v, const double* U, const double* V,
                                 const double* inv_u, const double* inv_v, double u, double v, double* A,
                                 double* Au, double* Av) noexcept {
  const int su = find_span(count_u, P, u, U);
  const int sv = find_span(count_v, Q, v, V);
  double Nu[P + 1], dNu[P + 1], Nv[Q + 1], dNv[Q + 1];
  constexpr int su_stride = P * (P + 1) / 2 + 2 * (P + 1), sv_stride = Q * (Q + 1) / 2 + 2 * (Q + 1);
  basis_d1_table<P>(su, u, U, inv_u + (su - P) * su_stride, Nu, dNu);
  basis_d1_table<Q>(sv, v, V, inv_v + (sv - Q) * sv_stride, Nv, dNv);
  for (int c = 0; c < 4; ++c) A[c] = Au[c] = Av[c] = 0.0;
  for (int i = 0; i <= P; ++i) {
    const double* row = pw + (static_cast<std::size_t>(su - P + i) * nv + (sv - Q)) * 4;
    double t0[4] = {0, 0, 0, 0}, t1[4] = {0, 0, 0, 0};
    for (int j = 0; j <= Q; ++j) {
      const double* Pj = row + 4 * j;
      for (int c = 0; c < 4; ++c) {
        t0[c] += Nv[j] * Pj[c];
        t1[c] += dNv[j] * Pj[c];
      }
    }
    for (int c = 0; c < 4; ++c) {
      A[c] += Nu[i] * t0[c];
      Au[c] += dNu[i] * t0[c];
      Av[c] += Nu[i] * t1[c];
    }
  }
}

using HomKernel = void (*)(const double*, int, int, int, const double*, const double*, const double*,
                           const double*, double, double, double*, double*, double*);

template <int P>
HomKernel pick_q(int q) {
  switch (q) {
    case 1: return &homogeneous_d1_fixed<P, 1>;
    case 2: return &homogeneous_d1_fixed<P, 2>;
    case 3: return &homogeneous_d1_fixed<P, 3>;
    case 4: return &homogeneous_d1_fixed<P, 4>;
    case 5: return &homogeneous_d1_fixed<P, 5>;
    default: return nullptr;
  }
}

HomKernel pick_kernel(int p, int q) {
  switch (p) {
    case 1: return pick_q<1>(q);
    case 2: return pick_q<2>(q);
    case 3: return pick_q<3>(q);
    case 4: return pick_q<4>(q);
    case 5: return pick_q<5>(q);
    default: return nullptr;
  }
}
}  // namespace

void NurbsSurface::evaluate(const Eigen::Ref<const Points2>& uv, Eigen::Ref<Points3> points,
                            Eigen::Ref<Points3> normals, SurfaceWorkspace& ws) const {
  const int p = degree_u_, q = degree_v_, nv = count_v_;
  check_workspace(ws, p, q, nv);
  const Eigen::Index m = uv.rows();
  NETSHAPE_CHECK(points.rows() == m, "points.rows", points.rows(), "must equal uv.rows");
  const bool want_n = normals.rows() > 0;
  NETSHAPE_CHECK(!want_n || normals.rows() == m, "normals.rows", normals.rows(), "must equal uv.rows (or be 0)");
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const double tu = 1e-12 * std::max(1.0, ub - ua), tv = 1e-12 * std::max(1.0, vb - va);
  const double* U = knots_u_.data();
  const double* V = knots_v_.data();
  const double* pw = pw_.data();
  double* Nu = ws.nu.data();
  double* Nv = ws.nv.data();
  const HomKernel kernel = pick_kernel(p, q);
  auto generic = [&](double u, double v, double* A, double* Au, double* Av) {
    const int su = find_span(count_u_, p, u, U);
    const int sv = find_span(count_v_, q, v, V);
    basis_functions_d1(su, u, p, U, Nu, Nu + p + 1, ws.scratch_u.data());
    basis_functions_d1(sv, v, q, V, Nv, Nv + q + 1, ws.scratch_v.data());
    for (int c = 0; c < 4; ++c) A[c] = Au[c] = Av[c] = 0.0;
    for (int i = 0; i <= p; ++i) {
      const double* row = pw + (static_cast<std::size_t>(su - p + i) * nv + (sv - q)) * 4;
      double t0[4] = {0, 0, 0, 0}, t1[4] = {0, 0, 0, 0};
      for (int j = 0; j <= q; ++j) {
        const double a = Nv[j], b = Nv[q + 1 + j];
        const double* Pj = row + 4 * j;
        for (int c = 0; c < 4; ++c) {
          t0[c] += a * Pj[c];
          t1[c] += b * Pj[c];
        }
      }
      const double a = Nu[i], b = Nu[p + 1 + i];
      for (int c = 0; c < 4; ++c) {
        A[c] += a * t0[c];
        Au[c] += b * t0[c];
        Av[c] += a * t1[c];
      }
    }
  };
  for (Eigen::Index k = 0; k < m; ++k) {
    double u = uv(k, 0), v = uv(k, 1);
    if (!(u >= ua - tu && u <= ub + tu)) check_parameters(u, v);  // throws (also NaN)
    if (!(v >= va - tv && v <= vb + tv)) check_parameters(u, v);
    u = std::clamp(u, ua, ub);
    v = std::clamp(v, va, vb);
    double A[4], Au[4], Av[4];
    if (kernel) {
      kernel(pw, nv, count_u_, count_v_, U, V, inv_u_.data(), inv_v_.data(), u, v, A, Au, Av);
    } else {
      generic(u, v, A, Au, Av);
    }
    double* P = &points(k, 0);
    double* N = want_n ? &normals(k, 0) : nullptr;
    if (!finish_point_normal(A, Au, Av, P, N, tiny_u_ * tiny_u_, tiny_v_ * tiny_v_)) {
      const Vec3 n = degenerate_normal(u, v);
      N[0] = n[0];
      N[1] = n[1];
      N[2] = n[2];
    }
  }
}

void NurbsSurface::evaluate_grid(const Eigen::Ref<const VectorXd>& us, const Eigen::Ref<const VectorXd>& vs,
                                 Eigen::Ref<Points3> points, Eigen::Ref<Points3> normals,
                                 SurfaceWorkspace& ws) const {
  const int p = degree_u_, q = degree_v_, nv = count_v_;
  check_workspace(ws, p, q, nv);
  const Eigen::Index a = us.size(), b = vs.size();
  NETSHAPE_CHECK(points.rows() == a * b, "points.rows", points.rows(), "must equal len(us) * len(vs)");
  const bool want_n = normals.rows() > 0;
  NETSHAPE_CHECK(!want_n || normals.rows() == a * b, "normals.rows", normals.rows(),
                 "must equal len(us) * len(vs) (or be 0)");
  for (Eigen::Index i = 0; i < a; ++i) check_parameters(us[i], domain_v().first);
  for (Eigen::Index j = 0; j < b; ++j) check_parameters(domain_u().first, vs[j]);
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const double* U = knots_u_.data();
  const double* V = knots_v_.data();
  const double* pw = pw_.data();
  double* Nu = ws.nu.data();
  double* Nv = ws.nv.data();
  double* r0 = ws.row0.data();
  double* r1 = ws.row1.data();
  (void)Nv;
  // v-basis once per column
  if (ws.col_span.size() < static_cast<std::size_t>(b)) ws.col_span.resize(b);
  if (ws.col_basis.size() < static_cast<std::size_t>(b * 2 * (q + 1))) ws.col_basis.resize(b * 2 * (q + 1));
  for (Eigen::Index j = 0; j < b; ++j) {
    const double v = std::clamp(vs[j], va, vb);
    const int sv = find_span(count_v_, q, v, V);
    ws.col_span[j] = sv;
    double* B = ws.col_basis.data() + j * 2 * (q + 1);
    basis_functions_d1(sv, v, q, V, B, B + q + 1, ws.scratch_v.data());
  }
  for (Eigen::Index i = 0; i < a; ++i) {
    const double u = std::clamp(us[i], ua, ub);
    const int su = find_span(count_u_, p, u, U);
    basis_functions_d1(su, u, p, U, Nu, Nu + p + 1, ws.scratch_u.data());
    // iso-curve (in v) control points at this u and their u-derivative, homogeneous
    std::fill(r0, r0 + 4 * nv, 0.0);
    std::fill(r1, r1 + 4 * nv, 0.0);
    for (int r = 0; r <= p; ++r) {
      const double* row = pw + static_cast<std::size_t>(su - p + r) * nv * 4;
      const double c0 = Nu[r], c1 = Nu[p + 1 + r];
      for (int t = 0; t < 4 * nv; ++t) {
        r0[t] += c0 * row[t];
        r1[t] += c1 * row[t];
      }
    }
    for (Eigen::Index j = 0; j < b; ++j) {
      const double v = std::clamp(vs[j], va, vb);
      const int sv = ws.col_span[j];
      const double* Nv = ws.col_basis.data() + j * 2 * (q + 1);
      double A[4] = {0, 0, 0, 0}, Au[4] = {0, 0, 0, 0}, Av[4] = {0, 0, 0, 0};
      for (int s = 0; s <= q; ++s) {
        const double* P0 = r0 + 4 * (sv - q + s);
        const double* P1 = r1 + 4 * (sv - q + s);
        const double e = Nv[s], f = Nv[q + 1 + s];
        for (int c = 0; c < 4; ++c) {
          A[c] += e * P0[c];
          Au[c] += e * P1[c];
          Av[c] += f * P0[c];
        }
      }
      const Eigen::Index k = i * b + j;
      double* P = &points(k, 0);
      double* N = want_n ? &normals(k, 0) : nullptr;
      if (!finish_point_normal(A, Au, Av, P, N, tiny_u_ * tiny_u_, tiny_v_ * tiny_v_)) {
        const Vec3 n = degenerate_normal(u, v);
        N[0] = n[0];
        N[1] = n[1];
        N[2] = n[2];
      }
    }
  }
}

Points3 NurbsSurface::evaluate(const Eigen::Ref<const Points2>& uv) const {
  SurfaceWorkspace ws = make_workspace();
  Points3 pts(uv.rows(), 3), none(0, 3);
  evaluate(uv, pts, none, ws);
  return pts;
}

std::pair<Points3, Points3> NurbsSurface::evaluate_with_normals(const Eigen::Ref<const Points2>& uv) const {
  SurfaceWorkspace ws = make_workspace();
  Points3 pts(uv.rows(), 3), nrm(uv.rows(), 3);
  evaluate(uv, pts, nrm, ws);
  return {std::move(pts), std::move(nrm)};
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

namespace {
struct ProjectionGrid {
  VectorXd us, vs;
  Points3 pts;
};
}  // namespace

static ProjectionGrid projection_grid(const NurbsSurface& s) {
  const auto [ua, ub] = s.domain_u();
  const auto [va, vb] = s.domain_v();
  const int na = std::max(12, 3 * s.count_u() * s.degree_u()), nb = std::max(12, 3 * s.count_v() * s.degree_v());
  ProjectionGrid g;
  g.us = VectorXd::LinSpaced(na, ua, ub);
  g.vs = VectorXd::LinSpaced(nb, va, vb);
  SurfaceWorkspace ws = s.make_workspace();
  g.pts.resize(static_cast<Eigen::Index>(na) * nb, 3);
  Points3 none(0, 3);
  s.evaluate_grid(g.us, g.vs, g.pts, none, ws);
  return g;
}

SurfaceProjection NurbsSurface::closest_point(const Vec3& p, double tolerance, int max_iterations) const {
  return closest_points(p.transpose(), tolerance, max_iterations).front();
}

std::vector<SurfaceProjection> NurbsSurface::closest_points(const Eigen::Ref<const Points3>& points, double tolerance,
                                                            int max_iterations) const {
  NETSHAPE_CHECK(tolerance > 0.0, "tolerance", tolerance, "must be positive [mm]");
  NETSHAPE_CHECK(max_iterations >= 1, "max_iterations", max_iterations, "must be at least 1");
  for (Eigen::Index k = 0; k < points.rows(); ++k)
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("point", points(k, c));
  const ProjectionGrid grid = projection_grid(*this);
  std::vector<SurfaceProjection> out;
  out.reserve(points.rows());
  std::vector<std::pair<double, Eigen::Index>> order(grid.pts.rows());
  for (Eigen::Index q = 0; q < points.rows(); ++q)
    out.push_back(project_from_grid(points.row(q).transpose(), grid.us, grid.vs, grid.pts, order, tolerance,
                                    max_iterations));
  return out;
}

SurfaceProjection NurbsSurface::project_from_grid(const Vec3& p, const VectorXd& us, const VectorXd& vs,
                                                  const Points3& pts,
                                                  std::vector<std::pair<double, Eigen::Index>>& order,
                                                  double tolerance, int max_iterations) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const Eigen::Index nb = vs.size();
  for (Eigen::Index k = 0; k < pts.rows(); ++k) order[k] = {(pts.row(k).transpose() - p).squaredNorm(), k};
  const int starts = static_cast<int>(std::min<std::size_t>(4, order.size()));
  std::partial_sort(order.begin(), order.begin() + starts, order.end());
  SurfaceProjection best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int st = 0; st < starts; ++st) {
    double u = us[order[st].second / nb], v = vs[order[st].second % nb];
    SurfaceProjection r;
    for (int it = 0; it < max_iterations; ++it) {
      r.iterations = it + 1;
      const MatrixXdR d = derivatives(u, v, 2);  // D = 3: row k·3 + l
      const Vec3 S = d.row(0).transpose(), Su = d.row(3).transpose(), Sv = d.row(1).transpose();
      const Vec3 Suu = d.row(6).transpose(), Suv = d.row(4).transpose(), Svv = d.row(2).transpose();
      const Vec3 rr = S - p;
      if (rr.norm() <= tolerance) {
        r.converged = true;
        break;
      }
      const double f = Su.dot(rr), g = Sv.dot(rr);
      if (std::abs(f) <= 1e-14 * Su.norm() * rr.norm() + 1e-300 &&
          std::abs(g) <= 1e-14 * Sv.norm() * rr.norm() + 1e-300) {
        r.converged = true;
        break;
      }
      Eigen::Matrix2d J;
      J << Su.squaredNorm() + rr.dot(Suu), Su.dot(Sv) + rr.dot(Suv), Su.dot(Sv) + rr.dot(Suv),
          Sv.squaredNorm() + rr.dot(Svv);
      Eigen::Vector2d step;
      const Eigen::Vector2d rhs(-f, -g);
      if (J.determinant() > 1e-300 && J(0, 0) > 0) {
        step = J.ldlt().solve(rhs);
      } else {  // not a descent Hessian: Gauss-Newton step
        Eigen::Matrix2d G;
        G << Su.squaredNorm(), Su.dot(Sv), Su.dot(Sv), Sv.squaredNorm();
        G.diagonal().array() += 1e-12 * (G.trace() + 1e-300);
        step = G.ldlt().solve(rhs);
      }
      const double un = std::clamp(u + step[0], ua, ub), vn = std::clamp(v + step[1], va, vb);
      const double moved = ((un - u) * Su + (vn - v) * Sv).norm();
      u = un;
      v = vn;
      if (moved <= tolerance) {
        r.converged = true;
        break;
      }
    }
    r.u = u;
    r.v = v;
    r.point = point(u, v);
    r.distance = (r.point - p).norm();
    if (r.distance < best.distance) best = r;
  }
  best.normal = normal(best.u, best.v);
  return best;
}

}  // namespace netshape::geometry
