#pragma once
/// \file machine.hpp  Area umbrella of netshape::machine (one include per concept header of the area).
#include "netshape/machine/compiled_machine.hpp"
#include "netshape/machine/error_function.hpp"
#include "netshape/machine/machine.hpp"
#include "netshape/machine/state_error.hpp"
#include "netshape/machine/synthesis.hpp"
#include "netshape/machine/table_interpolation.hpp"
