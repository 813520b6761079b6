#pragma once
/// \file ball_end_model.hpp
/// Ball end mill force model after Kim et al. eq. 1–10 (Feng–Menq coefficients K_T(ψ), K_R(ψ) cubic in
/// the position angle ψ of the edge element, chip-size exponents m_T, m_R), with inclined (ramp) cuts
/// handled by rotating the element frame by ξ about the axis normal to the feed (eq. 3–4).
///
/// Elements: one flute's ball part is cut into equal steps Δψ of the position angle ψ (0 at the
/// equator, π/2 at the tip; height above the tip z = R(1 − sin ψ), eq. 9; radius R cos ψ, eq. 10);
/// above the equator (a_p > R) the cylindrical part is cut into disks with the coefficients at ψ = 0.
/// The flute lags by k_β·z (k_β = tan β / R), as docs/conventions.md §2 (Kim et al. eq. 1 writes the
/// same lag as sin φ·tan β from the equator; the constant difference only moves the angle origin to the tip).
///
/// Chip and width (eq. 4–6): with the element at (X, Y, Z) relative to the ball centre and the
/// rotated frame X' = X cos ξ + Z sin ξ (along the inclined feed), Y' = Y, Z' = −X sin ξ + Z cos ξ:
/// cos φ' = √(X'² + Y'²)/R, sin ϕ = X'/(R cos φ'), chip t = f·sin ϕ (zero where X' ≤ 0), width
/// dw = R cos φ'·Δψ. dF_T = K_T(ψ) t^{m_T} dw, dF_R = K_R(ψ) t^{m_R} dw, projected in the tool frame
/// with the formulas of docs/conventions.md §3 (Kim et al. eq. 8 writes them with the feed along its
/// y axis). ξ > 0 is an upward ramp (the feed climbs along +Z). No axial force (the paper models
/// none): Fz = 0.
///
/// Steady cut (no map): `engagement` is the window at the tool's largest radius R and stands for straight
/// walls parallel to the feed, at y = R cos φ_st and y = R cos φ_ex in the tool frame (docs/conventions.md
/// §2). An element cuts where it is ahead of the feed (X' > 0), below a_p, and the point of the radius-R
/// circle on the front half at the element's own distance Y from the feed line lies in the window: acos(Y/R)
/// ∈ [φ_st, φ_ex]. Up milling with a_e (window [0, acos(1 − a_e/R)]) is the wall y = R − a_e with material on
/// +Y: an element of radius r cuts over φ ∈ [0, acos((R − a_e)/r)] and not at all when r ≤ R − a_e; down
/// milling mirrors it (wall y = −(R − a_e), material on −Y); a slot [0, π] has no wall and every element cuts
/// its whole front half. Rows at radius R (the cylinder above the equator) get the window itself. The chip
/// thickness does not depend on the window.
///
/// Runout (the catalogue's `runout`, as flat end mills, runout_size_effect.hpp): the tool axis is
/// offset by ρ at angle λ; flute j (0 … N−1) cuts at a radius larger by r_j = ρ·cos(λ − j·2π/N),
/// measured horizontally. On the sphere the element's outward normal is n = cos ψ·e_r − sin ψ·e_z, so
/// the horizontal step r_j − r_{j+1} over the flute before it thickens the chip (measured along n) by
/// (r_j − r_{j+1})·cos ψ (the full step on the cylinder, ψ = 0; none at the tip): t_j = f·sin ϕ +
/// (r_j − r_{j+1})·cos ψ, clamped at 0, where the element cuts (X' > 0, in the window or map). The
/// chip-size effect is the Feng–Menq exponents m_T, m_R. With ρ = 0 the forces are bit-identical to
/// the model without runout.

#include "netshape/core/types.hpp"
#include "netshape/force/coefficients.hpp"
#include "netshape/force/engagement.hpp"

namespace netshape::force {

struct BallEndModel {
  double radius = 6.0;                 ///< ball radius R [mm]
  int flutes = 2;                      ///< N
  double helix = 0.5235987755982988;   ///< β [rad]
  double axial_depth = 3.0;            ///< a_p [mm], measured from the tip along the feed-normal axis
  double feed_per_tooth = 0.05;        ///< f [mm/tooth]
  double inclination = 0.0;            ///< ramp angle ξ [rad], in (−80°, 80°); > 0 climbs
  AngularEngagement engagement{};      ///< window at the largest radius R = walls parallel to the
                                       ///< feed (see above); ignored with a map
  BallEndCoefficients coefficients{};
  double element_angle = 0.0174532925199432957;  ///< target Δψ [rad] (default 1°)
  double disk_height = 0.05;           ///< target dz of the cylindrical part [mm]
  double runout_rho = 0.0;             ///< ρ, offset of the tool axis [mm], in [0, R)
  double runout_lambda = 0.0;          ///< λ [rad]: flute j cuts at + ρ·cos(λ − j·2π/N)

  void validate() const;
  double k_beta() const;
};

class BallEndWorkspace {
 public:
  BallEndWorkspace() = default;
  explicit BallEndWorkspace(const BallEndModel& model) { reset(model); }
  void reset(const BallEndModel& model);

  /// Number of element rows per flute (ball steps + cylinder disks).
  int rows() const noexcept { return static_cast<int>(z_.size()); }
  int flutes() const noexcept { return flutes_; }
  /// Height above the tip of each row, (rows) [mm].
  const VectorXd& heights() const noexcept { return z_; }
  /// Radius of each row, (rows) [mm].
  const VectorXd& radii() const noexcept { return r_; }
  /// Position angle ψ of each row, (rows) [rad] (0 for cylinder rows).
  const VectorXd& position_angles() const noexcept { return psi_; }
  /// Chip width of each row for ξ = 0: R cos ψ·Δψ (ball) or dz (cylinder), (rows) [mm].
  const VectorXd& widths() const noexcept { return w0_; }

 private:
  friend void ball_end_forces(const BallEndModel&, BallEndWorkspace&, const Eigen::Ref<const VectorXd>&,
                              Eigen::Ref<Points3>, const EngagementMap*);
  int flutes_ = 0;
  double radius_ = 0, helix_ = -1, depth_ = 0, xi_ = 0, dpsi_target_ = 0, dz_target_ = 0;
  VectorXd z_, r_, psi_, step_, w0_;  // per row; step_ = Δψ (ball) or dz (cylinder)
  Eigen::ArrayXi is_ball_;
  Eigen::ArrayXd kt_, kr_;       // per row, refreshed each call from the coefficients
  Eigen::ArrayXd cos_psi_;       // per row: projection of a horizontal radial step on the normal
  Eigen::ArrayXd runout_step_;   // per flute: r_j − r_{j+1} [mm], refreshed each call
};

/// Forces on the cutter [N] at the angles (n) [rad] into out (n, 3). With `map`, rows of the map are
/// the workspace rows. Never allocates.
void ball_end_forces(const BallEndModel& model, BallEndWorkspace& workspace,
                     const Eigen::Ref<const VectorXd>& angles, Eigen::Ref<Points3> out,
                     const EngagementMap* map = nullptr);

Points3 ball_end_forces(const BallEndModel& model, const Eigen::Ref<const VectorXd>& angles);
Points3 ball_end_forces(const BallEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                        const EngagementMap& map);

}  // namespace netshape::force
