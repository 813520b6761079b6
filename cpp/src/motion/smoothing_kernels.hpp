#pragma once
/// \file smoothing_kernels.hpp
/// Internal: the array work of the smoothing stage's spline fit (smoothing_spline.hpp) in kernels
/// (kernels/smoothing.cpp) compiled once per instruction set (docs/simd.md), one lane per knot span.
/// Every lane does the scalar definition's operations in the same order and no copy contracts to FMA,
/// so every instruction set gives the same bits. Only plain doubles cross between the kernels and the
/// rest of the library.

#include "core/dispatch.hpp"

namespace netshape::motion::detail {

/// Segments prepared for distance queries, as rows: segment q starts at (ax[q], ay[q]), runs along
/// (dx[q], dy[q]) = end − start and has il2[q] = 1/|d|² (0 for a point).
struct SegRows {
  const double *ax, *ay, *dx, *dy, *il2;
};

/// The kernels of one instruction set.
struct SmoothingKernels {
  /// The power form of the cubic B-spline basis on the knot spans k0..k1 (3 ≤ k0, k1 + 4 < the number
  /// of knots) of the knots t: pb[16·k + 4·j + r] = D_j(N_{k−3+r})(t[k]) / j!, the coefficient of x^j
  /// (x = u − t[k]) of basis function k − 3 + r on span k, by the Cox–de Boor recursion on polynomials
  /// (Spline::power_basis() states it); all 16 zero for an empty span (t[k + 1] ≤ t[k]). Reads
  /// t[k0 − 3..k1 + 4], writes pb[16·k0..16·k1 + 15] only.
  void (*power_basis)(const double* t, int k0, int k1, double* pb);
  /// The squared distances of the points p0 = (p[0], p[1]) and p1 = (p[2], p[3]) to the segments lo..hi
  /// of s into D0[0..hi − lo] and D1[0..hi − lo], one lane per segment: for a point p and segment q,
  /// with r = p − a, t = clamp((r_x·d_x + r_y·d_y)·il2, 0, 1) (std::clamp's order: t < 0 gives 0, else
  /// 1 < t gives 1) and e = r − t·d, e_x·e_x + e_y·e_y. Then their minima over the window, each starting
  /// from 1e300 (an empty window's): mins[0] = min over q of max(D0, D1) (std::max), mins[1] = min D0,
  /// mins[2] = min D1, and where sag is not null mins[3] = min over q of √max(D0, D1) + sag[q] and
  /// mins[4] = min sag[q]. The values are ≥ +0 (sag too), so a minimum is the same bits in any order.
  /// Reads and writes nothing outside these ranges.
  void (*pair_window)(const double* p, const SegRows& s, long lo, long hi, const double* sag, double* D0,
                      double* D1, double* mins);
  const char* isa;  ///< "baseline", "avx2" or "avx512"
};
NETSHAPE_SIMD_DECLARE(SmoothingKernels, smoothing_kernel_table)
/// The kernels of the instruction set chosen for this process (core/dispatch.hpp, NETSHAPE_ISA).
const SmoothingKernels& smoothing_kernels();
/// The baseline kernels (tests compare them with the chosen ones).
const SmoothingKernels& smoothing_kernels_plain();

}  // namespace netshape::motion::detail
