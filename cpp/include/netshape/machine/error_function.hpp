#pragma once
/// \file error_function.hpp
/// One geometric error component of a linear axis as a function of the axis' own position q [mm]:
/// zero, a polynomial in q, or a table with linear interpolation (the layout of controller
/// volumetric-compensation files). Values are [mm] for translations (EXX, EYX, ...) and [rad] for
/// rotations (EAX, EBX, ECX, ...).

#include <cstdint>
#include <string>
#include <vector>

namespace netshape::machine {

/// What a table does with a position outside [positions.front(), positions.back()].
enum class OutOfRange : std::uint8_t {
  error = 0,        ///< throw std::invalid_argument naming the component and the position (default)
  clamp = 1,        ///< hold the end value (what most controllers do past the last table point)
  extrapolate = 2,  ///< continue the first/last table segment linearly
};

/// An error component e(q). Plain value type; `validate()` checks it.
///
/// - `polynomial`: e(q) = c0 + c1·q + c2·q² + … (ascending powers; c_k in [mm/mm^k] or [rad/mm^k]),
///   valid for every q.
/// - `table`: values at strictly increasing positions, linear interpolation between them
///   (piecewise linear, C0; the same as controller compensation tables), `out_of_range` outside.
struct ErrorFunction {
  enum class Kind : std::uint8_t { zero = 0, polynomial = 1, table = 2 };

  Kind kind = Kind::zero;
  std::vector<double> coefficients;  ///< polynomial: c0, c1, … ascending powers of q [mm]
  std::vector<double> positions;     ///< table: axis positions [mm], strictly increasing, ≥ 2
  std::vector<double> values;        ///< table: component values at `positions` [mm] or [rad]
  OutOfRange out_of_range = OutOfRange::error;
  std::string name;                  ///< ISO 230-1 name (e.g. "EXX"), used in error messages

  static ErrorFunction zero_function(std::string name = {});
  static ErrorFunction polynomial(std::vector<double> coefficients, std::string name = {});
  static ErrorFunction table(std::vector<double> positions, std::vector<double> values,
                             OutOfRange out_of_range = OutOfRange::error, std::string name = {});

  /// Throws std::invalid_argument naming `name` on non-finite numbers, fewer than 2 table points,
  /// size mismatch or non-increasing positions.
  void validate() const;

  /// e(q). Throws std::invalid_argument if q is outside a table and `out_of_range` is `error`.
  double operator()(double q) const;

  bool is_zero() const noexcept { return kind == Kind::zero; }
};

}  // namespace netshape::machine
