#pragma once
/// \file deflection.hpp  Area umbrella of netshape::deflection (one include per concept header of the area).
#include "netshape/deflection/cantilever.hpp"
#include "netshape/deflection/wall.hpp"
