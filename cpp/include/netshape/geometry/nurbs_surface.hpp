#pragma once
/// \file nurbs_surface.hpp
/// Non-uniform rational B-spline surface (Piegl & Tiller, The NURBS Book, 2nd ed.; Yang & Kweon eq. 13–15):
///
///     S(u, v) = Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) w_ij P_ij / Σ_i Σ_j N_{i,p}(u) N_{j,q}(v) w_ij      (eq. 13)
///     n(u, v) = S_u × S_v / |S_u × S_v|                                                          (eq. 15)
///
/// Evaluation, derivatives of any order (A3.6 on homogeneous points + A4.4), unit normals with a defined
/// answer at degenerate points (poles, collapsed edges), knot insertion (A5.1 row by row), iso-curves,
/// closest-point projection (Newton from a coarse grid), and a vectorised, non-allocating evaluation of
/// many (u, v) at once (scattered or on a grid) with a preallocated SurfaceWorkspace.
///
/// Control points are stored u-major, (n_u · n_v, 3): row i · n_v + j is P_ij (the order geomdl uses).

#include <utility>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/geometry/nurbs_curve.hpp"

namespace netshape::geometry {

/// Result of projecting a point onto a surface.
struct SurfaceProjection {
  double u = 0.0, v = 0.0;     ///< parameters of the closest point
  Vec3 point = Vec3::Zero();   ///< closest point on the surface [mm]
  Vec3 normal = Vec3::UnitZ(); ///< unit normal there (eq. 15, limit at degenerate points)
  double distance = 0.0;       ///< |point − query| [mm]
  int iterations = 0;          ///< Newton iterations of the chosen start
  bool converged = false;      ///< Newton met the tolerance (else the best iterate is returned)
};

/// Preallocated buffers for the vectorised evaluation (make one per thread with
/// NurbsSurface::make_workspace(); it is sized for that surface's degrees and control net).
struct SurfaceWorkspace {
  int degree_u = -1, degree_v = -1, count_v = 0;
  std::vector<double> nu, nv;          ///< (2, p + 1), (2, q + 1): basis functions and 1st derivatives
  std::vector<double> scratch_u, scratch_v;
  std::vector<double> row0, row1;      ///< (n_v, 4): iso-curve control points and their u-derivative
  std::vector<double> col_basis;       ///< grid: (b, 2 (q + 1)) v-basis per column (grown on demand)
  std::vector<int> col_span;           ///< grid: (b) v-span per column (grown on demand)
};

/// A NURBS surface. Immutable once built (validated in the constructor).
class NurbsSurface {
 public:
  NurbsSurface() = default;
  /// degree_u p ≥ 1, degree_v q ≥ 1; knots_u (n_u + p + 1), knots_v (n_v + q + 1) non-decreasing;
  /// control_points (n_u · n_v, 3) u-major [mm]; weights (n_u · n_v) > 0 (empty = all 1).
  /// Throws std::invalid_argument naming the bad field.
  NurbsSurface(int degree_u, int degree_v, VectorXd knots_u, VectorXd knots_v, Points3 control_points,
               VectorXd weights = VectorXd());

  int degree_u() const noexcept { return degree_u_; }
  int degree_v() const noexcept { return degree_v_; }
  int count_u() const noexcept { return count_u_; }
  int count_v() const noexcept { return count_v_; }
  const VectorXd& knots_u() const noexcept { return knots_u_; }
  const VectorXd& knots_v() const noexcept { return knots_v_; }
  const Points3& control_points() const noexcept { return control_points_; }
  const VectorXd& weights() const noexcept { return weights_; }
  const Points4& homogeneous() const noexcept { return pw_; }
  bool is_rational() const noexcept;
  std::pair<double, double> domain_u() const noexcept;
  std::pair<double, double> domain_v() const noexcept;
  /// Diagonal of the control points' bounding box [mm] (scale for tolerances).
  double size() const noexcept { return size_; }

