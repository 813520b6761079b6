#pragma once
/// \file cubic.hpp
/// Cubic Bézier blocks: the curvature-continuous pieces of a smoothed run (smoothing.hpp) as the
/// planner takes them. A cubic block is a toolpath::Block of kind line (its chord: start = P0,
/// end = P3, with its feed) plus the two inner control points P1, P2 held here; everything that reads
/// blocks as a program (G-code, stock, deviation) sees the chord unless it asks for these.
///
/// Units: mm.

#include "netshape/core/types.hpp"

namespace netshape::motion {

/// Inner control points of a cubic block; `cubic` false: the block is what its kind says.
struct CubicControls {
  bool cubic = false;
  Vec3 c1 = Vec3::Zero();  ///< P1 [mm]
  Vec3 c2 = Vec3::Zero();  ///< P2 [mm]
};

}  // namespace netshape::motion
