// Arcs of the Z-map sweep in the XY plane with a constant radius (planar or helical): per node the
// lowest reach over the arc's angle (closed form, or a bracketed golden-section search for helical
// ball and bull-nose arcs). Other arcs are swept as chords by sweep_block (sweep.cpp).
#include <algorithm>
#include <cmath>

#include "stock/sweep_internal.hpp"

namespace netshape::stock::detail {
namespace {

// golden-section minimum of f on [a, b] (f unimodal there)
template <class F>
double golden_min(F&& f, double a, double b, double& fbest) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int it = 0; it < 200 && b - a > angle_tol; ++it) {
    if (fc <= fd) {
      b = d; d = c; fd = fc; c = b - g * (b - a); fc = f(c);
    } else {
      a = c; c = d; fc = fd; d = a + g * (b - a); fd = f(d);
    }
  }
  const double x = 0.5 * (a + b);
  fbest = f(x);
  return x;
}

template <int Kind>
double reach_arc(const ArcSetup& s, const TipProfile& p, double x, double y) noexcept {
  const double R = p.radius;
  const double qx = x - s.cx, qy = y - s.cy;
  const double rho = std::hypot(qx, qy);
  if (std::abs(rho - s.r) > R) return inf;
  const bool planar = s.kz == 0.0;
  // node at the centre: distance to the axis is r for every angle
  if (rho <= 1e-12) {
    if (s.r > R) return inf;
    return s.z0 + std::min(0.0, s.kz * s.total) + (Kind == kFlat ? 0.0 : lift_c(p, s.r));
  }
  const double c = (rho * rho + s.r * s.r - R * R) / (2.0 * rho * s.r);
  if (c > 1.0) return inf;
  const double alpha = c <= -1.0 ? pi : std::acos(c);
  double d0 = s.sgn * (std::atan2(qy, qx) - s.th0);
  d0 = std::fmod(d0, two_pi);
  if (d0 < 0) d0 += two_pi;
  const int k_lo = static_cast<int>(std::ceil((-alpha - d0) / two_pi));
  const int k_hi = static_cast<int>(std::floor((s.total + alpha - d0) / two_pi));
  auto dist_at = [&](double delta) {
    const double d2 = rho * rho + s.r * s.r - 2.0 * rho * s.r * std::cos(delta);
    return std::sqrt(d2 > 0.0 ? d2 : 0.0);
  };
  double best = inf;
  for (int k = k_lo; k <= k_hi; ++k) {
    const double psi_k = d0 + two_pi * k;
    const double lo = std::max(0.0, psi_k - alpha);
    const double hi = std::min(s.total, psi_k + alpha);
    if (lo > hi) continue;
    if (planar) {
      const double delta = std::clamp(psi_k, lo, hi) - psi_k;
      const double z = s.z0 + (Kind == kFlat ? 0.0 : lift_c(p, dist_at(delta)));
      best = std::min(best, z);
      continue;
    }
    if (Kind == kFlat) {
      const double psi = s.kz > 0.0 ? lo : hi;
      best = std::min(best, s.z0 + s.kz * psi);
      continue;
    }
    // helical ball / bull: F(ψ) = z0 + kz·ψ + g(d(ψ − ψ_k)); g∘d is even in ψ − ψ_k and grows with
    // |ψ − ψ_k|, so the minimum lies on the side of ψ_k against the climb.
    double a = lo, b = hi;
    if (s.kz > 0.0) {
      if (a >= psi_k) { best = std::min(best, s.z0 + s.kz * a + lift_c(p, dist_at(a - psi_k))); continue; }
      b = std::min(b, psi_k);
    } else {
      if (b <= psi_k) { best = std::min(best, s.z0 + s.kz * b + lift_c(p, dist_at(b - psi_k))); continue; }
      a = std::max(a, psi_k);
    }
    auto f = [&](double psi) { return s.z0 + s.kz * psi + lift_c(p, dist_at(psi - psi_k)); };
    constexpr int n = 24;
    int ib = 0;
    double fb = inf;
    for (int t = 0; t <= n; ++t) {
      const double v = f(a + (b - a) * t / n);
      if (v < fb) { fb = v; ib = t; }
    }
    const double ga = a + (b - a) * std::max(ib - 1, 0) / n;
    const double gb = a + (b - a) * std::min(ib + 1, n) / n;
    double fg;
    golden_min(f, ga, gb, fg);
    best = std::min(best, std::min(fb, fg));
  }
  return best;
}

template <int Kind>
void sweep_arc_k(ZMap& zm, const TipProfile& p, const ArcSetup& s, SweepStats& st) {
  const double R = p.radius;
  // bounding box of the axis path
  double xlo, xhi, ylo, yhi;
  if (s.total >= two_pi) {
    xlo = s.cx - s.r; xhi = s.cx + s.r; ylo = s.cy - s.r; yhi = s.cy + s.r;
  } else {
    const double th1 = s.th0 + s.sgn * s.total;
    xlo = std::min(std::cos(s.th0), std::cos(th1));
    xhi = std::max(std::cos(s.th0), std::cos(th1));
    ylo = std::min(std::sin(s.th0), std::sin(th1));
    yhi = std::max(std::sin(s.th0), std::sin(th1));
    for (int q = -8; q <= 8; ++q) {  // cardinal angles passed on the way
      const double ang = q * 0.5 * pi;
      double rel = s.sgn * (ang - s.th0);
      if (rel >= 0.0 && rel <= s.total) {
        xlo = std::min(xlo, std::cos(ang)); xhi = std::max(xhi, std::cos(ang));
        ylo = std::min(ylo, std::sin(ang)); yhi = std::max(yhi, std::sin(ang));
      }
    }
    xlo = s.cx + s.r * xlo; xhi = s.cx + s.r * xhi; ylo = s.cy + s.r * ylo; yhi = s.cy + s.r * yhi;
  }
  int i0, i1, j0, j1;
  if (!node_range(ylo - R, yhi + R, zm.y0(), zm.dy(), zm.ny(), i0, i1)) return;
  if (!node_range(xlo - R, xhi + R, zm.x0(), zm.dx(), zm.nx(), j0, j1)) return;
  // quick reject: the tip z is linear in the angle, lowest at an end
  if (SweepAccess::above(zm, i0, i1, std::min(s.z0, s.z0 + s.kz * s.total), j1 - j0 + 1.0)) return;
  MatrixXdR& H = SweepAccess::heights(zm);
  const double bottom = zm.bottom();
  for (int i = i0; i <= i1; ++i) {
    const double y = zm.node_y(i);
    double* row = H.data() + static_cast<Eigen::Index>(i) * zm.nx();
    st.nodes_visited += j1 - j0 + 1;
    for (int j = j0; j <= j1; ++j) lower(row[j], reach_arc<Kind>(s, p, zm.node_x(j), y), bottom, st);
  }
}

}  // namespace

void sweep_arc(ZMap& zm, const TipProfile& p, ProfileKind kind, const ArcSetup& s, SweepStats& st) {
  switch (kind) {
    case kFlat: sweep_arc_k<kFlat>(zm, p, s, st); break;
    case kBall: sweep_arc_k<kBall>(zm, p, s, st); break;
    case kBull: sweep_arc_k<kBull>(zm, p, s, st); break;
  }
}

}  // namespace netshape::stock::detail
