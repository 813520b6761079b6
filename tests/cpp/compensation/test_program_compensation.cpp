// Program compensation from C++ (what a CAM plugin calls): the actual path of the compensated program
// follows the nominal one within the chord tolerance, commands keep their places, failures name the line.
// Reference: S.-H. Yang and S.-H. Kweon, volumetric error compensation in the post-processor, §4.2
// (docs/references.md); the check below is independent of the method: the compensated program is
// run through the machine model (p + e(p)) and measured against the nominal blocks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "netshape/compensation.hpp"
#include "netshape/machine.hpp"
#include "netshape/toolpath.hpp"

using namespace netshape;
using namespace netshape::machine;
using namespace netshape::compensation;
using toolpath::MotionKind;

namespace {
Machine test_machine() {
  Machine m = ideal_machine({0, 1}, {2}, 100.0);
  for (int k = 0; k < 3; ++k) {
    m.axes[k].travel_min = -500;
    m.axes[k].travel_max = 500;
  }
  m.axes[0].errors[0] = ErrorFunction::polynomial({0.01, 2e-4, 1e-7});   // EXX: positioning [mm]
  m.axes[1].errors[0] = ErrorFunction::polynomial({0.0, 3e-5});           // EXY: straightness [mm]
  m.axes[1].errors[5] = ErrorFunction::polynomial({0.0, 1e-7});           // ECY: yaw [rad]
  m.ec0y = 5e-5;
  m.validate();
  return m;
}

// Distance [mm] of p from the nominal block b (a line, or an arc in the XY plane at constant Z).
double distance_to(const toolpath::Block& b, const Vec3& p) {
  if (b.kind != MotionKind::arc) {
    const Vec3 ab = b.end - b.start;
    const double t = std::clamp((p - b.start).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (b.start + t * ab)).norm();
  }
  const double r = std::hypot(p.x() - b.center.x(), p.y() - b.center.y());
  return std::hypot(r - b.radius(), p.z() - b.start.z());
}

const char* kProgram =
    "(pocket corner)\n"
    "G21 G90 G17\n"
    "T1 M6\n"
    "S8000 M3\n"
    "G0 X-100 Y-50 Z5\n"
    "G1 Z0 F600\n"
    "G1 X150\n"
    "M8\n"
    "G3 X200 Y0 R50\n"
    "G1 Y120\n"
    "G2 X160 Y160 I-40 J0\n"
    "M30\n";
}  // namespace

TEST_CASE("a compensated program's actual path follows the nominal program") {
  const Machine m = test_machine();
  const toolpath::Toolpath nominal = toolpath::parse_gcode(kProgram, "corner.ngc");
  ProgramOptions opt;
  opt.chord_tolerance = 0.001;
  const ProgramResult res = compensate_program(m, nominal, opt);
  const toolpath::Toolpath& out = res.toolpath;
  CHECK(res.report.blocks_in == static_cast<long>(nominal.blocks.size()));
  CHECK(res.report.blocks_out == static_cast<long>(out.blocks.size()));
  CHECK(res.report.max_residual <= 1e-9);
  CHECK(res.report.max_correction > 0.01);  // there was something to compensate
  CHECK(res.report.max_path_deviation <= opt.chord_tolerance);
  // commands: same texts in the same order
  REQUIRE(out.commands.size() == nominal.commands.size());
  for (std::size_t i = 0; i < out.commands.size(); ++i) CHECK(out.commands[i].text == nominal.commands[i].text);
  // run every feed block of the output through the machine model and measure it against its source block
  double worst = 0.0, worst_uncompensated = 0.0;
  MachineData data(m);
  std::size_t src = 0;
  for (const auto& b : out.blocks) {
    while (nominal.blocks[src].line != b.line) ++src;
    const toolpath::Block& nb = nominal.blocks[src];
    if (nb.kind == MotionKind::rapid) continue;
    CHECK(b.feed == nb.feed);
    CHECK(b.tool == 1);
    for (double s : {0.0, 0.125, 0.25, 0.5, 0.75, 0.875, 1.0}) {
      const Vec3 p = b.point_at(s);
      const Vec3 actual = p + tip_error(m, data, p);
      worst = std::max(worst, distance_to(nb, actual));
    }
  }
  for (const auto& b : nominal.blocks) {
    if (b.kind == MotionKind::rapid) continue;
    const Vec3 p = b.point_at(0.5);
    worst_uncompensated = std::max(worst_uncompensated, distance_to(b, p + tip_error(m, data, p)));
  }
  CHECK(worst <= opt.chord_tolerance + 1e-9);
  CHECK(worst_uncompensated > 10 * opt.chord_tolerance);  // the check can fail
}

TEST_CASE("program compensation refuses bad input naming the field or the line") {
  Machine m = test_machine();
  const toolpath::Toolpath nominal = toolpath::parse_gcode(kProgram, "corner.ngc");
  ProgramOptions opt;
  opt.chord_tolerance = 0.0;
  CHECK_THROWS_WITH_AS(compensate_program(m, nominal, opt), doctest::Contains("chord_tolerance"),
                       std::invalid_argument);
  m.axes[0].travel_max = 199.9;  // the arc end X = 200 (line 9) needs the command X = 199.946
  try {
    compensate_program(m, nominal);
    FAIL("no throw");
  } catch (const std::invalid_argument& e) {
    INFO(std::string(e.what()));
    CHECK(std::string(e.what()).find("corner.ngc:9: compensated axis X") == 0);
  }
}
