// G-code writer: modal output, shortest exact numbers (std::to_chars), arcs as G2/G3 or chords.
#include "netshape/toolpath/gcode_writer.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::toolpath {

void WriterOptions::validate() const {
  NETSHAPE_CHECK(std::isfinite(chord_tolerance) && chord_tolerance > 0.0, "chord_tolerance", chord_tolerance,
                 "must be a positive number [mm]");
  NETSHAPE_CHECK(decimals >= -1 && decimals <= 12, "decimals", decimals, "must be -1 (shortest) or 0 … 12");
}

namespace {

// Every finite double fits this buffer in fixed notation: at most a sign, 309 integer digits, a point and
// 324 places (the shortest form of 5e-324), or 309 digits and 12 places with fixed decimals. A number that
// does not fit (or is not finite) throws instead of being copied past the buffer.
constexpr std::size_t number_chars = 400;

class NumberFormat {
 public:
  explicit NumberFormat(int decimals) : decimals_(decimals) {}
  void put(std::string& out, char letter, double v) const {
    if (!std::isfinite(v)) throw Error(std::string("write_gcode: ") + letter + " word is not a finite number");
    out += letter;
    char buf[number_chars];
    if (v == 0.0) v = 0.0;  // no "-0"
    if (decimals_ < 0) {
      auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
      if (r.ec != std::errc()) throw Error(std::string("write_gcode: ") + letter + " word does not fit");
      out.append(buf, r.ptr);
    } else {
      std::size_t n = printed(buf, std::snprintf(buf, sizeof buf, "%.*f", decimals_, v), letter);
      if (decimals_ > 0) {  // strip trailing zeros and a bare point
        while (n > 1 && buf[n - 1] == '0') --n;
        if (buf[n - 1] == '.') --n;
      }
      if (n == 2 && buf[0] == '-' && buf[1] == '0') {
        buf[0] = '0';
        n = 1;
      }
      out.append(buf, n);
    }
  }
  // Feed [units/min]: rounded to 1e-6 (shortest form would keep the binary noise of mm/s × 60, e.g.
  // 1000000.0000000001); fixed decimals when asked for fewer. `f` is in [0, max_feed_mm_per_min].
  void put_feed(std::string& out, double f) const {
    out += 'F';
    char buf[number_chars];
    const int d = decimals_ < 0 || decimals_ > 6 ? 6 : decimals_;
    std::size_t n = printed(buf, std::snprintf(buf, sizeof buf, "%.*f", d, f), 'F');
    if (d > 0) {
      while (n > 1 && buf[n - 1] == '0') --n;
      if (buf[n - 1] == '.') --n;
    }
    out.append(buf, n);
  }

 private:
  // The length snprintf reported, checked to lie inside the buffer it wrote.
  static std::size_t printed(const char*, int n, char letter) {
    if (n < 0 || static_cast<std::size_t>(n) >= number_chars)
      throw Error(std::string("write_gcode: ") + letter + " word does not fit the number buffer");
    return static_cast<std::size_t>(n);
  }
  int decimals_;
};

// Leading integer of `text` after `skip` characters ("S1600" → 1600), for the state the writer tracks.
double value_after(const std::string& text, std::size_t skip) {
  double v = 0.0;
  if (text.size() > skip) std::from_chars(text.data() + skip, text.data() + text.size(), v);
  return v;
}

}  // namespace

