#pragma once
/// \file wall.hpp
/// Tool deflection under the instantaneous cutting force of a flat end mill and the wall error it
/// leaves (Cho & Suh 1993 §3.2, §4.1; surface generation after Budak & Altintas).
///
/// Frames and signs (same as netshape::force): X_c along the feed, Z along the tool axis from the
/// tip, Y_c = Z × X_c; forces ON THE CUTTER; flute 1 at height z sits at φ = θ − k_β·z (θ the
/// rotation angle, k_β = tan β / R). The cutter deflects in the direction of the force on it.
///
/// Load models:
/// - resultant (paper eq. 7): the force summed over all engaged elements acts at l = L − A/2
///   (A the axial depth), the deflection at height z is δ(L − z; l) (eq. 6);
/// - distributed: every disk's force acts at its own height z_i, δ(z) = Σ_i F_i·g(L − z, L − z_i)
///   with g the exact cantilever influence function (no numerical ODE).
///
/// Surface generation: the wall point at height z is cut at the instant a flute's element at z
/// passes the wall angle φ_w: φ_w = 0 for the left wall (+Y_c, up milling) and φ_w = π for the
/// right wall (−Y_c, down milling). Flute 1 is there at θ_w(z) = φ_w + k_β·z. The wall error at z is
/// the tool's deflection at z at that instant, along the normal n from the axis to the wall,
/// counted positive when material is left (the tool is pushed away from the wall):
///     e(z) = −δ(z)·n,   n = +Y_c (left) or −Y_c (right).
/// A slot has both walls.

#include <cstdint>
#include <string>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/deflection/cantilever.hpp"
#include "netshape/force/flat_end_model.hpp"
#include "netshape/force/runout_size_effect.hpp"

namespace netshape::deflection {

enum class LoadModel : std::uint8_t { resultant = 0, distributed = 1 };
const char* to_string(LoadModel m) noexcept;
/// "resultant" or "distributed"; throws std::invalid_argument otherwise.
LoadModel load_model_from_string(const std::string& s);

/// Which wall is generated: left (+Y_c, φ_w = 0, up milling) or right (−Y_c, φ_w = π, down milling).
enum class WallSide : std::uint8_t { left = 0, right = 1 };
const char* to_string(WallSide s) noexcept;
/// "left" or "right"; throws std::invalid_argument otherwise.
WallSide wall_side_from_string(const std::string& s);
/// Wall angle φ_w [rad]: 0 (left) or π (right).
double wall_angle(WallSide side) noexcept;

/// The force model of the cut and the beam that carries it.
struct DeflectionModel {
  force::FlatEndModel force;            ///< geometry, cut (a_p, c, engagement window), coefficients
  Cantilever beam;                      ///< the tool as a cantilever (length = stick-out)
  LoadModel load = LoadModel::distributed;
  /// true: an element is weighted by the fraction of its helix segment (angular extent k_β·dz about
  /// its centre) inside the engagement window, so forces change continuously with the window; false:
  /// an element is in or out by its centre, exactly as force::flat_end_forces.
  bool smooth_edges = true;
  /// Clamp/holder compliance [mm/N] ≥ 0 (cutter::Cutter::holder_compliance): a spring in series with
  /// the cantilever, so the tool also translates rigidly by holder_compliance·F, F the total force.
  double holder_compliance = 0.0;
  /// Runout and chip-size effect of the element chips (force::RunoutSizeEffect, the same chip as
  /// force::flat_end_forces_extended, the power law evaluated exactly): flute j's chip
  /// h_j = c·sin φ + r_j − r_{j+1}, no force where h_j ≤ 0, cutting terms h_ref·(h_j/h_ref)^p.
  force::RunoutSizeEffect chip{};
  /// Separate material windows of one instant (material, an air gap, material again: a sliver left
  /// beside a cleared band). Empty: the single window force.engagement. Otherwise they replace it and
  /// an element's weight is the sum of its weights in each window (capped at 1), so the disk forces,
  /// and with them the deflection and the wall error, are the sums of the windows' own; the gaps
  /// between them carry no force. Each window as AngularEngagement::validate requires.
  std::vector<force::AngularEngagement> windows;

  /// force.validate(), beam.validate(), and beam.length ≥ force.axial_depth (a stick-out shorter than
  /// the cut cannot cut it); throws std::invalid_argument naming the field.
  void validate() const;
};

/// Buffers of one DeflectionModel geometry (disks, flutes); the per-point loop never allocates.
class DeflectionWorkspace {
 public:
  DeflectionWorkspace() = default;
  explicit DeflectionWorkspace(const DeflectionModel& model) { reset(model); }
  /// Size for `model` (validates it).
  void reset(const DeflectionModel& model);
  /// Rebuild only if the geometry of `model` differs from the one this workspace was made for.
  void ensure(const DeflectionModel& model);
  int disks() const noexcept { return disks_; }
  /// Disk-centre heights above the tip, (disks) [mm].
  const VectorXd& heights() const noexcept { return z_; }
  double disk_height() const noexcept { return dz_; }
  /// Forces of the last disk_forces call, (disks, 2) [N].
  const Points2& forces() const noexcept { return f_; }

 private:
  friend void disk_forces(const DeflectionModel&, DeflectionWorkspace&, double);
  int disks_ = 0, flutes_ = 0;
  double dz_ = 0, radius_ = 0, helix_ = -1, depth_ = 0, target_dz_ = 0;
  VectorXd z_;
  Points2 f_;
};

/// Per-disk forces (Fx_c, Fy_c) on the cutter at rotation θ [rad] into workspace.forces() [N].
/// Coefficients as the force model: linear edge or Kline–DeVor (paper eq. 1–5).
void disk_forces(const DeflectionModel& model, DeflectionWorkspace& workspace, double theta);

/// Deflection (δx_c, δy_c) [mm] at height z [mm] above the tip of the forces in workspace.forces():
/// the cantilever's bending plus the holder's translation holder_compliance·ΣF.
Vec2 deflection_from_forces(const DeflectionModel& model, const DeflectionWorkspace& workspace, double z);

/// Rotation angle θ_w(z) = φ_w + k_β·z [rad] at which flute 1 generates the wall at height z [mm].
double generation_angle(const DeflectionModel& model, WallSide side, double z);

/// Wall error at the heights z (k) [mm] above the tip on one wall.
struct WallErrors {
  VectorXd z;          ///< (k) [mm]
  VectorXd error;      ///< (k) e = −δ·n [mm], + material left
  Points2 deflection;  ///< (k, 2) (δx_c, δy_c) at z at its generation instant [mm]
  Points2 force;       ///< (k, 2) total (Fx_c, Fy_c) at that instant [N]
};
WallErrors wall_errors(const DeflectionModel& model, DeflectionWorkspace& workspace, WallSide side,
                       const Eigen::Ref<const VectorXd>& z);

/// The three levels of the cut: bottom (z = 0), middle (A/2), top (A) for axial depth A [mm].
VectorXd cut_levels(double axial_depth);

/// Largest |(Fx_c, Fy_c)| [N] over `samples` rotation angles of one tooth period (smooth_edges as
/// the model says).
double max_force(const DeflectionModel& model, DeflectionWorkspace& workspace, int samples = 720);

}  // namespace netshape::deflection
