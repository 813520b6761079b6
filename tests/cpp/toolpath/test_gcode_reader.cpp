// Reader: tokenizer, expressions, modal state, arcs, errors, round trip, and a seeded fuzz loop.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/toolpath.hpp"

#include "parse_error_of.hpp"

using namespace netshape;
using namespace netshape::toolpath;

namespace {
Toolpath P(const std::string& s) { return parse_gcode(s, "t"); }

// Value of X after evaluating `expr` as an X word.
double eval(const std::string& expr, const std::string& pre = "") {
  const Toolpath t = P(pre + "G0 X" + expr + "\n");
  REQUIRE(t.blocks.size() == 1);
  return t.blocks[0].end.x();
}

}  // namespace

TEST_CASE("words, comments, case and blanks") {
  const Toolpath t = P("%\n(header) ; c\nn10 g0 x 1 Y2.5 z-.5 (move)\nN20G1X.25F600;rest\n%\n");
  REQUIRE(t.blocks.size() == 2);
  CHECK(t.blocks[0].kind == MotionKind::rapid);
  CHECK(t.blocks[0].end.isApprox(Vec3(1, 2.5, -0.5)));
  CHECK(t.blocks[1].kind == MotionKind::line);
  CHECK(t.blocks[1].end.isApprox(Vec3(0.25, 2.5, -0.5)));
  CHECK(t.blocks[1].feed == doctest::Approx(10.0));  // 600 mm/min = 10 mm/s
  CHECK(t.blocks[1].line == 4);
  CHECK(t.blocks[0].start.isApprox(Vec3::Zero()));
}

TEST_CASE("numbers are read exactly like strtod") {
  for (const char* s : {"0.1", "123.456", "1234567890.123456789", ".000000000000000000000000001", "53.",
                        "0.30000000000000004", "99999999.99999999"}) {
    const double want = std::strtod(s, nullptr);
    if (std::abs(want) > 1e9) continue;
    CHECK(eval(s) == want);
  }
}

TEST_CASE("expressions follow NGC precedence and functions use degrees") {
  CHECK(eval("[1+2*3]") == 7.0);
  CHECK(eval("[2**3**2]") == 64.0);  // left to right: (2**3)**2
  CHECK(eval("[10-4-3]") == 3.0);
  CHECK(eval("[7 MOD 3]") == 1.0);
  CHECK(eval("[-7 MOD 3]") == 2.0);
  CHECK(eval("[1+2 GT 2]") == 1.0);  // relational below additive
  CHECK(eval("[1 EQ 1 AND 2 LT 1]") == 0.0);
  CHECK(eval("[1 OR 0]") == 1.0);
  CHECK(eval("[1 XOR 1]") == 0.0);
  CHECK(eval("SIN[30]") == doctest::Approx(0.5));
  CHECK(eval("[COS[60]]") == doctest::Approx(0.5));
  CHECK(eval("ATAN[1]/[1]") == doctest::Approx(45.0));
  CHECK(eval("ACOS[0]") == doctest::Approx(90.0));
  CHECK(eval("[SQRT[16]+ABS[-2]]") == 6.0);
  CHECK(eval("[FIX[-1.5]+FUP[1.2]+ROUND[2.5]]") == doctest::Approx(-2 + 2 + 3));
  CHECK(eval("[LN[EXP[2]]]") == doctest::Approx(2.0));
  CHECK(eval("[TAN[45]]") == doctest::Approx(1.0));
  CHECK(eval("[EXISTS[#<a>]]", "#<a>=1\n") == 1.0);
  CHECK(eval("[EXISTS[#<b>]]") == 0.0);
}

TEST_CASE("parameters: numbered, named, indirect, assignments after the line") {
  CHECK(eval("#1", "#1=5\n") == 5.0);
  CHECK(eval("##2", "#2=3 #3=7\n") == 7.0);
  CHECK(eval("#<Long Name>", "#<long_name>=1\n#<longname>=4\n") == 4.0);  // blanks removed, case folded
  CHECK(eval("#<_g>", "#<_g>=2\n") == 2.0);
  CHECK(eval("#7") == 0.0);  // numbered parameters start at 0
  // NGC: the assignment takes effect after the line, so X reads the old #1.
  const Toolpath t = P("#1=1\n#1=2 G0 X#1\nG0 X#1\n");
  CHECK(t.blocks[0].end.x() == 1.0);
  CHECK(t.blocks[1].end.x() == 2.0);
}

