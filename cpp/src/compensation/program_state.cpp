// State of a program on a machine with backlash or thermal drift: block times, approach directions,
// the tip's state offset per block, arcs as chords where an axis may reverse inside them.
#include "program_state.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/machine/state_error.hpp"

namespace netshape::compensation {

std::vector<double> block_end_times(const toolpath::Toolpath& program, double rapid_feed) {
  NETSHAPE_CHECK(std::isfinite(rapid_feed) && rapid_feed > 0.0, "rapid_feed", rapid_feed,
                 "must be a positive number [mm/s]");
  std::vector<double> t(program.blocks.size());
  double now = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const toolpath::Block& b = program.blocks[i];
    const bool feed = b.kind != toolpath::MotionKind::rapid && std::isfinite(b.feed) && b.feed > 0.0;
    now += b.length() / (feed ? b.feed : rapid_feed);
    t[i] = now;
  }
  return t;
}

namespace detail {

namespace {
double fraction(int i, int m) { return i == m ? 1.0 : static_cast<double>(i) * (1.0 / m); }
}  // namespace

StatefulProgram stateful_program(const machine::Machine& machine, const toolpath::Toolpath& program,
                                 const ProgramOptions& options) {
  const auto& src = program.blocks;
  std::vector<double> te = options.block_times.empty() ? block_end_times(program, options.rapid_feed)
                                                       : options.block_times;
  NETSHAPE_CHECK(te.size() == src.size(), "block_times size", te.size(), "must equal the number of blocks");
  for (std::size_t i = 0; i < te.size(); ++i) {
    NETSHAPE_CHECK(std::isfinite(te[i]) && te[i] >= 0.0, "block_times", te[i], "must be finite and ≥ 0 [s]");
    NETSHAPE_CHECK(i == 0 || te[i] >= te[i - 1], "block_times", te[i], "must not decrease");
  }
  bool backlash = false;
  for (const machine::Axis& a : machine.axes) backlash = backlash || a.backlash != 0.0;
  StatefulProgram out;
  std::vector<double> t0, t1;  // times at each output block's start and end [s]
  for (std::size_t i = 0; i < src.size(); ++i) {
    const toolpath::Block& b = src[i];
    const double ts = i == 0 ? 0.0 : te[i - 1];
    if (backlash && b.kind == toolpath::MotionKind::arc) {
      const int k = std::max(2, toolpath::chord_count(b.radius(), b.sweep(), 0.5 * options.chord_tolerance));
      Vec3 prev = b.start;
      for (int j = 1; j <= k; ++j) {
        toolpath::Block c = b;
        c.kind = toolpath::MotionKind::line;
        c.start = prev;
        c.end = j == k ? b.end : b.point_at(fraction(j, k));
        prev = c.end;
        out.blocks.push_back(c);
        out.source.push_back(static_cast<long>(i));
        t0.push_back(ts + fraction(j - 1, k) * (te[i] - ts));
        t1.push_back(j == k ? te[i] : ts + fraction(j, k) * (te[i] - ts));
      }
    } else {
      out.blocks.push_back(b);
      out.source.push_back(static_cast<long>(i));
      t0.push_back(ts);
      t1.push_back(te[i]);
    }
  }
  const std::size_t n = out.blocks.size();
  out.off_start.resize(n);
  out.off_end.resize(n);
  out.reversal.assign(n, 0);
  Vec3 d = options.initial_direction;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 step = out.blocks[i].end - out.blocks[i].start;
    for (int k = 0; k < 3; ++k)
      if (std::abs(step[k]) > 1e-9) d[k] = step[k] > 0 ? 1.0 : -1.0;
    out.off_start[i] = machine::state_error(machine, d, t0[i]);
    out.off_end[i] = machine::state_error(machine, d, t1[i]);
    out.reversal[i] = i > 0 && out.blocks[i].kind != toolpath::MotionKind::rapid &&
                      out.off_start[i] != out.off_end[i - 1] && out.blocks[i].start == out.blocks[i - 1].end;
  }
  return out;
}

}  // namespace detail
}  // namespace netshape::compensation
