// G-code reader, reading one line: the next source line, its normalised copy (no blanks or
// comments, lower case, each character's source column kept), numbers, parameters, [ ] expressions
// and functions, and the words of the line with their values (parameter assignments collected
// for after the line, as NGC says).
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "gcode_reader_impl.hpp"

namespace netshape::toolpath {

bool GcodeReader::Impl::fetch_line(const char*& b, const char*& e) {
  if (file == nullptr) {
    if (beg >= text.size()) return false;
    const char* base = text.data();
    const char* nl = static_cast<const char*>(std::memchr(base + beg, '\n', text.size() - beg));
    b = base + beg;
    e = nl ? nl : base + text.size();
    beg = nl ? static_cast<std::size_t>(nl - base) + 1 : text.size();
  } else {
    for (;;) {
      const char* nl = beg < end ? static_cast<const char*>(std::memchr(buf.data() + beg, '\n', end - beg)) : nullptr;
      if (nl) {
        b = buf.data() + beg;
        e = nl;
        beg = static_cast<std::size_t>(nl - buf.data()) + 1;
        break;
      }
      if (eof) {
        if (beg >= end) return false;
        b = buf.data() + beg;
        e = buf.data() + end;
        beg = end;
        break;
      }
      if (beg > 0) {  // keep the partial line, make room behind it
        std::memmove(buf.data(), buf.data() + beg, end - beg);
        end -= beg;
        beg = 0;
      }
      if (end == buf.size()) {
        if (static_cast<long>(buf.size()) > opt.max_line_length + 1)
          throw ParseError(source, line_no + 1, 0,
                           "line longer than " + std::to_string(opt.max_line_length) + " characters");
        buf.resize(buf.size() * 2);
      }
      const std::size_t got = std::fread(buf.data() + end, 1, buf.size() - end, file);
      if (got == 0) {
        if (std::ferror(file)) throw ParseError(source, line_no + 1, 0, "read error");
        eof = true;
      }
      end += got;
    }
  }
  if (e > b && e[-1] == '\r') --e;
  ++line_no;
  if (e - b > opt.max_line_length)
    throw ParseError(source, line_no, 0, "line longer than " + std::to_string(opt.max_line_length) + " characters");
  return true;
}

void GcodeReader::Impl::normalize(const char* b, const char* e) {
  line_b = b;
  line_e = e;
  const std::size_t n = static_cast<std::size_t>(e - b);
  if (nlen < n + 1) norm.resize(n + 1);
  comments.clear();
  char* out = &norm[0];
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(b[i]);
    const unsigned char t = kCharClass[c];
    if (t >= 32) {  // ordinary character (lower-cased by the table)
      out[k++] = static_cast<char>(t);
      continue;
    }
    if (t == kSkip) continue;
    if (t == kParen) {
      const void* close = std::memchr(b + i + 1, ')', n - i - 1);
      if (!close) throw ParseError(source, line_no, static_cast<long>(i) + 1, "comment '(' is not closed on its line");
      const std::size_t j = static_cast<std::size_t>(static_cast<const char*>(close) - b);
      comments.emplace_back(i, j + 1);
      i = j;
      continue;
    }
    if (t == kSemicolon) {
      std::size_t j = n;
      while (j > i + 1 && (b[j - 1] == ' ' || b[j - 1] == '\t')) --j;
      comments.emplace_back(i, j);
      break;
    }
    char tmp[48];
    std::snprintf(tmp, sizeof tmp, "unexpected character (byte 0x%02X)", c);
    throw ParseError(source, line_no, static_cast<long>(i) + 1, tmp);
  }
  nlen = k;
  norm[k] = '\0';
}

int GcodeReader::Impl::column_of(std::size_t idx) const {
  const std::size_t n = static_cast<std::size_t>(line_e - line_b);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char t = kCharClass[static_cast<unsigned char>(line_b[i])];
    if (t == kSkip) continue;
    if (t == kParen) {
      const void* close = std::memchr(line_b + i + 1, ')', n - i - 1);
      if (!close) break;
      i = static_cast<std::size_t>(static_cast<const char*>(close) - line_b);
      continue;
    }
    if (t == kSemicolon) break;
    if (k == idx) return static_cast<int>(i + 1);
    ++k;
  }
  return static_cast<int>(n + 1);
}

