#pragma once
// The tolerance-band smoothing stage's arcs and runs (private, included by smoothing.cpp only, so
// everything here has internal linkage): circular pieces and biarcs, one run's fit pulled back into the
// tube and checked both ways on its arcs, and the leads a run borrows from its neighbours.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "netshape/core/types.hpp"
#include "netshape/motion/smoothing.hpp"
#include "netshape/toolpath/block.hpp"
#include "smoothing_spline.hpp"

namespace netshape::motion {
namespace {

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

constexpr double sharp_turn = 0.3;  // [rad] a vertex turning more gets dense knots and samples
constexpr int sharp_reach = 8;      // they reach ±2·sharp_reach fit tolerances from the vertex

// Interior vertices of the polyline turning more than sharp_turn.
std::vector<std::size_t> sharp_vertices(const std::vector<V2>& pts, const std::vector<double>& cum) {
  std::vector<std::size_t> out;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double l0 = cum[i] - cum[i - 1], l1 = cum[i + 1] - cum[i];
    if (!(l0 > 0) || !(l1 > 0)) continue;
    const V2 a = (pts[i] - pts[i - 1]) / l0, b = (pts[i + 1] - pts[i]) / l1;
    if (std::atan2(std::abs(cross2(a, b)), a.dot(b)) > sharp_turn) out.push_back(i);
  }
  return out;
}

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
  // Next to a sharp vertex (turning more than sharp_turn) the curve has to turn within a few fit
  // tolerances: knots every 2·eps and samples every eps within ±16·eps of it give the spline the
  // freedom to do so and the fit the data to see it.
  const auto sharp = sharp_vertices(pts, cum);
  for (const std::size_t i : sharp)
    for (int q = -sharp_reach; q <= sharp_reach; ++q) {
      const double u = cum[i] + 2.0 * q * eps;
      if (u > 2.0 * eps && u < L - 2.0 * eps) knots.push_back(u);
    }
  if (!sharp.empty()) {
    std::sort(knots.begin(), knots.end());
    std::vector<double> kept;  // no two knots closer than eps
    for (const double u : knots)
      if (kept.empty() || u - kept.back() > eps) kept.push_back(u);
    knots.swap(kept);
  }
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
  for (const std::size_t i : sharp) {
    const V2 a = (pts[i] - pts[i - 1]) / (cum[i] - cum[i - 1]), b = (pts[i + 1] - pts[i]) / (cum[i + 1] - cum[i]);
    for (int q = -2 * sharp_reach; q <= 2 * sharp_reach; ++q) {
      const double u = cum[i] + q * eps;
      if (q == 0 || u <= cum[i - 1] || u >= cum[i + 1]) continue;
      samples.push_back(Sample{u, q < 0 ? V2(pts[i] + (u - cum[i]) * a) : V2(pts[i] + (u - cum[i]) * b), eps, u});
    }
  }
  if (!sharp.empty())
    std::sort(samples.begin(), samples.end(), [](const Sample& x, const Sample& y) { return x.u < y.u; });
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
        if (breaks[k] - breaks[k - 1] > std::min(mean / 16.0, 0.5 * eps)) knots.push_back(0.5 * (breaks[k - 1] + breaks[k]));
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
}  // namespace netshape::motion
