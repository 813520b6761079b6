#pragma once
/// \file motion.hpp  Area umbrella of netshape::motion (one include per concept header of the area).
