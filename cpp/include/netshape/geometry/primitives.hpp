#pragma once
/// \file primitives.hpp
/// Exact rational NURBS for standard shapes (Piegl & Tiller §7.5 A7.1, §8.5 A8.1): circular arcs,
/// surfaces of revolution, bilinear patches. Useful as design surfaces and as exact test cases.

#include "netshape/core/types.hpp"
#include "netshape/geometry/nurbs_curve.hpp"
#include "netshape/geometry/nurbs_surface.hpp"

namespace netshape::geometry {

/// Circular arc of radius r [mm] about `center` in the plane spanned by unit x_axis, y_axis, from angle
/// `start` to `end` [rad] (end > start, end − start ≤ 2π), measured from x_axis towards y_axis.
/// Degree 2, one rational segment per ≤ 90° (A7.1); parameter domain [0, 1].
NurbsCurve circular_arc(const Vec3& center, const Vec3& x_axis, const Vec3& y_axis, double radius, double start,
                        double end);

/// Surface of revolution of `profile` about the axis through `axis_point` along `axis_direction`, turned
/// by `angle` [rad] (0 < angle ≤ 2π, right-handed about the axis) (A8.1). u follows the profile, v the
/// turning (domain [0, 1]). Profile points on the axis give poles (coincident control points).
NurbsSurface revolve(const NurbsCurve& profile, const Vec3& axis_point, const Vec3& axis_direction, double angle);

/// Bilinear patch through four corners: S(0,0) = p00, S(1,0) = p10, S(0,1) = p01, S(1,1) = p11 [mm].
NurbsSurface bilinear(const Vec3& p00, const Vec3& p10, const Vec3& p01, const Vec3& p11);

}  // namespace netshape::geometry
