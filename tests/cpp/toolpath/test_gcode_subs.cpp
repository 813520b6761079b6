// Reader, o-words: Fanuc program numbers kept as words; LinuxCNC subroutines expanded at their calls
// (the same moves as the body written out in place of the call); control flow refused by line.
#include <doctest/doctest.h>

#include <string>

#include "netshape/core/error.hpp"
#include "netshape/toolpath.hpp"

#include "parse_error_of.hpp"

using namespace netshape;
using namespace netshape::toolpath;

namespace {
Toolpath P(const std::string& s) { return parse_gcode(s, "t"); }

void check_same_moves(const Toolpath& a, const Toolpath& b) {
  REQUIRE(a.blocks.size() == b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) {
    CHECK(a.blocks[i].kind == b.blocks[i].kind);
    CHECK(a.blocks[i].start == b.blocks[i].start);
    CHECK(a.blocks[i].end == b.blocks[i].end);
    CHECK(a.blocks[i].center == b.blocks[i].center);
    CHECK(a.blocks[i].clockwise == b.blocks[i].clockwise);
    CHECK(a.blocks[i].feed == b.blocks[i].feed);
  }
}
}  // namespace

TEST_CASE("a Fanuc program number is kept as a word and moves nothing") {
  const Toolpath t = P("%\nO1234 (PART A)\nG21 G90\nG1 X1 F600\nM30\n%\n");
  REQUIRE(t.blocks.size() == 1);
  REQUIRE(t.commands.size() >= 2);
  CHECK(t.commands[0].text == "O1234");
  CHECK(t.commands[0].kind == CommandKind::word);
  CHECK(t.commands[0].line == 2);
  CHECK(t.commands[1].text == "(PART A)");
  // written and read again: the same moves, the program number in place
  const Toolpath back = P(format_gcode(t));
  check_same_moves(t, back);
  CHECK(format_gcode(t).find("O1234") != std::string::npos);
}

TEST_CASE("a called subroutine makes the moves of its body written in place of the call") {
  const std::string sub =
      "o100 sub (square of side #1 at the current point)\n"
      "G91 G1 X#1 F600\nY#1\nX-#1\nY-#1\nG90\n"
      "o100 endsub\n";
  const Toolpath called = P("G21 G90\n" + sub + "G0 X0 Y0 Z1\no100 call [2]\nG0 X10\no<sq> sub\n"
                            "o100 call [#1]\no<sq> endsub\n#1 = 3\no<sq> call [0.5]\nG0 Z5\nM30\n");
  const std::string square2 = "G91 G1 X2 F600\nY2\nX-2\nY-2\nG90\n";
  const Toolpath inlined = P("G21 G90\nG0 X0 Y0 Z1\n" + square2 + "G0 X10\n#1 = 3\n"
                             "G91 G1 X0.5 F600\nY0.5\nX-0.5\nY-0.5\nG90\nG0 Z5\nM30\n");
  check_same_moves(called, inlined);
  // every move a call makes belongs to the (outermost) call line
  CHECK(called.blocks[1].line == 10);
  CHECK(called.blocks[4].line == 10);
  CHECK(called.blocks[6].line == 16);
  CHECK(called.blocks[9].line == 16);
  CHECK(called.blocks[10].line == 17);
}

TEST_CASE("a call gives #1 … #30 their values back and return leaves early") {
  const Toolpath t = P("#1 = 7\no1 sub\nG1 X#1 F100\no1 return\nG1 X99\no1 endsub\n"
                       "o1 call [2]\nG1 Y#1\no1 call\nM30\n");
  REQUIRE(t.blocks.size() == 3);
  CHECK(t.blocks[0].end.x() == 2.0);
  CHECK(t.blocks[1].end.y() == 7.0);
  CHECK(t.blocks[2].end.x() == 0.0);  // a missing argument is 0
}

TEST_CASE("what cannot be supported is refused naming the line") {
  ParseError e = parse_error_of("G0 X1\no100 while [#1 LT 3]\nG1 X2 F100\no100 endwhile\n");
  CHECK(e.line() == 2);
  CHECK(e.reason().find("'while'") != std::string::npos);
  e = parse_error_of("G0 X1\n\no200 if [#1 GT 0]\n");
  CHECK(e.line() == 3);
  CHECK(e.reason().find("'if'") != std::string::npos);
  e = parse_error_of("G0 X1\no5 call\n");
  CHECK(e.line() == 2);
  CHECK(e.reason().find("no subroutine o5") != std::string::npos);
  e = parse_error_of("o5 sub\nG1 X1 F100\n");
  CHECK(e.line() == 1);
  CHECK(e.reason().find("not closed") != std::string::npos);
  e = parse_error_of("o5 sub\no6 sub\no6 endsub\no5 endsub\n");
  CHECK(e.line() == 2);
  e = parse_error_of("o5 sub\no5 call\no5 endsub\no5 call\n");  // endless recursion stops at the depth limit
  CHECK(e.reason().find("nested deeper") != std::string::npos);
  e = parse_error_of("G1 X1 F100 o5 call\n");
  CHECK(e.reason().find("must begin its line") != std::string::npos);
  e = parse_error_of("G0 X1\nM98 P1234\n");
  CHECK(e.line() == 2);
}

TEST_CASE("calls that would replay an exponential number of lines are refused at the outermost call") {
  // o1 calls o2 twice, o2 calls o3 twice … o40 moves twice: 2^40 moves, 40 levels deep (under the
  // nesting limit); the reader stops at its line budget instead of running out of memory
  std::string s = "G21 G90\no40 sub\nG1 X1 F100\nG1 X0\no40 endsub\n";
  for (int k = 39; k >= 1; --k) {
    const std::string a = std::to_string(k), b = std::to_string(k + 1);
    s += "o" + a + " sub\no" + b + " call\no" + b + " call\no" + a + " endsub\n";
  }
  s += "G0 Z5\no1 call\nM30\n";
  const ParseError e = parse_error_of(s);
  CHECK(e.line() == 2 + 4 + 39 * 4 + 1);  // the line of "o1 call"
  CHECK(e.reason().find("replay more than") != std::string::npos);
}
