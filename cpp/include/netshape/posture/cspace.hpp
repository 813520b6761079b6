#pragma once
/// \file cspace.hpp
/// C-space of the tool posture at one cutter-contact (CC) point and the MC-space move.
///
/// Frame at a CC point: n the unit surface normal (out of the material, towards the tool), f the feed
/// direction projected onto the tangent plane (unit), b = n × f (the "left" side). A posture P = (θ, φ):
/// tilt θ ∈ [0, θ_max] from n, rotation φ ∈ (−π, π] about n measured from f towards b [rad]:
///
///     T(θ, φ) = cos θ·n + sin θ·(cos φ·f + sin φ·b)
///
/// For a ball end mill of radius R the ball centre O = CC + R·n does not depend on the posture, and the
/// tip (lowest point of the ball along the axis) is O − R·T. The C-space is drawn polar: a posture is the
/// point (θ cos φ, θ sin φ) of the plane, and distances between postures are measured there [rad].
///
/// C-obstacles: CA1 = postures that collide with an obstacle on the left (the mesh point nearest the
/// colliding part of the axis lies at (q − CC)·b > 0), CA2 = on the right. Their boundaries are found on
/// a polar grid (rays of constant φ every phi_step, rings of constant θ every theta_step): every grid
/// edge whose two ends differ in state is bisected to the angular tolerance (the boundary point lies
/// within tolerance/2 of the true boundary along that edge, measured in the polar plane).
///
/// MC-space (Park, Jung, Hwang, Jung, "A theoretical consideration for continuity control of cutter
/// posture", Proc. KSPE Conference, §2 steps 1–4): P_a = the nearest boundary point of CA1, P_b = the nearest of
/// CA2, M = (P_a + P_b)/2, for every posture, colliding or not. An empty C-obstacle is replaced by the
/// tilt limit on its side (θ_max at φ = +π/2 for CA1, −π/2 for CA2), so with no obstacle M = 0 (the
/// normal posture).

#include <cstdint>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/posture/assembly.hpp"

namespace netshape::posture {

/// Orthonormal frame at a CC point.
struct PostureFrame {
  Vec3 cc = Vec3::Zero();        ///< CC point [mm]
  Vec3 normal = Vec3::UnitZ();   ///< n
  Vec3 feed = Vec3::UnitX();     ///< f (⟂ n)
  Vec3 left = Vec3::UnitY();     ///< b = n × f

  /// Builds the frame; throws std::invalid_argument naming `field` (e.g. "CC point 7") if the normal is
  /// zero or not finite or the feed is parallel to the normal.
  static PostureFrame make(const Vec3& cc, const Vec3& normal, const Vec3& feed, const char* field = "CC point");
  /// Unit axis of posture (θ, φ) [rad].
  Vec3 axis(double theta, double phi) const;
  /// (θ, φ) [rad] of a unit axis.
  Vec2 posture(const Vec3& axis) const;
};

/// Point of the polar C-space plane of (θ, φ): (θ cos φ, θ sin φ) [rad], and back.
Vec2 to_plane(const Vec2& posture);
Vec2 from_plane(const Vec2& point);

/// Sampling of the C-space [rad].
struct CSpaceOptions {
  double theta_max = 1.0471975511965976;    ///< largest tilt (60°)
  double theta_step = 0.08726646259971647;  ///< ring spacing (5°)
  double phi_step = 0.17453292519943295;    ///< ray spacing (10°)
  double tolerance = 8.726646259971648e-4;  ///< bisection tolerance of the boundaries (0.05°)
  void validate() const;
};

/// State of a posture: free, in CA1 (left obstacle) or in CA2 (right obstacle).
enum class PostureState : std::int8_t { free = 0, ca1 = 1, ca2 = 2 };

/// A point of a C-obstacle boundary.
struct BoundaryPoint {
  double theta, phi;   ///< posture [rad]
  int obstacle;        ///< 1 (CA1) or 2 (CA2)
};

/// The C-space of one CC point.
struct CSpace {
  PostureFrame frame;
  CSpaceOptions options;
  int count_theta = 0, count_phi = 0;          ///< grid size: θ_k = k·theta_step (k < count_theta), φ_j = −π + j·phi_step
  std::vector<PostureState> states;            ///< (count_phi, count_theta), row j = ray φ_j
  std::vector<BoundaryPoint> boundary;         ///< bisected boundary points of CA1 and CA2
  int checks = 0;                              ///< interference checks spent

  double theta(int k) const { return k * options.theta_step; }
  double phi(int j) const;
  PostureState state(int j, int k) const { return states[static_cast<std::size_t>(j * count_theta + k)]; }
  /// MC-space posture M (θ, φ) for posture p (θ, φ) [rad].
  Vec2 mc_posture(const Vec2& p) const;
  /// Nearest boundary point of obstacle 1 or 2 to p in the polar plane (the tilt-limit stand-in if empty).
  Vec2 nearest_boundary(const Vec2& p, int obstacle) const;
};

/// State of posture (θ, φ) at `frame` for a ball end mill (tip = O − R·T).
PostureState classify(const InterferenceChecker& checker, const PostureFrame& frame, double theta, double phi);

/// Grid, states and bisected boundaries of the C-space at one CC point. Throws std::invalid_argument
/// naming `field` if no grid posture is free (the tool cannot reach the point).
CSpace compute_cspace(const InterferenceChecker& checker, const PostureFrame& frame, const CSpaceOptions& options,
                      const char* field = "CC point");

/// Repair of a posture p (θ, φ) [rad] that collides or tilts beyond θ_max: the segment of the polar plane from
/// p to the nearest free grid posture of `cs` is bisected to the tolerance and its free end returned (the
/// smallest move found along that segment). `checks` is increased by the interference checks spent.
Vec2 repair_posture(const InterferenceChecker& checker, const CSpace& cs, const Vec2& p, long& checks);

}  // namespace netshape::posture
