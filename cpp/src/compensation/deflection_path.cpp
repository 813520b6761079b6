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
    const Eigen::Index a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
    Vec2 t(nominal(b, 0) - nominal(a, 0), nominal(b, 1) - nominal(a, 1));
    if (t.norm() < 1e-12) t = Vec2(nominal(i, 0) - nominal(a, 0), nominal(i, 1) - nominal(a, 1));
    t.normalize();
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
    auto pos = [&](Eigen::Index j) { return Vec2(out.positions(j, 0), out.positions(j, 1)); };
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 tip = out.positions.row(i).transpose();
      const Vec2 xc = nominal_tangent(nominal, i);
      const Vec2 Pi = pos(i);
      const PointCut pc = scan_window(cutter, tip, xc, options.immersion, stock, [&](const Vec3& p) {
        return stock.is_material(p) && !removed_by_earlier(Vec2(p.x(), p.y()), i, Pi, cutter.radius, pos);
      });
      ev.evaluate(pc, xc, Vec2(normals(i, 0), normals(i, 1)), offsets[i], i, out);
    }
    return out;
  }
  stock::ZMap map = stock;
  for (Eigen::Index i = 0; i < n; ++i) {
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

}  // namespace netshape::compensation
