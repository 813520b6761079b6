#pragma once
/// \file profile.hpp
/// Speed profile of one segment: optional constant-speed windows at both ends, a speed-up, a cruise
/// and a slow-down. Trapezoidal (constant path acceleration) or, when the path jerk is finite, a
/// jerk-limited S-curve whose speed changes follow v0 + Δv·(3x² − 2x³), x = τ/T, with
/// T = max(1.5|Δv|/a, √(6|Δv|/j)) (peak acceleration 1.5|Δv|/T ≤ a, peak jerk 6|Δv|/T² ≤ j).

#include <algorithm>
#include <cmath>
#include <limits>

namespace netshape::motion {

/// Time [s] of a speed change from v0 to v1 [mm/s] under path acceleration a and jerk j.
double ramp_time(double v0, double v1, double a, double j) noexcept;
/// Distance [mm] of that speed change.
double ramp_distance(double v0, double v1, double a, double j) noexcept;
/// Largest speed reachable from v over a distance L (Lee & Lee eq. 3 and 5 for the trapezoid:
/// sqrt(v² + 2·a·L)) [mm/s].
double reach_speed(double v, double length, double a, double j) noexcept;

/// Largest start speed u from which a segment of length L can slow down to every end speed in
/// [w, u] [mm/s] (= reach_speed(w, L, a, j) without a jerk limit). With finite jerk one S-curve
/// ramp's distance is not monotone in its end speed: a jerk-bound ramp (T = √(6Δv/j)) from u down to
/// w covers (u + w)/2·T, which shrinks again as w falls below u/3 (the peak acceleration 1.5Δv/T grows
/// with Δv). A look-ahead that promises a start speed for one end speed must keep the promise when
/// that end speed rises, so u is bounded by the longest slow-down to an end speed in [w, u]:
/// max(ramp_distance(u, w), ramp_distance(u, u/3) where w < u/3), non-increasing in w.
double reach_back_speed(double w, double length, double a, double j) noexcept;

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

namespace detail {
/// Profile::make with finite jerk (the S-curve; profile.cpp).
Profile make_scurve(double length, double vs, double ve, double vmax, double a, double j, double ws,
                    double we) noexcept;

// The constant-speed windows at the ends (a window only where that end speed is > 0, the start's
// first, together at most the length) clipped in place; returns the length left for the ramps [mm].
inline double fit_windows(double length, double vs, double ve, double& ws, double& we) noexcept {
  ws = vs > 0 ? std::min(ws, length) : 0.0;
  we = ve > 0 ? std::min(we, length - ws) : 0.0;
  return std::max(0.0, length - ws - we);
}

// Profile::make for the trapezoid (j = +inf): the same construction with a reciprocal of a and one
// division for the cruise; inline (as is Profile::make), since the planner's freeze runs it for every
// segment
inline Profile make_trapezoid(double length, double vs, double ve, double vmax, double a, double ws, double we) noexcept {
  Profile p;
  p.vs = vs;
  p.ve = ve;
  const double lr = fit_windows(length, vs, ve, ws, we);
  const double vlow = std::max(vs, ve);
  const double s2 = vs * vs + ve * ve;
  double vp = std::sqrt(std::max(0.0, (2.0 * a * lr + s2) / 2.0));
  vp = std::max(vlow, std::min(vp, std::max(vmax, vlow)));
  p.vp = vp;
  // rounding (or a speed-dependent a chosen by the caller at the peak): make both ramps fit
  if (lr > 0 && 2.0 * vp * vp - s2 > 2.0 * lr * a) a = (2.0 * vp * vp - s2) / (2.0 * lr);
  p.a = a;
  const double ia = 1.0 / a;
  p.d[0] = ws;
  p.t[0] = ws > 0 ? ws / vs : 0.0;
  p.t[1] = (vp - vs) * ia;  // vp ≥ max(vs, ve)
  p.d[1] = 0.5 * (vs + vp) * p.t[1];
  p.t[3] = (vp - ve) * ia;
  p.d[3] = 0.5 * (vp + ve) * p.t[3];
  p.d[4] = we;
  p.t[4] = we > 0 ? we / ve : 0.0;
  // the cruise takes what is left, so that the distances add up to the length exactly
  double d2 = std::max(0.0, lr - p.d[1] - p.d[3]);
  if (vp > 0) {
    d2 += length - (p.d[0] + p.d[1] + d2 + p.d[3] + p.d[4]);
    if (d2 < 0) d2 = 0;
    p.t[2] = d2 / vp;
  }
  p.d[2] = d2;
  p.duration = p.t[0] + p.t[1] + p.t[2] + p.t[3] + p.t[4];
  return p;
}
}  // namespace detail

inline Profile Profile::make(double length, double vs, double ve, double vmax, double a, double j, double ws,
                             double we) noexcept {
  return std::isfinite(j) ? detail::make_scurve(length, vs, ve, vmax, a, j, ws, we)
                          : detail::make_trapezoid(length, vs, ve, vmax, a, ws, we);
}

}  // namespace netshape::motion
