#pragma once
/// \file cutter.hpp  Area umbrella: end mills.
#include "netshape/cutter/cutter.hpp"
