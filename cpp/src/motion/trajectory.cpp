#include "netshape/motion/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "netshape/motion/planner.hpp"
#include "netshape/motion/segment.hpp"

namespace netshape::motion {

namespace {
// Distance from p to a programmed block [mm] (arcs: through the angle of p about the centre).
double distance_to_block(const Vec3& p, const toolpath::Block& b) {
  if (b.kind != toolpath::MotionKind::arc) return point_segment_distance(p, b.start, b.end);
  const auto ax = toolpath::plane_axes(b.plane);
  const double sweep = b.sweep();
  const double a0 = std::atan2(b.start[ax.b] - b.center[ax.b], b.start[ax.a] - b.center[ax.a]);
  const double ap = std::atan2(p[ax.b] - b.center[ax.b], p[ax.a] - b.center[ax.a]);
  double d = ap - a0;
  // unwrap into the sweep direction; try the turns of a multi-turn arc
  double best = std::min((p - b.start).norm(), (p - b.end).norm());
  const double two_pi = 2.0 * pi;
  if (sweep > 0) {
    while (d < 0) d += two_pi;
  } else {
    while (d > 0) d -= two_pi;
  }
  const double len = b.length();
  for (int k = -1; k <= b.turns; ++k) {
    const double ang = d + (sweep > 0 ? 1 : -1) * two_pi * k;
    const double f0 = std::clamp(ang / sweep, 0.0, 1.0);
    if (std::abs(ang / sweep - f0) * len > best + 1e-9 && k != 0) continue;
    // the planar angle is exact for planar arcs; refine along the arc for helices (golden section)
    const double w = std::min(0.5, (best + 1e-6) / std::max(len, 1e-12));
    double lo = std::max(0.0, f0 - w), hi = std::min(1.0, f0 + w);
    const double g = 0.6180339887498949;
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double d1 = (p - b.point_at(x1)).norm(), d2 = (p - b.point_at(x2)).norm();
    for (int it = 0; it < 40; ++it) {
      if (d1 < d2) {
        hi = x2; x2 = x1; d2 = d1; x1 = hi - g * (hi - lo); d1 = (p - b.point_at(x1)).norm();
      } else {
        lo = x1; x1 = x2; d1 = d2; x2 = lo + g * (hi - lo); d2 = (p - b.point_at(x2)).norm();
      }
    }
    best = std::min({best, d1, d2, (p - b.point_at(f0)).norm()});
  }
  return best;
}
}  // namespace

void measure_samples(const Points3& x, double ts, TrajectoryStats& st) {
  const Eigen::Index n = x.rows();
  st.axis_velocity.setZero();
  st.axis_acceleration.setZero();
  st.axis_jerk.setZero();
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const Vec3 v = (x.row(k + 1) - x.row(k)).transpose() / ts;
    st.axis_velocity = st.axis_velocity.cwiseMax(v.cwiseAbs());
    if (k + 2 < n) {
      const Vec3 a = (x.row(k + 2) - 2.0 * x.row(k + 1) + x.row(k)).transpose() / (ts * ts);
      st.axis_acceleration = st.axis_acceleration.cwiseMax(a.cwiseAbs());
    }
    if (k + 3 < n) {
      const Vec3 j = (x.row(k + 3) - 3.0 * x.row(k + 2) + 3.0 * x.row(k + 1) - x.row(k)).transpose() / (ts * ts * ts);
      st.axis_jerk = st.axis_jerk.cwiseMax(j.cwiseAbs());
    }
  }
  st.max_axis_velocity = st.axis_velocity.maxCoeff();
  st.max_axis_acceleration = st.axis_acceleration.maxCoeff();
  st.max_axis_jerk = st.axis_jerk.maxCoeff();
}

Trajectory plan(const std::vector<toolpath::Block>& blocks, const AxisLimits& limits, const PlanOptions& options,
                bool with_deviation, long max_samples) {
  return plan(blocks, {}, limits, options, with_deviation, max_samples);
}

