#include "netshape/stock/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"

namespace netshape::stock {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double two_pi = 2.0 * pi;
/// Horizontal move length below which a line is treated as vertical (plunge) [mm].
constexpr double vertical_eps = 1e-9;
/// Tolerance of the 1-D minimisations: [mm] along lines, [rad] along arcs.
constexpr double line_tol = 1e-10;
constexpr double angle_tol = 1e-10;

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

// Bull-nose ramp: minimise F(σ) = m·σ + g(sqrt(sp² + (σ − tq)²)) on [lo, hi]; F is convex, so
// bisect on its non-decreasing derivative.
double bull_ramp_min(const TipProfile& p, double m, double sp2, double tq, double lo, double hi) noexcept {
  auto dfdx = [&](double sig) {
    const double u = sig - tq;
    const double d = std::sqrt(sp2 + u * u);
    const double gs = p.slope(d);
    if (gs == 0.0) return m;
    if (std::isinf(gs)) return u > 0 ? inf : (u < 0 ? -inf : m);
    return m + gs * u / d;
  };
  double sig;
  if (dfdx(lo) >= 0.0) {
    sig = lo;
  } else if (dfdx(hi) <= 0.0) {
    sig = hi;
  } else {
    double a = lo, b = hi;
    for (int it = 0; it < 200 && b - a > line_tol; ++it) {
      const double c = 0.5 * (a + b);
      if (dfdx(c) < 0.0) a = c; else b = c;
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

template <int Kind>
void sweep_line_k(ZMap& zm, const TipProfile& p, const LineSetup& s, double ylo, double yhi, SweepStats& st) {
  const double r = p.radius, r2 = r * r;
  int i0, i1;
  if (!node_range(ylo - r, yhi + r, zm.y0(), zm.dy(), zm.ny(), i0, i1)) return;
  MatrixXdR& H = zm.heights_mut();
  const double bottom = zm.bottom();
  for (int i = i0; i <= i1; ++i) {
    const double y = zm.node_y(i);
    double xlo, xhi;
    if (!row_range(s, r, y, xlo, xhi)) continue;
    int j0, j1;
    if (!node_range(xlo, xhi, zm.x0(), zm.dx(), zm.nx(), j0, j1)) continue;
    double* row = H.data() + static_cast<Eigen::Index>(i) * zm.nx();
    st.nodes_visited += j1 - j0 + 1;
    for (int j = j0; j <= j1; ++j) {
      const double z = reach_line<Kind>(s, p, r2, zm.node_x(j), y);
      lower(row[j], z, bottom, st);
    }
  }
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
  MatrixXdR& H = zm.heights_mut();
  const double bottom = zm.bottom();
  for (int i = i0; i <= i1; ++i) {
    const double y = zm.node_y(i);
    double* row = H.data() + static_cast<Eigen::Index>(i) * zm.nx();
    st.nodes_visited += j1 - j0 + 1;
    for (int j = j0; j <= j1; ++j) lower(row[j], reach_arc<Kind>(s, p, zm.node_x(j), y), bottom, st);
  }
}

int chords_for(double radius, double sweep_abs, double tol) {
  if (radius <= tol) return std::max(1, static_cast<int>(std::ceil(sweep_abs / (0.5 * pi))));
  const double step = 2.0 * std::acos(1.0 - tol / radius);
  const double n = std::ceil(sweep_abs / step);
  return static_cast<int>(std::clamp(n, 1.0, 1e7));
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

SweepStats sweep_polyline(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& points,
                          bool merge_collinear) {
  cutter.validate();
  NETSHAPE_CHECK(points.rows() >= 1, "points.shape[0]", points.rows(), "needs at least one point");
  for (Eigen::Index k = 0; k < points.rows(); ++k)
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("points", points(k, c));
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
      if (merge_collinear) {
        // extend the run a→b to c if c continues along the line a→b (within 1e-9 mm)
        const Vec3 ab = b - a, bc = c - b;
        const double lab = ab.norm();
        if (lab > 0.0 && ab.dot(bc) > 0.0 && ab.cross(c - a).norm() / lab <= 1e-9) {
          b = c;
          continue;
        }
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
  const int n = chords_for(std::max(block.radius(), 1e-12), std::abs(sw), options.chord_tolerance);
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
      if (run && blk.start == b) {
        const Vec3 ab = b - a, bc = blk.end - b;
        const double lab = ab.norm();
        if (lab > 0.0 && ab.dot(bc) > 0.0 && ab.cross(blk.end - a).norm() / lab <= 1e-9) {
          b = blk.end;
          continue;
        }
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
