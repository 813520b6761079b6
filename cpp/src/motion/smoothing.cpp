#include "netshape/motion/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/motion/segment.hpp"

namespace netshape::motion {

void SmoothOptions::validate() const {
  NETSHAPE_CHECK(tolerance > 0 && std::isfinite(tolerance), "tolerance", tolerance, "must be positive [mm]");
  NETSHAPE_CHECK(fit_share > 0 && fit_share < 1, "fit_share", fit_share, "must be in (0, 1)");
  NETSHAPE_CHECK(max_segment > 0 && std::isfinite(max_segment), "max_segment", max_segment, "must be positive [mm]");
  NETSHAPE_CHECK(max_turn > 0 && max_turn < pi, "max_turn", max_turn, "must be in (0, pi) [rad]");
  NETSHAPE_CHECK(min_blocks >= 2, "min_blocks", min_blocks, "must be >= 2");
  NETSHAPE_CHECK(window >= 8, "window", window, "must be >= 8 [blocks]");
  NETSHAPE_CHECK(max_refinements >= 1, "max_refinements", max_refinements, "must be >= 1");
  NETSHAPE_CHECK(smoothing_length >= 0 && std::isfinite(smoothing_length), "smoothing_length", smoothing_length,
                 "must be >= 0 [mm]");
  NETSHAPE_CHECK(knot_spacing > 0 && std::isfinite(knot_spacing), "knot_spacing", knot_spacing, "must be positive");
  NETSHAPE_CHECK(lead_length >= 0 && std::isfinite(lead_length), "lead_length", lead_length, "must be >= 0 [mm]");
  NETSHAPE_CHECK(plane_tolerance >= 0, "plane_tolerance", plane_tolerance, "must be >= 0 [mm]");
}

namespace {

using V2 = Eigen::Vector2d;

double cross2(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }
V2 perp(const V2& t) { return V2(-t.y(), t.x()); }

double seg_dist(const V2& p, const V2& a, const V2& b) {
  const V2 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

// Cubic B-spline (clamped) in the plane, parameter u ∈ [0, L].
struct Spline {
  std::vector<double> t;  // knots, 4 equal at each end
  std::vector<V2> P;      // control points
  int span(double u) const {
    const int m = static_cast<int>(P.size());
    if (u >= t[static_cast<std::size_t>(m)]) return m - 1;
    const auto it = std::upper_bound(t.begin() + 3, t.begin() + m + 1, u);
    return static_cast<int>(it - t.begin()) - 1;
  }
  // the four non-zero basis values at u in span k (functions k−3..k)
  void basis(int k, double u, double N[4]) const {
    double left[4], right[4];
    N[0] = 1.0;
    for (int j = 1; j <= 3; ++j) {
      left[j] = u - t[static_cast<std::size_t>(k + 1 - j)];
      right[j] = t[static_cast<std::size_t>(k + j)] - u;
      double saved = 0.0;
      for (int r = 0; r < j; ++r) {
        const double den = right[r + 1] + left[j - r];
        const double tmp = den > 0 ? N[r] / den : 0.0;
        N[r] = saved + right[r + 1] * tmp;
        saved = left[j - r] * tmp;
      }
      N[j] = saved;
    }
  }
  V2 point(double u) const {
    const int k = span(u);
    double N[4];
    basis(k, u, N);
    V2 p = V2::Zero();
    for (int r = 0; r < 4; ++r) p += N[r] * P[static_cast<std::size_t>(k - 3 + r)];
    return p;
  }
  // derivative by a central difference of the exact point (h relative to L) is not exact; use the
  // hodograph: a quadratic B-spline on t[1..] with control points 3(P_{i+1} − P_i)/(t_{i+4} − t_{i+1})
  V2 deriv(double u) const {
    const int k = span(u);
    // quadratic basis on the same knot span
    double N[3], left[3], right[3];
    N[0] = 1.0;
    for (int j = 1; j <= 2; ++j) {
      left[j] = u - t[static_cast<std::size_t>(k + 1 - j)];
      right[j] = t[static_cast<std::size_t>(k + j)] - u;
      double saved = 0.0;
      for (int r = 0; r < j; ++r) {
        const double den = right[r + 1] + left[j - r];
        const double tmp = den > 0 ? N[r] / den : 0.0;
        N[r] = saved + right[r + 1] * tmp;
        saved = left[j - r] * tmp;
      }
      N[j] = saved;
    }
    V2 d = V2::Zero();
    for (int r = 0; r < 3; ++r) {
      const int i = k - 3 + r;  // Q_i uses P_i, P_{i+1}
      const double den = t[static_cast<std::size_t>(i + 4)] - t[static_cast<std::size_t>(i + 1)];
      if (den > 0) d += N[r] * 3.0 * (P[static_cast<std::size_t>(i + 1)] - P[static_cast<std::size_t>(i)]) / den;
    }
    return d;
  }
  // values and first two derivatives of the four non-zero basis functions at u in span k
  // (The NURBS Book, algorithm A2.3, degree 3)
  void ders(int k, double u, double D[3][4]) const {
    double ndu[4][4], left[4], right[4], a[2][4];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= 3; ++j) {
      left[j] = u - t[static_cast<std::size_t>(k + 1 - j)];
      right[j] = t[static_cast<std::size_t>(k + j)] - u;
      double saved = 0.0;
      for (int r = 0; r < j; ++r) {
        ndu[j][r] = right[r + 1] + left[j - r];
        const double tmp = ndu[j][r] > 0 ? ndu[r][j - 1] / ndu[j][r] : 0.0;
        ndu[r][j] = saved + right[r + 1] * tmp;
        saved = left[j - r] * tmp;
      }
      ndu[j][j] = saved;
    }
    for (int j = 0; j <= 3; ++j) D[0][j] = ndu[j][3];
    for (int r = 0; r <= 3; ++r) {
      int s1 = 0, s2 = 1;
      a[0][0] = 1.0;
      for (int q = 1; q <= 2; ++q) {
        double d = 0.0;
        const int rk = r - q, pk = 3 - q;
        if (r >= q) {
          a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
          d = a[s2][0] * ndu[rk][pk];
        }
        const int j1 = rk >= -1 ? 1 : -rk;
        const int j2 = r - 1 <= pk ? q - 1 : 3 - r;
        for (int j = j1; j <= j2; ++j) {
          a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
          d += a[s2][j] * ndu[rk + j][pk];
        }
        if (r <= pk) {
          a[s2][q] = -a[s1][q - 1] / ndu[pk + 1][r];
          d += a[s2][q] * ndu[r][pk];
        }
        D[q][r] = d;
        std::swap(s1, s2);
      }
    }
    for (int r = 0; r <= 3; ++r) {
      D[1][r] *= 3.0;
      D[2][r] *= 6.0;
    }
  }
  // point, first and second derivative at u
  void eval(double u, V2& s0, V2& s1, V2& s2) const {
    const int k = span(u);
    double D[3][4];
    ders(k, u, D);
    s0 = s1 = s2 = V2::Zero();
    for (int r = 0; r < 4; ++r) {
      const V2& P = this->P[static_cast<std::size_t>(k - 3 + r)];
      s0 += D[0][r] * P;
      s1 += D[1][r] * P;
      s2 += D[2][r] * P;
    }
  }
};

// Symmetric banded solve (half bandwidth 3) by Cholesky; band[i][k] = A(i, i + k). In place on rhs.
bool band_solve(std::vector<std::array<double, 4>>& band, std::vector<V2>& rhs) {
  const int n = static_cast<int>(band.size());
  // L stored as lo[i][k] = L(i, i − k)
  std::vector<std::array<double, 4>> lo(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (int k = 3; k >= 0; --k) {
      const int j = i - k;
      if (j < 0) {
        lo[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = 0;
        continue;
      }
      double s = band[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];  // A(j, i) = A(i, j)
      for (int q = std::max(0, i - 3); q < j; ++q)
        s -= lo[static_cast<std::size_t>(i)][static_cast<std::size_t>(i - q)] *
             lo[static_cast<std::size_t>(j)][static_cast<std::size_t>(j - q)];
      if (k == 0) {
        if (!(s > 0)) return false;
        lo[static_cast<std::size_t>(i)][0] = std::sqrt(s);
      } else {
        lo[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = s / lo[static_cast<std::size_t>(j)][0];
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    V2 s = rhs[static_cast<std::size_t>(i)];
    for (int q = std::max(0, i - 3); q < i; ++q) s -= lo[static_cast<std::size_t>(i)][static_cast<std::size_t>(i - q)] * rhs[static_cast<std::size_t>(q)];
    rhs[static_cast<std::size_t>(i)] = s / lo[static_cast<std::size_t>(i)][0];
  }
  for (int i = n - 1; i >= 0; --i) {
    V2 s = rhs[static_cast<std::size_t>(i)];
    for (int q = i + 1; q <= std::min(n - 1, i + 3); ++q)
      s -= lo[static_cast<std::size_t>(q)][static_cast<std::size_t>(q - i)] * rhs[static_cast<std::size_t>(q)];
    rhs[static_cast<std::size_t>(i)] = s / lo[static_cast<std::size_t>(i)][0];
  }
  return true;
}

// One data sample of a run: the point p of the polyline, its spline parameter u (first its arc length
// along the polyline, then its foot point on the fitted curve) and its weight.
struct Sample {
  double u;
  V2 p;
  double w;
  double a;  // arc length of p along the polyline
};

// Monotone map from the spline parameter to arc length along the polyline, piecewise linear through the
// samples' (foot point parameter, arc length) pairs. The smoothed curve is shorter than the polyline
// where it cuts across wiggles, so its parameter drifts from the polyline's arc length along a run;
// program blocks and nearby polyline segments are found through this map.
struct ParamMap {
  std::vector<double> u, a;
  void build(const std::vector<Sample>& samples, double L) {
    std::vector<std::pair<double, double>> ua;
    ua.reserve(samples.size() + 2);
    ua.emplace_back(0.0, 0.0);
    for (const Sample& s : samples) ua.emplace_back(s.u, s.a);
    ua.emplace_back(L, L);
    std::sort(ua.begin(), ua.end());
    u.clear();
    a.clear();
    for (const auto& [x, y] : ua) {
      u.push_back(x);
      a.push_back(a.empty() ? y : std::max(a.back(), y));
    }
  }
  double operator()(double x) const {
    const auto it = std::upper_bound(u.begin(), u.end(), x);
    if (it == u.begin()) return a.front();
    if (it == u.end()) return a.back();
    const auto k = static_cast<std::size_t>(it - u.begin());
    const double du = u[k] - u[k - 1];
    return du > 0 ? a[k - 1] + (a[k] - a[k - 1]) * (x - u[k - 1]) / du : a[k];
  }
};

// Penalised least squares: the control points minimise
//   Σ_k w_k |s(u_k) − p_k|² + pen · ∫ |s''(u)|² du
// with the first front.size() and the last back.size() control points fixed to the given values
// (end points, and end tangents when the second control point is fixed too). Banded Cholesky, O(n).
// pen_band caches the penalty's band for these knots: it is filled when empty and must be cleared
// when the knots change.
bool fit(const std::vector<Sample>& samples, double L, const std::vector<double>& interior, double pen,
         const std::vector<V2>& front, const std::vector<V2>& back, Spline& sp,
         std::vector<std::array<double, 4>>& pen_band) {
  const int m = static_cast<int>(interior.size()) + 4;
  const int nf = static_cast<int>(front.size()), nk = static_cast<int>(back.size());
  if (nf + nk > m) return false;
  sp.t.assign(4, 0.0);
  sp.t.insert(sp.t.end(), interior.begin(), interior.end());
  sp.t.insert(sp.t.end(), 4, L);
  sp.P.assign(static_cast<std::size_t>(m), V2::Zero());
  if (pen_band.empty()) {
    // pen·∫|s''|² over [0, L]: s'' is linear on each knot span, so two Gauss points per span are exact
    pen_band.assign(static_cast<std::size_t>(m), std::array<double, 4>{0, 0, 0, 0});
    const double g = 0.5 / std::sqrt(3.0);
    for (int k = 3; k < m; ++k) {
      const double t0 = sp.t[static_cast<std::size_t>(k)], t1 = sp.t[static_cast<std::size_t>(k + 1)];
      const double h = t1 - t0;
      if (!(h > 0)) continue;
      for (const double x : {0.5 - g, 0.5 + g}) {
        double D[3][4];
        sp.ders(k, t0 + x * h, D);
        for (int r = 0; r < 4; ++r)
          for (int q = r; q < 4; ++q)
            pen_band[static_cast<std::size_t>(k - 3 + r)][static_cast<std::size_t>(q - r)] +=
                pen * 0.5 * h * D[2][r] * D[2][q];
      }
    }
  }
  std::vector<std::array<double, 4>> band = pen_band;
  std::vector<V2> rhs(static_cast<std::size_t>(m), V2::Zero());
  for (const Sample& s : samples) {
    const int k = sp.span(s.u);
    double N[4];
    sp.basis(k, s.u, N);
    for (int r = 0; r < 4; ++r) {
      const auto i = static_cast<std::size_t>(k - 3 + r);
      rhs[i] += s.w * N[r] * s.p;
      for (int q = r; q < 4; ++q) band[i][static_cast<std::size_t>(q - r)] += s.w * N[r] * N[q];
    }
  }
  for (int q = 0; q < nf; ++q) sp.P[static_cast<std::size_t>(q)] = front[static_cast<std::size_t>(q)];
  for (int q = 0; q < nk; ++q) sp.P[static_cast<std::size_t>(m - nk + q)] = back[static_cast<std::size_t>(q)];
  // move the fixed control points to the right-hand side: A(i, f) = band[min(i, f)][|i − f|]
  auto A = [&](int i, int f) {
    return band[static_cast<std::size_t>(std::min(i, f))][static_cast<std::size_t>(std::abs(i - f))];
  };
  for (int i = nf; i < m - nk; ++i) {
    for (int f = std::max(0, i - 3); f < nf; ++f) rhs[static_cast<std::size_t>(i)] -= A(i, f) * sp.P[static_cast<std::size_t>(f)];
    for (int f = std::max(m - nk, i + 1); f <= std::min(m - 1, i + 3); ++f)
      rhs[static_cast<std::size_t>(i)] -= A(i, f) * sp.P[static_cast<std::size_t>(f)];
  }
  std::vector<std::array<double, 4>> inner(band.begin() + nf, band.end() - nk);
  for (std::size_t i = 0; i < inner.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k)
      if (i + k >= inner.size()) inner[i][k] = 0;
  std::vector<V2> x(rhs.begin() + nf, rhs.end() - nk);
  if (!inner.empty() && !band_solve(inner, x)) return false;
  for (std::size_t i = 0; i < x.size(); ++i) sp.P[i + static_cast<std::size_t>(nf)] = x[i];
  return true;
}


// One planar piece of the chain: a line (k = 0) or an arc of signed curvature k [1/mm].
struct Piece {
  V2 a, b, c;     // start, end, centre (arcs)
  double k = 0;   // signed curvature (CCW > 0)
  double len = 0;
  double ua = 0, ub = 0;  // spline parameter range it stands for
  V2 at(double f) const {  // point at fraction f of the length
    if (k == 0) return a + f * (b - a);
    const double ang = f * len * k;
    const V2 r = a - c;
    const double cs = std::cos(ang), sn = std::sin(ang);
    return c + V2(cs * r.x() - sn * r.y(), sn * r.x() + cs * r.y());
  }
};

// Arc from a with unit tangent t through (ending at) b; a line when nearly straight.
Piece make_arc(const V2& a, const V2& t, const V2& b) {
  Piece p;
  p.a = a;
  p.b = b;
  const V2 d = b - a;
  const double l2 = d.squaredNorm();
  const double l = std::sqrt(l2);
  const double k = l2 > 0 ? 2.0 * cross2(t, d) / l2 : 0.0;
  if (std::abs(k) * l < 1e-7) {
    p.k = 0;
    p.len = l;
    return p;
  }
  p.k = k;
  p.c = a + perp(t) / k;
  // swept angle: the tangent turns by 2·asin(k·l/2) (minor arc; a biarc piece turns < π)
  const double half = std::asin(std::clamp(std::abs(k) * l / 2.0, 0.0, 1.0));
  const double ang = (t.dot(d) >= 0 ? 2.0 * half : 2.0 * (pi - half));
  p.len = ang / std::abs(k);
  return p;
}

double circle_dist(const Piece& p, const V2& q) {
  if (p.k == 0) return seg_dist(q, p.a, p.b);
  return std::abs((q - p.c).norm() - 1.0 / std::abs(p.k));
}

// Biarc between (p0, t0) and (p1, t1); false when it does not exist in a usable form.
bool biarc(const V2& p0, const V2& t0, const V2& p1, const V2& t1, Piece& A, Piece& B) {
  const V2 v = p1 - p0;
  const V2 ts = t0 + t1;
  const double vt = v.dot(ts);
  const double den = 2.0 * (1.0 - t0.dot(t1));
  double alpha;
  if (den < 1e-12) {
    if (vt <= 0) return false;
    alpha = v.squaredNorm() / (2.0 * vt);
  } else {
    const double disc = vt * vt + den * v.squaredNorm();
    alpha = (-vt + std::sqrt(disc)) / den;
  }
  if (!(alpha > 0) || !std::isfinite(alpha)) return false;
  const V2 m = 0.5 * (p0 + alpha * t0 + p1 - alpha * t1);
  A = make_arc(p0, t0, m);
  // second arc: from m to p1 ending with tangent t1 = the reverse arc from p1 with −t1 through m
  Piece R = make_arc(p1, -t1, m);
  B.a = m;
  B.b = p1;
  B.k = -R.k;
  B.c = R.c;
  B.len = R.len;
  return std::isfinite(A.len) && std::isfinite(B.len) && A.len > 0 && B.len > 0;
}

struct RunFit {
  std::vector<Piece> pieces;
  double bound = 0;
};

// Biarc chain of the spline (each piece halved until the spline's eighth points lie within fit_arc of
// its biarc and the biarc turns less than 90°), then the two-way check of the chain
// against the polyline. Fills out.pieces (their ua, ub as arc lengths along the polyline) and out.bound;
// the polyline arc lengths of the places where the bound exceeds eps go to bad. False when no usable
// biarc exists.
bool chain_check(const Spline& sp, const std::vector<V2>& pts, const std::vector<double>& cum,
                 const ParamMap& amap, double eps, double mean,
                 RunFit& out, std::vector<double>& bad) {
  const std::size_t n = pts.size();
  const double L = cum.back();
  const double sag_share = 0.05 * eps;
  const double fit_arc = 0.1 * eps;
  bad.clear();
  out.pieces.clear();
  // biarcs start over stretches of about four mean segments and are halved where they do not fit
  std::vector<double> breaks;
  const int nbr = std::max(1, static_cast<int>(std::round(L / (4.0 * mean))));
  for (int k = 0; k <= nbr; ++k) breaks.push_back(L * k / nbr);
  V2 pa = pts.front();
  for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
    // stack of parameter intervals (depth-first, in order)
    std::vector<std::pair<double, double>> todo{{breaks[s], breaks[s + 1]}};
    while (!todo.empty()) {
      const auto [ua, ub] = todo.back();
      todo.pop_back();
      const bool last = (s + 2 == breaks.size()) && todo.empty() && ub >= L;
      const V2 pb = last ? pts.back() : sp.point(ub);
      const V2 ta = sp.deriv(ua).normalized(), tb = sp.deriv(ub).normalized();
      Piece A, B;
      bool ok = biarc(pa, ta, pb, tb, A, B);
      if (ok) {
        const double turn = std::abs(A.k) * A.len + std::abs(B.k) * B.len;
        ok = turn < 0.5 * pi;
        for (double f : {0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875}) {
          if (!ok) break;
          const V2 q = sp.point(ua + f * (ub - ua));
          ok = std::min(circle_dist(A, q), circle_dist(B, q)) <= fit_arc;
        }
      }
      if (!ok && ub - ua > 1e-6 * std::max(1.0, L)) {
        const double um = 0.5 * (ua + ub);
        todo.push_back({um, ub});
        todo.push_back({ua, um});
        continue;
      }
      if (!ok) {
        return false;
      }
      const double um = 0.5 * (ua + ub);
      A.ua = ua;
      A.ub = um;
      B.ua = um;
      B.ub = ub;
      out.pieces.push_back(A);
      out.pieces.push_back(B);
      pa = pb;
    }
  }
  // chord samples of the chain with their parameters, sagitta, piece and fractions
  std::vector<V2> cp;
  std::vector<double> cu, csag, cf0, cf1;  // per chord j (cp[j], cp[j+1]): sagitta, fractions of its piece
  std::vector<int> cpi;
  cp.push_back(out.pieces.front().a);
  cu.push_back(0.0);
  for (std::size_t pi_ = 0; pi_ < out.pieces.size(); ++pi_) {
    const Piece& p = out.pieces[pi_];
    int nc = 1;
    if (p.k != 0) {
      const double h = std::sqrt(8.0 * sag_share / std::abs(p.k));
      nc = std::max(1, static_cast<int>(std::ceil(p.len / h)));
    }
    nc = std::max(nc, static_cast<int>(std::ceil(p.len / (0.5 * mean))));
    const double hc = p.len / nc;
    const double sag = std::abs(p.k) * hc * hc / 8.0;
    for (int j = 1; j <= nc; ++j) {
      cp.push_back(j == nc ? p.b : p.at(static_cast<double>(j) / nc));
      cu.push_back(amap(p.ua + (p.ub - p.ua) * j / nc));
      csag.push_back(sag);
      cf0.push_back(static_cast<double>(j - 1) / nc);
      cf1.push_back(static_cast<double>(j) / nc);
      cpi.push_back(static_cast<int>(pi_));
    }
  }
  double bound = 0;
  const double fine = 0.1 * eps;  // bisect a failing piece down to this length [mm]
  // chain -> polyline: every arc point between chord points c0, c1 is within
  // max(d(c0, S), d(c1, S)) + sagitta of segment S (distance to a segment is convex)
  const long ns = static_cast<long>(n) - 1;
  auto chain_bound = [&](const V2& c0, const V2& c1, long s) {
    double best = 1e300;
    for (long q = std::max(0L, s - 3); q <= std::min(ns - 1, s + 3); ++q) {
      const auto qi = static_cast<std::size_t>(q);
      best = std::min(best, std::max(seg_dist(c0, pts[qi], pts[qi + 1]), seg_dist(c1, pts[qi], pts[qi + 1])));
    }
    return best;
  };
  struct Job {
    double f0, f1, sag;
  };
  std::vector<Job> jobs;
  for (std::size_t j = 0; j + 1 < cp.size(); ++j) {
    const double um = 0.5 * (cu[j] + cu[j + 1]);
    const long s = std::clamp(static_cast<long>(std::upper_bound(cum.begin(), cum.end(), um) - cum.begin()) - 1, 0L, ns - 1);
    double best = chain_bound(cp[j], cp[j + 1], s) + csag[j];
    if (best > eps) {  // bisect the chord's arc piece where it straddles a polyline vertex
      const Piece& P = out.pieces[static_cast<std::size_t>(cpi[j])];
      jobs.assign(1, Job{cf0[j], cf1[j], csag[j]});
      best = 0;
      while (!jobs.empty()) {
        const Job jb = jobs.back();
        jobs.pop_back();
        const V2 c0 = P.at(jb.f0), c1 = P.at(jb.f1);
        const double b = chain_bound(c0, c1, s) + jb.sag;
        if (b > eps && (c1 - c0).norm() > fine) {
          const double fm = 0.5 * (jb.f0 + jb.f1);
          jobs.push_back(Job{jb.f0, fm, 0.25 * jb.sag});
          jobs.push_back(Job{fm, jb.f1, 0.25 * jb.sag});
          continue;
        }
        best = std::max(best, b);
      }
    }
    bound = std::max(bound, best);
    if (best > eps) bad.push_back(um);
  }
  // polyline -> chain: every point of a polyline piece [q0, q1] is within
  // max(d(q0, C), d(q1, C)) + sagitta of the arc over chord C
  const long nch = static_cast<long>(cp.size()) - 1;
  // chords whose arc length along the polyline (through the parameter map) lies within ±w of the
  // piece's; a chord outside the window can only make the bound larger, never smaller
  const double w = 0.25 * mean + 4.0 * eps;
  auto poly_bound = [&](const V2& q0, const V2& q1, double uq) {
    const long lo = std::max(0L, static_cast<long>(std::lower_bound(cu.begin(), cu.end(), uq - w) - cu.begin()) - 2);
    const long hi = std::min(nch - 1, static_cast<long>(std::upper_bound(cu.begin(), cu.end(), uq + w) - cu.begin()) + 1);
    double best = 1e300;
    for (long q = lo; q <= hi; ++q) {
      const auto qi = static_cast<std::size_t>(q);
      best = std::min(best, std::max(seg_dist(q0, cp[qi], cp[qi + 1]), seg_dist(q1, cp[qi], cp[qi + 1])) + csag[qi]);
    }
    return best;
  };
  std::vector<std::pair<V2, V2>> pj;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double li = cum[i + 1] - cum[i];
    const long c0 = std::clamp(static_cast<long>(std::upper_bound(cu.begin(), cu.end(), 0.5 * (cum[i] + cum[i + 1])) - cu.begin()) - 1, 0L, nch - 1);
    const double hc = (cp[static_cast<std::size_t>(c0) + 1] - cp[static_cast<std::size_t>(c0)]).norm();
    const int np = std::max(1, static_cast<int>(std::ceil(li / std::max(0.5 * hc, 0.25 * eps))));
    for (int k = 0; k < np; ++k) {
      const V2 q0 = pts[i] + (pts[i + 1] - pts[i]) * (static_cast<double>(k) / np);
      const V2 q1 = pts[i] + (pts[i + 1] - pts[i]) * (static_cast<double>(k + 1) / np);
      const double uq = cum[i] + li * (k + 0.5) / np;
      double best = poly_bound(q0, q1, uq);
      if (best > eps) {
        pj.assign(1, {q0, q1});
        best = 0;
        while (!pj.empty()) {
          const auto [a0, a1] = pj.back();
          pj.pop_back();
          const double b = poly_bound(a0, a1, uq);
          if (b > eps && (a1 - a0).norm() > fine) {
            const V2 am = 0.5 * (a0 + a1);
            pj.push_back({a0, am});
            pj.push_back({am, a1});
            continue;
          }
          best = std::max(best, b);
        }
      }
      bound = std::max(bound, best);
      if (best > eps) bad.push_back(uq);
    }
  }
  out.bound = bound;
  for (Piece& p : out.pieces) {
    p.ua = amap(p.ua);
    p.ub = amap(p.ub);
  }
  return true;
}

// Unit tangents a run's curve must start / end with (the direction of a line it continues), if any.
struct RunEnds {
  bool fix0 = false, fix1 = false;
  V2 d0 = V2::Zero(), d1 = V2::Zero();
};

// Fit a planar run (polyline pts, mean segment length `mean` without the leads) with a smoothing spline
// pulled back into the tolerance tube.
//
// The spline (cubic; knots uniform in arc length about knot_spacing mean segments apart; end points
// fixed, end tangents fixed where `ends` says) minimises Σ w_k·|s(u_k) − p_k|² over samples p_k of the
// polyline (every ≤ mean/2, w_k first the arc length each stands for) plus smoothing_length⁴·∫|s''|².
// A long smoothing length lets the curve use the whole tube (both sides of the polyline) and keeps its
// curvature low; where the curve then leaves the tube the weights of those samples are raised and the
// curve is fitted again, so it is pulled back only where it has to be. Each round the sample
// parameters move to their foot points on the curve, so a residual is the distance of the sample from
// the curve. A sample still out after a few rounds gets a knot next to it (its knot span is halved,
// down to mean/16). When every residual is within 0.8 of the fit tolerance the arc chain is built and
// checked both ways with rigorous bounds; where the check fails, the weights of the samples within one
// mean segment are raised and the round repeats. False when the check still fails after
// max_refinements rounds.
bool fit_run(const std::vector<V2>& pts, const RunEnds& ends, double mean, const SmoothOptions& opt,
             RunFit& out) {
  const std::size_t n = pts.size();  // vertices
  std::vector<double> cum(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) cum[i] = cum[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double L = cum.back();
  const double eps = opt.fit_tolerance();
  const int spans = std::max(3, static_cast<int>(std::ceil(L / (opt.knot_spacing * mean))));
  const double dk = L / spans;
  std::vector<double> knots;
  for (int i = 1; i < spans; ++i) knots.push_back(dk * i);
  // samples every ≤ mean/2 along each segment, weighted by the arc length each stands for
  std::vector<Sample> samples;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double li = cum[i + 1] - cum[i];
    const int q = std::max(2, static_cast<int>(std::ceil(li / (0.5 * mean))));
    for (int k = (i == 0 ? 1 : 0); k < q; ++k) {
      const double f = static_cast<double>(k) / q;
      samples.push_back(Sample{cum[i] + f * li, pts[i] + f * (pts[i + 1] - pts[i]), li / q, cum[i] + f * li});
    }
  }
  const double ell = opt.smoothing_length;
  const double pen = ell * ell * ell * ell;
  const double target = 0.9 * eps;
  Spline sp;
  ParamMap amap;
  std::vector<double> bad, add;
  std::vector<V2> front, back;
  std::vector<std::array<double, 4>> pen_band;
  for (int round = 0; round < opt.max_refinements; ++round) {
    // clamped cubic: s'(0) = 3 (P1 − P0) / t4 and s'(L) = 3 (P_{m−1} − P_{m−2}) / (L − t_{m−1});
    // a fixed end tangent fixes the second control point for unit speed
    front.assign(1, pts.front());
    back.assign(1, pts.back());
    if (ends.fix0) front.push_back(pts.front() + (knots.front() / 3.0) * ends.d0);
    if (ends.fix1) back.insert(back.begin(), pts.back() - ((L - knots.back()) / 3.0) * ends.d1);
    if (!fit(samples, L, knots, pen, front, back, sp, pen_band)) return false;
    bool over = false;
    add.clear();
    for (Sample& s : samples) {
      // foot point by Newton steps on (s(u) − p)·s'(u) = 0, kept only where it brings the curve closer
      double u = s.u;
      V2 c0, c1, c2;
      sp.eval(u, c0, c1, c2);
      const double r_old = (c0 - s.p).norm();
      for (int it = 0; it < 2; ++it) {
        const V2 r = c0 - s.p;
        const double fp = c1.squaredNorm() + r.dot(c2);
        if (!(fp > 0)) break;
        const double du = std::clamp(-r.dot(c1) / fp, -0.25 * mean, 0.25 * mean);
        u = std::clamp(u + du, 0.0, L);
        sp.eval(u, c0, c1, c2);
        if (std::abs(du) < 1e-9) break;
      }
      double res = (c0 - s.p).norm();
      if (res <= r_old) {
        s.u = u;
      } else {
        res = r_old;
      }
      if (res > target) {
        const double g = res / target;
        s.w *= std::clamp(1.2 * g * g, 1.2, 100.0);
        over = true;
        // a sample that stays out of the tube for a few rounds gets a knot next to it: the spline's
        // curvature may then change there (the ∫|s''|² penalty keeps the added freedom smooth)
        if (round % 4 == 3) add.push_back(s.u);
      }
    }
    if (!over) {
      amap.build(samples, L);
      if (!chain_check(sp, pts, cum, amap, eps, mean, out, bad)) return false;
      if (bad.empty()) return true;
      std::sort(bad.begin(), bad.end());
      for (Sample& s : samples) {
        const auto it = std::lower_bound(bad.begin(), bad.end(), s.a - mean);
        if (it != bad.end() && *it <= s.a + mean) s.w *= 4.0;
      }
    }
    if (!add.empty()) {  // split the knot spans that hold the samples, down to 1/16 of the mean segment
      std::vector<double> breaks{0.0};
      breaks.insert(breaks.end(), knots.begin(), knots.end());
      breaks.push_back(L);
      for (double u : add) {
        const auto k = static_cast<std::size_t>(
            std::clamp<long>(std::upper_bound(breaks.begin(), breaks.end(), u) - breaks.begin(), 1,
                             static_cast<long>(breaks.size()) - 1));
        if (breaks[k] - breaks[k - 1] > mean / 16.0) knots.push_back(0.5 * (breaks[k - 1] + breaks[k]));
      }
      std::sort(knots.begin(), knots.end());
      knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
      pen_band.clear();
    }
  }
  return false;
}

double turn_between(const Vec3& u1, const Vec3& u2) {
  return std::atan2(u1.cross(u2).norm(), u1.dot(u2));
}

}  // namespace

SmoothResult smooth(const std::vector<toolpath::Block>& program, const SmoothOptions& opt) {
  opt.validate();
  using toolpath::MotionKind;
  const std::size_t nb = program.size();
  for (std::size_t i = 0; i < nb; ++i) {
    try {
      program[i].validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("blocks[" + std::to_string(i) + "]: " + e.what());
    }
  }
  SmoothResult res;
  res.blocks.reserve(nb);
  auto micro = [&](std::size_t i) {
    const auto& b = program[i];
    const double l = b.length();
    return b.kind == MotionKind::line && l > 1e-9 && l <= opt.max_segment;
  };
  auto dir = [&](std::size_t i) { return ((program[i].end - program[i].start) / program[i].length()).eval(); };
  // corners between feed moves
  long prev = -1;
  for (std::size_t i = 0; i < nb; ++i) {
    const auto& b = program[i];
    if (b.length() <= 1e-9) continue;
    if (b.kind == MotionKind::rapid) {
      prev = -1;
      continue;
    }
    if (prev >= 0) {
      const Vec3 u1 = program[static_cast<std::size_t>(prev)].tangent_at(1.0), u2 = b.tangent_at(0.0);
      if (turn_between(u1, u2) > opt.max_turn) ++res.corners_kept;
    }
    prev = static_cast<long>(i);
  }
  // a line whose first part became the lead-out of the run before it starts later
  long start_override_block = -1;
  std::vector<bool> program_line;  // per new block: a program line block or a part of one
  Vec3 start_override = Vec3::Zero();
  auto keep = [&](std::size_t i) {
    res.blocks.push_back(program[i]);
    if (static_cast<long>(i) == start_override_block) res.blocks.back().start = start_override;
    res.source_first.push_back(static_cast<long>(i));
    res.source_last.push_back(static_cast<long>(i));
    program_line.push_back(program[i].kind == MotionKind::line);
  };
  std::size_t i = 0;
  std::vector<V2> pts;
  while (i < nb) {
    if (!micro(i)) {
      keep(i);
      ++i;
      continue;
    }
    // extend the run [i, j)
    int planes = 7;  // bit a: coordinate a constant
    auto plane_bits = [&](const Vec3& p, const Vec3& q) {
      int m = 0;
      for (int a = 0; a < 3; ++a)
        if (std::abs(p[a] - q[a]) <= opt.plane_tolerance) m |= 1 << a;
      return m;
    };
    const Vec3 origin = program[i].start;
    std::size_t j = i;
    while (j < nb && static_cast<long>(j - i) < opt.window && micro(j)) {
      if (j > i) {
        if (program[j].feed != program[i].feed) break;
        if ((program[j].start - program[j - 1].end).norm() > 1e-9) break;
        if (turn_between(dir(j - 1), dir(j)) > opt.max_turn) break;
      }
      const int m = planes & plane_bits(origin, program[j].end);
      if (m == 0) break;
      planes = m;
      ++j;
    }
    if (static_cast<long>(j - i) < opt.min_blocks) {
      // too short to smooth; a micro-segment that is in no coordinate plane by itself (j == i) is
      // kept too, so every pass of this loop moves past at least one block
      j = std::max(j, i + 1);
      for (std::size_t q = i; q < j; ++q) keep(q);
      i = j;
      continue;
    }
    // plane: normal axis = a constant coordinate (prefer Z, then Y, then X)
    toolpath::Plane plane = (planes & 4) ? toolpath::Plane::xy : (planes & 2) ? toolpath::Plane::zx : toolpath::Plane::yz;
    const auto ax = toolpath::plane_axes(plane);
    const double nval = program[i].start[ax.n];
    auto to3 = [&](const V2& p) {
      Vec3 v;
      v[ax.a] = p.x();
      v[ax.b] = p.y();
      v[ax.n] = nval;
      return v;
    };
    auto to2 = [&](const Vec3& p) { return V2(p[ax.a], p[ax.b]); };
    // a lead: block q (a line longer than a micro-segment, same feed, joined to the run, turning at
    // most max_turn against the run's end block e, in the run's plane) lends the run up to
    // lead_length (at most half of itself) next to the joint, so the curve starts / ends tangent to it
    auto lead_block = [&](long q, std::size_t e) {
      if (q < 0 || q >= static_cast<long>(nb)) return false;
      const auto& b = program[static_cast<std::size_t>(q)];
      if (b.kind != MotionKind::line || b.length() <= opt.max_segment || b.feed != program[e].feed) return false;
      if (std::abs(b.start[ax.n] - nval) > opt.plane_tolerance || std::abs(b.end[ax.n] - nval) > opt.plane_tolerance)
        return false;
      const bool before = static_cast<std::size_t>(q) < e;
      const Vec3 joint = before ? program[e].start : program[e].end;
      if ((joint - (before ? b.end : b.start)).norm() > 1e-9) return false;
      const Vec3 u1 = before ? dir(static_cast<std::size_t>(q)) : dir(e);
      const Vec3 u2 = before ? dir(e) : dir(static_cast<std::size_t>(q));
      return turn_between(u1, u2) <= opt.max_turn;
    };
    // A run's end block q next to a corner (the vertex at its other end turns more than max_turn) may
    // lend the run its inner half, so the corner stays between two lines and is rounded below: when it
    // is long enough for its direction to be sure (≥ 20·ε and ≥ 0.05 mm) and turns at most
    // max_turn / 2 against its neighbour r in the run.
    auto corner_lead = [&](std::size_t q, std::size_t r) {
      const bool at_start = r > q;
      const std::size_t c = at_start ? q : q + 1;  // the corner is at the start of block c
      if (c == 0 || c >= nb) return false;
      const auto &b0 = program[c - 1], &b1 = program[c];
      if (b0.kind == MotionKind::rapid || b1.kind == MotionKind::rapid || b0.length() <= 1e-9 ||
          b1.length() <= 1e-9 || (b1.start - b0.end).norm() > 1e-9)
        return false;
      if (turn_between(b0.tangent_at(1.0), b1.tangent_at(0.0)) <= opt.max_turn) return false;
      if (program[q].length() < std::max(0.05, 20.0 * opt.tolerance)) return false;
      return turn_between(dir(std::min(q, r)), dir(std::max(q, r))) <= 0.5 * opt.max_turn;
    };
    auto fit_emit = [&](std::size_t i, std::size_t j) -> bool {
      // Leads: the kept long line i − 1 (the block just emitted, shortened) and the long line j lend the
      // run their parts next to the joints, so the curve starts / ends tangent to them; without such a
      // line, next to a corner the run's own end block lends its run-side half (corner_lead) and its
      // corner-side half is emitted as a line.
      long lin = -1, lout = -1;
      bool lin_inner = false, lout_inner = false;
      if (lead_block(static_cast<long>(i) - 1, i) && !res.blocks.empty() &&
          res.source_first.back() == static_cast<long>(i) - 1 && res.blocks.back().kind == MotionKind::line) {
        lin = static_cast<long>(i) - 1;
      } else if (j - i > static_cast<std::size_t>(opt.min_blocks) && corner_lead(i, i + 1)) {
        lin = static_cast<long>(i);
        lin_inner = true;
      }
      if (lead_block(static_cast<long>(j), j - 1)) {
        lout = static_cast<long>(j);
      } else if (j - i - (lin_inner ? 1 : 0) > static_cast<std::size_t>(opt.min_blocks) && corner_lead(j - 1, j - 2)) {
        lout = static_cast<long>(j) - 1;
        lout_inner = true;
      }
      const std::size_t r0 = i + (lin_inner ? 1 : 0), r1 = j - (lout_inner ? 1 : 0);  // blocks wholly in the run
      std::vector<long> src;  // per polyline segment: its program block
      double run_len = 0;
      for (std::size_t q = r0; q < r1; ++q) run_len += program[q].length();
      const double mean = run_len / static_cast<double>(r1 - r0);
      pts.clear();
      RunEnds ends;
      Vec3 first3 = program[r0].start, last3 = program[r1 - 1].end;
      if (lin >= 0) {
        const auto& b = program[static_cast<std::size_t>(lin)];
        double a = std::min(opt.lead_length, 0.5 * b.length());
        if (!lin_inner) a = std::min(a, (res.blocks.back().end - res.blocks.back().start).norm());
        const Vec3 d = dir(static_cast<std::size_t>(lin));
        first3 = b.end - a * d;
        const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
        for (int q = 0; q < k; ++q) {
          pts.push_back(to2(first3 + (a * q / k) * d));
          src.push_back(lin);
        }
        ends.fix0 = true;
        ends.d0 = to2(d).normalized();
      }
      pts.push_back(to2(program[r0].start));
      for (std::size_t q = r0; q < r1; ++q) {
        pts.push_back(to2(program[q].end));
        src.push_back(static_cast<long>(q));
      }
      if (lout >= 0) {
        const auto& b = program[static_cast<std::size_t>(lout)];
        const double a = std::min(opt.lead_length, 0.5 * b.length());
        const Vec3 d = dir(static_cast<std::size_t>(lout));
        last3 = b.start + a * d;
        const int k = std::max(1, static_cast<int>(std::ceil(a / mean)));
        for (int q = 1; q <= k; ++q) {
          pts.push_back(to2(q == k ? last3 : Vec3(b.start + (a * q / k) * d)));
          src.push_back(lout);
        }
        ends.fix1 = true;
        ends.d1 = to2(d).normalized();
      }
      const bool lead_in = lin >= 0 && !lin_inner, lead_out = lout >= 0 && !lout_inner;
      RunFit rf;
      if (!fit_run(pts, ends, mean, opt, rf)) return false;
      ++res.runs_smoothed;
      res.max_fit_deviation = std::max(res.max_fit_deviation, rf.bound);
      if (lead_in) {  // the line before now ends where the curve starts
        res.blocks.back().end = first3;
        if ((res.blocks.back().end - res.blocks.back().start).norm() <= 1e-12) {
          res.blocks.pop_back();
          res.source_first.pop_back();
          res.source_last.pop_back();
          program_line.pop_back();
        }
      }
      if (lead_out) {  // the line after starts where the curve ends
        start_override_block = static_cast<long>(j);
        start_override = last3;
      }
      // parameter -> program block
      std::vector<double> cum(pts.size(), 0.0);
      for (std::size_t q = 1; q < pts.size(); ++q) cum[q] = cum[q - 1] + (pts[q] - pts[q - 1]).norm();
      auto block_at = [&](double u) {
        const long s = static_cast<long>(std::upper_bound(cum.begin(), cum.end(), u) - cum.begin()) - 1;
        return src[static_cast<std::size_t>(std::clamp(s, 0L, static_cast<long>(src.size()) - 1))];
      };
      if (lin_inner) {  // the first part of block i, from the corner to where the curve starts
        keep(i);
        res.blocks.back().end = first3;
      }
      Vec3 cur = first3;
      for (std::size_t q = 0; q < rf.pieces.size(); ++q) {
        const Piece& p = rf.pieces[q];
        toolpath::Block b = program[i];
        b.start = cur;
        b.end = q + 1 == rf.pieces.size() ? last3 : to3(p.b);
        if (p.k == 0) {
          b.kind = MotionKind::line;
        } else {
          b.kind = MotionKind::arc;
          b.plane = plane;
          b.center = to3(p.c);
          b.center[ax.n] = b.start[ax.n];
          b.clockwise = p.k < 0;
          b.turns = 1;
        }
        if ((b.end - b.start).norm() <= 1e-12) continue;
        res.blocks.push_back(b);
        res.source_first.push_back(block_at(p.ua));
        res.source_last.push_back(block_at(p.ub));
        program_line.push_back(false);
        cur = b.end;
      }
      if (lout_inner) {  // the last part of block j − 1, from where the curve ends to the corner
        keep(j - 1);
        res.blocks.back().start = last3;
      }
      return true;
    };
    // a run that fails the check is cut at its sharpest interior vertex and both parts are tried
    std::vector<std::pair<std::size_t, std::size_t>> parts{{i, j}};
    const auto mb = static_cast<std::size_t>(opt.min_blocks);
    while (!parts.empty()) {
      const auto [i0, j0] = parts.back();
      parts.pop_back();
      if (j0 - i0 >= mb && fit_emit(i0, j0)) continue;
      if (j0 - i0 >= 2 * mb) {
        std::size_t cut = i0 + mb;
        double worst = -1;
        for (std::size_t q = i0 + mb; q + mb <= j0; ++q) {
          const double th = turn_between(dir(q - 1), dir(q));
          if (th > worst) {
            worst = th;
            cut = q;
          }
        }
        parts.push_back({cut, j0});
        parts.push_back({i0, cut});
        continue;
      }
      if (j0 - i0 >= mb) ++res.runs_kept;
      for (std::size_t q = i0; q < j0; ++q) keep(q);
    }
    i = j;
  }
  // Corners between two program lines (kept corners, the vertices of runs left as programmed, joints
  // of long lines): a tangent arc inside the corner whose distance from the vertex is the fit tolerance
  // e, so the planner no longer has to turn there within the blend tolerance. For a turn θ (half
  // interior angle φ = (π − θ)/2) the arc has radius R = e·sin φ / (1 − sin φ) and touches the lines at
  // T = R·tan(θ/2) from the vertex; T is capped at half of each line's length before rounding (R and
  // the vertex distance shrink with it). Every point of the arc and of the two cut-off line pieces is
  // then within e of the other.
  if (opt.round_corners) {
    const double e = opt.fit_tolerance();
    std::vector<double> len0(res.blocks.size());
    for (std::size_t k = 0; k < res.blocks.size(); ++k) len0[k] = res.blocks[k].length();
    SmoothResult out;
    out.blocks.reserve(res.blocks.size());
    for (std::size_t k = 0; k < res.blocks.size(); ++k) {
      out.blocks.push_back(res.blocks[k]);
      out.source_first.push_back(res.source_first[k]);
      out.source_last.push_back(res.source_last[k]);
      if (k + 1 == res.blocks.size() || !program_line[k] || !program_line[k + 1]) continue;
      toolpath::Block& b1 = out.blocks.back();
      const toolpath::Block& b2 = res.blocks[k + 1];
      if (b1.feed != b2.feed || (b2.start - b1.end).norm() > 1e-9) continue;
      const double l1 = b1.length(), l2 = b2.length();
      if (l1 <= 1e-9 || l2 <= 1e-9) continue;
      const Vec3 d1 = (b1.end - b1.start) / l1, d2 = (b2.end - b2.start) / l2;
      const double th = turn_between(d1, d2);
      if (th < 1e-3 || th > pi - 1e-3) continue;  // nearly straight: the planner blends it; reversals stay
      int n = -1;  // the normal axis of a coordinate plane holding both lines (Z, then Y, then X)
      for (int a : {2, 1, 0})
        if (n < 0 && std::abs(b1.start[a] - b1.end[a]) <= opt.plane_tolerance &&
            std::abs(b2.end[a] - b1.end[a]) <= opt.plane_tolerance)
          n = a;
      if (n < 0) continue;
      const toolpath::Plane plane = n == 2 ? toolpath::Plane::xy : n == 1 ? toolpath::Plane::zx : toolpath::Plane::yz;
      const auto ax = toolpath::plane_axes(plane);
      const double sphi = std::cos(0.5 * th);  // sin φ
      const double tan_half = std::tan(0.5 * th);
      double R = e * sphi / (1.0 - sphi);
      double T = R * tan_half;
      const double cap = std::min({0.5 * len0[k], 0.5 * len0[k + 1], l1 - 1e-9, l2 - 1e-9});
      if (T > cap) {
        T = cap;
        R = T / tan_half;
      }
      if (!(T > 1e-9)) continue;
      const Vec3 V = b1.end;
      const Vec3 p1 = V - T * d1, p2 = V + T * d2;
      const V2 t1(d1[ax.a], d1[ax.b]), t2(d2[ax.a], d2[ax.b]);
      const bool ccw = cross2(t1, t2) > 0;
      const V2 nrm = ccw ? perp(t1) : V2(-perp(t1));
      toolpath::Block arc = b2;
      arc.kind = MotionKind::arc;
      arc.plane = plane;
      arc.start = p1;
      arc.end = p2;
      arc.center = p1;
      arc.center[ax.a] += R * nrm.x();
      arc.center[ax.b] += R * nrm.y();
      arc.clockwise = !ccw;
      arc.turns = 1;
      b1.end = p1;
      res.blocks[k + 1].start = p2;
      out.blocks.push_back(arc);
      out.source_first.push_back(res.source_first[k]);
      out.source_last.push_back(res.source_last[k + 1]);
      ++out.corners_rounded;
    }
    res.blocks = std::move(out.blocks);
    res.source_first = std::move(out.source_first);
    res.source_last = std::move(out.source_last);
    res.corners_rounded = out.corners_rounded;
  }
  return res;
}

double deviation_to_program(const std::vector<toolpath::Block>& program, const Points3& points,
                            const std::vector<long>& first, const std::vector<long>& last) {
  NETSHAPE_CHECK(static_cast<Eigen::Index>(first.size()) == points.rows() && first.size() == last.size(), "first",
                 first.size(), "must have one entry per point (and match last)");
  const long nb = static_cast<long>(program.size());
  double dev = 0;
  std::vector<Segment> segs;
  segs.reserve(program.size());
  for (const auto& b : program)
    segs.push_back(b.kind == toolpath::MotionKind::arc ? Segment::arc(b, 0) : Segment::line(b, 0));
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Vec3 p = points.row(k).transpose();
    const auto kk = static_cast<std::size_t>(k);
    double best = 1e300;
    for (long q = std::max(0L, first[kk] - 1); q <= std::min(nb - 1, last[kk] + 1); ++q) {
      const Segment& s = segs[static_cast<std::size_t>(q)];
      if (s.full_length <= 0) continue;
      best = std::min(best, s.distance_to_piece(p, 0.0, s.full_length));
    }
    if (best < 1e300) dev = std::max(dev, best);
  }
  return dev;
}

}  // namespace netshape::motion
