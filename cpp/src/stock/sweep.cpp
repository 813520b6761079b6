#include "netshape/stock/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#include <immintrin.h>
#endif

#include "netshape/core/error.hpp"

namespace netshape::stock {

/// Quick reject: a move is skipped when the band bounds of its rows are at least this far below the
/// lowest point its tip reaches [mm] (covers the rounding of the per-node z, ~1e-14 relative).
constexpr double kRejectMargin = 1e-9;
/// A band whose bound is above a move is recomputed exactly once the sweeps since its last exact
/// bound have booked at least this many times its node count (amortised: at most one read of a
/// height per 4 nodes of sweep work).
constexpr double kRefreshWork = 4.0;

/// The sweeps' access to a Z-map (a friend of ZMap): the heights without marking the bounds stale,
/// and the quick reject.
struct SweepAccess {
  static MatrixXdR& heights(ZMap& z) noexcept { return z.heights_; }

  /// True if every height of rows i0 … i1 is at least kRejectMargin below zlow [mm]: a move whose
  /// cutter never reaches below zlow lowers nothing there. Bands whose bound is above are
  /// recomputed when their booked work allows (above); when false, `width` nodes per row are booked
  /// on every band of the rows (the move is swept there).
  static bool above(ZMap& z, int i0, int i1, double zlow, double width) {
    if (z.bounds_stale_) z.init_bounds();
    const double lim = zlow - kRejectMargin;
    const int br = z.band_rows_, b0 = i0 / br, b1 = i1 / br;
    const double band_nodes = static_cast<double>(br) * z.nx_;
    bool ok = true;
    for (int b = b0; b <= b1; ++b) {
      const auto k = static_cast<std::size_t>(b);
      if (z.band_max_[k] <= lim) continue;
      if (static_cast<double>(z.band_work_[k]) >= kRefreshWork * band_nodes) {
        z.refresh_band(b);
        if (z.band_max_[k] <= lim) continue;
      }
      ok = false;
      break;
    }
    if (ok) return true;
    const auto w = static_cast<std::int64_t>(width * br) + 1;
    for (int b = b0; b <= b1; ++b) z.band_work_[static_cast<std::size_t>(b)] += w;
    return false;
  }
};

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double two_pi = 2.0 * pi;
/// Horizontal move length below which a line is treated as vertical (plunge) [mm].
constexpr double vertical_eps = 1e-9;
/// Tolerance of the 1-D minimisations: [mm] along lines, [rad] along arcs.
constexpr double line_tol = 1e-10;
constexpr double angle_tol = 1e-10;
/// Newton steps shorter than this end the bull-nose ramp search [mm]; the next step would be far
/// shorter still (quadratic convergence), and F is flat at its minimum.
constexpr double newton_tol = 1e-9;

enum ProfileKind { kFlat = 0, kBall = 1, kBull = 2 };

ProfileKind kind_of(const cutter::Cutter& c) {
  switch (c.kind) {
    case cutter::CutterKind::ball: return kBall;
    case cutter::CutterKind::bull: return kBull;
    case cutter::CutterKind::flat:
    default: return kFlat;
  }
}

// lift with d clamped to R (rounding at the edge of the footprint must not give +inf)
inline double lift_c(const TipProfile& p, double d) noexcept { return p.lift(std::min(d, p.radius)); }

// ---------------------------------------------------------------------------------------------
// Lines
// ---------------------------------------------------------------------------------------------
struct LineSetup {
  double ax = 0, ay = 0, az = 0;  // start of the tip path [mm]
  double ex = 1, ey = 0;          // unit horizontal direction
  double len = 0;                 // horizontal length [mm]
  double m = 0;                   // dz per mm of horizontal travel
  double kball = 0;               // m / sqrt(1 + m²)
  double zv = 0;                  // vertical moves: min(A_z, B_z)
  bool vertical = false;
};

LineSetup make_line(const Vec3& a, const Vec3& b) {
  LineSetup s;
  s.ax = a.x();
  s.ay = a.y();
  s.az = a.z();
  const double hx = b.x() - a.x(), hy = b.y() - a.y();
  s.len = std::hypot(hx, hy);
  if (s.len <= vertical_eps) {
    s.vertical = true;
    s.zv = std::min(a.z(), b.z());
    s.len = 0.0;
    return s;
  }
  s.ex = hx / s.len;
  s.ey = hy / s.len;
  s.m = (b.z() - a.z()) / s.len;
  s.kball = s.m / std::sqrt(1.0 + s.m * s.m);
  return s;
}

// Bull-nose ramp: minimise F(σ) = m·σ + g(sqrt(sp² + (σ − tq)²)) on [lo, hi]. F is convex, so its
// derivative is non-decreasing: find its root by Newton's method kept inside a shrinking bracket
// (bisection whenever a Newton step would leave it); ends when the bracket is below 1e-10 mm or a
// Newton step below 1e-9 mm (F is flat at its minimum, so the height error is far smaller).
double bull_ramp_min(const TipProfile& p, double m, double sp2, double tq, double lo, double hi) noexcept {
  const double a0 = p.flat_radius, rc = p.corner_radius;
  auto dfdx = [&](double sig, double* d2f) {
    const double u = sig - tq;
    const double d = std::sqrt(sp2 + u * u);
    const double e = d - a0;
    if (e <= 0.0) {  // flat zone
      if (d2f) *d2f = 0.0;
      return m;
    }
    const double w = rc * rc - e * e;
    if (w <= 0.0) return u > 0 ? inf : (u < 0 ? -inf : m);
    const double sw = std::sqrt(w);
    const double g1 = e / sw;                    // g'(d)
    if (d2f) {
      const double g2 = rc * rc / (w * sw);      // g''(d)
      *d2f = g2 * u * u / (d * d) + g1 * sp2 / (d * d * d);
    }
    return m + g1 * u / d;
  };
  double sig;
  const double flo = dfdx(lo, nullptr), fhi = dfdx(hi, nullptr);
  if (flo >= 0.0) {
    sig = lo;
  } else if (fhi <= 0.0) {
    sig = hi;
  } else {
    double a = lo, b = hi;
    // start where the torus begins on the side the slope pushes to (F' = m < 0 in the flat zone
    // means the root lies ahead, u > 0)
    const double ua = std::sqrt(std::max(a0 * a0 - sp2, 0.0));
    double x = std::clamp(tq + (m < 0.0 ? ua : -ua), a, b);
    for (int it = 0; it < 100; ++it) {
      double d2f = 0.0;
      const double fx = dfdx(x, &d2f);
      if (fx == 0.0) { a = b = x; break; }
      if (fx < 0.0) a = x; else b = x;
      if (b - a <= line_tol) break;
      double xn = d2f > 0.0 ? x - fx / d2f : 0.5 * (a + b);
      if (!(xn > a && xn < b)) xn = 0.5 * (a + b);
      if (std::abs(xn - x) <= newton_tol) { a = b = xn; break; }
      x = xn;
    }
    sig = 0.5 * (a + b);
  }
  const double u = sig - tq;
  return m * sig + lift_c(p, std::sqrt(sp2 + u * u));
}

template <int Kind>
inline double reach_line(const LineSetup& s, const TipProfile& p, double r2, double x, double y) noexcept {
  const double qx = x - s.ax, qy = y - s.ay;
  if (s.vertical) {
    const double d2 = qx * qx + qy * qy;
    if (d2 > r2) return inf;
    if (Kind == kFlat) return s.zv;
    return s.zv + lift_c(p, std::sqrt(d2));
  }
  const double tq = qx * s.ex + qy * s.ey;  // foot point of the node along the move [mm]
  const double sp = qy * s.ex - qx * s.ey;  // signed distance of the node from the line [mm]
  const double rho2 = r2 - sp * sp;
  if (rho2 < 0.0) return inf;
  const double rho = std::sqrt(rho2);
  const double lo = std::max(0.0, tq - rho);
  const double hi = std::min(s.len, tq + rho);
  if (lo > hi) return inf;
  if (Kind == kFlat) return s.az + s.m * (s.m >= 0.0 ? lo : hi);
  if (Kind == kBall) {
    const double sig = std::clamp(tq - s.kball * rho, lo, hi);
    const double u = sig - tq;
    const double w = rho2 - u * u;
    return s.az + s.m * sig + p.radius - std::sqrt(w > 0.0 ? w : 0.0);
  }
  // bull
  if (s.m == 0.0) {
    const double u = std::clamp(tq, lo, hi) - tq;
    return s.az + lift_c(p, std::sqrt(sp * sp + u * u));
  }
  return s.az + bull_ramp_min(p, s.m, sp * sp, tq, lo, hi);
}

// X range of row y covered by the stadium of radius R around the horizontal segment; false if none.
bool row_range(const LineSetup& s, double r, double y, double& xlo, double& xhi) noexcept {
  xlo = inf;
  xhi = -inf;
  auto disc = [&](double cx, double cy) {
    const double dy = y - cy;
    const double w = r * r - dy * dy;
    if (w < 0.0) return;
    const double h = std::sqrt(w);
    xlo = std::min(xlo, cx - h);
    xhi = std::max(xhi, cx + h);
  };
  disc(s.ax, s.ay);
  if (s.vertical) return xlo <= xhi;
  disc(s.ax + s.len * s.ex, s.ay + s.len * s.ey);
  // strip: |(y − ay)·ex − (x − ax)·ey| ≤ R and 0 ≤ (x − ax)·ex + (y − ay)·ey ≤ len
  double lo = -inf, hi = inf;
  auto constrain = [&](double coef, double off, double vmin, double vmax) {
    // vmin ≤ coef·x + off ≤ vmax
    if (std::abs(coef) < 1e-15) {
      if (off < vmin || off > vmax) { lo = inf; hi = -inf; }
      return;
    }
    double a = (vmin - off) / coef, b = (vmax - off) / coef;
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  };
  const double yy = y - s.ay;
  constrain(-s.ey, yy * s.ex + s.ey * s.ax, -r, r);
  constrain(s.ex, yy * s.ey - s.ex * s.ax, 0.0, s.len);
  if (lo <= hi) {
    xlo = std::min(xlo, lo);
    xhi = std::max(xhi, hi);
  }
  return xlo <= xhi;
}

// index range of nodes with centre in [lo, hi] along an axis with origin o, cell size h, n nodes
inline bool node_range(double lo, double hi, double o, double h, int n, int& k0, int& k1) noexcept {
  double a = std::ceil((lo - o) / h - 0.5 - 1e-9);
  double b = std::floor((hi - o) / h - 0.5 + 1e-9);
  a = std::max(a, 0.0);
  b = std::min(b, static_cast<double>(n - 1));
  if (!(a <= b)) return false;
  k0 = static_cast<int>(a);
  k1 = static_cast<int>(b);
  return true;
}

inline void lower(double& h, double z, double bottom, SweepStats& st) noexcept {
  if (z < h) {
    const double nz = z > bottom ? z : bottom;
    if (nz < h) {
      st.removed_volume += h - nz;  // scaled by the cell area at the end
      ++st.nodes_lowered;
      h = nz;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Row kernels. One grid row at a time over the contiguous nodes j0 … j0 + n − 1 the stadium of the
// move covers: plain loops with every per-row constant hoisted and only selects inside, which the
// compiler turns into SIMD code (`#pragma omp simd`, enabled by -fopenmp-simd for this file; no
// OpenMP runtime). With GCC on x86-64 each kernel is also compiled for AVX2 and AVX-512 and the
// best one the CPU has is chosen at load time (target_clones), so the wheel stays portable.
// Node coordinates are computed exactly as ZMap::node_x does and the per-node arithmetic follows
// the same order as netshape.stock.reference, so flat and ball heights match it bit for bit.
// ---------------------------------------------------------------------------------------------
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(NETSHAPE_NO_TARGET_CLONES)
#define NETSHAPE_SIMD_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define NETSHAPE_SIMD_CLONES
#endif
#if defined(_OPENMP) || defined(__GNUC__)
#define NETSHAPE_PRAGMA(x) _Pragma(#x)
#else
#define NETSHAPE_PRAGMA(x)
#endif
#if defined(__GNUC__)
#define NETSHAPE_ALWAYS_INLINE_LAMBDA __attribute__((always_inline))
#define NETSHAPE_INLINE inline __attribute__((always_inline))
#else
#define NETSHAPE_ALWAYS_INLINE_LAMBDA
#define NETSHAPE_INLINE inline
#endif

/// One row of nodes: node k sits at x = x0 + (jb + k)·dx (jb = j0 + ½), y; h points at node j0.
struct Row {
  double x0 = 0, dx = 1, jb = 0.5;  // grid X origin [mm], cell size [mm], j0 + ½
  double qy = 0;                    // node y − A_y [mm]
  int n = 0;                        // nodes in the row segment
};

/// Accumulated effect of the row kernels.
struct RowOut {
  double vol = 0.0;         // removed height summed over nodes [mm] (× cell area later)
  std::int64_t lowered = 0;  // nodes whose height went down
};


// Nodes are taken in blocks of kBlock. A block is skipped when no node of it can be lowered: every
// height is at least kSkipMargin below a cheap lower bound of the cutter there (no square root:
// the tip's lowest point over the node's feasible travel from ρ ≤ R, plus a lower bound of the lift
// from the node's distance to the line, g(d) ≥ (d − a)²/(2 r_c)). Exact — a skipped node would
// not have changed — and frequent when moves re-cut material (the margin covers rounding).
constexpr int kBlock = 32;
constexpr double kSkipMargin = 1e-9;

// The row loop: node(k, ok) gives the lowest reach z at node k (ok: the cutter covers it),
// bound(k) a lower bound of it. h = min(h, max(z, bottom)) where ok.
template <class Node, class Bound>
NETSHAPE_INLINE void row_blocks(int n, double* __restrict h, double bottom, const Node& node, const Bound& bound,
                                RowOut& out) {
  double vol = 0.0;
  int cnt = 0;  // an int reduction vectorises (a 64-bit one does not, GCC 12)
  for (int b0 = 0; b0 < n; b0 += kBlock) {
    const int b1 = b0 + kBlock < n ? b0 + kBlock : n;
    double gap = -inf;
    NETSHAPE_PRAGMA(omp simd reduction(max : gap))
    for (int k = b0; k < b1; ++k) {
      const double g = h[k] - bound(k);
      gap = g > gap ? g : gap;
    }
    if (gap <= -kSkipMargin) continue;
    NETSHAPE_PRAGMA(omp simd reduction(+ : vol, cnt))
    for (int k = b0; k < b1; ++k) {
      bool ok;
      const double z = node(k, ok);
      const double hk = h[k];
      const double zb = z > bottom ? z : bottom;
      const double nh = (ok & (zb < hk)) ? zb : hk;
      vol += hk - nh;
      cnt += nh < hk;
      h[k] = nh;
    }
  }
  out.vol += vol;
  out.lowered += cnt;
}

// per-row constants of a line
struct LineRow {
  double ax, az, ex, ey, len, x0, dx, jb, qy;
  LineRow(const LineSetup& s, const Row& row)
      : ax(s.ax), az(s.az), ex(s.ex), ey(s.ey), len(s.len), x0(row.x0), dx(row.dx), jb(row.jb), qy(row.qy) {}
  // node k relative to the start: foot point along the move and signed distance from it [mm]
  NETSHAPE_INLINE void at(int k, double& tq, double& sp) const {
    const double qx = (x0 + (jb + k) * dx) - ax;
    tq = qx * ex + qy * ey;
    sp = qy * ex - qx * ey;
  }
};

// lift lower bound from a lower bound dmin of the distance to the axis: (dmin − a)²/(2 r_c), ≥ 0
NETSHAPE_INLINE double lift_bound(double dmin, double a0, double half_inv_rc) {
  const double e = dmin - a0 > 0.0 ? dmin - a0 : 0.0;
  return e * e * half_inv_rc;
}

// level line (m = 0): the point of the segment nearest to the node, d² = s² + u² (bull-nose only; flat
// and ball level lines go to level_move in ramp_kernel.inc)
NETSHAPE_SIMD_CLONES void row_bull_level(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                         double bottom, double* __restrict h, RowOut& out) {
  const LineRow L(s, row);
  const double R = p.radius, rc = p.corner_radius, fr = p.flat_radius, rc2 = rc * rc;
  const double half_inv_rc = rc > 0.0 ? 0.5 / rc : 0.0;
  // nearest point of the segment: u = τ_q − clamp(τ_q, 0, L)
  auto near = [&](int k, double& sp, double& u) NETSHAPE_ALWAYS_INLINE_LAMBDA {
    double tq;
    L.at(k, tq, sp);
    const double c = tq > 0.0 ? (tq < L.len ? tq : L.len) : 0.0;
    u = tq - c;
  };
  auto bound = [&](int k) NETSHAPE_ALWAYS_INLINE_LAMBDA {
    double sp, u;
    near(k, sp, u);
    const double as = sp < 0.0 ? -sp : sp, au = u < 0.0 ? -u : u;
    return L.az + lift_bound(as > au ? as : au, fr, half_inv_rc);
  };
  auto node = [&](int k, bool& ok) NETSHAPE_ALWAYS_INLINE_LAMBDA {
    double sp, u;
    near(k, sp, u);
    const double d2 = sp * sp + u * u;
    const double d = std::sqrt(d2);
    const double e = (d < R ? d : R) - fr;
    const double w = rc2 - e * e;
    ok = d2 <= r2;
    return L.az + (e > 0.0 ? rc - std::sqrt(w > 0.0 ? w : 0.0) : 0.0);
  };
  row_blocks(row.n, h, bottom, node, bound, out);
}

// vertical move (plunge), any cutter: min(A_z, B_z) + g(d)
NETSHAPE_SIMD_CLONES void row_vertical(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                       double bottom, double* __restrict h, RowOut& out) {
  const double ax = s.ax, zv = s.zv;
  const double R = p.radius, rc = p.corner_radius, fr = p.flat_radius, rc2 = rc * rc;
  const double x0 = row.x0, dx = row.dx, jb = row.jb, qy = row.qy;
  auto node = [&](int k, bool& ok) NETSHAPE_ALWAYS_INLINE_LAMBDA {
    const double qx = (x0 + (jb + k) * dx) - ax;
    const double d2 = qx * qx + qy * qy;
    const double d = std::sqrt(d2);
    const double e = (d < R ? d : R) - fr;
    const double w = rc2 - e * e;
    ok = d2 <= r2;
    return zv + (e > 0.0 ? rc - std::sqrt(w > 0.0 ? w : 0.0) : 0.0);
  };
  auto bound = [&](int) NETSHAPE_ALWAYS_INLINE_LAMBDA { return zv; };
  row_blocks(row.n, h, bottom, node, bound, out);
}

// Bull-nose ramps. F(σ) = m·σ + g(sqrt(sp² + (σ − τ_q)²)) is convex on [lo, hi]; its minimum is
// where F' changes sign, found per node by Newton steps kept inside a bisection bracket — the same
// iteration as bull_ramp_min, run on many nodes at once: every lane takes one step per pass, lanes
// that have converged keep their result, and the pass repeats while any lane is still running
// (finished lanes are squeezed out when they are many). Nodes whose height is already at or below
// the lowest the tip itself gets over the node's interval (A_z + m·lo, or m·hi going down) cannot
// be lowered (the lift is ≥ 0) and are skipped before any iteration: exact, and common when a
// program re-cuts.
constexpr int kBullChunk = 256;

struct BullLanes {
  double tq[kBullChunk], sp2[kBullChunk], lo[kBullChunk], hi[kBullChunk];
  double a[kBullChunk], b[kBullChunk], x[kBullChunk], sig[kBullChunk];
  int node[kBullChunk];
  unsigned char done[kBullChunk];
};

// F'(σ) and F''(σ) of the bull ramp (F'' = 0 where F' is ±inf or in the flat zone)
inline void bull_derivs(double sig, double tq, double sp2, double m, double a0, double rc2, double& f,
                        double& f2) {
  const double u = sig - tq;
  const double dd = sp2 + u * u;
  const double d = std::sqrt(dd);
  const double e = d - a0;
  const double w = rc2 - e * e;
  const double sw = std::sqrt(w > 0.0 ? w : 1.0);
  const double g1 = e / sw;
  const double g2 = rc2 / (w * sw);
  const double dsafe = d > 0.0 ? d : 1.0;
  const double fin = m + g1 * u / dsafe;
  const double s2 = g2 * u * u / (dsafe * dsafe) + g1 * sp2 / (dsafe * dsafe * dsafe);
  const double finf = u > 0.0 ? inf : (u < 0.0 ? -inf : m);
  const bool flat = e <= 0.0, edge = w <= 0.0;
  f = flat ? m : (edge ? finf : fin);
  f2 = flat ? 0.0 : (edge ? 0.0 : s2);
}

NETSHAPE_SIMD_CLONES void row_bull_ramp(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                        double bottom, double* __restrict h, RowOut& out, BullLanes& L) {
  const double ax = s.ax, az = s.az, ex = s.ex, ey = s.ey, len = s.len, m = s.m;
  const bool up = m >= 0.0;
  const double a0 = p.flat_radius, rc = p.corner_radius, rc2 = rc * rc, R = p.radius;
  const double half_inv_rc = 0.5 / rc;
  const double x0 = row.x0, dx = row.dx, jb = row.jb, qy = row.qy;
  double vol = 0.0;
  std::int64_t cnt = 0;
  for (int c0 = 0; c0 < row.n; c0 += kBullChunk) {
    const int n = std::min(kBullChunk, row.n - c0);
    double* hc = h + c0;
    // 1. per node: interval, skip test; the nodes left are packed into the lanes
    int nl = 0;
    for (int k = 0; k < n; ++k) {
      const double qx = (x0 + (jb + (c0 + k)) * dx) - ax;
      const double tq = qx * ex + qy * ey;
      const double sp = qy * ex - qx * ey;
      const double rho2 = r2 - sp * sp;
      const double rho = std::sqrt(rho2 > 0.0 ? rho2 : 0.0);
      const double tlo = tq - rho, thi = tq + rho;
      const double lo = tlo > 0.0 ? tlo : 0.0;
      const double hi = thi < len ? thi : len;
      const bool ok = (rho2 >= 0.0) & (lo <= hi);
      const double asp = sp < 0.0 ? -sp : sp;
      const double zmin = az + m * (up ? lo : hi) + lift_bound(asp, a0, half_inv_rc);
      L.tq[nl] = tq;
      L.sp2[nl] = sp * sp;
      L.lo[nl] = lo;
      L.hi[nl] = hi;
      L.node[nl] = k;
      nl += (ok && hc[k] > zmin - kSkipMargin) ? 1 : 0;
    }
    if (nl == 0) continue;
    // 2. ends of the interval, Newton start
    NETSHAPE_PRAGMA(omp simd)
    for (int l = 0; l < nl; ++l) {
      double flo, fhi, f2;
      bull_derivs(L.lo[l], L.tq[l], L.sp2[l], m, a0, rc2, flo, f2);
      bull_derivs(L.hi[l], L.tq[l], L.sp2[l], m, a0, rc2, fhi, f2);
      const double ua2 = a0 * a0 - L.sp2[l];
      const double ua = std::sqrt(ua2 > 0.0 ? ua2 : 0.0);
      double x0l = L.tq[l] + (up ? -ua : ua);
      x0l = x0l < L.lo[l] ? L.lo[l] : (L.hi[l] < x0l ? L.hi[l] : x0l);
      const bool at_lo = flo >= 0.0, at_hi = !at_lo && fhi <= 0.0;
      L.sig[l] = at_lo ? L.lo[l] : L.hi[l];
      L.done[l] = (at_lo || at_hi) ? 1 : 0;
      L.a[l] = L.lo[l];
      L.b[l] = L.hi[l];
      L.x[l] = x0l;
    }
    // 3. bracketed Newton, all lanes at once
    int live = nl;  // lanes [0, live) may still run; sig of finished lanes is final
    for (int it = 0; it < 100 && live > 0; ++it) {
      int running = 0;
      NETSHAPE_PRAGMA(omp simd reduction(+ : running))
      for (int l = 0; l < live; ++l) {
        const double x = L.x[l];
        double fx, f2;
        bull_derivs(x, L.tq[l], L.sp2[l], m, a0, rc2, fx, f2);
        const bool neg = fx < 0.0;
        const double a = neg ? x : L.a[l];
        const double b = neg ? L.b[l] : x;
        const double mid = 0.5 * (a + b);
        double xn = f2 > 0.0 ? x - fx / f2 : mid;
        xn = (xn > a && xn < b) ? xn : mid;
        const double step = xn - x;
        const bool zero = fx == 0.0;
        const bool narrow = b - a <= line_tol;
        const bool small = (step < 0.0 ? -step : step) <= newton_tol;
        const bool stop = zero || narrow || small;
        const bool was = L.done[l] != 0;
        L.sig[l] = was ? L.sig[l] : (zero ? x : (narrow ? mid : xn));
        L.a[l] = was ? L.a[l] : a;
        L.b[l] = was ? L.b[l] : b;
        L.x[l] = was ? x : xn;
        L.done[l] = (was || stop) ? 1 : 0;
        running += (was || stop) ? 0 : 1;
      }
      if (running == 0) break;
      if (it == 99) {  // out of steps: the middle of the bracket (as bull_ramp_min)
        for (int l = 0; l < live; ++l)
          if (!L.done[l]) L.sig[l] = 0.5 * (L.a[l] + L.b[l]);
        break;
      }
      if (2 * running < live) {  // squeeze finished lanes behind the live ones (results kept)
        int w = 0;
        for (int l = 0; l < live; ++l) {
          if (!L.done[l]) {
            if (w != l) {
              std::swap(L.tq[w], L.tq[l]); std::swap(L.sp2[w], L.sp2[l]); std::swap(L.lo[w], L.lo[l]);
              std::swap(L.hi[w], L.hi[l]); std::swap(L.a[w], L.a[l]); std::swap(L.b[w], L.b[l]);
              std::swap(L.x[w], L.x[l]); std::swap(L.sig[w], L.sig[l]); std::swap(L.node[w], L.node[l]);
              std::swap(L.done[w], L.done[l]);
            }
            ++w;
          }
        }
        live = w;
      }
    }
    // 4. heights
    for (int l = 0; l < nl; ++l) {
      const int k = L.node[l];
      const double sig = L.sig[l];
      const double u = sig - L.tq[l];
      const double d = std::sqrt(L.sp2[l] + u * u);
      const double e = (d < R ? d : R) - a0;
      const double w = rc2 - e * e;
      const double z = az + m * sig + (e > 0.0 ? rc - std::sqrt(w > 0.0 ? w : 0.0) : 0.0);
      const double hk = hc[k];
      const double zb = z > bottom ? z : bottom;
      const double nh = zb < hk ? zb : hk;
      vol += hk - nh;
      cnt += nh < hk ? 1 : 0;
      hc[k] = nh;
    }
  }
  out.vol += vol;
  out.lowered += cnt;
}

// Node range [j0, j1] of row i covered by the stadium of the move; false if none.
inline bool row_nodes(const ZMap& zm, const LineSetup& s, double r, int i, int& j0, int& j1) noexcept {
  double xlo, xhi;
  if (!row_range(s, r, zm.node_y(i), xlo, xhi)) return false;
  return node_range(xlo, xhi, zm.x0(), zm.dx(), zm.nx(), j0, j1);
}

// The rows of a move lie nx·8 bytes apart, so every row segment starts with cache misses; the
// heights of the next row are prefetched while the current one is computed.
inline void prefetch_row(const double* h, int n) noexcept {
#if defined(__GNUC__)
  for (int k = 0; k < n; k += 8) __builtin_prefetch(h + k, 1, 3);
  __builtin_prefetch(h + n - 1, 1, 3);
#else
  (void)h;
  (void)n;
#endif
}

inline void prefetch_line(const double* p) noexcept {
#if defined(__GNUC__)
  __builtin_prefetch(p, 1, 3);
#else
  (void)p;
#endif
}

// ---------------------------------------------------------------------------------------------
// Flat and ball ramps and level lines (most of the lines of a program): one call per move, with
// explicit SIMD (AVX-512 or AVX2 intrinsics, chosen once per process from the CPU; plain C++
// elsewhere), so the speed does not hang on what the auto-vectoriser makes of a loop at -O2 vs -O3.
// The kernels are written once (ramp_kernel.inc) and compiled per instruction set. The stadium span
// of every row of the move is computed first, W rows at a time and without division (row_spans);
// per-column terms qx·ex and qx·ey once per move. Rows of a move lie nx·8 bytes apart (a new page
// per row for big grids); the row kAhead rows on is prefetched one cache line per chunk while a row
// is computed.
// ---------------------------------------------------------------------------------------------
struct MoveOut {
  double vol = 0.0;          // removed height summed over nodes [mm] (× cell area later)
  std::int64_t lowered = 0;  // nodes whose height went down
  std::int64_t visited = 0;  // nodes of the stadium rows
};

constexpr int kAhead = 4;  // rows prefetched ahead
/// Slack of the row spans of ramps [index units]: a node this close outside the stadium is visited
/// too (the per-node test rejects it), so rounding in the span can never drop a covered node.
constexpr double kSpanSlack = 1e-6;

/// Per-move constants of the row spans (ramp kernels): end points, direction and its reciprocals
/// (directions within 1e-15 of an axis use the axis-parallel form instead), grid origin and steps.
struct SpanSetup {
  double ax, ay, bx, by, r, r2, ex, ey, len, iex, iey, y0, dy, x0, idx;
  bool use_ex, use_ey;
  SpanSetup(const ZMap& zm, const LineSetup& s, double R)
      : ax(s.ax), ay(s.ay), bx(s.ax + s.len * s.ex), by(s.ay + s.len * s.ey), r(R), r2(R * R), ex(s.ex), ey(s.ey),
        len(s.len), iex(std::abs(s.ex) >= 1e-15 ? 1.0 / s.ex : 0.0), iey(std::abs(s.ey) >= 1e-15 ? 1.0 / s.ey : 0.0),
        y0(zm.y0()), dy(zm.dy()), x0(zm.x0()), idx(1.0 / zm.dx()), use_ex(std::abs(s.ex) >= 1e-15),
        use_ey(std::abs(s.ey) >= 1e-15) {}
};

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NETSHAPE_NO_X86_KERNELS)
#define NETSHAPE_X86_KERNELS 1
#endif

#ifdef NETSHAPE_X86_KERNELS
#pragma GCC push_options
#pragma GCC target("avx512f")
namespace k512 {
struct V {
  using D = __m512d;
  using M = __mmask8;
  static constexpr int W = 8;
  static D set(double x) { return _mm512_set1_pd(x); }
  static D iota() { return _mm512_set_pd(7, 6, 5, 4, 3, 2, 1, 0); }
  static void storeu(double* p, D x) { _mm512_storeu_pd(p, x); }
  static D floor(D a) { return _mm512_roundscale_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC); }
  static D ceil(D a) { return _mm512_roundscale_pd(a, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC); }
  static M valid(int n) { return n >= 8 ? M(0xFF) : M((1u << n) - 1u); }
  static D load(const double* p, M v, bool full) { return full ? _mm512_loadu_pd(p) : _mm512_maskz_loadu_pd(v, p); }
  static void store(double* p, D x, M v, bool full) {
    if (full) _mm512_storeu_pd(p, x);
    else _mm512_mask_storeu_pd(p, v, x);
  }
  static D add(D a, D b) { return _mm512_add_pd(a, b); }
  static D sub(D a, D b) { return _mm512_sub_pd(a, b); }
  static D mul(D a, D b) { return _mm512_mul_pd(a, b); }
  static D sqrt(D a) { return _mm512_sqrt_pd(a); }
  static D max(D a, D b) { return _mm512_max_pd(a, b); }  // a > b ? a : b
  static D min(D a, D b) { return _mm512_min_pd(a, b); }  // a < b ? a : b
  static M lt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }
  static M le(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
  static M gt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }
  static M ge(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_GE_OQ); }
  static M land(M a, M b) { return M(a & b); }
  static bool any(M m) { return m != 0; }
  static D blend(M m, D a, D b) { return _mm512_mask_blend_pd(m, a, b); }
  static int count(M m) { return __builtin_popcount(m); }
  static double sum(D a) { return _mm512_reduce_add_pd(a); }
};
#include "ramp_kernel.inc"
}  // namespace k512
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2")
namespace k256 {
struct V {
  using D = __m256d;
  using M = __m256d;
  static constexpr int W = 4;
  static D set(double x) { return _mm256_set1_pd(x); }
  static D iota() { return _mm256_set_pd(3, 2, 1, 0); }
  static void storeu(double* p, D x) { _mm256_storeu_pd(p, x); }
  static D floor(D a) { return _mm256_floor_pd(a); }
  static D ceil(D a) { return _mm256_ceil_pd(a); }
  static M valid(int n) {
    return _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(n), _mm256_set_epi64x(3, 2, 1, 0)));
  }
  static D load(const double* p, M v, bool full) {
    return full ? _mm256_loadu_pd(p) : _mm256_maskload_pd(p, _mm256_castpd_si256(v));
  }
  static void store(double* p, D x, M v, bool full) {
    if (full) _mm256_storeu_pd(p, x);
    else _mm256_maskstore_pd(p, _mm256_castpd_si256(v), x);
  }
  static D add(D a, D b) { return _mm256_add_pd(a, b); }
  static D sub(D a, D b) { return _mm256_sub_pd(a, b); }
  static D mul(D a, D b) { return _mm256_mul_pd(a, b); }
  static D sqrt(D a) { return _mm256_sqrt_pd(a); }
  static D max(D a, D b) { return _mm256_max_pd(a, b); }
  static D min(D a, D b) { return _mm256_min_pd(a, b); }
  static M lt(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
  static M le(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
  static M gt(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
  static M ge(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }
  static M land(M a, M b) { return _mm256_and_pd(a, b); }
  static bool any(M m) { return _mm256_movemask_pd(m) != 0; }
  static D blend(M m, D a, D b) { return _mm256_blendv_pd(a, b, m); }
  static int count(M m) { return __builtin_popcount(static_cast<unsigned>(_mm256_movemask_pd(m))); }
  static double sum(D a) {
    alignas(32) double t[4];
    _mm256_store_pd(t, a);
    return ((t[0] + t[1]) + t[2]) + t[3];
  }
};
#include "ramp_kernel.inc"
}  // namespace k256
#pragma GCC pop_options
#endif  // NETSHAPE_X86_KERNELS

namespace k64 {
struct V {  // one node at a time, plain C++ (other compilers and CPUs)
  using D = double;
  using M = bool;
  static constexpr int W = 1;
  static D set(double x) { return x; }
  static D iota() { return 0.0; }
  static void storeu(double* p, D x) { *p = x; }
  static D floor(D a) { return std::floor(a); }
  static D ceil(D a) { return std::ceil(a); }
  static M valid(int n) { return n > 0; }
  static D load(const double* p, M, bool) { return *p; }
  static void store(double* p, D x, M, bool) { *p = x; }
  static D add(D a, D b) { return a + b; }
  static D sub(D a, D b) { return a - b; }
  static D mul(D a, D b) { return a * b; }
  static D sqrt(D a) { return std::sqrt(a); }
  static D max(D a, D b) { return a > b ? a : b; }
  static D min(D a, D b) { return a < b ? a : b; }
  static M lt(D a, D b) { return a < b; }
  static M le(D a, D b) { return a <= b; }
  static M gt(D a, D b) { return a > b; }
  static M ge(D a, D b) { return a >= b; }
  static M land(M a, M b) { return a && b; }
  static bool any(M m) { return m; }
  static D blend(M m, D a, D b) { return m ? b : a; }
  static int count(M m) { return m ? 1 : 0; }
  static double sum(D a) { return a; }
};
#include "ramp_kernel.inc"
}  // namespace k64

enum class Isa { plain, avx2, avx512 };

// The instruction set of the ramp kernels, chosen once: the best the CPU (and OS) supports, or
// NETSHAPE_STOCK_ISA=plain|avx2|avx512 (a lower one than the CPU has; for tests and benchmarks).
Isa ramp_isa() {
  static const Isa isa = [] {
    Isa best = Isa::plain;
#ifdef NETSHAPE_X86_KERNELS
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) best = Isa::avx512;
    else if (__builtin_cpu_supports("avx2")) best = Isa::avx2;
#endif
    const char* env = std::getenv("NETSHAPE_STOCK_ISA");
    if (env != nullptr) {
      const std::string want(env);
      if (want == "plain") best = Isa::plain;
      else if (want == "avx2" && best == Isa::avx512) best = Isa::avx2;
    }
    return best;
  }();
  return isa;
}

