#pragma once
/// \file trajectory.hpp
/// Batch API: plan a whole program and return the fine samples with their figures.

#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/motion/cubic.hpp"
#include "netshape/motion/limits.hpp"
#include "netshape/motion/options.hpp"
#include "netshape/toolpath/block.hpp"

namespace netshape::motion {

/// What a planned run reached; "max" figures are the largest over all axes and samples, measured by
/// finite differences of the positions at ts2 (velocity: first, acceleration: second, jerk: third).
struct TrajectoryStats {
  long blocks = 0;                         ///< blocks planned (zero-length ones skipped)
  long samples = 0;                        ///< fine samples
  double cycle_time = 0;                   ///< [s]
  double max_axis_velocity = 0;            ///< [mm/s]
  double max_axis_acceleration = 0;        ///< [mm/s^2]
  double max_axis_jerk = 0;                ///< [mm/s^3]
  Vec3 axis_velocity = Vec3::Zero();       ///< per axis [mm/s]
  Vec3 axis_acceleration = Vec3::Zero();   ///< per axis [mm/s^2]
  Vec3 axis_jerk = Vec3::Zero();           ///< per axis [mm/s^3]
  double max_path_deviation = 0;           ///< largest distance of a sample from the program [mm]
  double end_error = 0;                    ///< distance of the last sample from the program end [mm]
};

/// Samples of a planned run: (n,) times, (n, 3) positions and velocities, (n,) feeds.
struct Trajectory {
  VectorXd t;           ///< [s]
  Points3 position;     ///< [mm]
  Points3 velocity;     ///< [mm/s]
  VectorXd feed;        ///< path speed [mm/s]
  Eigen::VectorXi block;  ///< program block index per sample
  TrajectoryStats stats;
};

/// Plan and interpolate a whole program (runs the streaming Planner; the blocks are validated first,
/// throwing std::invalid_argument on the first bad one). `with_deviation` measures each sample's
/// distance to the programmed blocks (costs a little). `max_samples` > 0 bounds the fine samples (about
/// 70 B each while planned): the plan stops with std::invalid_argument naming max_samples when it would
/// write more (0: no bound).
Trajectory plan(const std::vector<toolpath::Block>& blocks, const AxisLimits& limits,
                const PlanOptions& options, bool with_deviation = true, long max_samples = 0);
/// The same with cubic blocks: `controls` empty (no cubic block) or one per block; a block with
/// controls[i].cubic is the cubic Bézier (start, c1, c2, end) and must be of kind line (Planner::push).
/// `with_deviation` measures against the curve for those blocks.
Trajectory plan(const std::vector<toolpath::Block>& blocks, const std::vector<CubicControls>& controls,
                const AxisLimits& limits, const PlanOptions& options, bool with_deviation = true,
                long max_samples = 0);

/// Figures of (n, 3) samples at period ts [s] (finite differences).
void measure_samples(const Points3& position, double ts, TrajectoryStats& stats);

}  // namespace netshape::motion
