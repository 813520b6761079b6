// Writer numbers: every finite double written whole (bounded buffer, no over-read), feeds bounded.
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/toolpath.hpp"

using namespace netshape;
using namespace netshape::toolpath;

namespace {
Toolpath P(const std::string& s) { return parse_gcode(s, "t"); }

// The X word the writer writes for a one-block program ending at X = x, as a number (the reader
// refuses |X| > 1e9 mm, so the word is converted here) and its length.
double x_written(double x, int decimals, std::size_t* chars = nullptr) {
  Toolpath t = P("G1 X1 F600\n");
  t.blocks[0].end.x() = x;
  WriterOptions o;
  o.decimals = decimals;
  const std::string text = format_gcode(t, o);
  REQUIRE(text.find('\0') == std::string::npos);
  const std::size_t at = text.find("\nG1 X");
  REQUIRE(at != std::string::npos);
  const std::size_t b = at + 5, e = text.find_first_of(" \n", b);
  double v = std::nan("");
  const auto r = std::from_chars(text.data() + b, text.data() + e, v);
  CHECK(r.ptr == text.data() + e);
  if (chars) *chars = e - b;
  return v;
}
}  // namespace

TEST_CASE("writer: numbers longer than any fixed small buffer are written whole") {
  // A fixed-notation double can take 300+ characters (1e300, 5e-324); the writer once copied snprintf's
  // reported length out of a 64-byte buffer (an over-read that ASan reports; garbage words without it).
  const double huge[] = {1e300, -1e300, std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
                         1.2345678901234567e80, 4.5e200};
  for (double x : huge) {
    CAPTURE(x);
    std::size_t n = 0;
    CHECK(x_written(x, -1, &n) == x);  // shortest form
    CHECK(n > 64);                     // longer than the old buffer
    CHECK(x_written(x, 12) == x);      // an integer-valued double's fixed expansion is exact
    CHECK(x_written(x, 0) == x);
  }
  const double tiny[] = {5e-324, -5e-324, 1e-300, std::numeric_limits<double>::min()};
  for (double x : tiny) {
    CAPTURE(x);
    CHECK(x_written(x, -1) == x);
    CHECK(x_written(x, 12) == 0.0);
  }
}

TEST_CASE("writer: a spindle speed of any finite size is written whole") {
  Toolpath t = P("G1 X1 F600\n");
  t.blocks[0].spindle_rpm = 1e300;
  const std::string text = format_gcode(t);
  const std::size_t b = text.find("\nS") + 2, e = text.find(' ', b);
  double v = 0;
  std::from_chars(text.data() + b, text.data() + e, v);
  CHECK(v == 1e300);
}

TEST_CASE("writer: feeds above max_feed_mm_per_min are refused, the bound itself is written") {
  Toolpath t = P("G1 X1 F600\n");
  t.blocks[0].feed = max_feed_mm_per_min / 60.0;
  CHECK(P(format_gcode(t)).blocks[0].feed * 60.0 == doctest::Approx(max_feed_mm_per_min));
  for (double f : {max_feed_mm_per_min / 60.0 * (1 + 1e-12), 1e60 / 60.0, 1e300, 1.7e308}) {
    CAPTURE(f);
    t.blocks[0].feed = f;
    CHECK_THROWS_WITH_AS(format_gcode(t), doctest::Contains("block.feed"), std::invalid_argument);
  }
  for (double f : {std::nan(""), std::numeric_limits<double>::infinity(), -1.0}) {
    t.blocks[0].feed = f;
    CHECK_THROWS_AS(format_gcode(t), std::invalid_argument);
  }
}