double GcodeReader::Impl::number() {
  const std::size_t st = pos;
  std::uint64_t mant = 0;
  int digits = 0, frac = 0;
  bool dot = false;
  while (pos < nlen) {
    const char c = norm[pos];
    if (c >= '0' && c <= '9') {
      if (digits < 19) mant = mant * 10 + static_cast<unsigned>(c - '0');
      if (mant != 0 || digits != 0) ++digits;  // significant digits (leading zeros skipped)
      if (dot) ++frac;
    } else if (c == '.') {
      if (dot) fail("malformed number (two decimal points)");
      dot = true;
    } else {
      break;
    }
    ++pos;
  }
  if (pos == st + (dot ? 1u : 0u)) {
    pos = st;
    fail("expected a number");
  }
  if (digits <= 15 && frac <= 22) return static_cast<double>(mant) / kPow10[frac];
  double v = 0.0;
  auto r = std::from_chars(norm.data() + st, norm.data() + pos, v, std::chars_format::fixed);
  if (r.ec != std::errc() || !std::isfinite(v)) {
    pos = st;
    fail("number out of range");
  }
  return v;
}

void GcodeReader::Impl::enter() {
  if (++depth > kMaxDepth) fail("expression nested deeper than " + std::to_string(kMaxDepth) + " levels");
}

double GcodeReader::Impl::parameter_value() {
  const int c0 = static_cast<int>(pos) + 1;
  ++pos;
  if (peek() == '<') {
    const std::size_t st = ++pos;
    while (pos < nlen && norm[pos] != '>') ++pos;
    if (pos >= nlen) fail_at(c0, "parameter name '#<' is not closed by '>'");
    const std::size_t len = pos - st;
    ++pos;
    if (len == 0) fail_at(c0, "empty parameter name '#<>'");
    const double* v = named.find(norm.data() + st, len);
    if (!v) fail_at(c0, "parameter #<" + norm.substr(st, len) + "> is not defined");
    return *v;
  }
  enter();
  const double idx = real_value();
  --depth;
  return numbered[static_cast<std::size_t>(param_index(idx, c0))];
}

int GcodeReader::Impl::param_index(double idx, int column) const {
  const double r = std::round(idx);
  if (!(std::abs(idx - r) < 1e-6) || r < 1 || r > kMaxNumbered)
    fail_at(column, "parameter number " + fmt_num(idx) + " is not an integer in 1 … " + std::to_string(kMaxNumbered));
  return static_cast<int>(r);
}

double GcodeReader::Impl::real_value() {
  const char c = peek();
  if (c == '-' || c == '+') {
    ++pos;
    enter();
    const double v = real_value();
    --depth;
    return c == '-' ? -v : v;
  }
  if (c == '[') {
    ++pos;
    enter();
    const double v = expression();
    if (peek() != ']') fail("expected ']' to close the expression");
    ++pos;
    --depth;
    return v;
  }
  if (c == '#') return parameter_value();
  if ((c >= '0' && c <= '9') || c == '.') return number();
  if (c >= 'a' && c <= 'z') return function();
  if (c == '\0') fail("expected a value at the end of the line");
  fail(std::string("expected a value, found '") + c + "'");
}

bool GcodeReader::Impl::match(const char* word) {
  std::size_t k = 0;
  while (word[k] && norm[pos + k] == word[k]) ++k;  // norm is NUL-terminated
  if (word[k]) return false;
  pos += k;
  return true;
}

double GcodeReader::Impl::bracketed() {
  if (peek() != '[') fail("expected '[' after the function name");
  ++pos;
  enter();
  const double v = expression();
  if (peek() != ']') fail("expected ']' to close the function argument");
  ++pos;
  --depth;
  return v;
}

