#pragma once
/// \file error.hpp
/// netshape's error types and the input-checking macro.
///
/// - `netshape::Error` (a `std::runtime_error`): something went wrong that is not the caller's input,
///   e.g. an iteration that did not converge. Python: `netshape.Error`.
/// - `std::invalid_argument` (thrown by NETSHAPE_CHECK): bad user input; the message names the field
///   and the value. Python: `ValueError`.
/// - `netshape::ParseError` (a `std::invalid_argument`): bad input text with a source position
///   (file, line, column). Python: `netshape.ParseError`, a subclass of `ValueError`.

#include <sstream>
#include <stdexcept>
#include <string>

namespace netshape {

/// Base of netshape's own failures that are not bad input (non-convergence, internal limits).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input text at a known position. `line` and `column` are 1-based; 0 means unknown.
class ParseError : public std::invalid_argument {
 public:
  ParseError(std::string source, long line, long column, const std::string& what)
      : std::invalid_argument(format(source, line, column, what)),
        source_(std::move(source)), line_(line), column_(column), reason_(what) {}
  const std::string& source() const noexcept { return source_; }
  long line() const noexcept { return line_; }
  long column() const noexcept { return column_; }
  const std::string& reason() const noexcept { return reason_; }

 private:
  static std::string format(const std::string& source, long line, long column, const std::string& what) {
    std::ostringstream os;
    os << (source.empty() ? "<input>" : source);
    if (line > 0) os << ':' << line;
    if (column > 0) os << ':' << column;
    os << ": " << what;
    return os.str();
  }
  std::string source_;
  long line_;
  long column_;
  std::string reason_;
};

namespace detail {
template <class T>
[[noreturn]] void throw_invalid(const char* field, const T& value, const char* requirement) {
  std::ostringstream os;
  os.precision(17);
  os << field << " = " << value << ": " << requirement;
  throw std::invalid_argument(os.str());
}
}  // namespace detail

}  // namespace netshape

/// Check user input: `NETSHAPE_CHECK(radius > 0, "radius", radius, "must be positive [mm]")`
/// throws std::invalid_argument("radius = -1: must be positive [mm]").
#define NETSHAPE_CHECK(cond, field, value, requirement)                      \
  do {                                                                       \
    if (!(cond)) ::netshape::detail::throw_invalid((field), (value), (requirement)); \
  } while (false)

/// Check that a number is finite (not NaN, not ±inf).
#define NETSHAPE_CHECK_FINITE(field, value) \
  NETSHAPE_CHECK(std::isfinite(value), field, value, "must be a finite number")