TEST_CASE("modal state: units, incremental, feed, spindle, tool") {
  const Toolpath t = P("G20 F10 S1000 M3 T2 M6\nG1 X1\nG91 X1 Y-1\nG21 G90 X0 M4\nM5 G0 Z1\n");
  REQUIRE(t.blocks.size() == 4);
  CHECK(t.blocks[0].end.x() == doctest::Approx(25.4));
  CHECK(t.blocks[0].feed == doctest::Approx(25.4 * 10 / 60));
  CHECK(t.blocks[0].spindle_rpm == 1000.0);
  CHECK(t.blocks[0].tool == 2);
  CHECK(t.blocks[1].end.isApprox(Vec3(50.8, -25.4, 0)));
  CHECK(t.blocks[2].end.x() == 0.0);
  CHECK(t.blocks[2].spindle_rpm == -1000.0);
  CHECK(t.blocks[3].spindle_rpm == 0.0);
  CHECK(t.blocks[3].kind == MotionKind::rapid);
}

TEST_CASE("arcs: IJK, R, full circles, turns, planes, helix") {
  SUBCASE("quarter circle G3 IJK") {
    const Toolpath t = P("G0 X10 Y0\nG3 X0 Y10 I-10 J0 F100\n");
    const Block& b = t.blocks[1];
    CHECK(b.kind == MotionKind::arc);
    CHECK(!b.clockwise);
    CHECK(b.center.norm() < 1e-12);
    CHECK(b.sweep() == doctest::Approx(pi / 2));
    CHECK(b.length() == doctest::Approx(5 * pi));
    const Summary s = t.summary();
    CHECK(s.bbox_max.x() == doctest::Approx(10));
    CHECK(s.bbox_max.y() == doctest::Approx(10));
  }
  SUBCASE("R form picks the short and the long arc") {
    const Toolpath a = P("G0 X10\nG2 X0 Y10 R10 F60\n");  // clockwise from (10,0) to (0,10), < 180°
    CHECK(a.blocks[1].center.isApprox(Vec3(10, 10, 0)));
    CHECK(std::abs(a.blocks[1].sweep()) == doctest::Approx(pi / 2));
    const Toolpath b = P("G0 X10\nG2 X0 Y10 R-10 F60\n");
    CHECK(b.blocks[1].center.norm() < 1e-12);
    CHECK(std::abs(b.blocks[1].sweep()) == doctest::Approx(1.5 * pi));
  }
  SUBCASE("full circle with turns and helix") {
    const Toolpath t = P("G0 X5\nG2 X5 Y0 Z-3 I-5 P2 F60\n");
    const Block& b = t.blocks[1];
    CHECK(b.turns == 2);
    CHECK(b.sweep() == doctest::Approx(-4 * pi));
    CHECK(b.length() == doctest::Approx(std::hypot(20 * pi, 3.0)));
    const Summary s = t.summary();
    CHECK(s.bbox_min.x() == doctest::Approx(-5));
    CHECK(s.bbox_min.y() == doctest::Approx(-5));
    CHECK(s.bbox_max.y() == doctest::Approx(5));
  }
  SUBCASE("G18 and G19 planes") {
    const Toolpath t = P("G18 G0 X10\nG2 X0 Z10 I-10 K0 F60\nG19 G0 Y10 Z0 X0\nG3 Y0 Z10 J-10 F60\n");
    CHECK(t.blocks[1].plane == Plane::zx);
    CHECK(t.blocks[1].center.norm() < 1e-12);
    CHECK(t.blocks[3].plane == Plane::yz);
    CHECK(t.blocks[3].length() == doctest::Approx(5 * pi));
  }
  SUBCASE("G90.1 absolute centres") {
    const Toolpath t = P("G90.1 G0 X10 Y5\nG3 X5 Y10 I5 J5 F60\n");
    CHECK(t.blocks[1].center.isApprox(Vec3(5, 5, 0)));
  }
}

