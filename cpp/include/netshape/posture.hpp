#pragma once
/// \file posture.hpp  Area umbrella of netshape::posture (one include per concept header of the area).
#include "netshape/posture/assembly.hpp"
#include "netshape/posture/cspace.hpp"
#include "netshape/posture/kinematics.hpp"
#include "netshape/posture/mb_spline.hpp"
#include "netshape/posture/planner.hpp"
#include "netshape/posture/moves.hpp"
