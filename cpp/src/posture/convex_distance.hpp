#pragma once
// Certified distance bounds between a triangle and one solid of the cutter assembly (a frustum with flat ends,
// or a ball), for the interference checker. Private to cpp/src/posture.
//
// Frustum and triangle are convex, so their distance is the distance of the origin to the Minkowski difference
// C = T − F. GJK (Gilbert, Johnson, Keerthi 1988; van den Bergen, "Collision Detection in Interactive 3D
// Environments" §4.3) keeps a point v of C (upper bound |v|) and, from the support point w of C in the
// direction −v, the lower bound v·w / |v| (every x of C has v·x ≥ v·w): both are certified at every step, so
// the iteration can stop as soon as the question asked is answered.
//
// Frustum: points base + z·axis + ρ·u (u ⟂ axis unit, z ∈ [z0, z1], ρ ≤ r0 + (r1 − r0)(z − z0)/(z1 − z0)),
// the convex hull of its two end discs; its support in a direction d is the rim point of one end disc in the
// direction of d's component across the axis.

#include "netshape/core/types.hpp"

namespace netshape::detail {

struct Frustum {
  Vec3 base, axis;          ///< tip [mm] and unit axis
  double z0, z1, r0, r1;    ///< end heights from the tip and radii [mm], z1 > z0
};

/// Bounds lower ≤ distance ≤ upper [mm] (0 when they overlap) and the triangle point of the upper bound.
struct DistanceBounds {
  double lower, upper;
  Vec3 witness;
};

/// Distance bounds between the triangle (a, b, c) and the frustum. Iterates until lower ≥ far (the triangle
/// does not matter), upper < near (it certainly comes closer), or upper − lower ≤ tol [mm].
DistanceBounds triangle_frustum(const Vec3& a, const Vec3& b, const Vec3& c, const Frustum& f, double near,
                                double far, double tol);

/// Distance [mm] between the segment p0–p1 and the triangle (a, b, c) (0 when the segment pierces it): the least
/// of its endpoints to the triangle and of the triangle's edges to the segment. A frustum of largest radius r
/// about the segment lies within r of it, so this minus r is a lower bound of the frustum's distance.
double segment_triangle_distance(const Vec3& p0, const Vec3& p1, const Vec3& a, const Vec3& b, const Vec3& c);

/// Closest point of the triangle (a, b, c) to p (Ericson, "Real-Time Collision Detection" §5.1.5); `bary`
/// (optional) gets its barycentric weights of a, b, c.
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary = nullptr);

}  // namespace netshape::detail