TEST_CASE("errors name line, column and the reason") {
  ParseError e = parse_error_of("G0 X1\nG1 X2 G7 F100\n");
  CHECK(e.line() == 2);
  CHECK(e.column() == 7);
  CHECK(e.reason() == "unknown G-code G7");
  e = parse_error_of("G0 X5\nG2 X0 Y5.2 I-5 F60\n");
  CHECK(e.reason() == "arc radius mismatch: start radius 5.000 mm, end radius 5.200 mm");
  e = parse_error_of("G0 X5\nG2 X5 R3 F60\n");
  CHECK(e.reason().find("R arc with coincident end points") == 0);
  CHECK(parse_error_of("G5.2 X1 Y2 P1\n").reason().find("G5.2") != std::string::npos);
  CHECK(parse_error_of("G6.2 X1\n").reason().find("G6.2") != std::string::npos);
  CHECK(parse_error_of("G41 D1\n").reason().find("G41") != std::string::npos);
  CHECK(parse_error_of("G81 X1 Y1 Z-1 R1\n").reason().find("canned cycle G81") == 0);
  CHECK(parse_error_of("G92 X0\n").reason().find("G92") != std::string::npos);
  CHECK(parse_error_of("G93\n").reason().find("G93") != std::string::npos);
  CHECK(parse_error_of("o100 while [1]\n").reason().find("o-word") != std::string::npos);
  CHECK(parse_error_of("o100 sub\n").reason().find("not closed by o100 endsub") != std::string::npos);
  CHECK(parse_error_of("M98 P1\n").reason().find("M98") != std::string::npos);
  CHECK(parse_error_of("G1 X1\n").reason().find("no feed rate") != std::string::npos);
  CHECK(parse_error_of("G0 X[1/0]\n").reason() == "division by zero");
  CHECK(parse_error_of("G0 X[SQRT[-1]]\n").reason().find("SQRT of a negative") == 0);
  CHECK(parse_error_of("G0 X[0/0]\n").reason() == "division by zero");
  CHECK(parse_error_of("G0 X[ACOS[2]]\n").reason().find("ACOS") == 0);
  CHECK(parse_error_of("G0 X#<nope>\n").reason() == "parameter #<nope> is not defined");
  CHECK(parse_error_of("G0 X1 X2\n").reason().find("twice") != std::string::npos);
  CHECK(parse_error_of("G0 A1\n").reason().find("axis word A") == 0);
  CHECK(parse_error_of("G0 X1 (open\n").reason().find("comment") != std::string::npos);
  CHECK(parse_error_of("G0 X1.2.3\n").reason().find("malformed number") == 0);
  CHECK(parse_error_of("G0 X[1+2\n").reason().find("']'") != std::string::npos);
  CHECK(parse_error_of("G0 G1 X1 F1\n").reason().find("same modal group") != std::string::npos);
  CHECK(parse_error_of("G0 X99999999999\n").reason().find("out of range") != std::string::npos);
  CHECK(parse_error_of("G17 G2 X1 K1 F1\n").reason().find("K word") == 0);
  CHECK(parse_error_of("G0 X1 \x01\n").column() == 7);
}

TEST_CASE("expression nesting is bounded") {
  std::string deep = "G0 X";
  for (int i = 0; i < 100000; ++i) deep += '[';
  deep += "1";
  const ParseError e = parse_error_of(deep + "\n");
  CHECK(e.reason().find("nested deeper") != std::string::npos);
  std::string signs = "G0 X";
  for (int i = 0; i < 100000; ++i) signs += '-';
  CHECK(parse_error_of(signs + "1\n").reason().find("nested deeper") != std::string::npos);
}

TEST_CASE("program end: M2/M30 stop reading") {
  const Toolpath t = P("G0 X1\nM30\nG0 X2\nthis is not read\n");
  CHECK(t.blocks.size() == 1);
}

TEST_CASE("G4 dwell is counted, non-motion codes are kept in NGC order") {
  const Toolpath t = P("G21 G40 G49 G54 G64 P0.01 G80 G94 G97 G98 M8\nG43 H1\nG4 P1.5\nG0 X1\nG4 P0.5\nM9 M2\n");
  CHECK(t.blocks.size() == 1);
  CHECK(t.dwell_time == doctest::Approx(2.0));
  CHECK(t.summary().dwells == 2);
  std::vector<std::string> texts;
  for (const Command& c : t.commands) texts.push_back(c.text + "@" + std::to_string(c.before));
  const std::vector<std::string> want = {"M8@0", "G40@0", "G49@0", "G54@0", "G64 P0.01@0", "G97@0", "G98@0",
                                         "G80@0", "G43 H1@0", "G4 P1.5@0", "G4 P0.5@1", "M9@1", "M2@1"};
  CHECK(texts == want);
  CHECK(t.commands.back().kind == CommandKind::program_end);
  CHECK(t.commands[9].kind == CommandKind::dwell);
  CHECK(t.commands[9].value == 1.5);
  // no offsets given: one warning each for the work offset and the tool length, naming the line
  REQUIRE(t.warnings.size() == 2);
  CHECK(t.warnings[0].find("t:1: G54") == 0);
  CHECK(t.warnings[1].find("t:2: G43 H1") == 0);
}

