#pragma once
/// \file corner.hpp
/// Corner speed of each rule at a junction between unit tangents u1 (end of the previous block) and
/// u2 (start of the next). Free functions so they can be tested and compared on their own.

#include "netshape/core/types.hpp"
#include "netshape/motion/limits.hpp"
#include "netshape/motion/options.hpp"

namespace netshape::motion {

/// Turn angle θ between two unit tangents [rad] (0 = straight on, π = reversal).
double turn_angle(const Vec3& u1, const Vec3& u2) noexcept;

/// Lee & Lee eq. 4: Acc·Ts/(1 − cos θ) [mm/s] (+inf for θ = 0), θ the turn angle.
double paper_corner_speed(double acc, double ts, double theta) noexcept;

/// Vector velocity-jump bound: largest F with F·|u2 − u1| ≤ acc·ts [mm/s] (+inf when u1 = u2).
double vector_corner_speed(const Vec3& u1, const Vec3& u2, double acc, double ts) noexcept;

/// Per-axis bound: largest F with F·|u2_i − u1_i| ≤ acc_i·ts for every axis i [mm/s].
double per_axis_corner_speed(const Vec3& u1, const Vec3& u2, const Vec3& acc, double ts) noexcept;

/// Junction deviation (grbl `$11`) at a turn φ between the unit tangents [rad] (0 = straight on,
/// π = reversal): the circle tangent to both moves whose nearest point is δ [mm] from the vertex has
/// radius r = δ·cos(φ/2)/(1 − cos(φ/2)), and v = √(acc·r) [mm/s]. +inf for φ = 0, 0 for φ = π.
/// (grbl writes it with the angle between the two moves at the vertex, θ = π − φ: sin(θ/2) = cos(φ/2).)
double junction_deviation_speed(double acc, double deviation, double turn) noexcept;

/// The acceleration [mm/s^2] the junction-deviation rule uses at the corner u1 → u2 (unit tangents):
/// min_moving_axis: the smallest limit of the axes that move along u1 or u2 (moving_axes_min);
/// along_change: grbl's limit along the velocity change, min_i A_i/|e_i| with e = unit(u2 − u1)
/// (min_moving_axis when u1 = u2).
double junction_acceleration(const Vec3& per_axis, const Vec3& u1, const Vec3& u2, JunctionAccel mode) noexcept;

/// Corner speed of the junction-deviation rule between unit tangents u1 and u2 with per-axis
/// accelerations `per_axis` [mm/s^2] and deviation δ [mm] [mm/s]: junction_deviation_speed with the
/// turn angle of u1, u2 and junction_acceleration. +inf for a straight continuation.
double junction_deviation_corner_speed(const Vec3& u1, const Vec3& u2, const Vec3& per_axis, double deviation,
                                       JunctionAccel mode) noexcept;

/// Klipper: the junction deviation δ [mm] that makes a 90° corner run at `scv` [mm/s] with `acc`.
double klipper_junction_deviation(double square_corner_velocity, double acc) noexcept;

/// Smallest acceleration among the axes that move along u1 or u2 [mm/s^2] (Lee & Lee's "Acc").
double moving_axes_min(const Vec3& per_axis, const Vec3& u1, const Vec3& u2) noexcept;

/// Largest path acceleration (or velocity) along the unit direction u so that every axis
/// component stays within its limit: min_i limit_i/|u_i|.
double along(const Vec3& per_axis, const Vec3& u) noexcept;

}  // namespace netshape::motion
