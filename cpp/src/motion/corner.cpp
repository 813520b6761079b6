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

double junction_deviation_speed(double acc, double deviation, double theta) noexcept {
  const double s = std::sin(0.5 * theta);
  if (s <= 0) return inf;
  if (s >= 1.0 - 1e-12) return 0.0;  // reversal: stop
  return std::sqrt(acc * deviation * s / (1.0 - s));
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
