#pragma once
// The program as the volumetric compensation sees it on a machine with state-dependent errors
// (machine/state_error.hpp): arcs as chords where the machine has backlash, and per block the tip's
// state offset s(d, t) at its start and end.
#include <vector>

#include "netshape/compensation/program_compensation.hpp"

namespace netshape::compensation::detail {

struct StatefulProgram {
  std::vector<toolpath::Block> blocks;  ///< the source blocks; on a machine with backlash arcs as chords
  std::vector<long> source;             ///< source block index of each block
  std::vector<Vec3> off_start;          ///< s(d, t) at the block's start [mm] (its own directions)
  std::vector<Vec3> off_end;            ///< s(d, t) at the block's end [mm]
  /// Per block: it reverses an axis with backlash, so its start needs a take-up move (off_start
  /// differs from the previous block's off_end).
  std::vector<char> reversal;
};

/// Blocks, directions and offsets of `program` on `machine` (times: options.block_times, else
/// block_end_times; within a block linear in its fraction).
StatefulProgram stateful_program(const machine::Machine& machine, const toolpath::Toolpath& program,
                                 const ProgramOptions& options);

}  // namespace netshape::compensation::detail