double GcodeReader::Impl::checked(double v, int column, const char* what) const {
  if (!std::isfinite(v)) fail_at(column, std::string(what) + " is not a finite number");
  return v;
}

double GcodeReader::Impl::function() {
  const int c0 = static_cast<int>(pos) + 1;
  if (match("exists")) {
    if (peek() != '[') fail("expected '[' after EXISTS");
    ++pos;
    if (!match("#<")) fail("EXISTS takes a named parameter, EXISTS[#<name>]");
    const std::size_t st = pos;
    while (pos < nlen && norm[pos] != '>') ++pos;
    if (pos >= nlen) fail_at(c0, "parameter name '#<' is not closed by '>'");
    const bool found = named.find(norm.data() + st, pos - st) != nullptr;
    ++pos;
    if (peek() != ']') fail("expected ']' to close EXISTS[…]");
    ++pos;
    return found ? 1.0 : 0.0;
  }
  if (match("atan")) {
    const double y = bracketed();
    if (peek() != '/') fail("ATAN needs two arguments: ATAN[y]/[x]");
    ++pos;
    const double x = bracketed();
    return rad2deg(std::atan2(y, x));
  }
  constexpr double d2r = pi / 180.0;
  if (match("abs")) return std::abs(bracketed());
  if (match("acos")) {
    const double a = bracketed();
    if (a < -1.0 || a > 1.0) fail_at(c0, "ACOS of " + fmt_num(a) + " (outside -1 … 1)");
    return rad2deg(std::acos(a));
  }
  if (match("asin")) {
    const double a = bracketed();
    if (a < -1.0 || a > 1.0) fail_at(c0, "ASIN of " + fmt_num(a) + " (outside -1 … 1)");
    return rad2deg(std::asin(a));
  }
  if (match("cos")) return std::cos(bracketed() * d2r);
  if (match("sin")) return std::sin(bracketed() * d2r);
  if (match("tan")) return checked(std::tan(bracketed() * d2r), c0, "TAN");
  if (match("exp")) return checked(std::exp(bracketed()), c0, "EXP");
  if (match("fix")) return std::floor(bracketed());
  if (match("fup")) return std::ceil(bracketed());
  if (match("round")) return std::round(bracketed());
  if (match("ln")) {
    const double a = bracketed();
    if (!(a > 0.0)) fail_at(c0, "LN of " + fmt_num(a) + " (must be positive)");
    return std::log(a);
  }
  if (match("sqrt")) {
    const double a = bracketed();
    if (a < 0.0) fail_at(c0, "SQRT of a negative number " + fmt_num(a));
    return std::sqrt(a);
  }
  std::size_t e = pos;
  while (e < nlen && norm[e] >= 'a' && norm[e] <= 'z') ++e;
  fail("unknown function or misplaced word '" + norm.substr(pos, e - pos) + "'");
}

int GcodeReader::Impl::binary_op() {
  const char c = peek();
  switch (c) {
    case '*':
      if (pos + 1 < nlen && norm[pos + 1] == '*') { pos += 2; return op_pow; }
      ++pos; return op_mul;
    case '/': ++pos; return op_div;
    case '+': ++pos; return op_add;
    case '-': ++pos; return op_sub;
    default: break;
  }
  switch (c) {
    case 'm': return match("mod") ? op_mod : op_none;
    case 'e': return match("eq") ? op_eq : op_none;
    case 'n': return match("ne") ? op_ne : op_none;
    case 'g': return match("gt") ? op_gt : match("ge") ? op_ge : op_none;
    case 'l': return match("lt") ? op_lt : match("le") ? op_le : op_none;
    case 'a': return match("and") ? op_and : op_none;
    case 'o': return match("or") ? op_or : op_none;
    case 'x': return match("xor") ? op_xor : op_none;
    default: return op_none;
  }
}

