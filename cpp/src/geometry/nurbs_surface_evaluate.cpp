// NurbsSurface batch evaluation (netshape/geometry/nurbs_surface.hpp): points, normals and grids through
// a caller-owned workspace, with per-degree basis kernels for the common degrees.
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

}  // namespace netshape::geometry
