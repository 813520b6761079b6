#pragma once
/// \file cutter_location.hpp
/// Cutter-contact (CC) to cutter-location (CL) points for flat, ball and bull-nose end mills with a
/// general tool axis, and the signed distance from points to the cutter's solid (for gouge checks).
///
/// Every end mill is treated as a torus-ended solid of revolution: corner radius r (flat 0, ball R,
/// bull 0 < r < R) whose tube centres lie on the circle of radius R − r at height r above the tip.
/// The CL point is the tool TIP (centre of the tool's end face, z = 0 in the tool frame). With the
/// surface's unit normal n at the CC point pointing out of the material (towards the tool), unit axis a
/// (from the tip into the spindle) and e the unit projection of n onto the plane ⟂ a:
///
///     tip = CC + r·n + (R − r)·e − r·a
///
/// ball (r = R): tip = CC + R·n − R·a (the ball centre CC + R·n lies on the offset surface at d = R);
/// flat (r = 0): tip = CC + R·e (the rim touches the surface); where n ∥ a (e undefined) the end face
/// sits on the surface and tip = CC (e = 0). A normal facing away from the tool (n·a < 0) cannot be
/// reached from the tool side and is refused.

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"

namespace netshape::geometry {

/// CL (tool tip) for one CC point [mm]. normal and axis need not be unit (they are normalised).
Vec3 cc_to_cl(const cutter::Cutter& cutter, const Vec3& cc, const Vec3& normal, const Vec3& axis);
/// Many CC points: cc (m, 3), normals (m, 3) → out (m, 3). No allocation.
void cc_to_cl(const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& cc,
              const Eigen::Ref<const Points3>& normals, const Vec3& axis, Eigen::Ref<Points3> out);

/// Signed distance [mm] from each point (m, 3) to the cutter's solid (tip at `tip`, axis `axis`, the
/// body extending without end along +axis): negative inside, 0 on the surface, positive outside.
VectorXd cutter_signed_distance(const cutter::Cutter& cutter, const Vec3& tip, const Vec3& axis,
                                const Eigen::Ref<const Points3>& points);

}  // namespace netshape::geometry
