// BlockArrays: a tool path as columns holds every field of every block (blocks → arrays → blocks is
// the identity) in the documented layout (row-major (n, 3) points).
#include <doctest/doctest.h>

#include "netshape/toolpath.hpp"

using namespace netshape;
using namespace netshape::toolpath;

TEST_CASE("BlockArrays: blocks to columns and back") {
  const Toolpath tp = parse_gcode("G0 X1 Y2 Z3\nT4 M6\nS900 M4\nG1 X5 F600\nG18 G2 X7 Z1 I1 K-1 P2\nG17 G3 X5 Y2 R2\n");
  const BlockArrays a = BlockArrays::from_blocks(tp.blocks);
  REQUIRE(a.size() == tp.blocks.size());
  CHECK(a.start.size() == 3 * a.size());
  const std::vector<Block> back = a.to_blocks();
  for (std::size_t i = 0; i < back.size(); ++i) {
    const Block &x = tp.blocks[i], &y = back[i];
    CHECK(x.kind == y.kind);
    CHECK(x.start == y.start);
    CHECK(x.end == y.end);
    CHECK(x.center == y.center);
    CHECK(x.clockwise == y.clockwise);
    CHECK(x.plane == y.plane);
    CHECK(x.turns == y.turns);
    CHECK(x.feed == y.feed);
    CHECK(x.spindle_rpm == y.spindle_rpm);
    CHECK(x.tool == y.tool);
    CHECK(x.line == y.line);
    CHECK(a.end[3 * i + 2] == x.end.z());
  }
  CHECK(a.turns[2] == 2);
  CHECK(a.spindle_rpm[1] == -900.0);
}
