#pragma once
/// \file assembly.hpp
/// Ball-end cutter assembly (ball + shank + holder, solids of revolution about the tool axis) and its
/// interference with an obstacle triangle mesh (CGAL AABB tree of geometry::TriangleMesh).
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
/// Interference gap g = distance between the solid and the mesh [mm] (≤ 0: they overlap); a posture
/// collides when g < clearance. Branch and bound over pieces of the solid: a piece is a slab
/// z ∈ [z_c − h, z_c + h] of one part, either the whole disc ρ ≤ ρ_1 (centre on the axis) or a cell
/// ρ ∈ [ρ_0, ρ_1], ψ ∈ [ψ_c − δ, ψ_c + δ] of it (centre at ρ_m = (ρ_0 + ρ_1)/2, ψ_c), with ρ_1 ≥ the part's
/// radius over the slab. Every point of the piece lies within b of its centre c, b² = h² + max over
/// ρ ∈ {ρ_0, ρ_1} of (ρ² + ρ_m² − 2ρρ_m cos δ) (h² + ρ_1² for the disc), so with d = dist(c, mesh) (the
/// AABB tree's point distance) no mesh point is closer to the piece than d − b (the lower bound). The
/// closest mesh point q to c gives the upper bound: the exact distance from q to the solid, computed in
/// the meridian plane (z, ρ). Pieces are split (z while h ≥ ρ_1 / 4, then a disc into an inner disc and
/// eight outer cells, a cell along its longest extent) until the answer is certain or b < tolerance;
/// undecided pieces (or more than 20 000 per query) count as colliding, so "free" is always certified. The ball is exact: d − R.

#include <algorithm>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/geometry/triangle_mesh.hpp"

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
  /// resolution of the branch and bound (default 1e-3 mm).
  InterferenceChecker(geometry::TriangleMesh obstacles, CutterAssembly assembly, double clearance,
                      double tolerance = 1e-3);

  const geometry::TriangleMesh& obstacles() const noexcept { return mesh_; }
  const CutterAssembly& assembly() const noexcept { return assembly_; }
  double clearance() const noexcept { return clearance_; }
  double tolerance() const noexcept { return tolerance_; }

  /// Whether the assembly with its tip at `tip` and unit axis `axis` comes closer than the clearance.
  /// When it does and `witness` is given, *witness is the mesh point of least gap found [mm].
  bool collides(const Vec3& tip, const Vec3& axis, Vec3* witness = nullptr) const;
  /// The interference gap g [mm] to within the tolerance (negative: the mesh penetrates the assembly).
  double gap(const Vec3& tip, const Vec3& axis) const;
  /// collides() for many postures: tips (n, 3), axes (n, 3) → (n) flags.
  std::vector<bool> collides(const Eigen::Ref<const Points3>& tips, const Eigen::Ref<const Points3>& axes) const;
  /// Three-way test with a margin ≥ 0 [mm]: +1 if the gap is certainly ≥ clearance + margin, −1 if it is
  /// certainly < clearance, 0 if undecided at the resolution max(tolerance, margin / 4). (The between-point
  /// check asks whether a posture is free by the largest displacement of a sub-step.)
  int clear_by(const Vec3& tip, const Vec3& axis, double margin) const;
  /// Closest point of the mesh to p [mm].
  Vec3 closest_point(const Vec3& p) const;

 private:
  struct Outcome {
    double upper;  ///< least exact distance of a mesh point found [mm]
    int state;     ///< −1 below stop_below, +1 every piece ≥ prune_at, 0 undecided at the resolution
    Vec3 witness;  ///< mesh point of `upper`
  };
  /// Branch and bound over the pieces (see the file comment). stop_below: stop once a mesh point is
  /// certainly closer; prune_at: drop pieces whose lower bound reaches it; resolution: smallest piece.
  Outcome search(const Vec3& tip, const Vec3& axis, double stop_below, double prune_at, double resolution) const;

  geometry::TriangleMesh mesh_;
  CutterAssembly assembly_;
  double clearance_ = 0.0;
  double tolerance_ = 1e-3;
};

}  // namespace netshape::posture
