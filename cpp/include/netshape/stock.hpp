#pragma once
/// \file stock.hpp  Area umbrella of netshape::stock (one include per concept header of the area).
#include "netshape/stock/engagement.hpp"
#include "netshape/stock/stl.hpp"
#include "netshape/stock/sweep.hpp"
#include "netshape/stock/tip_profile.hpp"
#include "netshape/stock/zmap.hpp"
