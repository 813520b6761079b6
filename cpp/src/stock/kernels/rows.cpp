// Row kernels of the Z-map sweep for plunges and bull-nose lines: one grid row at a time over the
// contiguous nodes the stadium of the move covers, plain loops with every per-row constant hoisted and
// only selects inside, which `#pragma omp simd` vectorises; compiled once per instruction set by
// netshape_add_kernels (kernels/sweep_kernels.hpp). Node coordinates are computed exactly as
// ZMap::node_x does.
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include <cmath>
#include <cstdint>

#include "stock/kernels/sweep_kernels.hpp"

#define NETSHAPE_SIMD_PRAGMA(x) _Pragma(#x)

namespace netshape::stock::kernels::NETSHAPE_KERNEL_ISA {
namespace {

// (kernel files use only functions of their own unit: no out-of-line std template can leak)
template <class T>
NETSHAPE_SIMD_INLINE void swap(T& a, T& b) noexcept {
  const T t = a;
  a = b;
  b = t;
}

// Nodes are taken in blocks of kBlock. A block is skipped when no node of it can be lowered: every
// height is at least kSkipMargin below a cheap lower bound of the cutter there (no square root:
// the tip's lowest point over the node's feasible travel from ρ ≤ R, plus a lower bound of the lift
// from the node's distance to the line, g(d) ≥ (d − a)²/(2 r_c)). Exact — a skipped node would
// not have changed — and frequent when moves re-cut material (the margin covers rounding).

// The row loop: node(k, ok) gives the lowest reach z at node k (ok: the cutter covers it),
// bound(k) a lower bound of it. h = min(h, max(z, bottom)) where ok.
template <class Node, class Bound>
NETSHAPE_SIMD_INLINE void row_blocks(int n, double* __restrict h, double bottom, const Node& node, const Bound& bound,
                                RowOut& out) {
  double vol = 0.0;
  int cnt = 0;  // an int reduction vectorises (a 64-bit one does not, GCC 12)
  for (int b0 = 0; b0 < n; b0 += kBlock) {
    const int b1 = b0 + kBlock < n ? b0 + kBlock : n;
    double gap = -inf;
    NETSHAPE_SIMD_PRAGMA(omp simd reduction(max : gap))
    for (int k = b0; k < b1; ++k) {
      const double g = h[k] - bound(k);
      gap = g > gap ? g : gap;
    }
    if (gap <= -kSkipMargin) continue;
    NETSHAPE_SIMD_PRAGMA(omp simd reduction(+ : vol, cnt))
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
  NETSHAPE_SIMD_INLINE void at(int k, double& tq, double& sp) const {
    const double qx = (x0 + (jb + k) * dx) - ax;
    tq = qx * ex + qy * ey;
    sp = qy * ex - qx * ey;
  }
};

// lift lower bound from a lower bound dmin of the distance to the axis: (dmin − a)²/(2 r_c), ≥ 0
NETSHAPE_SIMD_INLINE double lift_bound(double dmin, double a0, double half_inv_rc) {
  const double e = dmin - a0 > 0.0 ? dmin - a0 : 0.0;
  return e * e * half_inv_rc;
}

// level line (m = 0): the point of the segment nearest to the node, d² = s² + u² (bull-nose only; flat
// and ball level lines go to level_move in kernels/ramp.cpp)
void row_bull_level(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                         double bottom, double* __restrict h, RowOut& out) {
  const LineRow L(s, row);
  const double R = p.radius, rc = p.corner_radius, fr = p.flat_radius, rc2 = rc * rc;
  const double half_inv_rc = rc > 0.0 ? 0.5 / rc : 0.0;
  // nearest point of the segment: u = τ_q − clamp(τ_q, 0, L)
  auto near = [&](int k, double& sp, double& u) NETSHAPE_SIMD_LAMBDA {
    double tq;
    L.at(k, tq, sp);
    const double c = tq > 0.0 ? (tq < L.len ? tq : L.len) : 0.0;
    u = tq - c;
  };
  auto bound = [&](int k) NETSHAPE_SIMD_LAMBDA {
    double sp, u;
    near(k, sp, u);
    const double as = sp < 0.0 ? -sp : sp, au = u < 0.0 ? -u : u;
    return L.az + lift_bound(as > au ? as : au, fr, half_inv_rc);
  };
  auto node = [&](int k, bool& ok) NETSHAPE_SIMD_LAMBDA {
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
void row_vertical(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                       double bottom, double* __restrict h, RowOut& out) {
  const double ax = s.ax, zv = s.zv;
  const double R = p.radius, rc = p.corner_radius, fr = p.flat_radius, rc2 = rc * rc;
  const double x0 = row.x0, dx = row.dx, jb = row.jb, qy = row.qy;
  auto node = [&](int k, bool& ok) NETSHAPE_SIMD_LAMBDA {
    const double qx = (x0 + (jb + k) * dx) - ax;
    const double d2 = qx * qx + qy * qy;
    const double d = std::sqrt(d2);
    const double e = (d < R ? d : R) - fr;
    const double w = rc2 - e * e;
    ok = d2 <= r2;
    return zv + (e > 0.0 ? rc - std::sqrt(w > 0.0 ? w : 0.0) : 0.0);
  };
  auto bound = [&](int) NETSHAPE_SIMD_LAMBDA { return zv; };
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
// F'(σ) and F''(σ) of the bull ramp (F'' = 0 where F' is ±inf or in the flat zone)
NETSHAPE_SIMD_INLINE void bull_derivs(double sig, double tq, double sp2, double m, double a0, double rc2, double& f,
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

void row_bull_ramp(const LineSetup& s, const TipProfile& p, double r2, const Row& row,
                                        double bottom, double* __restrict h, RowOut& out, BullLanes& L) {
  const double ax = s.ax, az = s.az, ex = s.ex, ey = s.ey, len = s.len, m = s.m;
  const bool up = m >= 0.0;
  const double a0 = p.flat_radius, rc = p.corner_radius, rc2 = rc * rc, R = p.radius;
  const double half_inv_rc = 0.5 / rc;
  const double x0 = row.x0, dx = row.dx, jb = row.jb, qy = row.qy;
  double vol = 0.0;
  std::int64_t cnt = 0;
  for (int c0 = 0; c0 < row.n; c0 += kBullChunk) {
    const int n = row.n - c0 < kBullChunk ? row.n - c0 : kBullChunk;
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
    NETSHAPE_SIMD_PRAGMA(omp simd)
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
      NETSHAPE_SIMD_PRAGMA(omp simd reduction(+ : running))
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
              swap(L.tq[w], L.tq[l]); swap(L.sp2[w], L.sp2[l]); swap(L.lo[w], L.lo[l]);
              swap(L.hi[w], L.hi[l]); swap(L.a[w], L.a[l]); swap(L.b[w], L.b[l]);
              swap(L.x[w], L.x[l]); swap(L.sig[w], L.sig[l]); swap(L.node[w], L.node[l]);
              swap(L.done[w], L.done[l]);
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

}  // namespace

extern const RowKernels row_kernels;
const RowKernels row_kernels{&row_vertical, &row_bull_level, &row_bull_ramp};

}  // namespace netshape::stock::kernels::NETSHAPE_KERNEL_ISA