double GcodeReader::Impl::apply(int op, double a, double b, int column) const {
  double r = 0.0;
  switch (op) {
    case op_pow:
      r = std::pow(a, b);
      if (!std::isfinite(r)) fail_at(column, fmt_num(a) + " ** " + fmt_num(b) + " is not a finite number");
      return r;
    case op_mul: r = a * b; break;
    case op_div:
      if (b == 0.0) fail_at(column, "division by zero");
      r = a / b;
      break;
    case op_mod:
      if (b == 0.0) fail_at(column, "MOD by zero");
      r = a - b * std::floor(a / b);
      break;
    case op_add: r = a + b; break;
    case op_sub: r = a - b; break;
    // comparisons with LinuxCNC's equality tolerance
    case op_eq: return std::abs(a - b) < 1e-6 ? 1.0 : 0.0;
    case op_ne: return std::abs(a - b) < 1e-6 ? 0.0 : 1.0;
    case op_gt: return a > b ? 1.0 : 0.0;
    case op_ge: return a >= b ? 1.0 : 0.0;
    case op_lt: return a < b ? 1.0 : 0.0;
    case op_le: return a <= b ? 1.0 : 0.0;
    case op_and: return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
    case op_or: return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
    case op_xor: return ((a != 0.0) != (b != 0.0)) ? 1.0 : 0.0;
    default: break;
  }
  if (!std::isfinite(r)) fail_at(column, "expression result is not a finite number");
  return r;
}

double GcodeReader::Impl::expression_level(int min_prec) {
  double lhs = real_value();
  for (;;) {
    const std::size_t save = pos;
    const std::size_t op_pos = pos;
    const int op = binary_op();
    if (op == op_none) return lhs;
    const int p = precedence(op);
    if (p < min_prec) {
      pos = save;
      return lhs;
    }
    enter();
    const double rhs = expression_level(p + 1);
    --depth;
    lhs = apply(op, lhs, rhs, static_cast<int>(op_pos) + 1);
  }
}

void GcodeReader::Impl::read_words() {
  wcol.fill(0);
  ng = nm = 0;
  assigns.clear();
  pos = 0;
  depth = 0;
  while (pos < nlen) {
    const char c = norm[pos];
    const int column = static_cast<int>(pos) + 1;
    if (c == '#') {
      read_assignment();
      continue;
    }
    if (c < 'a' || c > 'z') fail(std::string("expected a word letter, found '") + c + "'");
    if (c == 'o') fail("an o-word must begin its line (oN sub / endsub / call / return, or O1234)");
    ++pos;
    const double v = real_value();
    if (c == 'g') {
      if (ng == static_cast<int>(gval.size())) fail_at(column, "too many G words on one line");
      gval[ng] = v;
      gcol[ng++] = column;
    } else if (c == 'm') {
      if (nm == static_cast<int>(mval.size())) fail_at(column, "too many M words on one line");
      mval[nm] = v;
      mcol[nm++] = column;
    } else {
      const int k = c - 'a';
      if (wcol[k]) fail_at(column, std::string("word ") + static_cast<char>(c - 32) + " appears twice on the line");
      wval[k] = v;
      wcol[k] = column;
    }
  }
}

void GcodeReader::Impl::read_assignment() {
  const int c0 = static_cast<int>(pos) + 1;
  ++pos;
  Assignment a;
  if (peek() == '<') {
    const std::size_t st = ++pos;
    while (pos < nlen && norm[pos] != '>') ++pos;
    if (pos >= nlen) fail_at(c0, "parameter name '#<' is not closed by '>'");
    if (pos == st) fail_at(c0, "empty parameter name '#<>'");
    a.name = norm.substr(st, pos - st);
    ++pos;
  } else {
    a.number = param_index(real_value(), c0);
  }
  if (peek() != '=') fail("expected '=' after the parameter (assignment '#… = value')");
  ++pos;
  a.value = real_value();
  assigns.push_back(std::move(a));
}

void GcodeReader::Impl::apply_assignments() {
  for (const auto& a : assigns) {
    if (a.number) numbered[static_cast<std::size_t>(a.number)] = a.value;
    else named.set(a.name, a.value);
  }
}

}  // namespace netshape::toolpath
