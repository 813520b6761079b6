#pragma once
// The tolerance-band smoothing stage's check (private, included through smoothing_fit.hpp by
// smoothing.cpp only, so everything here has internal linkage): a run's spline as cubic Bézier pieces
// and the two-way check of the spline against the run's polyline, with rigorous bounds.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "netshape/core/types.hpp"
#include "smoothing_spline.hpp"

namespace netshape::motion {
namespace {

// One knot span of the fitted spline as a cubic Bézier (control points b0..b3); consecutive pieces
// join with equal tangents and curvatures (the spline is C²).
struct Piece {
  V2 b0, b1, b2, b3;
  double ua = 0, ub = 0;  // spline parameter range; after chain_check: arc lengths along the polyline
};

struct RunFit {
  std::vector<Piece> pieces;
  double bound = 0;
};

// The pieces of the spline (its non-empty knot spans, from the power form: with a_j = c_j·h^j,
// b0 = a0, b1 = a0 + a1/3, b2 = a0 + 2a1/3 + a2/3, b3 = a0 + a1 + a2 + a3), then the two-way check of the
// spline against the polyline. Chords of the spline within one knot span, at parameters u0 < u1,
// deviate from it by at most σ = (u1 − u0)²/8 · max|s''| (linear interpolation error; s'' is linear
// on a span, so its largest norm is at u0 or u1); chords are placed so that σ ≤ 0.03·eps and no chord
// is longer than half a mean segment. Fills out.pieces (their ua, ub as arc lengths along the polyline)
// and out.bound; the polyline arc lengths of the places where the bound exceeds eps go to bad.
// Bisections of one failing chord or polyline piece before it counts as out of the tube (a curve that
// really leaves the tube would otherwise be bisected down to `fine` all along the stretch it is out).
constexpr int max_bisections = 64;

// The bounds of the last check, so that a check of a spline that changed only in places re-checks only
// what the change reaches. A bound is an upper bound of distances between real points of the spline
// and the polyline, so it stays valid while the chords and segments it was computed from stay (which
// chords and segments a window holds only makes it tighter or looser). A bound that is negative (to
// be checked) or above eps is computed again.
struct CheckCache {
  std::vector<double> span_bound;      // per knot span: the largest bound of its chords (spline -> polyline)
  std::vector<double> seg_bound;       // per polyline segment: its bound (polyline -> spline)
  std::vector<double> seg_u0, seg_u1;  // per polyline segment: the parameter range of the chords it was bounded by
  // buffers kept between checks (chain_check says what they hold)
  std::vector<V2> cp, cw;
  std::vector<double> cu, cpar, csag, Q0, Q1;
  std::vector<int> cspan;
  std::vector<char> todo;
  std::vector<std::pair<double, double>> fresh;
  std::vector<Seg> cseg;
  SegTable crows;  // cseg and cw as rows
  RunWork run;
};

// In a check with the cache, the chords of a knot span whose bound is valid and the polyline segments
// whose chords all lie in such spans keep their bounds.
bool chain_check(const Spline& sp, const std::vector<V2>& pts, const SegTable& srows, const std::vector<double>& cum,
                 const ParamMap& amap, double eps, double mean, CheckCache& cache, RunFit& out,
                 std::vector<double>& bad) {
  const std::size_t n = pts.size();
  const double sag_share = 0.03 * eps;
  bad.clear();
  out.pieces.clear();
  const int m = static_cast<int>(sp.P.size());
  // chord samples of the spline with their parameters, sagitta bound and span
  auto& cp = cache.cp;
  auto& cu = cache.cu;      // polyline arc length of each chord point
  auto& cpar = cache.cpar;  // parameter of each chord point
  auto& csag = cache.csag;
  auto& cspan = cache.cspan;  // per chord j (cp[j], cp[j+1]): its knot span
  cp.assign(1, sp.P.front());
  cu.clear();
  cpar.clear();
  csag.clear();
  cspan.clear();
  cu.push_back(0.0);
  cpar.push_back(0.0);
  std::size_t mk = 0;  // cursor of amap for the nondecreasing chord parameters
  for (int k = 3; k < m; ++k) {
    const double t0 = sp.t[static_cast<std::size_t>(k)], t1 = sp.t[static_cast<std::size_t>(k + 1)];
    const double h = t1 - t0;
    if (!(h > 0)) continue;
    const auto& c = sp.pw[static_cast<std::size_t>(k)];
    Piece pc;
    const V2 a1 = c[1] * h, a2 = c[2] * (h * h), a3 = c[3] * (h * h * h);
    pc.b0 = c[0];
    pc.b1 = c[0] + a1 / 3.0;
    pc.b2 = c[0] + (2.0 / 3.0) * a1 + a2 / 3.0;
    pc.b3 = c[0] + a1 + a2 + a3;
    pc.ua = t0;
    pc.ub = t1;
    out.pieces.push_back(pc);
    const double k2 = std::max((2.0 * c[2]).norm(), (2.0 * c[2] + 6.0 * h * c[3]).norm());  // max |s''|
    int nc = std::max(1, static_cast<int>(std::ceil(h / (0.5 * mean))));
    if (k2 > 0) nc = std::max(nc, static_cast<int>(std::ceil(h * std::sqrt(k2 / (8.0 * sag_share)))));
    const double hc = h / nc;
    const double sag = k2 * hc * hc / 8.0;
    for (int j = 1; j <= nc; ++j) {
      const double u = j == nc ? t1 : t0 + hc * j;
      cp.push_back(j == nc && k == m - 1 ? sp.P.back() : sp.point_in(k, u));
      cu.push_back(amap.walk(u, mk));
      cpar.push_back(u);
      csag.push_back(sag);
      cspan.push_back(k);
    }
  }
  if (out.pieces.empty()) return false;
  double bound = 0;
  const double fine = 0.1 * eps;  // bisect a failing chord down to this length [mm]
  // spline -> polyline: every spline point between chord points c0, c1 is within σ of the chord, and
  // every chord point within run_bound of the polyline segments s − 3..s + 3 (s: the segment at the
  // chord's middle through the parameter map); squared distances, one root at the end (the root is
  // increasing, so min and max commute with it)
  const long ns = static_cast<long>(n) - 1;
  double D0[7], D1[7];
  auto window = [&](long s, long& lo, long& hi) {
    lo = std::max(0L, s - 3);
    hi = std::min(ns - 1, s + 3);
  };
  // The bound for chord [c0, c1] with sagitta bound sag against the window lo..hi, D0 and D1 filled
  // for c0, c1 on the way: first the best single segment (best2: the smallest over q of the larger
  // squared distance of c0, c1 to segment q), then run_bound. `lost`: an end point alone is farther
  // than eps from the window, so every part of the chord that holds it is bounded above eps however the
  // chord is cut (the chord fails).
  auto chord_bound = [&](const V2& c0, const V2& c1, long lo, long hi, double sag, bool& lost) {
    double mins[3];  // best2, then the smallest squared distances m0, m1 of c0 and of c1
    pair_window(c0, c1, srows, lo, hi, nullptr, D0, D1, mins);
    const double best2 = mins[0], m0 = mins[1], m1 = mins[2];
    const double b = std::sqrt(best2) + sag;
    lost = std::sqrt(std::max(m0, m1)) > eps;
    if (b <= eps || lost) return b;  // one segment will do, or nothing will
    return std::min(b, std::sqrt(run_bound(c0, c1, srows, lo, hi, D0, D1, nullptr, cache.run)) + sag);
  };
  struct Job {
    double u0, u1, sag;
    V2 c0, c1;
  };
  std::vector<Job> jobs;
  std::size_t sc = 0;      // segment search: cum[sc] <= um for the chords' nondecreasing middles um
  auto& span_bound = cache.span_bound;
  auto valid = [eps](double b) { return b >= 0 && b <= eps; };
  // the spans to check (their bounds start at 0) and their parameter ranges, merged
  auto& todo = cache.todo;
  auto& fresh = cache.fresh;
  todo.assign(static_cast<std::size_t>(m), 0);
  fresh.clear();
  for (int k = 3; k < m; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    if (valid(span_bound[uk]) || !(sp.t[uk + 1] > sp.t[uk])) continue;
    todo[uk] = 1;
    span_bound[uk] = 0;
    if (!fresh.empty() && fresh.back().second >= sp.t[uk]) {
      fresh.back().second = sp.t[uk + 1];
    } else {
      fresh.emplace_back(sp.t[uk], sp.t[uk + 1]);
    }
  }
  for (std::size_t j = 0; j + 1 < cp.size(); ++j) {
    const double um = 0.5 * (cu[j] + cu[j + 1]);
    while (sc + 1 < cum.size() && cum[sc + 1] <= um) ++sc;
    double& sb = span_bound[static_cast<std::size_t>(cspan[j])];
    if (!todo[static_cast<std::size_t>(cspan[j])]) {
      bound = std::max(bound, sb);
      continue;
    }
    const long s = std::clamp(static_cast<long>(sc), 0L, ns - 1);
    long lo, hi;
    window(s, lo, hi);
    bool lost;
    double best = chord_bound(cp[j], cp[j + 1], lo, hi, csag[j], lost);
    if (best > eps && !lost) {  // bisect the chord; the first part that fails decides
      jobs.assign(1, Job{cpar[j], cpar[j + 1], csag[j], cp[j], cp[j + 1]});
      best = 0;
      int budget = max_bisections;
      while (!jobs.empty()) {
        const Job jb = jobs.back();
        jobs.pop_back();
        const double b = chord_bound(jb.c0, jb.c1, lo, hi, jb.sag, lost);
        if (b > eps && !lost && (jb.c1 - jb.c0).norm() > fine && --budget > 0) {
          const double um2 = 0.5 * (jb.u0 + jb.u1);
          const V2 cm = sp.point(um2);
          jobs.push_back(Job{jb.u0, um2, 0.25 * jb.sag, jb.c0, cm});
          jobs.push_back(Job{um2, jb.u1, 0.25 * jb.sag, cm, jb.c1});
          continue;
        }
        best = std::max(best, b);
        if (best > eps) break;
      }
    }
    bound = std::max(bound, best);
    if (best > eps) bad.push_back(um);
    sb = std::max(sb, best);
  }
  // polyline -> spline: every point of a polyline piece [q0, q1] is within run_bound of the chords, each
  // chord's part plus its σ, so within that of the spline
  const long nch = static_cast<long>(cp.size()) - 1;
  auto& cseg = cache.cseg;  // the chords and the bisectors at the chord points between them
  auto& cw = cache.cw;
  auto& crows = cache.crows;
  cseg.clear();
  cw.clear();
  for (long q = 0; q < nch; ++q) cseg.push_back(make_seg(cp[static_cast<std::size_t>(q)], cp[static_cast<std::size_t>(q) + 1]));
  for (long q = 0; q + 1 < nch; ++q) cw.push_back(bisector(cseg[static_cast<std::size_t>(q)], cseg[static_cast<std::size_t>(q) + 1]));
  crows.assign(cseg, cw);
  // the chords whose arc length along the polyline (through the parameter map) lies within ±w of the
  // piece's arc lengths [ua, ub], and two more each side; a chord outside the window can only make the
  // bound larger, never smaller
  const double w = 0.25 * mean + 4.0 * eps;
  auto cwindow = [&](double ua, double ub, long& lo, long& hi) {
    lo = std::max(0L, static_cast<long>(std::lower_bound(cu.begin(), cu.end(), ua - w) - cu.begin()) - 2);
    hi = std::min(nch - 1, static_cast<long>(std::upper_bound(cu.begin(), cu.end(), ub + w) - cu.begin()) + 1);
  };
  // Also `ends`: at most the bound of the degenerate pieces [q0, q0] and [q1, q1] (the square root of the
  // larger of the two smallest squared distances plus the smallest σ); above eps, every bisection of
  // the piece keeps a part whose bound is above eps, so the piece fails whatever it is cut into.
  // Q0, Q1: squared distances of q0, q1 to the chords lo..hi, filled on the way.
  auto& Q0 = cache.Q0;
  auto& Q1 = cache.Q1;
  auto poly_bound = [&](const V2& q0, const V2& q1, long lo, long hi, double& ends) {
    Q0.resize(static_cast<std::size_t>(hi - lo + 1));
    Q1.resize(static_cast<std::size_t>(hi - lo + 1));
    // the best single chord (the smallest over q of √max(d0, d1) + σ_q), the smallest squared
    // distances m0, m1 of q0 and of q1, and the smallest σ
    double mins[5];
    pair_window(q0, q1, crows, lo, hi, csag.data(), Q0.data(), Q1.data(), mins);
    double best = mins[3];
    const double m0 = mins[1], m1 = mins[2], smin = mins[4];
    ends = std::sqrt(std::max(m0, m1)) + smin;
    if (best > eps && ends <= eps)
      best = std::min(best, run_bound(q0, q1, crows, lo, hi, Q0.data(), Q1.data(), csag.data(), cache.run));
    return best;
  };
  struct Part {
    V2 a0, a1;
    double ua, ub;
  };
  std::vector<Part> pj;
  std::size_t wa = 0, wb = 0;  // cwindow's searches for the segments' nondecreasing arc lengths
  // does the parameter range [u0, u1] meet a span checked again?
  auto meets_fresh = [&](double u0, double u1) {
    const auto it = std::lower_bound(fresh.begin(), fresh.end(), u0,
                                     [](const std::pair<double, double>& f, double u) { return f.second < u; });
    return it != fresh.end() && it->first <= u1;
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    double& gb = cache.seg_bound[i];
    double& gu0 = cache.seg_u0[i];
    double& gu1 = cache.seg_u1[i];
    if (valid(gb) && !meets_fresh(gu0, gu1)) {
      bound = std::max(bound, gb);
      continue;
    }
    const double li = cum[i + 1] - cum[i];
    // the chords a window lo..hi holds span the parameters cpar[lo]..cpar[hi + 1]
    auto used = [&](long lo, long hi) {
      gu0 = std::min(gu0, cpar[static_cast<std::size_t>(lo)]);
      gu1 = std::max(gu1, cpar[static_cast<std::size_t>(hi) + 1]);
    };
    gu0 = 1e300;
    gu1 = -1e300;
    // the whole segment first
    {
      while (wa < cu.size() && cu[wa] < cum[i] - w) ++wa;
      while (wb < cu.size() && cu[wb] <= cum[i + 1] + w) ++wb;
      const long lo = std::max(0L, static_cast<long>(wa) - 2), hi = std::min(nch - 1, static_cast<long>(wb) + 1);
      used(lo, hi);
      double ends;
      const double b = poly_bound(pts[i], pts[i + 1], lo, hi, ends);
      if (b <= eps) {
        bound = std::max(bound, b);
        gb = b;
        continue;
      }
    }
    gb = 0;
    // else the segment is bisected while a part fails, each part [a0, a1] (arc lengths ua..ub) bounded
    // against the chords within ±w of it; the first part that fails decides. The budget is 64
    // bisections for each piece of half a chord the segment holds.
    const long c0 = std::clamp(static_cast<long>(std::upper_bound(cu.begin(), cu.end(), 0.5 * (cum[i] + cum[i + 1])) - cu.begin()) - 1, 0L, nch - 1);
    const double hc = (cp[static_cast<std::size_t>(c0) + 1] - cp[static_cast<std::size_t>(c0)]).norm();
    const int np = std::max(1, static_cast<int>(std::ceil(li / std::max(0.5 * hc, 0.25 * eps))));
    long budget = static_cast<long>(max_bisections) * np;
    const V2 pm = 0.5 * (pts[i] + pts[i + 1]);
    const double um = 0.5 * (cum[i] + cum[i + 1]);
    pj.assign({Part{pm, pts[i + 1], um, cum[i + 1]}, Part{pts[i], pm, cum[i], um}});
    while (!pj.empty()) {
      const Part pt = pj.back();
      pj.pop_back();
      long lo, hi;
      cwindow(pt.ua, pt.ub, lo, hi);
      used(lo, hi);
      double ends;
      const double b = poly_bound(pt.a0, pt.a1, lo, hi, ends);
      if (b > eps && ends <= eps && (pt.a1 - pt.a0).norm() > fine && --budget > 0) {
        const V2 am = 0.5 * (pt.a0 + pt.a1);
        const double uh = 0.5 * (pt.ua + pt.ub);
        pj.push_back(Part{am, pt.a1, uh, pt.ub});
        pj.push_back(Part{pt.a0, am, pt.ua, uh});
        continue;
      }
      bound = std::max(bound, b);
      gb = std::max(gb, b);
      if (b > eps) {  // the segment fails
        bad.push_back(0.5 * (pt.ua + pt.ub));
        break;
      }
    }
  }
  out.bound = bound;
  std::size_t pk = 0;  // the pieces' parameters are nondecreasing
  for (Piece& p : out.pieces) {
    p.ua = amap.walk(p.ua, pk);
    p.ub = amap.walk(p.ub, pk);
  }
  return true;
}

}  // namespace
}  // namespace netshape::motion
