#pragma once
// Private pieces shared by the deflection prediction along a path (deflection_path.cpp) and its
// compensation (deflection_compensation.cpp): the engagement scan, the single-point evaluator and
// result helpers.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
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

/// Material of the stock before the contour at p, read from the Z-map's bilinear surface (height_at)
/// rather than its cells: a wall the stock already has (a pre-cut, an earlier pass) then moves
/// continuously with the point instead of in steps of one cell, so the engagement, the deflection and
/// the compensated offsets are continuous along the path, as the real wall is.
inline bool material_at(const stock::ZMap& z, const Vec3& p) {
  const double h = z.height_at(p.x(), p.y());
  return p.z() >= z.bottom() && p.z() < h;  // false outside the map (h NaN)
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

/// Engagement of one point: the window, the axial depth, whether it cuts.
struct PointCut {
  bool engaged = false;
  double phi_st = 0, phi_ex = 0, depth = 0, width = 0;
};

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
      if (window_holds(pc.phi_st, pc.phi_ex, 0.0)) flags |= 1;
      if (window_holds(pc.phi_st, pc.phi_ex, pi)) flags |= 2;
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

/// Unit central-difference tangent of the nominal polyline at i (one-sided at the ends), in XY.
inline Vec2 nominal_tangent(const Eigen::Ref<const Points3>& p, Eigen::Index i) {
  const Eigen::Index n = p.rows();
  const Eigen::Index a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
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
  }
  // axial depth: material height above the tip along the engaged arc (pillar heights of the base),
  // capped at the flute length
  double depth = 0.0;
  for (int k = 0; k < m; ++k) {
    const double a = two_pi * k / m;
    if (!window_holds(st, ex, a)) continue;
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
