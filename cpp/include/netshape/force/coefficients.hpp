#pragma once
/// \file coefficients.hpp
/// Cutting-force coefficients: the linear edge-force model (Altintas), the Kline–DeVor constant
/// coefficients (Cho & Suh eq. 1) and the Feng–Menq ball-end polynomials (Kim et al. eq. 6–7), plus the
/// named coefficient sets netshape ships.

#include <array>
#include <string>
#include <vector>

namespace netshape::force {

/// Linear edge-force model (docs/conventions.md §2): per unit length of cutting edge along the tool axis
///   dFt = (ktc·h + kte)·dz,  dFr = (krc·h + kre)·dz,  dFa = (kac·h + kae)·dz,  h = c·sin φ.
struct LinearEdgeCoefficients {
  double ktc = 0.0;  ///< tangential cutting coefficient [N/mm²]
  double krc = 0.0;  ///< radial cutting coefficient [N/mm²]
  double kac = 0.0;  ///< axial cutting coefficient [N/mm²]
  double kte = 0.0;  ///< tangential edge coefficient [N/mm]
  double kre = 0.0;  ///< radial edge coefficient [N/mm]
  double kae = 0.0;  ///< axial edge coefficient [N/mm]

  /// All finite; throws std::invalid_argument naming the field otherwise. Signs are not restricted
  /// (a fit may return a small negative edge coefficient).
  void validate() const;
  /// (ktc, krc, kac, kte, kre, kae).
  std::array<double, 6> as_array() const noexcept { return {ktc, krc, kac, kte, kre, kae}; }
  static LinearEdgeCoefficients from_array(const std::array<double, 6>& k) noexcept {
    return {k[0], k[1], k[2], k[3], k[4], k[5]};
  }
};

/// Kline–DeVor constant coefficients (Cho & Suh eq. 1): dF_T = K_T·t_c·D_z, dF_R = K_R·dF_T.
/// No edge and no axial force. Equivalent to a linear edge model with ktc = kt, krc = kr·kt.
struct KlineDevorCoefficients {
  double kt = 0.0;  ///< K_T, tangential specific cutting force [N/mm²]; > 0
  double kr = 0.0;  ///< K_R, ratio radial/tangential [-]; finite
  void validate() const;
  LinearEdgeCoefficients to_linear_edge() const noexcept { return {kt, kr * kt, 0.0, 0.0, 0.0, 0.0}; }
};

/// Feng–Menq style ball-end coefficients (Kim et al. eq. 6–7):
///   dF_T = K_T(ψ)·t^{m_T}·dw,  dF_R = K_R(ψ)·t^{m_R}·dw,
///   K_T(ψ) = a0 + a1 ψ + a2 ψ² + a3 ψ³,  K_R(ψ) = b0 + b1 ψ + b2 ψ² + b3 ψ³,
/// with ψ [rad] the position angle of the edge element on the ball (Kim et al.'s φ: 0 at the equator,
/// π/2 at the tip), t [mm] the chip thickness and dw [mm] the chip width. The units of a, b follow
/// from the exponents (N/mm^(1+m)). The model has no axial force.
struct BallEndCoefficients {
  std::array<double, 4> a{};  ///< K_T polynomial, a0 … a3
  std::array<double, 4> b{};  ///< K_R polynomial, b0 … b3
  double m_t = 1.0;           ///< chip-thickness exponent of the tangential force, in (0, 2]
  double m_r = 1.0;           ///< chip-thickness exponent of the radial force, in (0, 2]
  void validate() const;
  double kt(double psi) const noexcept { return a[0] + psi * (a[1] + psi * (a[2] + psi * a[3])); }
  double kr(double psi) const noexcept { return b[0] + psi * (b[1] + psi * (b[2] + psi * b[3])); }
};

/// Geometry a named ball-end coefficient set was measured with (for information and defaults).
struct BallEndCoefficientSet {
  std::string name;
  BallEndCoefficients coefficients;
  double diameter = 0.0;  ///< [mm]
  int flutes = 0;
  double helix = 0.0;     ///< [rad]
  std::string source;     ///< citation
};

/// A named linear edge-force set (for information and defaults).
struct LinearEdgeCoefficientSet {
  std::string name;
  LinearEdgeCoefficients coefficients;
  std::string source;
};

/// Named ball-end sets: "kim_zas_ball12" — Kim et al. (G. M. Kim, P. J. Cho, B. H. Kim, C. N. Chu,
/// "Cutting force prediction in the ball-end milling process of various cutting area using Z-map",
/// §4.2): zinc alloy ZAS, D = 12 mm, 2 flutes, 30° helix, 600 rpm. Throws std::invalid_argument for an
/// unknown name.
BallEndCoefficientSet ball_end_coefficient_set(const std::string& name);
/// Named linear edge sets: "leekunhwee_flat_slot" (the README reference regression of the
/// leekunhwee-flat-slot recordings: Ktc 958.8, Krc 251.1, Kac 146.4 N/mm², Kte 15.8, Kre 19.4,
/// Kae 18.2 N/mm). Throws std::invalid_argument for an unknown name.
LinearEdgeCoefficientSet linear_edge_coefficient_set(const std::string& name);
std::vector<std::string> ball_end_coefficient_set_names();
std::vector<std::string> linear_edge_coefficient_set_names();

}  // namespace netshape::force
