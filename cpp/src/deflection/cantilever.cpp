#include "netshape/deflection/cantilever.hpp"

#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"
#include "netshape/core/types.hpp"

namespace netshape::deflection {

const char* to_string(InertiaModel m) noexcept { return m == InertiaModel::square ? "square" : "equivalent"; }

InertiaModel inertia_model_from_string(const std::string& s) {
  if (s == "square") return InertiaModel::square;
  if (s == "equivalent") return InertiaModel::equivalent;
  throw std::invalid_argument("inertia = " + s + ": must be \"square\" or \"equivalent\"");
}

double second_moment(double diameter, InertiaModel model) {
  NETSHAPE_CHECK_FINITE("diameter", diameter);
  NETSHAPE_CHECK(diameter > 0.0, "diameter", diameter, "must be positive [mm]");
  if (model == InertiaModel::square) return std::pow(diameter, 4) / 48.0;
  const double d = 0.8 * diameter;
  return pi * std::pow(d, 4) / 64.0;
}

void Cantilever::validate() const {
  NETSHAPE_CHECK_FINITE("stick_out", length);
  NETSHAPE_CHECK(length > 0.0, "stick_out", length, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("youngs_modulus", youngs_modulus);
  NETSHAPE_CHECK(youngs_modulus > 0.0, "youngs_modulus", youngs_modulus, "must be positive [MPa]");
  NETSHAPE_CHECK_FINITE("inertia", inertia);
  NETSHAPE_CHECK(inertia > 0.0, "inertia", inertia, "must be positive [mm^4]");
}

double Cantilever::influence(double x, double a) const noexcept {
  const double ei6 = 6.0 * youngs_modulus * inertia;
  if (x <= a) return x * x * (3.0 * a - x) / ei6;
  return a * a * (3.0 * x - a) / ei6;
}

Cantilever Cantilever::tool(double diameter, double stick_out, double youngs_modulus, InertiaModel model) {
  Cantilever c;
  c.length = stick_out;
  c.youngs_modulus = youngs_modulus;
  c.inertia = second_moment(diameter, model);
  c.validate();
  return c;
}

}  // namespace netshape::deflection
