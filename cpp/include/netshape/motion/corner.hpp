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

/// seeds/002 eq. 4: Acc·Ts/(1 − cos θ) [mm/s] (+inf for θ = 0), θ the turn angle.
double paper_corner_speed(double acc, double ts, double theta) noexcept;

/// Vector velocity-jump bound: largest F with F·|u2 − u1| ≤ acc·ts [mm/s] (+inf when u1 = u2).
double vector_corner_speed(const Vec3& u1, const Vec3& u2, double acc, double ts) noexcept;

/// Per-axis bound: largest F with F·|u2_i − u1_i| ≤ acc_i·ts for every axis i [mm/s].
double per_axis_corner_speed(const Vec3& u1, const Vec3& u2, const Vec3& acc, double ts) noexcept;

/// grbl junction deviation: sqrt(acc·δ·sin(θ/2)/(1 − sin(θ/2))) [mm/s]; +inf for θ = 0.
double junction_deviation_speed(double acc, double deviation, double theta) noexcept;

/// Klipper: the junction deviation δ [mm] that makes a 90° corner run at `scv` [mm/s] with `acc`.
double klipper_junction_deviation(double square_corner_velocity, double acc) noexcept;

/// Smallest acceleration among the axes that move along u1 or u2 [mm/s^2] (seeds/002 "Acc").
double moving_axes_min(const Vec3& per_axis, const Vec3& u1, const Vec3& u2) noexcept;

/// Largest path acceleration (or velocity) along the unit direction u so that every axis
/// component stays within its limit: min_i limit_i/|u_i|.
double along(const Vec3& per_axis, const Vec3& u) noexcept;

}  // namespace netshape::motion
