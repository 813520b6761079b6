// G-code writer: modal output, shortest exact numbers (std::to_chars), arcs as G2/G3 or chords.
#include "netshape/toolpath/gcode_writer.hpp"

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

class NumberFormat {
 public:
  explicit NumberFormat(int decimals) : decimals_(decimals) {}
  void put(std::string& out, char letter, double v) const {
    out += letter;
    char buf[64];
    if (v == 0.0) v = 0.0;  // no "-0"
    if (decimals_ < 0) {
      auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed);
      out.append(buf, r.ptr);
    } else {
      int n = std::snprintf(buf, sizeof buf, "%.*f", decimals_, v);
      if (decimals_ > 0) {  // strip trailing zeros and a bare point
        while (n > 1 && buf[n - 1] == '0') --n;
        if (buf[n - 1] == '.') --n;
      }
      if (n == 2 && buf[0] == '-' && buf[1] == '0') {
        buf[0] = '0';
        n = 1;
      }
      out.append(buf, static_cast<std::size_t>(n));
    }
  }

 private:
  int decimals_;
};

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
  Vec3 pos = Vec3::Zero();
  int motion = -1;
  Plane plane = Plane::xy;
  double feed = 0.0;
  double rpm = 0.0;
  int tool = 0;
  const char axis[3] = {'X', 'Y', 'Z'};
  const char offs[3] = {'I', 'J', 'K'};
  std::vector<Block> pieces;

  auto emit = [&](const Block& b) {
    for (int i = 0; i < 3; ++i) {
      NETSHAPE_CHECK_FINITE("block.start", b.start[i]);
      NETSHAPE_CHECK_FINITE("block.end", b.end[i]);
    }
    NETSHAPE_CHECK(std::isfinite(b.feed) && b.feed >= 0.0, "block.feed", b.feed, "must be a non-negative number [mm/s]");
    if (b.tool != tool) {
      NETSHAPE_CHECK(b.tool >= 0, "block.tool", b.tool, "must not be negative");
      os << 'T' << b.tool << " M6\n";
      tool = b.tool;
    }
    if (b.spindle_rpm != rpm) {
      NETSHAPE_CHECK(std::isfinite(b.spindle_rpm), "block.spindle_rpm", b.spindle_rpm, "must be finite [rev/min]");
      line.clear();
      if (b.spindle_rpm == 0.0) {
        line = "M5";
      } else {
        nf.put(line, 'S', std::abs(b.spindle_rpm));
        line += b.spindle_rpm > 0.0 ? " M3" : " M4";
      }
      os << line << '\n';
      rpm = b.spindle_rpm;
    }
    if (b.start != pos) {  // discontinuity: move there at rapid
      line = motion == 0 ? "" : "G0 ";
      for (int a = 0; a < 3; ++a) {
        nf.put(line, axis[a], b.start[a]);
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
        nf.put(line, axis[a], b.end[a]);
        line += ' ';
        any = true;
      }
    }
    if (!any) {  // zero-length move or full circle: still a block
      const int a = b.kind == MotionKind::arc ? plane_axes(b.plane).a : 0;
      nf.put(line, axis[a], b.end[a]);
      line += ' ';
    }
    if (b.kind == MotionKind::arc) {
      const PlaneAxes ax = plane_axes(b.plane);
      for (int k : {ax.a, ax.b}) {
        NETSHAPE_CHECK_FINITE("block.center", b.center[k]);
        nf.put(line, offs[k], opt.absolute_arc_centers ? b.center[k] : b.center[k] - b.start[k]);
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
      nf.put(line, 'F', b.feed * 60.0);
      line += ' ';
      feed = b.feed;
    }
    line.pop_back();
    os << line << '\n';
    pos = b.end;
  };

  for (const Block& b : tp.blocks) {
    if (opt.split_arcs && b.kind == MotionKind::arc) {
      pieces.clear();
      split_block(b, opt.chord_tolerance, pieces);
      for (const Block& p : pieces) emit(p);
    } else {
      emit(b);
    }
  }
  os << "M2\n";
  if (!os) throw Error("write_gcode: the output stream failed");
}

std::string format_gcode(const Toolpath& tp, const WriterOptions& opt) {
  std::ostringstream os;
  write_gcode(tp, os, opt);
  return os.str();
}

}  // namespace netshape::toolpath
