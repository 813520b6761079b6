#include "netshape/geometry/offset.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

void offset_points(const NurbsSurface& surface, const Eigen::Ref<const Points2>& uv, double distance,
                   Eigen::Ref<Points3> out, Eigen::Ref<Points3> normals, SurfaceWorkspace& ws) {
  NETSHAPE_CHECK_FINITE("distance", distance);
  NETSHAPE_CHECK(out.rows() == uv.rows(), "out.rows", out.rows(), "must equal uv.rows");
  if (normals.rows() > 0) {
    surface.evaluate(uv, out, normals, ws);
    out += distance * normals;
    return;
  }
  // no caller buffer for normals: evaluate in blocks into a small stack buffer
  constexpr int B = 64;
  Eigen::Matrix<double, B, 3, Eigen::RowMajor> nb;
  for (Eigen::Index k = 0; k < uv.rows(); k += B) {
    const Eigen::Index m = std::min<Eigen::Index>(B, uv.rows() - k);
    Eigen::Ref<Points3> o = out.middleRows(k, m);
    Eigen::Ref<Points3> n = nb.topRows(m);
    surface.evaluate(uv.middleRows(k, m), o, n, ws);
    o += distance * n;
  }
}

Points3 offset_points(const NurbsSurface& surface, const Eigen::Ref<const Points2>& uv, double distance) {
  SurfaceWorkspace ws = surface.make_workspace();
  Points3 out(uv.rows(), 3), n(uv.rows(), 3);
  offset_points(surface, uv, distance, out, n, ws);
  return out;
}

Points3 offset_grid(const NurbsSurface& surface, const Eigen::Ref<const VectorXd>& us,
                    const Eigen::Ref<const VectorXd>& vs, double distance) {
  NETSHAPE_CHECK_FINITE("distance", distance);
  SurfaceWorkspace ws = surface.make_workspace();
  Points3 out(us.size() * vs.size(), 3), n(us.size() * vs.size(), 3);
  surface.evaluate_grid(us, vs, out, n, ws);
  out += distance * n;
  return out;
}

}  // namespace netshape::geometry
