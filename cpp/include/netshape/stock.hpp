#pragma once
/// \file stock.hpp  Area umbrella of netshape::stock (one include per concept header of the area).
