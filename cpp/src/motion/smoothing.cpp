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
  NETSHAPE_CHECK(max_refinements >= 0, "max_refinements", max_refinements, "must be >= 0");
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

// Least-squares fit with fixed end points; data at vertices and segment midpoints.
bool fit(const std::vector<V2>& pts, const std::vector<double>& cum, const std::vector<double>& interior, Spline& sp) {
  const double L = cum.back();
  const int m = static_cast<int>(interior.size()) + 4;
  sp.t.assign(4, 0.0);
  sp.t.insert(sp.t.end(), interior.begin(), interior.end());
  sp.t.insert(sp.t.end(), 4, L);
  sp.P.assign(static_cast<std::size_t>(m), V2::Zero());
  std::vector<std::array<double, 4>> band(static_cast<std::size_t>(m), std::array<double, 4>{0, 0, 0, 0});
  std::vector<V2> rhs(static_cast<std::size_t>(m), V2::Zero());
  auto add = [&](double u, const V2& p) {
    const int k = sp.span(u);
    double N[4];
    sp.basis(k, u, N);
    for (int r = 0; r < 4; ++r) {
      const auto i = static_cast<std::size_t>(k - 3 + r);
      rhs[i] += N[r] * p;
      for (int q = r; q < 4; ++q) band[i][static_cast<std::size_t>(q - r)] += N[r] * N[q];
    }
  };
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    add(cum[i], pts[i]);
    if (i + 1 < n) add(0.5 * (cum[i] + cum[i + 1]), 0.5 * (pts[i] + pts[i + 1]));
  }
  // a light second-difference penalty keeps spans without data well posed
  const double lam = 1e-6;
  for (int i = 1; i + 1 < m; ++i) {
    const double c[3] = {1.0, -2.0, 1.0};
    for (int r = 0; r < 3; ++r)
      for (int q = r; q < 3; ++q) band[static_cast<std::size_t>(i - 1 + r)][static_cast<std::size_t>(q - r)] += lam * c[r] * c[q];
  }
  const V2 P0 = pts.front(), P1 = pts.back();
  // eliminate the fixed end control points
  for (int i = 1; i <= 3 && i < m - 1; ++i) rhs[static_cast<std::size_t>(i)] -= band[0][static_cast<std::size_t>(i)] * P0;
  for (int i = std::max(1, m - 4); i < m - 1; ++i)
    rhs[static_cast<std::size_t>(i)] -= band[static_cast<std::size_t>(i)][static_cast<std::size_t>(m - 1 - i)] * P1;
  std::vector<std::array<double, 4>> inner(band.begin() + 1, band.end() - 1);
  for (std::size_t i = 0; i < inner.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k)
      if (i + k >= inner.size()) inner[i][k] = 0;
  std::vector<V2> x(rhs.begin() + 1, rhs.end() - 1);
  if (!inner.empty() && !band_solve(inner, x)) return false;
  sp.P.front() = P0;
  sp.P.back() = P1;
  for (std::size_t i = 0; i < x.size(); ++i) sp.P[i + 1] = x[i];
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

// Fit a planar run; returns false when the check fails after the allowed refinements.
bool fit_run(const std::vector<V2>& pts, const SmoothOptions& opt, RunFit& out) {
  const std::size_t n = pts.size();  // vertices
  std::vector<double> cum(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) cum[i] = cum[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double L = cum.back();
  const double eps = opt.fit_tolerance();
  const double mean = L / static_cast<double>(n - 1);
  // initial interior knots: uniform in arc length, about three segments apart
  std::vector<double> knots;
  const int r0 = std::max(0, static_cast<int>(std::floor(L / (3.0 * mean))) - 1);
  for (int i = 1; i <= r0; ++i) knots.push_back(L * i / (r0 + 1));
  Spline sp;
  const double sag_share = 0.05 * eps;
  const double fit_arc = 0.1 * eps;
  for (int round = 0; round <= opt.max_refinements; ++round) {
    if (!fit(pts, cum, knots, sp)) {
      return false;
    }
    // biarc chain over the knot spans, split until the spline's quarter points are within fit_arc
    out.pieces.clear();
    std::vector<double> bad;
    std::vector<double> breaks;
    breaks.push_back(0.0);
    for (double k : knots)
      if (k > breaks.back()) breaks.push_back(k);
    if (L > breaks.back()) breaks.push_back(L);
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
          for (double f : {0.25, 0.5, 0.75}) {
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
        cu.push_back(p.ua + (p.ub - p.ua) * j / nc);
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
    // chords whose parameter lies within ±w of the polyline piece's (the spline parameter follows the
    // polyline's arc length closely; a miss only overestimates the bound)
    const double w = 0.75 * mean;
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
    if (bad.empty()) return true;
    // refine: a knot in the middle of every knot span that holds a failure
    std::vector<double> add;
    std::sort(bad.begin(), bad.end());
    for (double u : bad) {
      const auto it = std::upper_bound(breaks.begin(), breaks.end(), u);
      const std::size_t s = std::clamp<std::size_t>(static_cast<std::size_t>(it - breaks.begin()), 1, breaks.size() - 1);
      const double mid = 0.5 * (breaks[s - 1] + breaks[s]);
      // spans are not split below a quarter of the mean segment: they would hold too little data
      if (breaks[s] - breaks[s - 1] < 0.25 * mean) continue;
      if (add.empty() || add.back() != mid) add.push_back(mid);
    }
    if (add.empty()) return false;
    knots.insert(knots.end(), add.begin(), add.end());
    std::sort(knots.begin(), knots.end());
    knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
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
  auto keep = [&](std::size_t i) {
    res.blocks.push_back(program[i]);
    res.source_first.push_back(static_cast<long>(i));
    res.source_last.push_back(static_cast<long>(i));
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
    auto fit_emit = [&](std::size_t i, std::size_t j) -> bool {
      pts.clear();
      pts.emplace_back(program[i].start[ax.a], program[i].start[ax.b]);
      for (std::size_t q = i; q < j; ++q) pts.emplace_back(program[q].end[ax.a], program[q].end[ax.b]);
      RunFit rf;
      if (!fit_run(pts, opt, rf)) return false;
      ++res.runs_smoothed;
      res.max_fit_deviation = std::max(res.max_fit_deviation, rf.bound);
      // parameter -> program block
      std::vector<double> cum(pts.size(), 0.0);
      for (std::size_t q = 1; q < pts.size(); ++q) cum[q] = cum[q - 1] + (pts[q] - pts[q - 1]).norm();
      auto block_at = [&](double u) {
        const long s = static_cast<long>(std::upper_bound(cum.begin(), cum.end(), u) - cum.begin()) - 1;
        return static_cast<long>(i) + std::clamp(s, 0L, static_cast<long>(j - i) - 1);
      };
      const double nval = program[i].start[ax.n];
      auto to3 = [&](const V2& p) {
        Vec3 v;
        v[ax.a] = p.x();
        v[ax.b] = p.y();
        v[ax.n] = nval;
        return v;
      };
      Vec3 cur = program[i].start;
      for (std::size_t q = 0; q < rf.pieces.size(); ++q) {
        const Piece& p = rf.pieces[q];
        toolpath::Block b = program[i];
        b.start = cur;
        b.end = q + 1 == rf.pieces.size() ? program[j - 1].end : to3(p.b);
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
        cur = b.end;
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
