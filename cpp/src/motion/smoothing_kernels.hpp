#pragma once
/// \file smoothing_kernels.hpp
/// Internal: the array work of the smoothing stage's spline fit (smoothing_spline.hpp) in kernels
/// (kernels/smoothing.cpp) compiled once per instruction set (docs/simd.md), one lane per knot span.
/// Every lane does the scalar definition's operations in the same order and no copy contracts to FMA,
/// so every instruction set gives the same bits. Only plain doubles cross between the kernels and the
/// rest of the library.

#include "core/dispatch.hpp"

namespace netshape::motion::detail {

/// The kernels of one instruction set.
struct SmoothingKernels {
  /// The power form of the cubic B-spline basis on the knot spans k0..k1 (3 ≤ k0, k1 + 4 < the number
  /// of knots) of the knots t: pb[16·k + 4·j + r] = D_j(N_{k−3+r})(t[k]) / j!, the coefficient of x^j
  /// (x = u − t[k]) of basis function k − 3 + r on span k, by the Cox–de Boor recursion on polynomials
  /// (Spline::power_basis() states it); all 16 zero for an empty span (t[k + 1] ≤ t[k]). Reads
  /// t[k0 − 3..k1 + 4], writes pb[16·k0..16·k1 + 15] only.
  void (*power_basis)(const double* t, int k0, int k1, double* pb);
  const char* isa;  ///< "baseline", "avx2" or "avx512"
};
NETSHAPE_SIMD_DECLARE(SmoothingKernels, smoothing_kernel_table)
/// The kernels of the instruction set chosen for this process (core/dispatch.hpp, NETSHAPE_ISA).
const SmoothingKernels& smoothing_kernels();
/// The baseline kernels (tests compare them with the chosen ones).
const SmoothingKernels& smoothing_kernels_plain();

}  // namespace netshape::motion::detail
