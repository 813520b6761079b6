// plan(): the fine-sample bound and the look-ahead ring sized by the program.
#include <doctest/doctest.h>

#include <stdexcept>
#include <vector>

#include "netshape/motion.hpp"
#include "netshape/toolpath.hpp"

using namespace netshape;
using namespace netshape::motion;

namespace {
std::vector<toolpath::Block> square() {
  return toolpath::parse_gcode("G21 G90\nG1 X10 F600\nG1 Y10\nG1 X0\nG1 Y0\nG1 X5\n", "sq").blocks;
}
}  // namespace

TEST_CASE("plan: max_samples stops the planner with invalid_argument naming it") {
  PlanOptions o;
  o.rule = CornerRule::vector;
  const AxisLimits lim = AxisLimits::uniform(200, 2000);
  const Trajectory full = plan(square(), lim, o);
  const long n = full.stats.samples;
  CHECK(plan(square(), lim, o, true, n).stats.samples == n);
  CHECK_THROWS_WITH_AS(plan(square(), lim, o, true, n - 1), doctest::Contains("max_samples = "),
                       std::invalid_argument);
  CHECK_THROWS_AS(plan(square(), lim, o, true, -1), std::invalid_argument);
}

TEST_CASE("plan: a look-ahead deeper than the program plans the same trajectory") {
  const AxisLimits lim = AxisLimits::uniform(200, 2000);
  for (CornerRule r : {CornerRule::vector, CornerRule::blend}) {
    PlanOptions a, b;
    a.rule = b.rule = r;
    a.lookahead = 7;
    b.lookahead = 1000000;  // its ring alone would take ~30 GB
    const Trajectory x = plan(square(), lim, a), y = plan(square(), lim, b);
    REQUIRE(x.t.size() == y.t.size());
    CHECK(x.position == y.position);
    CHECK(x.stats.cycle_time == y.stats.cycle_time);
  }
}
