#pragma once
/// \file flat_end_model.hpp
/// Flat end mill force model (Cho & Suh §3.1, docs/conventions.md §2): the flute is cut into disks of
/// height dz along the tool axis; each flute's element on a disk carries a tangential, radial and axial force
/// from the chip h = c·sin φ; the forces on the cutter in the cutting frame (X feed, Z tool axis from
/// the tip, forces ON THE CUTTER) are summed over the engaged elements for every rotation angle.
///
/// Split as pinocchio Model/Data: FlatEndModel is an immutable value (geometry, cut, coefficients),
/// FlatEndWorkspace holds everything precomputed and the buffers, so the angle loop never allocates.

#include <cstdint>

#include "netshape/core/types.hpp"
#include "netshape/force/coefficients.hpp"
#include "netshape/force/engagement.hpp"

namespace netshape::force {

/// Which coefficient model the flat end mill uses.
enum class FlatCoefficientModel : std::uint8_t {
  linear_edge = 0,  ///< dFt = (ktc h + kte) dz, … (docs/conventions.md §2)
  kline_devor = 1,  ///< dF_T = K_T t_c D_z, dF_R = K_R dF_T (Cho & Suh eq. 1–5, its α = π − φ inside)
};

/// Everything that does not change during an angle sweep.
struct FlatEndModel {
  double radius = 5.0;                  ///< cutter radius R [mm]
  int flutes = 2;                       ///< number of flutes N
  double helix = 0.5235987755982988;    ///< helix angle β [rad], in [0, 85°)
  double axial_depth = 1.0;             ///< axial depth of cut a_p [mm] (from the tip)
  double feed_per_tooth = 0.05;         ///< c [mm/tooth]
  AngularEngagement engagement{};       ///< radial engagement window (ignored with an EngagementMap)
  FlatCoefficientModel coefficient_model = FlatCoefficientModel::linear_edge;
  LinearEdgeCoefficients linear_edge{};  ///< used when coefficient_model == linear_edge
  KlineDevorCoefficients kline_devor{};  ///< used when coefficient_model == kline_devor
  double disk_height = 0.05;            ///< target dz [mm]; disks = ceil(a_p/dz), all of height a_p/disks

  void validate() const;
  int disks() const;
  double k_beta() const;  ///< helix lag constant tan β / R [rad/mm]
};

/// Precomputed element constants for one FlatEndModel. Rebuild it (or call reset) when
/// the model's geometry changes; coefficients, feed and engagement may change freely.
class FlatEndWorkspace {
 public:
  FlatEndWorkspace() = default;
  explicit FlatEndWorkspace(const FlatEndModel& model) { reset(model); }
  /// Size and fill the per-element constants for `model` (validates it).
  void reset(const FlatEndModel& model);

  int disks() const noexcept { return disks_; }
  int flutes() const noexcept { return flutes_; }
  int elements() const noexcept { return disks_ * flutes_; }
  /// Disk-centre heights above the tip, (disks) [mm].
  const VectorXd& heights() const noexcept { return z_; }
  double disk_height() const noexcept { return dz_; }

 private:
  friend void flat_end_forces(const FlatEndModel&, FlatEndWorkspace&, const Eigen::Ref<const VectorXd>&,
                              Eigen::Ref<Points3>, const EngagementMap*);
  friend void flat_end_moments(const FlatEndModel&, FlatEndWorkspace&, const Eigen::Ref<const VectorXd>&,
                               Eigen::Ref<MatrixXdR>);
  int disks_ = 0, flutes_ = 0;
  double dz_ = 0.0, radius_ = 0.0, helix_ = -1.0, depth_ = 0.0, target_dz_ = 0.0;
  VectorXd z_;                 // (disks)
  Eigen::ArrayXd off_;         // (elements) angle offset j·2π/N − k_β z wrapped to [0, 2π)
  Eigen::ArrayXd cos_off_, sin_off_;
  Eigen::ArrayXi disk_of_;     // (elements) disk index
};

/// Forces on the cutter [N] at the rotation angles `angles` (n) [rad] (immersion of flute 1 at the
/// tip), written into `out` (n, 3) = (Fx, Fy, Fz). With `map` the engagement comes from it (its rows
/// must equal workspace.disks()), else from model.engagement. Never allocates.
void flat_end_forces(const FlatEndModel& model, FlatEndWorkspace& workspace,
                     const Eigen::Ref<const VectorXd>& angles, Eigen::Ref<Points3> out,
                     const EngagementMap* map = nullptr);

/// The six engagement moments per angle, out (n, 6): Σ w·h·cos φ, Σ w·h·sin φ, Σ w·h, Σ w·cos φ,
/// Σ w·sin φ, Σ w over the engaged elements (w = dz [mm], h = max(c sin φ, 0) [mm]). Every linear
/// edge force is a linear map of them:
///   Fx = −ktc M0 − krc M1 − kte M3 − kre M4,  Fy = ktc M1 − krc M0 + kte M4 − kre M3,
///   Fz = kac M2 + kae M5.
/// Used by calibration (one pass gives the response to all six coefficients).
void flat_end_moments(const FlatEndModel& model, FlatEndWorkspace& workspace,
                      const Eigen::Ref<const VectorXd>& angles, Eigen::Ref<MatrixXdR> out);

/// Convenience: builds a workspace and returns (n, 3) [N].
Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles);

/// Convenience with an engagement map.
Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                        const EngagementMap& map);

/// `count` angles uniformly covering `revolutions` turns from 0: θ_k = 2π·revolutions·k/count.
VectorXd rotation_angles(int count, double revolutions = 1.0);

}  // namespace netshape::force
