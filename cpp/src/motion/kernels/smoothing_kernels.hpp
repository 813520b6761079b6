#pragma once
/// \file smoothing_kernels.hpp
/// Internal: the array work of the smoothing stage's spline fit (smoothing/spline.hpp) in kernels
/// (kernels/smoothing.cpp) compiled once per instruction set (docs/simd.md), one lane per knot span.
/// Every lane does the scalar definition's operations in the same order and no copy contracts to FMA,
/// so every instruction set gives the same bits. Only plain doubles cross between the kernels and the
/// rest of the library.

#include "core/dispatch.hpp"

namespace netshape::motion::detail {

/// Segments prepared for distance queries, as rows: segment q starts at (ax[q], ay[q]), runs along
/// (dx[q], dy[q]) = end − start and has il2[q] = 1/|d|² (0 for a point). For a chain (segment q + 1
/// starts where q ends), (wx[q], wy[q]) is the bisector direction at the vertex between q and q + 1.
struct SegRows {
  const double *ax, *ay, *dx, *dy, *il2;
  const double *wx, *wy;
};

/// A clamped cubic B-spline in the plane in power form (Spline::pw): knots t[0..m + 3], and per knot
/// span k the 8 doubles pw[8·k..8·k + 7] = c0, c1, c2, c3 (x, y each) of s(u) = c0 + c1·x + c2·x² +
/// c3·x³, x = u − t[k]; parameter u ∈ [0, L]; mean: the run's mean segment length (a Newton step is at
/// most mean/4).
struct FootSpline {
  const double* t;
  const double* pw;
  int m;
  double L, mean;
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
  /// The parts of run_bound() (smoothing/spline.hpp) for the segment [c0, c1] (c = c0x, c0y, c1x, c1y)
  /// against the chain s[lo..hi], one lane per segment or vertex, each value val(d2, q) = d2, or
  /// √d2 + sag[q] where sag is not null: V0[i], V1[i] = val(D0[i], q), val(D1[i], q) for q = lo + i ≤ hi
  /// (D0, D1: the squared distances of c0, c1 to segment q); and for each vertex q = lo + i < hi, the
  /// point x where [c0, c1] crosses its bisector — with e = c1 − c0, τ = cross(s.a[q + 1] − c0, w[q]) /
  /// cross(e, w[q]), set to 0 unless τ ≥ 0 (NaN too), then to 1 unless τ ≤ 1, x = c0 + τ·e,
  /// cross(a, b) = a_x·b_y − a_y·b_x — VN[i] = val(dist2(x, q), q) and VX[i] = val(dist2(x, q + 1),
  /// q + 1), dist2 as in pair_window. Writes V0, V1 [0..hi − lo], VN, VX [0..hi − lo − 1] only.
  void (*run_parts)(const double* c, const SegRows& s, long lo, long hi, const double* sag, const double* D0,
                    const double* D1, double* V0, double* V1, double* VN, double* VX);
  /// The foot points of the points (px[i], py[i]), i < n, on the spline sp, one lane per point, as
  /// fit_run() takes them: from the parameter u[i] in span k[i] (a span to search from; Spline::eval
  /// finds u's span, span_near()), Newton steps on (s(u) − p)·s'(u) = 0 — with r = s(u) − p and
  /// fp = |s'|² + r·s'', du = clamp(−(r·s')/fp, −mean/4, mean/4) where fp > 0, u = clamp(u + du, 0, L)
  /// — at most two, the second only after a step with |du| ≥ 1e-9, one evaluation after each. Where
  /// the distance at the last evaluation is ≤ the first one, u[i], k[i] become its parameter and span
  /// and res[i] that distance; elsewhere u[i] stays, k[i] becomes the first evaluation's span and
  /// res[i] its distance. Distances are √(r_x·r_x + r_y·r_y).
  void (*foot_points)(const FootSpline& sp, int n, double* u, int* k, const double* px, const double* py,
                      double* res);
  const char* isa;  ///< "baseline", "avx2" or "avx512"
};
NETSHAPE_SIMD_DECLARE(SmoothingKernels, smoothing_kernel_table)
/// The kernels of the instruction set chosen for this process (core/dispatch.hpp, NETSHAPE_ISA).
const SmoothingKernels& smoothing_kernels();
/// The baseline kernels (tests compare them with the chosen ones).
const SmoothingKernels& smoothing_kernels_plain();

}  // namespace netshape::motion::detail