// Sweep a flat or ball ramp or level line over rows i0 … i1.
template <int Kind>
void ramp_rows(ZMap& zm, const LineSetup& s, double R, int i0, int i1, SweepStats& st) {
  // the columns the move can reach, widened to whole chunks of 8 and padded so that chunk loads of
  // the per-column terms stay inside the buffer
  int jlo, jhi;
  if (!node_range(std::min(s.ax, s.ax + s.len * s.ex) - R, std::max(s.ax, s.ax + s.len * s.ex) + R, zm.x0(),
                  zm.dx(), zm.nx(), jlo, jhi))
    return;
  const int cmin = jlo - jlo % 8;
  const int ncol = (jhi - cmin) / 8 * 8 + 16;
  thread_local std::vector<double> cols;  // grows to the widest move a thread has swept
  if (static_cast<int>(cols.size()) < 2 * ncol) cols.resize(2 * static_cast<std::size_t>(ncol));
  double* tqx = cols.data();
  double* spx = cols.data() + ncol;
  for (int k = 0; k < ncol; ++k) {  // qx exactly as ZMap::node_x − A_x
    const double qx = (zm.x0() + (static_cast<double>(cmin + k) + 0.5) * zm.dx()) - s.ax;
    tqx[k] = qx * s.ex;
    spx[k] = qx * s.ey;
  }
  const int nrows = i1 - i0 + 1;
  thread_local std::vector<int> spans;  // j0, j1 of each row of the move
  if (static_cast<int>(spans.size()) < 2 * nrows + 16) spans.resize(2 * static_cast<std::size_t>(nrows) + 16);
  int* j0s = spans.data();
  int* j1s = spans.data() + nrows + 8;
  const SpanSetup q(zm, s, R);
  MoveOut mo;
  double* H = SweepAccess::heights(zm).data();
  const double bottom = zm.bottom();
  const bool up = s.m >= 0.0;
#define NETSHAPE_RAMP(ns)                                                                                   \
  ns::row_spans(q, i0, nrows, jlo, jhi, j0s, j1s);                                                          \
  if (s.m == 0.0) ns::level_move<Kind>(zm, H, s, R, i0, i1, j0s, j1s, bottom, tqx, spx, cmin, mo);          \
  else if (up) ns::ramp_move<Kind, true>(zm, H, s, R, i0, i1, j0s, j1s, bottom, tqx, spx, cmin, mo);        \
  else ns::ramp_move<Kind, false>(zm, H, s, R, i0, i1, j0s, j1s, bottom, tqx, spx, cmin, mo);
  switch (ramp_isa()) {
#ifdef NETSHAPE_X86_KERNELS
    case Isa::avx512: NETSHAPE_RAMP(k512) break;
    case Isa::avx2: NETSHAPE_RAMP(k256) break;
#endif
    default: NETSHAPE_RAMP(k64) break;
  }
#undef NETSHAPE_RAMP
  st.nodes_visited += mo.visited;
  st.removed_volume += mo.vol;
  st.nodes_lowered += mo.lowered;
}

