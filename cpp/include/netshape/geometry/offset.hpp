#pragma once
/// \file offset.hpp
/// Offset surface of a NURBS design surface (Yang & Kweon eq. 12):
///
///     O(u, v) = Q(u, v) + d · n(u, v)
///
/// with n the unit normal of eq. 15 (limit at poles, see NurbsSurface::normal) and d the signed offset
/// distance [mm] (positive along n). Yang & Kweon write f(d) for the offset implied by the tool tip; for a
/// ball end mill of radius R the centre of the ball lies on the offset at d = R (see cutter_location.hpp).

#include "netshape/core/types.hpp"
#include "netshape/geometry/nurbs_surface.hpp"

namespace netshape::geometry {

/// Offset points at scattered parameters uv (m, 2) into out (m, 3) [mm]; `normals` (m, 3) receives the
/// unit normals if it has rows. No allocation (except at degenerate normals).
void offset_points(const NurbsSurface& surface, const Eigen::Ref<const Points2>& uv, double distance,
                   Eigen::Ref<Points3> out, Eigen::Ref<Points3> normals, SurfaceWorkspace& ws);
/// Allocating form: (m, 3) offset points.
Points3 offset_points(const NurbsSurface& surface, const Eigen::Ref<const Points2>& uv, double distance);
/// Offset sampled on the grid us (a) × vs (b): (a · b, 3), row i · b + j.
Points3 offset_grid(const NurbsSurface& surface, const Eigen::Ref<const VectorXd>& us,
                    const Eigen::Ref<const VectorXd>& vs, double distance);

}  // namespace netshape::geometry