void write_gcode(const Toolpath& tp, std::ostream& os, const WriterOptions& opt) {
  opt.validate();
  const NumberFormat nf(opt.decimals);
  std::string line;
  line.reserve(160);
  if (!opt.header_comment.empty()) {
    std::string c = opt.header_comment;
    for (char& ch : c)
      if (ch == '(' || ch == ')' || ch == '\n' || ch == '\r' || static_cast<unsigned char>(ch) < 32) ch = ' ';
    os << '(' << c << ")\n";
  }
  os << "G21 G90 G17 G94 " << (opt.absolute_arc_centers ? "G90.1" : "G91.1") << '\n';
  if (opt.work_offset_word) {
    const bool selected_first = std::any_of(tp.commands.begin(), tp.commands.end(), [](const Command& c) {
      return c.kind == CommandKind::work_offset && c.before == 0;
    });
    if (!selected_first) os << "G54\n";
  }
  // Block coordinates are in the tool path's frame (program + work offset + tool length); `off` is the
  // offset the commands written so far put in force, subtracted from every written coordinate.
  int coord_system = 0;
  double tool_offset = 0.0;
  Vec3 off = tp.work_offsets.row(0).transpose();
  Vec3 pos = off;  // the reader's tool starts at program (0, 0, 0)
  int motion = -1;
  Plane plane = Plane::xy;
  double feed = 0.0;
  double speed = 0.0;  // S [rev/min]
  int spindle_dir = 0; // M3 +1, M4 −1, M5 0
  int selected = 0;
  int tool = 0;
  bool ended = false;  // an M2 / M30 command was written
  std::size_t ci = 0;  // next command
  const std::size_t nc = tp.commands.size();
  for (std::size_t i = 1; i < nc; ++i)
    NETSHAPE_CHECK(tp.commands[i].before >= tp.commands[i - 1].before, "commands.before", tp.commands[i].before,
                   "must be non-decreasing");
  // Write the commands placed before block `k` (k = blocks.size(): the rest) and track the state they set.
  auto commands_before = [&](std::size_t k) {
    for (; ci < nc && tp.commands[ci].before <= k; ++ci) {
      const Command& c = tp.commands[ci];
      for (char ch : c.text)
        NETSHAPE_CHECK(ch != '\n' && ch != '\r', "command.text", c.text, "must be one line");
      os << c.text << '\n';
      const std::string& t = c.text;
      switch (c.kind) {
        case CommandKind::work_offset:
          NETSHAPE_CHECK(c.value >= 0 && c.value <= 8 && c.value == std::floor(c.value), "command.value", c.value,
                         "work offset index must be 0 … 8 (G54 … G59.3)");
          coord_system = static_cast<int>(c.value);
          break;
        case CommandKind::tool_length:
          NETSHAPE_CHECK_FINITE("command.value", c.value);
          tool_offset = c.value;
          break;
        case CommandKind::program_end:
          ended = true;
          break;
        case CommandKind::word:
          if (t.size() > 1 && t[0] == 'S') speed = value_after(t, 1);
          else if (t.size() > 1 && t[0] == 'T') selected = static_cast<int>(value_after(t, 1));
          else if (t == "M6") tool = selected;
          else if (t == "M3") spindle_dir = 1;
          else if (t == "M4") spindle_dir = -1;
          else if (t == "M5") spindle_dir = 0;
          else if (t == "G80") motion = -1;
          break;
        default:
          break;
      }
      if (c.kind == CommandKind::work_offset || c.kind == CommandKind::tool_length) {
        off = tp.work_offsets.row(coord_system).transpose();
        off.z() += tool_offset;
      }
    }
  };
  const char axis[3] = {'X', 'Y', 'Z'};
  const char offs[3] = {'I', 'J', 'K'};
  std::vector<Block> pieces;

  auto emit = [&](const Block& b) {
    for (int i = 0; i < 3; ++i) {
      NETSHAPE_CHECK_FINITE("block.start", b.start[i]);
      NETSHAPE_CHECK_FINITE("block.end", b.end[i]);
    }
    NETSHAPE_CHECK(std::isfinite(b.feed) && b.feed >= 0.0, "block.feed", b.feed, "must be a non-negative number [mm/s]");
    NETSHAPE_CHECK(b.feed <= max_feed_mm_per_min / 60.0, "block.feed", b.feed,
                   "must not exceed max_feed_mm_per_min / 60 = 1666666.67 mm/s (F 1e8 mm/min) [mm/s]");
    // tool and spindle the commands did not set (tool paths built in code, or changed by a transform)
    if (b.tool != tool) {
      NETSHAPE_CHECK(b.tool >= 0, "block.tool", b.tool, "must not be negative");
      os << 'T' << b.tool << " M6\n";
      tool = selected = b.tool;
    }
    if (b.spindle_rpm != spindle_dir * speed) {
      NETSHAPE_CHECK(std::isfinite(b.spindle_rpm), "block.spindle_rpm", b.spindle_rpm, "must be finite [rev/min]");
      line.clear();
      if (b.spindle_rpm == 0.0) {
        line = "M5";
        spindle_dir = 0;
      } else {
        nf.put(line, 'S', std::abs(b.spindle_rpm));
        line += b.spindle_rpm > 0.0 ? " M3" : " M4";
        speed = std::abs(b.spindle_rpm);
        spindle_dir = b.spindle_rpm > 0.0 ? 1 : -1;
      }
      os << line << '\n';
    }
    if (b.start != pos) {  // discontinuity: move there at rapid
      line = motion == 0 ? "" : "G0 ";
      for (int a = 0; a < 3; ++a) {
        nf.put(line, axis[a], b.start[a] - off[a]);
        if (a < 2) line += ' ';
      }
      os << line << '\n';
      motion = 0;
      pos = b.start;
    }
    line.clear();
    const int code = b.kind == MotionKind::rapid ? 0 : b.kind == MotionKind::line ? 1 : (b.clockwise ? 2 : 3);
    if (b.kind == MotionKind::arc && b.plane != plane) {
      line += b.plane == Plane::xy ? "G17 " : b.plane == Plane::zx ? "G18 " : "G19 ";
      plane = b.plane;
    }
    if (code != motion) {
      line += 'G';
      line += static_cast<char>('0' + code);
      line += ' ';
      motion = code;
    }
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      if (b.end[a] != pos[a]) {
        nf.put(line, axis[a], b.end[a] - off[a]);
        line += ' ';
        any = true;
      }
    }
    if (!any) {  // zero-length move or full circle: still a block
      const int a = b.kind == MotionKind::arc ? plane_axes(b.plane).a : 0;
      nf.put(line, axis[a], b.end[a] - off[a]);
      line += ' ';
    }
    if (b.kind == MotionKind::arc) {
      const PlaneAxes ax = plane_axes(b.plane);
      for (int k : {ax.a, ax.b}) {
        NETSHAPE_CHECK_FINITE("block.center", b.center[k]);
        nf.put(line, offs[k], opt.absolute_arc_centers ? b.center[k] - off[k] : b.center[k] - b.start[k]);
        line += ' ';
      }
      if (b.turns != 1) {
        NETSHAPE_CHECK(b.turns >= 1, "block.turns", b.turns, "must be at least 1");
        line += 'P';
        line += std::to_string(b.turns);
        line += ' ';
      }
    }
    if (b.feed != feed) {
      nf.put_feed(line, b.feed * 60.0);
      line += ' ';
      feed = b.feed;
    }
    line.pop_back();
    os << line << '\n';
    pos = b.end;
  };

  for (std::size_t k = 0; k < tp.blocks.size(); ++k) {
    commands_before(k);
    NETSHAPE_CHECK(!ended, "commands", k, "a block follows the program end (M2/M30) command");
    const Block& b = tp.blocks[k];
    if (opt.split_arcs && b.kind == MotionKind::arc) {
      pieces.clear();
      split_block(b, opt.chord_tolerance, pieces);
      for (const Block& p : pieces) emit(p);
    } else {
      emit(b);
    }
  }
  commands_before(tp.blocks.size());
  if (!ended) os << "M2\n";
  if (!os) throw Error("write_gcode: the output stream failed");
}

std::string format_gcode(const Toolpath& tp, const WriterOptions& opt) {
  std::ostringstream os;
  write_gcode(tp, os, opt);
  return os.str();
}

}  // namespace netshape::toolpath