template <int Kind>
void sweep_line_k(ZMap& zm, const TipProfile& p, const LineSetup& s, double ylo, double yhi, SweepStats& st) {
  const double r = p.radius, r2 = r * r;
  int i0, i1;
  if (!node_range(ylo - r, yhi + r, zm.y0(), zm.dy(), zm.ny(), i0, i1)) return;
  {  // quick reject: the tip never goes below min(A_z, B_z) (the profile only adds lift)
    const double zlow = s.vertical ? s.zv : std::min(s.az, s.az + s.m * s.len);
    const double width = std::min(static_cast<double>(zm.nx()), (std::abs(s.len * s.ex) + 2.0 * r) / zm.dx() + 1.0);
    if (SweepAccess::above(zm, i0, i1, zlow, width)) return;
  }
  MatrixXdR& H = SweepAccess::heights(zm);
  const Eigen::Index nx = zm.nx();
  const double bottom = zm.bottom();
  if (Kind != kBull && !s.vertical) {  // flat and ball ramps and level lines: the SIMD kernels
    ramp_rows<Kind>(zm, s, r, i0, i1, st);
    return;
  }
  RowOut out;
  BullLanes* lanes = nullptr;
  BullLanes lanes_storage;  // only touched for bull ramps
  if (Kind == kBull && !s.vertical && s.m != 0.0) lanes = &lanes_storage;
  int j0 = 0, j1 = -1;
  bool has = row_nodes(zm, s, r, i0, j0, j1);
  for (int i = i0; i <= i1; ++i) {
    // the next row's range, prefetched before this row is computed
    int n0 = 0, n1 = -1;
    const bool next = i < i1 && row_nodes(zm, s, r, i + 1, n0, n1);
    if (next) prefetch_row(H.data() + (i + 1) * nx + n0, n1 - n0 + 1);
    if (has) {
      double* h = H.data() + static_cast<Eigen::Index>(i) * nx + j0;
      st.nodes_visited += j1 - j0 + 1;
      Row row;
      row.x0 = zm.x0();
      row.dx = zm.dx();
      row.jb = j0 + 0.5;
      row.qy = zm.node_y(i) - s.ay;
      row.n = j1 - j0 + 1;
      if (s.vertical) row_vertical(s, p, r2, row, bottom, h, out);
      else if (s.m == 0.0) row_bull_level(s, p, r2, row, bottom, h, out);
      else row_bull_ramp(s, p, r2, row, bottom, h, out, *lanes);
    }
    has = next;
    j0 = n0;
    j1 = n1;
  }
  st.removed_volume += out.vol;
  st.nodes_lowered += out.lowered;
}

