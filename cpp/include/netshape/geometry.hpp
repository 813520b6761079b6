#pragma once
/// \file geometry.hpp  Area umbrella of netshape::geometry (one include per concept header of the area).
