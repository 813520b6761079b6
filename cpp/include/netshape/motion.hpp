#pragma once
/// \file motion.hpp  Area umbrella of netshape::motion (one include per concept header of the area).
#include "netshape/motion/corner.hpp"
#include "netshape/motion/limits.hpp"
#include "netshape/motion/options.hpp"
#include "netshape/motion/planner.hpp"
#include "netshape/motion/profile.hpp"
#include "netshape/motion/segment.hpp"
#include "netshape/motion/smoother.hpp"
#include "netshape/motion/smoothing.hpp"
#include "netshape/motion/trajectory.hpp"
