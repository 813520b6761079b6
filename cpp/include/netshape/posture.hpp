#pragma once
/// \file posture.hpp  Area umbrella of netshape::posture (one include per concept header of the area).
