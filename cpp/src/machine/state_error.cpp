// State-dependent tip errors: backlash from the approach direction, thermal drift from the program time.
#include "netshape/machine/state_error.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::machine {

Vec3 state_error(const Machine& machine, const Vec3& direction, double time) noexcept {
  Vec3 s = Vec3::Zero();
  for (int k = 0; k < 3; ++k) s[k] = 0.5 * machine.axes[k].backlash * direction[k];
  for (const ThermalDrift& t : machine.thermal) s[t.axis] -= t.amplitude * std::expm1(-time / t.time_constant);
  return s;
}

Points3 state_error(const Machine& machine, const Eigen::Ref<const Points3>& directions,
                    const Eigen::Ref<const Eigen::VectorXd>& times) {
  NETSHAPE_CHECK(times.size() == directions.rows(), "times size", times.size(),
                 "must equal the number of direction rows");
  Points3 out(directions.rows(), 3);
  for (Eigen::Index i = 0; i < directions.rows(); ++i) {
    NETSHAPE_CHECK_FINITE("times", times[i]);
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("directions", directions(i, c));
    out.row(i) = state_error(machine, Vec3(directions.row(i).transpose()), times[i]).transpose();
  }
  return out;
}

Points3 approach_directions(const Eigen::Ref<const Points3>& path, const Vec3& initial, double resolution) {
  Points3 out(path.rows(), 3);
  Vec3 d = initial;
  for (Eigen::Index i = 0; i < path.rows(); ++i) {
    if (i > 0)
      for (int k = 0; k < 3; ++k) {
        const double step = path(i, k) - path(i - 1, k);
        if (std::abs(step) > resolution) d[k] = step > 0 ? 1.0 : -1.0;
      }
    out.row(i) = d.transpose();
  }
  return out;
}

}  // namespace netshape::machine
