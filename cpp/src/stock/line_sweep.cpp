// Lines of the Z-map sweep: the lowest reach of the tip over a node, the rows and row spans a move
// covers, and the calls into the SIMD kernels (kernels/sweep_kernels.hpp) that lower the heights.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/simd.hpp"
#include "stock/sweep_internal.hpp"

namespace netshape::stock::detail {

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

namespace {

using kernels::line_tol;
using kernels::newton_tol;

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
double reach_line(const LineSetup& s, const TipProfile& p, double r2, double x, double y) noexcept {
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

// The row span of every row of the move is found by the kernels from these constants.
kernels::SpanSetup span_setup(const ZMap& zm, const LineSetup& s, double R) {
  kernels::SpanSetup q;
  q.ax = s.ax;
  q.ay = s.ay;
  q.bx = s.ax + s.len * s.ex;
  q.by = s.ay + s.len * s.ey;
  q.r = R;
  q.r2 = R * R;
  q.ex = s.ex;
  q.ey = s.ey;
  q.len = s.len;
  q.use_ex = std::abs(s.ex) >= 1e-15;
  q.use_ey = std::abs(s.ey) >= 1e-15;
  q.iex = q.use_ex ? 1.0 / s.ex : 0.0;
  q.iey = q.use_ey ? 1.0 / s.ey : 0.0;
  q.y0 = zm.y0();
  q.dy = zm.dy();
  q.x0 = zm.x0();
  q.idx = 1.0 / zm.dx();
  return q;
}

// The kernel tables of the instruction set chosen for this process (core/dispatch.hpp).
const kernels::RampKernels& ramp_kernels() {
  static const kernels::RampKernels& k = NETSHAPE_SIMD_SELECT(kernels, ramp_kernels);
  return k;
}
const kernels::RowKernels& row_kernels() {
  static const kernels::RowKernels& k = NETSHAPE_SIMD_SELECT(kernels, row_kernels);
  return k;
}

// Node range [j0, j1] of row i covered by the stadium of the move; false if none.
inline bool row_nodes(const ZMap& zm, const LineSetup& s, double r, int i, int& j0, int& j1) noexcept {
  double xlo, xhi;
  if (!row_range(s, r, zm.node_y(i), xlo, xhi)) return false;
  return node_range(xlo, xhi, zm.x0(), zm.dx(), zm.nx(), j0, j1);
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
  const kernels::SpanSetup q = span_setup(zm, s, R);
  const kernels::RampKernels& k = ramp_kernels();
  k.row_spans(q, i0, nrows, jlo, jhi, j0s, j1s);
  const kernels::MoveArgs args{SweepAccess::heights(zm).data(), zm.nx(), zm.y0(), zm.dy(), s, R, zm.bottom(), i0, i1,
                               j0s, j1s, tqx, spx, cmin};
  kernels::MoveOut mo;
  k.move[Kind][s.m == 0.0 ? 0 : (s.m > 0.0 ? 1 : 2)](args, mo);
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
  const kernels::RowKernels& k = row_kernels();
  kernels::RowOut out;
  kernels::BullLanes* lanes = nullptr;
  kernels::BullLanes lanes_storage;  // only touched for bull ramps
  if (Kind == kBull && !s.vertical && s.m != 0.0) lanes = &lanes_storage;
  int j0 = 0, j1 = -1;
  bool has = row_nodes(zm, s, r, i0, j0, j1);
  for (int i = i0; i <= i1; ++i) {
    // the next row's range, prefetched before this row is computed (rows lie nx·8 bytes apart, so
    // every row segment starts with cache misses)
    int n0 = 0, n1 = -1;
    const bool next = i < i1 && row_nodes(zm, s, r, i + 1, n0, n1);
    if (next) simd::prefetch_span_for_write(H.data() + (i + 1) * nx + n0, n1 - n0 + 1);
    if (has) {
      double* h = H.data() + static_cast<Eigen::Index>(i) * nx + j0;
      st.nodes_visited += j1 - j0 + 1;
      kernels::Row row;
      row.x0 = zm.x0();
      row.dx = zm.dx();
      row.jb = j0 + 0.5;
      row.qy = zm.node_y(i) - s.ay;
      row.n = j1 - j0 + 1;
      if (s.vertical) k.vertical(s, p, r2, row, bottom, h, out);
      else if (s.m == 0.0) k.bull_level(s, p, r2, row, bottom, h, out);
      else k.bull_ramp(s, p, r2, row, bottom, h, out, *lanes);
    }
    has = next;
    j0 = n0;
    j1 = n1;
  }
  st.removed_volume += out.vol;
  st.nodes_lowered += out.lowered;
}

}  // namespace

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


double lowest_reach(const TipProfile& p, const LineSetup& s, double x, double y) noexcept {
  const double r2 = p.radius * p.radius;
  if (p.corner_radius == 0.0) return reach_line<kFlat>(s, p, r2, x, y);
  if (p.flat_radius <= 0.0) return reach_line<kBall>(s, p, r2, x, y);
  return reach_line<kBull>(s, p, r2, x, y);
}

}  // namespace netshape::stock::detail
