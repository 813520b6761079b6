#pragma once
/// \file limits.hpp
/// Kinematic limits of the three linear axes of a machine.

#include <limits>

#include "netshape/core/types.hpp"

namespace netshape::motion {

/// Per-axis limits (x, y, z). A jerk limit of +infinity means "not jerk-limited".
struct AxisLimits {
  Vec3 velocity = Vec3::Constant(100.0);       ///< vmax per axis [mm/s]
  Vec3 acceleration = Vec3::Constant(1000.0);  ///< amax per axis [mm/s^2]
  Vec3 jerk = Vec3::Constant(std::numeric_limits<double>::infinity());  ///< jmax per axis [mm/s^3]

  /// The same limits on all three axes; `jmax` = +inf for trapezoidal (not jerk-limited) profiles.
  static AxisLimits uniform(double vmax, double amax,
                            double jmax = std::numeric_limits<double>::infinity());
  /// True when any axis has a finite jerk limit (profiles are then S-curves).
  bool jerk_limited() const noexcept;
  /// Throws std::invalid_argument naming the field unless every limit is positive (jerk may be +inf).
  void validate() const;
};

}  // namespace netshape::motion
