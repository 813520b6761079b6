#pragma once
/// \file smoother.hpp
/// Streaming tolerance-band smoothing: smooth() (smoothing.hpp) over a bounded window of the program,
/// with the Planner's push / next protocol, so a controller can put it between its interpreter and
/// the Planner.
///
///     netshape::motion::Smoother smoother(smooth_options);
///     netshape::motion::Planner planner(limits, plan_options);   // blend rule: tolerance blend_tolerance(),
///                                                                // corner_tolerance the whole tolerance
///     netshape::motion::SmoothedBlock sb;
///     netshape::motion::Sample sample;
///     for (;;) {
///       auto st = planner.next(sample);
///       if (st == Status::finished) break;
///       if (st == Status::ok) { drive(sample.position, sample.velocity); continue; }
///       // the planner needs a block: take one from the smoother, refill the smoother if it has none
///       auto ss = smoother.next(sb);
///       if (ss == Status::ok) planner.push(sb.block);
///       else if (ss == Status::finished) planner.finish();
///       else if (have_block) smoother.push(block); else smoother.finish();
///     }
///
/// How it cuts. The smoother holds at most `capacity()` = 2·window + 2 program blocks. It calls smooth()
/// on a chunk that ends at a *cut block* c: a block of non-zero length that is no micro-segment (a
/// rapid, an arc, or a line longer than max_segment). Nothing smooth() does reaches across such a
/// block, except on a line c: the run before c may borrow c's first part (a lead), and the vertex
/// before c may be rounded. So the chunk's output is handed out up to, not including, c's own block;
/// c stays in the buffer as programmed and heads the next chunk, whose output of c starts where the
/// chunk before ended.
/// A cut is accepted when c's start did not move, or when it moved by a lead (the block before c is a
/// micro-segment, c moved by exactly min(lead_length, length/2)).
///
/// When it cuts. Eagerly: next() tries a cut as soon as a cut block arrives with at least `min_chunk`
/// blocks before it (default 64), so output starts after the first stretch of micro-segments, not
/// after a full buffer, and a Smoother thread can feed a Planner thread while it reads on. Nothing in
/// a chunk depends on the blocks after its cut block, so the output does not depend on when it cuts.
/// A refused cut costs one more smooth() of the chunk; after four refusals the smoother waits for a
/// full buffer, where it tries the last four cut blocks it holds, newest first.
///
/// Equal to batch: the blocks handed out equal smooth(program) bit for bit (kinds, coordinates, source
/// indices) and so do the counters, as long as every cut is clean — i.e. every stretch of
/// micro-segments between two cut blocks fits in the buffer (at most 2·window blocks, which includes
/// every run smooth() fits in one piece). Otherwise (`forced_cuts()` > 0) the buffer is cut at its
/// sharpest vertex in the second half: the curve ends at that vertex there and a new one starts, like
/// the cut of a run longer than `window` in smooth(); the output still follows the program within
/// fit_tolerance() (checked by the fit), but it is no longer the batch output, and the corner at the
/// cut is left to the planner's blend.
///
/// Memory and errors: the buffer and a chunk copy (each `capacity()` blocks) are allocated in the
/// constructor; push() never allocates; next() calls smooth(), which allocates its result and work
/// arrays once per chunk. push(), finish(), next() never throw: a bad block is answered with
/// invalid_input (last_error() names the field and value), and an error inside smooth() (out of
/// memory) makes next() answer invalid_input too.
///
/// Units: mm, rad.

#include <cstddef>
#include <string>
#include <vector>

#include "netshape/motion/planner.hpp"
#include "netshape/motion/smoothing.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

/// One block of the smoothed program with the range of program blocks it replaces.
struct SmoothedBlock {
  toolpath::Block block;    ///< a cubic piece: its chord (kind line)
  CubicControls controls;   ///< the inner control points when the block is a cubic piece
  long source_first = -1;  ///< first program block (0-based index in push order)
  long source_last = -1;   ///< last program block (0-based index in push order)
};

