#include "netshape/force/engagement.hpp"

#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"

namespace netshape::force {

const char* to_string(MillingMode m) noexcept {
  switch (m) {
    case MillingMode::up: return "up";
    case MillingMode::down: return "down";
    case MillingMode::slot: return "slot";
  }
  return "?";
}

MillingMode milling_mode_from_string(const std::string& s) {
  if (s == "up") return MillingMode::up;
  if (s == "down") return MillingMode::down;
  if (s == "slot") return MillingMode::slot;
  throw std::invalid_argument("mode = " + s + ": must be up, down or slot");
}

void AngularEngagement::validate() const {
  NETSHAPE_CHECK_FINITE("phi_st", phi_st);
  NETSHAPE_CHECK_FINITE("phi_ex", phi_ex);
  NETSHAPE_CHECK(phi_st >= 0.0 && phi_st < 2.0 * pi, "phi_st", phi_st, "must be in [0, 2π) [rad]");
  NETSHAPE_CHECK(phi_ex > phi_st && phi_ex <= phi_st + 2.0 * pi + 1e-12, "phi_ex", phi_ex,
                 "must be in (phi_st, phi_st + 2π] [rad]");
}

AngularEngagement AngularEngagement::from_mode(MillingMode mode, double radius, double radial_depth) {
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "radius", radius, "must be positive [mm]");
  AngularEngagement e;
  if (mode == MillingMode::slot) {
    e.phi_st = 0.0;
    e.phi_ex = pi;
    return e;
  }
  NETSHAPE_CHECK_FINITE("ae", radial_depth);
  NETSHAPE_CHECK(radial_depth > 0.0 && radial_depth <= 2.0 * radius * (1 + 1e-12), "ae", radial_depth,
                 "radial depth must be in (0, D] [mm]");
  const double w = std::acos(std::max(-1.0, 1.0 - radial_depth / radius));
  if (mode == MillingMode::up) {
    e.phi_st = 0.0;
    e.phi_ex = w;
  } else {
    e.phi_st = pi - w;
    e.phi_ex = pi;
  }
  return e;
}

EngagementMap EngagementMap::from_window(const AngularEngagement& window, int disks, int bins) {
  window.validate();
  NETSHAPE_CHECK(disks >= 1, "disks", disks, "must be at least 1");
  NETSHAPE_CHECK(bins >= 4, "bins", bins, "must be at least 4");
  EngagementMap m;
  m.mask.resize(disks, bins);
  const double span = window.phi_ex - window.phi_st;
  for (int b = 0; b < bins; ++b) {
    double u = (b + 0.5) * 2.0 * pi / bins - window.phi_st;
    u -= 2.0 * pi * std::floor(u / (2.0 * pi));
    const std::uint8_t v = u <= span ? 1 : 0;
    for (int i = 0; i < disks; ++i) m.mask(i, b) = v;
  }
  return m;
}

}  // namespace netshape::force
