#pragma once
/// \file toolpath.hpp
/// A machining program as a sequence of motion blocks, and what can be said about it as a whole.

#include <array>
#include <string>
#include <vector>

#include "netshape/toolpath/block.hpp"

namespace netshape::toolpath {

/// Whole-program figures, as printed by `netshape info`.
struct Summary {
  long rapids = 0;                ///< number of rapid (G0) blocks
  long lines = 0;                 ///< number of feed lines (G1)
  long arcs = 0;                  ///< number of arcs (G2/G3)
  double rapid_length = 0.0;      ///< [mm]
  double feed_length = 0.0;       ///< lines + arcs [mm]
  Vec3 bbox_min = Vec3::Zero();   ///< bounding box of all motion, arcs included [mm]
  Vec3 bbox_max = Vec3::Zero();   ///< [mm]
  double feed_time = 0.0;         ///< time of feed moves at programmed feed [s] (rapids excluded)
  double dwell_time = 0.0;        ///< total G4 dwell time [s] (not in feed_time)
  long dwells = 0;                ///< number of G4 dwells
  long source_lines = 0;          ///< source lines read (0 when summarised from blocks)

  long blocks() const noexcept { return rapids + lines + arcs; }
};

/// A program: its blocks in order, and the name of its source (for messages).
struct Toolpath {
  std::vector<Block> blocks;
  std::string source;
  double dwell_time = 0.0;  ///< total G4 dwell time of the program [s] (dwells are not blocks)
  long dwells = 0;          ///< number of G4 dwells

  /// Counts, lengths, bounding box (exact for arcs, not only end points) and time at programmed feed.
  Summary summary() const;
  /// A copy with every arc replaced by lines whose chord error is at most `chord_tolerance` [mm].
  Toolpath split_arcs(double chord_tolerance) const;
};

/// Number of chords needed so that an arc of radius r [mm] and |sweep| [rad] deviates at most tol [mm]
/// from its chords. Throws std::invalid_argument for a non-positive or non-finite tolerance, or when
/// more than 10 million chords would be needed.
int chord_count(double radius, double sweep, double tol);

/// Append the chords of `arc` (an arc block) to `out`: lines (kind line) through points of the arc
/// with chord error at most `chord_tolerance` [mm]; they carry the arc's feed, spindle, tool and line.
/// Non-arc blocks are appended unchanged.
void split_block(const Block& arc, double chord_tolerance, std::vector<Block>& out);

/// Exact axis-aligned bounding box of one block [mm] (arcs: their extreme points, not only ends).
void block_bounds(const Block& block, Vec3& lo, Vec3& hi);

}  // namespace netshape::toolpath