SweepStats sweep_line_impl(ZMap& zm, const TipProfile& p, ProfileKind kind, const Vec3& a, const Vec3& b) {
  SweepStats st;
  st.moves = 1;
  const LineSetup s = make_line(a, b);
  const double ylo = std::min(a.y(), b.y()), yhi = std::max(a.y(), b.y());
  switch (kind) {
    case kFlat: sweep_line_k<kFlat>(zm, p, s, ylo, yhi, st); break;
    case kBall: sweep_line_k<kBall>(zm, p, s, ylo, yhi, st); break;
    case kBull: sweep_line_k<kBull>(zm, p, s, ylo, yhi, st); break;
  }
  st.removed_volume *= zm.dx() * zm.dy();
  return st;
}

void check_point(const char* field, const Vec3& p) {
  for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE(field, p[k]);
}

// ---------------------------------------------------------------------------------------------
// Arcs in the XY plane with a constant radius (planar or helical)
// ---------------------------------------------------------------------------------------------
struct ArcSetup {
  double cx = 0, cy = 0;  // centre [mm]
  double r = 0;           // axis radius [mm]
  double th0 = 0;         // start angle [rad]
  double sgn = 1;         // +1 counter-clockwise, −1 clockwise
  double total = 0;       // |sweep| [rad]
  double z0 = 0;          // start z [mm]
  double kz = 0;          // dz per rad of travel [mm/rad]
};

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

