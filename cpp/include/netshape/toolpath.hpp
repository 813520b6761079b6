#pragma once
/// \file toolpath.hpp  Area umbrella: blocks, programs, G-code reading and writing.
#include "netshape/toolpath/block.hpp"
#include "netshape/toolpath/toolpath.hpp"
#include "netshape/toolpath/gcode_reader.hpp"
#include "netshape/toolpath/gcode_writer.hpp"
#include "netshape/toolpath/block_arrays.hpp"
#include "netshape/toolpath/frames.hpp"
