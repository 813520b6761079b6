// Tool-deflection wall error along a 2-D contour (netshape/compensation/deflection_compensation.hpp):
// wall normals and the per-point prediction in a Z-map stock.
#include "netshape/compensation/deflection_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/QR>

#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "netshape/stock/sweep.hpp"
#include "compensation/deflection_path_internal.hpp"

namespace netshape::compensation {

using deflection::DeflectionModel;
using deflection::DeflectionWorkspace;
using deflection::WallSide;
using namespace detail;

Points2 wall_normals(const Eigen::Ref<const Points3>& nominal, WallSide side) {
  check_path(nominal);
  const Eigen::Index n = nominal.rows();
  Points2 out(n, 2);
  const double s = side == WallSide::left ? 1.0 : -1.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec2 t = nominal_tangent(nominal, i);
    out(i, 0) = -s * t.y();
    out(i, 1) = s * t.x();
  }
  return out;
}

PathWallErrors path_wall_errors(const DeflectionModel& model, const cutter::Cutter& cutter, const stock::ZMap& stock,
                                const Eigen::Ref<const Points3>& nominal, const Eigen::Ref<const Points2>& normals,
                                const Eigen::Ref<const VectorXd>& offsets, const PathOptions& options) {
  options.validate();
  cutter.validate();
  model.beam.validate();
  check_path(nominal);
  const Eigen::Index n = nominal.rows();
  NETSHAPE_CHECK(normals.rows() == n, "normals.rows", normals.rows(), "must equal the number of path points");
  NETSHAPE_CHECK(offsets.size() == n, "offsets.size", offsets.size(), "must equal the number of path points");
  for (Eigen::Index i = 0; i < n; ++i) NETSHAPE_CHECK_FINITE("offsets", offsets[i]);
  NETSHAPE_CHECK(cutter.kind == cutter::CutterKind::flat, "cutter.kind", cutter::to_string(cutter.kind),
                 "must be flat (the deflection model is the flat end mill's)");
  PathWallErrors out;
  size_result(out, n, options.profile_levels);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.positions(i, 0) = nominal(i, 0) + offsets[i] * normals(i, 0);
    out.positions(i, 1) = nominal(i, 1) + offsets[i] * normals(i, 1);
    out.positions(i, 2) = nominal(i, 2);
  }
  PointEvaluator ev(model, cutter, options);
  if (options.exact_self_removal) {
    // the contour's own removal before point i: the flat end's discs swept along every earlier move,
    // found through a grid of the moves so that a point visits only the moves within reach
    auto pos = [&](Eigen::Index j) { return Vec2(out.positions(j, 0), out.positions(j, 1)); };
    const double R = cutter.radius;
    SweptIndex swept;
    swept.build(n, pos, R * (1.0 + 1e-9) + 1e-9);
    core::Progress progress("deflection", static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) {
      progress.tick(static_cast<std::size_t>(i));
      const Vec3 tip = out.positions.row(i).transpose();
      const Vec2 xc = nominal_tangent(nominal, i);
      const PointCut pc = scan_window(cutter, tip, xc, options.immersion, stock, [&](const Vec3& p) {
        const Vec2 q(p.x(), p.y());
        return material_at(stock, p) && !swept.near_before(q, i - 1, R, pos) &&
               !(i > 0 && in_last_sweep(q, pos(i - 1), pos(i), R));
      });
      ev.evaluate(pc, xc, Vec2(normals(i, 0), normals(i, 1)), offsets[i], i, out);
    }
    return out;
  }
  stock::ZMap map = stock;
  core::Progress progress("deflection", static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    progress.tick(static_cast<std::size_t>(i));
    const Vec3 tip = out.positions.row(i).transpose();
    const Vec2 xc = nominal_tangent(nominal, i);
    const stock::Immersion im = stock::immersion(map, cutter, tip, Vec3(xc.x(), xc.y(), 0.0), options.immersion);
    PointCut pc;
    if (im.engaged && im.axial_depth > 1e-9) {
      pc.engaged = true;
      pc.phi_st = im.phi_st;
      pc.phi_ex = im.phi_ex;
      pc.depth = im.axial_depth;
      pc.width = im.radial_depth;
    }
    ev.evaluate(pc, xc, Vec2(normals(i, 0), normals(i, 1)), offsets[i], i, out);
    const Vec3 from = i > 0 ? Vec3(out.positions.row(i - 1).transpose()) : tip;
    stock::sweep_line(map, cutter, from, tip);
  }
  return out;
}

