#pragma once
/// \file table_interpolation.hpp
/// Linear interpolation on a table of values at increasing positions: where a position q falls
/// (segment, held end value or refused, by the out-of-range policy), the value a + t·(b − a) and the
/// slope (b − a)/(x_{i+1} − x_i). Every table evaluation of netshape::machine goes through these
/// functions: `ErrorFunction::operator()`, the prepared functions and packed axis tables of a
/// `CompiledMachine`, and the vectorised lanes (`interpolate`, `segment_slope` and `uniform_position`
/// are templates so that they also take vector packs).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "netshape/machine/error_function.hpp"

namespace netshape::machine::detail {

/// The positions of a table (not owned): x[0..n) strictly increasing [mm], n ≥ 2. `uniform` when they
/// are equally spaced (to 1e-9 of the range); then inv_step = (n − 1)/(hi − lo) [1/mm].
struct TableGrid {
  const double* x = nullptr;
  int n = 0;
  double lo = 0.0, hi = 0.0;  ///< x[0], x[n − 1] [mm]
  double inv_step = 0.0;      ///< (n − 1)/(hi − lo) [1/mm]
  bool uniform = false;
};

/// The grid of `positions` (validated: ≥ 2, strictly increasing). With `detect_uniform` false the grid
/// is treated as non-uniform (binary search; no O(n) scan, inv_step left 0).
inline TableGrid table_grid(const std::vector<double>& positions, bool detect_uniform) noexcept {
  TableGrid g;
  g.x = positions.data();
  g.n = static_cast<int>(positions.size());
  g.lo = positions.front();
  g.hi = positions.back();
  if (detect_uniform) {
    const double step = (g.hi - g.lo) / (g.n - 1);
    g.inv_step = 1.0 / step;
    g.uniform = true;
    for (int i = 0; i < g.n; ++i)
      if (std::abs(positions[i] - (g.lo + i * step)) > 1e-9 * (1.0 + std::abs(g.hi - g.lo))) g.uniform = false;
  }
  return g;
}

/// u = (q − lo)·inv_step: q in steps from the first position of a uniform grid.
template <class T>
inline T uniform_position(const T& q, double lo, double inv_step) noexcept {
  return (q - lo) * inv_step;
}

/// Segment of a uniform grid holding u = uniform_position(q) for lo ≤ q ≤ hi: min(⌊u⌋, n − 2).
inline int uniform_segment(double u, int n) noexcept {
  const int i = static_cast<int>(u);
  return i > n - 2 ? n - 2 : i;
}

/// a + t·(b − a): the value at fraction t of the segment from a to b (t outside [0, 1] extrapolates).
template <class T, class U>
inline T interpolate(const T& a, const T& b, const U& t) noexcept {
  return a + t * (b - a);
}

/// (b − a)·inv_dx: the slope of the segment from a to b, inv_dx = 1/(x_{i+1} − x_i) [1/mm].
template <class T, class U>
inline T segment_slope(const T& a, const T& b, const U& inv_dx) noexcept {
  return (b - a) * inv_dx;
}

/// Where q falls on a table with out-of-range policy `policy`.
struct TableLookup {
  enum class Where : std::uint8_t {
    segment,  ///< interpolate on [x_i, x_{i+1}] at fraction t (inside, or extrapolate outside)
    first,    ///< clamp below the table: hold the first value, slope 0
    last,     ///< clamp above the table: hold the last value, slope 0
    refused,  ///< outside with policy `error`, or q not finite
  };
  Where where = Where::segment;
  int i = 0;            ///< segment index, 0 ≤ i ≤ n − 2
  double t = 0.0;       ///< fraction of q along the segment
  double inv_dx = 0.0;  ///< 1/(x_{i+1} − x_i) [1/mm] (set when `Slope`)
};

/// Locate q [mm]. Inside [lo, hi] on a uniform grid: u = uniform_position(q), i = uniform_segment(u),
/// t = u − i (O(1), no division); otherwise i from a binary search (i = 0 or n − 2 outside with
/// `extrapolate`) and t = (q − x_i)/(x_{i+1} − x_i), which is exactly 0 and 1 at the segment's ends.
template <bool Slope>
inline TableLookup look_up(const TableGrid& g, OutOfRange policy, double q) noexcept {
  TableLookup r;
  if (!(q >= g.lo && q <= g.hi)) {
    if (policy == OutOfRange::error || !std::isfinite(q)) {
      r.where = TableLookup::Where::refused;
      return r;
    }
    if (policy == OutOfRange::clamp) {
      r.where = q < g.lo ? TableLookup::Where::first : TableLookup::Where::last;
      return r;
    }
    r.i = q < g.lo ? 0 : g.n - 2;
  } else if (g.uniform) {
    const double u = uniform_position(q, g.lo, g.inv_step);
    r.i = uniform_segment(u, g.n);
    r.t = u - r.i;
    if (Slope) r.inv_dx = g.inv_step;
    return r;
  } else {
    r.i = static_cast<int>(std::upper_bound(g.x, g.x + g.n, q) - g.x) - 1;
    if (r.i > g.n - 2) r.i = g.n - 2;
    if (r.i < 0) r.i = 0;
  }
  const double dx = g.x[r.i + 1] - g.x[r.i];
  r.t = (q - g.x[r.i]) / dx;
  if (Slope) r.inv_dx = 1.0 / dx;
  return r;
}

/// Value (and slope when `Slope`) of column `column` of a table whose row j is at values[j·stride]:
/// `lookup.where` must not be `refused`.
template <bool Slope>
inline double table_value(const TableLookup& lookup, const double* values, int n, int stride, int column,
                          double* slope) noexcept {
  switch (lookup.where) {
    case TableLookup::Where::first:
    case TableLookup::Where::last:
    case TableLookup::Where::refused: {
      if (Slope) *slope = 0.0;
      const int row = lookup.where == TableLookup::Where::first ? 0 : n - 1;
      return values[static_cast<std::ptrdiff_t>(row) * stride + column];
    }
    case TableLookup::Where::segment:
    default: {
      const double a = values[static_cast<std::ptrdiff_t>(lookup.i) * stride + column];
      const double b = values[static_cast<std::ptrdiff_t>(lookup.i + 1) * stride + column];
      if (Slope) *slope = segment_slope(a, b, lookup.inv_dx);
      return interpolate(a, b, lookup.t);
    }
  }
}

}  // namespace netshape::machine::detail
