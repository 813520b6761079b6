#pragma once
/// \file types.hpp
/// Common Eigen types. Bulk arrays crossing into Python are row-major so that NumPy's default
/// C-ordered arrays map onto them without a copy (see cpp/bindings/default_types.hpp).

#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace netshape {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Iso3 = Eigen::Isometry3d;

/// (n, 3) row-major array of points or vectors.
using Points3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// (n, 2) row-major array.
using Points2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
/// (n, m) row-major array.
using MatrixXdR = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using VectorXd = Eigen::VectorXd;

constexpr double pi = 3.14159265358979323846;

inline double deg2rad(double d) { return d * pi / 180.0; }
inline double rad2deg(double r) { return r * 180.0 / pi; }

/// Distance [mm] of the point p from the segment [a, b] (from a when a = b).
inline double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) noexcept {
  const Vec3 d = b - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

}  // namespace netshape
