#pragma once
/// \file netshape.hpp
/// Umbrella header: everything netshape offers to a C++ program. Each area also has its own
/// umbrella `netshape/<area>.hpp`; include only those you use to keep builds fast.

#include "netshape/core/error.hpp"
#include "netshape/core/types.hpp"
#include "netshape/toolpath.hpp"
#include "netshape/cutter.hpp"
#include "netshape/stock.hpp"
#include "netshape/force.hpp"
#include "netshape/deflection.hpp"
#include "netshape/geometry.hpp"
#include "netshape/machine.hpp"
#include "netshape/compensation.hpp"
#include "netshape/motion.hpp"
#include "netshape/posture.hpp"
