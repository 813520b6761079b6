#pragma once
// Bounding-volume hierarchy of the obstacle triangles for the interference checker: axis-aligned boxes, split at
// the median of the longest extent of the triangle centroids, leaves of up to 4 triangles. Private to
// cpp/src/posture; built once per checker, read-only afterwards (thread-safe).

#include <cstdint>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/geometry/triangle_mesh.hpp"

namespace netshape::detail {

struct BvhNode {
  Vec3 lo, hi;       ///< box [mm]
  int first, count;  ///< leaf: triangles [first, first + count); count = 0 for an inner node
  int left, right;   ///< children of an inner node
};

struct TriangleBvh {
  std::vector<Vec3> a, b, c;  ///< corners of the non-degenerate triangles, in leaf order [mm]
  std::vector<Vec3> lo, hi;   ///< bounding box of each triangle [mm]
  std::vector<Vec3> m;        ///< centroid (a + b + c) / 3 of each triangle [mm]
  std::vector<double> r;      ///< largest distance of a corner from the centroid [mm]
  std::vector<Vec3> n;        ///< unit normal of each triangle's plane
  std::vector<double> d;      ///< offset n · a of each triangle's plane [mm]
  std::vector<BvhNode> nodes; ///< nodes[0] is the root

  explicit TriangleBvh(const geometry::TriangleMesh& mesh);
};

/// Squared distance between the boxes [lo0, hi0] and [lo1, hi1] [mm²].
inline double box_distance2(const Vec3& lo0, const Vec3& hi0, const Vec3& lo1, const Vec3& hi1) {
  return (lo1 - hi0).cwiseMax(lo0 - hi1).cwiseMax(0.0).squaredNorm();
}

}  // namespace netshape::detail