Eigen::VectorXi wall_remains(const Eigen::Ref<const Points3>& wall, const Eigen::Ref<const VectorXd>& top,
                             const Eigen::Ref<const Eigen::VectorXi>& first_later,
                             const Eigen::Ref<const Points3>& path, const Eigen::Ref<const Eigen::VectorXi>& cutting,
                             double radius, double clearance) {
  const Eigen::Index n = wall.rows(), m = path.rows();
  NETSHAPE_CHECK(top.size() == n, "top.size", top.size(), "must equal the number of wall points");
  NETSHAPE_CHECK(first_later.size() == n, "first_later.size", first_later.size(),
                 "must equal the number of wall points");
  NETSHAPE_CHECK(cutting.size() == m, "cutting.size", cutting.size(), "must equal the number of path rows");
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "radius", radius, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("clearance", clearance);
  NETSHAPE_CHECK(clearance >= 0.0 && clearance < radius, "clearance", clearance, "must be in [0, radius) [mm]");
  for (Eigen::Index j = 0; j < m; ++j)
    for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("path", path(j, k));
  Eigen::VectorXi out = Eigen::VectorXi::Ones(n);
  if (m < 2) return out;
  auto xy = [&](Eigen::Index j) { return Vec2(path(j, 0), path(j, 1)); };
  SweptIndex moves;
  moves.build(m, xy, radius);
  const double r = radius - clearance;
  for (Eigen::Index k = 0; k < n; ++k) {
    NETSHAPE_CHECK_FINITE("wall", wall(k, 0));
    NETSHAPE_CHECK_FINITE("wall", wall(k, 1));
    const double zt = top[k] - 1e-9;
    auto cuts_here = [&](Eigen::Index j) {
      return j >= 1 && cutting[j] != 0 && std::min(path(j - 1, 2), path(j, 2)) < zt;
    };
    if (moves.near_from(Vec2(wall(k, 0), wall(k, 1)), std::max<Eigen::Index>(first_later[k], 1), r, xy, cuts_here))
      out[k] = 0;
  }
  return out;
}

DrawingOffsets drawing_offsets(const Eigen::Ref<const Points3>& points, const Eigen::Ref<const Points3>& drawing,
                               WallSide side, double window) {
  check_path(drawing);
  NETSHAPE_CHECK_FINITE("window", window);
  NETSHAPE_CHECK(window > 0.0, "window", window, "must be positive [mm]");
  const Eigen::Index n = points.rows(), m = drawing.rows();
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("points", points(i, k));
  VectorXd arc(m);
  arc[0] = 0.0;
  for (Eigen::Index j = 1; j < m; ++j)
    arc[j] = arc[j - 1] + std::hypot(drawing(j, 0) - drawing(j - 1, 0), drawing(j, 1) - drawing(j - 1, 1));
  const double sgn = side == WallSide::left ? 1.0 : -1.0;
  DrawingOffsets out;
  out.offsets.resize(n);
  out.normals.resize(n, 2);
  out.s.resize(n);
  out.foot_distance.resize(n);
  Eigen::Index seg = 1;  // segment j joins drawing rows j − 1 and j
  double s_prev = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec2 p(points(i, 0), points(i, 1));
    const double moved = i > 0 ? std::hypot(points(i, 0) - points(i - 1, 0), points(i, 1) - points(i - 1, 1)) : arc[m - 1];
    const double s_max = s_prev + moved + window;
    double best = std::numeric_limits<double>::infinity(), best_t = 0.0;
    Eigen::Index best_j = seg;
    for (Eigen::Index j = seg; j < m && (j == seg || arc[j - 1] <= s_max); ++j) {
      const Vec2 a(drawing(j - 1, 0), drawing(j - 1, 1)), b(drawing(j, 0), drawing(j, 1));
      const Vec2 ab = b - a;
      const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d2 = (a + t * ab - p).squaredNorm();
      if (d2 < best - 1e-18) {
        best = d2;
        best_j = j;
        best_t = t;
      }
    }
    const Vec2 a(drawing(best_j - 1, 0), drawing(best_j - 1, 1)), b(drawing(best_j, 0), drawing(best_j, 1));
    const Vec2 t_hat = (b - a).normalized();
    const Vec2 n_seg(-sgn * t_hat.y(), sgn * t_hat.x());
    const Vec2 foot = a + best_t * (b - a);
    const Vec2 d = p - foot;
    Vec2 nrm = n_seg;
    if ((best_t <= 0.0 || best_t >= 1.0) && d.norm() > 1e-12 && std::abs(d.normalized().dot(t_hat)) > 1e-9)
      nrm = d.normalized() * (d.dot(n_seg) >= 0.0 ? 1.0 : -1.0);  // foot at a corner: along the chord to it
    out.offsets[i] = d.dot(nrm);
    out.normals(i, 0) = nrm.x();
    out.normals(i, 1) = nrm.y();
    out.s[i] = arc[best_j - 1] + best_t * (arc[best_j] - arc[best_j - 1]);
    out.foot_distance[i] = d.norm();
    seg = best_j;
    s_prev = out.s[i];
  }
  return out;
}

}  // namespace netshape::compensation
