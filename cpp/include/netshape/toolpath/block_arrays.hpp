#pragma once
/// \file block_arrays.hpp
/// A tool path as a structure of arrays: one array per Block field, row i = block i. What crosses into
/// Python as NumPy arrays (one typed object, zero-copy views) and what array-based consumers (the
/// planner, CL point lists) read, instead of per-block objects.

#include <cstdint>
#include <string>
#include <vector>

#include "netshape/toolpath/block.hpp"

namespace netshape::toolpath {

struct BlockArrays {
  std::vector<std::uint8_t> kind;          ///< (n) MotionKind codes
  std::vector<double> start, end, center;  ///< (n, 3) row-major [mm]
  std::vector<std::uint8_t> clockwise;     ///< (n) 1 for G2
  std::vector<std::uint8_t> plane;         ///< (n) Plane codes
  std::vector<std::int32_t> turns;         ///< (n)
  std::vector<double> feed;                ///< (n) [mm/s]
  std::vector<double> spindle_rpm;         ///< (n) [rev/min], negative for M4
  std::vector<std::int32_t> tool;          ///< (n)
  std::vector<std::int64_t> line;          ///< (n) 1-based source line (0 = not from a file)
  std::vector<double> dwell;               ///< (n) G4 dwell time executed before block i [s]
  std::vector<double> dwell_after;         ///< (n) dwell after block i that precedes no other block [s] (last only)
  std::vector<std::string> warnings;       ///< reader warnings (offsets used but not given)

  std::size_t size() const noexcept { return kind.size(); }
  void reserve(std::size_t n);
  /// Append block b; `dwell_before` [s] goes to `dwell`, 0 to `dwell_after`.
  void push_back(const Block& b, double dwell_before = 0.0);
  /// Block i as a Block value.
  Block block(std::size_t i) const;
  static BlockArrays from_blocks(const std::vector<Block>& blocks);
  std::vector<Block> to_blocks() const;
};

}  // namespace netshape::toolpath
