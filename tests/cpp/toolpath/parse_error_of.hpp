// The ParseError the reader raises for a program text (source name "t"); the test fails when it
// raises none. Shared by the reader's test files.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "netshape/core/error.hpp"
#include "netshape/toolpath.hpp"

inline netshape::ParseError parse_error_of(const std::string& s) {
  try {
    netshape::toolpath::parse_gcode(s, "t");
  } catch (const netshape::ParseError& e) {
    return e;
  }
  FAIL("no ParseError for: " << s);
  return netshape::ParseError("", 0, 0, "");
}
