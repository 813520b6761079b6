#pragma once
/// \file compensation.hpp  Area umbrella of netshape::compensation (one include per concept header of the area).
