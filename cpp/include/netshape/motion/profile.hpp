#pragma once
/// \file profile.hpp
/// Speed profile of one segment: optional constant-speed windows at both ends, a speed-up, a cruise
/// and a slow-down. Trapezoidal (constant path acceleration) or, when the path jerk is finite, a
/// jerk-limited S-curve whose speed changes follow v0 + Δv·(3x² − 2x³), x = τ/T, with
/// T = max(1.5|Δv|/a, √(6|Δv|/j)) (peak acceleration 1.5|Δv|/T ≤ a, peak jerk 6|Δv|/T² ≤ j).

#include <limits>

namespace netshape::motion {

/// Time [s] of a speed change from v0 to v1 [mm/s] under path acceleration a and jerk j.
double ramp_time(double v0, double v1, double a, double j) noexcept;
/// Distance [mm] of that speed change.
double ramp_distance(double v0, double v1, double a, double j) noexcept;
/// Largest speed reachable from v over a distance L (seeds/002 eq. 3 and 5 for the trapezoid:
/// sqrt(v² + 2·a·L)) [mm/s].
double reach_speed(double v, double length, double a, double j) noexcept;

/// The profile of one segment of length L.
struct Profile {
  double vs = 0, ve = 0, vp = 0;  ///< start, end, peak speed [mm/s]
  double a = 1, j = std::numeric_limits<double>::infinity();  ///< path acceleration, jerk
  double t[5] = {0, 0, 0, 0, 0};  ///< durations: start window, up, cruise, down, end window [s]
  double d[5] = {0, 0, 0, 0, 0};  ///< distances of the same phases [mm]
  double duration = 0;            ///< [s]

  /// Build: start/end speeds vs, ve, cruise cap vmax [mm/s], window distances ws, we [mm] that are
  /// run at constant vs and ve (they hold a velocity jump at the vertex clear of any acceleration).
  static Profile make(double length, double vs, double ve, double vmax, double a, double j, double ws,
                      double we) noexcept;
  /// Distance s [mm], speed v [mm/s] and path acceleration acc [mm/s^2] at time tau ∈ [0, duration].
  void eval(double tau, double& s, double& v, double& acc) const noexcept;
};

}  // namespace netshape::motion
