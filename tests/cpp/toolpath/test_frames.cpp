// A program's frames: to_machine applies the offset in force at each block as the reader does when given
// the offsets (for moves that give every axis after an offset change: the reader keeps the machine
// position of an axis not given, a program-frame tool path its program position), to_program undoes it,
// the writer writes the program coordinates of either; the sampler's points lie on the moves at the
// stated spacing.
#include <doctest/doctest.h>

#include <cmath>

#include "netshape/toolpath.hpp"

using namespace netshape;
using namespace netshape::toolpath;

namespace {

const char* two_offsets =
    "G21 G90 G17 G94\nG54\nG0 Z5\nG0 X-10 Y-5\nG1 Z-1 F300\nG1 X10 F900\nG2 X10 Y5 I0 J5\nG0 Z5\n"
    "G55\nG43 H1\nG0 X-10 Y-5 Z5\nG1 Z-1 F300\nG3 X10 Y5 I10 J5\nM30\n";

WorkOffsets offsets() {
  WorkOffsets o = WorkOffsets::Zero();
  o.row(0) << -150.0, 80.0, -300.0;
  o.row(1) << 120.0, -60.0, -280.0;
  return o;
}

}  // namespace

TEST_CASE("frames: to_machine equals reading with the offsets; to_program undoes it") {
  const Toolpath program = parse_gcode(two_offsets, "two.ngc");
  ReaderOptions ro;
  ro.has_work_offsets = true;
  ro.work_offsets = offsets();
  const Toolpath read = parse_gcode(two_offsets, "two.ngc", ro);
  const Toolpath machine = to_machine(program, offsets());
  REQUIRE(machine.blocks.size() == read.blocks.size());
  CHECK(machine.work_offsets == offsets());
  const std::vector<int> idx = work_offset_index(program);
  for (std::size_t k = 0; k < read.blocks.size(); ++k) {
    CHECK((machine.blocks[k].end - read.blocks[k].end).norm() < 1e-12);
    CHECK(idx[k] == (k < 6 ? 0 : 1));
  }
  const Points3 d = block_offsets(machine);
  CHECK(d.row(0).transpose() == offsets().row(0).transpose());
  CHECK(d.row(6).transpose() == offsets().row(1).transpose());
  const Toolpath back = to_program(machine);
  CHECK(back.work_offsets.isZero(0.0));
  for (std::size_t k = 0; k < back.blocks.size(); ++k) {
    CHECK((back.blocks[k].start - program.blocks[k].start).norm() < 1e-12);
    CHECK((back.blocks[k].center - program.blocks[k].center).norm() < 1e-12);
  }
  CHECK_THROWS_AS(to_machine(machine, offsets()), std::invalid_argument);
}

TEST_CASE("frames: the writer writes a machine-frame tool path in program coordinates") {
  const Toolpath program = parse_gcode("G54\nG0 X1 Y2 Z5\nG1 Z-1 F300\nG2 X3 Y2 I1 J0\n", "one.ngc");
  const Toolpath again = parse_gcode(format_gcode(to_machine(program, offsets())), "again.ngc");
  REQUIRE(again.blocks.size() == program.blocks.size());
  for (std::size_t k = 0; k < again.blocks.size(); ++k) {
    CHECK((again.blocks[k].end - program.blocks[k].end).norm() < 1e-9);
    CHECK((again.blocks[k].center - program.blocks[k].center).norm() < 1e-9);
  }
}

TEST_CASE("frames: a zero offset keeps the block bit for bit") {
  Toolpath program = parse_gcode("G1 X1 F100\n", "z.ngc");
  program.blocks[0].end.x() = -0.0;
  const Toolpath machine = to_machine(program, WorkOffsets::Zero());
  CHECK(std::signbit(machine.blocks[0].end.x()));
}

TEST_CASE("writer: work_offset_word names G54 when the program selects no offset first") {
  const Toolpath bare = parse_gcode("G1 X1 Y2 F100\n", "bare.ngc");
  WriterOptions o;
  o.work_offset_word = true;
  CHECK(format_gcode(bare, o) == "G21 G90 G17 G94 G91.1\nG54\nG1 X1 Y2 F100\nM2\n");
  const Toolpath selected = parse_gcode("G55\nG1 X1 Y2 F100\n", "g55.ngc");
  CHECK(format_gcode(selected, o) == format_gcode(selected));
}

TEST_CASE("sample: points every <= spacing along the feed moves, s their distance") {
  const Toolpath tp = parse_gcode("G0 X0 Y0 Z0\nG1 X1 F100\nG0 X5\nG1 Y2\nG2 X7 Y2 I1 J0\n", "s.ngc");
  const Samples all = sample(tp, 0.25, false);
  const Samples feeds = sample(tp, 0.25, true);
  CHECK(feeds.points.rows() < all.points.rows());
  // the first feed move: 4 points at 0, 0.25, 0.5, 0.75 mm
  CHECK(feeds.points(1, 0) == 0.25);
  CHECK(feeds.s[3] == 0.75);
  for (Eigen::Index i = 1; i < feeds.s.size(); ++i) {
    CHECK(feeds.s[i] > feeds.s[i - 1]);
    CHECK(feeds.s[i] - feeds.s[i - 1] <= 0.25 + 1e-12);
  }
  // the last point is the end of the arc; s adds the lengths of the moves taken (1 + 2 + π·1 as chords)
  CHECK(feeds.points.row(feeds.points.rows() - 1).transpose() == tp.blocks.back().end);
  CHECK(std::abs(feeds.s[feeds.s.size() - 1] - (3.0 + pi)) < 1e-3);
  CHECK_THROWS_AS(sample(tp, 0.0), std::invalid_argument);
  CHECK(sample(parse_gcode("G0 X1\n", "r.ngc"), 1.0).points.rows() == 0);
}
