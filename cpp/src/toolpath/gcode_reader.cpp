// Streaming RS274/NGC reader. One pass per line: (1) copy the line without blanks and comments,
// lower-cased, remembering each character's source column; (2) read the words, evaluating
// parameters and [ ] expressions (parameter assignments are collected and applied after the line,
// as NGC says); (3) execute the line in NGC order (F, S, T, M6, spindle, coolant, dwell, modes, offsets,
// motion, stop) and emit at most one block. Comments and the words that do not move the tool are
// recorded as Commands (`before` = blocks emitted so far) in that order; G54…/G43 change the offset
// added to block coordinates.
#include "netshape/toolpath/gcode_reader.hpp"

#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gcode_reader_impl.hpp"

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

bool GcodeReader::Impl::next(Block& out) {
  const char* b = nullptr;
  const char* e = nullptr;
  while (!ended) {
    if (!fetch(b, e)) {
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
    if (norm[0] == 'o') {
      o_word();
      continue;
    }
    if (norm[0] == '/') throw ParseError(source, line_no, column_of(0), "block delete '/' is not supported");
    read_words();
    const bool produced = execute(out);
    apply_assignments();
    if (produced) return true;
  }
  return false;
}


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