// -------------------------------------------------------------------------------------------------
void SweepOptions::validate() const {
  NETSHAPE_CHECK_FINITE("sweep.chord_tolerance", chord_tolerance);
  NETSHAPE_CHECK(chord_tolerance > 0.0, "sweep.chord_tolerance", chord_tolerance, "must be positive [mm]");
}

SweepStats& SweepStats::operator+=(const SweepStats& o) noexcept {
  moves += o.moves;
  nodes_visited += o.nodes_visited;
  nodes_lowered += o.nodes_lowered;
  removed_volume += o.removed_volume;
  rapids_cutting += o.rapids_cutting;
  return *this;
}

double lowest_reach_line(const TipProfile& p, const Vec3& a, const Vec3& b, double x, double y) noexcept {
  const LineSetup s = make_line(a, b);
  const double r2 = p.radius * p.radius;
  if (p.corner_radius == 0.0) return reach_line<kFlat>(s, p, r2, x, y);
  if (p.flat_radius <= 0.0) return reach_line<kBall>(s, p, r2, x, y);
  return reach_line<kBull>(s, p, r2, x, y);
}

SweepStats sweep_line(ZMap& zmap, const cutter::Cutter& cutter, const Vec3& a, const Vec3& b) {
  cutter.validate();
  check_point("line.start", a);
  check_point("line.end", b);
  return sweep_line_impl(zmap, TipProfile::of(cutter), kind_of(cutter), a, b);
}

