// Streaming RS274/NGC reader. One pass per line: (1) copy the line without blanks and comments,
// lower-cased, remembering each character's source column; (2) read the words, evaluating
// parameters and [ ] expressions (parameter assignments are collected and applied after the line,
// as NGC says); (3) execute the line in NGC order (F, S, T, M6, spindle, coolant, dwell, modes, offsets,
// motion, stop) and emit at most one block. Comments and the words that do not move the tool are
// recorded as Commands (`before` = blocks emitted so far) in that order; G54…/G43 change the offset
// added to block coordinates.
#include "netshape/toolpath/gcode_reader.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::toolpath {

void ReaderOptions::validate() const {
  for (int i = 0; i < 3; ++i) NETSHAPE_CHECK_FINITE("initial_position", initial_position[i]);
  NETSHAPE_CHECK(max_line_length >= 16, "max_line_length", max_line_length, "must be at least 16 [characters]");
  for (int i = 0; i < 9; ++i)
    for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("work_offsets", work_offsets(i, k));
  for (const auto& [t, len] : tool_lengths) {
    NETSHAPE_CHECK(t >= 0, "tool_lengths", t, "tool numbers must not be negative");
    NETSHAPE_CHECK_FINITE("tool_lengths", len);
  }
}

namespace {

constexpr int kMaxDepth = 64;            // nesting of [ ], functions and # indirection
constexpr int kMaxNumbered = 5602;       // numbered parameters #1 … #5602 (LinuxCNC)
constexpr double kMaxCoordinate = 1e9;   // [mm] larger coordinates are refused
constexpr double kInch = 25.4;

const double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                         1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

std::string fmt_num(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A word value as G-code text: shortest form that reads back exactly, never in exponent notation.
std::string fmt_word(double v) {
  char buf[400];
  if (v == 0.0) v = 0.0;  // no "-0"
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

std::string fmt_fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Code value ×10 (G5.2 → 52) if the number is a valid code (at most one decimal); −1 otherwise.
long code10(double v) {
  if (!(v >= 0.0) || v > 1e6) return -1;
  const double t = v * 10.0;
  const double r = std::round(t);
  if (std::abs(t - r) > 1e-6) return -1;
  return static_cast<long>(r);
}

std::string code_name(char letter, long c10) {
  std::string s(1, letter);
  s += std::to_string(c10 / 10);
  if (c10 % 10) {
    s += '.';
    s += std::to_string(c10 % 10);
  }
  return s;
}

// Open-addressing table of named parameters (names are stored lower-case without blanks). Lookups
// take a pointer and a length so that reading `#<name>` allocates nothing.
class NamedParams {
 public:
  NamedParams() : slots_(64) {}
  const double* find(const char* s, std::size_t n) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t h = hash(s, n) & mask;; h = (h + 1) & mask) {
      const Slot& e = slots_[h];
      if (!e.used) return nullptr;
      if (e.name.size() == n && std::memcmp(e.name.data(), s, n) == 0) return &e.value;
    }
  }
  void set(const std::string& name, double v) {
    if (double* p = const_cast<double*>(find(name.data(), name.size()))) {
      *p = v;
      return;
    }
    if (2 * (count_ + 1) > slots_.size()) grow();
    insert(name, v);
  }

 private:
  struct Slot {
    std::string name;
    double value = 0.0;
    bool used = false;
  };
  static std::size_t hash(const char* s, std::size_t n) {
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(s[i])) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
  void insert(const std::string& name, double v) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t h = hash(name.data(), name.size()) & mask;
    while (slots_[h].used) h = (h + 1) & mask;
    slots_[h].name = name;
    slots_[h].value = v;
    slots_[h].used = true;
    ++count_;
  }
  void grow() {
    std::vector<Slot> old(slots_.size() * 2);
    old.swap(slots_);
    count_ = 0;
    for (auto& e : old)
      if (e.used) insert(e.name, e.value);
  }
  std::vector<Slot> slots_;
  std::size_t count_ = 0;
};

enum BinOp : int { op_none, op_pow, op_mul, op_div, op_mod, op_add, op_sub,
                   op_eq, op_ne, op_gt, op_ge, op_lt, op_le, op_and, op_or, op_xor };

int precedence(int op) {
  switch (op) {
    case op_pow: return 4;
    case op_mul: case op_div: case op_mod: return 3;
    case op_add: case op_sub: return 2;
    case op_eq: case op_ne: case op_gt: case op_ge: case op_lt: case op_le: return 1;
    case op_and: case op_or: case op_xor: return 0;
    default: return -1;
  }
}

// Character classes for normalize(): letters map to lower case, other printable characters to
// themselves, the rest to the codes below (all under 32).
constexpr unsigned char kSkip = 1;
constexpr unsigned char kParen = 2;
constexpr unsigned char kSemicolon = 3;
constexpr unsigned char kBad = 4;

