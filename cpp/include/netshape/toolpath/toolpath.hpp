#pragma once
/// \file toolpath.hpp
/// A machining program as a sequence of motion blocks, and what can be said about it as a whole.

#include <array>
#include <cstdint>
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
  std::vector<std::string> warnings;  ///< reader warnings (work offset / tool length used but not given)

  long blocks() const noexcept { return rapids + lines + arcs; }
  /// Feed time plus dwell time [s] (rapids and accelerations not included).
  double total_time() const noexcept { return feed_time + dwell_time; }
};

/// What a non-motion record of a program is.
enum class CommandKind : std::uint8_t {
  comment = 0,      ///< "( … )" or "; …" comment, text as written in the source
  word = 1,         ///< a code that does not move the tool: M codes, S, T, G40, G61/G61.1/G64 P Q, G80, G97 …
  dwell = 2,        ///< G4 P: `value` is the duration [s]
  work_offset = 3,  ///< G54 … G59.3: `value` is the index 0 … 8 (G54 … G59.3)
  tool_length = 4,  ///< G43 [H] / G49: `value` is the tool length applied along +Z [mm] (0: G49, or no table)
  program_end = 5,  ///< M2 or M30 (the last record of a program that has one)
};

/// A non-motion record: a comment, or the words of one code, at its place among the motion blocks.
struct Command {
  std::size_t before = 0;  ///< index of the motion block it precedes; blocks.size(): after the last block
  CommandKind kind = CommandKind::word;
  std::string text;        ///< as written out, e.g. "M8", "S1600", "G64 P0.1 Q0.02", "G4 P0.5", "(finish)"
  double value = 0.0;      ///< see CommandKind (dwell [s], offset index, tool length [mm])
  long line = 0;           ///< 1-based source line (0 = not from a file)
};

/// Work offsets G54 … G59.3 (rows 0 … 8) as (X, Y, Z) [mm].
using WorkOffsets = Eigen::Matrix<double, 9, 3, Eigen::RowMajor>;

/// A program: its motion blocks in order, the non-motion records (comments, M/S/T words, dwells,
/// offsets …) at their places among them, and the name of its source (for messages).
///
/// Frame: block coordinates are program coordinates plus the work offset and tool length in force
/// (machine axis positions) when the reader was given offsets; program coordinates otherwise.
struct Toolpath {
  std::vector<Block> blocks;
  std::vector<Command> commands;  ///< in program order; `before` non-decreasing
  std::string source;
  double dwell_time = 0.0;  ///< total G4 dwell time of the program [s] (dwells are commands)
  long dwells = 0;          ///< number of G4 dwells
  WorkOffsets work_offsets = WorkOffsets::Zero();  ///< offsets the blocks include (writer subtracts them) [mm]
  std::vector<std::string> warnings;  ///< reader warnings (offsets used but not given)

  /// Counts, lengths, bounding box (exact for arcs, not only end points) and time at programmed feed.
  Summary summary() const;
  /// A copy with every arc replaced by lines whose chord error is at most `chord_tolerance` [mm].
  Toolpath split_arcs(double chord_tolerance) const;
  /// A copy with `new_blocks` in place of the blocks, for transforms that move, add or split moves:
  /// `origin[i]` is the index of the block new block i came from (non-decreasing, < blocks.size()).
  /// Every command keeps its order and goes before the first new block that came from the block it
  /// preceded (after the last new block if there is none). Throws std::invalid_argument for a bad
  /// `origin`.
  Toolpath with_blocks(std::vector<Block> new_blocks, const std::vector<long>& origin) const;
};

/// Number of chords needed so that an arc of radius r [mm] and |sweep| [rad] deviates at most tol [mm]
/// from its chords: ceil(|sweep| / θ) with θ = 2·acos(1 − tol/r), a quarter turn when tol ≥ r; at least
/// 1. The one arc chord count of netshape: the reader/writer's arc splitting, contour offsets, the
/// program compensation and the stock sweep all use it. Throws std::invalid_argument for a
/// non-positive or non-finite tolerance, or when more than 10 million chords would be needed.
int chord_count(double radius, double sweep, double tol);

/// Whether the point c continues the straight run a → b [mm]: b ≠ a, c lies ahead of b (the step b → c
/// goes the same way as a → b) and c is within `tolerance` [mm] of the line through a and b. The one
/// collinear-run test of netshape (the stock sweep merges runs of lines with it).
bool continues_run(const Vec3& a, const Vec3& b, const Vec3& c, double tolerance = 1e-9) noexcept;

/// Append the chords of `arc` (an arc block) to `out`: lines (kind line) through points of the arc
/// with chord error at most `chord_tolerance` [mm]; they carry the arc's feed, spindle, tool and line.
/// Non-arc blocks are appended unchanged.
void split_block(const Block& arc, double chord_tolerance, std::vector<Block>& out);

/// Exact axis-aligned bounding box of one block [mm] (arcs: their extreme points, not only ends).
void block_bounds(const Block& block, Vec3& lo, Vec3& hi);

}  // namespace netshape::toolpath
