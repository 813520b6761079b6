#pragma once
// The machine's batch kernel (private): the exact synthesis of `batch_lanes` points in packs of W
// (chain_step.hpp), compiled once per instruction set by netshape_add_kernels (kernels/lanes.cpp):
// W = 8 with AVX-512, 4 with AVX2, 2 on the baseline (1 without vector types).
#include "core/dispatch.hpp"
#include "netshape/machine/synthesis.hpp"

namespace netshape::machine::kernels {

struct LaneKernels {
  /// tip_error_lanes of one instruction set (netshape/machine/synthesis.hpp).
  unsigned (*lanes)(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                    double (*jacobian)[9][batch_lanes]);
  int width;  ///< points per vector
};

NETSHAPE_SIMD_DECLARE(LaneKernels, lane_kernels)

}  // namespace netshape::machine::kernels
