#pragma once
// Block arrays (the parallel arrays of netshape.motion) into blocks for the planner, with cubic blocks:
// kind 3 rows are cubic Béziers whose inner control points are the row of `ctrl`.
#include <vector>

#include "default_types.hpp"
#include "netshape/motion/cubic.hpp"
#include "netshape/motion/planner.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion_arrays {

/// Blocks and their cubic controls from block arrays: kind 0 (rapid), 1 (line), 2 (arc) as they are;
/// kind 3 (cubic) becomes a line block (its chord start -> end) with controls {true, ctrl[i, 0:3],
/// ctrl[i, 3:6]} (P1, P2); ctrl is (n, 6) and read only on kind 3 rows. `controls` is left empty when
/// no row is cubic. Throws std::invalid_argument naming the field and row.
std::vector<toolpath::Block> planned_blocks_from_arrays(
    const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
    py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
    const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
    py_types::RefVector feed, py_types::RefMatrix ctrl, std::vector<motion::CubicControls>& controls);

/// Blocks as parallel arrays (the dict smooth_path returns): kind, start, end, center, clockwise,
/// plane, turns, feed, and ctrl (n, 2, 3): P1, P2 of cubic blocks, whose kind is 3 (zeros elsewhere).
pybind11::dict block_arrays(const std::vector<toolpath::Block>& blocks,
                            const std::vector<motion::CubicControls>& controls);

/// Blocks of a program from parallel arrays (so the planner does not depend on how toolpath binds its
/// Block): kinds 0, 1, 2 only; a cubic row (kind 3), which only arrays that are planned may hold, is
/// refused (std::invalid_argument naming the row).
std::vector<toolpath::Block> program_blocks_from_arrays(
    const Eigen::Ref<const Eigen::VectorXi>& kind, py_types::RefPoints3 start, py_types::RefPoints3 end,
    py_types::RefPoints3 center, const Eigen::Ref<const Eigen::VectorXi>& clockwise,
    const Eigen::Ref<const Eigen::VectorXi>& plane, const Eigen::Ref<const Eigen::VectorXi>& turns,
    py_types::RefVector feed);

/// Blocks of a program as program_blocks_from_arrays builds them from its columns: the eight planning
/// fields of each block (kind, start, end, center, clockwise, plane, turns, feed), line = row + 1, the
/// rest (spindle, tool) default — so a Toolpath or BlockArrays plans bit for bit as its arrays do.
std::vector<toolpath::Block> program_blocks(const std::vector<toolpath::Block>& blocks);

/// Hands out the Planner's segments until it needs blocks or is done (returns that status), counting
/// them in `segments` and keeping the end time of the last in `t_end` [s].
motion::Status drain(motion::Planner& p, motion::PlannedSegment& seg, long& segments, double& t_end);

}  // namespace netshape::motion_arrays
