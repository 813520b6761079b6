// The streaming smoother (netshape/motion/smoother.hpp): a bounded buffer of program blocks, cut into
// chunks at blocks that no smoothing action reaches across, each chunk smoothed by smooth().
#include "netshape/motion/smoother.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/motion/corner.hpp"

namespace netshape::motion {

namespace {
constexpr int max_window = 1 << 24;  // keeps 2·window + 2 inside int
constexpr int cut_attempts = 4;      // smooth() calls spent looking for a clean cut before a forced one

bool micro_line(const toolpath::Block& b, const SmoothOptions& o) noexcept {
  const double l = b.length();
  return b.kind == toolpath::MotionKind::line && l > 1e-9 && l <= o.max_segment;
}
}  // namespace

Smoother::Smoother(const SmoothOptions& options, int min_chunk) : options_(options) {
  options_.validate();
  NETSHAPE_CHECK(options_.window <= max_window, "window", options_.window,
                 "must be <= 16777216 [blocks] for the streaming smoother");
  NETSHAPE_CHECK(min_chunk >= 1, "min_chunk", min_chunk, "must be >= 1 [blocks]");
  capacity_ = 2 * options_.window + 2;
  min_chunk_ = std::min(min_chunk, capacity_ - 1);
  buf_.reserve(static_cast<std::size_t>(capacity_));
  chunk_.reserve(static_cast<std::size_t>(capacity_));
  error_.reserve(256);
}

Status Smoother::push(const toolpath::Block& block) noexcept {
  try {
    if (finished_) {
      error_ = "push after finish(): call reset() to start a new program";
      return Status::invalid_input;
    }
    if (buf_.size() >= static_cast<std::size_t>(capacity_)) return Status::buffer_full;
    block.validate();
    buf_.push_back(block);  // within the capacity reserved in the constructor: no allocation
    ++pushed_;
    return Status::ok;
  } catch (const std::exception& e) {
    try {
      error_ = "block " + std::to_string(pushed_) + ": " + e.what();
    } catch (...) {
      error_.clear();
    }
    return Status::invalid_input;
  }
}

void Smoother::finish() noexcept { finished_ = true; }

Status Smoother::next(SmoothedBlock& out) noexcept {
  try {
    while (out_pos_ == out_end_) {  // each pass hands out a chunk or consumes blocks, so it ends
      if (done_) return Status::finished;
      if (!finished_ && buf_.size() < static_cast<std::size_t>(capacity_)) {
        if (!eager_cut()) return Status::need_blocks;
        continue;
      }
      smooth_chunk(finished_);
    }
    const std::size_t k = out_pos_++;
    out.block = result_.blocks[k];
    out.controls = result_.controls[k];
    out.source_first = result_.source_first[k] + out_base_;
    out.source_last = result_.source_last[k] + out_base_;
    return Status::ok;
  } catch (const std::exception& e) {
    try {
      error_ = std::string("smoothing failed: ") + e.what();
    } catch (...) {
      error_.clear();
    }
    return Status::invalid_input;
  }
}

void Smoother::reset() noexcept {
  buf_.clear();
  chunk_.clear();
  result_ = SmoothResult{};
  out_pos_ = out_end_ = 0;
  base_ = out_base_ = pushed_ = 0;
  scanned_ = 0;
  eager_tries_ = 0;
  front_moved_ = false;
  finished_ = done_ = false;
  counts_ = SmoothCounts{};
  error_.clear();
}

int Smoother::free_blocks() const noexcept {
  return finished_ ? 0 : capacity_ - static_cast<int>(buf_.size());
}

void Smoother::smooth_chunk(bool finishing) {
  const std::size_t n = buf_.size();
  if (finishing) {  // the rest of the program in one chunk
    done_ = true;
    if (n == 0) return;
    smooth_front(n);
    take(n, result_.blocks.size());
    return;
  }
  // a full buffer: the last clean cut block, else a vertex
  int attempts = 0;
  if (!try_cuts(1, attempts)) forced_cut();
}

bool Smoother::eager_cut() {
  // the cut blocks pushed since the last look with at least min_chunk_ blocks before them
  const std::size_t first = std::max<std::size_t>(scanned_, static_cast<std::size_t>(min_chunk_));
  scanned_ = buf_.size();
  return try_cuts(first, eager_tries_);
}

bool Smoother::try_cuts(std::size_t first, int& tries) {
  // newest first, each try counted in `tries` (a refusal smooths the chunk once more), at most
  // cut_attempts of them
  for (std::size_t c = buf_.size(); c-- > std::max<std::size_t>(first, 1) && tries < cut_attempts;) {
    const toolpath::Block& b = buf_[c];
    if (b.length() <= 1e-9 || micro_line(b, options_)) continue;  // no cut block
    ++tries;
    if (try_cut(c)) return true;
  }
  return false;
}

bool Smoother::try_cut(std::size_t c) {
  smooth_front(c + 1);
  const auto& r = result_;
  const std::size_t m = r.blocks.size();
  const long cl = static_cast<long>(c);
  const toolpath::Block& prog = buf_[c];
  // c's own block is the last one, kept whole at its end
  if (m < 2 || r.source_first[m - 1] != cl || r.source_last[m - 1] != cl) return false;
  const toolpath::Block& own = r.blocks[m - 1];
  if (r.controls[m - 1].cubic || own.kind != prog.kind || own.end != prog.end) return false;
  if (own.start != prog.start) {
    // moved: only a lead of the run before c (the block before c is a micro-segment, the start moved
    // by min(lead_length, length/2)); a rounded vertex before c (moved by the arc's tangent length)
    // is not a clean cut. The next chunk reads c as programmed with its output starting at own.start
    // (smooth_front()), as smooth() of the whole program does, however little of c is left.
    const double L = options_.lead_length, len = prog.length();
    if (prog.kind != toolpath::MotionKind::line || !micro_line(buf_[c - 1], options_)) return false;
    const double moved = (own.start - prog.start).norm(), lent = std::min(L, 0.5 * len);
    if (std::abs(moved - lent) > 1e-12 * (1.0 + len)) return false;
    // a corner arc starts as far before the vertex on the line before as it ends after it on c
    const toolpath::Block& before = r.blocks[m - 2];
    const toolpath::Block& b0 = buf_[c - 1];
    const Vec3 d0 = (b0.end - b0.start) / b0.length();
    if ((prog.start - moved * d0 - before.start).norm() <= 1e-9) return false;
  } else if (r.source_last[m - 2] >= cl) {
    return false;  // a block before c reaches into c without moving it (a lead of zero length)
  }
  // c stays in the buffer as programmed, its output starting where this chunk's ended (read before
  // take(), which shifts the buffer under `prog`)
  const bool moved = own.start != prog.start;
  const Vec3 start = own.start;
  take(c, m - 1);
  front_moved_ = moved;
  front_start_ = start;
  return true;
}

void Smoother::forced_cut() {
  // the sharpest vertex between two lines in the second half of the buffer; the chunk ends before it
  const std::size_t n = buf_.size();
  std::size_t v = n - 1;
  double worst = -1;
  auto dir = [](const toolpath::Block& b) { return ((b.end - b.start) / b.length()).eval(); };
  for (std::size_t q = std::max<std::size_t>(1, n / 2); q < n; ++q) {
    const auto &b0 = buf_[q - 1], &b1 = buf_[q];
    if (b0.kind != toolpath::MotionKind::line || b1.kind != toolpath::MotionKind::line || b0.length() <= 1e-9 ||
        b1.length() <= 1e-9)
      continue;
    const double th = turn_angle(dir(b0), dir(b1));
    if (th > worst) {
      worst = th;
      v = q;
    }
  }
  smooth_front(v);
  take(v, result_.blocks.size());
  // the vertex at the cut lies in neither chunk: count it here when it is a corner
  if (worst > options_.max_turn) ++counts_.corners_kept;
  ++counts_.forced_cuts;
}

void Smoother::smooth_front(std::size_t blocks) {
  chunk_.assign(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(blocks));
  result_ = front_moved_ ? smooth(chunk_, options_, front_start_) : smooth(chunk_, options_);
}

void Smoother::take(std::size_t blocks, std::size_t out_blocks) {
  front_moved_ = false;  // the new front block is as programmed (try_cut() may say otherwise)
  out_pos_ = 0;
  out_end_ = out_blocks;
  out_base_ = base_;
  counts_.runs_smoothed += result_.runs_smoothed;
  counts_.runs_kept += result_.runs_kept;
  counts_.corners_kept += result_.corners_kept;
  counts_.corners_rounded += result_.corners_rounded;
  counts_.max_fit_deviation = std::max(counts_.max_fit_deviation, result_.max_fit_deviation);
  ++counts_.chunks;
  buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(std::min(blocks, buf_.size())));
  base_ += static_cast<long>(blocks);
  scanned_ = 0;  // the blocks left are looked at again from the new front
  eager_tries_ = 0;
}

}  // namespace netshape::motion
