#include "netshape/geometry/basis.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

int find_span(int count, int degree, double u, const double* U) noexcept {
  const int n = count - 1;  // index of the last control point (P&T's n)
  if (u >= U[n + 1]) return n;
  if (u <= U[degree]) {
    // first non-empty span at or after `degree`
    int s = degree;
    while (s < n && U[s + 1] <= U[degree]) ++s;
    return s;
  }
  int low = degree, high = n + 1;
  int mid = (low + high) / 2;
  while (u < U[mid] || u >= U[mid + 1]) {
    if (u < U[mid])
      high = mid;
    else
      low = mid;
    mid = (low + high) / 2;
  }
  return mid;
}

void basis_functions(int span, double u, int p, const double* U, double* N, double* scratch) noexcept {
  double* left = scratch;
  double* right = scratch + (p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

void basis_functions_d1(int span, double u, int p, const double* U, double* N, double* dN,
                        double* scratch) noexcept {
  double* left = scratch;
  double* right = scratch + (p + 1);
  double* low = scratch + 2 * (p + 1);  // degree p − 1 functions N_{span-p+1 .. span, p-1}
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    if (j == p)
      for (int r = 0; r < p; ++r) low[r] = N[r];
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
  // i = span − p + r; N_{i,p−1} = low[r − 1], N_{i+1,p−1} = low[r]
  for (int r = 0; r <= p; ++r) {
    const int i = span - p + r;
    double d = 0.0;
    if (r >= 1) {
      const double den = U[i + p] - U[i];
      if (den > 0) d += low[r - 1] / den;
    }
    if (r <= p - 1) {
      const double den = U[i + p + 1] - U[i + 1];
      if (den > 0) d -= low[r] / den;
    }
    dN[r] = p * d;
  }
}

std::size_t ders_scratch_size(int p) noexcept {
  const std::size_t q = static_cast<std::size_t>(p) + 1;
  return 2 * q + q * q + 2 * q;  // left, right, ndu (q x q), a (2 x q)
}

void basis_function_derivatives(int span, double u, int p, int order, const double* U, double* ders,
                                double* scratch) noexcept {
  const int q = p + 1;
  double* left = scratch;
  double* right = left + q;
  double* ndu = right + q;  // ndu[j*q + r]
  double* a = ndu + q * q;  // a[s*q + k], two rows
  auto NDU = [&](int j, int r) -> double& { return ndu[j * q + r]; };
  auto A = [&](int s, int k) -> double& { return a[s * q + k]; };
  NDU(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      NDU(j, r) = right[r + 1] + left[j - r];  // lower triangle: knot differences
      const double temp = NDU(r, j - 1) / NDU(j, r);
      NDU(r, j) = saved + right[r + 1] * temp;  // upper triangle: basis functions
      saved = left[j - r] * temp;
    }
    NDU(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = NDU(j, p);
  const int nd = std::min(order, p);
  for (int k = 1; k <= order; ++k)
    for (int j = 0; j <= p; ++j) ders[k * q + j] = 0.0;
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    A(0, 0) = 1.0;
    for (int k = 1; k <= nd; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        A(s2, 0) = A(s1, 0) / NDU(pk + 1, rk);
        d = A(s2, 0) * NDU(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        A(s2, j) = (A(s1, j) - A(s1, j - 1)) / NDU(pk + 1, rk + j);
        d += A(s2, j) * NDU(rk + j, pk);
      }
      if (r <= pk) {
        A(s2, k) = -A(s1, k - 1) / NDU(pk + 1, r);
        d += A(s2, k) * NDU(r, pk);
      }
      ders[k * q + r] = d;
      std::swap(s1, s2);
    }
  }
  double f = p;
  for (int k = 1; k <= nd; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * q + j] *= f;
    f *= (p - k);
  }
}

MatrixXdR basis_function_derivatives(double u, int degree, const VectorXd& knots, int order) {
  NETSHAPE_CHECK(degree >= 1, "degree", degree, "must be at least 1");
  NETSHAPE_CHECK(order >= 0, "order", order, "must be non-negative");
  const int count = static_cast<int>(knots.size()) - degree - 1;
  validate_knots(knots, degree, count, "knots");
  const int span = find_span(count, degree, u, knots.data());
  MatrixXdR out(order + 1, degree + 1);
  std::vector<double> scratch(ders_scratch_size(degree));
  basis_function_derivatives(span, u, degree, order, knots.data(), out.data(), scratch.data());
  return out;
}

void validate_knots(const VectorXd& U, int p, int count, const char* field) {
  NETSHAPE_CHECK(p >= 1, "degree", p, "must be at least 1");
  NETSHAPE_CHECK(count >= p + 1, (std::string(field) + " (control point count)").c_str(), count,
                 "need at least degree + 1 control points");
  NETSHAPE_CHECK(U.size() == count + p + 1, (std::string(field) + ".size").c_str(), U.size(),
                 "must equal control point count + degree + 1");
  for (Eigen::Index i = 0; i < U.size(); ++i) {
    NETSHAPE_CHECK(std::isfinite(U[i]), (std::string(field) + "[" + std::to_string(i) + "]").c_str(), U[i],
                   "must be finite");
    if (i > 0)
      NETSHAPE_CHECK(U[i] >= U[i - 1], (std::string(field) + "[" + std::to_string(i) + "]").c_str(), U[i],
                     "knot vector must be non-decreasing");
  }
  NETSHAPE_CHECK(U[count] > U[p], (std::string(field) + " domain end").c_str(), U[count],
                 "parameter domain [U[p], U[n]] must not be empty");
  // interior multiplicity <= p (strictly inside the domain)
  int mult = 1;
  for (Eigen::Index i = 1; i < U.size(); ++i) {
    mult = (U[i] == U[i - 1]) ? mult + 1 : 1;
    if (U[i] > U[p] && U[i] < U[count])
      NETSHAPE_CHECK(mult <= p, (std::string(field) + "[" + std::to_string(i) + "]").c_str(), U[i],
                     "interior knot multiplicity must not exceed the degree");
  }
}

double binomial(int n, int k) noexcept {
  if (k < 0 || k > n) return 0.0;
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

}  // namespace netshape::geometry
