#include "netshape/motion/limits.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::motion {

AxisLimits AxisLimits::uniform(double vmax, double amax, double jmax) {
  AxisLimits l;
  l.velocity = Vec3::Constant(vmax);
  l.acceleration = Vec3::Constant(amax);
  l.jerk = Vec3::Constant(jmax);
  return l;
}

bool AxisLimits::jerk_limited() const noexcept {
  return std::isfinite(jerk[0]) || std::isfinite(jerk[1]) || std::isfinite(jerk[2]);
}

void AxisLimits::validate() const {
  static const char* vname[3] = {"limits.velocity.x", "limits.velocity.y", "limits.velocity.z"};
  static const char* aname[3] = {"limits.acceleration.x", "limits.acceleration.y", "limits.acceleration.z"};
  static const char* jname[3] = {"limits.jerk.x", "limits.jerk.y", "limits.jerk.z"};
  for (int i = 0; i < 3; ++i) {
    NETSHAPE_CHECK(std::isfinite(velocity[i]) && velocity[i] > 0, vname[i], velocity[i],
                   "must be a positive finite velocity [mm/s]");
    NETSHAPE_CHECK(std::isfinite(acceleration[i]) && acceleration[i] > 0, aname[i], acceleration[i],
                   "must be a positive finite acceleration [mm/s^2]");
    NETSHAPE_CHECK(!std::isnan(jerk[i]) && jerk[i] > 0, jname[i], jerk[i],
                   "must be a positive jerk [mm/s^3] (inf: not jerk-limited)");
  }
}

}  // namespace netshape::motion
