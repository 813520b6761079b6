#pragma once
/// \file force.hpp  Area umbrella of netshape::force (one include per concept header of the area).
#include "netshape/force/coefficients.hpp"
#include "netshape/force/engagement.hpp"
#include "netshape/force/flat_end_model.hpp"
#include "netshape/force/ball_end_model.hpp"
#include "netshape/force/force_summary.hpp"
#include "netshape/force/calibration.hpp"
#include "netshape/force/program.hpp"
#include "netshape/force/runout_size_effect.hpp"