struct CharClass {
  unsigned char t[256];
  constexpr CharClass() : t() {
    for (int c = 0; c < 256; ++c) {
      unsigned char v = kBad;
      if (c >= 'A' && c <= 'Z') v = static_cast<unsigned char>(c + 32);
      else if (c >= 32 && c < 127) v = static_cast<unsigned char>(c);
      if (c == ' ' || c == '\t') v = kSkip;
      if (c == '(') v = kParen;
      if (c == ';') v = kSemicolon;
      t[c] = v;
    }
  }
  unsigned char operator[](unsigned char c) const { return t[c]; }
};
constexpr CharClass kCharClass{};

struct Assignment {
  int number = 0;        // numbered parameter, or 0 for a named one
  std::string name;      // named parameter
  double value = 0.0;
};

}  // namespace

struct GcodeReader::Impl {
  // ---- source ---------------------------------------------------------------------------------
  std::string source;
  ReaderOptions opt;
  std::FILE* file = nullptr;
  std::string text;          // from_string: the whole program
  std::vector<char> buf;     // file: read buffer
  std::size_t beg = 0, end = 0;
  bool eof = false;
  long line_no = 0;
  bool ended = false;        // M2 / M30 seen or end of input

  // ---- current line -----------------------------------------------------------------------------
  std::string norm;          // line without blanks/comments, lower case
  std::size_t nlen = 0;      // length of norm (norm[nlen] == '\0')
  const char* line_b = nullptr;  // the source line (valid until the next fetch)
  const char* line_e = nullptr;
  std::size_t pos = 0;       // cursor into norm
  int depth = 0;

  // words of the line
  std::array<double, 26> wval{};
  std::array<int, 26> wcol{};   // 0 = absent
  std::array<double, 16> gval{};
  std::array<int, 16> gcol{};
  int ng = 0;
  std::array<double, 8> mval{};
  std::array<int, 8> mcol{};
  int nm = 0;
  std::vector<Assignment> assigns;

  // ---- parameters and modal state ---------------------------------------------------------------
  std::vector<double> numbered = std::vector<double>(kMaxNumbered + 1, 0.0);
  NamedParams named;
  Vec3 position = Vec3::Zero();
  int motion = -1;           // 0, 1, 2, 3 or −1 (none / after G80)
  Plane plane = Plane::xy;
  bool inch = false;
  bool incremental = false;
  bool arc_absolute = false;  // G90.1
  double feed = 0.0;          // [mm/s]
  double speed = 0.0;         // [rev/min], magnitude
  int spindle_dir = 0;        // +1 M3, −1 M4, 0 M5
  int selected_tool = 0;
  int tool = 0;
  double dwell_total = 0.0;
  long dwell_count = 0;

  // ---- non-motion records, offsets ------------------------------------------------------------
  std::vector<Command> pending;   // commands not yet taken
  std::size_t blocks_out = 0;     // blocks returned so far (the `before` of new commands)
  std::vector<std::pair<std::size_t, std::size_t>> comments;  // [b, e) offsets into the line
  std::vector<std::string> warns;
  bool warned_offsets = false, warned_tools = false;
  int coord_system = 0;           // 0 … 8: G54 … G59.3
  double tool_offset = 0.0;       // tool length applied along +Z [mm]
  Vec3 offset = Vec3::Zero();     // work offset + tool length in force [mm]
  Vec3 mpos = Vec3::Zero();       // position in the output frame (program + offset) [mm]

  void record(CommandKind kind, std::string text, double value = 0.0) {
    if (!opt.keep_commands) return;
    Command c;
    c.before = blocks_out;
    c.kind = kind;
    c.text = std::move(text);
    c.value = value;
    c.line = line_no;
    pending.push_back(std::move(c));
  }
  // Initial state: G54 in force, no tool length, the tool at opt.initial_position (program coordinates).
  void start() {
    position = opt.initial_position;
    offset = opt.has_work_offsets ? Vec3(opt.work_offsets.row(0).transpose()) : Vec3::Zero();
    mpos = position + offset;
  }
  void warn(const std::string& what) { warns.push_back(source + ":" + std::to_string(line_no) + ": " + what); }
  // Offset in force changed: the tool stays where it is, its program coordinates change.
  void set_offset() {
    Vec3 o = opt.has_work_offsets ? Vec3(opt.work_offsets.row(coord_system).transpose()) : Vec3::Zero();
    o.z() += tool_offset;
    offset = o;
    position = mpos - offset;
  }

  ~Impl() {
    if (file) std::fclose(file);
  }