namespace {
// Every entry of an (n, 3) array finite; the error names the entry ("starts[1, 2] = nan: …").
template <class M>
void check_finite_rows(const char* name, const M& m) {
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      if (!std::isfinite(m(k, c))) {
        const std::string f = std::string(name) + "[" + std::to_string(k) + ", " + std::to_string(c) + "]";
        NETSHAPE_CHECK_FINITE(f.c_str(), m(k, c));
      }
}
}  // namespace

SweepStats sweep_lines(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const MatrixXdR>& starts,
                       const Eigen::Ref<const MatrixXdR>& ends) {
  cutter.validate();
  NETSHAPE_CHECK(starts.cols() == 3, "starts.shape[1]", starts.cols(), "must be 3 (x, y, z) [mm]");
  NETSHAPE_CHECK(ends.cols() == 3, "ends.shape[1]", ends.cols(), "must be 3 (x, y, z) [mm]");
  if (ends.rows() != starts.rows()) {
    const std::string req = "must equal starts.shape[0] = " + std::to_string(starts.rows());
    NETSHAPE_CHECK(false, "ends.shape[0]", ends.rows(), req.c_str());
  }
  check_finite_rows("starts", starts);
  check_finite_rows("ends", ends);
  const Eigen::Index n = starts.rows();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Vec3 a(starts(k, 0), starts(k, 1), starts(k, 2));
    const Vec3 b(ends(k, 0), ends(k, 1), ends(k, 2));
    st += sweep_line_impl(zmap, p, kind, a, b);
  }
  return st;
}

