// Machine model: validation and names.
#include "netshape/machine/machine.hpp"

#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"

namespace netshape::machine {

namespace {
const char* const kAxisLetters = "XYZ";
const char* const kComponentLetters = "XYZABC";

void check_finite_vec(const std::string& field, const Vec3& v) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i])) {
      const std::string f = field + "[" + std::to_string(i) + "]";
      detail::throw_invalid(f.c_str(), v[i], "must be a finite number");
    }
  }
}
}  // namespace

std::string component_name(Component c, int axis) {
  if (axis < 0 || axis > 2) detail::throw_invalid("axis", axis, "must be 0 (X), 1 (Y) or 2 (Z)");
  std::string s = "E";
  s += kComponentLetters[static_cast<int>(c)];
  s += kAxisLetters[axis];
  return s;
}

void Machine::validate() const {
  std::array<int, 3> seen{0, 0, 0};
  for (int k : tool_chain) {
    NETSHAPE_CHECK(k >= 0 && k <= 2, "tool_chain axis", k, "must be 0 (X), 1 (Y) or 2 (Z)");
    ++seen[k];
  }
  for (int k : workpiece_chain) {
    NETSHAPE_CHECK(k >= 0 && k <= 2, "workpiece_chain axis", k, "must be 0 (X), 1 (Y) or 2 (Z)");
    ++seen[k];
  }
  for (int k = 0; k < 3; ++k) {
    const std::string field = std::string("axis ") + kAxisLetters[k];
    NETSHAPE_CHECK(seen[k] == 1, field.c_str(), seen[k],
                   "times in tool_chain + workpiece_chain: every axis X, Y, Z must appear exactly once");
  }
  for (int k = 0; k < 3; ++k) {
    const Axis& a = axes[k];
    const std::string ax(1, kAxisLetters[k]);
    NETSHAPE_CHECK(std::isfinite(a.travel_min), (ax + " travel_min").c_str(), a.travel_min,
                   "must be a finite number [mm]");
    NETSHAPE_CHECK(std::isfinite(a.travel_max), (ax + " travel_max").c_str(), a.travel_max,
                   "must be a finite number [mm]");
    NETSHAPE_CHECK(a.travel_min < a.travel_max, (ax + " travel_max").c_str(), a.travel_max,
                   "must be greater than travel_min [mm]");
    check_finite_vec(ax + " origin", a.origin);
    for (int c = 0; c < 6; ++c) a.errors[c].validate();
    for (const CyclicTerm& t : a.cyclic) {
      NETSHAPE_CHECK(std::isfinite(t.amplitude) && t.amplitude >= 0, (ax + " cyclic amplitude").c_str(),
                     t.amplitude, "must be a finite number ≥ 0 [mm]");
      NETSHAPE_CHECK(std::isfinite(t.period) && t.period > 0, (ax + " cyclic period").c_str(), t.period,
                     "must be a finite number > 0 [mm]");
      NETSHAPE_CHECK_FINITE((ax + " cyclic phase").c_str(), t.phase);
    }
    NETSHAPE_CHECK_FINITE((ax + " backlash").c_str(), a.backlash);
  }
  for (const ThermalDrift& t : thermal) {
    NETSHAPE_CHECK(t.axis >= 0 && t.axis <= 2, "thermal axis", t.axis, "must be 0 (X), 1 (Y) or 2 (Z)");
    NETSHAPE_CHECK_FINITE("thermal amplitude", t.amplitude);
    NETSHAPE_CHECK(std::isfinite(t.time_constant) && t.time_constant > 0, "thermal time_constant",
                   t.time_constant, "must be a finite number > 0 [s]");
  }
  NETSHAPE_CHECK_FINITE("EC0Y", ec0y);
  NETSHAPE_CHECK_FINITE("EB0Z", eb0z);
  NETSHAPE_CHECK_FINITE("EA0Z", ea0z);
  NETSHAPE_CHECK_FINITE("spindle_tilt_a", spindle_tilt_a);
  NETSHAPE_CHECK_FINITE("spindle_tilt_b", spindle_tilt_b);
  check_finite_vec("spindle_nose", spindle_nose);
  check_finite_vec("tool_direction", tool_direction);
  NETSHAPE_CHECK(std::isfinite(tool_length) && tool_length >= 0, "tool_length", tool_length,
                 "must be a finite number ≥ 0 [mm]");
  NETSHAPE_CHECK(std::abs(tool_direction.norm() - 1.0) < 1e-9, "tool_direction norm", tool_direction.norm(),
                 "must be a unit vector");
}

bool Machine::has_state_errors() const noexcept {
  if (!thermal.empty()) return true;
  for (const Axis& a : axes)
    if (a.backlash != 0.0) return true;
  return false;
}

Side Machine::side(int axis) const {
  for (int k : tool_chain)
    if (k == axis) return Side::tool;
  for (int k : workpiece_chain)
    if (k == axis) return Side::workpiece;
  detail::throw_invalid("axis", axis, "is in neither chain");
}

Machine ideal_machine(std::vector<int> tool_chain, std::vector<int> workpiece_chain, double tool_length) {
  Machine m;
  m.name = "ideal";
  m.tool_chain = std::move(tool_chain);
  m.workpiece_chain = std::move(workpiece_chain);
  m.tool_length = tool_length;
  m.validate();
  return m;
}

}  // namespace netshape::machine
