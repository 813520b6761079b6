// G-code reader, o-words: Fanuc program numbers and LinuxCNC subroutines. A subroutine's body is
// stored (as written) when its definition is read and replayed line by line at each call, so a
// call makes exactly the moves of the same lines written out in its place. Calls nest up to
// kMaxDepth; #1 … #30 take the call's arguments (0 where none is given) and get their values back
// when the sub returns, as LinuxCNC does.
#include <algorithm>
#include <string>
#include <utility>

#include "gcode_reader_impl.hpp"

namespace netshape::toolpath {

namespace {

bool is_letter(char c) { return c >= 'a' && c <= 'z'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// The end of the label of the o-word that starts `s` (normalised, s[0] == 'o'): after its digits or
// its <name>; 1 when there is neither.
std::size_t label_end(const std::string& s, std::size_t n) {
  std::size_t p = 1;
  if (p < n && s[p] == '<') {
    const std::size_t close = s.find('>', p);
    return close == std::string::npos || close >= n ? 1 : close + 1;
  }
  while (p < n && is_digit(s[p])) ++p;
  return p;
}

// The label of the o-word that starts `s`: "100" for o100 and o0100, "<name>" for o<name>; empty
// for none.
std::string o_label(const std::string& s, std::size_t n) {
  const std::size_t k = label_end(s, n);
  if (k == 1) return {};
  const std::string l = s.substr(1, k - 1);
  return l[0] == '<' ? l : std::to_string(std::stoll(l.substr(0, 18)));
}

// The keyword after the o-word's label ("sub", "call" …; empty for none).
std::string o_keyword(const std::string& s, std::size_t n) {
  const std::size_t k = label_end(s, n);
  std::size_t p = k;
  while (p < n && is_letter(s[p])) ++p;
  return s.substr(k, p - k);
}

}  // namespace

bool GcodeReader::Impl::fetch(const char*& b, const char*& e) {
  while (!calls.empty()) {
    CallFrame& f = calls.back();
    if (f.next < f.body->lines.size()) {
      if (++replayed > kMaxReplayedLines)
        throw ParseError(source, calls.front().caller_line, 1,
                         "o-word calls replay more than " + std::to_string(kMaxReplayedLines) +
                             " lines (subroutines calling each other too often); the program is not read");
      const auto& [ln, text] = f.body->lines[f.next++];
      line_no = ln;
      b = text.data();
      e = text.data() + text.size();
      return true;
    }
    return_sub();  // the body ran to its endsub
  }
  return fetch_line(b, e);
}

void GcodeReader::Impl::o_word() {
  wcol.fill(0);  // an o-word line has no other words
  pos = 1;
  const std::size_t kw = label_end(norm, nlen);
  if (kw == 1) fail("o-word needs a number or a closed <name> (o100 sub, o<name> call, O1234)");
  const std::string label = o_label(norm, nlen);
  pos = kw;
  const std::string keyword = o_keyword(norm, nlen);
  pos += keyword.size();
  if (keyword.empty()) {  // Fanuc program number: kept as written, changes nothing
    if (label[0] == '<' || pos != nlen) fail("expected sub, endsub, call or return after the o-word");
    record(CommandKind::word, "O" + norm.substr(1, nlen - 1));
    record_comments();  // after the number, which heads its line
    return;
  }
  record_comments();
  const int kw_col = static_cast<int>(kw) + 1;
  if (keyword == "sub") {
    if (pos != nlen) fail("unexpected text after 'sub'");
    define_sub(label);
  } else if (keyword == "call") {
    call_sub(label);
  } else if (keyword == "return" || keyword == "endsub") {
    if (calls.empty() || calls.back().label != label)
      fail_at(kw_col, "o" + label + " " + keyword + " outside a call of o" + label);
    if (pos < nlen && peek() == '[') named.set("_value", bracketed());
    if (pos != nlen) fail("unexpected text after '" + keyword + "'");
    return_sub();
  } else {
    fail_at(kw_col, "o-word control flow '" + keyword +
                        "' is not supported (only sub, endsub, call and return; O1234 program numbers)");
  }
}

void GcodeReader::Impl::define_sub(const std::string& label) {
  if (!calls.empty()) fail("o" + label + " sub: a subroutine cannot be defined inside a call");
  if (subs.count(label)) fail("o" + label + " sub: defined twice");
  SubBody body;
  body.def_line = line_no;
  const char* b = nullptr;
  const char* e = nullptr;
  for (;;) {
    if (!fetch_line(b, e))
      throw ParseError(source, body.def_line, 1, "o" + label + " sub is not closed by o" + label + " endsub");
    normalize(b, e);
    const bool o_line = nlen > 1 && norm[0] == 'o';
    if (o_line && o_keyword(norm, nlen) == "endsub" && o_label(norm, nlen) == label) break;
    if (o_line && o_keyword(norm, nlen) == "sub")
      fail("a subroutine cannot be defined inside o" + label + " sub");
    body.lines.emplace_back(line_no, std::string(b, e));
  }
  subs.emplace(label, std::move(body));
}

void GcodeReader::Impl::call_sub(const std::string& label) {
  const auto it = subs.find(label);
  if (it == subs.end()) fail("o" + label + " call: no subroutine o" + label + " is defined above this line");
  if (static_cast<int>(calls.size()) >= kMaxDepth)
    fail("o" + label + " call: calls nested deeper than " + std::to_string(kMaxDepth));
  std::array<double, kSubParams> args{};
  int n = 0;
  while (pos < nlen) {
    if (peek() != '[') fail("o" + label + " call: arguments are written in brackets, o100 call [1] [2.5]");
    if (n == kSubParams) fail("o" + label + " call: more than 30 arguments");
    args[static_cast<std::size_t>(n++)] = bracketed();
  }
  CallFrame f;
  f.label = label;
  f.body = &it->second;
  f.caller_line = calls.empty() ? line_no : calls.front().caller_line;
  for (int i = 0; i < kSubParams; ++i) {
    f.saved[static_cast<std::size_t>(i)] = numbered[static_cast<std::size_t>(i + 1)];
    numbered[static_cast<std::size_t>(i + 1)] = args[static_cast<std::size_t>(i)];
  }
  calls.push_back(std::move(f));
}

void GcodeReader::Impl::return_sub() {
  CallFrame& f = calls.back();
  std::copy(f.saved.begin(), f.saved.end(), numbered.begin() + 1);  // #1 … #30 as before the call
  const long caller = f.caller_line;
  calls.pop_back();
  if (calls.empty()) line_no = caller;  // the source continues after the outermost call line
}

}  // namespace netshape::toolpath