  /// Point S(u, v) [mm].
  Vec3 point(double u, double v) const;
  /// All partial derivatives up to total order `order`: ((order+1)², 3), row k·(order+1) + l holds
  /// ∂^{k+l}S / ∂u^k ∂v^l [mm]; rows with k + l > order are zero.
  MatrixXdR derivatives(double u, double v, int order) const;
  /// Unit normal (eq. 15). Where S_u × S_v vanishes (a pole or a collapsed edge) the answer is the limit
  /// of the normal approaching (u, v) from inside the domain: with S_v ≡ 0 along an edge u = u0 it is
  /// ±unit(S_u × ∂^k S_v/∂u^k) for the first k with a non-zero product (sign of the approach direction
  /// to the power k), likewise with u and v exchanged; otherwise the mean of the normals on a small ring
  /// of neighbouring parameters. Throws netshape::Error only if the surface is degenerate all around.
  Vec3 normal(double u, double v) const;

  /// A workspace sized for this surface (allocate once, reuse for every call).
  SurfaceWorkspace make_workspace() const;
  /// Points (and unit normals if `normals` has rows) at scattered parameters uv (m, 2) into
  /// points (m, 3) / normals (m, 3). No allocation except at degenerate points (normal() fallback).
  void evaluate(const Eigen::Ref<const Points2>& uv, Eigen::Ref<Points3> points, Eigen::Ref<Points3> normals,
                SurfaceWorkspace& ws) const;
  /// Grid evaluation at us (a) × vs (b) into (a · b, 3) arrays, row i · b + j = S(us[i], vs[j]).
  /// Basis functions are computed once per row and column and the u-sums once per row.
  void evaluate_grid(const Eigen::Ref<const VectorXd>& us, const Eigen::Ref<const VectorXd>& vs,
                     Eigen::Ref<Points3> points, Eigen::Ref<Points3> normals, SurfaceWorkspace& ws) const;
  /// Allocating conveniences.
  Points3 evaluate(const Eigen::Ref<const Points2>& uv) const;
  std::pair<Points3, Points3> evaluate_with_normals(const Eigen::Ref<const Points2>& uv) const;

  /// The same surface with knot u (or v) inserted `times` times (A5.1 on every row). Shape unchanged.
  NurbsSurface insert_knot_u(double u, int times = 1) const;
  NurbsSurface insert_knot_v(double v, int times = 1) const;

  /// The same surface with u and v exchanged: S'(v, u) = S(u, v); its normal S'_u × S'_v = −n, so this is
  /// how to turn a design surface's normals to the other side (e.g. towards the tool for CC→CL).
  NurbsSurface swap_uv() const;

  /// Iso-parametric curve at fixed u = u0 (a curve in v, exact: degree q, knots_v).
  NurbsCurve iso_curve_u(double u0) const;
  /// Iso-parametric curve at fixed v = v0 (a curve in u, exact: degree p, knots_u).
  NurbsCurve iso_curve_v(double v0) const;

  /// Closest point to p: the nearest points of a coarse grid, then Newton on
  /// (S_u·(S − p), S_v·(S − p)) = 0 with the full Hessian, clamped to the domain; best result kept.
  SurfaceProjection closest_point(const Vec3& p, double tolerance = 1e-10, int max_iterations = 50) const;
  /// closest_point for many points (n, 3), the coarse grid evaluated once for all of them.
  std::vector<SurfaceProjection> closest_points(const Eigen::Ref<const Points3>& points, double tolerance = 1e-10,
                                                int max_iterations = 50) const;

  /// Check (u, v) in the domain (within 1e-12 relative) and return it clamped. Throws otherwise.
  std::pair<double, double> check_parameters(double u, double v) const;

 private:
  Vec3 degenerate_normal(double u, double v) const;
  SurfaceProjection project_from_grid(const Vec3& p, const VectorXd& us, const VectorXd& vs, const Points3& pts,
                                      std::vector<std::pair<double, Eigen::Index>>& order, double tolerance,
                                      int max_iterations) const;
  void point_normal_fast(int su, int sv, const double* Nu, const double* Nv, double u, double v, double* P,
                         double* N) const;

  int degree_u_ = 0, degree_v_ = 0, count_u_ = 0, count_v_ = 0;
  VectorXd knots_u_, knots_v_;
  Points3 control_points_;
  VectorXd weights_;
  Points4 pw_;
  double size_ = 1.0;
  double tiny_u_ = 0.0, tiny_v_ = 0.0;
  std::vector<double> inv_u_, inv_v_;  // per-span reciprocal knot differences (fast kernels)
};

}  // namespace netshape::geometry
