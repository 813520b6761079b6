#pragma once
/// \file cantilever.hpp
/// The end mill as a uniform cantilever clamped at the holder face (Cho & Suh 1993, eq. 6–7).
///
/// Beam coordinate x [mm] runs from the clamp (x = 0) to the tool tip (x = L, L = stick-out). A point
/// load F at x = a deflects the beam, in the load's direction, by (Euler–Bernoulli, e.g. Gere &
/// Goodno, Mechanics of Materials, cantilever with a concentrated load):
///
///     δ(x; a) = F·x²·(3a − x) / (6EI)    for x ≤ a
///     δ(x; a) = F·a²·(3x − a) / (6EI)    for x ≥ a
///
/// which is eq. 6 of the paper, δ(x, l) = F/(6EI)·(⟨x − l⟩³ − x³ + 3x²l), with ⟨·⟩ the Macaulay
/// bracket. Height above the tip z and beam coordinate are related by x = L − z.

#include <cstdint>
#include <string>

namespace netshape::deflection {

/// How the second moment of area of the fluted section is approximated.
enum class InertiaModel : std::uint8_t {
  square = 0,      ///< inscribed square of the diameter: I = D⁴/48
  equivalent = 1,  ///< a round bar of 0.8·D (Kops & Vo 1990): I = π(0.8D)⁴/64
};
const char* to_string(InertiaModel m) noexcept;
/// "square" or "equivalent"; throws std::invalid_argument otherwise.
InertiaModel inertia_model_from_string(const std::string& s);

/// Second moment of area [mm⁴] of a tool of diameter [mm] (> 0) under the given approximation.
double second_moment(double diameter, InertiaModel model);

/// Uniform cantilever clamped at x = 0.
struct Cantilever {
  double length = 40.0;           ///< L: holder face to tip (stick-out) [mm]
  double youngs_modulus = 600e3;  ///< E [MPa]
  double inertia = 100.0;         ///< I [mm⁴]

  /// Throws std::invalid_argument naming the field when L, E or I is not a positive finite number.
  void validate() const;
  /// Flexural rigidity E·I [N·mm²].
  double rigidity() const noexcept { return youngs_modulus * inertia; }
  /// Deflection at x [mm] per unit load at a [mm] (both from the clamp, in [0, L]) [mm/N].
  double influence(double x, double a) const noexcept;
  /// eq. 6: deflection at x of a load `force` [N] at l [mm] [mm].
  double deflection(double force, double x, double l) const noexcept { return force * influence(x, l); }

  /// A tool of diameter D [mm], stick-out L [mm] and modulus E [MPa].
  static Cantilever tool(double diameter, double stick_out, double youngs_modulus, InertiaModel model);
};

}  // namespace netshape::deflection
