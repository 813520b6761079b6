#include "netshape/motion/options.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::motion {

const char* rule_name(CornerRule rule) noexcept {
  switch (rule) {
    case CornerRule::paper: return "paper";
    case CornerRule::vector: return "vector";
    case CornerRule::per_axis: return "per-axis";
    case CornerRule::junction_deviation: return "junction-deviation";
    case CornerRule::blend: return "blend";
  }
  return "?";
}

CornerRule parse_rule(const std::string& name) {
  std::string n = name;
  for (char& c : n)
    if (c == '_') c = '-';
  for (CornerRule r : {CornerRule::paper, CornerRule::vector, CornerRule::per_axis,
                       CornerRule::junction_deviation, CornerRule::blend})
    if (n == rule_name(r)) return r;
  NETSHAPE_CHECK(false, "rule", name, "must be paper, vector, per-axis, junction-deviation or blend");
  return CornerRule::vector;
}

const char* junction_accel_name(JunctionAccel mode) noexcept {
  switch (mode) {
    case JunctionAccel::min_moving_axis: return "min-moving-axis";
    case JunctionAccel::along_change: return "along-change";
  }
  return "?";
}

JunctionAccel parse_junction_accel(const std::string& name) {
  std::string n = name;
  for (char& c : n)
    if (c == '_') c = '-';
  for (JunctionAccel m : {JunctionAccel::min_moving_axis, JunctionAccel::along_change})
    if (n == junction_accel_name(m)) return m;
  NETSHAPE_CHECK(false, "junction_accel", name, "must be min-moving-axis or along-change");
  return JunctionAccel::min_moving_axis;
}

int PlanOptions::fine_steps() const noexcept {
  return static_cast<int>(std::lround(ts1 / ts2));
}

void PlanOptions::validate() const {
  NETSHAPE_CHECK(std::isfinite(ts2) && ts2 > 0 && ts2 <= 1.0, "ts2", ts2, "must be in (0, 1] [s]");
  NETSHAPE_CHECK(std::isfinite(ts1) && ts1 >= ts2 && ts1 <= 1.0, "ts1", ts1, "must be in [ts2, 1] [s]");
  const double n = ts1 / ts2;
  NETSHAPE_CHECK(std::abs(n - std::round(n)) <= 1e-6 * n, "ts1", ts1,
                 "must be an integer multiple of ts2 [s]");
  NETSHAPE_CHECK(lookahead >= 2 && lookahead <= 1000000, "lookahead", lookahead, "must be in [2, 1e6] blocks");
  NETSHAPE_CHECK(std::isfinite(allowable_speed_difference) && allowable_speed_difference >= 0,
                 "allowable_speed_difference", allowable_speed_difference, "must be >= 0 [mm/s]");
  // below a nanometre a blend is numerically a sharp corner: refused rather than planned with a jump
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance >= min_tolerance, "tolerance", tolerance,
                 "must be >= 1e-06 [mm]");
  NETSHAPE_CHECK(std::isfinite(corner_tolerance) && (corner_tolerance == 0 || corner_tolerance >= min_tolerance),
                 "corner_tolerance", corner_tolerance, "must be 0 or >= 1e-06 [mm]");
  NETSHAPE_CHECK(std::isfinite(junction_deviation) && junction_deviation >= 0, "junction_deviation",
                 junction_deviation, "must be >= 0 [mm]");
  NETSHAPE_CHECK(std::isfinite(square_corner_velocity) && square_corner_velocity >= 0,
                 "square_corner_velocity", square_corner_velocity, "must be >= 0 [mm/s]");
  NETSHAPE_CHECK(rule != CornerRule::junction_deviation || junction_deviation > 0 || square_corner_velocity > 0,
                 "junction_deviation", junction_deviation,
                 "junction-deviation rule needs junction_deviation > 0 or square_corner_velocity > 0");
  NETSHAPE_CHECK(junction_accel == JunctionAccel::min_moving_axis || junction_accel == JunctionAccel::along_change,
                 "junction_accel", static_cast<int>(junction_accel), "must be min_moving_axis or along_change");
  NETSHAPE_CHECK(std::isfinite(centripetal_fraction) && centripetal_fraction > 0 && centripetal_fraction < 1,
                 "centripetal_fraction", centripetal_fraction, "must be in (0, 1)");
}

}  // namespace netshape::motion