TEST_CASE("writer keeps every command in place; M30 stays M30; feeds without binary noise") {
  const std::string prog =
      "(prog) G21 G90\nG64 P0.05 Q0.02\nT2 M6\nG43 H2\nG54\nS12000 M3\nM8\nG0 X0 Y0 Z5\nM7\n"
      "G1 Z-2 F1000000 (plunge)\nG4 P0.5\nG1 X10 F450\n(finish pass)\nG2 X20 R5\nM9\nM5\nG0 Z50\nM30\n";
  const Toolpath a = P(prog);
  const std::string text = format_gcode(a);
  CHECK(text.find("F1000000\n") != std::string::npos);
  CHECK(text.find("M30\n") != std::string::npos);
  CHECK(text.find("M2\n") == std::string::npos);
  const Toolpath b = P(text);
  REQUIRE(a.commands.size() == b.commands.size());
  for (std::size_t i = 0; i < a.commands.size(); ++i) {
    CHECK(a.commands[i].text == b.commands[i].text);
    CHECK(a.commands[i].before == b.commands[i].before);
    CHECK(a.commands[i].kind == b.commands[i].kind);
  }
  REQUIRE(a.blocks.size() == b.blocks.size());
  for (std::size_t i = 0; i < a.blocks.size(); ++i) CHECK(a.blocks[i].end == b.blocks[i].end);
  // inch program: G64 P is a length, written in mm
  CHECK(P("G20 G64 P0.1\n").commands.at(0).text == "G64 P2.54");
  // M0 on a motion line stops after the move
  const Toolpath m = P("G0 X1 M0\n");
  CHECK(m.commands.at(0).before == 1);
}

TEST_CASE("work offsets and tool lengths are applied and written back") {
  ReaderOptions o;
  o.has_work_offsets = true;
  o.work_offsets.row(0) << 100.0, 50.0, -20.0;  // G54
  o.work_offsets.row(1) << -10.0, 0.0, 5.0;     // G55
  o.has_tool_table = true;
  o.tool_lengths[3] = 120.5;
  const std::string prog = "G0 X1 Y2 Z3\nG55 G0 X1\nG43 H3 G1 Z0 F100\nG2 X3 I1 J0\nG49\nG0 Z1\nG91 G0 X1\n";
  const Toolpath t = parse_gcode(prog, "t", o);
  CHECK(t.warnings.empty());
  REQUIRE(t.blocks.size() == 6);
  CHECK(t.blocks[0].end == Vec3(101.0, 52.0, -17.0));
  CHECK(t.blocks[1].start == t.blocks[0].end);      // changing the offset does not move the tool
  CHECK(t.blocks[1].end == Vec3(-9.0, 52.0, -17.0)); // G55: X = 1 - 10; Y, Z stay (machine)
  CHECK(t.blocks[2].end.z() == doctest::Approx(5.0 + 120.5));
  CHECK(t.blocks[3].center.x() == doctest::Approx(-10.0 + 2.0));
  CHECK(t.blocks[4].end.z() == doctest::Approx(5.0 + 1.0));
  CHECK(t.blocks[5].end.x() == doctest::Approx(-10.0 + 3.0 + 1.0));
  CHECK(t.commands[1].kind == CommandKind::tool_length);
  CHECK(t.commands[1].value == 120.5);
  // the writer subtracts them: reading its output with the same offsets gives the same blocks
  const Toolpath b = parse_gcode(format_gcode(t), "w", o);
  REQUIRE(b.blocks.size() == t.blocks.size());
  for (std::size_t i = 0; i < t.blocks.size(); ++i) {
    CHECK((b.blocks[i].end - t.blocks[i].end).norm() < 1e-12);
    CHECK((b.blocks[i].start - t.blocks[i].start).norm() < 1e-12);
  }
  // a tool that is not in the table is an error naming the line
  try {
    parse_gcode("G0 X0\nG43 H7\n", "t", o);
    FAIL("accepted H7");
  } catch (const ParseError& e) {
    CHECK(e.line() == 2);
    CHECK(e.reason().find("tool 7 is not in the tool table") != std::string::npos);
  }
}

