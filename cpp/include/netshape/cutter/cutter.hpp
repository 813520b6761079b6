#pragma once
/// \file cutter.hpp
/// End mills: flat, ball and bull-nose, described by the geometry the force, stock and deflection
/// models need. Tool frame: Z along the tool axis from the tip (z = 0) into the spindle.

#include <cstdint>
#include <string>

namespace netshape::cutter {

enum class CutterKind : std::uint8_t { flat = 0, ball = 1, bull = 2 };

/// An end mill. Plain value type; call validate() after filling it in.
struct Cutter {
  CutterKind kind = CutterKind::flat;
  double radius = 5.0;            ///< nominal radius R = D/2 [mm]
  double corner_radius = 0.0;     ///< flat: 0; ball: = radius; bull: 0 < r < radius [mm]
  int flutes = 2;                 ///< number of flutes N
  double helix = 0.5235987755982988;  ///< helix angle β [rad] (default 30°)
  double flute_length = 20.0;     ///< length of the fluted part from the tip [mm]
  double stick_out = 40.0;        ///< length from the holder face to the tip [mm]; ≥ flute_length
  double youngs_modulus = 600e3;  ///< E of the tool material [MPa] (carbide ≈ 600 GPa)
  /// Clamp/holder/spindle compliance at the tool [mm/N] ≥ 0: the whole tool translates by
  /// holder_compliance·F under the cutting force F (a spring in series with the cantilever).
  double holder_compliance = 0.0;
  double runout_rho = 0.0;     ///< radial runout ρ: offset of the tool axis [mm], ≥ 0 and < radius
  double runout_lambda = 0.0;  ///< runout angle λ [rad]: flute j cuts at R + ρ·cos(λ − j·2π/N)

  /// Throws std::invalid_argument naming the field and the value if anything is inconsistent.
  void validate() const;

  double diameter() const noexcept { return 2.0 * radius; }
  /// Radius of the cutter's envelope at height z above the tip [mm]; 0 ≤ z. Beyond the flute
  /// length the envelope keeps the nominal radius (the shank is taken as the same size).
  double radius_at(double z) const noexcept;
  /// Helix lag constant k_β = tan β / R [rad/mm] (docs/conventions.md §2; flat part of the flute).
  double helix_lag() const noexcept;

  static Cutter flat_end(double diameter, int flutes, double helix_rad);
  static Cutter ball_end(double diameter, int flutes, double helix_rad);
  static Cutter bull_nose(double diameter, double corner_radius, int flutes, double helix_rad);
};

/// Largest number of flutes netshape models.
inline constexpr int max_flutes = 64;
/// The one flute-count check: throws std::invalid_argument "`field` = N: must be between 1 and 64"
/// unless 1 ≤ flutes ≤ max_flutes. Cutter::validate and the force models call it; the layers above
/// rely on it and pass its message through.
void check_flutes(int flutes, const char* field = "flutes");

const char* to_string(CutterKind k) noexcept;
/// "flat", "ball" or "bull" (also "bullnose", "bull-nose"); throws std::invalid_argument otherwise.
CutterKind cutter_kind_from_string(const std::string& s);

}  // namespace netshape::cutter
