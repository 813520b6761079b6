#pragma once
/// \file nurbs_curve.hpp
/// Non-uniform rational B-spline curve in 3-D (Piegl & Tiller, The NURBS Book, 2nd ed.):
/// evaluation (A4.1), derivatives of any order (A3.2 on homogeneous points + A4.2), knot insertion (A5.1),
/// closest-point projection (Newton, §6.1, from a coarse-sample start).

#include <utility>

#include "netshape/core/types.hpp"

namespace netshape::geometry {

/// Result of projecting a point onto a curve.
struct CurveProjection {
  double u = 0.0;            ///< parameter of the closest point
  Vec3 point = Vec3::Zero(); ///< closest point on the curve [mm]
  double distance = 0.0;     ///< |point − query| [mm]
  int iterations = 0;        ///< Newton iterations used
  bool converged = false;    ///< Newton met the tolerance (else the best sample/iterate is returned)
};

/// Homogeneous control points (x w, y w, z w, w), one per row.
using Points4 = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// A NURBS curve C(u) = Σ N_{i,p}(u) w_i P_i / Σ N_{i,p}(u) w_i. Immutable once built (validated).
class NurbsCurve {
 public:
  NurbsCurve() = default;
  /// degree p ≥ 1; knots (n + p + 1) non-decreasing; control_points (n, 3) [mm]; weights (n) > 0
  /// (empty = all 1, non-rational). Throws std::invalid_argument naming the bad field.
  NurbsCurve(int degree, VectorXd knots, Points3 control_points, VectorXd weights = VectorXd());

  int degree() const noexcept { return degree_; }
  int count() const noexcept { return static_cast<int>(control_points_.rows()); }
  const VectorXd& knots() const noexcept { return knots_; }
  const Points3& control_points() const noexcept { return control_points_; }
  const VectorXd& weights() const noexcept { return weights_; }
  /// Homogeneous control points (n, 4).
  const Points4& homogeneous() const noexcept { return pw_; }
  bool is_rational() const noexcept;
  /// Parameter domain [U[p], U[n]].
  std::pair<double, double> domain() const noexcept;

  /// Point C(u) [mm]. u is clamped into the domain if it lies within 1e-12 of it; further out throws.
  Vec3 point(double u) const;
  /// Derivatives C^(k)(u), k = 0 … order, as rows of an (order + 1, 3) array [mm / unit^k].
  Points3 derivatives(double u, int order) const;
  /// Unit tangent at u (degenerate first derivative: direction of the first non-zero higher derivative).
  Vec3 tangent(double u) const;
  /// Points at many parameters: us (m) → (m, 3).
  Points3 evaluate(const Eigen::Ref<const VectorXd>& us) const;
  /// Points at `count` parameters evenly spaced over the domain.
  Points3 sample(int count) const;

  /// The same curve with knot u inserted `times` times (A5.1). Shape unchanged.
  NurbsCurve insert_knot(double u, int times = 1) const;
  /// Multiplicity of knot value u in the knot vector (exact comparison).
  int knot_multiplicity(double u) const noexcept;

  /// Closest point on the curve to p: coarse sampling then Newton on f(u) = C'(u)·(C(u) − p).
  /// `tolerance` [mm] stops Newton on point coincidence or on a parameter step below it (scaled).
  CurveProjection closest_point(const Vec3& p, double tolerance = 1e-10, int max_iterations = 50) const;

  /// Check that u lies in the domain (within 1e-12 relative) and return it clamped. Throws otherwise.
  double check_parameter(double u, const char* field = "u") const;

 private:
  int degree_ = 0;
  VectorXd knots_;
  Points3 control_points_;
  VectorXd weights_;
  Points4 pw_;
};

namespace detail {
/// Checks control points (n, 3) and weights (n,) — empty weights become all ones — and returns the
/// homogeneous points (x·w, y·w, z·w, w) (n, 4). Shared by curve and surface constructors.
Points4 homogeneous_control_points(const Points3& control_points, VectorXd& weights);

/// Knot insertion (A5.1) applied to several curves at once: each row of `pw` holds the homogeneous
/// control points of control-point index i for all curves (columns). Returns the new knots and rows.
void insert_knot_rows(int degree, const VectorXd& knots, const MatrixXdR& pw, double u, int times,
                      VectorXd& new_knots, MatrixXdR& new_pw);
}  // namespace detail

}  // namespace netshape::geometry
