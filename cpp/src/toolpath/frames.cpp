// A program's frames (program ↔ machine coordinates by the offset in force at each block) and its sampler.
#include "netshape/toolpath/frames.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::toolpath {

namespace {

// Per block: work offset index and tool length in force, read from the commands as the writer does.
template <class F>
void for_each_block_state(const Toolpath& tp, F&& f) {
  int coord_system = 0;
  double tool_length = 0.0;
  std::size_t ci = 0;
  for (std::size_t k = 0; k < tp.blocks.size(); ++k) {
    for (; ci < tp.commands.size() && tp.commands[ci].before <= k; ++ci) {
      const Command& c = tp.commands[ci];
      if (c.kind == CommandKind::work_offset) {
        NETSHAPE_CHECK(c.value >= 0 && c.value <= 8 && c.value == std::floor(c.value), "command.value",
                       c.value, "work offset index must be 0 … 8 (G54 … G59.3)");
        coord_system = static_cast<int>(c.value);
      } else if (c.kind == CommandKind::tool_length) {
        NETSHAPE_CHECK_FINITE("command.value", c.value);
        tool_length = c.value;
      }
    }
    f(k, coord_system, tool_length);
  }
}

// The blocks of `tp` moved by `sign`·(offset in force) with the offsets `rows`; zero offsets keep the block.
Toolpath shifted(const Toolpath& tp, const WorkOffsets& rows, double sign) {
  Toolpath out = tp;
  for_each_block_state(tp, [&](std::size_t k, int cs, double tool_length) {
    Vec3 d = rows.row(cs).transpose();
    d.z() += tool_length;
    if (d.isZero(0.0)) return;
    Block& b = out.blocks[k];
    if (sign > 0.0) {
      b.start += d;
      b.end += d;
      b.center += d;
    } else {
      b.start -= d;
      b.end -= d;
      b.center -= d;
    }
  });
  return out;
}

}  // namespace

std::vector<int> work_offset_index(const Toolpath& tp) {
  std::vector<int> idx(tp.blocks.size(), 0);
  for_each_block_state(tp, [&](std::size_t k, int cs, double) { idx[k] = cs; });
  return idx;
}

Points3 block_offsets(const Toolpath& tp) {
  Points3 out(static_cast<Eigen::Index>(tp.blocks.size()), 3);
  for_each_block_state(tp, [&](std::size_t k, int cs, double tool_length) {
    Vec3 d = tp.work_offsets.row(cs).transpose();
    d.z() += tool_length;
    out.row(static_cast<Eigen::Index>(k)) = d.transpose();
  });
  return out;
}

Toolpath to_machine(const Toolpath& tp, const WorkOffsets& offsets) {
  NETSHAPE_CHECK(tp.work_offsets.isZero(0.0), "work_offsets", tp.work_offsets.norm(),
                 "must be zero: the tool path is already in machine coordinates");
  NETSHAPE_CHECK(offsets.allFinite(), "offsets", offsets.norm(), "must be finite [mm]");
  Toolpath out = shifted(tp, offsets, 1.0);
  out.work_offsets = offsets;
  return out;
}

Toolpath to_program(const Toolpath& tp) {
  Toolpath out = shifted(tp, tp.work_offsets, -1.0);
  out.work_offsets = WorkOffsets::Zero();
  return out;
}

Samples sample(const Toolpath& tp, double spacing, bool feeds_only, double chord_tolerance) {
  NETSHAPE_CHECK(std::isfinite(spacing) && spacing > 0.0, "spacing", spacing,
                 "must be a positive number [mm]");
  NETSHAPE_CHECK(std::isfinite(chord_tolerance) && chord_tolerance > 0.0, "chord_tolerance", chord_tolerance,
                 "must be a positive number [mm]");
  std::vector<Block> moves;
  for (const Block& b : tp.blocks)
    if (!feeds_only || b.kind != MotionKind::rapid) split_block(b, chord_tolerance, moves);
  if (moves.empty()) return {Points3(0, 3), Eigen::VectorXd(0)};
  // lengths and point counts first; points a + (k/n)·(b − a), s = s0 + (k/n)·L, in this order of operations
  std::vector<double> length(moves.size());
  std::vector<long> count(moves.size());
  long total = 1;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Vec3 d = moves[i].end - moves[i].start;
    length[i] = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    count[i] = std::max(1L, static_cast<long>(std::ceil(length[i] / spacing)));
    total += count[i];
  }
  Samples out{Points3(total, 3), Eigen::VectorXd(total)};
  double s0 = 0.0;
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Vec3& a = moves[i].start;
    const Vec3 ab = moves[i].end - a;
    for (long k = 0; k < count[i]; ++k, ++row) {
      const double t = static_cast<double>(k) / static_cast<double>(count[i]);
      for (int j = 0; j < 3; ++j) out.points(row, j) = a[j] + t * ab[j];
      out.s[row] = s0 + t * length[i];
    }
    if (i + 1 < moves.size()) s0 += length[i];
  }
  out.points.row(row) = moves.back().end.transpose();
  out.s[row] = s0 + length.back();
  return out;
}

}  // namespace netshape::toolpath
