#include "netshape/cutter/cutter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"

namespace netshape::cutter {

void Cutter::validate() const {
  NETSHAPE_CHECK_FINITE("cutter.radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "cutter.radius", radius, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("cutter.corner_radius", corner_radius);
  switch (kind) {
    case CutterKind::flat:
      NETSHAPE_CHECK(corner_radius == 0.0, "cutter.corner_radius", corner_radius,
                     "must be 0 for a flat end mill [mm]");
      break;
    case CutterKind::ball:
      NETSHAPE_CHECK(std::abs(corner_radius - radius) <= 1e-12 * radius, "cutter.corner_radius", corner_radius,
                     "must equal the radius for a ball end mill [mm]");
      break;
    case CutterKind::bull:
      NETSHAPE_CHECK(corner_radius > 0.0 && corner_radius < radius, "cutter.corner_radius", corner_radius,
                     "must be between 0 and the radius (exclusive) for a bull-nose end mill [mm]");
      break;
  }
  check_flutes(flutes, "cutter.flutes");
  NETSHAPE_CHECK_FINITE("cutter.helix", helix);
  NETSHAPE_CHECK(helix >= 0.0 && helix < 1.4835298641951802, "cutter.helix", helix,
                 "must be in [0, 85°) [rad]");
  NETSHAPE_CHECK_FINITE("cutter.flute_length", flute_length);
  NETSHAPE_CHECK(flute_length > 0.0, "cutter.flute_length", flute_length, "must be positive [mm]");
  NETSHAPE_CHECK(flute_length >= corner_radius, "cutter.flute_length", flute_length,
                 "must be at least the corner radius [mm]");
  NETSHAPE_CHECK_FINITE("cutter.stick_out", stick_out);
  NETSHAPE_CHECK(stick_out >= flute_length, "cutter.stick_out", stick_out,
                 "must be at least the flute length [mm]");
  NETSHAPE_CHECK_FINITE("cutter.youngs_modulus", youngs_modulus);
  NETSHAPE_CHECK(youngs_modulus > 0.0, "cutter.youngs_modulus", youngs_modulus, "must be positive [MPa]");
  NETSHAPE_CHECK_FINITE("cutter.holder_compliance", holder_compliance);
  NETSHAPE_CHECK(holder_compliance >= 0.0, "cutter.holder_compliance", holder_compliance, "must be ≥ 0 [mm/N]");
  NETSHAPE_CHECK_FINITE("cutter.runout_rho", runout_rho);
  NETSHAPE_CHECK(runout_rho >= 0.0 && runout_rho < radius, "cutter.runout_rho", runout_rho,
                 "must be ≥ 0 and below the radius [mm]");
  NETSHAPE_CHECK_FINITE("cutter.runout_lambda", runout_lambda);
}

double Cutter::radius_at(double z) const noexcept {
  if (z <= 0.0) return kind == CutterKind::flat ? radius : (kind == CutterKind::bull ? radius - corner_radius : 0.0);
  const double rc = corner_radius;
  if (rc <= 0.0 || z >= rc) return radius;
  // torus section: centre of the corner circle at (R - rc, rc)
  const double dz = rc - z;
  return (radius - rc) + std::sqrt(std::max(0.0, rc * rc - dz * dz));
}

double Cutter::helix_lag() const noexcept { return std::tan(helix) / radius; }

Cutter Cutter::flat_end(double diameter, int flutes, double helix_rad) {
  Cutter c;
  c.kind = CutterKind::flat;
  c.radius = 0.5 * diameter;
  c.corner_radius = 0.0;
  c.flutes = flutes;
  c.helix = helix_rad;
  c.flute_length = std::max(c.flute_length, 2.0 * diameter);
  c.stick_out = std::max(c.stick_out, c.flute_length + diameter);
  c.validate();
  return c;
}

Cutter Cutter::ball_end(double diameter, int flutes, double helix_rad) {
  Cutter c = flat_end(diameter, flutes, helix_rad);
  c.kind = CutterKind::ball;
  c.corner_radius = c.radius;
  c.validate();
  return c;
}

Cutter Cutter::bull_nose(double diameter, double corner_radius, int flutes, double helix_rad) {
  Cutter c = flat_end(diameter, flutes, helix_rad);
  c.kind = CutterKind::bull;
  c.corner_radius = corner_radius;
  c.validate();
  return c;
}

void check_flutes(int flutes, const char* field) {
  NETSHAPE_CHECK(flutes >= 1 && flutes <= max_flutes, field, flutes, "must be between 1 and 64");
}

const char* to_string(CutterKind k) noexcept {
  switch (k) {
    case CutterKind::ball: return "ball";
    case CutterKind::bull: return "bull";
    case CutterKind::flat:
    default: return "flat";
  }
}

CutterKind cutter_kind_from_string(const std::string& s) {
  if (s == "flat") return CutterKind::flat;
  if (s == "ball") return CutterKind::ball;
  if (s == "bull" || s == "bullnose" || s == "bull-nose") return CutterKind::bull;
  throw std::invalid_argument("cutter.kind = '" + s + "': must be one of flat, ball, bull");
}

}  // namespace netshape::cutter