TEST_CASE("with_blocks keeps the commands before the first block of their source block") {
  Toolpath t = P("M8\nG0 X1\nM7\nG2 X3 R1 F60\nM9\nG0 X4\nM30\n");
  const Toolpath s = t.split_arcs(0.001);
  REQUIRE(s.blocks.size() > 3);
  CHECK(s.commands.at(0).before == 0);
  CHECK(s.commands.at(1).before == 1);
  CHECK(s.commands.at(2).before == s.blocks.size() - 1);
  CHECK(s.commands.at(3).before == s.blocks.size());
  CHECK_THROWS_AS(t.with_blocks(t.blocks, {0, 2, 1}), std::invalid_argument);
}

TEST_CASE("writer round trip gives the same blocks") {
  const std::string prog =
      "G21 G0 X1.1 Y2.2 Z3.3\nG1 X0.1 F1234.5\nG17 G2 X10.1 Y2.2 I5 J0 F200\nG3 X10.1 Y2.2 Z-2 I-3 J0 P3\n"
      "G18 G2 X13 Z1 R4\nG19 G3 Y5.2 Z4 J1 K2 S3000 M4\nG0 Z5 T3 M6\nG1 X10 F50\n";
  const Toolpath a = P(prog);
  for (bool absolute : {false, true}) {
    WriterOptions o;
    o.absolute_arc_centers = absolute;
    const Toolpath b = P(format_gcode(a, o));
    REQUIRE(a.blocks.size() == b.blocks.size());
    for (std::size_t i = 0; i < a.blocks.size(); ++i) {
      const Block& x = a.blocks[i];
      const Block& y = b.blocks[i];
      CHECK(x.kind == y.kind);
      CHECK(x.start == y.start);
      CHECK(x.end == y.end);
      CHECK((x.center - y.center).norm() <= 1e-12);
      CHECK(x.clockwise == y.clockwise);
      CHECK(x.plane == y.plane);
      CHECK(x.turns == y.turns);
      CHECK(x.feed == doctest::Approx(y.feed).epsilon(1e-14));
      CHECK(x.spindle_rpm == y.spindle_rpm);
      CHECK(x.tool == y.tool);
    }
  }
}

TEST_CASE("split_arcs: chord error within tolerance, ends kept") {
  const Toolpath a = P("G0 X10\nG3 X-10 Y0 I-10 F60\n");
  const double tol = 0.01;
  const Toolpath s = a.split_arcs(tol);
  const int n = chord_count(10.0, pi, tol);
  CHECK(static_cast<int>(s.blocks.size()) == 1 + n);
  CHECK(s.blocks.back().end == a.blocks.back().end);
  for (std::size_t i = 1; i < s.blocks.size(); ++i) {
    const Vec3 mid = 0.5 * (s.blocks[i].start + s.blocks[i].end);
    const double err = 10.0 - mid.head<2>().norm();
    CHECK(err <= tol + 1e-12);
    CHECK(err >= 0.0);
  }
  CHECK_THROWS_AS(a.split_arcs(0.0), std::invalid_argument);
  CHECK_THROWS_AS(chord_count(1e6, 2 * pi, 1e-12), std::invalid_argument);
}

TEST_CASE("streaming summary equals the summary of the blocks") {
  const std::string prog = "G0 X1\nG1 X5 Y2 F600\nG2 X9 Y2 R2\nG4 P2\nG0 Z10\n";
  const Summary a = summarize_gcode_text(prog);
  const Summary b = P(prog).summary();
  CHECK(a.rapids == 2);
  CHECK(a.lines == 1);
  CHECK(a.arcs == 1);
  CHECK(a.feed_length == doctest::Approx(b.feed_length));
  CHECK(a.feed_time == doctest::Approx(b.feed_time));
  CHECK(a.dwell_time == 2.0);
  CHECK(a.bbox_min == b.bbox_min);
  CHECK(a.bbox_max == b.bbox_max);
  CHECK(a.bbox_max.y() == doctest::Approx(4.0));  // top of the arc, not its end points
  CHECK(a.source_lines == 5);
}

