#pragma once
/// \file assembly.hpp
/// Ball-end cutter assembly (ball + shank + holder, solids of revolution about the tool axis) and its
/// interference with an obstacle triangle mesh.
///
/// Tool frame: tip at z = 0 (lowest point of the ball), unit axis a from the tip into the spindle, ρ the
/// distance from the axis. Lengths are measured from the tip. The assembly is the union of
///
///     ball   : sphere of centre z = R, radius R                               (R = ball_radius)
///     shank  : cylinder z ∈ [R, shank_length], radius r_s, flat ends
///     holder : cylinder z ∈ [shank_length, holder_length], radius r_h, a flat face at shank_length;
///              or, with holder_profile = (z_0, r_0) … (z_k, r_k) (z_0 = shank_length, z non-decreasing),
///              the frustums between consecutive pairs (a shrink-fit taper, a neck, steps where z repeats).
///
/// The checked solid is exactly this union: nothing is rounded or left out (the holder's flat face out to
/// its radius is in it).
///
/// Interference gap g = distance between the solid and the mesh [mm] (0 when they overlap); a posture
/// collides when g < clearance. The mesh's triangles sit in a bounding-volume hierarchy; a box of it is
/// skipped when a lower bound of its distance to a part (ball: exact point–box distance − R; frustum: the
/// larger of the box–box distance to the part's bounding box and the distance of the box's bounding sphere to
/// the part's axis segment minus its largest radius) reaches the threshold asked. A triangle against the ball
/// is exact (closest point to the centre, minus R); against a frustum, GJK on the two convex sets gives a
/// certified lower and upper bound at every step (cpp/src/posture/convex_distance.hpp), refined until they decide the
/// question or lie within the tolerance of each other. Undecided at the tolerance counts as colliding, so
/// "free" is certified: the gap of a free posture is ≥ clearance (up to rounding, ~1e-9 mm).
/// The triangle that decided the last collision is tried first in the next query (neighbouring postures
/// mostly collide with the same triangle).

#include <algorithm>
#include <atomic>
#include <memory>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/geometry/triangle_mesh.hpp"

namespace netshape::detail {
struct TriangleBvh;
}

namespace netshape::posture {

/// A frustum of the profile: z ∈ [z0, z1] from the tip, radius linear from r0 (at z0) to r1 (at z1) [mm].
struct ProfileSection {
  double z0, z1, r0, r1;
  double radius(double z) const { return z1 > z0 ? r0 + (r1 - r0) * (z - z0) / (z1 - z0) : std::max(r0, r1); }
};

/// Radii and lengths of a ball-end cutter assembly [mm]. Plain value type; validate() after filling.
struct CutterAssembly {
  double ball_radius = 2.0;     ///< R [mm]
  double shank_radius = 2.0;    ///< r_s [mm]
  double shank_length = 30.0;   ///< tip to the end of the shank (start of the holder) [mm], > R
  double holder_radius = 8.0;   ///< r_h [mm] (cylinder holder; ignored with a holder_profile)
  double holder_length = 70.0;  ///< tip to the end of the holder [mm], > shank_length (ignored with a profile)
  /// (k, 2) pairs (z [mm] from the tip, r [mm]) of a holder profile; empty = the flat-faced cylinder.
  Points2 holder_profile;

  /// Throws std::invalid_argument naming the field and the value.
  void validate() const;
  /// The shank and the holder as frustums, bottom to top (the ball is separate).
  std::vector<ProfileSection> sections() const;
  /// Largest distance of a point of the solid from the tip [mm] (lever arm of a rotation about the tip).
  double reach() const;
  /// Exact distance [mm] from the point (z, ρ) of the meridian half-plane to the solid (0 inside it).
  double distance(double z, double rho) const;
};

/// Interference queries of one assembly against one obstacle mesh. Immutable; const queries are
/// thread-safe (the mesh is).
class InterferenceChecker {
 public:
  /// clearance ≥ 0 [mm]: the safety distance the assembly must keep from the mesh. tolerance > 0 [mm]:
  /// resolution of the distance bounds (default 1e-3 mm): a gap within it of the clearance may count as colliding.
  InterferenceChecker(geometry::TriangleMesh obstacles, CutterAssembly assembly, double clearance,
                      double tolerance = 1e-3);

  const geometry::TriangleMesh& obstacles() const noexcept { return mesh_; }
  const CutterAssembly& assembly() const noexcept { return assembly_; }
  double clearance() const noexcept { return clearance_; }
  double tolerance() const noexcept { return tolerance_; }

  /// Whether the assembly with its tip at `tip` and unit axis `axis` comes closer than the clearance.
  /// When it does and `witness` is given, *witness is the mesh point of least gap found [mm].
  bool collides(const Vec3& tip, const Vec3& axis, Vec3* witness = nullptr) const;
  /// The interference gap g [mm] to within the tolerance (0: the mesh touches or penetrates the assembly).
  double gap(const Vec3& tip, const Vec3& axis) const;
  /// collides() for many postures: tips (n, 3), axes (n, 3) → (n) flags.
  std::vector<bool> collides(const Eigen::Ref<const Points3>& tips, const Eigen::Ref<const Points3>& axes) const;
  /// Three-way test with a margin ≥ 0 [mm]: +1 if the gap is certainly ≥ clearance + margin, −1 if it is
  /// certainly < clearance, 0 if undecided at the resolution max(tolerance, margin / 4). (The between-point
  /// check asks whether a posture is free by the largest displacement of a sub-step.)
  int clear_by(const Vec3& tip, const Vec3& axis, double margin) const;
  /// Closest point of the mesh to p [mm].
  Vec3 closest_point(const Vec3& p) const;
  /// Frustum–triangle GJK runs of all queries so far (a measure of the work, shared by copies).
  long long gjk_runs() const noexcept { return gjk_runs_->load(std::memory_order_relaxed); }

 private:
  struct Outcome {
    double upper;  ///< least upper bound of a triangle's distance found [mm]
    int state;     ///< −1 some triangle certainly below `near`, 0 some undecided below `far`, +1 none below `far`
    Vec3 witness;  ///< mesh point of `upper`
  };
  /// Traversal of the hierarchy (see the file comment). near: a triangle certainly closer decides −1 (the
  /// search stops unless `least`); far: triangles certainly at least this far are skipped; tol: resolution of
  /// a triangle's bounds; least: go on to the least distance (the witness, the gap).
  Outcome search(const Vec3& tip, const Vec3& axis, double near, double far, double tol, bool least) const;

  geometry::TriangleMesh mesh_;
  CutterAssembly assembly_;
  std::vector<ProfileSection> sections_;
  std::shared_ptr<const detail::TriangleBvh> bvh_;
  std::shared_ptr<std::atomic<int>> last_hit_;  ///< triangle of the last collision (a hint; −1 none)
  std::shared_ptr<std::atomic<long long>> gjk_runs_;  ///< see gjk_runs()
  double clearance_ = 0.0;
  double tolerance_ = 1e-3;
};

}  // namespace netshape::posture