/// Running counters of a Smoother (the SmoothResult counters summed over the chunks handed out).
struct SmoothCounts {
  long runs_smoothed = 0;         ///< runs replaced by arcs
  long runs_kept = 0;             ///< runs that failed the check and were left as programmed
  long corners_kept = 0;          ///< vertices between feed moves turning more than max_turn
  long corners_rounded = 0;       ///< vertices between two program lines replaced by an arc
  double max_fit_deviation = 0;   ///< largest checked bound over the smoothed runs [mm]
  long chunks = 0;                ///< smooth() calls whose output was handed out
  long forced_cuts = 0;           ///< chunks cut at a vertex (no clean cut block in a full buffer)
};

class Smoother {
 public:
  /// Validates the options and `min_chunk` (>= 1: the fewest blocks before a cut block that is tried
  /// before the buffer is full; 1 gives the least latency, larger values fewer smooth() calls; throws
  /// std::invalid_argument naming the field) and allocates the buffer.
  explicit Smoother(const SmoothOptions& options, int min_chunk = default_min_chunk);

  /// Default `min_chunk` [blocks].
  static constexpr int default_min_chunk = 64;

  /// Append a program block: ok, buffer_full (call next() first), or invalid_input (see
  /// last_error(); nothing was added).
  Status push(const toolpath::Block& block) noexcept;
  /// No more blocks will come; next() hands out the rest.
  void finish() noexcept;
  /// Next smoothed block: ok, need_blocks (push more or finish), finished, or invalid_input (an
  /// error inside smooth(), see last_error()).
  Status next(SmoothedBlock& out) noexcept;

  /// Back to the empty state (options and memory kept).
  void reset() noexcept;
  /// Blocks that can be pushed now.
  int free_blocks() const noexcept;
  /// Largest number of program blocks held: 2·window + 2.
  int capacity() const noexcept { return capacity_; }
  /// Number of program blocks accepted so far.
  long blocks_pushed() const noexcept { return pushed_; }
  /// Counters of the chunks smoothed so far.
  const SmoothCounts& counts() const noexcept { return counts_; }
  /// Message of the last invalid_input.
  const char* last_error() const noexcept { return error_.c_str(); }
  const SmoothOptions& options() const noexcept { return options_; }

 private:
  void smooth_chunk(bool finishing);              // smooths the next chunk into result_; may throw
  void smooth_front(std::size_t blocks);          // smooth buf_[0, blocks) into result_
  bool eager_cut();                               // try the cut blocks pushed since the last look
  bool try_cuts(std::size_t first, int& tries);   // try buf_[first..] newest first; true on a cut
  bool try_cut(std::size_t c);                    // smooth buf_[0..c]; true if c is a clean cut
  void forced_cut();                              // smooth up to the sharpest vertex of the buffer
  void take(std::size_t blocks, std::size_t out_blocks);  // hand out result_[0, out_blocks)

  SmoothOptions options_;
  int capacity_ = 0;
  int min_chunk_ = default_min_chunk;
  std::vector<toolpath::Block> buf_;    // program blocks [base_, base_ + size), as pushed
  std::vector<toolpath::Block> chunk_;  // the chunk passed to smooth()
  SmoothResult result_;                 // output of the chunk being handed out
  std::size_t out_pos_ = 0, out_end_ = 0;  // result_ blocks [out_pos_, out_end_) are still to hand out
  long base_ = 0;                       // program index of buf_[0]; of result_'s block 0 while handing out
  long out_base_ = 0;
  long pushed_ = 0;
  std::size_t scanned_ = 0;             // buf_[0, scanned_) were looked at for an eager cut
  int eager_tries_ = 0;                 // eager cuts tried (and refused) since the last chunk was taken
  bool front_moved_ = false;            // buf_[0]'s first part was handed out: its output starts at front_start_
  Vec3 front_start_ = Vec3::Zero();
  bool finished_ = false, done_ = false;
  SmoothCounts counts_;
  std::string error_;
};

}  // namespace netshape::motion
