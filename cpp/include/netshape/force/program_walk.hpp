#pragma once
/// \file program_walk.hpp
/// The walk of a cutter along a program over a Z-map stock that every per-sample computation shares
/// (netshape::force::simulate_program, netshape::compensation::feed_samples): rapids are swept whole;
/// a feed block of length L gets n = ⌈L/step⌉ samples at fractions s/n (s = 1 … n); a sample whose feed
/// direction has a horizontal part and whose tip is below the stock's top is visited BEFORE the move
/// that ends at it is swept (the material that move removes is the material in front of the edges).

#include <cstddef>
#include <functional>

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/stock/zmap.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::force {

/// One visited sample.
struct WalkSample {
  std::size_t block = 0;   ///< index of the block in the program
  double fraction = 0.0;   ///< position in the block, in (0, 1]
  Vec3 tip;                ///< tip position [mm]
  Vec3 tangent;            ///< unit tangent of the block at the sample
  Vec3 feed_direction;     ///< unit horizontal feed direction
  double depth = 0.0;      ///< min(flute length, stock top − tip z) [mm], > 0
};

/// Walk `program` over `stock` (modified: it ends as the machined part), calling `visit` at every
/// sample as the file comment says, with progress reported under `progress_name`. Returns the
/// removed volume [mm³]. step [mm] > 0.
double walk_program(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                    double step, const std::function<void(const WalkSample&)>& visit, const char* progress_name);

}  // namespace netshape::force
