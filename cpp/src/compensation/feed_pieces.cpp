#include <algorithm>
#include <cmath>
#include <vector>

#include "netshape/compensation/feed_schedule.hpp"
#include "netshape/core/error.hpp"

namespace netshape::compensation {

namespace {

struct Piece {
  int block = 0;
  double start = 0.0, end = 1.0, feed = 0.0;
  int binding = static_cast<int>(FeedLimit::air);
  int sample = -1;
};

/// A sample's feed [mm/s] and what sets it.
void sample_feed(const FeedSamples& s, const Eigen::Ref<const MatrixXdR>& allowed, const FeedLimits& lim,
                 Eigen::Index i, double& feed, int& binding) {
  if (!s.engaged[i]) {
    feed = lim.air_feed > 0.0 ? lim.air_feed : lim.max_feed;
    binding = static_cast<int>(FeedLimit::air);
    return;
  }
  feed = lim.max_feed;
  binding = static_cast<int>(FeedLimit::max_feed);
  for (int j = 0; j < feed_limit_columns; ++j)
    if (allowed(i, j) < feed) {
      feed = allowed(i, j);
      binding = j;
    }
}

/// Same engagement as the piece's first sample `r`: both in air, or both engaged with depth, chip
/// factor and engaged share within the relative tolerance and the same walls.
bool same_engagement(const FeedSamples& s, Eigen::Index r, Eigen::Index i, double tol) {
  if (s.engaged[r] != s.engaged[i]) return false;
  if (!s.engaged[i]) return true;
  auto close = [tol](double a, double b) { return std::abs(a - b) <= tol * std::max(std::abs(a), 1e-12); };
  return close(s.depth[r], s.depth[i]) && close(s.chip_factor[r], s.chip_factor[i]) &&
         close(s.engaged_share[r], s.engaged_share[i]) && s.walls[r] == s.walls[i];
}

/// Pieces of one block from its samples [first, last).
void block_pieces(const FeedSamples& s, const Eigen::Ref<const MatrixXdR>& allowed, const FeedLimits& lim, int block,
                  double length, Eigen::Index first, Eigen::Index last, double tol, double min_length,
                  std::vector<Piece>& out) {
  std::vector<Piece> ps;
  Eigen::Index ref = first;
  for (Eigen::Index i = first; i < last; ++i) {
    double f = 0.0;
    int why = 0;
    sample_feed(s, allowed, lim, i, f, why);
    if (i == first || !same_engagement(s, ref, i, tol)) {
      Piece p;
      p.block = block;
      p.start = i == first ? 0.0 : s.fraction[i - 1];
      p.feed = f;
      p.binding = why;
      p.sample = static_cast<int>(i);
      ps.push_back(p);
      ref = i;
    } else if (f < ps.back().feed) {
      ps.back().feed = f;
      ps.back().binding = why;
      ps.back().sample = static_cast<int>(i);
    }
    ps.back().end = i + 1 == last ? 1.0 : s.fraction[i];
  }
  // a short piece joins the one before when both cut or both are in air; the joined piece takes the
  // smaller feed (never faster than any of its samples)
  std::vector<Piece> merged;
  auto in_air = [](const Piece& q) { return q.binding == static_cast<int>(FeedLimit::air); };
  for (const Piece& p : ps) {
    const bool short_piece = (p.end - p.start) * length < min_length;
    const bool short_last = !merged.empty() && (merged.back().end - merged.back().start) * length < min_length;
    if (!merged.empty() && (short_piece || short_last) && in_air(merged.back()) == in_air(p)) {
      Piece& q = merged.back();
      q.end = p.end;
      if (p.feed < q.feed) {
        q.feed = p.feed;
        q.binding = p.binding;
        q.sample = p.sample;
      }
    } else {
      merged.push_back(p);
    }
  }
  out.insert(out.end(), merged.begin(), merged.end());
}

}  // namespace

FeedPieces feed_pieces(const toolpath::Toolpath& program, const FeedSamples& s,
                       const Eigen::Ref<const MatrixXdR>& allowed, const FeedLimits& lim, double tolerance,
                       double min_length) {
  lim.validate();
  const Eigen::Index m = s.block.size();
  NETSHAPE_CHECK(allowed.rows() == m && allowed.cols() == feed_limit_columns, "allowed.rows", allowed.rows(),
                 "must be (samples, 6)");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance >= 0.0, "tolerance", tolerance, "must be ≥ 0 [-]");
  NETSHAPE_CHECK(std::isfinite(min_length) && min_length >= 0.0, "min_length", min_length, "must be ≥ 0 [mm]");
  std::vector<Piece> ps;
  Eigen::Index i = 0;
  for (std::size_t bi = 0; bi < program.blocks.size(); ++bi) {
    const toolpath::Block& b = program.blocks[bi];
    const int block = static_cast<int>(bi);
    Eigen::Index j = i;
    while (j < m && s.block[j] == block) ++j;
    if (b.kind == toolpath::MotionKind::rapid || b.length() <= 0.0) {
      i = j;
      continue;
    }
    if (j == i) {  // a feed move without samples: above the stock (air), or vertical (kept as programmed)
      Piece p;
      p.block = block;
      const Vec3 d = b.end - b.start;
      const bool vertical = b.kind == toolpath::MotionKind::line && std::hypot(d.x(), d.y()) <= 1e-9;
      p.feed = vertical ? b.feed : (lim.air_feed > 0.0 ? lim.air_feed : lim.max_feed);
      p.binding = static_cast<int>(vertical ? FeedLimit::programmed : FeedLimit::air);
      ps.push_back(p);
    } else {
      block_pieces(s, allowed, lim, block, b.length(), i, j, tolerance, min_length, ps);
    }
    i = j;
  }
  FeedPieces out;
  const Eigen::Index k = static_cast<Eigen::Index>(ps.size());
  out.block.resize(k);
  out.start.resize(k);
  out.end.resize(k);
  out.feed.resize(k);
  out.binding.resize(k);
  out.sample.resize(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    out.block[r] = ps[r].block;
    out.start[r] = ps[r].start;
    out.end[r] = ps[r].end;
    out.feed[r] = ps[r].feed;
    out.binding[r] = ps[r].binding;
    out.sample[r] = ps[r].sample;
  }
  return out;
}

}  // namespace netshape::compensation
