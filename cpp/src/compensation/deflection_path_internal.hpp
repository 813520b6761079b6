#pragma once
// Private pieces shared by the deflection prediction along a path (deflection_path.cpp) and its
// compensation (deflection_compensation.cpp): the engagement scan, the single-point evaluator and
// result helpers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "netshape/compensation/deflection_compensation.hpp"
#include "netshape/core/error.hpp"
#include "compensation/swept_index.hpp"

namespace netshape::compensation::detail {

using deflection::DeflectionModel;
using deflection::DeflectionWorkspace;
using deflection::WallSide;

inline constexpr double two_pi = 2.0 * pi;
inline double wrap(double a) { return a - two_pi * std::floor(a / two_pi); }

inline std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

inline bool window_holds(double st, double ex, double a) { return wrap(a - st) <= ex - st + 1e-12; }

/// Material of the stock before the contour at p: the bilinear interpolation, over the four Z-map nodes
/// around p, of the nodes' material indicator at p's height (1 where a node's column stands above p.z,
/// else 0) exceeds 1/2. A wall the stock already has (a pre-cut, an earlier pass) is thus placed half-way
/// between the last node that holds material at that height and the first that does not, and moves
/// continuously with the point, whatever the heights on either side of it: also where a pre-cut's floor
/// lies exactly at the contour's Z (the interpolated height itself would cross the tip's height only
/// inside the floor nodes' squares, a staircase of cells). For a step between heights above and below
/// p.z it places the wall where the interpolated height crosses the step's middle, as the surface does.
inline bool material_at(const stock::ZMap& z, const Vec3& p) {
  if (!(p.z() >= z.bottom())) return false;
  if (!(p.x() >= z.x0() && p.x() <= z.x1() && p.y() >= z.y0() && p.y() <= z.y1())) return false;
  const int nx = z.nx(), ny = z.ny();
  const double u = std::clamp((p.x() - z.x0()) / z.dx() - 0.5, 0.0, static_cast<double>(nx - 1));
  const double v = std::clamp((p.y() - z.y0()) / z.dy() - 0.5, 0.0, static_cast<double>(ny - 1));
  const int j = std::min(static_cast<int>(u), std::max(nx - 2, 0));
  const int i = std::min(static_cast<int>(v), std::max(ny - 2, 0));
  const double fu = nx > 1 ? u - j : 0.0, fv = ny > 1 ? v - i : 0.0;
  const int j1 = std::min(j + 1, nx - 1), i1 = std::min(i + 1, ny - 1);
  const auto& h = z.heights();
  auto in = [&](int r, int c) { return h(r, c) > p.z() ? 1.0 : 0.0; };
  const double m0 = in(i, j) * (1 - fu) + in(i, j1) * fu;
  const double m1 = in(i1, j) * (1 - fu) + in(i1, j1) * fu;
  return m0 * (1 - fv) + m1 * fv > 0.5;
}

/// True if q lies within the tool's sweep from `from` up to (not including) the disc at `to`: closer
/// than R·(1 − 1e-9) to the segment, so the points of the circle about `to` ahead of the motion
/// (exactly R from `to`) stay material. Together with the moves before `from` this is the material
/// the tool has removed when it arrives at `to`, independent of how densely the path is sampled
/// (without it, the sliver between the disc at `from` and the circle at `to` would count as uncut
/// and widen the window by (|to − from| / 2R) rad behind the wall angle).
inline bool in_last_sweep(const Vec2& q, const Vec2& from, const Vec2& to, double R) {
  const Vec2 ab = to - from;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((q - from).dot(ab) / l2, 0.0, 1.0) : 0.0;
  const double r = R * (1.0 - 1e-9);
  return (from + t * ab - q).squaredNorm() < r * r;
}

/// Engagement of one point: the window from the first to the last material angle (phi_st, phi_ex, width),
/// the separate material runs inside it (`runs`, (start, exit) with start in [0, 2π); one run when the
/// material is contiguous), the axial depth, whether it cuts. The force acts on the runs only: an air gap
/// between a sliver and the main cut carries none.
struct PointCut {
  bool engaged = false;
  double phi_st = 0, phi_ex = 0, depth = 0, width = 0;
  std::vector<std::pair<double, double>> runs;
};

/// True if angle a lies in one of pc's material runs (in its window when it lists no runs: a Z-map
/// immersion, which knows only the window).
inline bool runs_hold(const PointCut& pc, double a) {
  if (pc.runs.empty()) return window_holds(pc.phi_st, pc.phi_ex, a);
  for (const auto& r : pc.runs)
    if (window_holds(r.first, r.second, a)) return true;
  return false;
}

/// Everything a single-point evaluation needs; reused along the path.
struct PointEvaluator {
  DeflectionModel model;
  DeflectionWorkspace ws;
  double radius;
  int profile_levels;
  WallSide side;

