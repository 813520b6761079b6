#pragma once
/// \file triangle_mesh.hpp
/// Triangle mesh with a CGAL AABB tree built once, queried many times: unsigned distance, closest
/// point (with the face it lies on), first intersection of rays and segments, batched over (n, 3)
/// arrays with the loop in C++. CGAL stays in triangle_mesh.cpp (pimpl); this header needs only Eigen.
/// Copies share the (immutable) tree. Queries are const and thread-safe.

#include <cstdint>
#include <memory>

#include "netshape/core/types.hpp"

namespace netshape::geometry {

/// (m, 3) row-major vertex indices of triangles.
using Faces = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// Result arrays of a batched closest-point query, one row per query point.
struct ClosestPoints {
  Points3 points;              ///< (n, 3) closest points on the mesh [mm]
  VectorXd distances;          ///< (n) distances [mm]
  Eigen::VectorXi faces;       ///< (n) index of the face holding the closest point
};

/// Result arrays of a batched ray / segment query, one row per query.
struct RayHits {
  VectorXd t;                  ///< (n) parameter of the first hit: distance along the unit ray [mm], or
                               ///<     fraction of the segment in [0, 1]; NaN where nothing is hit
  Points3 points;              ///< (n, 3) first hit point [mm] (NaN where none)
  Eigen::VectorXi faces;       ///< (n) face index hit, −1 where none
};

class TriangleMesh {
 public:
  /// vertices (v, 3) [mm], faces (m, 3) indices into vertices. Validates (finite vertices, indices in
  /// range, at least one non-degenerate triangle) and builds the AABB tree. Zero-area triangles are kept
  /// in the arrays but left out of the tree (they cannot be the unique closest feature).
  TriangleMesh(Points3 vertices, Faces faces);
  /// A triangle soup: corners (3 m, 3), rows 3k, 3k + 1, 3k + 2 form triangle k.
  static TriangleMesh from_triangles(const Eigen::Ref<const Points3>& corners);

  TriangleMesh(const TriangleMesh&) = default;
  TriangleMesh(TriangleMesh&&) noexcept = default;
  TriangleMesh& operator=(const TriangleMesh&) = default;
  TriangleMesh& operator=(TriangleMesh&&) noexcept = default;
  ~TriangleMesh();

  const Points3& vertices() const noexcept;
  const Faces& faces() const noexcept;
  Eigen::Index face_count() const noexcept;
  /// Total area [mm²].
  double area() const noexcept;
  /// Axis-aligned bounding box corners [mm].
  Vec3 bbox_min() const noexcept;
  Vec3 bbox_max() const noexcept;
  /// Unit face normals (m, 3) from the vertex order (right-hand rule); zero rows for degenerate faces.
  Points3 face_normals() const;

  /// Unsigned distance of each point (n, 3) to the mesh [mm] into out (n). No allocation.
  void distance(const Eigen::Ref<const Points3>& points, Eigen::Ref<VectorXd> out) const;
  VectorXd distance(const Eigen::Ref<const Points3>& points) const;
  /// Closest points, distances and faces for each query point.
  ClosestPoints closest_points(const Eigen::Ref<const Points3>& points) const;
  /// First hit of rays origin + s·unit(direction), s ≥ 0 (t = s [mm]).
  RayHits ray_hits(const Eigen::Ref<const Points3>& origins, const Eigen::Ref<const Points3>& directions) const;
  /// First hit (nearest to a) of segments a → b (t in [0, 1]).
  RayHits segment_hits(const Eigen::Ref<const Points3>& a, const Eigen::Ref<const Points3>& b) const;
  /// Whether each segment a → b touches the mesh at all (cheaper than segment_hits).
  Eigen::Matrix<bool, Eigen::Dynamic, 1> segments_intersect(const Eigen::Ref<const Points3>& a,
                                                           const Eigen::Ref<const Points3>& b) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace netshape::geometry
