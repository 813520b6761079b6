#pragma once
/// \file planner.hpp
/// Streaming look-ahead planner and 2-step interpolator for controllers (Lee & Lee §2–3).
///
/// Push blocks, pull samples. All memory (the ring buffer of segments) is allocated in the
/// constructor; push(), next() and next_segment() never allocate and never throw: they return a
/// Status (like ruckig's non-throwing update with throw_error = false).
///
///     netshape::motion::Planner planner(limits, options);
///     netshape::motion::Sample sample;
///     for (;;) {
///       auto st = planner.next(sample);               // one fine period (ts2)
///       if (st == Status::need_blocks) {              // look-ahead buffer wants more
///         if (have_block) planner.push(block); else planner.finish();
///       } else if (st == Status::finished) break;
///       else drive(sample.position, sample.velocity);
///     }
///
/// Look-ahead (Lee & Lee §3.2): each new segment gets the largest entry speed it can stop from
/// (eq. 3 with the end speed 0), the corner speed of the junction (eq. 4 or another rule) and the
/// previous block's reachable end speed (eq. 5); the smallest wins, and the backward pass carries the
/// change back through the buffer until nothing changes. A segment's profile is frozen when the
/// rough loop (period ts1) reaches it; the fine loop (period ts2) evaluates the frozen profiles on
/// the path geometry, so every sample lies on the (blended) path.

#include <cstdint>
#include <memory>

#include "netshape/motion/cubic.hpp"
#include "netshape/motion/limits.hpp"
#include "netshape/motion/options.hpp"
#include "netshape/motion/profile.hpp"
#include "netshape/motion/segment.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

/// Result of a non-throwing planner call.
enum class Status : std::int8_t {
  ok = 0,            ///< done; for next(): `sample` holds the next fine sample
  buffer_full = 1,   ///< push(): no room; pull samples first
  need_blocks = 2,   ///< next(): the look-ahead buffer must be refilled (push or finish)
  finished = 3,      ///< next(): the program has ended (the last sample was the end point)
  invalid_input = -1 ///< push(): the block is not valid (see last_error()); nothing was added
};

/// One fine-loop sample.
struct Sample {
  double t = 0;                     ///< time since start [s]
  Vec3 position = Vec3::Zero();     ///< [mm]
  Vec3 velocity = Vec3::Zero();     ///< per-axis velocity [mm/s]
  double feed = 0;                  ///< path speed [mm/s]
  double path_acceleration = 0;     ///< tangential acceleration [mm/s^2]
  long block = -1;                  ///< index of the program block being run (blend: the one before)
};

/// A frozen segment with its speed profile (for controllers that interpolate themselves).
struct PlannedSegment {
  Segment segment;
  Profile profile;
  double t0 = 0;  ///< start time [s]
};

namespace detail {
class PlannerState;
}  // namespace detail

class Planner {
 public:
  /// Validates limits and options (throws std::invalid_argument) and allocates the ring buffer.
  Planner(const AxisLimits& limits, const PlanOptions& options);
  /// A copy is an independent planner in the same state (it allocates its own buffers).
  Planner(const Planner& other);
  Planner& operator=(const Planner& other);
  /// Moving hands the state over without allocating; a moved-from planner may only be assigned to
  /// or destroyed.
  Planner(Planner&& other) noexcept;
  Planner& operator=(Planner&& other) noexcept;
  ~Planner();

  /// Append a block (rapids run at the axis limits; zero-length blocks are skipped).
  Status push(const toolpath::Block& block) noexcept;
  /// Append a block with its cubic controls (cubic.hpp). controls.cubic false: push(block). Else a
  /// cubic Bézier block: `block` is its chord (kind line, start = P0, end = P3, its feed), P1 and P2
  /// are controls.c1 and c2. It is planned on the curve (pieces at its arc-length table nodes, per-axis
  /// bounds on each); samples follow it and Sample::block is its index. Junctions are as for any
  /// block: at a tangent joint no corner (jerk mode: no speed cap where the curvature vectors agree,
  /// as between the pieces of one C² spline), else the rule's corner (the blend rule blends it).
  Status push(const toolpath::Block& block, const CubicControls& controls) noexcept;
  /// No more blocks will come: the last block stops at its end.
  void finish() noexcept;
  /// Next fine sample (period ts2).
  Status next(Sample& out) noexcept;
  /// Alternative to next(): freeze and hand out the next segment with its profile.
  Status next_segment(PlannedSegment& out) noexcept;

  /// Back to the empty state (limits, options and memory kept).
  void reset() noexcept;
  /// Free slots in the ring buffer, counted in blocks that can still be pushed now.
  int free_blocks() const noexcept;
  /// Program end time once known (after finish() and the last segment is frozen), else −1 [s].
  double end_time() const noexcept;
  /// End time of the segments planned for good so far (their samples are due up to it) [s]. Grows as
  /// next() freezes segments; lets a caller refuse a plan whose time already exceeds a budget.
  double frozen_time() const noexcept;
  /// Number of blocks accepted so far.
  long blocks_pushed() const noexcept;
  /// Message of the last invalid_input.
  const char* last_error() const noexcept;
  const AxisLimits& limits() const noexcept;
  const PlanOptions& options() const noexcept;

 private:
  std::unique_ptr<detail::PlannerState> state_;  // the ring, the pass records and the blend stores
};

}  // namespace netshape::motion
