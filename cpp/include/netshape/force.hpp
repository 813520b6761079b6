#pragma once
/// \file force.hpp  Area umbrella of netshape::force (one include per concept header of the area).
