#pragma once
/// \file assembly.hpp
/// Ball-end cutter assembly (ball + shank + holder, solids of revolution about the tool axis) and its
/// interference with an obstacle triangle mesh (CGAL AABB tree of geometry::TriangleMesh).
///
/// Tool frame: tip at z = 0 (lowest point of the ball), unit axis a from the tip into the spindle.
/// The assembly is the union of three capsules (segment ⊕ ball) on the axis:
///
///     ball   : centre z = R                        radius R       (R = ball_radius)
///     shank  : segment z ∈ [R, shank_length]       radius r_s     (r_s = shank_radius ≤ R … any > 0)
///     holder : segment z ∈ [shank_length + r_h, holder_length] radius r_h
///
/// Lengths are measured from the tip. The shank is a cylinder from the ball centre with a rounded end that
/// reaches r_s past shank_length (conservative); the holder is a cylinder with a hemispherical nose whose
/// lowest point is at shank_length, and a rounded far end reaching r_h past holder_length (conservative).
///
/// Interference gap: g = min over parts of (dist(axis segment of the part, mesh) − part radius) [mm]; the
/// posture collides when g < clearance. dist(segment, mesh) is bounded by branch and bound on the
/// segment with the 1-Lipschitz point distance of the AABB tree: an interval of half-length h whose
/// midpoint is at distance d holds no point closer than d − h. Intervals are split until the answer is
/// certain or h < tolerance; undecided intervals count as colliding, so "free" is always certified.

#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/geometry/triangle_mesh.hpp"

namespace netshape::posture {

/// Radii and lengths of a ball-end cutter assembly [mm]. Plain value type; validate() after filling.
struct CutterAssembly {
  double ball_radius = 2.0;     ///< R [mm]
  double shank_radius = 2.0;    ///< r_s [mm]
  double shank_length = 30.0;   ///< tip to the end of the shank (start of the holder) [mm], > R
  double holder_radius = 8.0;   ///< r_h [mm]
  double holder_length = 70.0;  ///< tip to the end of the holder [mm], ≥ shank_length + holder_radius

  /// Throws std::invalid_argument naming the field and the value.
  void validate() const;
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
  /// When it does and `witness` is given, *witness is the axis point of least gap [mm].
  bool collides(const Vec3& tip, const Vec3& axis, Vec3* witness = nullptr) const;
  /// The interference gap g [mm] to within the tolerance (negative: the mesh penetrates the assembly).
  double gap(const Vec3& tip, const Vec3& axis) const;
  /// collides() for many postures: tips (n, 3), axes (n, 3) → (n) flags.
  std::vector<bool> collides(const Eigen::Ref<const Points3>& tips, const Eigen::Ref<const Points3>& axes) const;
  /// Closest point of the mesh to p [mm].
  Vec3 closest_point(const Vec3& p) const;

 private:
  /// Branch and bound: least (distance − radius) over the parts, stopping early once it is certainly
  /// below `stop_below` (collides) or certainly ≥ `prune_at` everywhere. Returns the bound found and the
  /// witness axis point.
  double search(const Vec3& tip, const Vec3& axis, double stop_below, double prune_at, Vec3* witness) const;

  geometry::TriangleMesh mesh_;
  CutterAssembly assembly_;
  double clearance_ = 0.0;
  double tolerance_ = 1e-3;
};

}  // namespace netshape::posture