  PointEvaluator(const DeflectionModel& m, const cutter::Cutter& c, const PathOptions& o)
      : model(m), radius(c.radius), profile_levels(o.profile_levels), side(o.side) {}

  /// Deflection at the three levels (and the profile) for the cut `pc` with the feed direction
  /// x_c (unit, XY); fills row i of `out` given the wall normal n and offset C.
  void evaluate(const PointCut& pc, const Vec2& x_c, const Vec2& n, double C, Eigen::Index i, PathWallErrors& out) {
    out.width[i] = pc.width;
    out.depth[i] = pc.depth;
    out.phi_st[i] = pc.phi_st;
    out.phi_ex[i] = pc.phi_ex;
    out.engaged[i] = pc.engaged ? 1 : 0;
    int flags = 0;
    if (pc.engaged) {
      if (runs_hold(pc, 0.0)) flags |= 1;
      if (runs_hold(pc, pi)) flags |= 2;
    }
    out.wall_flags[i] = flags;
    if (!pc.engaged) {
      out.error.row(i).setConstant(-C);
      out.deflection.row(i).setZero();
      out.normal_deflection[i] = out.tangential_deflection[i] = 0.0;
      out.force.row(i).setZero();
      if (profile_levels > 0) out.profile.row(i).setConstant(-C);
      return;
    }
    model.force.axial_depth = pc.depth;
    const double st = wrap(pc.phi_st);
    model.force.engagement.phi_st = st;
    model.force.engagement.phi_ex = st + std::min(pc.phi_ex - pc.phi_st, two_pi);
    model.windows.clear();
    if (pc.runs.size() > 1)
      for (const auto& r : pc.runs)
        model.windows.push_back({r.first, r.first + std::min(r.second - r.first, two_pi)});
    ws.ensure(model);
    const Vec2 y_c(-x_c.y(), x_c.x());
    const VectorXd lv = deflection::cut_levels(pc.depth);
    const deflection::WallErrors w = deflection::wall_errors(model, ws, side, lv);
    for (int k = 0; k < 3; ++k) {
      const Vec2 d = w.deflection(k, 0) * x_c + w.deflection(k, 1) * y_c;
      out.error(i, k) = -C - d.dot(n);
      if (k == 1) {
        out.deflection.row(i) = d.transpose();
        out.normal_deflection[i] = d.dot(n);
        out.tangential_deflection[i] = d.dot(x_c);
        const Vec2 f = w.force(k, 0) * x_c + w.force(k, 1) * y_c;
        out.force.row(i) = f.transpose();
      }
    }
    if (profile_levels > 0) {
      VectorXd zs(profile_levels);
      for (int k = 0; k < profile_levels; ++k)
        zs[k] = profile_levels == 1 ? 0.0 : pc.depth * k / (profile_levels - 1);
      const deflection::WallErrors wp = deflection::wall_errors(model, ws, side, zs);
      for (int k = 0; k < profile_levels; ++k) {
        const Vec2 d = wp.deflection(k, 0) * x_c + wp.deflection(k, 1) * y_c;
        out.profile(i, k) = -C - d.dot(n);
      }
    }
  }
};

inline void size_result(PathWallErrors& r, Eigen::Index n, int profile_levels) {
  r.positions.resize(n, 3);
  r.error.resize(n, 3);
  r.deflection.resize(n, 2);
  r.normal_deflection.resize(n);
  r.tangential_deflection.resize(n);
  r.force.resize(n, 2);
  r.width.resize(n);
  r.depth.resize(n);
  r.phi_st.resize(n);
  r.phi_ex.resize(n);
  r.engaged.resize(n);
  r.wall_flags.resize(n);
  r.profile.resize(n, std::max(profile_levels, 0));
}

/// The polyline turns by more than this at a corner [rad] (30°): more than a sampled arc does.
inline constexpr double corner_turn = pi / 6.0;

/// True at an inner point i where the polyline turns by more than corner_turn.
inline bool is_corner(const Eigen::Ref<const Points3>& p, Eigen::Index i) {
  if (i <= 0 || i + 1 >= p.rows()) return false;
  const Vec2 in(p(i, 0) - p(i - 1, 0), p(i, 1) - p(i - 1, 1));
  const Vec2 out(p(i + 1, 0) - p(i, 0), p(i + 1, 1) - p(i, 1));
  if (in.norm() <= 1e-12 || out.norm() <= 1e-12) return false;
  return in.normalized().dot(out.normalized()) < std::cos(corner_turn);
}

/// Unit tangent of the nominal polyline at i in XY: the central difference, one-sided at the ends. At a
/// corner (the move out of i turns by more than corner_turn from the move into it) it is the outgoing
/// move's direction: a corner point starts the wall of the move it starts (a finish pass that begins
/// where its lead-in ends), so its wall normal and cutting frame are that move's, not the bisector's,
/// which would put the corner's wall point beside both walls and its offset across them.
inline Vec2 nominal_tangent(const Eigen::Ref<const Points3>& p, Eigen::Index i) {
  const Eigen::Index n = p.rows();
  const Eigen::Index a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
  if (is_corner(p, i)) return Vec2(p(b, 0) - p(i, 0), p(b, 1) - p(i, 1)).normalized();
  Vec2 t(p(b, 0) - p(a, 0), p(b, 1) - p(a, 1));
  if (t.norm() < 1e-12) t = Vec2(p(i, 0) - p(a, 0), p(i, 1) - p(a, 1));
  return t.normalized();
}

inline void check_path(const Eigen::Ref<const Points3>& nominal) {
  NETSHAPE_CHECK(nominal.rows() >= 2, "path.points", nominal.rows(), "must be at least 2 points");
  for (Eigen::Index i = 0; i < nominal.rows(); ++i)
    for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("path.points", nominal(i, k));
  for (Eigen::Index i = 1; i < nominal.rows(); ++i) {
    const double d = std::hypot(nominal(i, 0) - nominal(i - 1, 0), nominal(i, 1) - nominal(i - 1, 1));
    NETSHAPE_CHECK(d > 1e-9, "path.point", static_cast<double>(i),
                   "coincides in XY with the point before it (zero-length move)");
  }
}

/// Engaged window of the cutter at `tip` moving along x_c where `in_material(point)` says what is
/// material: angular scan at the probe height, the complement of the largest gap, edges bisected.
template <typename InMaterial>
PointCut scan_window(const cutter::Cutter& cutter, const Vec3& tip, const Vec2& x_c, const stock::ImmersionOptions& o,
                     const stock::ZMap& base, InMaterial in_material) {
  const int m = o.angles;
  const Vec2 y_c(-x_c.y(), x_c.x());
  const double R = cutter.radius;
  const double zp = tip.z() + o.probe_height;
  auto point = [&](double phi) {
    const Vec2 d = std::sin(phi) * x_c + std::cos(phi) * y_c;
    return Vec3(tip.x() + R * d.x(), tip.y() + R * d.y(), zp);
  };
  std::vector<char> in(m);
  int count = 0;
  for (int k = 0; k < m; ++k) count += (in[k] = in_material(point(two_pi * k / m))) ? 1 : 0;
  PointCut pc;
  if (count == 0) return pc;
  pc.engaged = true;
  double st, ex;
  if (count == m) {
    st = 0.0;
    ex = two_pi;
    pc.runs.emplace_back(0.0, two_pi);
  } else {
    // largest circular run of empty samples
    int best_len = 0, best_start = 0;
    for (int k = 0; k < m; ++k) {
      if (in[k]) continue;
      if (!in[(k - 1 + m) % m]) continue;  // not the start of a run
      int len = 0;
      while (len < m && !in[(k + len) % m]) ++len;
      if (len > best_len) {
        best_len = len;
        best_start = k;
      }
    }
    const int first_in = (best_start + best_len) % m;    // first engaged sample after the gap
    const int last_in = (best_start - 1 + m) % m;        // last engaged sample before the gap
    auto bisect = [&](double a_out, double b_in) {       // edge between an empty and an engaged angle
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (a_out + b_in);
        if (in_material(point(mid)))
          b_in = mid;
        else
          a_out = mid;
      }
      return b_in;
    };
    const double step = two_pi / m;
    st = bisect(first_in * step - step, first_in * step);
    ex = bisect(last_in * step + step, last_in * step);
    while (ex < st) ex += two_pi;
    // every run of material samples, from the first after the largest gap on; its edges bisected
    for (int k = 0; k < m;) {
      const int a = (first_in + k) % m;
      if (!in[a]) {
        ++k;
        continue;
      }
      int len = 0;
      while (k + len < m && in[(first_in + k + len) % m]) ++len;
      const int b = (a + len - 1) % m;
      const double rs = a == first_in ? st : bisect(a * step - step, a * step);
      double re = b == last_in ? ex : bisect(b * step + step, b * step);
      const double rs0 = wrap(rs);
      re = rs0 + wrap(re - rs);
      if (re - rs0 > 1e-12) pc.runs.emplace_back(rs0, re);
      k += len;
    }
  }
  // axial depth: material height above the tip along the engaged arc (pillar heights of the base),
  // capped at the flute length
  double depth = 0.0;
  for (int k = 0; k < m; ++k) {
    const double a = two_pi * k / m;
    if (!runs_hold(pc, a)) continue;
    const Vec3 p = point(a);
    const double h = base.cell_height(p.x(), p.y());
    if (std::isfinite(h)) depth = std::max(depth, h - tip.z());
  }
  depth = std::min(depth, cutter.flute_length);
  if (depth <= 1e-9) return PointCut{};
  pc.phi_st = st > pi ? st - two_pi : st;
  pc.phi_ex = pc.phi_st + (ex - st);
  pc.depth = depth;
  pc.width = R * (std::cos(pc.phi_st) - std::cos(pc.phi_ex));
  return pc;
}

/// Largest |error| at `level` over the points with active[i] ≠ 0 (every point when `active` is
/// empty); its index in *where. NaN counts as the worst.
inline double max_abs_level(const PathWallErrors& r, int level, int* where, const Eigen::VectorXi& active = {}) {
  double best = -1.0;
  int w = 0;
  for (Eigen::Index i = 0; i < r.error.rows(); ++i) {
    if (active.size() && !active[i]) continue;
    const double v = std::abs(r.error(i, level));
    if (!(v <= best)) {
      best = std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
      w = static_cast<int>(i);
    }
  }
  if (where) *where = w;
  return std::max(best, 0.0);
}

}  // namespace netshape::compensation::detail
