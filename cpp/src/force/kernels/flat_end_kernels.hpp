#pragma once
// The flat end mill's element loop (private): for every rotation angle, the forces of all
// (disk, flute) elements summed (Altintas' linear edge model or Kline–DeVor), compiled once per
// instruction set by netshape_add_kernels (kernels/flat_end.cpp) and chosen at run time.
//
// Every copy keeps 4 partial sums per force component (elements e ≡ 0, 1, 2, 3 mod 4) and adds them
// as (s0 + s1) + (s2 + s3), and none contracts to FMA, so every instruction set gives bit-identical
// forces (only the order of the sum over elements differs from a one-element-at-a-time loop: ~1e-16
// relative).
#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "core/dispatch.hpp"
#include "netshape/core/types.hpp"
#include "netshape/force/coefficients.hpp"

namespace netshape::force::kernels {

/// a wrapped into [0, 2π) [rad]. Internal linkage (static): the model's baseline code and each
/// instruction-set copy of the kernel keep their own, so no copy is shared between them.
static inline double wrap_angle(double a) noexcept { return a - 2.0 * pi * std::floor(a / (2.0 * pi)); }

/// Per-element data of the workspace: angular offset [rad] (wrapped to [0, 2π)), its cosine and
/// sine, and the element's disk.
struct ElementArrays {
  const double* off;
  const double* co;
  const double* so;
  const int* disk;
};

/// Per-call constants: element count, feed per tooth c [mm], disk height dz [mm], engagement start
/// and span [rad], coefficients, optional engagement map (disks × bins, row stride mask_stride).
struct LoopConstants {
  int n;
  double c, dz, st, span;
  LinearEdgeCoefficients k;
  double KT, KR;
  const std::uint8_t* mask;  ///< null without map
  Eigen::Index mask_stride;
  int bins;
  double bin_scale;
};

/// Forces (Fx, Fy, Fz) [N] at `count` angles into rows of `out` (row stride out_stride).
using LoopFn = void (*)(const LoopConstants& L, const ElementArrays& A, const double* angles, Eigen::Index count,
                        double* out, Eigen::Index out_stride);
struct FlatEndKernels {
  LoopFn loop[2][2];  ///< [with engagement map][Kline–DeVor coefficients]
};

NETSHAPE_SIMD_DECLARE(FlatEndKernels, flat_end_kernels)

}  // namespace netshape::force::kernels
