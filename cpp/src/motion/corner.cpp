#include "netshape/motion/corner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace netshape::motion {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
}

double turn_angle(const Vec3& u1, const Vec3& u2) noexcept {
  // atan2 of |u1 x u2| and u1.u2 is accurate for small and large angles alike
  return std::atan2(u1.cross(u2).norm(), u1.dot(u2));
}

double paper_corner_speed(double acc, double ts, double theta) noexcept {
  const double c = 1.0 - std::cos(theta);
  return c > 0 ? acc * ts / c : inf;
}

double vector_corner_speed(const Vec3& u1, const Vec3& u2, double acc, double ts) noexcept {
  const double d = (u2 - u1).norm();
  return d > 0 ? acc * ts / d : inf;
}

double per_axis_corner_speed(const Vec3& u1, const Vec3& u2, const Vec3& acc, double ts) noexcept {
  double v = inf;
  for (int i = 0; i < 3; ++i) {
    const double d = std::abs(u2[i] - u1[i]);
    if (d > 0) v = std::min(v, acc[i] * ts / d);
  }
  return v;
}

double junction_deviation_speed(double acc, double deviation, double turn) noexcept {
  // v² = a·δ·c/(1 − c), c = cos(φ/2); 1 − c = 2·sin²(φ/4) keeps the gentle turns accurate
  const double c = std::cos(0.5 * turn);
  const double s = std::sin(0.25 * turn);
  const double one_minus_c = 2.0 * s * s;
  if (!(one_minus_c > 0)) return inf;  // straight on
  if (!(c > 1e-12)) return 0.0;        // reversal (cos(π/2) rounds to 6e-17): stop
  return std::sqrt(acc * deviation * c / one_minus_c);
}

double junction_acceleration(const Vec3& per_axis, const Vec3& u1, const Vec3& u2, JunctionAccel mode) noexcept {
  if (mode == JunctionAccel::along_change) {
    const Vec3 d = u2 - u1;
    const double n = d.norm();
    if (n > 0) return along(per_axis, Vec3(d / n));
  }
  return moving_axes_min(per_axis, u1, u2);
}

double junction_deviation_corner_speed(const Vec3& u1, const Vec3& u2, const Vec3& per_axis, double deviation,
                                       JunctionAccel mode) noexcept {
  return junction_deviation_speed(junction_acceleration(per_axis, u1, u2, mode), deviation, turn_angle(u1, u2));
}

double klipper_junction_deviation(double square_corner_velocity, double acc) noexcept {
  return square_corner_velocity * square_corner_velocity * (std::sqrt(2.0) - 1.0) / acc;
}

double moving_axes_min(const Vec3& per_axis, const Vec3& u1, const Vec3& u2) noexcept {
  double a = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(u1[i]) > 1e-12 || std::abs(u2[i]) > 1e-12) a = std::min(a, per_axis[i]);
  return std::isfinite(a) ? a : per_axis.minCoeff();
}

double along(const Vec3& per_axis, const Vec3& u) noexcept {
  double a = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(u[i]) > 1e-12) a = std::min(a, per_axis[i] / std::abs(u[i]));
  return std::isfinite(a) ? a : per_axis.minCoeff();
}

}  // namespace netshape::motion
