#pragma once
/// \file runout_size_effect.hpp
/// Flat end mill forces with cutter runout and the chip-size effect (the catalogue's `runout` and
/// `size_effect`, docs/discrepancy.md), on top of the linear edge-force model of flat_end_model.hpp.
///
/// Runout: the tool axis is offset by ρ at angle λ; flute j (0 … N−1, flute 1 = j 0) cuts at radius
/// R_j = R + r_j, r_j = ρ·cos(λ − j·2π/N), and removes the chip h_j = c·sin φ + r_j − r_{j+1},
/// clamped at 0 (the flute before it left the surface at r_{j+1}).
/// Size effect: the cutting terms follow g(h) = h_ref·(h/h_ref)^p instead of h (p = 1: the linear
/// model; p < 1: thin chips cut relatively harder), so dFt = (ktc·g(h) + kte)·dz where h > 0.
/// g is evaluated as its piecewise-linear interpolant over the knots h_k = c·{0, .006, .02, .05, .1,
/// .18, .3, .45, .62, .8, 1} (continued linearly beyond c), the form the discrepancy workflow fits.
///
/// Evaluation: every term is one call of the flat end mill kernel with one flute, the angle shifted by
/// j·2π/N, the window narrowed to sin φ ≥ (h_k − Δ_j)/c and edge coefficients −(h_k − Δ_j)·K_c, so the
/// extension is exact for the element model of flat_end_forces (same disks, same engagement rule).

#include "netshape/core/types.hpp"
#include "netshape/force/flat_end_model.hpp"

namespace netshape::force {

/// Runout and chip-size-effect parameters of a flat end mill cut.
struct RunoutSizeEffect {
  double runout_rho = 0.0;     ///< ρ, offset of the tool axis [mm], ≥ 0
  double runout_lambda = 0.0;  ///< λ [rad]
  double chip_exponent = 1.0;  ///< p, in (0, 2]; 1 = no size effect
  double reference_chip = 0.0; ///< h_ref [mm] > 0 (0: the feed per tooth)

  /// Throws std::invalid_argument naming the field when a value is non-finite or out of range.
  void validate() const;
  /// true when neither runout nor a size effect is set (the plain linear edge model).
  bool none() const noexcept { return runout_rho == 0.0 && chip_exponent == 1.0; }
};

/// Forces on the cutter (n, 3) [N] at the rotation angles (n) [rad] of flute 1 at the tip, for the
/// model's angular engagement (an engagement map: the overload below) and its coefficients (Kline–DeVor
/// as its linear edge equivalent). With `extension.none()` equal to flat_end_forces(model, angles).
Points3 flat_end_forces_extended(const FlatEndModel& model, const RunoutSizeEffect& extension,
                                 const Eigen::Ref<const VectorXd>& angles);

/// The same chip (h_j = c·sin φ + r_j − r_{j+1}, cutting terms g(h_j), edge terms where h_j > 0) on
/// the elements an engagement `map` marks (as flat_end_forces with a map: bin ⌊φ·bins/2π⌋ of the
/// element's disk), written into `out` (n, 3) [N]. The program force simulation's model
/// (force/program.hpp). With `extension.none()` exactly flat_end_forces(model, workspace, angles,
/// out, &map), which also applies edge forces on engaged elements with sin φ ≤ 0.
void flat_end_forces_extended(const FlatEndModel& model, const RunoutSizeEffect& extension,
                              FlatEndWorkspace& workspace, const Eigen::Ref<const VectorXd>& angles,
                              Eigen::Ref<Points3> out, const EngagementMap& map);

}  // namespace netshape::force