  // ---- errors -----------------------------------------------------------------------------------
  // `mark` is 1 + the index into the normalised line; the source column is worked out only here.
  [[noreturn]] void fail_at(int mark, const std::string& why) const {
    throw ParseError(source, line_no, column_of(static_cast<std::size_t>(mark > 0 ? mark - 1 : 0)), why);
  }
  [[noreturn]] void fail(const std::string& why) const { fail_at(static_cast<int>(pos) + 1, why); }

  // ---- line input -------------------------------------------------------------------------------
  // Sets [b, e) to the next line (without its line break). False at the end of input.
  bool fetch_line(const char*& b, const char*& e) {
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

  // Copy the line into `norm` (lower case, no blanks, no comments). Source columns are not stored:
  // column_of() recomputes one when an error needs it.
  void normalize(const char* b, const char* e) {
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

  // Source column (1-based) of character `idx` of the normalised line.
  int column_of(std::size_t idx) const {
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

  // ---- values -----------------------------------------------------------------------------------
  char peek() const { return norm[pos]; }

  double number() {
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

  void enter() {
    if (++depth > kMaxDepth) fail("expression nested deeper than " + std::to_string(kMaxDepth) + " levels");
  }

  // `#…` read (pos at '#'). Returns the value of the parameter.
  double parameter_value() {
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

  int param_index(double idx, int column) const {
    const double r = std::round(idx);
    if (!(std::abs(idx - r) < 1e-6) || r < 1 || r > kMaxNumbered)
      fail_at(column, "parameter number " + fmt_num(idx) + " is not an integer in 1 … " + std::to_string(kMaxNumbered));
    return static_cast<int>(r);
  }

  // A real value: number, [expression], #parameter, function[…], with an optional sign.
  double real_value() {
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

  bool match(const char* word) {
    std::size_t k = 0;
    while (word[k] && norm[pos + k] == word[k]) ++k;  // norm is NUL-terminated
    if (word[k]) return false;
    pos += k;
    return true;
  }

  double bracketed() {
    if (peek() != '[') fail("expected '[' after the function name");
    ++pos;
    enter();
    const double v = expression();
    if (peek() != ']') fail("expected ']' to close the function argument");
    ++pos;
    --depth;
    return v;
  }

  double checked(double v, int column, const char* what) const {
    if (!std::isfinite(v)) fail_at(column, std::string(what) + " is not a finite number");
    return v;
  }

  double function() {
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

  int binary_op() {
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

  double apply(int op, double a, double b, int column) const {
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

  // Precedence climbing over the NGC binary operators, left to right within a level.
  double expression() { return expression_level(0); }

  double expression_level(int min_prec) {
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

  // ---- words ------------------------------------------------------------------------------------
  void read_words() {
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
      if (c == 'o') fail("o-word subroutines and control flow (O…) are not supported");
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

  void read_assignment() {
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

  void apply_assignments() {
    for (const auto& a : assigns) {
      if (a.number) numbered[static_cast<std::size_t>(a.number)] = a.value;
      else named.set(a.name, a.value);
    }
  }

  bool has(char c) const { return wcol[c - 'a'] != 0; }
  double val(char c) const { return wval[c - 'a']; }
  int wc(char c) const { return wcol[c - 'a']; }

  // ---- execution --------------------------------------------------------------------------------
  // Returns true if a block was produced.
  // Comments of the current line, in order (after its N word when line numbers are kept).
  void record_comments() {
    if (!comments.empty() && opt.keep_commands)
      for (const auto& [cb, ce] : comments) record(CommandKind::comment, std::string(line_b + cb, line_b + ce));
  }

  bool execute(Block& out) {
    if (opt.keep_line_numbers && has('n')) {
      const double n = val('n');
      if (n < 0.0 || n > 1e9 || std::round(n) != n) fail_at(wc('n'), "N = " + fmt_num(n) + ": line number must be a non-negative integer");
      record(CommandKind::word, "N" + std::to_string(static_cast<long>(n)));
    }
    record_comments();
    // Unsupported letters first (they change the path or belong to refused codes).
    static const char* const kAxisNames = "abcuvw";
    for (const char* p = kAxisNames; *p; ++p)
      if (has(*p))
        fail_at(wc(*p), std::string("axis word ") + static_cast<char>(*p - 32) +
                            " is not supported (only X, Y, Z axes)");

    // G codes: sort into modal groups, refuse what is not supported.
    int g_motion = -2, g_motion_col = 0, g_plane = -1, g_units = -1, g_dist = -1, g_arcdist = -1;
    bool g_dwell = false;
    int g_dwell_col = 0;
    // codes kept as commands (×10 code, or −1 when absent)
    long g_cutter = -1, g_tlo = -1, g_cs = -1, g_path = -1, g_spindle_mode = -1, g_retract = -1, g_g92 = -1;
    bool g_cancel = false;
    int group_col[16] = {0};
    auto group = [&](int gi, int column, long c10) {
      if (group_col[gi]) fail_at(column, code_name('G', c10) + " conflicts with another G-code of the same modal group on the line");
      group_col[gi] = column;
    };
    bool uses_p = false, uses_q = false, uses_h = false;
    for (int i = 0; i < ng; ++i) {
      const long c = code10(gval[i]);
      const int column = gcol[i];
      if (c < 0) fail_at(column, "unknown G-code G" + fmt_num(gval[i]));
      switch (c) {
        case 0: case 10: case 20: case 30: case 800:
          group(0, column, c);
          g_motion = static_cast<int>(c / 10);
          if (c == 800) {
            g_motion = -1;
            g_cancel = true;
          }
          g_motion_col = column;
          break;
        case 40:
          group(1, column, c);
          g_dwell = true;
          g_dwell_col = column;
          break;
        case 170: case 180: case 190:
          group(2, column, c);
          g_plane = static_cast<int>(c / 10 - 17);
          break;
        case 200: case 210:
          group(3, column, c);
          g_units = c == 200 ? 1 : 0;
          break;
        case 900: case 910:
          group(4, column, c);
          g_dist = c == 910 ? 1 : 0;
          break;
        case 901: case 911:
          group(5, column, c);
          g_arcdist = c == 901 ? 1 : 0;
          break;
        case 400:  // cutter compensation off: nothing to undo
          group(6, column, c);
          g_cutter = c;
          break;
        case 430: case 490:  // tool length offset (applied from the tool table when given)
          group(7, column, c);
          if (c == 430) uses_h = true;
          g_tlo = c;
          break;
        case 540: case 550: case 560: case 570: case 580: case 590: case 591: case 592: case 593:
          group(8, column, c);  // work offsets (applied when given)
          g_cs = c;
          break;
        case 610: case 611: case 640:
          group(9, column, c);
          if (c == 640) uses_p = uses_q = true;
          g_path = c;
          break;
        case 940:  // the only feed mode: the writer states it in its header
          group(10, column, c);
          break;
        case 970:
          group(11, column, c);
          g_spindle_mode = c;
          break;
        case 980: case 990:
          group(12, column, c);
          g_retract = c;
          break;
        case 921: case 922:  // cancel G92 offsets: there are none
          group(13, column, c);
          g_g92 = c;
          break;
        case 50: case 51: case 52: case 53: case 62: case 63:
          fail_at(column, "NURBS/spline block " + code_name('G', c) + " is not supported");
        case 410: case 411: case 420: case 421:
          fail_at(column, "cutter radius compensation " + code_name('G', c) + " is not supported");
        case 730: case 760: case 810: case 820: case 830: case 840: case 850: case 860: case 870: case 880: case 890:
          fail_at(column, "canned cycle " + code_name('G', c) + " is not supported");
        case 920: case 923:
          fail_at(column, "coordinate offset " + code_name('G', c) + " is not supported");
        case 930:
          fail_at(column, "inverse-time feed G93 is not supported (use G94, units per minute)");
        case 950:
          fail_at(column, "feed per revolution G95 is not supported (use G94, units per minute)");
        case 960:
          fail_at(column, "constant surface speed G96 is not supported");
        case 100: case 280: case 281: case 300: case 301: case 330: case 331:
        case 382: case 383: case 384: case 385: case 431: case 432: case 520: case 530: case 171: case 181:
        case 191: case 761: case 742: case 642:
          fail_at(column, code_name('G', c) + " is not supported (it changes the path in a way this reader does not model)");
        default:
          fail_at(column, "unknown G-code " + code_name('G', c));
      }
    }

    // M codes.
    int m_spindle = -1, m_stop = -1, m_override = -1;
    int m_coolant[3] = {-1, -1, -1};  // M7, M8, M9 in the order given
    int n_coolant = 0;
    bool m_change = false;
    int mgroup_col[8] = {0};
    auto mgroup = [&](int gi, int column, long c) {
      if (mgroup_col[gi]) fail_at(column, "M" + std::to_string(c) + " conflicts with another M-code of the same modal group on the line");
      mgroup_col[gi] = column;
    };
    for (int i = 0; i < nm; ++i) {
      const long c10 = code10(mval[i]);
      const int column = mcol[i];
      if (c10 < 0 || c10 % 10) fail_at(column, "unknown M-code M" + fmt_num(mval[i]));
      const long c = c10 / 10;
      switch (c) {
        case 0: case 1: case 2: case 30: case 60:
          mgroup(0, column, c);
          m_stop = static_cast<int>(c);
          break;
        case 3: case 4: case 5:
          mgroup(1, column, c);
          m_spindle = static_cast<int>(c);
          break;
        case 6:
          mgroup(2, column, c);
          m_change = true;
          break;
        case 7: case 8: case 9:  // coolant (M7 and M8 may share a line)
          if (n_coolant == 3) fail_at(column, "too many coolant M-codes on one line");
          m_coolant[n_coolant++] = static_cast<int>(c);
          break;
        case 48: case 49: case 50: case 51: case 52: case 53:
          mgroup(3, column, c);
          m_override = static_cast<int>(c);
          break;  // overrides
        case 98: case 99:
          fail_at(column, "subroutine M" + std::to_string(c) + " is not supported");
        default:
          fail_at(column, (c >= 100 && c <= 199 ? "user M-code M" : "unsupported M-code M") + std::to_string(c));
      }
    }

    // Units first: F and axis words on this line are read in the units in force after it.
    if (g_units >= 0) inch = g_units == 1;
    const double u = inch ? kInch : 1.0;

    if (has('f')) {
      const double f = val('f');
      if (f < 0.0) fail_at(wc('f'), "F = " + fmt_num(f) + ": feed must not be negative");
      feed = f * u / 60.0;
      if (!(feed <= kMaxCoordinate)) fail_at(wc('f'), "F = " + fmt_num(f) + ": feed out of range");
    }
    if (has('s')) {
      const double s = val('s');
      if (s < 0.0 || !(s <= 1e7)) fail_at(wc('s'), "S = " + fmt_num(s) + ": spindle speed must be in 0 … 1e7 [rev/min]");
      speed = s;
      record(CommandKind::word, "S" + fmt_word(s));
    }
    if (has('t')) {
      const double t = val('t');
      if (t < 0.0 || t > 1e9 || std::round(t) != t) fail_at(wc('t'), "T = " + fmt_num(t) + ": tool number must be a non-negative integer");
      selected_tool = static_cast<int>(t);
      record(CommandKind::word, "T" + std::to_string(selected_tool));
    }
    if (m_change) {
      tool = selected_tool;
      record(CommandKind::word, "M6");
    }
    if (m_spindle == 3) spindle_dir = 1;
    if (m_spindle == 4) spindle_dir = -1;
    if (m_spindle == 5) spindle_dir = 0;
    if (m_spindle >= 0) record(CommandKind::word, "M" + std::to_string(m_spindle));
    for (int i = 0; i < n_coolant; ++i) record(CommandKind::word, "M" + std::to_string(m_coolant[i]));
    if (m_override >= 0) record(CommandKind::word, "M" + std::to_string(m_override));

    if (g_dwell) {
      if (!has('p')) fail_at(g_dwell_col, "G4 dwell needs a P word (seconds)");
      const double p = val('p');
      if (p < 0.0 || !(p <= 1e7)) fail_at(wc('p'), "P = " + fmt_num(p) + ": dwell must be in 0 … 1e7 [s]");
      dwell_total += p;
      ++dwell_count;
      uses_p = true;
      record(CommandKind::dwell, "G4 P" + fmt_word(p), p);
    }
    if (g_plane >= 0) plane = static_cast<Plane>(g_plane);
    if (g_cutter >= 0) record(CommandKind::word, code_name('G', g_cutter));
    if (g_tlo >= 0) tool_length(g_tlo);
    if (g_cs >= 0) work_offset(g_cs);
    if (g_path >= 0) {
      std::string t = code_name('G', g_path);
      if (g_path == 640) {  // P (blending tolerance) and Q (naive CAM tolerance) are lengths: in mm
        for (const char l : {'p', 'q'}) {
          if (!has(l)) continue;
          const double v = val(l);
          if (!(v >= 0.0 && v <= kMaxCoordinate))
            fail_at(wc(l), std::string(1, static_cast<char>(l - 32)) + " = " + fmt_num(v) +
                               ": G64 tolerance must be a non-negative length");
          t += ' ';
          t += static_cast<char>(l - 32);
          t += fmt_word(v * u);
        }
      }
      record(CommandKind::word, std::move(t));
    }
    if (g_dist >= 0) incremental = g_dist == 1;
    if (g_arcdist >= 0) arc_absolute = g_arcdist == 1;
    if (g_g92 >= 0) record(CommandKind::word, code_name('G', g_g92));
    if (g_spindle_mode >= 0) record(CommandKind::word, code_name('G', g_spindle_mode));
    if (g_retract >= 0) record(CommandKind::word, code_name('G', g_retract));
    if (g_cancel) record(CommandKind::word, "G80");
    if (g_motion != -2) motion = g_motion;

    const bool axes = has('x') || has('y') || has('z');
    const bool arc_words = has('i') || has('j') || has('k') || has('r');
    bool produced = false;

    if (g_motion != -2 && g_motion_col && motion >= 2 && !axes)
      fail_at(g_motion_col, std::string(motion == 2 ? "G2" : "G3") + " arc without X, Y or Z end point words");
    if (axes) {
      if (motion < 0)
        fail_at(wc(has('x') ? 'x' : has('y') ? 'y' : 'z'),
                "axis words without an active motion mode (program G0, G1, G2 or G3)");
      Vec3 target = position;
      const char letters[3] = {'x', 'y', 'z'};
      for (int a = 0; a < 3; ++a) {
        if (!has(letters[a])) continue;
        const double v = val(letters[a]) * u;
        if (!(std::abs(v) <= kMaxCoordinate))
          fail_at(wc(letters[a]), std::string(1, static_cast<char>(letters[a] - 32)) + " = " + fmt_num(val(letters[a])) +
                                      ": coordinate out of range (|value| ≤ 1e9 mm)");
        target[a] = incremental ? position[a] + v : v;
        if (!(std::abs(target[a]) <= kMaxCoordinate))
          fail_at(wc(letters[a]), "coordinate out of range (|value| ≤ 1e9 mm)");
      }
      const int mcol0 = g_motion_col ? g_motion_col : wc(has('x') ? 'x' : has('y') ? 'y' : 'z');
      if (motion >= 1 && !(feed > 0.0))
        fail_at(mcol0, "feed move with no feed rate: program F (units per minute) before G1/G2/G3");
      out.start = position;
      out.end = target;
      out.feed = feed;
      out.spindle_rpm = spindle_dir * speed;
      out.tool = tool;
      out.line = line_no;
      out.turns = 1;
      out.clockwise = false;
      out.plane = plane;
      out.center = Vec3::Zero();
      if (motion <= 1) {
        if (arc_words) {
          const char w = has('i') ? 'i' : has('j') ? 'j' : has('k') ? 'k' : 'r';
          fail_at(wc(w), std::string("word ") + static_cast<char>(w - 32) + " is only used with G2/G3 arcs");
        }
        out.kind = motion == 0 ? MotionKind::rapid : MotionKind::line;
      } else {
        make_arc(out, target, u, mcol0);
        uses_p = true;
      }
      if (offset != Vec3::Zero()) {  // to the output frame; the start is exactly where the last block ended
        out.start = mpos;
        out.end = target + offset;
        out.center += offset;
      }
      position = target;
      mpos = out.end;
      produced = true;
      ++blocks_out;
    } else if (arc_words) {
      const char w = has('i') ? 'i' : has('j') ? 'j' : has('k') ? 'k' : 'r';
      fail_at(wc(w), std::string("word ") + static_cast<char>(w - 32) + " without a motion (no X, Y or Z on the line)");
    }
    if (has('p') && !uses_p) fail_at(wc('p'), "word P is not used by any code on the line");
    if (has('q') && !uses_q) fail_at(wc('q'), "word Q is not used by any code on the line");
    if (has('h') && !uses_h) fail_at(wc('h'), "word H is not used by any code on the line");
    static const char* const kUnused = "del";
    for (const char* p = kUnused; *p; ++p)
      if (has(*p)) fail_at(wc(*p), std::string("word ") + static_cast<char>(*p - 32) + " is not supported here");

    if (m_stop >= 0)
      record(m_stop == 2 || m_stop == 30 ? CommandKind::program_end : CommandKind::word, "M" + std::to_string(m_stop));
    if (m_stop == 2 || m_stop == 30) ended = true;
    return produced;
  }

  // G43 [H] / G49: tool length along +Z from the tool table (zero, with one warning, without one).
  void tool_length(long c) {
    if (c == 490) {
      tool_offset = 0.0;
      set_offset();
      record(CommandKind::tool_length, "G49", 0.0);
      return;
    }
    std::string text = "G43";
    int t = tool;
    if (has('h')) {
      const double h = val('h');
      if (h < 0.0 || h > 1e9 || std::round(h) != h)
        fail_at(wc('h'), "H = " + fmt_num(h) + ": tool number must be a non-negative integer");
      t = static_cast<int>(h);
      text += " H" + std::to_string(t);
    }
    double len = 0.0;
    if (opt.has_tool_table) {
      if (t != 0) {
        const auto it = opt.tool_lengths.find(t);
        if (it == opt.tool_lengths.end())
          fail_at(has('h') ? wc('h') : 1, "G43: tool " + std::to_string(t) + " is not in the tool table");
        len = it->second;
      }
    } else if (!warned_tools) {
      warned_tools = true;
      warn(text + " applies a tool length but no tool table was given; taken as zero");
    }
    tool_offset = len;
    set_offset();
    record(CommandKind::tool_length, std::move(text), len);
  }

  // G54 … G59.3: work offset from the options (zero, with one warning, without them).
  void work_offset(long c) {
    static const long codes[9] = {540, 550, 560, 570, 580, 590, 591, 592, 593};
    int k = 0;
    while (codes[k] != c) ++k;
    if (!opt.has_work_offsets && !warned_offsets) {
      warned_offsets = true;
      warn(code_name('G', c) + " selects a work offset but no work offsets were given; taken as zero");
    }
    coord_system = k;
    set_offset();
    record(CommandKind::work_offset, code_name('G', c), k);
  }

  void make_arc(Block& out, const Vec3& target, double u, int column) {
    const PlaneAxes ax = plane_axes(plane);
    const char off_letter[3] = {'i', 'j', 'k'};
    const char* plane_name[3] = {"XY plane (G17)", "ZX plane (G18)", "YZ plane (G19)"};
    const int pl = static_cast<int>(plane);
    if (has(off_letter[ax.n]))
      fail_at(wc(off_letter[ax.n]), std::string(1, static_cast<char>(off_letter[ax.n] - 32)) +
                                         " word given for an arc in the " + plane_name[pl]);
    out.kind = MotionKind::arc;
    out.clockwise = motion == 2;
    const Vec3& s = position;
    const Vec3& e = target;
    const double tol = (inch ? 0.0005 * kInch : 0.002);
    Vec3 c = s;
    if (has('r')) {
      if (has(off_letter[ax.a]) || has(off_letter[ax.b]))
        fail_at(wc('r'), "arc given with both R and I/J/K words");
      const double r = val('r') * u;
      if (!(std::abs(r) <= kMaxCoordinate)) fail_at(wc('r'), "R = " + fmt_num(val('r')) + ": radius out of range");
      const double da = e[ax.a] - s[ax.a], db = e[ax.b] - s[ax.b];
      const double chord = std::hypot(da, db);
      if (std::abs(r) < 1e-9) fail_at(wc('r'), "R arc with zero radius");
      if (chord <= 1e-9 * (1.0 + std::abs(r)))
        fail_at(wc('r'), "R arc with coincident end points (program a full circle with I/J/K)");
      double half = 0.5 * chord;
      const double ar = std::abs(r);
      if (half > ar) {
        if (half - ar > tol)
          fail_at(wc('r'), "arc radius too small to reach the end point: R " + fmt_fixed(ar, 4) +
                               " mm, half chord " + fmt_fixed(half, 4) + " mm");
        half = ar;
      }
      const double h = std::sqrt(std::max(0.0, ar * ar - half * half));
      // left normal of the chord; G3 with R > 0 (arc under 180°) has its centre on the left.
      const double na = -db / chord, nb = da / chord;
      double side = out.clockwise ? -1.0 : 1.0;
      if (r < 0.0) side = -side;
      c[ax.a] = 0.5 * (s[ax.a] + e[ax.a]) + side * h * na;
      c[ax.b] = 0.5 * (s[ax.b] + e[ax.b]) + side * h * nb;
    } else {
      if (!has(off_letter[ax.a]) && !has(off_letter[ax.b]))
        fail_at(column, std::string("arc needs R or the centre words ") +
                            static_cast<char>(off_letter[ax.a] - 32) + "/" + static_cast<char>(off_letter[ax.b] - 32) +
                            " in the " + plane_name[pl]);
      for (int k : {ax.a, ax.b}) {
        const char l = off_letter[k];
        if (arc_absolute) {
          if (!has(l))
            fail_at(column, std::string("absolute arc centres (G90.1) need both ") +
                                static_cast<char>(off_letter[ax.a] - 32) + " and " +
                                static_cast<char>(off_letter[ax.b] - 32));
          c[k] = val(l) * u;
        } else {
          c[k] = s[k] + (has(l) ? val(l) * u : 0.0);
        }
        if (!(std::abs(c[k]) <= kMaxCoordinate)) fail_at(wc(l), "arc centre out of range (|value| ≤ 1e9 mm)");
      }
      const double r0 = std::hypot(s[ax.a] - c[ax.a], s[ax.b] - c[ax.b]);
      const double r1 = std::hypot(e[ax.a] - c[ax.a], e[ax.b] - c[ax.b]);
      if (r0 <= 1e-9) fail_at(column, "arc centre coincides with its start point (zero radius)");
      if (std::abs(r1 - r0) > tol + 1e-3 * r0)
        fail_at(column, "arc radius mismatch: start radius " + fmt_fixed(r0, 3) + " mm, end radius " +
                            fmt_fixed(r1, 3) + " mm");
    }
    c[ax.n] = s[ax.n];
    out.center = c;
    out.turns = 1;
    if (has('p')) {
      const double p = val('p');
      if (p < 1.0 || p > 1e4 || std::round(p) != p)
        fail_at(wc('p'), "P = " + fmt_num(p) + ": arc turns must be an integer in 1 … 10000");
      out.turns = static_cast<int>(p);
    }
  }

  bool next(Block& out) {
    const char* b = nullptr;
    const char* e = nullptr;
    while (!ended) {
      if (!fetch_line(b, e)) {
        ended = true;
        break;
      }
      normalize(b, e);
      if (nlen == 0) {
        record_comments();
        continue;
      }
      if (norm[0] == '%') {
        if (nlen == 1) continue;
        throw ParseError(source, line_no, column_of(1), "unexpected text after '%'");
      }
      if (norm[0] == '/') throw ParseError(source, line_no, column_of(0), "block delete '/' is not supported");
      read_words();
      const bool produced = execute(out);
      apply_assignments();
      if (produced) return true;
    }
    return false;
  }
};

GcodeReader::GcodeReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GcodeReader::GcodeReader(GcodeReader&&) noexcept = default;
GcodeReader& GcodeReader::operator=(GcodeReader&&) noexcept = default;
GcodeReader::~GcodeReader() = default;

GcodeReader GcodeReader::open(const std::string& path, const ReaderOptions& options) {
  options.validate();
  auto impl = std::make_unique<Impl>();
  impl->source = path;
  impl->opt = options;
  impl->start();
  impl->file = std::fopen(path.c_str(), "rb");
  if (!impl->file) {
    throw std::invalid_argument("path = " + path + ": cannot open the file for reading (" + std::strerror(errno) + ")");
  }
  impl->buf.resize(1 << 20);
  return GcodeReader(std::move(impl));
}

GcodeReader GcodeReader::from_string(std::string text, const std::string& source, const ReaderOptions& options) {
  options.validate();
  auto impl = std::make_unique<Impl>();
  impl->source = source;
  impl->opt = options;
  impl->start();
  impl->text = std::move(text);
  return GcodeReader(std::move(impl));
}

bool GcodeReader::next(Block& block) { return impl_->next(block); }
const std::string& GcodeReader::source() const noexcept { return impl_->source; }
long GcodeReader::lines_read() const noexcept { return impl_->line_no; }
double GcodeReader::dwell_time() const noexcept { return impl_->dwell_total; }
long GcodeReader::dwells() const noexcept { return impl_->dwell_count; }
Vec3 GcodeReader::position() const noexcept { return impl_->position; }
void GcodeReader::take_commands(std::vector<Command>& out) {
  if (out.empty()) {
    out.swap(impl_->pending);
  } else {
    out.insert(out.end(), std::make_move_iterator(impl_->pending.begin()), std::make_move_iterator(impl_->pending.end()));
  }
  impl_->pending.clear();
}
const std::vector<std::string>& GcodeReader::warnings() const noexcept { return impl_->warns; }

namespace {
Toolpath drain(GcodeReader& r) {
  Toolpath tp;
  tp.source = r.source();
  Block b;
  while (r.next(b)) tp.blocks.push_back(b);
  r.take_commands(tp.commands);
  tp.dwell_time = r.dwell_time();
  tp.dwells = r.dwells();
  tp.warnings = r.warnings();
  return tp;
}
Summary summarize(GcodeReader& r) {
  SummaryBuilder sb;
  Block b;
  while (r.next(b)) sb.add(b);
  sb.add_dwell(r.dwell_time(), r.dwells());
  Summary s = sb.summary();
  s.source_lines = r.lines_read();
  s.warnings = r.warnings();
  return s;
}
}  // namespace

Toolpath read_gcode(const std::string& path, const ReaderOptions& options) {
  GcodeReader r = GcodeReader::open(path, options);
  Toolpath tp = drain(r);
  if (options.has_work_offsets) tp.work_offsets = options.work_offsets;
  return tp;
}

Toolpath parse_gcode(const std::string& text, const std::string& source, const ReaderOptions& options) {
  GcodeReader r = GcodeReader::from_string(text, source, options);
  Toolpath tp = drain(r);
  if (options.has_work_offsets) tp.work_offsets = options.work_offsets;
  return tp;
}

Summary summarize_gcode(const std::string& path, const ReaderOptions& options) {
  ReaderOptions o = options;
  o.keep_commands = false;
  GcodeReader r = GcodeReader::open(path, o);
  return summarize(r);
}

Summary summarize_gcode_text(const std::string& text, const std::string& source, const ReaderOptions& options) {
  ReaderOptions o = options;
  o.keep_commands = false;
  GcodeReader r = GcodeReader::from_string(text, source, o);
  return summarize(r);
}

}  // namespace netshape::toolpath
