#pragma once
// Private to the G-code reader (not installed): the reader state GcodeReader::Impl and the helpers
// its three parts share — gcode_reader.cpp (options, the per-line loop next(), the public API),
// gcode_line.cpp (reading one line: input, normalised copy, numbers, parameters, expressions, words)
// and gcode_execute.cpp (executing one line: modal state, offsets, records, the emitted block).

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/toolpath/gcode_reader.hpp"

namespace netshape::toolpath {

namespace gcode_detail {

inline constexpr int kMaxDepth = 64;            // nesting of [ ], functions and # indirection
inline constexpr int kMaxNumbered = 5602;       // numbered parameters #1 … #5602 (LinuxCNC)
inline constexpr double kMaxCoordinate = 1e9;   // [mm] larger coordinates are refused
inline constexpr double kInch = 25.4;

inline constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                         1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

inline std::string fmt_num(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A word value as G-code text: shortest form that reads back exactly, never in exponent notation.
inline std::string fmt_word(double v) {
  char buf[400];
  if (v == 0.0) v = 0.0;  // no "-0"
  auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
  return std::string(buf, r.ptr);
}

inline std::string fmt_fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Code value ×10 (G5.2 → 52) if the number is a valid code (at most one decimal); −1 otherwise.
inline long code10(double v) {
  if (!(v >= 0.0) || v > 1e6) return -1;
  const double t = v * 10.0;
  const double r = std::round(t);
  if (std::abs(t - r) > 1e-6) return -1;
  return static_cast<long>(r);
}

inline std::string code_name(char letter, long c10) {
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

inline int precedence(int op) {
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
inline constexpr unsigned char kSkip = 1;
inline constexpr unsigned char kParen = 2;
inline constexpr unsigned char kSemicolon = 3;
inline constexpr unsigned char kBad = 4;

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
inline constexpr CharClass kCharClass{};

// A LinuxCNC subroutine `oN sub` … `oN endsub`: its body lines as written, with their line numbers.
struct SubBody {
  long def_line = 0;
  std::vector<std::pair<long, std::string>> lines;
};

// An active `oN call`: the body being replayed, the next body line, the caller's line, and the
// parameters #1 … #30 the call replaced (restored when the sub returns).
inline constexpr int kSubParams = 30;
// Lines all calls of a program may replay together: calls nest only kMaxDepth deep, but a sub that
// calls another twice at each of 40 levels would replay 2^40 lines; past this budget the reader
// refuses the program instead of expanding it until memory runs out.
inline constexpr long kMaxReplayedLines = 5'000'000;
struct CallFrame {
  std::string label;
  const SubBody* body = nullptr;
  std::size_t next = 0;
  long caller_line = 0;
  std::array<double, kSubParams> saved{};
};

struct Assignment {
  int number = 0;        // numbered parameter, or 0 for a named one
  std::string name;      // named parameter
  double value = 0.0;
};

}  // namespace gcode_detail

using namespace gcode_detail;

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
  std::map<std::string, SubBody> subs;  // subroutines defined so far, by label ("100", "<name>")
  std::vector<CallFrame> calls;         // active calls, outermost first
  long replayed = 0;                    // body lines replayed by calls so far (≤ kMaxReplayedLines)

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
    c.line = owner_line();
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
  bool fetch_line(const char*& b, const char*& e);
  // The next line to execute: the active subroutine's next body line, else the next source line.
  bool fetch(const char*& b, const char*& e);
  // The source line the current line's blocks and records belong to: the outermost call's line
  // while a subroutine runs (so a call line owns every move it makes), the current line otherwise.
  long owner_line() const { return calls.empty() ? line_no : calls.front().caller_line; }

  // ---- o-words (gcode_subs.cpp) -----------------------------------------------------------------
  // A line that starts with an o-word: a Fanuc program number `O1234` (kept as a word record), or
  // LinuxCNC `oN sub` (the body is stored until `oN endsub`), `oN call [a] [b] …`, `oN return`.
  // Control flow (if, while, do, repeat …) is refused with a ParseError naming the line.
  void o_word();
  void define_sub(const std::string& label);
  void call_sub(const std::string& label);
  void return_sub();

  // Copy the line into `norm` (lower case, no blanks, no comments). Source columns are not stored:
  // column_of() recomputes one when an error needs it.
  void normalize(const char* b, const char* e);

  // Source column (1-based) of character `idx` of the normalised line.
  int column_of(std::size_t idx) const;

  // ---- values -----------------------------------------------------------------------------------
  char peek() const { return norm[pos]; }

  double number();

  void enter();

  // `#…` read (pos at '#'). Returns the value of the parameter.
  double parameter_value();

  int param_index(double idx, int column) const;

  // A real value: number, [expression], #parameter, function[…], with an optional sign.
  double real_value();

  bool match(const char* word);

  double bracketed();

  double checked(double v, int column, const char* what) const;

  double function();

  int binary_op();

  double apply(int op, double a, double b, int column) const;

  // Precedence climbing over the NGC binary operators, left to right within a level.
  double expression() { return expression_level(0); }

  double expression_level(int min_prec);

  // ---- words ------------------------------------------------------------------------------------
  void read_words();

  void read_assignment();

  void apply_assignments();

  bool has(char c) const { return wcol[c - 'a'] != 0; }
  double val(char c) const { return wval[c - 'a']; }
  int wc(char c) const { return wcol[c - 'a']; }

  // ---- execution --------------------------------------------------------------------------------
  // Comments of the current line, in order (after its N word when line numbers are kept).
  void record_comments();

  // Returns true if a block was produced.
  bool execute(Block& out);

  // G43 [H] / G49: tool length along +Z from the tool table (zero, with one warning, without one).
  void tool_length(long c);

  // G54 … G59.3: work offset from the options (zero, with one warning, without them).
  void work_offset(long c);

  void make_arc(Block& out, const Vec3& target, double u, int column);

  bool next(Block& out);
};

}  // namespace netshape::toolpath
