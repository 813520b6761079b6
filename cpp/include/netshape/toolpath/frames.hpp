#pragma once
/// \file frames.hpp
/// A program's frames and its sampler: program coordinates (what the G-code says), machine coordinates
/// (program point + the work offset G54…G59.3 and the tool length in force at each block), and points
/// along its moves.
///
/// The offset in force at block k is the one the writer subtracts there (gcode_writer.hpp):
/// `work_offsets.row(i) + (0, 0, l)` with i the index of the last work_offset command before block k
/// (0, G54, before any) and l the value of the last tool_length command before it (0 before any). So
/// `format_gcode(to_machine(tp, offsets))` writes the program coordinates of `tp` again.

#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::toolpath {

/// (n) index 0…8 (G54…G59.3) of the work offset in force at each block of `tp`, from its work_offset
/// commands (0 before any). The one per-block work-offset lookup of netshape.
std::vector<int> work_offset_index(const Toolpath& tp);

/// (n, 3) offset [mm] from program to machine coordinates at each block of `tp`: its `work_offsets` row
/// of the offset in force plus the tool length in force along +Z (see the file comment).
Points3 block_offsets(const Toolpath& tp);

/// `tp` (program coordinates, `tp.work_offsets` zero) in machine coordinates: every block's start, end
/// and arc centre moved by the offset in force there taken from `offsets` (rows G54…G59.3 [mm]); the
/// result carries `offsets` as its `work_offsets`. A block whose offset is (0, 0, 0) is copied as it is.
/// Throws std::invalid_argument when `tp.work_offsets` is not zero (already in machine coordinates) or
/// `offsets` is not finite.
Toolpath to_machine(const Toolpath& tp, const WorkOffsets& offsets);

/// `tp` (machine coordinates) in program coordinates: every block moved back by the offset in force
/// there (block_offsets); the result's `work_offsets` are zero. A block whose offset is (0, 0, 0) is
/// copied as it is. `to_program(to_machine(tp, o))` returns the blocks of `tp` to rounding.
Toolpath to_program(const Toolpath& tp);

/// Points along the moves of a program.
struct Samples {
  Points3 points;          ///< (m, 3) [mm], in the tool path's frame
  Eigen::VectorXd s;       ///< (m) distance along the sampled moves [mm] (gaps between moves not counted)
};

/// Points every ≤ `spacing` [mm] along the moves of `tp` (only the feed moves when `feeds_only`), arcs
/// first split into chords within `chord_tolerance` [mm]: each move of length L gives n = max(1,
/// ceil(L / spacing)) points at fractions k/n (k = 0 … n−1), and the last move's end closes the list.
/// `s` runs on over the moves taken, as if they joined. Empty when no move is taken. Throws
/// std::invalid_argument for a non-positive or non-finite `spacing` or `chord_tolerance`.
Samples sample(const Toolpath& tp, double spacing, bool feeds_only = true, double chord_tolerance = 1e-4);

}  // namespace netshape::toolpath
