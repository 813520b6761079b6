#pragma once
// The tolerance-band smoothing stage's fit (private, included by smoothing.cpp only, so everything here
// has internal linkage): 2-D helpers, the cubic B-spline with its banded least-squares fit and exact
// curvature penalty, the samples of a run and the map from spline parameter to program arc length.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "motion/smoothing/stage.hpp"
#include "netshape/core/types.hpp"
#include "motion/kernels/smoothing_kernels.hpp"

namespace netshape::motion {
namespace {

inline double cross2(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline V2 perp(const V2& t) { return V2(-t.y(), t.x()); }

// A segment prepared for distance queries: start a, vector d = end − a, il2 = 1/|d|² (0 for a point).
struct Seg {
  V2 a, d;
  double il2;
};

inline Seg make_seg(const V2& a, const V2& b) {
  const V2 d = b - a;
  const double l2 = d.squaredNorm();
  return Seg{a, d, l2 > 0 ? 1.0 / l2 : 0.0};
}

// squared distance from p to the segment
inline double dist2(const V2& p, const Seg& s) {
  const V2 r = p - s.a;
  const double t = std::clamp(r.dot(s.d) * s.il2, 0.0, 1.0);
  return (r - t * s.d).squaredNorm();
}

// Direction of the bisector at the vertex between consecutive segments s0 and s1: u1 − u0 for their unit
// directions u0, u1 (points on the line through the vertex with this direction are equally far from
// both segments), the normal of s0 where they run straight on, any direction for a point segment.
inline V2 bisector(const Seg& s0, const Seg& s1) {
  const V2 u0 = s0.d * std::sqrt(s0.il2), u1 = s1.d * std::sqrt(s1.il2);
  const V2 w = u1 - u0;
  if (w.squaredNorm() > 0) return w;
  return u0.squaredNorm() > 0 ? perp(u0) : V2(1.0, 0.0);
}

// A chain of segments as rows (detail::SegRows) for the smoothing kernels: the values make_seg()
// gives, one array per field, and the bisectors w[q] (bisector(seg[q], seg[q + 1])) at its vertices.
struct SegTable {
  std::vector<double> ax, ay, dx, dy, il2, wx, wy;
  void assign(const std::vector<Seg>& segs, const std::vector<V2>& w) {
    const std::size_t n = segs.size();
    for (auto* v : {&ax, &ay, &dx, &dy, &il2}) v->resize(n);
    for (std::size_t q = 0; q < n; ++q) {
      ax[q] = segs[q].a.x();
      ay[q] = segs[q].a.y();
      dx[q] = segs[q].d.x();
      dy[q] = segs[q].d.y();
      il2[q] = segs[q].il2;
    }
    wx.resize(w.size());
    wy.resize(w.size());
    for (std::size_t q = 0; q < w.size(); ++q) {
      wx[q] = w[q].x();
      wy[q] = w[q].y();
    }
  }
  detail::SegRows rows() const {
    return {ax.data(), ay.data(), dx.data(), dy.data(), il2.data(), wx.data(), wy.data()};
  }
};

// The squared distances of p0 and p1 to the segments lo..hi of s (dist2() of each) into D0, D1
// [0..hi − lo] and their minima over the window (SmoothingKernels::pair_window says which; sag: per
// segment, or null), several segments per step in the smoothing kernel.
inline void pair_window(const V2& p0, const V2& p1, const SegTable& s, long lo, long hi, const double* sag, double* D0,
                 double* D1, double* mins) {
  static const detail::SmoothingKernels& kernels = detail::smoothing_kernels();
  const double p[4] = {p0.x(), p0.y(), p1.x(), p1.y()};
  const detail::SegRows rows = s.rows();
  kernels.pair_window(p, rows, lo, hi, sag, D0, D1, mins);
}

// A bound on the distance of every point x of the segment [c0, c1] to the chain of segments seg[lo..hi]
// (consecutive: seg[q + 1] starts where seg[q] ends; w[q] = bisector(seg[q], seg[q + 1])). A run of
// consecutive segments qa..qb covers [c0, c1] in parts, cut where [c0, c1] crosses the bisectors of the
// vertices between them; a part is within the larger distance of its two ends from its segment, as the
// distance to a segment is convex along a line. Any cuts give a valid bound, since the parts join
// from c0 to c1 whatever their order; at the bisector the distances to both segments are equal, which
// makes the bound tight where [c0, c1] passes a vertex. The bound's measure val(d2, q) of the squared
// distance d2 to seg[q] is d2 itself, or √d2 + sag[q] where sag is not null (increasing in d2); D0, D1:
// squared distances of c0, c1 to seg[lo..hi]. Returns the smallest largest part value over all runs (a
// single segment included). The values of the ends and of the cuts on both sides of each vertex are
// independent of one another: the smoothing kernel computes them (run_parts), the runs are folded here.
struct RunWork {
  std::vector<double> v0, v1, vn, vx;
};

inline double run_bound(const V2& c0, const V2& c1, const SegTable& seg, long lo, long hi, const double* D0, const double* D1,
                 const double* sag, RunWork& work) {
  static const detail::SmoothingKernels& kernels = detail::smoothing_kernels();
  const auto n = static_cast<std::size_t>(hi - lo + 1);
  for (auto* v : {&work.v0, &work.v1, &work.vn, &work.vx}) v->resize(n);
  const double c[4] = {c0.x(), c0.y(), c1.x(), c1.y()};
  const detail::SegRows rows = seg.rows();
  kernels.run_parts(c, rows, lo, hi, sag, D0, D1, work.v0.data(), work.v1.data(), work.vn.data(), work.vx.data());
  const double *V0 = work.v0.data(), *V1 = work.v1.data();
  const double *VN = work.vn.data(), *VX = work.vx.data();  // per vertex lo + i: the cut's values
  double best = 1e300;
  double cover = 1e300;  // best bound on c0..x (x: the last cut), over runs ending at segment q − 1
  for (long q = lo; q <= hi; ++q) {
    const auto i = static_cast<std::size_t>(q - lo);
    const double v0 = V0[i];
    best = std::min(best, std::max(v0, V1[i]));
    double vx = 0;  // the previous cut's value for segment q
    if (q > lo) {
      vx = VX[i - 1];
      best = std::min(best, std::max({cover, vx, V1[i]}));
    }
    if (q == hi) break;
    const double vn = VN[i];  // the next cut's value for segment q
    cover = std::min(std::max(v0, vn), q > lo ? std::max({cover, vx, vn}) : 1e300);
  }
  return best;
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
  // span(u) for u ≥ 0, searched from span k first (a few steps when u is in or next to it)
  int span_near(double u, int k) const {
    const int m = static_cast<int>(P.size());
    if (u >= t[static_cast<std::size_t>(m)]) return m - 1;
    k = std::clamp(k, 3, m - 1);
    for (int step = 0; step < 4; ++step) {
      if (u < t[static_cast<std::size_t>(k)]) {
        if (k == 3) return 3;
        --k;
      } else if (u >= t[static_cast<std::size_t>(k + 1)]) {
        ++k;  // stays ≤ m − 1, as u < t[m]
      } else {
        return k;
      }
    }
    return span(u);
  }
  // the four non-zero basis values at u in span k (functions k−3..k), from their power form
  void basis(int k, double u, double N[4]) const {
    const auto& b = pb[static_cast<std::size_t>(k)];
    const double x = u - t[static_cast<std::size_t>(k)];
    for (std::size_t r = 0; r < 4; ++r) N[r] = b[r] + x * (b[4 + r] + x * (b[8 + r] + x * b[12 + r]));
  }
  // Power form of each knot span k (t[k] < t[k + 1]): s(u) = c0 + c1·x + c2·x² + c3·x³ with x = u − t[k],
  // the Taylor coefficients at t[k] of the spline. prepare() builds them after the control points
  // change; point(), deriv() and eval() read only them.
  std::vector<std::array<V2, 4>> pw;
  // The same for the basis functions: pb[k][4·j + r] = D_j(N_{k−3+r})(t[k]) / j!, the coefficient of x^j
  // of basis function k − 3 + r on span k, which depend on the knots t[k − 3..k + 4] only.
  // power_basis() fills them after the knots change; prepare() combines them with P and basis()
  // evaluates them.
  std::vector<std::array<double, 16>> pb;
  // Built by the Cox–de Boor recursion on polynomials in x = u − t[k]:
  //   N_{i,p} = (u − t_i)/(t_{i+p} − t_i) · N_{i,p−1} + (t_{i+p+1} − u)/(t_{i+p+1} − t_{i+1}) · N_{i+1,p−1}
  // (a term with a zero denominator is zero), starting from N_{k,0} = 1 on span k.
  // pb of the spans k0..k1 (clipped to 3..m − 1); pb holds m entries. The spans are independent: the
  // smoothing kernel does them several at a time, each with the operations of the recursion above in
  // its order: per degree p = 1..3 and r = 0..p, with a0, a1, b0, b1 = t_i, t_{i+p}, t_{i+1}, t_{i+p+1}
  // relative to t[k] and n = N_{·, p−1}, M[r][j] += f·(n[j−1] − a0·n[j]) with f = 1/(a1 − a0) where
  // a1 > a0 (n[−1] = 0, the j = 0 term f·(−a0·n[0])), then M[r][j] += f·(b1·n'[j] − n'[j−1]) with
  // n' = N_{i+1, p−1}, f = 1/(b1 − b0) where b1 > b0 (the j = 0 term f·(b1·n'[0])), M starting at zero.
  void power_basis(int k0, int k1) {
    const int m = static_cast<int>(P.size());
    k0 = std::max(k0, 3);
    k1 = std::min(k1, m - 1);
    if (k0 > k1) return;
    static const detail::SmoothingKernels& kernels = detail::smoothing_kernels();
    kernels.power_basis(t.data(), k0, k1, pb.data()->data());
  }
  // pw of the spans k0..k1 (clipped to 3..m − 1) from pb and P; the spans a control point i reaches
  // are i..i + 3, so after P[lo..hi] change, prepare(lo, hi + 3) brings pw up to date
  void prepare(int k0, int k1) {
    const int m = static_cast<int>(P.size());
    if (pw.size() != P.size()) pw.resize(P.size());
    for (int k = std::max(k0, 3); k <= std::min(k1, m - 1); ++k) {
      auto& c = pw[static_cast<std::size_t>(k)];
      c = {V2::Zero(), V2::Zero(), V2::Zero(), V2::Zero()};
      if (!(t[static_cast<std::size_t>(k + 1)] > t[static_cast<std::size_t>(k)])) continue;
      const auto& b = pb[static_cast<std::size_t>(k)];
      for (int r = 0; r < 4; ++r) {
        const V2& Pr = P[static_cast<std::size_t>(k - 3 + r)];
        c[0] += b[static_cast<std::size_t>(r)] * Pr;
        c[1] += b[static_cast<std::size_t>(4 + r)] * Pr;
        c[2] += b[static_cast<std::size_t>(8 + r)] * Pr;
        c[3] += b[static_cast<std::size_t>(12 + r)] * Pr;
      }
    }
  }
  // Insert the knot x (t[3] < x < t[m], no knot yet) without changing the curve (Boehm): in x's span k
  // the control points k − 2..k become P'_i = a_i·P_i + (1 − a_i)·P_{i−1}, a_i = (x − t_i)/(t_{i+3} − t_i),
  // and the ones after move up by one; span k becomes spans k and k + 1. pb and pw are left to the caller
  // (a span the new knot does not reach, outside k − 3..k + 4, keeps them, one index up). Returns k.
  int insert_knot(double x) {
    const int k = span(x);
    P.insert(P.begin() + k, V2::Zero());  // the old P_i, i ≥ k, is now at i + 1
    for (int i = k; i >= k - 2; --i) {
      const double ti = t[static_cast<std::size_t>(i)];
      const double a = (x - ti) / (t[static_cast<std::size_t>(i + 3)] - ti);
      const V2& pi = P[static_cast<std::size_t>(i == k ? k + 1 : i)];
      P[static_cast<std::size_t>(i)] = a * pi + (1.0 - a) * P[static_cast<std::size_t>(i - 1)];
    }
    t.insert(t.begin() + k + 1, x);
    return k;
  }
  V2 point(double u) const { return point_in(span(u), u); }
  // the polynomial of span k at u (u in [t[k], t[k + 1]])
  V2 point_in(int k, double u) const {
    const auto& c = pw[static_cast<std::size_t>(k)];
    const double x = u - t[static_cast<std::size_t>(k)];
    return c[0] + x * (c[1] + x * (c[2] + x * c[3]));
  }
  V2 deriv(double u) const {
    const int k = span(u);
    const auto& c = pw[static_cast<std::size_t>(k)];
    const double x = u - t[static_cast<std::size_t>(k)];
    return c[1] + x * (2.0 * c[2] + x * (3.0 * c[3]));
  }
  // point, first and second derivative at u; k: on entry a span to search from, on return u's span
  void eval(double u, int& k, V2& s0, V2& s1, V2& s2) const {
    k = span_near(u, k);
    const auto& c = pw[static_cast<std::size_t>(k)];
    const double x = u - t[static_cast<std::size_t>(k)];
    s0 = c[0] + x * (c[1] + x * (c[2] + x * c[3]));
    s1 = c[1] + x * (2.0 * c[2] + x * (3.0 * c[3]));
    s2 = 2.0 * c[2] + (6.0 * x) * c[3];
  }
};

// Symmetric banded solve (half bandwidth 3) by Cholesky: A(i, i + k) = band[i][k] for rows 0..n − 1
// (entries with i + k ≥ n are not read); in place on rhs (left changed when A is not positive
// definite: false). lo: workspace, lo[i][k] = L(i, i − k). Each row's forward substitution follows its
// factorisation in the same pass (the same operations as two passes: a row's step reads only rows
// already done), so the processor overlaps the two chains of divisions and roots.
inline bool band_solve(const std::array<double, 4>* band, V2* rhs, int n, std::vector<std::array<double, 4>>& lo) {
  lo.resize(static_cast<std::size_t>(n));
  auto L = [&](int i) -> std::array<double, 4>& { return lo[static_cast<std::size_t>(i)]; };
  for (int i = 0; i < n; ++i) {
    auto& li = L(i);
    li = {0, 0, 0, 0};
    double diag = band[i][0];
    if (i >= 3) {  // the general case below, unrolled
      li[3] = band[i - 3][3] / L(i - 3)[0];
      diag -= li[3] * li[3];
      li[2] = (band[i - 2][2] - li[3] * L(i - 2)[1]) / L(i - 2)[0];
      diag -= li[2] * li[2];
      li[1] = (band[i - 1][1] - li[3] * L(i - 1)[2] - li[2] * L(i - 1)[1]) / L(i - 1)[0];
      diag -= li[1] * li[1];
    } else {
      for (int k = i; k >= 1; --k) {  // L(i, j) for j = i − k, from A(j, i) = band[j][k]
        const int j = i - k;
        const auto& lj = L(j);
        double s = band[j][static_cast<std::size_t>(k)];
        for (int q = 0; q < j; ++q) s -= li[static_cast<std::size_t>(i - q)] * lj[static_cast<std::size_t>(j - q)];
        li[static_cast<std::size_t>(k)] = s / lj[0];
        diag -= li[static_cast<std::size_t>(k)] * li[static_cast<std::size_t>(k)];
      }
    }
    if (!(diag > 0)) return false;
    li[0] = std::sqrt(diag);
    V2 s = rhs[i];
    if (i >= 3) {
      s -= li[3] * rhs[i - 3];
      s -= li[2] * rhs[i - 2];
      s -= li[1] * rhs[i - 1];
    } else {
      for (int q = 0; q < i; ++q) s -= li[static_cast<std::size_t>(i - q)] * rhs[q];
    }
    rhs[i] = s / li[0];
  }
  for (int i = n - 1; i >= 0; --i) {
    V2 s = rhs[i];
    if (i + 3 < n) {
      s -= L(i + 1)[1] * rhs[i + 1];
      s -= L(i + 2)[2] * rhs[i + 2];
      s -= L(i + 3)[3] * rhs[i + 3];
    } else {
      for (int q = i + 1; q < n; ++q) s -= L(q)[static_cast<std::size_t>(q - i)] * rhs[q];
    }
    rhs[i] = s / L(i)[0];
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

// The samples whose foot points a round moves (their indices q) and, per sample, the parameter u and
// span k (in: the sample's, out: its foot point's) and the residual res, for SmoothingKernels::foot_points.
struct FootWork {
  std::vector<std::size_t> q;
  std::vector<double> u, px, py, res;
  std::vector<int> k;
  // the samples on the spans marked in `changed` (span[i]: sample i's), in their order
  void collect(const std::vector<Sample>& samples, const std::vector<int>& span, const std::vector<char>& changed) {
    const std::size_t n = samples.size();
    q.resize(n);
    u.resize(n);
    px.resize(n);
    py.resize(n);
    k.resize(n);
    std::size_t c = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int ki = span[i];
      if (!changed[static_cast<std::size_t>(ki)]) continue;
      q[c] = i;
      u[c] = samples[i].u;
      px[c] = samples[i].p.x();
      py[c] = samples[i].p.y();
      k[c] = ki;
      ++c;
    }
    for (auto* v : {&u, &px, &py}) v->resize(c);
    q.resize(c);
    k.resize(c);
  }
  void run(const Spline& sp, double L, double mean) {
    static const detail::SmoothingKernels& kernels = detail::smoothing_kernels();
    res.resize(q.size());
    const detail::FootSpline f{sp.t.data(), sp.pw.data()->data()->data(), static_cast<int>(sp.P.size()), L, mean};
    kernels.foot_points(f, static_cast<int>(q.size()), u.data(), k.data(), px.data(), py.data(), res.data());
  }
};

// Monotone map from the spline parameter to arc length along the polyline, piecewise linear through the
// samples' (foot point parameter, arc length) pairs. The smoothed curve is shorter than the polyline
// where it cuts across wiggles, so its parameter drifts from the polyline's arc length along a run;
// program blocks and nearby polyline segments are found through this map.
struct ParamMap {
  std::vector<double> u, a;
  std::vector<std::pair<double, double>> ua;  // (build's buffer)
  void build(const std::vector<Sample>& samples, double L) {
    ua.clear();
    ua.emplace_back(0.0, 0.0);
    for (const Sample& s : samples) ua.emplace_back(s.u, s.a);
    ua.emplace_back(L, L);
    // (the samples' parameters mostly ascend already)
    if (!std::is_sorted(ua.begin(), ua.end())) std::sort(ua.begin(), ua.end());
    u.clear();
    a.clear();
    for (const auto& [x, y] : ua) {
      u.push_back(x);
      a.push_back(a.empty() ? y : std::max(a.back(), y));
    }
  }
  double operator()(double x) const {
    std::size_t k = static_cast<std::size_t>(std::upper_bound(u.begin(), u.end(), x) - u.begin());
    return at(x, k);
  }
  // the same for nondecreasing x over a sequence of calls; k: a cursor, 0 before the first call
  double walk(double x, std::size_t& k) const {
    while (k < u.size() && u[k] <= x) ++k;
    return at(x, k);
  }
  // with k the first index with u[k] > x
  double at(double x, std::size_t k) const {
    if (k == 0) return a.front();
    if (k == u.size()) return a.back();
    const double du = u[k] - u[k - 1];
    return du > 0 ? a[k - 1] + (a[k] - a[k - 1]) * (x - u[k - 1]) / du : a[k];
  }
};

// Rows r0..r1 (clipped to 0..m − 1) of the band of pen·∫|s''|² over [0, L] in the control points (rows
// as in band_solve) from sp's power basis: row r sums the spans r..r + 3. On span k the basis function
// r has N_r'' = α_r + β_r·x (x = u − t[k]), with α_r = 2·pb[8 + r] and β_r = 6·pb[12 + r], so
// ∫_0^h N_r''·N_q'' dx is exact in closed form.
inline void penalty_rows(const Spline& sp, double pen, std::vector<std::array<double, 4>>& pen_band, int r0, int r1) {
  const int m = static_cast<int>(sp.P.size());
  r0 = std::max(r0, 0);
  r1 = std::min(r1, m - 1);
  for (int r = r0; r <= r1; ++r) pen_band[static_cast<std::size_t>(r)] = {0, 0, 0, 0};
  for (int k = std::max(r0, 3); k <= std::min(r1 + 3, m - 1); ++k) {
    const double h = sp.t[static_cast<std::size_t>(k + 1)] - sp.t[static_cast<std::size_t>(k)];
    if (!(h > 0)) continue;
    const auto& b = sp.pb[static_cast<std::size_t>(k)];
    double al[4], be[4];
    for (std::size_t r = 0; r < 4; ++r) {
      al[r] = 2.0 * b[8 + r];
      be[r] = 6.0 * b[12 + r];
    }
    const double h2 = 0.5 * h * h, h3 = h * h * h / 3.0;
    for (int r = std::max(0, r0 - k + 3); r < 4 && k - 3 + r <= r1; ++r)
      for (int q = r; q < 4; ++q)
        pen_band[static_cast<std::size_t>(k - 3 + r)][static_cast<std::size_t>(q - r)] +=
            pen * (al[r] * al[q] * h + (al[r] * be[q] + al[q] * be[r]) * h2 + be[r] * be[q] * h3);
  }
}

// Penalised least squares on a window of control points: P[lo..hi] minimise
//   Σ_k w_k |s(u_k) − p_k|² + pen · ∫ |s''(u)|² du
// with every other control point held at its value in sp.P — rows lo..hi of the normal equations, the
// held points moved to the right-hand side; banded Cholesky, O(hi − lo) plus a pass over the samples'
// spans. Row i involves the samples in spans i..i + 3 only, so the samples in spans lo..hi + 3 (span[k]:
// sample k's) give rows lo..hi and their couplings to the held points lo − 3..lo − 1 in full. With lo
// and hi the first and last free control point this is the global solve. pen_band: penalty_rows() of
// every row; sp.pw of the spans lo..hi + 3 is rebuilt. work: buffers kept between calls.
struct FitWork {
  std::vector<std::array<double, 4>> band, lo;
  std::vector<V2> rhs;
};

inline bool solve_window(const std::vector<Sample>& samples, const std::vector<int>& span, int lo, int hi,
                  const std::vector<std::array<double, 4>>& pen_band, Spline& sp, FitWork& work) {
  const int m = static_cast<int>(sp.P.size());
  auto& band = work.band;
  auto& rhs = work.rhs;
  band.resize(static_cast<std::size_t>(m));
  rhs.resize(static_cast<std::size_t>(m));
  const int r0 = std::max(0, lo - 3), r1 = std::min(m - 1, hi + 3);  // rows the samples below touch
  for (int i = r0; i <= r1; ++i) {
    band[static_cast<std::size_t>(i)] = pen_band[static_cast<std::size_t>(i)];
    rhs[static_cast<std::size_t>(i)] = V2::Zero();
  }
  for (std::size_t q = 0; q < samples.size(); ++q) {
    const int k = span[q];
    if (k < lo || k > hi + 3) continue;
    const Sample& s = samples[q];
    double N[4];
    sp.basis(k, s.u, N);
    // rows k − 3..k: rhs += w·N_r·p, A(r, c) += w·N_r·N_c
    const double w0 = s.w * N[0], w1 = s.w * N[1], w2 = s.w * N[2], w3 = s.w * N[3];
    auto* b = band.data() + (k - 3);
    V2* y = rhs.data() + (k - 3);
    b[0][0] += w0 * N[0];
    b[0][1] += w0 * N[1];
    b[0][2] += w0 * N[2];
    b[0][3] += w0 * N[3];
    b[1][0] += w1 * N[1];
    b[1][1] += w1 * N[2];
    b[1][2] += w1 * N[3];
    b[2][0] += w2 * N[2];
    b[2][1] += w2 * N[3];
    b[3][0] += w3 * N[3];
    y[0] += w0 * s.p;
    y[1] += w1 * s.p;
    y[2] += w2 * s.p;
    y[3] += w3 * s.p;
  }
  // move the held control points to the right-hand side: A(i, f) = band[min(i, f)][|i − f|]
  for (int i = lo; i <= hi; ++i) {
    auto& ri = rhs[static_cast<std::size_t>(i)];
    for (int f = std::max(0, i - 3); f < lo; ++f)
      ri -= band[static_cast<std::size_t>(f)][static_cast<std::size_t>(i - f)] * sp.P[static_cast<std::size_t>(f)];
    for (int f = hi + 1; f <= std::min(m - 1, i + 3); ++f)
      ri -= band[static_cast<std::size_t>(i)][static_cast<std::size_t>(f - i)] * sp.P[static_cast<std::size_t>(f)];
  }
  if (!band_solve(band.data() + lo, rhs.data() + lo, hi - lo + 1, work.lo)) return false;
  for (int i = lo; i <= hi; ++i) sp.P[static_cast<std::size_t>(i)] = rhs[static_cast<std::size_t>(i)];
  sp.prepare(lo, hi + 3);
  return true;
}

}  // namespace
}  // namespace netshape::motion
