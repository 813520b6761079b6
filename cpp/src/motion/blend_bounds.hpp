#pragma once
/// \file blend_bounds.hpp
/// Internal: per-axis bounds of a cubic Bézier's unit tangent and curvature vector over runs of its
/// arc-length table intervals; the planner's corner blends (planner_blend.cpp) and cubic blocks
/// (planner_cubic.cpp) bound each of their pieces with them.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "netshape/core/types.hpp"

namespace netshape::motion::detail {

// Per-axis bounds of a blend's unit tangent |u_i| (U) and curvature vector |κ n_i| (K) over runs of
// its 17 table nodes, with a margin for what lies between the nodes (a quarter of the largest second
// difference of the node values, twice the parabolic estimate). The raw maxima are taken once per
// table interval; a run's bound is the max over its intervals (max is exact, so the bounds of the
// whole blend equal those computed over all nodes at once).
struct BlendBounds {
  double mu[16][3], mk[16][3], du[16][3], dk[16][3];  // raw maxima per table interval
  void fill(const std::array<Vec3, 17>& T, const std::array<Vec3, 17>& Kv) noexcept {
    double t[17][3], k[17][3], dt[17][3], dkk[17][3];
    for (int i = 0; i < 17; ++i)
      for (int c = 0; c < 3; ++c) {
        t[i][c] = std::abs(T[static_cast<std::size_t>(i)][c]);
        k[i][c] = std::abs(Kv[static_cast<std::size_t>(i)][c]);
      }
    for (int c = 0; c < 3; ++c) dt[0][c] = dkk[0][c] = dt[16][c] = dkk[16][c] = 0.0;  // ends: none
    for (int i = 1; i <= 15; ++i)
      for (int c = 0; c < 3; ++c) {
        dt[i][c] = std::abs(t[i - 1][c] - 2 * t[i][c] + t[i + 1][c]);
        dkk[i][c] = std::abs(k[i - 1][c] - 2 * k[i][c] + k[i + 1][c]);
      }
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 3; ++c) {
        mu[r][c] = std::max(t[r][c], t[r + 1][c]);
        mk[r][c] = std::max(k[r][c], k[r + 1][c]);
        du[r][c] = std::max(dt[r][c], dt[r + 1][c]);
        dk[r][c] = std::max(dkk[r][c], dkk[r + 1][c]);
      }
  }
  // bounds over the table intervals [r0, r1)
  void bounds(int r0, int r1, Vec3& U, Vec3& K) const noexcept {
    for (int c = 0; c < 3; ++c) {
      double a = mu[r0][c], b = mk[r0][c], e = du[r0][c], f = dk[r0][c];
      for (int r = r0 + 1; r < r1; ++r) {
        a = std::max(a, mu[r][c]);
        b = std::max(b, mk[r][c]);
        e = std::max(e, du[r][c]);
        f = std::max(f, dk[r][c]);
      }
      U[c] = std::min(1.0, std::max(0.0, a) + 0.25 * std::max(0.0, e) + 1e-12);
      K[c] = std::max(0.0, b) * (1.0 + 1e-9) + 0.25 * std::max(0.0, f);
    }
  }
};

}  // namespace netshape::motion::detail