SweepStats sweep_polyline(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& points,
                          bool merge_collinear) {
  cutter.validate();
  NETSHAPE_CHECK(points.rows() >= 1, "points.shape[0]", points.rows(), "needs at least one point");
  check_finite_rows("points", points);
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  if (points.rows() == 1) {
    const Vec3 a = points.row(0).transpose();
    return sweep_line_impl(zmap, p, kind, a, a);
  }
  Vec3 a = points.row(0).transpose();
  Vec3 b = points.row(1).transpose();
  for (Eigen::Index k = 2; k <= points.rows(); ++k) {
    if (k < points.rows()) {
      const Vec3 c = points.row(k).transpose();
      if (merge_collinear && toolpath::continues_run(a, b, c, 1e-9)) {  // extend the run a→b to c
        b = c;
        continue;
      }
      st += sweep_line_impl(zmap, p, kind, a, b);
      a = b;
      b = c;
    } else {
      st += sweep_line_impl(zmap, p, kind, a, b);
    }
  }
  return st;
}

SweepStats sweep_block(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Block& block,
                       const SweepOptions& options) {
  cutter.validate();
  options.validate();
  block.validate();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  using toolpath::MotionKind;
  if (block.kind == MotionKind::rapid) {
    if (!options.include_rapids) return {};
    SweepStats st = sweep_line_impl(zmap, p, kind, block.start, block.end);
    st.rapids_cutting = st.nodes_lowered > 0 ? 1 : 0;
    return st;
  }
  if (block.kind == MotionKind::line) return sweep_line_impl(zmap, p, kind, block.start, block.end);

  // arcs
  const double r0 = std::hypot(block.start.x() - block.center.x(), block.start.y() - block.center.y());
  const double r1 = std::hypot(block.end.x() - block.center.x(), block.end.y() - block.center.y());
  const double sw = block.sweep();
  if (block.plane == toolpath::Plane::xy && std::abs(r1 - r0) <= 1e-9) {
    ArcSetup s;
    s.cx = block.center.x();
    s.cy = block.center.y();
    s.r = r0;
    s.th0 = std::atan2(block.start.y() - s.cy, block.start.x() - s.cx);
    s.sgn = sw < 0.0 ? -1.0 : 1.0;
    s.total = std::abs(sw);
    s.z0 = block.start.z();
    s.kz = (block.end.z() - block.start.z()) / s.total;
    SweepStats st;
    st.moves = 1;
    switch (kind) {
      case kFlat: sweep_arc_k<kFlat>(zmap, p, s, st); break;
      case kBall: sweep_arc_k<kBall>(zmap, p, s, st); break;
      case kBull: sweep_arc_k<kBull>(zmap, p, s, st); break;
    }
    st.removed_volume *= zmap.dx() * zmap.dy();
    return st;
  }
  // other planes / varying radius: chords
  const int n = toolpath::chord_count(std::max(block.radius(), 1e-12), sw, options.chord_tolerance);
  SweepStats st;
  Vec3 a = block.start;
  for (int k = 1; k <= n; ++k) {
    const Vec3 b = k == n ? block.end : block.point_at(static_cast<double>(k) / n);
    st += sweep_line_impl(zmap, p, kind, a, b);
    a = b;
  }
  return st;
}

SweepStats sweep(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                 const SweepOptions& options) {
  cutter.validate();
  options.validate();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  bool run = false;  // a pending run of collinear feed lines a → b
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  auto flush = [&]() {
    if (run) st += sweep_line_impl(zmap, p, kind, a, b);
    run = false;
  };
  for (const toolpath::Block& blk : program.blocks) {
    blk.validate();
    if (blk.kind == toolpath::MotionKind::line && options.merge_collinear) {
      if (run && blk.start == b && toolpath::continues_run(a, b, blk.end, 1e-9)) {
        b = blk.end;
        continue;
      }
      flush();
      run = true;
      a = blk.start;
      b = blk.end;
      continue;
    }
    flush();
    st += sweep_block(zmap, cutter, blk, options);
  }
  flush();
  return st;
}

}  // namespace netshape::stock