TEST_CASE("shared programs read; the NURBS files are refused") {
  const std::string dir = std::string(NETSHAPE_SHARED_DIR) + "/data/gcode/";
  std::ifstream probe(dir + "tort.ngc");
  if (!probe) {
    MESSAGE("shared data absent: skipped");
    return;
  }
  for (const char* f : {"3D_Chips.ngc", "cds.ngc", "arcspiral.ngc", "tort.ngc"}) {
    const Toolpath t = read_gcode(dir + f);
    CHECK(t.blocks.size() > 200);
  }
  for (const char* f : {"butterfly-xy_G5.2.ngc", "Curva_Farfalla_1_G6.2.ngc"}) {
    try {
      read_gcode(dir + f);
      FAIL("accepted " << f);
    } catch (const ParseError& e) {
      CHECK(e.reason().find("NURBS") != std::string::npos);
      CHECK(e.line() > 0);
    }
  }
}

TEST_CASE("file reading handles lines across buffer boundaries and CRLF") {
  const std::string path = "/tmp/netshape_test_reader_crlf.ngc";
  {
    std::ofstream o(path, std::ios::binary);
    o << "G21\r\n";
    for (int i = 0; i < 60000; ++i) o << "G1 X" << i % 100 << ".125 Y" << (i * 7) % 50 << " F1000 (padding comment)\r\n";
  }
  const Summary s = summarize_gcode(path);
  CHECK(s.lines == 60000);
  CHECK(s.source_lines == 60001);
  std::remove(path.c_str());
  CHECK_THROWS_AS(summarize_gcode("/nonexistent/x.ngc"), std::invalid_argument);
}

TEST_CASE("fuzz: mutated programs give a ParseError/invalid_argument or blocks, never a crash") {
  const std::string seeds[] = {
      "%\n#<s>=2\nG21 G90 G17\nG0 X[#<s>*1.5] Y-2 Z5\nG1 Z-1 F300\nG2 X10 Y0 I5 J1\nG3 X0 Y0 R6\nG18 G2 X3 Z0 I1 K1\n"
      "G19 G3 Y4 Z2 J1 K0 P2\nG91 G1 X1 Y1\nG90 G4 P0.5\nG20 G1 X1\nM2\n",
      "G0 X[SIN[30]*ATAN[1]/[2]] Y[2**0.5 MOD 1] Z[1 GT 0 AND 2 LE 3]\n#1=[SQRT[4]+LN[2]-EXP[1]]\nG1 X#1 F[10*60]\n",
  };
  std::mt19937 rng(12345);
  const char* inserts[] = {"G2", "G3", "R", "[", "]", "#", "#<", "=", "X1e308", "99999999999999999999",
                           "SQRT[-1]", "[0/0]", "P", "G91", "G20", "(", ";", "G5.2", "**", "ATAN[1]/", "\x01", "\xff"};
  int ok = 0, bad = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    std::string s = seeds[iter % 2];
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = rng() % (s.size() + 1);
      switch (rng() % 4) {
        case 0: if (at < s.size()) s[at] = static_cast<char>(rng() % 256); break;
        case 1: s.resize(at); break;
        case 2: s.insert(at, inserts[rng() % (sizeof inserts / sizeof *inserts)]); break;
        case 3: if (at < s.size()) s.erase(at, 1 + rng() % 5); break;
      }
    }
    try {
      const Toolpath t = P(s);
      for (const Block& b : t.blocks) {
        CHECK(std::isfinite(b.length()));
        CHECK(b.end.allFinite());
      }
      const Summary sum = t.summary();
      CHECK(std::isfinite(sum.feed_time));
      WriterOptions o;
      const Toolpath back = P(format_gcode(t, o));
      CHECK(back.blocks.size() == t.blocks.size());
      // the same commands at the same places (plus the M2 the writer adds when there was no end)
      const bool end = !t.commands.empty() && t.commands.back().kind == CommandKind::program_end;
      REQUIRE(back.commands.size() == t.commands.size() + (end ? 0 : 1));
      for (std::size_t i = 0; i < t.commands.size(); ++i) {
        CHECK(back.commands[i].text == t.commands[i].text);
        CHECK(back.commands[i].before == t.commands[i].before);
      }
      ++ok;
    } catch (const std::invalid_argument&) {
      ++bad;
    }
  }
  CHECK(ok > 100);
  CHECK(bad > 100);
}
