#pragma once
// The tolerance-band smoothing stage's runs (private, included by smoothing.cpp only, so everything
// here has internal linkage): one run's spline fit pulled back into the tube until the check
// (smoothing_check.hpp) passes.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "netshape/core/types.hpp"
#include "netshape/motion/smoothing.hpp"
#include "netshape/toolpath/block.hpp"
#include "smoothing_check.hpp"
#include "smoothing_spline.hpp"

namespace netshape::motion {
namespace {

// Unit tangents a run's curve must start / end with (the direction of a line it continues), if any.
struct RunEnds {
  bool fix0 = false, fix1 = false;
  V2 d0 = V2::Zero(), d1 = V2::Zero();
};

constexpr double sharp_turn = 0.3;  // [rad] a vertex turning more gets dense knots and samples
constexpr int sharp_reach = 8;      // they reach ±2·sharp_reach fit tolerances from the vertex
constexpr int fit_reach = 6;        // a round solves the control points this many spans around raised samples

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
// curve is fitted again, so it is pulled back only where it has to be. The first fit is global; a later
// round solves only the control points within fit_reach spans of the samples whose weights rose, the
// others held (a block Gauss–Seidel sweep on the same normal equations: the spline's response to a
// weight decays along the curve), and moves only the samples on the spans it changed — a sample
// elsewhere keeps its foot point and its residual within the target. The sample parameters move to
// their foot points on the curve, so a residual is the distance of the sample from the curve. A sample still out after a few rounds gets a knot next to it (its knot span is halved,
// down to mean/16; the knot is inserted without changing the curve). When every residual is within
// 0.93 of the fit tolerance the arc chain is built and checked both ways with rigorous bounds, again
// only where the spline changed since the last check (CheckCache); where the check fails, the weights
// of the samples within one mean segment are raised, a failing place between samples gets a sample of
// its own, and the round repeats. False when the check still fails after max_refinements rounds.
bool fit_run(const std::vector<V2>& pts, const RunEnds& ends, double mean, const SmoothOptions& opt,
             RunFit& out) {
  const std::size_t n = pts.size();  // vertices
  std::vector<double> cum(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) cum[i] = cum[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double L = cum.back();
  std::vector<Seg> segs;  // the polyline's segments and the bisectors at its interior vertices
  std::vector<V2> wseg;
  for (std::size_t i = 0; i + 1 < n; ++i) segs.push_back(make_seg(pts[i], pts[i + 1]));
  for (std::size_t i = 0; i + 1 < segs.size(); ++i) wseg.push_back(bisector(segs[i], segs[i + 1]));
  SegTable srows;  // segs and wseg as rows
  srows.assign(segs, wseg);
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
  const double target = 0.93 * eps;
  Spline sp;
  sp.t.assign(4, 0.0);
  sp.t.insert(sp.t.end(), knots.begin(), knots.end());
  sp.t.insert(sp.t.end(), 4, L);
  sp.P.assign(knots.size() + 4, V2::Zero());
  const int nf = ends.fix0 ? 2 : 1, nk = ends.fix1 ? 2 : 1;  // control points held at each end
  // clamped cubic: s'(0) = 3 (P1 − P0) / t4 and s'(L) = 3 (P_{m−1} − P_{m−2}) / (L − t_{m−1});
  // a fixed end tangent fixes the second control point for unit speed
  auto hold_ends = [&] {
    const std::size_t m = sp.P.size();
    sp.P.front() = pts.front();
    sp.P.back() = pts.back();
    if (ends.fix0) sp.P[1] = pts.front() + (sp.t[4] / 3.0) * ends.d0;
    if (ends.fix1) sp.P[m - 2] = pts.back() - ((L - sp.t[m - 1]) / 3.0) * ends.d1;
  };
  hold_ends();
  const int m0 = static_cast<int>(sp.P.size());
  sp.pb.resize(sp.P.size());
  sp.power_basis(3, m0 - 1);
  std::vector<std::array<double, 4>> pen_band(sp.P.size());
  penalty_rows(sp, pen, pen_band, 0, m0 - 1);
  std::vector<int> span(samples.size());  // each sample's knot span
  // every sample's span; the samples' parameters (nearly) ascend, so each search starts at the previous
  // sample's span
  auto find_spans = [&] {
    int k = 3;
    for (std::size_t q = 0; q < samples.size(); ++q) k = span[q] = sp.span_near(samples[q].u, k);
  };
  find_spans();
  std::vector<char> raised(samples.size(), 1);  // weight raised since the last solve (all before the first)
  std::vector<char> changed;                    // per knot span: its polynomial changed in this round
  std::vector<char> hot;                        // per knot span: holds a sample whose weight rose
  std::vector<std::pair<int, int>> win;
  ParamMap amap;
  std::vector<double> bad, add;
  FitWork work;
  FootWork foot;
  CheckCache cache;  // the bounds of the last check, per knot span and per polyline segment
  cache.span_bound.assign(sp.P.size(), -1.0);
  cache.seg_bound.assign(n - 1, -1.0);
  cache.seg_u0.assign(n - 1, 0.0);
  cache.seg_u1.assign(n - 1, 0.0);
  for (int round = 0; round < opt.max_refinements; ++round) {
    // Solve the free control points within fit_reach spans of the samples whose weights rose (block
    // Gauss–Seidel on the normal equations: the others are held), windows closer than the band merged;
    // the first solve is global. (A run has at least 3 spans, so at least 2 free control points.)
    const int m = static_cast<int>(sp.P.size());
    win.clear();
    if (round == 0) {
      win.emplace_back(nf, m - nk - 1);
    } else {
      // the spans holding a raised sample, in order: their windows come out sorted (both ends grow with
      // the span), each once
      hot.assign(static_cast<std::size_t>(m), 0);
      for (std::size_t q = 0; q < samples.size(); ++q)
        if (raised[q]) hot[static_cast<std::size_t>(span[q])] = 1;
      for (int k = 0; k < m; ++k)
        if (hot[static_cast<std::size_t>(k)]) win.emplace_back(std::max(nf, k - 3 - fit_reach), std::min(m - nk - 1, k + fit_reach));
    }
    changed.assign(static_cast<std::size_t>(m), 0);
    for (std::size_t w = 0; w < win.size();) {
      auto [lo, hi] = win[w];
      for (++w; w < win.size() && win[w].first <= hi + 4; ++w) hi = std::max(hi, win[w].second);
      if (lo > hi) continue;
      if (!solve_window(samples, span, lo, hi, pen_band, sp, work)) return false;
      std::fill(changed.begin() + lo, changed.begin() + std::min(m, hi + 4), 1);
    }
    for (int k = 0; k < m; ++k)
      if (changed[static_cast<std::size_t>(k)]) cache.span_bound[static_cast<std::size_t>(k)] = -1.0;
    std::fill(raised.begin(), raised.end(), 0);
    bool over = false;
    add.clear();
    // A sample on a span the solve left alone keeps its foot point and residual (within the target).
    // The others move to their foot points by Newton steps on (s(u) − p)·s'(u) = 0, kept only where
    // they bring the curve closer (at most two steps, the second only after a step of at least 1e-9;
    // SmoothingKernels::foot_points, several samples at a time), in the order of the samples.
    foot.collect(samples, span, changed);
    foot.run(sp, L, mean);
    for (std::size_t i = 0; i < foot.q.size(); ++i) {
      const std::size_t q = foot.q[i];
      Sample& s = samples[q];
      s.u = foot.u[i];
      span[q] = foot.k[i];
      const double res = foot.res[i];
      if (res > target) {
        const double g = res / target;
        s.w *= std::clamp(1.2 * g * g, 1.2, 100.0);
        raised[q] = 1;
        over = true;
        // a sample that stays out of the tube for a few rounds gets a knot next to it: the spline's
        // curvature may then change there (the ∫|s''|² penalty keeps the added freedom smooth)
        if (round % 4 == 3) add.push_back(s.u);
      }
    }
    if (!over) {
      amap.build(samples, L);
      if (!chain_check(sp, pts, srows, cum, amap, eps, mean, cache, out, bad)) return false;
      if (bad.empty()) return true;
      std::sort(bad.begin(), bad.end());
      for (std::size_t q = 0; q < samples.size(); ++q) {
        Sample& s = samples[q];
        const auto it = std::lower_bound(bad.begin(), bad.end(), s.a - mean);
        if (it != bad.end() && *it <= s.a + mean) {
          s.w *= 4.0;
          raised[q] = 1;
        }
      }
      // A failing place between two samples more than mean/16 from both gets a sample of its own (the
      // polyline point there, weighted as the heavier neighbour, its parameter interpolated between
      // theirs): the curve may leave the tube between samples however heavy they are.
      for (const double b : bad) {
        const auto it = std::lower_bound(samples.begin(), samples.end(), b,
                                         [](const Sample& x, double v) { return x.a < v; });
        if (it == samples.begin() || it == samples.end()) continue;
        const Sample &s0 = *(it - 1), &s1 = *it;
        if (b - s0.a < mean / 16.0 || s1.a - b < mean / 16.0) continue;
        const std::size_t i = std::min(static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), b) - cum.begin()) - 1, n - 2);
        const double f = std::clamp((b - cum[i]) / (cum[i + 1] - cum[i]), 0.0, 1.0);
        const double u = s0.u + (b - s0.a) / (s1.a - s0.a) * (s1.u - s0.u);
        const auto q = it - samples.begin();
        samples.insert(it, Sample{u, V2(pts[i] + f * (pts[i + 1] - pts[i])), std::max(s0.w, s1.w), b});
        span.insert(span.begin() + q, sp.span(u));
        raised.insert(raised.begin() + q, 1);
      }
    }
    if (!add.empty()) {  // split the knot spans that hold the samples, down to 1/16 of the mean segment
      std::vector<double> mids;
      for (double u : add) {
        const auto k = static_cast<std::size_t>(sp.span(u));
        if (sp.t[k + 1] - sp.t[k] > std::min(mean / 16.0, 0.5 * eps)) mids.push_back(0.5 * (sp.t[k] + sp.t[k + 1]));
      }
      std::sort(mids.begin(), mids.end());
      mids.erase(std::unique(mids.begin(), mids.end()), mids.end());
      if (!mids.empty()) {  // the same curve on the finer knots; the raised samples' windows reach the new knots
        const std::vector<double> t0 = sp.t;
        for (const double x : mids) sp.insert_knot(x);
        hold_ends();  // as the insertions left them, up to rounding
        // A span or penalty row k no new knot reaches moves to k + (the new knots below t0[k]); the
        // others are rebuilt below, and the split spans' two halves are checked again.
        auto remap = [&](auto& v, const auto& blank) {
          auto old = std::move(v);
          v.assign(sp.P.size(), blank);
          std::size_t c = 0;
          for (std::size_t k = 0; k < old.size(); ++k) {
            while (c < mids.size() && mids[c] < t0[k]) ++c;
            v[k + c] = old[k];
          }
        };
        remap(sp.pb, std::array<double, 16>{});
        remap(sp.pw, std::array<V2, 4>{});
        remap(pen_band, std::array<double, 4>{});
        remap(cache.span_bound, -1.0);
        // the basis and the pieces of the spans a new knot reaches (knot j: spans j − 4..j + 3) and of
        // the end spans, then the penalty rows that sum them
        const int m1 = static_cast<int>(sp.P.size());
        changed.assign(static_cast<std::size_t>(m1), 0);
        auto touch = [&](int k0, int k1) {
          std::fill(changed.begin() + std::max(k0, 3), changed.begin() + std::min(k1, m1 - 1) + 1, 1);
        };
        for (const double x : mids) {
          const int j = static_cast<int>(std::lower_bound(sp.t.begin(), sp.t.end(), x) - sp.t.begin());
          touch(j - 4, j + 3);
          cache.span_bound[static_cast<std::size_t>(j - 1)] = -1.0;
          cache.span_bound[static_cast<std::size_t>(j)] = -1.0;
        }
        touch(3, 4);
        touch(m1 - 2, m1 - 1);
        for (int pass = 0; pass < 2; ++pass)  // every span's basis first: a penalty row sums four spans
          for (int k0 = 3; k0 < m1;) {
            if (!changed[static_cast<std::size_t>(k0)]) {
              ++k0;
              continue;
            }
            int k1 = k0;
            while (k1 + 1 < m1 && changed[static_cast<std::size_t>(k1 + 1)]) ++k1;
            if (pass == 0) {
              sp.power_basis(k0, k1);
              sp.prepare(k0, k1);
            } else {
              penalty_rows(sp, pen, pen_band, k0 - 3, k1);
            }
            k0 = k1 + 1;
          }
        find_spans();
      }
    }
  }
  return false;
}

double turn_between(const Vec3& u1, const Vec3& u2) {
  return std::atan2(u1.cross(u2).norm(), u1.dot(u2));
}

}  // namespace
}  // namespace netshape::motion
