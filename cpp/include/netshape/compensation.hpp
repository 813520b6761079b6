#pragma once
/// \file compensation.hpp  Area umbrella of netshape::compensation (one include per concept header of the area).
#include "netshape/compensation/volumetric_compensation.hpp"
#include "netshape/compensation/deflection_compensation.hpp"
#include "netshape/compensation/program_compensation.hpp"
#include "netshape/compensation/feed_schedule.hpp"