Trajectory plan(const std::vector<toolpath::Block>& blocks, const std::vector<CubicControls>& controls,
                const AxisLimits& limits, const PlanOptions& options, bool with_deviation, long max_samples) {
  NETSHAPE_CHECK(max_samples >= 0, "max_samples", max_samples, "must be >= 0 (0: no limit)");
  NETSHAPE_CHECK(controls.empty() || controls.size() == blocks.size(), "controls", controls.size(),
                 "must be empty or hold one entry per block");
  options.validate();
  static const CubicControls none;
  const auto controls_of = [&](std::size_t i) -> const CubicControls& { return controls.empty() ? none : controls[i]; };
  // cubic blocks as curves (the deviation is measured against them), by block index
  std::vector<Segment> curves(controls.empty() ? 0 : blocks.size());
  // validate first so that the error names the block
  std::vector<long> index;  // input index of every block the planner accepts (zero-length skipped)
  index.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    try {
      blocks[i].validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("blocks[" + std::to_string(i) + "]: " + e.what());
    }
    const CubicControls& c = controls_of(i);
    if (c.cubic) {
      const toolpath::Block& b = blocks[i];
      if (b.kind != toolpath::MotionKind::line)
        throw std::invalid_argument("blocks[" + std::to_string(i) + "]: kind = " +
                                    std::to_string(static_cast<int>(b.kind)) +
                                    ": a cubic block must be of kind line (its chord)");
      for (const Vec3* q : {&c.c1, &c.c2})
        if (!q->allFinite())
          throw std::invalid_argument("controls[" + std::to_string(i) + "]: " + (q == &c.c1 ? "c1" : "c2") +
                                      " must have finite coordinates");
      curves[i] = Segment::blend(b.start, c.c1, c.c2, b.end, static_cast<long>(i));
    }
    const double len = c.cubic ? curves[i].full_length : blocks[i].length();
    if (len > 1e-9) index.push_back(static_cast<long>(i));
  }
  // distance from p to program block b [mm]
  const auto distance_to = [&](const Vec3& p, std::size_t b) {
    return controls_of(b).cubic ? curves[b].distance_to_piece(p, 0.0, curves[b].full_length)
                                : distance_to_block(p, blocks[b]);
  };
  NETSHAPE_CHECK(!index.empty(), "blocks", blocks.size(), "must contain at least one block that moves");
  // A look-ahead deeper than the program holds the whole program either way; its ring is sized by the
  // depth (tens of kB per block), so plan with the depth the program can use: the same trajectory.
  PlanOptions used = options;
  used.lookahead = std::min(options.lookahead, std::max(2, static_cast<int>(std::min<std::size_t>(index.size(), 1000000)) + 2));
  Planner planner(limits, used);

  std::vector<double> t, feed;
  std::vector<Vec3> pos, vel;
  std::vector<int> blk;
  std::size_t next_block = 0;
  Sample s;
  core::Progress progress("plan", index.size());
  for (;;) {
    const Status st = planner.next(s);
    if (st == Status::ok) {
      progress.tick(next_block);
      // refused as soon as the planned time implies too many samples, before they are made
      const double planned = std::max(s.t, planner.frozen_time());
      if (max_samples > 0 && (static_cast<long>(t.size()) >= max_samples ||
                              planned / options.ts2 > static_cast<double>(max_samples)))
      {
        char buf[160];
        std::snprintf(buf, sizeof buf, "(%.6g s of motion planned, one sample every %.3g s)", planned, options.ts2);
        throw std::invalid_argument("max_samples = " + std::to_string(max_samples) +
                                    ": the plan needs more fine samples " + buf +
                                    "; raise the limit or the fine period ts2");
      }
      t.push_back(s.t);
      pos.push_back(s.position);
      vel.push_back(s.velocity);
      feed.push_back(s.feed);
      blk.push_back(s.block >= 0 ? static_cast<int>(index[static_cast<std::size_t>(s.block)]) : -1);
      continue;
    }
    if (st == Status::finished) break;
    if (st != Status::need_blocks) throw Error(std::string("motion planner: ") + planner.last_error());
    if (next_block >= index.size()) {
      planner.finish();
      continue;
    }
    bool pushed = false;
    while (next_block < index.size()) {
      const auto bi = static_cast<std::size_t>(index[next_block]);
      const Status ps = planner.push(blocks[bi], controls_of(bi));
      if (ps == Status::buffer_full) break;
      if (ps == Status::invalid_input)
        throw std::invalid_argument("blocks[" + std::to_string(index[next_block]) + "]: " + planner.last_error());
      ++next_block;
      pushed = true;
    }
    if (next_block >= index.size()) planner.finish();
    else if (!pushed) throw Error("motion planner stalled: the look-ahead buffer is too small for this program");
  }

  Trajectory tr;
  const Eigen::Index n = static_cast<Eigen::Index>(t.size());
  tr.t.resize(n);
  tr.feed.resize(n);
  tr.position.resize(n, 3);
  tr.velocity.resize(n, 3);
  tr.block.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    tr.t[k] = t[static_cast<std::size_t>(k)];
    tr.feed[k] = feed[static_cast<std::size_t>(k)];
    tr.position.row(k) = pos[static_cast<std::size_t>(k)].transpose();
    tr.velocity.row(k) = vel[static_cast<std::size_t>(k)].transpose();
    tr.block[k] = blk[static_cast<std::size_t>(k)];
  }
  TrajectoryStats& st = tr.stats;
  st.blocks = static_cast<long>(index.size());
  st.samples = static_cast<long>(n);
  st.cycle_time = planner.end_time();
  measure_samples(tr.position, options.ts2, st);
  const Vec3 end = blocks[static_cast<std::size_t>(index.back())].end;
  st.end_error = n > 0 ? (tr.position.row(n - 1).transpose() - end).norm() : 0.0;
  if (with_deviation) {
    double dev = 0;
    for (Eigen::Index k = 0; k < n; ++k) {
      const int b = tr.block[k];
      if (b < 0) continue;
      const Vec3 p = tr.position.row(k).transpose();
      double d = distance_to(p, static_cast<std::size_t>(b));
      // a blend sample belongs to the corner between this block and the next moving one
      if (d > 1e-9) {
        const auto it = std::upper_bound(index.begin(), index.end(), static_cast<long>(b));
        if (it != index.end()) d = std::min(d, distance_to(p, static_cast<std::size_t>(*it)));
      }
      dev = std::max(dev, d);
    }
    st.max_path_deviation = dev;
  }
  return tr;
}

}  // namespace netshape::motion
