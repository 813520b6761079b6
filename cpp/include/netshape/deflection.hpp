#pragma once
/// \file deflection.hpp  Area umbrella of netshape::deflection (one include per concept header of the area).
