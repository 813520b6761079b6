#pragma once
/// \file machine.hpp  Area umbrella of netshape::machine (one include per concept header of the area).
